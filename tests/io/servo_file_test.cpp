// The machine file's `servo:` section (docs/machine-file.md, "Servo"): a full section read back in the units
// kept inside (s, rad, kg·mm²), the defaults, one mapping for every drive or one per drive, the unit keys of
// linear and angular actuators, the shipped machines' sections, and every refused input named by file, line,
// column and key.
#include <fmt/format.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

#include "machine/limits_test_support.hpp"
#include "test_support.hpp"

namespace pkm {
namespace {

using test::appended_line;
using test::kCh5HexapodText;

// The shipped rotopod's geometry (examples/machines/rotopod.yaml): its actuators are the carriages' angles.
const std::string kServoRotopodText = R"(type: rotopod
angles: abc
circle: {center: [0, 0], radius: 300}
joint_heights: 0
strut_lengths: [400, 400, 400, 400, 400, 400]
platform_joints:
  - [-26.04722665, 147.721162952, 0]
  - [26.04722665, 147.721162952, 0]
  - [-114.906666468, -96.418141453, 0]
  - [-140.953893118, -51.303021499, 0]
  - [140.953893118, -51.303021499, 0]
  - [114.906666468, -96.418141453, 0]
branch: [1, -1, 1, -1, 1, -1]
tool: [0, 0, 100]
home: [0, 0, 320, 0, 0, 0]
)";

// A drive's required keys for linear actuators.
const std::string kServoDrive = "current_time_constant_ms: 1.0, base_speed_mm_s: 500, base_force_N: 3000";

// "test.yaml:LINE:COLUMN" of the first `token` in `section` appended to `base`.
std::string servo_error_place(const std::string& base, const std::string& section, const std::string& token) {
  const std::size_t at = section.find(token);
  EXPECT_NE(at, std::string::npos) << token;
  if (at == std::string::npos) return "(token not found)";
  const std::size_t line_start = section.rfind('\n', at);
  const int line =
      appended_line(base) + static_cast<int>(std::count(section.begin(), section.begin() + at, '\n'));
  const std::size_t column = at - (line_start == std::string::npos ? 0 : line_start + 1) + 1;
  return "test.yaml:" + std::to_string(line) + ":" + std::to_string(column);
}

void expect_servo_refused(const std::string& base, const std::string& section, const std::string& token,
                          const std::string& what) {
  const std::string message = test::appended_section_error(base, section);
  const std::string expected = servo_error_place(base, section, token) + ": " + what;
  EXPECT_NE(message.find(expected), std::string::npos)
      << "expected: " << expected << "\ngot:      " << message;
}

void expect_servo_refused(const std::string& section, const std::string& token, const std::string& what) {
  expect_servo_refused(kCh5HexapodText, section, token, what);
}

TEST(ServoFile, NothingWithoutTheSection) {
  const Machine m = test::machine_from_text(kCh5HexapodText);
  EXPECT_FALSE(m.servo.given());
  EXPECT_EQ(m.servo.line, 0);
  EXPECT_EQ(m.servo.drive_count, 0);
}

TEST(ServoFile, AFullSectionWithOneMappingPerDriveReadsBackInTheUnitsKeptInside) {
  std::string section =
      "servo:\n"
      "  tuning: explicit\n"
      "  loop_period_ms: 0.25\n"
      "  velocity_feedforward: 0.75\n"
      "  drives:\n";
  for (int j = 0; j < 6; ++j) {
    section += fmt::format(
        "    - {{current_time_constant_ms: {}, current_gain: 1.25, base_speed_mm_s: {}, base_force_N: {}, "
        "motor_inertia_kg_cm2: {}, screw_lead_mm: {}, error_max_mm: 2, command_max: 3, position_gain_per_s: "
        "{}, speed_gain: 0.5, speed_integral_ms: {}}}\n",
        0.5 * (j + 1), 100 * (j + 1), 1000 * (j + 1), 1.5 * j, 5 * (j + 1), 100 + j, 4 * j);
  }
  const int base = appended_line(kCh5HexapodText);
  const Machine m = test::machine_from_text(kCh5HexapodText + section);
  const ServoParameters& s = m.servo;
  ASSERT_TRUE(s.given());
  EXPECT_EQ(s.line, base);
  EXPECT_EQ(s.tuning, ServoTuning::explicit_gains);
  EXPECT_EQ(s.tuning_line, base + 1);
  EXPECT_DOUBLE_EQ(s.loop_period_s, 0.25e-3);
  EXPECT_EQ(s.loop_period_line, base + 2);
  EXPECT_DOUBLE_EQ(s.velocity_feedforward, 0.75);
  EXPECT_EQ(s.drive_count, 6);
  for (int j = 0; j < 6; ++j) {
    SCOPED_TRACE(j);
    const DriveServo& d = s.drives[j];
    EXPECT_DOUBLE_EQ(d.current_time_constant_s, 0.5e-3 * (j + 1));
    EXPECT_DOUBLE_EQ(d.current_gain, 1.25);
    EXPECT_DOUBLE_EQ(d.base_speed, 100.0 * (j + 1));
    EXPECT_DOUBLE_EQ(d.base_force, 1000.0 * (j + 1));
    EXPECT_DOUBLE_EQ(d.motor_inertia_kg_mm2, 150.0 * j);                // kg·cm² × 100
    EXPECT_DOUBLE_EQ(d.motor_rad_per_unit, 2 * kPi / (5.0 * (j + 1)));  // 2π / lead
    EXPECT_DOUBLE_EQ(d.error_max, 2.0);
    EXPECT_DOUBLE_EQ(d.command_max, 3.0);
    EXPECT_DOUBLE_EQ(d.position_gain_per_s, 100.0 + j);
    EXPECT_DOUBLE_EQ(d.speed_gain, 0.5);
    EXPECT_DOUBLE_EQ(d.speed_integral_s, 4e-3 * j);
    EXPECT_EQ(d.line, base + 5 + j);
    EXPECT_EQ(d.time_constant_line, base + 5 + j);
    EXPECT_EQ(d.position_gain_line, base + 5 + j);
    EXPECT_EQ(d.speed_gain_line, base + 5 + j);
  }
}

TEST(ServoFile, DefaultsAndOneMappingForEveryDrive) {
  const std::string section =
      "servo:\n"
      "  drives:\n"
      "    base_speed_mm_s: 400\n"
      "    current_time_constant_ms: 2\n"
      "    base_force_N: 1000\n";
  const int base = appended_line(kCh5HexapodText);
  const Machine m = test::machine_from_text(kCh5HexapodText + section);
  const ServoParameters& s = m.servo;
  ASSERT_TRUE(s.given());
  EXPECT_EQ(s.line, base);
  EXPECT_EQ(s.tuning, ServoTuning::technical_optimum);
  EXPECT_EQ(s.tuning_line, 0);
  EXPECT_EQ(s.loop_period_s, 0.0);  // the servo period drives.period_ms
  EXPECT_EQ(s.loop_period_line, 0);
  EXPECT_EQ(s.velocity_feedforward, 0.0);
  EXPECT_EQ(s.drive_count, 6);
  for (int j = 0; j < 6; ++j) {
    SCOPED_TRACE(j);
    const DriveServo& d = s.drives[j];
    EXPECT_DOUBLE_EQ(d.current_time_constant_s, 2e-3);
    EXPECT_EQ(d.current_gain, 1.0);
    EXPECT_EQ(d.base_speed, 400.0);
    EXPECT_EQ(d.base_force, 1000.0);
    EXPECT_EQ(d.motor_inertia_kg_mm2, 0.0);
    EXPECT_EQ(d.motor_rad_per_unit, 0.0);
    EXPECT_EQ(d.error_max, std::numeric_limits<double>::infinity());
    EXPECT_EQ(d.command_max, std::numeric_limits<double>::infinity());
    EXPECT_EQ(d.position_gain_per_s, 0.0);
    EXPECT_EQ(d.speed_gain, 0.0);
    EXPECT_EQ(d.speed_integral_s, 0.0);
    EXPECT_EQ(d.line, base + 2);  // the mapping starts at its first key
    EXPECT_EQ(d.time_constant_line, base + 3);
    EXPECT_EQ(d.position_gain_line, 0);
    EXPECT_EQ(d.speed_gain_line, 0);
  }
  // A drive count of 3 for a tripod: the section follows the mechanism.
  const Machine tripod = test::machine_from_example("examples/machines/tripod.yaml");
  EXPECT_EQ(tripod.servo.drive_count, 3);
  // The symmetric optimum is named, and speed_integral_ms 0 is allowed under explicit tuning.
  const Machine symmetric = test::machine_from_text(
      kCh5HexapodText + "servo: {tuning: symmetric_optimum, drives: {" + kServoDrive + "}}\n");
  EXPECT_EQ(symmetric.servo.tuning, ServoTuning::symmetric_optimum);
  const Machine zero =
      test::machine_from_text(kCh5HexapodText + "servo: {tuning: explicit, drives: {" + kServoDrive +
                              ", position_gain_per_s: 250, speed_gain: 0.5, speed_integral_ms: 0}}\n");
  EXPECT_EQ(zero.servo.drives[5].speed_integral_s, 0.0);
  EXPECT_EQ(zero.servo.drives[5].position_gain_per_s, 250.0);
}

TEST(ServoFile, AngularActuatorsGiveDegreesTorqueAndAGearRatio) {
  const std::string section =
      "servo:\n"
      "  drives: {current_time_constant_ms: 0.8, base_speed_deg_s: 180, base_torque_Nmm: 20000, "
      "motor_inertia_kg_cm2: 0.5, gear_ratio: 50, error_max_deg: 2}\n";
  const Machine m = test::machine_from_text(kServoRotopodText + section);
  ASSERT_TRUE(m.mechanism->actuators_are_angles());
  EXPECT_EQ(m.servo.drive_count, 6);
  for (int j = 0; j < 6; ++j) {
    const DriveServo& d = m.servo.drives[j];
    EXPECT_DOUBLE_EQ(d.current_time_constant_s, 0.8e-3);
    EXPECT_DOUBLE_EQ(d.base_speed, kPi);  // rad/s
    EXPECT_DOUBLE_EQ(d.base_force, 20000.0);
    EXPECT_DOUBLE_EQ(d.motor_inertia_kg_mm2, 50.0);
    EXPECT_DOUBLE_EQ(d.motor_rad_per_unit, 50.0);
    EXPECT_DOUBLE_EQ(d.error_max, rad_from_deg(2.0));
  }
}

// The drives' imperfections: friction (Coulomb, static with its Stribeck speed, viscous), backlash and the
// encoder's count, in the actuators' units (degrees for a rotopod's carriages, radians inside), and the
// sampling delay; each refused with its place and key where it cannot hold.
TEST(ServoFile, ImperfectionsReadBackInTheUnitsKeptInside) {
  const Machine hexapod = test::machine_from_text(
      kCh5HexapodText + "servo:\n  sample_delay_periods: 2\n  drives: {" + kServoDrive +
      ", friction_coulomb_N: 40, friction_static_N: 60, stribeck_speed_mm_s: 2, friction_viscous_N_s_per_mm: "
      "0.5, backlash_mm: 0.01, encoder_resolution_mm: 0.0005}\n");
  EXPECT_EQ(hexapod.servo.sample_delay_periods, 2);
  for (int j = 0; j < 6; ++j) {
    const DriveServo& d = hexapod.servo.drives[j];
    EXPECT_DOUBLE_EQ(d.friction_coulomb, 40.0);
    EXPECT_DOUBLE_EQ(d.friction_static, 60.0);
    EXPECT_DOUBLE_EQ(d.stribeck_speed, 2.0);
    EXPECT_DOUBLE_EQ(d.friction_viscous, 0.5);
    EXPECT_DOUBLE_EQ(d.backlash, 0.01);
    EXPECT_DOUBLE_EQ(d.encoder_resolution, 0.0005);
  }
  // The static friction defaults to the Coulomb friction (no Stribeck speed needed then); nothing given: 0.
  const Machine coulomb_only = test::machine_from_text(kCh5HexapodText + "servo:\n  drives: {" + kServoDrive +
                                                       ", friction_coulomb_N: 25}\n");
  EXPECT_DOUBLE_EQ(coulomb_only.servo.drives[0].friction_static, 25.0);
  EXPECT_EQ(coulomb_only.servo.drives[0].backlash, 0.0);
  EXPECT_EQ(coulomb_only.servo.sample_delay_periods, 0);
  const Machine rotopod = test::machine_from_text(
      kServoRotopodText +
      "servo:\n  drives: {current_time_constant_ms: 0.8, base_speed_deg_s: 180, base_torque_Nmm: 20000, "
      "friction_coulomb_Nmm: 300, friction_static_Nmm: 400, stribeck_speed_deg_s: 1, "
      "friction_viscous_Nmm_s_per_deg: 2, backlash_deg: 0.05, encoder_resolution_deg: 0.001}\n");
  const DriveServo& r = rotopod.servo.drives[3];
  EXPECT_DOUBLE_EQ(r.friction_coulomb, 300.0);
  EXPECT_DOUBLE_EQ(r.friction_static, 400.0);
  EXPECT_DOUBLE_EQ(r.stribeck_speed, rad_from_deg(1.0));
  EXPECT_DOUBLE_EQ(r.friction_viscous, 2.0 / rad_from_deg(1.0));  // N·mm per rad/s
  EXPECT_DOUBLE_EQ(r.backlash, rad_from_deg(0.05));
  EXPECT_DOUBLE_EQ(r.encoder_resolution, rad_from_deg(0.001));
}

TEST(ServoFile, ImperfectionsThatCannotHoldAreNamedByPlaceAndKey) {
  const std::string d = "servo:\n  drives: {" + kServoDrive;
  expect_servo_refused(d + ", backlash_mm: -0.01}\n", "-0.01",
                       "servo.drives.backlash_mm: must be ≥ 0, got -0.01");
  expect_servo_refused(d + ", friction_coulomb_N: 50, friction_static_N: 30}\n", "30}",
                       "servo.drives.friction_static_N: must be at least friction_coulomb_N (the Coulomb "
                       "friction, 50), got 30");
  expect_servo_refused(d + ", friction_coulomb_N: 50, friction_static_N: 80}\n", "{current",
                       "servo.drives.stribeck_speed_mm_s: missing");
  expect_servo_refused(d + ", backlash_deg: 0.1}\n", "backlash_deg",
                       "servo.drives.backlash_deg: the hexapod's actuators are lengths: give backlash_mm");
  expect_servo_refused(d + ", encoder_resolution_deg: 0.1}\n", "encoder_resolution_deg",
                       "servo.drives.encoder_resolution_deg: the hexapod's actuators are lengths: give "
                       "encoder_resolution_mm");
  expect_servo_refused("servo:\n  sample_delay_periods: 1.5\n  drives: {" + kServoDrive + "}\n", "1.5",
                       "servo.sample_delay_periods: must be a whole number of loop periods, 0 … 8, got 1.5");
  expect_servo_refused("servo:\n  sample_delay_periods: 9\n  drives: {" + kServoDrive + "}\n", "9",
                       "servo.sample_delay_periods: must be a whole number of loop periods, 0 … 8, got 9");
}

TEST(ServoFile, TheStaticCharacteristicIsAPiecewiseLinearTableFromZero) {
  const Machine m = test::machine_from_text(kCh5HexapodText + "servo:\n  drives: {" + kServoDrive +
                                            ", characteristic: [[0, 0], [0.05, 0], [1, 0.95], [3, 2]]}\n");
  const DriveServo& d = m.servo.drives[2];
  ASSERT_EQ(d.characteristic_points, 4);
  EXPECT_EQ(d.characteristic[1][0], 0.05);
  EXPECT_EQ(d.characteristic[3][1], 2.0);
  const std::string c = "servo:\n  drives: {" + kServoDrive + ", characteristic: ";
  expect_servo_refused(c + "[[0.1, 0], [1, 1]]}\n", "[0.1",
                       "servo.drives.characteristic[0]: the characteristic starts at [0, 0]");
  expect_servo_refused(c + "[[0, 0], [1, 1], [1, 2]]}\n", "1, 2]",
                       "servo.drives.characteristic[2]: the commands must rise from point to point");
  expect_servo_refused(c + "[[0, 0], [1, 1], [2, 0.5]]}\n", "0.5]",
                       "servo.drives.characteristic[2]: the force must not fall as the command rises");
  expect_servo_refused(c + "[[0, 0]]}\n", "[[0, 0]]",
                       "servo.drives.characteristic: expected a list of 2 … 16 points");
  expect_servo_refused(c + "[[0, 0], [1]]}\n", "[1]", "servo.drives.characteristic[1]: expected a point");
  expect_servo_refused(c + "[[0, 0], [1, -1]]}\n", "-1",
                       "servo.drives.characteristic[1]: must be finite and ≥ 0");
}

TEST(ServoFile, TheShippedMachinesHaveServoSections) {
  const Machine hexapod = test::machine_from_example("examples/machines/hexapod_ch5.yaml");
  ASSERT_TRUE(hexapod.servo.given());
  EXPECT_EQ(hexapod.servo.tuning, ServoTuning::technical_optimum);
  EXPECT_DOUBLE_EQ(hexapod.servo.loop_period_s, 0.25e-3);
  EXPECT_EQ(hexapod.servo.drive_count, 6);
  const DriveServo& strut = hexapod.servo.drives[3];
  EXPECT_DOUBLE_EQ(strut.current_time_constant_s, 1e-3);
  EXPECT_DOUBLE_EQ(strut.base_speed, 500.0);
  EXPECT_DOUBLE_EQ(strut.base_force, 3000.0);
  EXPECT_DOUBLE_EQ(strut.motor_inertia_kg_mm2, 150.0);
  EXPECT_DOUBLE_EQ(strut.motor_rad_per_unit, 2 * kPi / 10.0);
  EXPECT_DOUBLE_EQ(strut.error_max, 2.0);
  EXPECT_DOUBLE_EQ(strut.command_max, 3.0);
  // The drives' loops run within the servo period, and the base speed is above the actuators' speed limit.
  ASSERT_TRUE(hexapod.drives.period_ms.has_value());
  EXPECT_LE(hexapod.servo.loop_period_s, *hexapod.drives.period_ms * 1e-3);
  EXPECT_GT(strut.base_speed, *hexapod.limits.speed);

  for (const char* path : {"examples/machines/tripod.yaml", "examples/machines/rotopod.yaml"}) {
    SCOPED_TRACE(path);
    const Machine m = test::machine_from_example(path);
    ASSERT_TRUE(m.servo.given());
    EXPECT_EQ(m.servo.drive_count, m.mechanism->actuator_count());
    ASSERT_TRUE(m.limits.speed.has_value());
    for (int j = 0; j < m.servo.drive_count; ++j) {
      const DriveServo& d = m.servo.drives[j];
      EXPECT_GT(d.current_time_constant_s, 0.0);
      EXPECT_GT(d.base_speed, *m.limits.speed);  // both in mm/s, or both in rad/s
      EXPECT_GT(d.base_force, 0.0);
      if (d.motor_inertia_kg_mm2 > 0.0) {
        EXPECT_GT(d.motor_rad_per_unit, 0.0);
      }
    }
  }
}

TEST(ServoFile, MissingRequiredKeysAreNamedByPlaceAndKey) {
  expect_servo_refused("servo:\n  tuning: symmetric_optimum\n", "tuning",
                       "servo.drives: missing (expected one mapping for every drive or a list of 6 mappings");
  expect_servo_refused("servo:\n  drives: {base_speed_mm_s: 500, base_force_N: 3000}\n", "{base",
                       "servo.drives.current_time_constant_ms: missing");
  expect_servo_refused("servo:\n  drives: {current_time_constant_ms: 1, base_force_N: 3000}\n", "{current",
                       "servo.drives.base_speed_mm_s: missing");
  expect_servo_refused("servo:\n  drives: {current_time_constant_ms: 1, base_speed_mm_s: 500}\n", "{current",
                       "servo.drives.base_force_N: missing");
  // The third of six drives.
  std::string list = "servo:\n  drives:\n";
  for (int j = 0; j < 6; ++j) {
    list += j == 2 ? "    - {current_time_constant_ms: 1, base_speed_mm_s: 250}\n"
                   : "    - {" + kServoDrive + "}\n";
  }
  expect_servo_refused(list, "{current_time_constant_ms: 1,", "servo.drives[2].base_force_N: missing");
  // A motor's inertia needs its transmission to the actuator.
  expect_servo_refused("servo:\n  drives: {" + kServoDrive + ", motor_inertia_kg_cm2: 1.5}\n", "{current",
                       "servo.drives.screw_lead_mm: missing (expected the screw's lead, mm");
  expect_servo_refused(kServoRotopodText,
                       "servo:\n  drives: {current_time_constant_ms: 1, base_speed_deg_s: 90, "
                       "base_torque_Nmm: 9000, motor_inertia_kg_cm2: 1.5}\n",
                       "{current", "servo.drives.gear_ratio: missing (expected the gear ratio");
}

TEST(ServoFile, BadValuesAreNamedByPlaceAndKey) {
  expect_servo_refused(
      "servo:\n  drives: {current_time_constant_ms: 0, base_speed_mm_s: 500, base_force_N: 3000}\n", "0,",
      "servo.drives.current_time_constant_ms: must be positive, got 0");
  expect_servo_refused(
      "servo:\n  drives: {current_time_constant_ms: -2, base_speed_mm_s: 500, base_force_N: 3000}\n", "-2",
      "servo.drives.current_time_constant_ms: must be positive, got -2");
  expect_servo_refused(
      "servo:\n  drives: {" + kServoDrive + ", motor_inertia_kg_cm2: -1, screw_lead_mm: 5}\n", "-1",
      "servo.drives.motor_inertia_kg_cm2: must be ≥ 0, got -1");
  expect_servo_refused("servo:\n  drives: {" + kServoDrive + ", command_max: 0}\n", "0}",
                       "servo.drives.command_max: must be positive, got 0");
  expect_servo_refused(
      "servo:\n  drives: {current_time_constant_ms: 1, base_speed_mm_s: .nan, base_force_N: 3000}\n", ".nan",
      "servo.drives.base_speed_mm_s: expected a finite number");
  expect_servo_refused(
      "servo:\n  drives: {current_time_constant_ms: 1, base_speed_mm_s: 500, base_force_N: .inf}\n", ".inf",
      "servo.drives.base_force_N: expected a finite number");
  expect_servo_refused(
      "servo:\n  drives: {current_time_constant_ms: , base_speed_mm_s: 500, base_force_N: 3000}\n", "current",
      "servo.drives.current_time_constant_ms: expected a number, got nothing");
  // The one given in a list of six, with its index; the error's fields say the same.
  std::string list = "servo:\n  drives:\n";
  for (int j = 0; j < 6; ++j) {
    list += j == 2 ? "    - {current_time_constant_ms: 0.0, base_speed_mm_s: 500, base_force_N: 3000}\n"
                   : "    - {" + kServoDrive + "}\n";
  }
  expect_servo_refused(list, "0.0", "servo.drives[2].current_time_constant_ms: must be positive, got 0");
  auto error = parse_machine_text(kCh5HexapodText + list, "test.yaml");
  ASSERT_FALSE(error.ok());
  EXPECT_EQ(error.error().location.key, "servo.drives[2].current_time_constant_ms");
  EXPECT_EQ(error.error().location.line, appended_line(kCh5HexapodText) + 4);
  const std::size_t value_at = list.find("0.0");
  EXPECT_EQ(error.error().location.column, static_cast<int>(value_at - list.rfind('\n', value_at)));
  // Feedforward within 0…1, the loop period within 0…20 ms, a known tuning.
  const std::string drives = "  drives: {" + kServoDrive + "}\n";
  expect_servo_refused("servo:\n  velocity_feedforward: 1.5\n" + drives, "1.5",
                       "servo.velocity_feedforward: must be within 0…1, got 1.5");
  expect_servo_refused("servo:\n  velocity_feedforward: -0.1\n" + drives, "-0.1",
                       "servo.velocity_feedforward: must be within 0…1, got -0.1");
  expect_servo_refused("servo:\n  loop_period_ms: 25\n" + drives, "25",
                       "servo.loop_period_ms: must be at most 20 ms, got 25");
  expect_servo_refused("servo:\n  loop_period_ms: 0\n" + drives, "0\n",
                       "servo.loop_period_ms: must be positive, got 0");
  expect_servo_refused("servo:\n  tuning: fast\n" + drives, "fast",
                       "servo.tuning: expected technical_optimum, symmetric_optimum or explicit, got 'fast'");
  expect_servo_refused("servo: 5\n", "5", "servo: expected a mapping");
}

TEST(ServoFile, GainsBelongToExplicitTuningOnly) {
  expect_servo_refused(
      "servo:\n  drives: {" + kServoDrive + ", position_gain_per_s: 250}\n", "250",
      "servo.drives.position_gain_per_s: only with tuning: explicit (tuning: technical_optimum");
  expect_servo_refused(
      "servo:\n  tuning: symmetric_optimum\n  drives: {" + kServoDrive + ", speed_gain: 0.5}\n", "0.5",
      "servo.drives.speed_gain: only with tuning: explicit (tuning: symmetric_optimum");
  expect_servo_refused("servo:\n  drives: {" + kServoDrive + ", speed_integral_ms: 4}\n", "4}",
                       "servo.drives.speed_integral_ms: only with tuning: explicit");
  expect_servo_refused("servo:\n  tuning: explicit\n  drives: {" + kServoDrive + ", speed_gain: 0.5}\n",
                       "{current",
                       "servo.drives.position_gain_per_s: missing (expected the position loop's gain");
  expect_servo_refused(
      "servo:\n  tuning: explicit\n  drives: {" + kServoDrive + ", position_gain_per_s: 250}\n", "{current",
      "servo.drives.speed_gain: missing (expected the speed loop's gain");
  expect_servo_refused("servo:\n  tuning: explicit\n  drives: {" + kServoDrive +
                           ", position_gain_per_s: 0, speed_gain: 0.5}\n",
                       "0, speed", "servo.drives.position_gain_per_s: must be positive, got 0");
  expect_servo_refused("servo:\n  tuning: explicit\n  drives: {" + kServoDrive +
                           ", position_gain_per_s: 250, speed_gain: 0.5, speed_integral_ms: -1}\n",
                       "-1", "servo.drives.speed_integral_ms: must be ≥ 0, got -1");
}

TEST(ServoFile, ListsOfTheWrongLengthAndUnknownKeysAreRefused) {
  expect_servo_refused("servo:\n  drives: [{" + kServoDrive + "}, {" + kServoDrive + "}]\n", "[{",
                       "servo.drives: expected one mapping for every drive or a list of 6 mappings (one per "
                       "actuator), got a list of 2");
  expect_servo_refused("servo:\n  drives: 3\n", "3",
                       "servo.drives: expected one mapping for every drive or a list of 6 mappings");
  expect_servo_refused("servo:\n  drives:\n", "drives", "servo.drives: expected one mapping for every drive");
  expect_servo_refused(
      "servo:\n  tunning: explicit\n  drives: {" + kServoDrive + "}\n", "tunning",
      "servo.tunning: unknown key (allowed here: tuning, loop_period_ms, velocity_feedforward, "
      "sample_delay_periods, drives)");
  expect_servo_refused("servo:\n  drives: {" + kServoDrive + ", speed_gian: 0.5}\n", "speed_gian",
                       "servo.drives.speed_gian: unknown key");
  std::string list = "servo:\n  drives:\n";
  for (int j = 0; j < 6; ++j) list += "    - {" + kServoDrive + (j == 4 ? ", current_gane: 1" : "") + "}\n";
  expect_servo_refused(list, "current_gane", "servo.drives[4].current_gane: unknown key");
  expect_servo_refused("servo:\n  drives: [1, 2, 3, 4, 5, 6]\n", "1,", "servo.drives[0]: expected a mapping");
}

TEST(ServoFile, TheWrongUnitKeyForTheActuatorsSaysWhichToGive) {
  expect_servo_refused(
      "servo:\n  drives: {current_time_constant_ms: 1, base_speed_deg_s: 90, base_force_N: 3000}\n",
      "base_speed_deg_s",
      "servo.drives.base_speed_deg_s: the hexapod's actuators are lengths: give base_speed_mm_s");
  expect_servo_refused("servo:\n  drives: {" + kServoDrive + ", gear_ratio: 50}\n", "gear_ratio",
                       "servo.drives.gear_ratio: the hexapod's actuators are lengths: give screw_lead_mm");
  expect_servo_refused("servo:\n  drives: {" + kServoDrive + ", error_max_deg: 1}\n", "error_max_deg",
                       "servo.drives.error_max_deg: the hexapod's actuators are lengths: give error_max_mm");
  const std::string angular = "current_time_constant_ms: 1, base_speed_deg_s: 90, base_torque_Nmm: 9000";
  expect_servo_refused(kServoRotopodText, "servo:\n  drives: {" + angular + ", screw_lead_mm: 10}\n",
                       "screw_lead_mm",
                       "servo.drives.screw_lead_mm: the rotopod's actuators are angles: give gear_ratio");
  expect_servo_refused(
      kServoRotopodText, "servo:\n  drives: {" + kServoDrive + "}\n", "base_speed_mm_s",
      "servo.drives.base_speed_mm_s: the rotopod's actuators are angles: give base_speed_deg_s");
  expect_servo_refused(
      kServoRotopodText,
      "servo:\n  drives: {current_time_constant_ms: 1, base_speed_deg_s: 90, base_force_N: 1}\n",
      "base_force_N", "servo.drives.base_force_N: the rotopod's actuators are angles: give base_torque_Nmm");
}

TEST(ServoFile, TuningNamesAreTheFilesWords) {
  EXPECT_STREQ(to_string(ServoTuning::technical_optimum), "technical_optimum");
  EXPECT_STREQ(to_string(ServoTuning::symmetric_optimum), "symmetric_optimum");
  EXPECT_STREQ(to_string(ServoTuning::explicit_gains), "explicit");
}

}  // namespace
}  // namespace pkm
