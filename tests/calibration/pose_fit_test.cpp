// The pose from targets (Smirnov 2019, §5.2.4, eqs. 173–174 generalised to a weighted Kabsch fit).
#include "calibration/pose_fit.hpp"

#include <gtest/gtest.h>

#include <random>

#include "calibration/synthetic_measurements.hpp"
#include "core/rotation.hpp"

namespace pkm::calibration {
namespace {

Pose calib_fit_random_pose(std::mt19937_64& rng) {
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  PoseVector v;
  v << 300 * u(rng), 300 * u(rng), 700 + 300 * u(rng), 3 * u(rng), 1.4 * u(rng), 3 * u(rng);
  return pose_from_vector(AngleConvention::abc, v);
}

std::vector<TargetPair> calib_fit_pairs(const Pose& pose, const std::vector<Eigen::Vector3d>& tool_points) {
  std::vector<TargetPair> pairs;
  for (const auto& t : tool_points) pairs.push_back({t, pose.to_base(t), 0.01});
  return pairs;
}

TEST(CalibPoseFit, ExactTargetsGiveThePoseToRoundOff) {
  std::mt19937_64 rng(7);
  std::vector<Eigen::Vector3d> plate;
  for (const FixtureTarget& t : triangular_plate(100.0)) plate.push_back(t.position_mm);
  std::vector<Eigen::Vector3d> scattered = {
      {10, 20, -150}, {-80, 5, 30}, {40, -90, 12}, {0, 0, 0}, {55, 60, -20}};
  for (int trial = 0; trial < 50; ++trial) {
    const Pose truth = calib_fit_random_pose(rng);
    for (const std::vector<Eigen::Vector3d>* points : {&plate, &scattered}) {
      auto fit = fit_pose(calib_fit_pairs(truth, *points));
      ASSERT_TRUE(fit) << fit.error().message;
      EXPECT_LT((fit->pose.position_mm - truth.position_mm).norm(), 1e-12);
      EXPECT_LT((fit->pose.rotation - truth.rotation).cwiseAbs().maxCoeff(), 1e-12);
      EXPECT_LT(fit->max_misfit_mm, 1e-12);
    }
  }
}

TEST(CalibPoseFit, TriangleCentroidIsTheToolPointOfTheDissertation) {
  // Eq. 173: with the plate centred on the tool point, the fitted tool point is the vertices' centroid.
  const Pose truth =
      pose_from_vector(AngleConvention::krylov, (PoseVector() << 10, -20, 650, 0.08, -0.05, 0.03).finished());
  auto pairs = calib_fit_pairs(truth, {triangular_plate()[0].position_mm, triangular_plate()[1].position_mm,
                                       triangular_plate()[2].position_mm});
  pairs[0].measured_mm += Eigen::Vector3d(0.003, -0.002, 0.001);
  const Eigen::Vector3d centroid = (pairs[0].measured_mm + pairs[1].measured_mm + pairs[2].measured_mm) / 3.0;
  auto fit = fit_pose(pairs);
  ASSERT_TRUE(fit);
  EXPECT_LT((fit->pose.position_mm - centroid).norm(), 1e-12);
  EXPECT_GT(fit->max_misfit_mm, 1e-4);  // the disturbed vertex no longer fits a rigid triangle exactly
}

TEST(CalibPoseFit, FailsForTooFewOrCollinearTargets) {
  const Pose truth = calib_fit_random_pose(*std::make_unique<std::mt19937_64>(3));
  auto two = fit_pose(calib_fit_pairs(truth, {{0, 0, 0}, {100, 0, 0}}));
  ASSERT_FALSE(two);
  EXPECT_NE(two.error().message.find("at least 3 targets"), std::string::npos);
  auto line = fit_pose(calib_fit_pairs(truth, {{0, 0, 0}, {100, 0, 0}, {-50, 0, 0}, {30, 0, 0}}));
  ASSERT_FALSE(line);
  EXPECT_NE(line.error().message.find("one line"), std::string::npos);
  auto pairs = calib_fit_pairs(truth, {{0, 0, 0}, {100, 0, 0}, {0, 100, 0}});
  pairs[1].sigma_mm = 0.0;
  EXPECT_FALSE(fit_pose(pairs));
}

TEST(CalibPoseFit, CovarianceMatchesTheScatterOfNoisyFits) {
  // The fit's first-order covariance against 4000 noisy fits of the same targets.
  std::mt19937_64 rng(11);
  const Pose truth = calib_fit_random_pose(rng);
  const std::vector<Eigen::Vector3d> plate = {{0, 100, 0}, {-86.6, -50, 0}, {86.6, -50, 0}};
  std::normal_distribution<double> noise(0.0, 0.01);
  PoseCovariance scatter = PoseCovariance::Zero();
  PoseCovariance predicted;
  const int n = 4000;
  for (int i = 0; i < n; ++i) {
    auto pairs = calib_fit_pairs(truth, plate);
    for (auto& p : pairs) p.measured_mm += Eigen::Vector3d(noise(rng), noise(rng), noise(rng));
    auto fit = fit_pose(pairs);
    ASSERT_TRUE(fit);
    predicted = fit->covariance;
    Eigen::Matrix<double, 6, 1> e;
    e.head<3>() = fit->pose.position_mm - truth.position_mm;
    const Eigen::AngleAxisd turn(fit->pose.rotation * truth.rotation.transpose());
    e.tail<3>() = turn.angle() * turn.axis();
    scatter += e * e.transpose() / n;
  }
  for (int i = 0; i < 6; ++i) EXPECT_NEAR(scatter(i, i) / predicted(i, i), 1.0, 0.15) << "coordinate " << i;
}

}  // namespace
}  // namespace pkm::calibration
