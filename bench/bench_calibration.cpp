// Identification of the ch5 hexapod's 42 parameters (18 base joints, 18 platform joints, 6 drive offsets)
// from 100 poses measured with the triangular plate (goal < 50 ms), for docs/PERFORMANCE.md. The
// true machine is 0.1 mm off the drawing, the targets measured with σ = 0.01 mm; one iteration is one whole
// calibration::identify: residual model, Jacobians, the SVD diagnostics at start and solution, the LM solve.
//
// BM_PlanMonteCarlo/<plan> runs once and reports, as counters, the plan comparison of docs/calibration.md:
// 200 trials of the same setup for the seven-pose plan (0), random 30 (1), random 60 (2) and D-optimal 30 of
// 400 candidates (3); held-out tool error at 100 random poses, in µm.
#include <benchmark/benchmark.h>

#include <random>

#include "bench_support.hpp"
#include "calibration/identify.hpp"
#include "calibration/plan_design.hpp"
#include "calibration/simulate.hpp"
#include "machine/actuator_offsets.hpp"

namespace pkm {
namespace {

void BM_Identify42ParametersFrom100Poses(benchmark::State& state) {
  auto model = with_actuator_offset_parameters(*bench::ch5_hexapod().mechanism);
  if (!model) {
    state.SkipWithError(model.error().message.c_str());
    return;
  }
  const Mechanism& nominal = **model;
  auto layout = calibration::parameter_layout(nominal);
  auto plan = calibration::random_plan(nominal, 100, calibration::PoseBox{}, 1);
  if (!layout || !plan) {
    state.SkipWithError("no plan");
    return;
  }
  std::mt19937_64 rng(2);
  const Eigen::VectorXd truth_values = calibration::perturbed_parameters(
      *layout, calibration::parameter_vector(layout->groups), calibration::PerturbationOptions{}, rng);
  auto truth = calibration::mechanism_with_parameters(nominal, *layout, truth_values);
  auto data = calibration::simulate_measurements(nominal, **truth, plan->poses,
                                                 calibration::target_setup(0.01), &rng);
  if (!data) {
    state.SkipWithError(data.error().message.c_str());
    return;
  }
  int iterations = 0;
  for (auto _ : state) {
    auto result = calibration::identify(nominal, *data);
    if (!result) {
      state.SkipWithError(result.error().message.c_str());
      break;
    }
    iterations = result->iterations;
    benchmark::DoNotOptimize(result);
  }
  state.counters["lm_iterations"] = iterations;
}
BENCHMARK(BM_Identify42ParametersFrom100Poses)->Unit(benchmark::kMillisecond);

void BM_PlanMonteCarlo(benchmark::State& state) {
  auto model = with_actuator_offset_parameters(*bench::ch5_hexapod().mechanism);
  if (!model) {
    state.SkipWithError(model.error().message.c_str());
    return;
  }
  const Mechanism& nominal = **model;
  const calibration::MeasurementSetup setup = calibration::target_setup(0.01);
  Result<calibration::PosePlan> plan = calibration::PosePlan{};
  switch (state.range(0)) {
    case 0:
      plan = calibration::seven_pose_plan(nominal);
      break;
    case 1:
      plan = calibration::random_plan(nominal, 30, calibration::PoseBox{}, 4);
      break;
    case 2:
      plan = calibration::random_plan(nominal, 60, calibration::PoseBox{}, 5);
      break;
    default: {
      calibration::DOptimalOptions options;
      options.candidates = 400;
      options.seed = 6;
      plan = calibration::d_optimal_plan(nominal, setup, 30, options);
    }
  }
  auto held_out = calibration::random_plan(nominal, 100, calibration::PoseBox{}, 99);
  if (!plan || !held_out) {
    state.SkipWithError("no plan");
    return;
  }
  state.SetLabel(plan->name);
  const calibration::TrialSetup trials{plan->poses, setup, held_out->poses, {0.1, 0.1}, {}};
  calibration::MonteCarloSummary summary;
  for (auto _ : state) summary = calibration::monte_carlo(nominal, trials, 200, 2024);
  state.counters["held_out_rms_median_um"] = 1000.0 * summary.held_out_rms_mm.median;
  state.counters["held_out_rms_p90_um"] = 1000.0 * summary.held_out_rms_mm.p90;
  state.counters["held_out_max_median_um"] = 1000.0 * summary.held_out_max_mm.median;
  state.counters["parameter_error_max_median_um"] = 1000.0 * summary.parameter_error_max_mm.median;
  state.counters["condition_number"] = summary.mean_condition_number;
  state.counters["failed"] = summary.failed + summary.unusable;
}
BENCHMARK(BM_PlanMonteCarlo)->DenseRange(0, 3)->Iterations(1)->Unit(benchmark::kSecond);

}  // namespace
}  // namespace pkm

BENCHMARK_MAIN();
