// Noise-free identification recovers every parameter: the 42 of the hexapod with drive offsets
// from random plans, on random true geometries.
#include <gtest/gtest.h>

#include <random>

#include "calib_test_support.hpp"
#include "calibration/identify.hpp"
#include "calibration/plan_design.hpp"
#include "calibration/simulate.hpp"

namespace pkm::calibration {
namespace {

struct CalibRecovery {
  double max_error = 0.0;
  IdentificationStatus status = IdentificationStatus::not_converged;
  int iterations = 0;
  double condition = 0.0;
};

CalibRecovery calib_recover(const Mechanism& model, const std::vector<Pose>& plan,
                            const MeasurementSetup& setup, double joint_error_mm, std::uint64_t seed) {
  auto layout = parameter_layout(model);
  EXPECT_TRUE(layout);
  std::mt19937_64 rng(seed);
  const Eigen::VectorXd truth_values =
      perturbed_parameters(*layout, parameter_vector(layout->groups), {joint_error_mm, joint_error_mm}, rng);
  auto truth = mechanism_with_parameters(model, *layout, truth_values);
  EXPECT_TRUE(truth);
  auto data = simulate_measurements(model, **truth, plan, setup, nullptr);
  EXPECT_TRUE(data) << data.error().message;
  auto result = identify(model, *data);
  EXPECT_TRUE(result) << result.error().message;
  if (!result) return {};
  return {(result->identified - truth_values).cwiseAbs().maxCoeff(), result->status, result->iterations,
          result->at_start.identifiable_condition_number};
}

TEST(CalibIdentifyNoiseFree, AllFortyTwoHexapodParametersFromRandomPlans) {
  auto model = calib_ch5_model();
  for (std::uint64_t seed : {1u, 2u, 3u, 4u}) {
    auto plan = random_plan(*model, 30 + 5 * static_cast<int>(seed), PoseBox{}, 100 + seed);
    ASSERT_TRUE(plan) << plan.error().message;
    const double joint_error = seed % 2 == 0 ? 1.0 : 0.1;
    const CalibRecovery r = calib_recover(*model, plan->poses, target_setup(0.01), joint_error, seed);
    EXPECT_EQ(r.status, IdentificationStatus::identified) << "seed " << seed;
    EXPECT_LT(r.max_error, 1e-8) << "seed " << seed << ", " << r.iterations << " iterations, condition "
                                 << r.condition;
  }
}

TEST(CalibIdentifyNoiseFree, TargetsThroughForwardKinematicsToo) {
  // Without the pose-fit form every target goes through FK_θ(readings): the same answer.
  auto model = calib_ch5_model();
  auto plan = random_plan(*model, 30, PoseBox{}, 77);
  ASSERT_TRUE(plan);
  auto layout = parameter_layout(*model);
  std::mt19937_64 rng(5);
  const Eigen::VectorXd truth_values =
      perturbed_parameters(*layout, parameter_vector(layout->groups), {0.5, 0.5}, rng);
  auto truth = mechanism_with_parameters(*model, *layout, truth_values);
  auto data = simulate_measurements(*model, **truth, plan->poses, target_setup(0.01), nullptr);
  ASSERT_TRUE(data);
  IdentifyOptions options;
  options.residuals.pose_inverse_where_possible = false;
  auto result = identify(*model, *data, options);
  ASSERT_TRUE(result) << result.error().message;
  EXPECT_EQ(result->status, IdentificationStatus::identified);
  EXPECT_LT((result->identified - truth_values).cwiseAbs().maxCoeff(), 1e-8);
  EXPECT_LT(result->after.max_mm, 1e-9);
  EXPECT_GT(result->before.max_mm, 0.05);
}

}  // namespace
}  // namespace pkm::calibration
