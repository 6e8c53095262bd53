// The machine file's `motion:` section (docs/machine-file.md) and the lines of the actuator limits.
#include <fmt/format.h>
#include <gtest/gtest.h>

#include "limits_test_support.hpp"
#include "test_support.hpp"

namespace pkm {
namespace {

using test::appended_line;
using test::kCh5HexapodText;

// The loader's message for the ch5 hexapod with `extra` appended; fails the test if the file loads.
std::string motion_settings_load_error(const std::string& extra) {
  auto m = parse_machine_text(kCh5HexapodText + extra, "test.yaml");
  if (m) {
    ADD_FAILURE() << "expected an error for:\n" << extra;
    return {};
  }
  EXPECT_EQ(m.error().code, ErrorCode::bad_input);
  return m.error().message;
}

const char* kPlanar3Text = R"(type: planar3
base_joints: [[0.0, 200.0], [-173.20508075688772, -100.0], [173.20508075688772, -100.0]]
platform_joints: [[0.0, 100.0], [-86.60254037844386, -50.0], [86.60254037844386, -50.0]]
home: [0.0, 0.0, 15.0]
)";

TEST(MotionSettings, DefaultsWithoutTheSection) {
  const Machine m = test::machine_from_text(kCh5HexapodText);
  const MotionSettings defaults;
  EXPECT_EQ(m.motion.rapid_mm_min, defaults.rapid_mm_min);
  EXPECT_EQ(m.motion.max_feed_mm_min, defaults.max_feed_mm_min);
  EXPECT_EQ(m.motion.path_accel_mm_s2, defaults.path_accel_mm_s2);
  EXPECT_EQ(m.motion.path_jerk_mm_s3, defaults.path_jerk_mm_s3);
  EXPECT_EQ(m.motion.path_tolerance_mm, defaults.path_tolerance_mm);
  EXPECT_EQ(m.motion.angular_feed_deg_min, defaults.angular_feed_deg_min);
  EXPECT_EQ(m.motion.program_origin_mm, Eigen::Vector3d::Zero());
  EXPECT_EQ(m.motion.line, 0);
  // The documented defaults.
  EXPECT_EQ(defaults.rapid_mm_min, 6000.0);
  EXPECT_EQ(defaults.max_feed_mm_min, 6000.0);
  EXPECT_EQ(defaults.path_accel_mm_s2, 1000.0);
  EXPECT_EQ(defaults.path_jerk_mm_s3, 20000.0);
  EXPECT_EQ(defaults.path_tolerance_mm, 0.01);
  EXPECT_EQ(defaults.angular_feed_deg_min, 3600.0);
}

TEST(MotionSettings, ReadsEveryKey) {
  const std::string extra = R"(motion:
  rapid_mm_min: 12000
  max_feed_mm_min: 3000
  path_accel_mm_s2: 500
  path_jerk_mm_s3: 8000
  path_tolerance_mm: 0.005
  angular_feed_deg_min: 1800
  program_origin_mm: [10, -20, 650]
)";
  const Machine m = test::machine_from_text(kCh5HexapodText + extra);
  EXPECT_EQ(m.motion.rapid_mm_min, 12000.0);
  EXPECT_EQ(m.motion.max_feed_mm_min, 3000.0);
  EXPECT_EQ(m.motion.path_accel_mm_s2, 500.0);
  EXPECT_EQ(m.motion.path_jerk_mm_s3, 8000.0);
  EXPECT_EQ(m.motion.path_tolerance_mm, 0.005);
  EXPECT_EQ(m.motion.angular_feed_deg_min, 1800.0);
  EXPECT_EQ(m.motion.program_origin_mm, Eigen::Vector3d(10, -20, 650));
  EXPECT_EQ(m.motion.line, appended_line(kCh5HexapodText));
}

TEST(MotionSettings, MissingKeysKeepTheirDefaults) {
  const Machine m =
      test::machine_from_text(std::string(kCh5HexapodText) + "motion: {path_accel_mm_s2: 250}\n");
  EXPECT_EQ(m.motion.path_accel_mm_s2, 250.0);
  EXPECT_EQ(m.motion.rapid_mm_min, MotionSettings{}.rapid_mm_min);
  EXPECT_EQ(m.motion.path_tolerance_mm, MotionSettings{}.path_tolerance_mm);
  EXPECT_EQ(m.motion.program_origin_mm, Eigen::Vector3d::Zero());
}

TEST(MotionSettings, NonPositiveValuesNameFileLineAndKey) {
  const int line = appended_line(kCh5HexapodText) + 1;
  for (const char* key : {"rapid_mm_min", "max_feed_mm_min", "path_accel_mm_s2", "path_jerk_mm_s3",
                          "path_tolerance_mm", "angular_feed_deg_min"}) {
    for (const char* value : {"0", "-5"}) {
      const std::string message = motion_settings_load_error(fmt::format("motion:\n  {}: {}\n", key, value));
      EXPECT_TRUE(test::names_yaml_place(message, fmt::format("test.yaml:{}", line),
                                         fmt::format("motion.{}: must be positive", key)))
          << message;
    }
  }
}

