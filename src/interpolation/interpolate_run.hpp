#pragma once
// A whole interpolation run (Smirnov 2019, ch. 5): path and ideal timing in, whole drive steps per period
// out (to any number of StepSinks: CSV, binary stream, the real-time player), with the contour error of the
// tool measured as the drives would produce it. Methods:
//   exact              strut values by IK at every period end, remainder registers (eq. 156–158);
//   carrier            the carrier-frequency method (§5.2.2): fitted strut laws, chord check (eqs. 152–153),
//                      remainder registers (eq. 156–158);
//   carrier-corrected  as carrier, with the floor/ceil choice of every actuator that keeps the tool nearest
//                      the path (§5.2.5, the discreteness correction);
//   estimating         estimating functions (§5.2.1): tact by tact, every strut ±1 step, the candidate
//                      that best follows the path; a reference/offline mode.
#include <functional>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "core/duration_histogram.hpp"
#include "core/progress.hpp"
#include "core/result.hpp"
#include "interpolation/contour/contour_monitor.hpp"
#include "interpolation/error_amplification_scan.hpp"
#include "interpolation/methods/carrier_interpolator.hpp"
#include "interpolation/methods/estimating_function.hpp"
#include "interpolation/methods/ideal_timing.hpp"
#include "interpolation/methods/strut_laws.hpp"
#include "interpolation/quantisation/discreteness_corrector.hpp"
#include "interpolation/quantisation/step_period.hpp"
#include "planning/plan_producer.hpp"

namespace pkm::interpolation {

enum class Method { exact, carrier, carrier_corrected, estimating };

/// The compute budget of one period that the summary counts periods above: 10 µs, a tenth of a 10 kHz period.
inline constexpr std::int64_t kPeriodTimeBudgetNs = 10'000;
std::optional<Method> method_from_string(std::string_view name);
std::string_view to_string(Method method);

/// The smallest contour tolerance ρ_max taken: a nanometre, a thousandth of the finest drive steps. Below it
/// the work grows without bound while no drive can follow.
inline constexpr double kMinContourToleranceMm = 1e-6;

struct InterpolateOptions {
  Method method = Method::carrier_corrected;
  double period_s = 0.001;
  double step_mm = 0.001;  ///< Δ: mm (deg for angular actuators) per step; 0 = continuous drives (no steps)
  double rho_max_mm = 1e-3;             ///< ρ_max: the contour tolerance (≥ kMinContourToleranceMm)
  std::optional<double> delta_rho_max;  ///< δρ_max; default: the largest along the path (eq. 146)
  bool chord_check = true;
  OverrideSettings feed_override;
  int error_samples = 5;  ///< contour-error instants inside each period (plus its end)
  bool orientation_criterion = false;
  bool linearise = true;
  std::optional<double> max_step_rate_hz;  ///< per drive; limits the steps per period
  EstimatingSettings estimating;           ///< deviation and candidates (its step is step_mm)
  double amplification_spacing = 1.0;      ///< path units between the δρ samples
  ProgressSink progress;                   ///< told how far the run is, now and then
  /// Called after every period with what the drives did to the tool then, and the programmed point at the
  /// period's end (base frame): traces and reports (formats/contour_trace.hpp).
  std::function<void(const StepPeriod&, const PeriodContour&, const Eigen::Vector3d& path_mm)> on_period;
};

struct InterpolateSummary {
  Method method = Method::carrier_corrected;
  double period_s = 0.0, step_mm = 0.0, rho_max_mm = 0.0;
  double delta_rho_max = 0.0;
  int delta_rho_max_line = 0;
  double strut_tolerance = 0.0;  ///< ΔL_allowed = 0.9·ρ_max/δρ_max (eq. 155)
  long periods = 0;
  double ideal_time_s = 0.0, real_time_s = 0.0;
  ContourStatistics contour;
  CarrierStatistics carrier;
  LawReport laws;
  CorrectorStatistics corrector;
  EstimatingStatistics estimating;
  double max_remainder_steps = 0.0;  ///< remainder registers (eqs. 156–158 methods), in steps
  int max_steps_per_period = 0;
  int max_steps_line = 0;
  double fk_solves_per_period = 0.0;  ///< of the method itself (the error measurement not counted)
  double jacobians_per_period = 0.0;
  double max_compute_us_per_period = 0.0;
  double mean_compute_us_per_period = 0.0;
  /// The compute time of every period (what a servo loop runs: ideal time, strut laws, chord check,
  /// quantisation; not the contour measurement nor the sinks), steady clock; over_budget counts the periods
  /// above kPeriodTimeBudgetNs.
  DurationDistribution period_time;
  int actuators = 0;
  std::array<std::int64_t, kMaxActuators> start_position{};
  std::array<std::int64_t, kMaxActuators> end_position{};
  std::array<double, kMaxActuators> ideal_start{};
  std::array<double, kMaxActuators> ideal_end{};
  /// Along a plan made while it streams (interpolate_streamed): the most ticks of ideal timing, strut-law
  /// pieces and path segments held at once, bounded by the planner's window, not by the program. 0: whole.
  std::size_t peak_window_ticks = 0, peak_window_pieces = 0, peak_window_segments = 0;
};

/// Runs the interpolation. `sinks` receive every period (none for a measurement only); a failing run
/// finishes none of them, so staged files are discarded. Errors name `source` and the line.
Result<InterpolateSummary> interpolate(const Machine& machine, const path::Path& path,
                                       const IdealTiming& timing, const InterpolateOptions& options,
                                       const std::vector<StepSink*>& sinks, const std::string& source);

/// What a first pass over a plan made while it streams finds before any period is interpolated: every tick
/// within the plan's limits (the actuators' ranges: software stops in both spaces), δρ_max along the path,
/// and the plan's duration.
struct StreamedPlanCheck {
  ErrorAmplification amplification;
  double duration_s = 0.0;
};
/// Streams `streamed` through (its memory bounded by the planner's window). Errors name the program line.
Result<StreamedPlanCheck> check_streamed_plan(const Machine& machine, planning::StreamedPlan& streamed,
                                              double amplification_spacing, const std::string& source,
                                              const ProgressSink& progress);

/// interpolate() along a plan made while it streams, a second stream of the plan `check` was made on: the
/// timing and the strut laws are windows that follow the interpolator, so memory does not grow with the
/// program, and the periods equal those of interpolate() on the whole plan. The carrier methods and exact.
Result<InterpolateSummary> interpolate_streamed(const Machine& machine, planning::StreamedPlan& streamed,
                                                const StreamedPlanCheck& check,
                                                const InterpolateOptions& options,
                                                const std::vector<StepSink*>& sinks,
                                                const std::string& source);

/// The drives' positions before the first period, in steps: the path start's actuator values truncated to
/// whole steps, as every method starts (§5.2.5). For the header of step files, written before the run.
Result<std::array<std::int64_t, kMaxActuators>> start_positions(const Machine& machine,
                                                                const path::Path& path, double step_mm);

}  // namespace pkm::interpolation
