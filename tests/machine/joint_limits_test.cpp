// Passive-joint swing limits and the conditioning limit (machine/joint_limits.hpp): the machine file's keys,
// the joint angles against hand-computed values, the messages of the checks.
#include "machine/joint_limits.hpp"

#include <fmt/format.h>
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "core/units.hpp"
#include "limits_test_support.hpp"
#include "machine/conditioning.hpp"
#include "machine/planar3.hpp"
#include "test_support.hpp"

namespace pkm {
namespace {

using test::appended_line;
using test::kCh5HexapodText;

constexpr double kAngleTolerance = 1e-12;

Machine ch5_with(const std::string& extra) {
  return test::machine_from_text(kCh5HexapodText + extra);
}

std::string joint_limits_load_error(const std::string& text) {
  auto m = parse_machine_text(text, "test.yaml");
  if (m) {
    ADD_FAILURE() << "expected an error for:\n" << text;
    return {};
  }
  EXPECT_EQ(m.error().code, ErrorCode::bad_input);
  return m.error().message;
}

Pose translated(const Pose& pose, const Eigen::Vector3d& by_mm) {
  Pose out = pose;
  out.position_mm += by_mm;
  return out;
}

// The ch5 geometry as the test's own numbers (base frame; platform joints in the platform frame, z = 0).
const Eigen::Vector3d kBase[6] = {
    {400.0, 0.0, 0.0},  {200.0, 346.41016151377545, 0.0},   {-200.0, 346.41016151377545, 0.0},
    {-400.0, 0.0, 0.0}, {-200.0, -346.41016151377545, 0.0}, {200.0, -346.41016151377545, 0.0}};
const Eigen::Vector3d kPlatform[6] = {{173.20508075688772, 100, 0},
                                      {173.20508075688772, 100, 0},
                                      {-173.20508075688772, 100, 0},
                                      {-173.20508075688772, 100, 0},
                                      {0, -200, 0},
                                      {0, -200, 0}};

// ---- the machine file -----------------------------------------------------------------------------------

TEST(JointLimitsFile, ReadsEveryKeyWithItsLine) {
  const int first = appended_line(kCh5HexapodText) + 1;
  const Machine m = ch5_with(
      "limits:\n  base_joint_max_deg: 40\n  platform_joint_max_deg: 45\n"
      "  max_condition_number: 4000\n");
  const JointLimits& l = m.joint_limits;
  EXPECT_NEAR(*l.base_joint_max_rad, rad_from_deg(40), 1e-15);
  EXPECT_NEAR(*l.platform_joint_max_rad, rad_from_deg(45), 1e-15);
  EXPECT_EQ(*l.max_condition_number, 4000.0);
  EXPECT_EQ(l.base_joint_max_line, first);
  EXPECT_EQ(l.platform_joint_max_line, first + 1);
  EXPECT_EQ(l.max_condition_number_line, first + 2);
  EXPECT_NEAR(l.base_joint_min_cos, std::cos(rad_from_deg(40)), 1e-15);
  EXPECT_NEAR(l.platform_joint_min_cos, std::cos(rad_from_deg(45)), 1e-15);
}

TEST(JointLimitsFile, DefaultsWithoutKeys) {
  const Machine m = test::machine_from_text(kCh5HexapodText);
  EXPECT_FALSE(m.joint_limits.base_joint_max_rad);
  EXPECT_FALSE(m.joint_limits.platform_joint_max_rad);
  EXPECT_FALSE(m.joint_limits.max_condition_number);
  EXPECT_EQ(m.joint_limits.base_joint_max_line, 0);
  // The neutral axes are still known (the angles can be reported without limits): the home strut directions.
  ASSERT_EQ(m.joint_axes.count, 6);
  EXPECT_EQ(m.joint_axes.base_line, 0);
  EXPECT_EQ(m.joint_axes.platform_line, 0);
  const Eigen::Vector3d home_strut_1 = (kPlatform[0] + Eigen::Vector3d(0, 0, 550) - kBase[0]).normalized();
  EXPECT_LT((m.joint_axes.base[0] - home_strut_1).norm(), 1e-15);
  EXPECT_LT((m.joint_axes.platform[0] - home_strut_1).norm(), 1e-15);  // level home: same in both frames
}

TEST(JointLimitsFile, BadValuesNameFileLineAndKey) {
  const int line = appended_line(kCh5HexapodText) + 1;
  struct Case {
    const char* entry;
    const char* expected;
  };
  for (const Case& c : {
           Case{"base_joint_max_deg: 0", "limits.base_joint_max_deg: must be in (0, 180] degrees, got 0"},
           Case{"base_joint_max_deg: 181", "limits.base_joint_max_deg: must be in (0, 180] degrees, got 181"},
           Case{"platform_joint_max_deg: -5", "limits.platform_joint_max_deg: must be in (0, 180] degrees"},
           Case{"platform_joint_max_deg: wide", "limits.platform_joint_max_deg: expected a number"},
           Case{"max_condition_number: 0.5", "limits.max_condition_number: must be at least 1"},
           Case{"max_condition_number: [200]", "limits.max_condition_number: expected a number"},
           Case{"joint_max_deg: 40", "limits.joint_max_deg: unknown key"},
           Case{"actuator_speed: -1", "limits.actuator_speed: must be positive"},
       }) {
    const std::string message =
        joint_limits_load_error(fmt::format("{}limits:\n  {}\n", kCh5HexapodText, c.entry));
    EXPECT_TRUE(test::names_yaml_place(message, fmt::format("test.yaml:{}", line), c.expected))
        << "got: " << message;
  }
}

TEST(JointLimitsFile, GivenNeutralAxesAreNormalisedAndKeepTheirLines) {
  const int first = appended_line(kCh5HexapodText);
  const Machine m = ch5_with(
      "base_joint_axes: [[0, 0, 2], [0, 0, 2], [0, 0, 2], [0, 0, 2], [0, 0, 2], [0, 0, 2]]\n"
      "platform_joint_axes: [[0, 0, 1], [0, 0, 1], [0, 0, 1], [0, 0, 1], [0, 0, 1], [0, 0, 1]]\n");
  for (int j = 0; j < 6; ++j) {
    EXPECT_EQ(m.joint_axes.base[j], Eigen::Vector3d::UnitZ());
    EXPECT_EQ(m.joint_axes.platform[j], Eigen::Vector3d::UnitZ());
  }
  EXPECT_EQ(m.joint_axes.base_line, first);
  EXPECT_EQ(m.joint_axes.platform_line, first + 1);
}

TEST(JointLimitsFile, BadNeutralAxesAreRejected) {
  const int line = appended_line(kCh5HexapodText);
  const std::string count = joint_limits_load_error(std::string(kCh5HexapodText) +
                                                    "base_joint_axes: [[0, 0, 1], [0, 0, 1], [0, 0, 1]]\n");
  EXPECT_NE(count.find(fmt::format("test.yaml:{}:18: base_joint_axes: expected a list of 6 points", line)),
            std::string::npos)
      << count;
  const std::string zero =
      joint_limits_load_error(std::string(kCh5HexapodText) +
                              "platform_joint_axes: [[0, 0, 1], [0, 0, 1], [0, 0, 0], [0, 0, 1], "
                              "[0, 0, 1], [0, 0, 1]]\n");
  EXPECT_NE(
      zero.find(fmt::format("test.yaml:{}:45: platform_joint_axes[2]: a direction must not be zero", line)),
      std::string::npos)
      << zero;
}

TEST(JointLimitsFile, HomeBeyondAJointLimitIsRejected) {
  // Axes along x put every base joint of the home pose far from its axis.
  const int limit_line = appended_line(kCh5HexapodText) + 2;
  const std::string message = joint_limits_load_error(
      std::string(kCh5HexapodText) +
      "base_joint_axes: [[1, 0, 0], [1, 0, 0], [1, 0, 0], [1, 0, 0], [1, 0, 0], [1, 0, 0]]\n"
      "limits:\n  base_joint_max_deg: 40\n");
  EXPECT_NE(message.find("home: the home pose is beyond a joint limit: base joint 1 swings"),
            std::string::npos)
      << message;
  EXPECT_NE(message.find(fmt::format("limits.base_joint_max_deg = 40 (test.yaml:{})", limit_line)),
            std::string::npos)
      << message;
}

TEST(JointLimitsFile, HomeBeyondTheConditioningLimitIsRejected) {
  const std::string message =
      joint_limits_load_error(std::string(kCh5HexapodText) + "limits: {max_condition_number: 1}\n");
  EXPECT_NE(message.find("home: the home pose is too badly conditioned: the Jacobian's condition number"),
            std::string::npos)
      << message;
}

TEST(JointLimitsFile, PlanarMachinesHaveNoSwingLimitsButMayLimitConditioning) {
  const std::string planar3 = R"(type: planar3
base_joints: [[0.0, 200.0], [-173.20508075688772, -100.0], [173.20508075688772, -100.0]]
platform_joints: [[0.0, 100.0], [-86.60254037844386, -50.0], [86.60254037844386, -50.0]]
home: [0.0, 0.0, 15.0]
)";
  const std::string swing = joint_limits_load_error(planar3 + "limits: {base_joint_max_deg: 40}\n");
  EXPECT_NE(swing.find("test.yaml:5:30: limits.base_joint_max_deg: planar mechanisms have pin joints"),
            std::string::npos)
      << swing;
  const std::string axes = joint_limits_load_error(planar3 + "base_joint_axes: [[0, 1], [0, 1], [0, 1]]\n");
  EXPECT_NE(axes.find("test.yaml:5:1: base_joint_axes: unknown key"), std::string::npos) << axes;
  const Machine m = test::machine_from_text(planar3 + "limits: {max_condition_number: 1000}\n");
  EXPECT_EQ(*m.joint_limits.max_condition_number, 1000.0);
  EXPECT_EQ(m.joint_axes.count, 0);
}

// ---- the angles ----------------------------------------------------------------------------------------

TEST(JointLimitsAngles, ZeroAtHomeForEveryShippedMachine) {
  struct Case {
    const char* file;
    int struts;
  };
  for (const Case& c :
       {Case{"hexapod_ch5.yaml", 6}, Case{"hexapod_ch3.yaml", 6}, Case{"hexapod_genhexkins.yaml", 6},
        Case{"hexapod_refined.yaml", 6}, Case{"tripod.yaml", 3}, Case{"tricept.yaml", 3},
        Case{"hexaglide.yaml", 6}, Case{"triglide.yaml", 3}, Case{"rotopod.yaml", 6}, Case{"planar2.yaml", 0},
        Case{"planar3.yaml", 0}}) {
    const Machine m = test::machine_from_example(std::string("examples/machines/") + c.file);
    const PassiveJointAngles a = passive_joint_angles(m, m.mechanism->home());
    ASSERT_EQ(a.count, c.struts) << c.file;
    for (int j = 0; j < a.count; ++j) {
      EXPECT_NEAR(a.base_rad[j], 0.0, 1e-7) << c.file << " base joint " << j + 1;
      EXPECT_NEAR(a.platform_rad[j], 0.0, 1e-7) << c.file << " platform joint " << j + 1;
    }
    EXPECT_TRUE(check_joint_limits(m, m.mechanism->home()).ok()) << c.file;
  }
}

TEST(JointLimitsAngles, HexapodTranslationAgainstVerticalAxes) {
  // Vertical neutral axes: a joint's swing is the strut's angle from vertical, atan(horizontal / vertical).
  const Machine m = ch5_with(
      "base_joint_axes: [[0, 0, 1], [0, 0, 1], [0, 0, 1], [0, 0, 1], [0, 0, 1], [0, 0, 1]]\n"
      "platform_joint_axes: [[0, 0, 1], [0, 0, 1], [0, 0, 1], [0, 0, 1], [0, 0, 1], [0, 0, 1]]\n");
  const Eigen::Vector3d shift(-50, 30, -100);
  const PassiveJointAngles a = passive_joint_angles(m, translated(m.mechanism->home(), shift));
  ASSERT_EQ(a.count, 6);
  // Strut 1 by hand: platform joint (173.205 − 50, 100 + 30, 700 − 150 − 100), base joint (400, 0, 0).
  EXPECT_NEAR(a.base_rad[0], std::atan(std::hypot(400.0 - 123.20508075688772, 130.0) / 450.0),
              kAngleTolerance);
  for (int j = 0; j < 6; ++j) {
    const Eigen::Vector3d strut = kPlatform[j] + Eigen::Vector3d(0, 0, 550) + shift - kBase[j];
    const double expected = std::atan(std::hypot(strut.x(), strut.y()) / strut.z());
    EXPECT_NEAR(a.base_rad[j], expected, kAngleTolerance) << j;
    EXPECT_NEAR(a.platform_rad[j], expected, kAngleTolerance) << j;  // no rotation: same angle at both ends
  }
}

TEST(JointLimitsAngles, TranslationAlongAStrutKeepsItsJointsCentred) {
  // Home neutral axes: moving the platform along strut 1 keeps strut 1's direction, so its joints stay at 0,
  // while strut 4 (opposite) turns by the angle between its old and new directions.
  const Machine m = test::machine_from_text(kCh5HexapodText);
  const Eigen::Vector3d strut1 = kPlatform[0] + Eigen::Vector3d(0, 0, 550) - kBase[0];
  const Eigen::Vector3d shift = 100.0 * strut1.normalized();
  const PassiveJointAngles a = passive_joint_angles(m, translated(m.mechanism->home(), shift));
  EXPECT_NEAR(a.base_rad[0], 0.0, 1e-7);
  EXPECT_NEAR(a.platform_rad[0], 0.0, 1e-7);
  const Eigen::Vector3d strut4 = kPlatform[3] + Eigen::Vector3d(0, 0, 550) - kBase[3];
  const double expected = std::acos(strut4.normalized().dot((strut4 + shift).normalized()));
  EXPECT_NEAR(a.base_rad[3], expected, 1e-9);
  EXPECT_NEAR(a.platform_rad[3], expected, 1e-9);
}

TEST(JointLimitsAngles, PlatformRotationTurnsOnlyThePlatformSide) {
  // A pure rotation of the platform about the tool point by θ about z: every platform-side axis turns with
  // the platform; the base side sees the strut move, the platform side sees it in its own turned frame.
  const Machine m = test::machine_from_text(kCh5HexapodText);
  Pose pose = m.mechanism->home();
  pose.rotation = Eigen::AngleAxisd(rad_from_deg(5), Eigen::Vector3d::UnitZ()).toRotationMatrix();
  const PassiveJointAngles a = passive_joint_angles(m, pose);
  for (int j = 0; j < 6; ++j) {
    const Eigen::Vector3d home_strut = kPlatform[j] + Eigen::Vector3d(0, 0, 550) - kBase[j];
    const Eigen::Vector3d strut =
        pose.rotation * (kPlatform[j] - Eigen::Vector3d(0, 0, 150)) + pose.position_mm - kBase[j];
    EXPECT_NEAR(a.base_rad[j], std::acos(home_strut.normalized().dot(strut.normalized())), 1e-9) << j;
    const Eigen::Vector3d in_platform = pose.rotation.transpose() * strut;
    EXPECT_NEAR(a.platform_rad[j], std::acos(home_strut.normalized().dot(in_platform.normalized())), 1e-9)
        << j;
  }
}

TEST(JointLimitsAngles, RotopodCarriagesTurnWithTheirJoints) {
  // Turning a rotopod's platform about the circle's axis moves every carriage round the circle by the same
  // angle: the whole machine turns rigidly, so no joint swings in its (turning) mount.
  const Machine m = test::machine_from_example("examples/machines/rotopod.yaml");
  Pose pose = m.mechanism->home();
  const Eigen::Matrix3d turn =
      Eigen::AngleAxisd(rad_from_deg(25), Eigen::Vector3d::UnitZ()).toRotationMatrix();
  pose.rotation = turn * pose.rotation;
  pose.position_mm = turn * pose.position_mm;  // the tool point is on the axis: stays put
  const PassiveJointAngles a = passive_joint_angles(m, pose);
  ASSERT_EQ(a.count, 6);
  for (int j = 0; j < 6; ++j) {
    EXPECT_NEAR(a.base_rad[j], 0.0, 1e-7) << j;
    EXPECT_NEAR(a.platform_rad[j], 0.0, 1e-7) << j;
  }
  // A tilt does swing them.
  Pose tilted = m.mechanism->home();
  tilted.rotation = Eigen::AngleAxisd(rad_from_deg(5), Eigen::Vector3d::UnitX()).toRotationMatrix();
  const PassiveJointAngles t = passive_joint_angles(m, tilted);
  EXPECT_GT(t.base_rad[0] + t.platform_rad[0], rad_from_deg(0.5));
}

TEST(JointLimitsAngles, HexaglideCarriagesSlidingTogetherKeepJointsCentred) {
  // All guides are parallel to x: moving the platform along x moves every carriage by as much.
  const Machine m = test::machine_from_example("examples/machines/hexaglide.yaml");
  const PassiveJointAngles a = passive_joint_angles(m, translated(m.mechanism->home(), {120, 0, 0}));
  ASSERT_EQ(a.count, 6);
  for (int j = 0; j < 6; ++j) {
    EXPECT_NEAR(a.base_rad[j], 0.0, 1e-7) << j;
    EXPECT_NEAR(a.platform_rad[j], 0.0, 1e-7) << j;
  }
  const PassiveJointAngles lifted = passive_joint_angles(m, translated(m.mechanism->home(), {0, 0, 40}));
  EXPECT_GT(lifted.base_rad[0], rad_from_deg(1));
}

TEST(JointLimitsAngles, ReducedMechanismsCompleteThePose) {
  // Tripod and tricept: only the controlled coordinates count; the angles are those of the completed pose.
  for (const char* file : {"examples/machines/tripod.yaml", "examples/machines/tricept.yaml"}) {
    const Machine m = test::machine_from_example(file);
    const Mechanism& mech = *m.mechanism;
    PoseVector c = vector_from_pose(mech.convention(), mech.home());
    const AxisMask mask = mech.controlled_axes();
    for (int axis = 0; axis < 6; ++axis) {
      if (mask.controlled[axis]) c[axis] += axis < 3 ? 20.0 : rad_from_deg(4);
    }
    const Pose incomplete = pose_from_vector(mech.convention(), c);
    const Pose complete = *mech.complete_pose(incomplete);
    const PassiveJointAngles a = passive_joint_angles(m, incomplete);
    const PassiveJointAngles b = passive_joint_angles(m, complete);
    ASSERT_EQ(a.count, 3) << file;
    for (int j = 0; j < 3; ++j) {
      EXPECT_NEAR(a.base_rad[j], b.base_rad[j], 1e-12) << file;
      EXPECT_NEAR(a.platform_rad[j], b.platform_rad[j], 1e-12) << file;
      EXPECT_GT(a.base_rad[j] + a.platform_rad[j], 1e-4) << file;
    }
  }
}

TEST(JointLimitsAngles, UnreachableCarriageGivesNaNAndAnError) {
  Machine glide = test::machine_from_example("examples/machines/hexaglide.yaml");
  glide.joint_limits.base_joint_max_rad = rad_from_deg(60);
  glide.joint_limits.update_cosines();
  const Pose far = translated(glide.mechanism->home(), {0, 0, -2000});  // 2 m under the rails: out of reach
  const PassiveJointAngles a = passive_joint_angles(glide, far);
  EXPECT_EQ(a.count, 6);
  EXPECT_TRUE(std::isnan(a.base_rad[0]));
  const Status s = check_joint_limits(glide, far);
  ASSERT_FALSE(s.ok());
  EXPECT_EQ(s.error().code, ErrorCode::unreachable);
}

// ---- check_joint_limits --------------------------------------------------------------------------------

TEST(JointLimitsCheck, MessageNamesTheJointItsAngleTheLimitAndTheLine) {
  const int first = appended_line(kCh5HexapodText) + 1;
  const Machine m = ch5_with("limits:\n  base_joint_max_deg: 60\n  platform_joint_max_deg: 10\n");
  const Pose pose = translated(m.mechanism->home(), {150, 0, 0});
  const PassiveJointAngles a = passive_joint_angles(m, pose);
  int first_beyond = -1;
  for (int j = 0; j < 6 && first_beyond < 0; ++j) {
    ASSERT_LT(a.base_rad[j], rad_from_deg(60));
    if (a.platform_rad[j] > rad_from_deg(10)) first_beyond = j;
  }
  ASSERT_GE(first_beyond, 0) << "the pose must swing a platform joint beyond 10 deg";
  const Status s = check_joint_limits(m, pose);
  ASSERT_FALSE(s.ok());
  EXPECT_EQ(s.error().code, ErrorCode::limit_exceeded);
  EXPECT_EQ(
      s.error().message,
      fmt::format(
          "platform joint {} swings {:.1f} deg, beyond limits.platform_joint_max_deg = 10 (test.yaml:{})",
          first_beyond + 1, deg_from_rad(a.platform_rad[first_beyond]), first + 1));

  const Machine tight_base = ch5_with("limits:\n  base_joint_max_deg: 5\n");
  const Status b = check_joint_limits(tight_base, pose);
  ASSERT_FALSE(b.ok());
  EXPECT_EQ(b.error().message.rfind("base joint ", 0), 0u) << b.error().message;
  EXPECT_NE(b.error().message.find(fmt::format("limits.base_joint_max_deg = 5 (test.yaml:{})", first)),
            std::string::npos)
      << b.error().message;
}

TEST(JointLimitsCheck, LimitsBeyondNinetyDegrees) {
  // Downward axes: every base joint swings 180° minus its strut's angle from vertical (24.3° at home).
  const Machine m = ch5_with(
      "base_joint_axes: [[0, 0, -1], [0, 0, -1], [0, 0, -1], [0, 0, -1], [0, 0, -1], [0, 0, -1]]\n"
      "limits: {base_joint_max_deg: 160}\n");
  EXPECT_TRUE(check_joint_limits(m, m.mechanism->home()).ok());
  // 100 mm towards base joint 1 stands strut 1 up to atan(hypot(126.8, 100) / 550) = 16.4° from vertical.
  const Pose pose = translated(m.mechanism->home(), {100, 0, 0});
  const double from_vertical = std::atan(std::hypot(400.0 - 273.20508075688772, 100.0) / 550.0);
  const PassiveJointAngles a = passive_joint_angles(m, pose);
  EXPECT_NEAR(a.base_rad[0], kPi - from_vertical, kAngleTolerance);
  const Status s = check_joint_limits(m, pose);
  ASSERT_FALSE(s.ok());
  EXPECT_EQ(s.error().message.rfind(
                fmt::format("base joint 1 swings {:.1f} deg, beyond limits.base_joint_max_deg = 160",
                            deg_from_rad(kPi - from_vertical)),
                0),
            0u)
      << s.error().message;
}

TEST(JointLimitsCheck, AgreesWithTheAnglesOnRandomPoses) {
  Machine m = ch5_with("limits: {base_joint_max_deg: 12, platform_joint_max_deg: 15}\n");
  std::mt19937_64 rng(7);
  int violations = 0;
  for (int i = 0; i < 2000; ++i) {
    PoseVector c = vector_from_pose(AngleConvention::krylov, m.mechanism->home());
    for (int k = 0; k < 3; ++k) c[k] += test::uniform(rng, -150, 150);
    for (int k = 3; k < 6; ++k) c[k] += rad_from_deg(test::uniform(rng, -15, 15));
    const Pose pose = pose_from_vector(AngleConvention::krylov, c);
    const PassiveJointAngles a = passive_joint_angles(m, pose);
    bool beyond = false;
    for (int j = 0; j < 6; ++j) {
      beyond = beyond || a.base_rad[j] > *m.joint_limits.base_joint_max_rad ||
               a.platform_rad[j] > *m.joint_limits.platform_joint_max_rad;
    }
    violations += beyond ? 1 : 0;
    EXPECT_EQ(check_joint_limits(m, pose).ok(), !beyond) << i;
  }
  EXPECT_GT(violations, 100);
  EXPECT_LT(violations, 1900);
}

TEST(JointLimitsCheck, OkWithoutLimits) {
  const Machine m = test::machine_from_text(kCh5HexapodText);
  EXPECT_TRUE(check_joint_limits(m, translated(m.mechanism->home(), {300, 0, 0})).ok());
  EXPECT_TRUE(check_conditioning_limit(m, translated(m.mechanism->home(), {300, 0, 0})).ok());
}

TEST(JointLimitsCheck, ShippedCh5HexapodRegionAroundHomeIsInsideItsLimits) {
  // ±50 mm / ±10° around home, as the example's comment promises: its joint and conditioning limits hold.
  const Machine m = test::machine_from_example("examples/machines/hexapod_ch5.yaml");
  ASSERT_TRUE(m.joint_limits.base_joint_max_rad && m.joint_limits.platform_joint_max_rad &&
              m.joint_limits.max_condition_number);
  EXPECT_NEAR(*m.joint_limits.base_joint_max_rad, rad_from_deg(40), 1e-15);
  EXPECT_NEAR(*m.joint_limits.platform_joint_max_rad, rad_from_deg(45), 1e-15);
  EXPECT_EQ(*m.joint_limits.max_condition_number, 4000.0);
  const PoseVector home = vector_from_pose(AngleConvention::krylov, m.mechanism->home());
  int poses = 0;
  for (int index = 0; index < 729; ++index) {
    PoseVector c = home;
    int rest = index;
    for (int axis = 0; axis < 6; ++axis, rest /= 3) {
      c[axis] += (rest % 3 - 1) * (axis < 3 ? 50.0 : rad_from_deg(10));
    }
    const Pose pose = pose_from_vector(AngleConvention::krylov, c);
    const Status joints = check_joint_limits(m, pose);
    const Status conditioning = check_conditioning_limit(m, pose);
    EXPECT_TRUE(joints.ok()) << joints.error().message;
    EXPECT_TRUE(conditioning.ok()) << conditioning.error().message;
    ++poses;
  }
  EXPECT_EQ(poses, 729);
}

// ---- check_conditioning_limit --------------------------------------------------------------------------

TEST(JointLimitsConditioning, Planar3NearItsSingularOrientation) {
  // The shipped planar 3-RPR has similar triangles: φ = 0 is singular at every (x, y) (Smirnov 2019, §3.3).
  // With φ in rad, the condition number is 69 at home (φ = 15°) and grows as 1/φ near 0: 2026 at φ = 0.0001°.
  const std::string text = R"(type: planar3
base_joints: [[0.0, 200.0], [-173.20508075688772, -100.0], [173.20508075688772, -100.0]]
platform_joints: [[0.0, 100.0], [-86.60254037844386, -50.0], [86.60254037844386, -50.0]]
home: [0.0, 0.0, 15.0]
limits: {max_condition_number: 1000}
)";
  const Machine m = test::machine_from_text(text);
  EXPECT_TRUE(check_conditioning_limit(m, m.mechanism->home()).ok());
  const Pose near = pose_from_planar({0, 0, rad_from_deg(1e-4)});
  const auto measures = jacobian_measures(*m.mechanism, near);
  ASSERT_TRUE(measures.ok());
  ASSERT_GT(measures->condition_number, 1000);
  const Status s = check_conditioning_limit(m, near);
  ASSERT_FALSE(s.ok());
  EXPECT_EQ(s.error().code, ErrorCode::limit_exceeded);
  // "the Jacobian's condition number N is beyond limits.max_condition_number = 1000 (test.yaml:5)"
  const std::string& message = s.error().message;
  const std::string prefix = "the Jacobian's condition number ";
  ASSERT_EQ(message.rfind(prefix, 0), 0u) << message;
  EXPECT_NEAR(std::stod(message.substr(prefix.size())), measures->condition_number, 0.051) << message;
  EXPECT_NE(message.find(" is beyond limits.max_condition_number = 1000 (test.yaml:5)"), std::string::npos)
      << message;
  // At the singularity itself: singular (or a condition number beyond any limit).
  const Status at = check_conditioning_limit(m, pose_from_planar({0, 0, 0}));
  ASSERT_FALSE(at.ok());
  EXPECT_TRUE(at.error().code == ErrorCode::singular || at.error().code == ErrorCode::limit_exceeded)
      << at.error().message;
}

TEST(JointLimitsConditioning, MatchesJacobianMeasuresOnTheHexapod) {
  Machine m = test::machine_from_text(kCh5HexapodText);
  const Pose pose = translated(m.mechanism->home(), {40, -30, 20});
  const double condition = jacobian_measures(*m.mechanism, pose)->condition_number;
  m.joint_limits.max_condition_number = condition * (1 + 1e-9);
  EXPECT_TRUE(check_conditioning_limit(m, pose).ok());
  m.joint_limits.max_condition_number = condition * (1 - 1e-9);
  const Status s = check_conditioning_limit(m, pose);
  ASSERT_FALSE(s.ok());
  EXPECT_EQ(s.error().code, ErrorCode::limit_exceeded);
}

}  // namespace
}  // namespace pkm