TEST(MotionSettings, NonNumbersNameFileLineAndKey) {
  const int line = appended_line(kCh5HexapodText) + 1;
  const std::string message = motion_settings_load_error("motion:\n  rapid_mm_min: fast\n");
  EXPECT_NE(message.find(fmt::format("test.yaml:{}:17: motion.rapid_mm_min: expected a number", line)),
            std::string::npos)
      << message;
  const std::string origin = motion_settings_load_error("motion:\n  program_origin_mm: [0, zero, 700]\n");
  EXPECT_NE(origin.find(fmt::format("test.yaml:{}:26: motion.program_origin_mm[1]: expected a number", line)),
            std::string::npos)
      << origin;
}

TEST(MotionSettings, UnknownKeyIsRejected) {
  const int line = appended_line(kCh5HexapodText) + 1;
  const std::string message = motion_settings_load_error("motion:\n  rapid_speed: 6000\n");
  EXPECT_NE(message.find(fmt::format("test.yaml:{}:3: motion.rapid_speed: unknown key", line)),
            std::string::npos)
      << message;
  EXPECT_NE(message.find("rapid_mm_min"), std::string::npos) << "lists the allowed keys: " << message;
}

TEST(MotionSettings, SectionMustBeAMapping) {
  const std::string message = motion_settings_load_error("motion: 6000\n");
  EXPECT_NE(
      message.find(fmt::format("test.yaml:{}:9: motion: expected a mapping", appended_line(kCh5HexapodText))),
      std::string::npos)
      << message;
}

TEST(MotionSettings, ProgramOriginOfASpatialMachineHasThreeNumbers) {
  const std::string message = motion_settings_load_error("motion: {program_origin_mm: [0, 0]}\n");
  EXPECT_NE(message.find("motion.program_origin_mm: expected 3 numbers, got 2"), std::string::npos)
      << message;
}

TEST(MotionSettings, PlanarProgramOriginTakesTwoNumbersOrAZeroZ) {
  const Machine two =
      test::machine_from_text(std::string(kPlanar3Text) + "motion: {program_origin_mm: [5, 6]}\n");
  EXPECT_EQ(two.motion.program_origin_mm, Eigen::Vector3d(5, 6, 0));
  const Machine three =
      test::machine_from_text(std::string(kPlanar3Text) + "motion: {program_origin_mm: [5, 6, 0]}\n");
  EXPECT_EQ(three.motion.program_origin_mm, Eigen::Vector3d(5, 6, 0));

  auto off_plane =
      parse_machine_text(std::string(kPlanar3Text) + "motion: {program_origin_mm: [5, 6, 1]}\n", "p.yaml");
  ASSERT_FALSE(off_plane.ok());
  EXPECT_NE(off_plane.error().message.find(
                "p.yaml:5:29: motion.program_origin_mm: a planar machine moves in z = 0"),
            std::string::npos)
      << off_plane.error().message;
  auto four =
      parse_machine_text(std::string(kPlanar3Text) + "motion: {program_origin_mm: [1, 2, 0, 4]}\n", "p.yaml");
  ASSERT_FALSE(four.ok());
  EXPECT_NE(four.error().message.find("p.yaml:5:29: motion.program_origin_mm: expected [x, y] or [x, y, 0]"),
            std::string::npos)
      << four.error().message;
}

TEST(MotionSettings, ActuatorLimitsKeepTheLineOfEveryKey) {
  const int first = appended_line(kCh5HexapodText) + 1;
  const Machine m = test::machine_from_text(
      std::string(kCh5HexapodText) +
      "limits:\n  actuator_min: 350\n  actuator_max: 900\n  actuator_speed: 100\n  actuator_accel: 2000\n");
  EXPECT_EQ(m.limits.min_line, first);
  EXPECT_EQ(m.limits.max_line, first + 1);
  EXPECT_EQ(m.limits.speed_line, first + 2);
  EXPECT_EQ(m.limits.accel_line, first + 3);
  EXPECT_EQ(*m.limits.speed, 100.0);
  EXPECT_EQ(*m.limits.accel, 2000.0);
  const Machine none = test::machine_from_text(kCh5HexapodText);
  EXPECT_EQ(none.limits.speed_line, 0);
  EXPECT_EQ(none.limits.accel_line, 0);
}

TEST(MotionSettings, ShippedCh5HexapodHasItsMotionSection) {
  const Machine m = test::machine_from_example("examples/machines/hexapod_ch5.yaml");
  EXPECT_EQ(m.motion.rapid_mm_min, 6000.0);
  EXPECT_EQ(m.motion.max_feed_mm_min, 6000.0);
  EXPECT_EQ(m.motion.path_accel_mm_s2, 1000.0);
  EXPECT_GT(m.motion.path_jerk_mm_s3, 0.0);  // tuned by the planner's tests, not pinned here
  EXPECT_EQ(m.motion.path_tolerance_mm, 0.01);
  EXPECT_EQ(m.motion.program_origin_mm, Eigen::Vector3d(0, 0, 700));
  EXPECT_GT(m.motion.line, 0);
  // The existing actuator limits are unchanged.
  EXPECT_EQ(*m.limits.min, 350.0);
  EXPECT_EQ(*m.limits.max, 900.0);
  EXPECT_EQ(*m.limits.speed, 100.0);
  EXPECT_EQ(*m.limits.accel, 2000.0);
}

}  // namespace
}  // namespace pkm
