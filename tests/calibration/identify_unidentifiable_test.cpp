// Plans that cannot identify every parameter are reported as such, never as converged.
#include <gtest/gtest.h>

#include <random>

#include "calib_test_support.hpp"
#include "calibration/identify.hpp"
#include "calibration/plan_design.hpp"
#include "calibration/simulate.hpp"

namespace pkm::calibration {
namespace {

MeasurementSet calib_measure(const Mechanism& model, const std::vector<Pose>& plan,
                             const MeasurementSetup& setup, std::uint64_t seed, bool noisy) {
  auto layout = parameter_layout(model);
  std::mt19937_64 rng(seed);
  const Eigen::VectorXd truth_values =
      perturbed_parameters(*layout, parameter_vector(layout->groups), {0.1, 0.1}, rng);
  auto truth = mechanism_with_parameters(model, *layout, truth_values);
  auto data = simulate_measurements(model, **truth, plan, setup, noisy ? &rng : nullptr);
  EXPECT_TRUE(data) << data.error().message;
  return *data;
}

// |component of the scaled direction `d` in the identified subspace| / |d|.
double calib_identified_share(const Identifiability& a, const Eigen::VectorXd& d) {
  return (a.identifiable_basis().transpose() * d).norm() / d.norm();
}

TEST(CalibIdentifyPlans, TooFewEquationsIsAnError) {
  auto model = calib_ch5_model();
  auto plan = random_plan(*model, 6, PoseBox{}, 3);
  ASSERT_TRUE(plan);
  auto result = identify(*model, calib_measure(*model, plan->poses, target_setup(0.01), 1, true));
  ASSERT_FALSE(result);
  EXPECT_EQ(result.error().code, ErrorCode::bad_input);
  EXPECT_NE(result.error().message.find("36 equations for 42 parameters"), std::string::npos)
      << result.error().message;
}

TEST(CalibIdentifyPlans, TheSamePoseRepeatedIsFlaggedWithItsDroppedCombinations) {
  auto model = calib_ch5_model();
  const std::vector<Pose> plan(12, model->home());
  for (bool noisy : {false, true}) {
    auto result = identify(*model, calib_measure(*model, plan, target_setup(0.01), 2, noisy));
    ASSERT_TRUE(result) << result.error().message;
    EXPECT_EQ(result->status, IdentificationStatus::partially_identified) << "noisy " << noisy;
    EXPECT_FALSE(result->converged());
    // One pose gives six independent equations: 36 of the 42 combinations are dropped and named.
    EXPECT_EQ(result->at_start.rank, 6);
    ASSERT_EQ(result->at_start.unidentifiable.size(), 36u);
    for (const auto& c : result->at_start.unidentifiable) EXPECT_FALSE(c.description.empty());
    ASSERT_FALSE(result->warnings.empty());
    EXPECT_NE(result->warnings.front().find("36 of 42 parameter combinations cannot be identified"),
              std::string::npos)
        << result->warnings.front();
    // Nothing moved along the dropped directions: the identified values differ from the drawing only inside
    // the six identified ones.
    const Eigen::MatrixXd basis = result->at_start.identifiable_basis();
    const Eigen::VectorXd moved = result->identified - result->nominal;
    EXPECT_LT((moved - basis * (basis.transpose() * moved)).norm(), 1e-9 * std::max(1.0, moved.norm()));
  }
}

TEST(CalibIdentifyPlans, BallbarCannotSeeRotationsAboutTheBallOrTheToolPoint) {
  // A ballbar measures only |tool point − ball centre|: turning the whole base about the ball, or the
  // platform's joints about the tool point, changes no reading. Both are dropped, the rest identified.
  auto model = calib_ch5_model();
  auto plan = random_plan(*model, 100, PoseBox{}, 9);
  ASSERT_TRUE(plan);
  const Eigen::Vector3d ball(20.0, -10.0, 550.0);
  auto result = identify(*model, calib_measure(*model, plan->poses, ballbar_setup(ball, 0.001), 4, false));
  ASSERT_TRUE(result) << result.error().message;
  EXPECT_EQ(result->status, IdentificationStatus::partially_identified);
  EXPECT_FALSE(result->converged());
  EXPECT_EQ(result->at_start.rank, 36);
  const ParameterLayout& layout = result->layout;
  const Eigen::VectorXd values = result->nominal;
  for (int axis = 0; axis < 3; ++axis) {
    const Eigen::Vector3d w = Eigen::Vector3d::Unit(axis);
    Eigen::VectorXd base_turn = Eigen::VectorXd::Zero(layout.size());
    Eigen::VectorXd platform_turn = Eigen::VectorXd::Zero(layout.size());
    for (int j = 0; j < 6; ++j) {
      const Eigen::Vector3d a = values.segment<3>(3 * j);
      const Eigen::Vector3d b = values.segment<3>(18 + 3 * j);
      base_turn.segment<3>(3 * j) = w.cross(a - ball);
      platform_turn.segment<3>(18 + 3 * j) = w.cross(b);
    }
    EXPECT_LT(calib_identified_share(result->at_start, base_turn), 1e-4) << "axis " << axis;
    EXPECT_LT(calib_identified_share(result->at_start, platform_turn), 1e-4) << "axis " << axis;
  }
  // And what is identified is right: the tool point's distance errors are gone.
  EXPECT_LT(result->after.max_mm, 1e-9);
}

}  // namespace
}  // namespace pkm::calibration
