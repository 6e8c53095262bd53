// Measurement plans (Smirnov 2019, §5.2.4): the dissertation's seven poses, random and D-optimal plans,
// and what each predicts.
#include "calibration/plan_design.hpp"

#include <gtest/gtest.h>

#include "calib_test_support.hpp"
#include "calibration/plan_prediction.hpp"
#include "calibration/simulate.hpp"

namespace pkm::calibration {
namespace {

TEST(CalibPlanDesign, SevenPosePlanChangesOneStrutMoreEachTime) {
  auto model = calib_ch5_model();
  auto plan = seven_pose_plan(*model, 10.0);  // 10 mm: every pose near home
  ASSERT_TRUE(plan) << plan.error().message;
  ASSERT_EQ(plan->poses.size(), 7u);
  auto home = model->inverse(plan->poses[0]);
  ASSERT_TRUE(home);
  for (int k = 1; k < 7; ++k) {
    auto lengths = model->inverse(plan->poses[static_cast<std::size_t>(k)]);
    ASSERT_TRUE(lengths);
    for (int j = 0; j < 6; ++j)
      EXPECT_NEAR((*lengths)[j] - (*home)[j], j < k ? 10.0 : 0.0, 1e-9) << k << " " << j;
  }
}

TEST(CalibPlanDesign, RandomPlanStaysInTheBoxAndTheCallersLimits) {
  auto model = calib_ch5_model();
  const PoseFilter short_struts = [](const Pose&, const ActuatorVector& lengths) {
    return lengths.maxCoeff() < 640.0;
  };
  auto plan = random_plan(*model, 40, PoseBox{30.0, 0.1}, 5, short_struts);
  ASSERT_TRUE(plan) << plan.error().message;
  ASSERT_EQ(plan->poses.size(), 40u);
  for (const Pose& p : plan->poses) {
    EXPECT_LE((p.position_mm - model->home().position_mm).cwiseAbs().maxCoeff(), 30.0);
    EXPECT_LT(model->inverse(p)->maxCoeff(), 640.0);
  }
  auto again = random_plan(*model, 40, PoseBox{30.0, 0.1}, 5, short_struts);
  EXPECT_EQ(again->poses.back().position_mm, plan->poses.back().position_mm);  // seeded: reproducible
  const PoseFilter nothing = [](const Pose&, const ActuatorVector&) { return false; };
  auto none = random_plan(*model, 3, PoseBox{}, 5, nothing);
  ASSERT_FALSE(none);
  EXPECT_NE(none.error().message.find("only 0 of 3"), std::string::npos) << none.error().message;
}

TEST(CalibPlanDesign, SevenPosePlanIsBadlyConditionedAndWarnsSo) {
  auto model = calib_ch5_model();
  auto seven = seven_pose_plan(*model);
  auto held_out = random_plan(*model, 50, PoseBox{}, 99);
  ASSERT_TRUE(seven && held_out);
  auto prediction = predict_plan(*model, seven->poses, target_setup(0.01), held_out->poses);
  ASSERT_TRUE(prediction) << prediction.error().message;
  const Identifiability& a = prediction->identifiability;
  EXPECT_EQ(a.equations, 42);
  EXPECT_TRUE(a.full_rank());  // exactly determined, as the dissertation's six 7 × 7 systems
  EXPECT_GT(a.identifiable_condition_number, 1e4);
  EXPECT_TRUE(a.badly_conditioned);
  ASSERT_FALSE(a.warnings.empty());
  EXPECT_NE(a.warnings.back().find("badly conditioned"), std::string::npos) << a.warnings.back();
  EXPECT_FALSE(a.weakest.empty());

  auto random30 = random_plan(*model, 30, PoseBox{}, 4);
  auto good = predict_plan(*model, random30->poses, target_setup(0.01), held_out->poses);
  ASSERT_TRUE(good);
  EXPECT_FALSE(good->identifiability.badly_conditioned);
  EXPECT_TRUE(good->identifiability.warnings.empty());
  EXPECT_GT(prediction->tool_rms_mm, 5.0 * good->tool_rms_mm);
}

TEST(CalibPlanDesign, SevenPosePlanIsMuchWorseThanRandomPosesWithNoise) {
  auto model = calib_ch5_model();
  auto seven = seven_pose_plan(*model);
  auto random30 = random_plan(*model, 30, PoseBox{}, 4);
  auto held_out = random_plan(*model, 50, PoseBox{}, 99);
  ASSERT_TRUE(seven && random30 && held_out);
  TrialSetup setup{seven->poses, target_setup(0.01), held_out->poses, {0.1, 0.1}, {}};
  const MonteCarloSummary bad = monte_carlo(*model, setup, 16, 21);
  setup.plan = random30->poses;
  const MonteCarloSummary good = monte_carlo(*model, setup, 16, 21);
  EXPECT_LT(bad.failed, 8);
  EXPECT_EQ(good.failed, 0);
  EXPECT_GT(bad.held_out_rms_mm.median, 3.0 * good.held_out_rms_mm.median)
      << "seven-pose " << bad.held_out_rms_mm.median << " mm, random 30 " << good.held_out_rms_mm.median
      << " mm";
  EXPECT_GT(bad.parameter_error_max_mm.median, 3.0 * good.parameter_error_max_mm.median);
}

TEST(CalibPlanDesign, DOptimalPlanBeatsARandomPlanOfTheSameSize) {
  auto model = calib_ch5_model();
  DOptimalOptions options;
  options.candidates = 200;
  options.seed = 8;
  auto optimal = d_optimal_plan(*model, target_setup(0.01), 30, options);
  ASSERT_TRUE(optimal) << optimal.error().message;
  ASSERT_EQ(optimal->poses.size(), 30u);
  auto random30 = random_plan(*model, 30, PoseBox{}, 4);
  auto held_out = random_plan(*model, 50, PoseBox{}, 99);
  auto p_optimal = predict_plan(*model, optimal->poses, target_setup(0.01), held_out->poses);
  auto p_random = predict_plan(*model, random30->poses, target_setup(0.01), held_out->poses);
  ASSERT_TRUE(p_optimal && p_random);
  // D-optimality maximises det JᵀJ: the product of the singular values is larger.
  const double log_det_optimal = p_optimal->identifiability.singular_values.array().log().sum();
  const double log_det_random = p_random->identifiability.singular_values.array().log().sum();
  EXPECT_GT(log_det_optimal, log_det_random);
  EXPECT_LT(p_optimal->tool_rms_mm, p_random->tool_rms_mm);
}

}  // namespace
}  // namespace pkm::calibration
