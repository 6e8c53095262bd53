// A reduced-DOF mechanism: the 3-RPS tripod's 21 parameters (A1..A3, B1..B3, dL1..dL3) from targets. Its IK
// ignores the dependent coordinates x, y, C that the targets also measure, so every target goes through
// FK_θ(readings) (residuals.hpp, targets_forward).
#include <gtest/gtest.h>

#include <random>

#include "calib_test_support.hpp"
#include "calibration/identify.hpp"
#include "calibration/plan_design.hpp"
#include "calibration/simulate.hpp"

namespace pkm::calibration {
namespace {

TEST(CalibIdentifyTripod, NoiseFreeRecoveryOfAllParameters) {
  const Machine machine = test::machine_from_example("examples/machines/tripod.yaml");
  auto model = with_actuator_offset_parameters(*machine.mechanism);
  ASSERT_TRUE(model) << model.error().message;
  auto layout = parameter_layout(**model);
  ASSERT_TRUE(layout);
  ASSERT_EQ(layout->size(), 21);
  for (std::uint64_t seed : {1u, 2u, 3u}) {
    auto plan = random_plan(**model, 30, PoseBox{}, 40 + seed);
    ASSERT_TRUE(plan) << plan.error().message;
    std::mt19937_64 rng(seed);
    const Eigen::VectorXd truth_values =
        perturbed_parameters(*layout, parameter_vector(layout->groups), {0.5, 0.5}, rng);
    auto truth = mechanism_with_parameters(**model, *layout, truth_values);
    ASSERT_TRUE(truth) << truth.error().message;
    auto data = simulate_measurements(**model, **truth, plan->poses, target_setup(0.01), nullptr);
    ASSERT_TRUE(data) << data.error().message;
    auto result = identify(**model, *data);
    ASSERT_TRUE(result) << result.error().message;
    EXPECT_EQ(result->status, IdentificationStatus::identified);
    EXPECT_EQ(result->at_start.rank, 21);
    // The struts stand nearly upright within ±50 mm, ±10°: moving a base joint up and shortening the drive's
    // offset by as much look alike, and the diagnostics say so (condition ≈ 5e4 over ±50 mm, ±10°).
    ASSERT_FALSE(result->at_start.weakest.empty());
    const std::string& weakest = result->at_start.weakest.front().description;
    EXPECT_NE(weakest.find("dL"), std::string::npos) << weakest;
    EXPECT_NE(weakest.find(".z"), std::string::npos) << weakest;
    EXPECT_LT((result->identified - truth_values).cwiseAbs().maxCoeff(), 1e-8) << "seed " << seed;
  }
}

}  // namespace
}  // namespace pkm::calibration
