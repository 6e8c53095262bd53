#pragma once
// Reducing the errors of drive discreteness (Smirnov 2019, §5.2.5): per period, every actuator may end on the
// whole step just below or just above its ideal value; of the 2^n combinations the one whose tool point lies
// nearest the programmed path is issued. Targets are absolute (the law's value minus the actual integer
// position), so the start positions' quantisation error is absorbed in the first period (Fig. 193).
//
//  - The error is the perpendicular (contour) distance from the path, not the 3-D distance to the ideal
//  point:
//    that one lets the tool lag along the path and roughly doubles the contour error (eq. 145, §5.2.5).
//  - Checked at the period's end and at its middle (eq. 177: the drives move linearly through the period, so
//    the tool passes L_prev + ΔL*/2 half way); combinations whose middle exceeds ρ_max are dropped while any
//    other remains (else the one with the smallest larger error of the two is taken and counted).
//  - Linearised (§5.2.5): FK only for the all-floor state at the end, the other combinations from the FK
//    sensitivities ∂Y/∂L (the inverse Jacobian) there: 1 FK solve and 1 Jacobian per period instead of
//    2·2^n FK solves (Smirnov's "7 + 7" counts 6 FK solves per Jacobian; ours is analytic). The middle
//    point is the midpoint of the issued state's point and the end's, with half the end's sensitivities:
//    a period's motion is short enough that FK is linear over it to far below a step.
//    `linearise = false` solves FK for every combination (the reference).
//  - Optional secondary criterion (eq. 143): among the combinations within a share of ρ_max at both points,
//    the least (ψ − ψ_req)² + (ϑ − ϑ_req)² + (γ − γ_req)², in the machine's angle convention. The share
//    (half by default) leaves room for the linearisation and for the instants between end and middle, which
//    are not checked: with the whole ρ_max the chosen combinations sit on its edge and the tool crosses it.
#include <array>
#include <optional>

#include "interpolation/contour/contour_gauge.hpp"
#include "interpolation/methods/carrier_interpolator.hpp"
#include "interpolation/pose_tracker.hpp"
#include "interpolation/quantisation/step_period.hpp"

namespace pkm::interpolation {

struct CorrectorSettings {
  double step = 0.001;       ///< Δ, mm (rad) per step
  double rho_max_mm = 1e-3;  ///< ρ_max, the contour tolerance of the middle check
  bool orientation_criterion = false;
  double orientation_contour_share = 0.5;  ///< of ρ_max, where the orientation criterion may choose
  bool linearise = true;
};

struct CorrectorStatistics {
  long periods = 0;
  long fk_solves = 0;
  long jacobians = 0;
  long fallbacks = 0;                   ///< periods where no combination met ρ_max in the middle
  double max_predicted_error_mm = 0.0;  ///< of the chosen combinations (end and middle)
};

class DiscretenessCorrector {
 public:
  DiscretenessCorrector(const Machine& machine, const path::Path& path, const ContourGauge& gauge,
                        const CorrectorSettings& settings);
  /// Start positions: the ideal start truncated to whole steps (as Smirnov 2019, §5.2.5), FK there.
  Status start(const std::array<double, kMaxActuators>& ideal_start);
  /// Chooses the period's steps; fills `out.steps` and `out.position`. No allocation.
  Status quantize(const CarrierPeriod& period, StepPeriod& out);
  const std::array<std::int64_t, kMaxActuators>& position() const { return position_; }
  const CorrectorStatistics& statistics() const { return statistics_; }

 private:
  struct Linearisation {
    Eigen::Vector3d point_mm;  ///< controlled point of the all-floor state
    Eigen::Vector3d angles;    ///< its angles in the machine's convention, rad
    std::array<Eigen::Vector3d, kMaxActuators> point_per_step;  ///< ∂p/∂L_j · step
    std::array<Eigen::Vector3d, kMaxActuators> angles_per_step;
  };
  struct PeriodGoal;  ///< the period's all-floor state and the path's points and tangents at its end and
                      ///< middle
  struct Choice;      ///< the best combination of extra steps so far, by each criterion
  bool linearise(PoseTracker& tracker, const std::array<double, kMaxActuators>& values, Linearisation& out);
  Status fail(const CarrierPeriod& period, const char* where) const;
  PeriodGoal period_goal(const CarrierPeriod& period);
  void choose_linearised(const PeriodGoal& goal, const Linearisation& end, Choice& choice) const;
  Status choose_exact(const CarrierPeriod& period, const PeriodGoal& goal, Choice& choice);
  void issue(const CarrierPeriod& period, const PeriodGoal& goal, unsigned chosen, StepPeriod& out);

  const Machine& machine_;
  const path::Path& path_;
  const ContourGauge& gauge_;
  CorrectorSettings settings_;
  int count_;
  std::array<int, 6> coordinate_axis_{};  ///< axis (0…5) of each controlled coordinate
  int coordinates_ = 0;
  PoseTracker end_tracker_;
  PoseTracker probe_tracker_;  ///< the non-linearised reference
  std::array<std::int64_t, kMaxActuators> position_{};
  Eigen::Vector3d issued_point_mm_{0.0, 0.0, 0.0};  ///< tool point of `position_` (linearised)
  int end_hint_ = 0;                                ///< path segment of the last period's end
  int middle_hint_ = 0;                             ///< and of its middle
  CorrectorStatistics statistics_;
};

}  // namespace pkm::interpolation
