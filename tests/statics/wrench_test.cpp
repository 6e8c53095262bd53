// Moving a wrench's moment point.
#include "statics/wrench.hpp"

#include <gtest/gtest.h>

#include <Eigen/Geometry>

namespace pkm::statics {
namespace {

TEST(StaticsWrench, ShiftKeepsTheForceAndTransportsTheMoment) {
  // A force of 10 N along x at the point (0, 5, 0): about the origin its moment is (0,5,0) × (10,0,0).
  const Wrench at_point{Eigen::Vector3d(10, 0, 0), Eigen::Vector3d::Zero()};
  const Wrench about_origin = shift_wrench(at_point, Eigen::Vector3d(0, 5, 0), Eigen::Vector3d::Zero());
  EXPECT_EQ(about_origin.force_N, Eigen::Vector3d(10, 0, 0));
  EXPECT_TRUE(about_origin.moment_Nmm.isApprox(Eigen::Vector3d(0, 0, -50)));
}

TEST(StaticsWrench, ShiftThereAndBackIsTheIdentity) {
  const Wrench w{Eigen::Vector3d(1, -2, 3), Eigen::Vector3d(40, 50, -60)};
  const Eigen::Vector3d a(10, 20, 30), b(-7, 8, 900);
  const Wrench back = shift_wrench(shift_wrench(w, a, b), b, a);
  EXPECT_TRUE(back.force_N.isApprox(w.force_N));
  EXPECT_TRUE(back.moment_Nmm.isApprox(w.moment_Nmm));
  // Moving along the force's own line does not change the moment.
  const Wrench along = shift_wrench(w, a, a + 3.0 * w.force_N);
  EXPECT_TRUE(along.moment_Nmm.isApprox(w.moment_Nmm));
}

}  // namespace
}  // namespace pkm::statics
