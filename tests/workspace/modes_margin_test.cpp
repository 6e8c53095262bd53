// The assembly-mode margin (workspace/modes_margin.hpp) checked against its definition, not against
// numbers it printed once: the configuration found is singular (det J small against det J at the pose, by the
// mechanism's own Jacobian) and its actuator distance is the margin; actuator changes below the margin,
// solved by warm-started forward kinematics, stay regular and in the pose's assembly mode; the margin shrinks
// as a pose moves towards a singular configuration; it scales with the machine; and along a program every
// sample carries its line and the summary is the samples' extreme.
#include "workspace/modes_margin.hpp"

#include <fmt/format.h>
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <Eigen/SVD>
#include <algorithm>
#include <cmath>
#include <limits>
#include <random>
#include <string>

#include "core/units.hpp"
#include "formats/modes_margin_output.hpp"
#include "io/pose_input.hpp"
#include "pipeline/load_program.hpp"
#include "planning/motion_plan.hpp"
#include "test_support.hpp"
#include "workspace/modes_margin_program.hpp"
#include "workspace/other_modes.hpp"

namespace pkm {
namespace {

workspace::AssemblyModeMargin mm_margin_of(const Mechanism& mechanism, const Pose& pose) {
  auto margin = workspace::assembly_mode_margin(mechanism, pose);
  if (!margin) {
    ADD_FAILURE() << margin.error().message;
    throw std::runtime_error(margin.error().message);
  }
  return std::move(margin.value());
}

Pose mm_user_pose(const Mechanism& mechanism, const std::vector<double>& values) {
  auto pose = pose_from_user(mechanism, values, "pose");
  if (!pose) {
    ADD_FAILURE() << pose.error().message;
    throw std::runtime_error(pose.error().message);
  }
  return *pose;
}

// det of the mechanism's Jacobian in its controlled coordinates: independent of the twist form the margin may
// use (the two differ by det E of the angle convention, which is far from 0 at these tilts).
double mm_coordinate_det(const Mechanism& mechanism, const Pose& pose) {
  auto j = mechanism.jacobian(pose);
  if (!j) {
    ADD_FAILURE() << j.error().message;
    return NAN;
  }
  return j->determinant();
}

// The ch5 hexapod (6-3) with every length times k: base joints on a 400·k mm circle, platform joints merged
// in pairs on a 200·k mm circle, the tool 150·k mm above them, home at z = 700·k.
std::string mm_ch5_scaled_text(double k) {
  std::string yaml = "type: hexapod\nangles: krylov\nbase_joints:\n";
  for (int j = 0; j < 6; ++j) {
    const double a = rad_from_deg(60.0 * j);
    yaml += fmt::format("  - [{:.17g}, {:.17g}, 0]\n", 400 * k * std::cos(a), 400 * k * std::sin(a));
  }
  yaml += "platform_joints:\n";
  for (int j = 0; j < 6; ++j) {
    const double a = rad_from_deg(30.0 + 120.0 * (j / 2));
    yaml += fmt::format("  - [{:.17g}, {:.17g}, 0]\n", 200 * k * std::cos(a), 200 * k * std::sin(a));
  }
  yaml += fmt::format("tool: [0, 0, {:.17g}]\nhome: [0, 0, {:.17g}, 0, 0, 0]\n", 150 * k, 700 * k);
  return yaml;
}

TEST(ModesMargin, FoundConfigurationIsSingularAndItsActuatorDistanceIsTheMargin) {
  struct Case {
    std::string machine;
    std::vector<double> pose;
  };
  const std::vector<Case> cases = {
      {"hexapod_ch5.yaml", {0, 0, 700, 0, 0, 0}},
      {"hexapod_ch5.yaml", {40, -30, 760, 5, -4, 10}},
      {"planar3.yaml", {0, 0, 15}},
      {"planar3.yaml", {30, -20, 5}},
      {"tripod.yaml", {0, 0, 800, 0, 0, 0}},
      {"tricept.yaml", {}},
      {"hexaglide.yaml", {}},
  };
  for (const Case& c : cases) {
    SCOPED_TRACE(c.machine);
    const Machine machine = test::machine_from_example("examples/machines/" + c.machine);
    const Mechanism& mech = *machine.mechanism;
    const Pose pose = c.pose.empty() ? mech.home() : mm_user_pose(mech, c.pose);
    const workspace::AssemblyModeMargin m = mm_margin_of(mech, pose);
    ASSERT_TRUE(m.found) << m.note;
    EXPECT_TRUE(m.note.empty()) << m.note;
    EXPECT_GT(m.margin_mm, 0.0);
    // Singular by the mechanism's own Jacobian, not only by the search's constraint.
    const double det0 = mm_coordinate_det(mech, m.pose);
    const double det_star = mm_coordinate_det(mech, m.singular_pose);
    EXPECT_LT(std::abs(det_star), 1e-6 * std::abs(det0)) << det_star << " against " << det0;
    EXPECT_LT(std::abs(m.det_ratio), 1e-8);
    // The margin is the actuator distance of that configuration, by inverse kinematics.
    auto q0 = mech.inverse(m.pose);
    auto q_star = mech.inverse(m.singular_pose);
    ASSERT_TRUE(q0 && q_star);
    EXPECT_NEAR((*q_star - *q0).norm(), m.margin_mm, 1e-9 * m.margin_mm);
    EXPECT_NEAR((m.singular_actuators - *q0).norm(), m.margin_mm, 1e-9 * m.margin_mm);
    // The first-order condition of the nearest point: where J(X*) is singular, the actuator changes it can
    // make span a hyperplane, the tangent of the image of the singular configurations; the nearest of them
    // is reached along its normal, the left null vector of J(X*).
    const Eigen::JacobiSVD<Eigen::MatrixXd> svd(Eigen::MatrixXd(mech.jacobian(m.singular_pose).value()),
                                                Eigen::ComputeFullU);
    const Eigen::VectorXd normal = svd.matrixU().col(svd.matrixU().cols() - 1);
    const Eigen::VectorXd change = *q_star - *q0;
    EXPECT_GT(std::abs(normal.dot(change)) / change.norm(), 1.0 - 1e-6)
        << "Δq " << change.transpose() << ", normal " << normal.transpose();
  }
}

TEST(ModesMargin, ActuatorChangesBelowTheMarginStayRegularAndInTheMode) {
  std::mt19937_64 rng(20);
  for (const std::string file : {"hexapod_ch5.yaml", "planar3.yaml", "tripod.yaml", "hexaglide.yaml"}) {
    SCOPED_TRACE(file);
    const Machine machine = test::machine_from_example("examples/machines/" + file);
    const Mechanism& mech = *machine.mechanism;
    const Pose x0 = mech.home();
    const workspace::AssemblyModeMargin m = mm_margin_of(mech, x0);
    ASSERT_TRUE(m.found) << m.note;
    double det0 = 0.0;
    ASSERT_TRUE(workspace::margin_determinant(mech, x0, det0));
    FkOptions options;
    options.require_same_branch = false;  // let the solver go where it goes; the test judges
    options.max_iterations = 200;
    auto own = mech.forward(m.actuators, x0, options);
    ASSERT_TRUE(own) << own.error().message;
    const int n = mech.actuator_count();
    for (int trial = 0; trial < 60; ++trial) {
      ActuatorVector direction(n);
      for (int j = 0; j < n; ++j) direction[j] = std::normal_distribution<double>(0.0, 1.0)(rng);
      const double radius = test::uniform(rng, 0.05, 0.95) * m.margin_mm;
      const ActuatorVector q = m.actuators + radius * direction.normalized();
      auto fk = mech.forward(q, x0, options);
      ASSERT_TRUE(fk) << "trial " << trial << ", |Δq| " << radius << ": " << fk.error().message;
      double det = 0.0;
      ASSERT_TRUE(workspace::margin_determinant(mech, fk->pose, det));
      EXPECT_GT(det * det0, 0.0) << "trial " << trial << ", |Δq| " << radius << " of " << m.margin_mm;
      EXPECT_EQ(fk->branch, own->branch) << "trial " << trial;
    }
  }
}

TEST(ModesMargin, ShrinksAsThePoseApproachesASingularConfiguration) {
  const Machine machine = test::machine_from_example("examples/machines/planar3.yaml");
  const Mechanism& mech = *machine.mechanism;
  // Turn the platform from φ = 60° back towards the base's orientation until det J changes sign, then bisect:
  // a singular configuration X_s of the pose's aspect, found without the margin's search. (The planar
  // tripod's platform triangle is similar to its base's, so at φ = 0 every position is singular: the three
  // struts meet in the triangles' centre of similitude.)
  const double x_mm = 20.0, y_mm = -10.0, start_deg = 60.0;
  const auto at_phi = [&](double phi_deg) { return mm_user_pose(mech, {x_mm, y_mm, phi_deg}); };
  const double det_start = mm_coordinate_det(mech, at_phi(start_deg));
  double inside = start_deg, outside = NAN;
  for (double phi = start_deg - 1.0; phi > start_deg - 180.0; phi -= 1.0) {
    if (mm_coordinate_det(mech, at_phi(phi)) * det_start <= 0.0) {
      outside = phi;
      break;
    }
    inside = phi;
  }
  ASSERT_TRUE(std::isfinite(outside)) << "no singular configuration by turning the platform";
  for (int k = 0; k < 60; ++k) {
    const double mid = 0.5 * (inside + outside);
    (mm_coordinate_det(mech, at_phi(mid)) * det_start > 0.0 ? inside : outside) = mid;
  }
  const double singular_phi = inside;
  auto q_singular = mech.inverse(at_phi(singular_phi));
  ASSERT_TRUE(q_singular);
  double previous = INFINITY;
  for (double t : {0.0, 0.3, 0.6, 0.8, 0.9, 0.97}) {
    const Pose pose = at_phi(start_deg + t * (singular_phi - start_deg));
    const workspace::AssemblyModeMargin m = mm_margin_of(mech, pose);
    ASSERT_TRUE(m.found) << "t = " << t << ": " << m.note;
    EXPECT_LT(m.margin_mm, previous) << "t = " << t;
    previous = m.margin_mm;
    // X_s is a singular configuration of this aspect: the margin is no larger than its actuator distance.
    auto q = mech.inverse(pose);
    ASSERT_TRUE(q);
    EXPECT_LE(m.margin_mm, (*q_singular - *q).norm() * (1 + 1e-9)) << "t = " << t;
  }
  EXPECT_LT(previous, 0.1 * mm_margin_of(mech, at_phi(start_deg)).margin_mm);
}

TEST(ModesMargin, ScalesWithTheMachine) {
  const Machine unit = test::machine_from_text(mm_ch5_scaled_text(1.0), "ch5.yaml");
  for (double k : {0.5, 3.0}) {
    SCOPED_TRACE(k);
    const Machine scaled = test::machine_from_text(mm_ch5_scaled_text(k), "ch5_scaled.yaml");
    for (const std::vector<double>& p :
         {std::vector<double>{0, 0, 700, 0, 0, 0}, std::vector<double>{30, 20, 650, -6, 4, 12}}) {
      const Pose pose = mm_user_pose(*unit.mechanism, p);
      Pose pose_k = pose;
      pose_k.position_mm *= k;
      const workspace::AssemblyModeMargin m1 = mm_margin_of(*unit.mechanism, pose);
      const workspace::AssemblyModeMargin mk = mm_margin_of(*scaled.mechanism, pose_k);
      ASSERT_TRUE(m1.found && mk.found);
      EXPECT_NEAR(mk.margin_mm, k * m1.margin_mm, 1e-6 * k * m1.margin_mm);
      // The ch5 hexapod is 3-fold symmetric about z: at a pose on its axis the nearest singular poses come in
      // threes with equal margins, and rounding picks one of them. So the singular pose scales up to a turn
      // by a multiple of 120° about z.
      double nearest = std::numeric_limits<double>::infinity();
      for (int turn = 0; turn < 3; ++turn) {
        const Eigen::Vector3d turned = Eigen::AngleAxisd(turn * 2.0 * kPi / 3.0, Eigen::Vector3d::UnitZ()) *
                                       m1.singular_pose.position_mm;
        nearest = std::min(nearest, (mk.singular_pose.position_mm - k * turned).norm());
      }
      EXPECT_NEAR(nearest, 0.0, 1e-4 * k * m1.margin_mm);
    }
  }
}

TEST(ModesMargin, SingularPoseHasMarginZero) {
  // The planar tripod turned onto its singular configuration (found as in the shrinking test): margin 0.
  const Machine machine = test::machine_from_example("examples/machines/planar3.yaml");
  const Mechanism& mech = *machine.mechanism;
  const Pose home = mech.home();
  const workspace::AssemblyModeMargin m = mm_margin_of(mech, home);
  ASSERT_TRUE(m.found);
  const workspace::AssemblyModeMargin at_singular = mm_margin_of(mech, m.singular_pose);
  ASSERT_TRUE(at_singular.found);
  EXPECT_LT(at_singular.margin_mm, 1e-6 * m.margin_mm);
}

TEST(ModesMargin, OtherModesAreEnumeratedWhereTheMechanismCan) {
  // The 6-3 hexapod enumerates its modes: the pose's own is among them, every one has the same actuators.
  const Machine hexapod = test::machine_from_example("examples/machines/hexapod_ch5.yaml");
  const Mechanism& mech = *hexapod.mechanism;
  const Pose pose = mm_user_pose(mech, {20, -10, 720, 3, 2, -5});
  auto q = mech.inverse(pose);
  ASSERT_TRUE(q);
  const workspace::OtherAssemblyModes modes = workspace::other_assembly_modes(mech, pose, *q);
  ASSERT_TRUE(modes.enumerated) << modes.note;
  EXPECT_TRUE(modes.current_found) << modes.note;
  EXPECT_GE(modes.real_modes, 2);
  EXPECT_GT(modes.nearest_other_position_mm + modes.nearest_other_rotation_deg, 1e-3);
  auto q_other = mech.inverse(modes.nearest_other);
  ASSERT_TRUE(q_other);
  EXPECT_LT((*q_other - *q).norm(), 1e-6);
  const PoseDistance d = pose_distance(pose, modes.nearest_other);
  EXPECT_NEAR(d.position_mm, modes.nearest_other_position_mm, 1e-9);
  EXPECT_NEAR(rad_from_deg(modes.nearest_other_rotation_deg), d.rotation_rad, 1e-12);
  // A glide machine enumerates its modes too (its carriages' Gough–Stewart platform).
  const Machine glide = test::machine_from_example("examples/machines/hexaglide.yaml");
  const Pose glide_home = glide.mechanism->home();
  auto q_glide = glide.mechanism->inverse(glide_home);
  ASSERT_TRUE(q_glide);
  const workspace::OtherAssemblyModes glide_modes =
      workspace::other_assembly_modes(*glide.mechanism, glide_home, *q_glide);
  EXPECT_TRUE(glide_modes.enumerated) << glide_modes.note;
  EXPECT_TRUE(glide_modes.current_found) << glide_modes.note;
  EXPECT_GE(glide_modes.real_modes, 2);
  EXPECT_TRUE(std::isfinite(glide_modes.nearest_other_position_mm));
}

TEST(ModesMargin, AlongAProgramEverySampleHasItsLineAndTheSummaryIsTheirMinimum) {
  const Machine machine = test::machine_from_example("examples/machines/hexapod_ch5.yaml");
  auto program = pipeline::load_program_for(machine, test::source_path("examples/programs/ch5_line.ngc"));
  ASSERT_TRUE(program) << program.error().message;
  auto plan = planning::plan_motion(machine, *program, {});
  ASSERT_TRUE(plan) << plan.error().message;
  workspace::ProgramModesMarginOptions options;
  options.samples = 12;
  auto r = workspace::modes_margin_along_plan(machine, *plan, options);
  ASSERT_TRUE(r) << r.error().message;
  ASSERT_EQ(r->samples.size(), 14u);  // the start, 12 between, the end
  EXPECT_EQ(r->samples.front().time_s, 0.0);
  EXPECT_NEAR(r->samples.back().time_s, plan->duration_s, plan->period_s);
  double smallest = INFINITY;
  for (std::size_t i = 0; i < r->samples.size(); ++i) {
    const workspace::ModesMarginSample& s = r->samples[i];
    if (i > 0) {
      EXPECT_GT(s.time_s, r->samples[i - 1].time_s);
      // Evenly in time, to a servo period.
      EXPECT_NEAR(s.time_s - r->samples[i - 1].time_s, plan->duration_s / 13, 1.01 * plan->period_s);
    }
    // The moves of ch5_line.ngc are on lines 5 (G0) and 6 (G1).
    EXPECT_TRUE(s.line == 5 || s.line == 6) << s.line;
    ASSERT_TRUE(s.margin.found) << s.margin.note;
    // Each sample is the margin at its own pose.
    const workspace::AssemblyModeMargin again = mm_margin_of(*machine.mechanism, s.margin.pose);
    EXPECT_NEAR(again.margin_mm, s.margin.margin_mm, 1e-9 * s.margin.margin_mm);
    smallest = std::min(smallest, s.margin.margin_mm);
    EXPECT_TRUE(s.modes.enumerated) << s.modes.note;
  }
  ASSERT_TRUE(r->summary.min_margin);
  EXPECT_EQ(r->samples[*r->summary.min_margin].margin.margin_mm, smallest);
  EXPECT_EQ(r->summary.margins_found, 14);
  EXPECT_GE(r->summary.min_real_modes, 2);
  EXPECT_LE(r->summary.min_real_modes, r->summary.max_real_modes);
  // The CSV has a row per sample under its header.
  const std::string csv = formats::modes_margin_csv(*machine.mechanism, *r);
  EXPECT_EQ(csv.rfind("time_s,line,x_mm,", 0), 0u) << csv.substr(0, 80);
  EXPECT_EQ(std::count(csv.begin(), csv.end(), '\n'), 15);
  // No samples is a parameter error.
  options.samples = 0;
  auto none = workspace::modes_margin_along_plan(machine, *plan, options);
  ASSERT_FALSE(none);
  EXPECT_EQ(none.error().code, ErrorCode::bad_input);
  EXPECT_NE(none.error().message.find("samples"), std::string::npos) << none.error().message;
}

}  // namespace
}  // namespace pkm
