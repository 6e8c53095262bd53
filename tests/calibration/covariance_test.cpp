// The predicted parameter covariance σ²(JᵀJ)⁻¹ against the scatter of identifications from noisy data.
#include <gtest/gtest.h>

#include "calib_test_support.hpp"
#include "calibration/plan_design.hpp"
#include "calibration/plan_prediction.hpp"
#include "calibration/simulate.hpp"

namespace pkm::calibration {
namespace {

TEST(CalibCovariance, EmpiricalParameterErrorsMatchThePredictedStandardDeviations) {
  auto model = calib_ch5_model();
  auto plan = random_plan(*model, 30, PoseBox{}, 31);
  auto held_out = random_plan(*model, 20, PoseBox{}, 32);
  ASSERT_TRUE(plan && held_out);
  auto prediction = predict_plan(*model, plan->poses, target_setup(0.01), held_out->poses);
  ASSERT_TRUE(prediction) << prediction.error().message;
  const Eigen::VectorXd& predicted = prediction->identifiability.standard_deviation;

  const TrialSetup setup{plan->poses, target_setup(0.01), held_out->poses, {0.1, 0.1}, {}};
  const int trials = 200;
  const MonteCarloSummary summary = monte_carlo(*model, setup, trials, 5);
  ASSERT_EQ(summary.failed, 0);
  Eigen::VectorXd mean_square = Eigen::VectorXd::Zero(42);
  for (const TrialResult& r : summary.results) mean_square += r.parameter_error.cwiseAbs2() / trials;
  const Eigen::VectorXd empirical = mean_square.cwiseSqrt();
  // With 200 trials an rms is known to about ±5 % (1/√(2·200)); the bound is loose on purpose.
  double log_ratio_sum = 0.0;
  for (int i = 0; i < 42; ++i) {
    const double ratio = empirical[i] / predicted[i];
    EXPECT_GT(ratio, 0.5) << i;
    EXPECT_LT(ratio, 2.0) << i;
    log_ratio_sum += std::log(ratio);
  }
  EXPECT_NEAR(std::exp(log_ratio_sum / 42), 1.0, 0.15);
  // The identification's own estimate at its solution says the same as the plan's prediction.
  EXPECT_NEAR(summary.results.front().predicted_sd[0] / predicted[0], 1.0, 0.05);
}

}  // namespace
}  // namespace pkm::calibration
