// Cutting loads along a path (statics/load_model.hpp): directions, the cutter-edge moment, rapids and points
// that do not move, line ranges, and a circle.
#include "statics/load_model.hpp"

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>

#include "core/units.hpp"

namespace pkm::statics {
namespace {

LoadPoint along_x() {
  LoadPoint p;
  p.tangent = Eigen::Vector3d::UnitX();
  p.tool_axis = Eigen::Vector3d::UnitZ();
  return p;
}

TEST(LoadModel, ComponentsAlongTangentNormalAndAxis) {
  LoadModel model;
  model.default_load.tangential_N = 1000;
  model.default_load.normal_N = 100;
  model.default_load.axial_N = 30;
  const Wrench w = model.wrench_at(along_x());
  // Travel +x under a tool pointing up: the left of travel (seen from the spindle) is +y.
  EXPECT_TRUE(w.force_N.isApprox(Eigen::Vector3d(-1000, 100, 30)));
  EXPECT_TRUE(w.moment_Nmm.isZero());  // no cutter radius: everything through the tool point
}

TEST(LoadModel, TangentialForceAtTheCutterEdgeGivesAMoment) {
  LoadModel model;
  model.default_load.tangential_N = 1000;
  model.default_load.cutter_radius_mm = 5;
  // Contact on the left, c = (0, 5, 0): (0, 5, 0) × (−1000, 0, 0) = (0, 0, 5000), |M| = P_τ R_Ф
  // (Smirnov 2019, §3.4.2).
  EXPECT_TRUE(model.wrench_at(along_x()).moment_Nmm.isApprox(Eigen::Vector3d(0, 0, 5000)));
  model.default_load.contact_side = -1;
  EXPECT_TRUE(model.wrench_at(along_x()).moment_Nmm.isApprox(Eigen::Vector3d(0, 0, -5000)));
}

TEST(LoadModel, TangentNeedNotBeUnit) {
  LoadModel model;
  model.default_load.tangential_N = 10;
  LoadPoint p = along_x();
  p.tangent *= 7.0;
  EXPECT_TRUE(model.wrench_at(p).force_N.isApprox(Eigen::Vector3d(-10, 0, 0)));
}

TEST(LoadModel, OnlyTheConstantLoadWhereNothingIsCut) {
  LoadModel model;
  model.default_load.tangential_N = 1000;
  model.default_load.normal_N = 100;
  model.default_load.axial_N = 50;
  model.default_load.cutter_radius_mm = 5;
  model.default_load.force_N = Eigen::Vector3d(1, 2, 3);
  model.default_load.moment_Nmm = Eigen::Vector3d(4, 5, 6);
  LoadPoint still = along_x();
  still.tangent = Eigen::Vector3d::Zero();
  Wrench w = model.wrench_at(still);
  EXPECT_EQ(w.force_N, Eigen::Vector3d(1, 2, 3));
  EXPECT_EQ(w.moment_Nmm, Eigen::Vector3d(4, 5, 6));
  LoadPoint rapid = along_x();
  rapid.cutting = false;
  w = model.wrench_at(rapid);
  EXPECT_EQ(w.force_N, Eigen::Vector3d(1, 2, 3));
  EXPECT_EQ(w.moment_Nmm, Eigen::Vector3d(4, 5, 6));
}

TEST(LoadModel, PlungeAlongTheToolAxisHasNoSide) {
  LoadModel model;
  model.default_load.tangential_N = 200;
  model.default_load.normal_N = 100;
  model.default_load.cutter_radius_mm = 5;
  LoadPoint plunge = along_x();
  plunge.tangent = -Eigen::Vector3d::UnitZ();  // down into the work
  const Wrench w = model.wrench_at(plunge);
  EXPECT_TRUE(w.force_N.isApprox(Eigen::Vector3d(0, 0, 200)));  // resists the feed: pushes up
  EXPECT_TRUE(w.moment_Nmm.isZero());
}

TEST(LoadModel, LaterBlocksWinAndTheDefaultFillsTheRest) {
  LoadModel model;
  model.default_load.tangential_N = 1;
  model.blocks.push_back({10, 20, CuttingLoad{}});
  model.blocks.back().load.tangential_N = 2;
  model.blocks.push_back({15, 30, CuttingLoad{}});
  model.blocks.back().load.tangential_N = 3;
  EXPECT_EQ(model.load_for_line(9).tangential_N, 1);
  EXPECT_EQ(model.load_for_line(10).tangential_N, 2);
  EXPECT_EQ(model.load_for_line(14).tangential_N, 2);
  EXPECT_EQ(model.load_for_line(15).tangential_N, 3);
  EXPECT_EQ(model.load_for_line(30).tangential_N, 3);
  EXPECT_EQ(model.load_for_line(31).tangential_N, 1);
  LoadPoint p = along_x();
  p.line = 12;
  EXPECT_TRUE(model.wrench_at(p).force_N.isApprox(Eigen::Vector3d(-2, 0, 0)));
}

TEST(LoadModel, EmptyOnlyWhenEveryCaseIsZero) {
  LoadModel model;
  EXPECT_TRUE(model.empty());
  model.default_load.cutter_radius_mm = 5;  // a radius alone applies no load
  model.default_load.contact_side = -1;
  EXPECT_TRUE(model.empty());
  model.blocks.push_back({1, 2, CuttingLoad{}});
  EXPECT_TRUE(model.empty());
  model.blocks.back().load.moment_Nmm.x() = 1;
  EXPECT_FALSE(model.empty());
}

TEST(LoadModel, ConstantTangentialLoadRotatesWithTheTangentOnACircle) {
  // The circle of Smirnov 2019, §3.4.2 (R = 40 mm, counter-clockwise): the cutting force turns with the feed
  // direction while its size and the cutter-edge moment stay constant.
  LoadModel model;
  model.default_load.tangential_N = 1000;
  model.default_load.normal_N = 100;
  model.default_load.cutter_radius_mm = 5;
  for (int k = 0; k < 360; k += 15) {
    const double angle = rad_from_deg(k);
    LoadPoint p;
    p.tangent = Eigen::Vector3d(-std::sin(angle), std::cos(angle), 0);
    const Wrench w = model.wrench_at(p);
    const Eigen::Vector3d inward(-std::cos(angle), -std::sin(angle), 0);  // left of counter-clockwise travel
    EXPECT_TRUE(w.force_N.isApprox(-1000.0 * p.tangent + 100.0 * inward)) << k;
    EXPECT_NEAR(w.force_N.norm(), std::hypot(1000.0, 100.0), 1e-9);
    EXPECT_TRUE(w.moment_Nmm.isApprox(Eigen::Vector3d(0, 0, 5000))) << k;
  }
}

}  // namespace
}  // namespace pkm::statics
