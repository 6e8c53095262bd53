// The machine file's `dynamics:` section and `limits.actuator_force_max` (docs/machine-file.md; Smirnov 2019,
// chapter 4): the shipped values read and converted (kg·m² → kg·mm²), both forms of `struts:`, and every
// refused input named by file, line, column and key. The expected place of an error is found in the input
// text itself (the line and column of a token), not taken from the reader.
#include <gtest/gtest.h>

#include <algorithm>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "machine/limits_test_support.hpp"
#include "test_support.hpp"

namespace pkm {
namespace {

using test::appended_line;
using test::kCh5HexapodText;

constexpr double kTestMm2PerM2 = 1e6;

std::string dynamics_example_text(const std::string& relative_path) {
  std::ifstream in(test::source_path(relative_path));
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

// "test.yaml:LINE:COLUMN" of the first `token` in `section` when it is appended to `base`.
std::string dynamics_error_place(const std::string& base, const std::string& section,
                                 const std::string& token) {
  const std::size_t at = section.find(token);
  EXPECT_NE(at, std::string::npos) << token << " not in\n" << section;
  const std::size_t line_start = section.rfind('\n', at);
  const int line =
      appended_line(base) + static_cast<int>(std::count(section.begin(), section.begin() + at, '\n'));
  const std::size_t column = at - (line_start == std::string::npos ? 0 : line_start + 1) + 1;
  return "test.yaml:" + std::to_string(line) + ":" + std::to_string(column);
}

// The loader refuses `base` + `section` with "PLACE: what", PLACE at `token`.
void expect_dynamics_refused(const std::string& base, const std::string& section, const std::string& token,
                             const std::string& what) {
  const std::string message = test::appended_section_error(base, section);
  const std::string expected = dynamics_error_place(base, section, token) + ": " + what;
  EXPECT_NE(message.find(expected), std::string::npos)
      << "expected: " << expected << "\ngot:      " << message;
}

const char* kDynamicsPlatform = "  platform: {mass_kg: 60}\n";

// ---------------------------------------------------------------------------------------------------------
// What is read

TEST(DynamicsFile, NotGivenMeansNothingHasMass) {
  const Machine m = test::machine_from_text(kCh5HexapodText);
  EXPECT_FALSE(m.dynamics.given());
  EXPECT_EQ(m.dynamics.line, 0);
  EXPECT_EQ(m.dynamics.platform.mass_kg, 0.0);
  EXPECT_EQ(m.dynamics.strut_count, 0);
  EXPECT_FALSE(m.limits.force_N.has_value());
}

TEST(DynamicsFile, ShippedHexapodsHaveTheSeedsE1MassesInKgMm2) {
  for (const char* file : {"examples/machines/hexapod_ch5.yaml", "examples/machines/hexapod_ch3.yaml",
                           "examples/machines/hexapod_ch3_delta30.yaml"}) {
    SCOPED_TRACE(file);
    const Machine m = test::machine_from_example(file);
    const DynamicsParameters& d = m.dynamics;
    ASSERT_TRUE(d.given());
    const std::string text = dynamics_example_text(file);
    EXPECT_EQ(d.line, appended_line(text.substr(0, text.find("\ndynamics:") + 1)));
    // Smirnov 2019, §4.4: platform 60 kg, 0.5 kg·m² about each axis; strut parts 15 / 10 kg, 0.4 kg·m²
    // transverse.
    EXPECT_EQ(d.platform.mass_kg, 60.0);
    EXPECT_EQ(d.platform.inertia_kg_mm2, Eigen::Matrix3d(Eigen::Vector3d::Constant(5e5).asDiagonal()));
    EXPECT_EQ(d.payload.mass_kg, 0.0);
    EXPECT_EQ(d.gravity_mm_s2, Eigen::Vector3d(0, 0, -9810));
    EXPECT_EQ(d.drive, DriveModel::ideal);
    ASSERT_EQ(d.strut_count, 6);
    for (int j = 0; j < 6; ++j) {
      EXPECT_EQ(d.struts[j].lower.mass_kg, 15.0);
      EXPECT_EQ(d.struts[j].upper.mass_kg, 10.0);
      EXPECT_EQ(d.struts[j].lower.transverse_inertia_kg_mm2, 4e5);
      EXPECT_EQ(d.struts[j].upper.transverse_inertia_kg_mm2, 4e5);
      EXPECT_EQ(d.struts[j].lower.com_mm, 150.0);
      EXPECT_EQ(d.struts[j].upper.com_mm, 150.0);
    }
  }
}

TEST(DynamicsFile, ShippedCh5HexapodHasElasticStrutsWithQuadraticFriction) {
  const Machine m = test::machine_from_example("examples/machines/hexapod_ch5.yaml");
  // The platform's centre of mass at the centre of its joint circle: the tool point is 150 mm above it.
  EXPECT_EQ(m.dynamics.platform.com_mm, Eigen::Vector3d(0, 0, -150));
  for (int j = 0; j < 6; ++j) {
    EXPECT_EQ(m.dynamics.struts[j].stiffness_N_mm, 200000.0);
    EXPECT_EQ(m.dynamics.struts[j].damping, StrutDamping::quadratic);
    EXPECT_EQ(m.dynamics.struts[j].damping_coefficient, 0.4);
  }
  const Machine ch3 = test::machine_from_example("examples/machines/hexapod_ch3.yaml");
  EXPECT_EQ(ch3.dynamics.platform.com_mm, Eigen::Vector3d(0, 0, -200));
  EXPECT_EQ(ch3.dynamics.struts[0].stiffness_N_mm, 0.0);  // §4.4's example is the rigid model
  EXPECT_EQ(ch3.dynamics.struts[0].damping, StrutDamping::none);
}

TEST(DynamicsFile, ShippedPlanarBipedAndTripod) {
  const Machine biped = test::machine_from_example("examples/machines/planar2.yaml");
  ASSERT_EQ(biped.dynamics.strut_count, 2);
  EXPECT_EQ(biped.dynamics.gravity_mm_s2, Eigen::Vector3d(0, -9810, 0));  // y up, Smirnov 2019, §4.2
  EXPECT_EQ(biped.dynamics.platform.mass_kg, 2.0);                        // m_B, a point mass
  EXPECT_EQ(biped.dynamics.platform.inertia_kg_mm2, Eigen::Matrix3d::Zero());
  for (int j = 0; j < 2; ++j) {
    EXPECT_EQ(biped.dynamics.struts[j].lower.mass_kg, 3.0);
    EXPECT_EQ(biped.dynamics.struts[j].upper.mass_kg, 1.5);
    EXPECT_NEAR(biped.dynamics.struts[j].lower.transverse_inertia_kg_mm2, 0.01 * kTestMm2PerM2, 1e-9);
    EXPECT_EQ(biped.dynamics.struts[j].stiffness_N_mm, 50000.0);
    EXPECT_EQ(biped.dynamics.struts[j].damping, StrutDamping::quadratic);
  }
  const Machine tripod = test::machine_from_example("examples/machines/tripod.yaml");
  ASSERT_EQ(tripod.dynamics.strut_count, 3);
  EXPECT_EQ(tripod.dynamics.platform.mass_kg, 40.0);
  EXPECT_NEAR(tripod.dynamics.platform.inertia_kg_mm2(2, 2), 1.25e6, 1e-6);
  EXPECT_EQ(tripod.dynamics.struts[2].upper.mass_kg, 5.0);
}

TEST(DynamicsFile, OneMappingForEveryStrut) {
  const Machine m = test::machine_from_text(kCh5HexapodText + "dynamics:\n" + kDynamicsPlatform +
                                            "  struts:\n"
                                            "    lower: {mass_kg: 15, com_mm: 120, inertia_kg_m2: 0.4}\n"
                                            "    stiffness_N_mm: 1000\n"
                                            "    damping: {model: viscous, coefficient: 2}\n");
  ASSERT_EQ(m.dynamics.strut_count, 6);
  for (int j = 0; j < 6; ++j) {
    EXPECT_EQ(m.dynamics.struts[j].lower.com_mm, 120.0);
    EXPECT_EQ(m.dynamics.struts[j].upper.mass_kg, 0.0);  // not given: no sliding part
    EXPECT_EQ(m.dynamics.struts[j].stiffness_N_mm, 1000.0);
    EXPECT_EQ(m.dynamics.struts[j].damping, StrutDamping::viscous);
    EXPECT_EQ(m.dynamics.struts[j].damping_coefficient, 2.0);
  }
}

TEST(DynamicsFile, OneMappingPerStrut) {
  std::string section = std::string("dynamics:\n") + kDynamicsPlatform + "  struts:\n";
  for (int j = 0; j < 6; ++j) {
    section +=
        "    - lower: {mass_kg: " + std::to_string(j + 1) + ", com_mm: " + std::to_string(100 + j) + "}\n";
    section +=
        "      upper: {mass_kg: 0.5, com_mm: 80, inertia_kg_m2: " + std::to_string(0.01 * (j + 1)) + "}\n";
    if (j == 4) section += "      damping: {model: coulomb, coefficient: 7}\n      stiffness_N_mm: 5e4\n";
  }
  const Machine m = test::machine_from_text(kCh5HexapodText + section);
  for (int j = 0; j < 6; ++j) {
    EXPECT_EQ(m.dynamics.struts[j].lower.mass_kg, j + 1.0);
    EXPECT_EQ(m.dynamics.struts[j].lower.com_mm, 100.0 + j);
    EXPECT_NEAR(m.dynamics.struts[j].upper.transverse_inertia_kg_mm2, 1e4 * (j + 1), 1e-6);
    EXPECT_EQ(m.dynamics.struts[j].damping, j == 4 ? StrutDamping::coulomb : StrutDamping::none);
    EXPECT_EQ(m.dynamics.struts[j].stiffness_N_mm, j == 4 ? 5e4 : 0.0);
  }
}

TEST(DynamicsFile, SixTensorComponentsAreTheOffDiagonalEntries) {
  const Machine m = test::machine_from_text(
      kCh5HexapodText +
      "dynamics:\n"
      "  gravity_mm_s2: [0, 0, 9810]\n"
      "  platform: {mass_kg: 60, com_mm: [1, 2, -3], inertia_kg_m2: [2, 3, 4, 0.1, -0.2, 0.3]}\n"
      "  payload: {mass_kg: 2.5, com_mm: [0, 0, 50], inertia_kg_m2: [0.01, 0.01, 0.001]}\n");
  Eigen::Matrix3d expected;
  expected << 2, 0.1, 0.3, 0.1, 3, -0.2, 0.3, -0.2, 4;
  EXPECT_TRUE(m.dynamics.platform.inertia_kg_mm2.isApprox(expected * kTestMm2PerM2, 1e-15));
  EXPECT_EQ(m.dynamics.platform.com_mm, Eigen::Vector3d(1, 2, -3));
  EXPECT_EQ(m.dynamics.gravity_mm_s2, Eigen::Vector3d(0, 0, 9810));
  EXPECT_EQ(m.dynamics.payload.mass_kg, 2.5);
  EXPECT_EQ(m.dynamics.payload.com_mm, Eigen::Vector3d(0, 0, 50));
  EXPECT_NEAR(m.dynamics.payload.inertia_kg_mm2(2, 2), 1000.0, 1e-9);
}

TEST(DynamicsFile, BoundaryInertiasOfRealBodiesAreAccepted) {
  // A thin plate (Izz = Ixx + Iyy), a slender rod (no axial moment), a point mass: each on an equality.
  for (const char* inertia : {"[0.1, 0.2, 0.3]", "[0.4, 0.4, 0]", "[0, 0, 0]", "[0.3, 0.3, 0.6, 0, 0, 0]"}) {
    const Machine m = test::machine_from_text(
        kCh5HexapodText + "dynamics:\n  platform: {mass_kg: 1, inertia_kg_m2: " + inertia + "}\n");
    EXPECT_TRUE(m.dynamics.given()) << inertia;
  }
}

TEST(DynamicsFile, DriveModels) {
  const Machine lag = test::machine_from_text(kCh5HexapodText + "dynamics:\n" + kDynamicsPlatform +
                                              "  drive: {model: lag, tau_s: 0.005}\n");
  EXPECT_EQ(lag.dynamics.drive, DriveModel::first_order_lag);
  EXPECT_EQ(lag.dynamics.drive_lag_s, 0.005);
  const Machine characteristic =
      test::machine_from_text(kCh5HexapodText + "dynamics:\n" + kDynamicsPlatform +
                              "  drive: {model: static, speed_gain_N_s_mm: 0.1}\n");
  EXPECT_EQ(characteristic.dynamics.drive, DriveModel::static_characteristic);
  EXPECT_EQ(characteristic.dynamics.drive_speed_gain_N_s_mm, 0.1);
}

TEST(DynamicsFile, PlanarMachinesMayGiveCentresOfMassAsXY) {
  const std::string planar = dynamics_example_text("examples/machines/planar2.yaml");
  const std::string base = planar.substr(0, planar.find("\ndynamics:") + 1) + "home: [120.0, 250.0]\n";
  const Machine m = test::machine_from_text(base + "dynamics:\n  platform: {mass_kg: 2, com_mm: [5, -4]}\n");
  EXPECT_EQ(m.dynamics.platform.com_mm, Eigen::Vector3d(5, -4, 0));
  EXPECT_EQ(m.dynamics.strut_count, 2);
}

TEST(DynamicsFile, GlideMachinesHaveCarriagesAndConstantLengthStruts) {
  const std::string triglide = dynamics_example_text("examples/machines/triglide.yaml");
  const Machine m = test::machine_from_text(triglide +
                                            "dynamics:\n  platform: {mass_kg: 8}\n"
                                            "  struts: {lower: {mass_kg: 2, com_mm: 225}, carriage_kg: 6}\n");
  ASSERT_EQ(m.dynamics.strut_count, 3);
  EXPECT_EQ(m.dynamics.struts[2].carriage_kg, 6.0);
  const std::string upper =
      "dynamics:\n  platform: {mass_kg: 8}\n"
      "  struts: {lower: {mass_kg: 2, com_mm: 225}, upper: {mass_kg: 1, com_mm: 9}}\n";
  expect_dynamics_refused(triglide, upper, "upper",
                          "dynamics.struts.upper: the struts of a glide have a constant length");
  const std::string carriage = std::string("dynamics:\n") + kDynamicsPlatform +
                               "  struts: {lower: {mass_kg: 2, com_mm: 225}, carriage_kg: 6}\n";
  expect_dynamics_refused(kCh5HexapodText, carriage, "6}",
                          "dynamics.struts.carriage_kg: a hexapod has no carriages");
}

TEST(ActuatorForceLimit, IsReadInNewtonsWithItsLine) {
  const std::string limits = "limits:\n  actuator_speed: 100\n  actuator_force_max: 5000\n";
  const Machine m = test::machine_from_text(kCh5HexapodText + limits);
  EXPECT_EQ(m.limits.force_N, 5000.0);
  EXPECT_EQ(m.limits.force_line, appended_line(kCh5HexapodText) + 2);
  // The rotopod's limits turn to radians, its force stays in N.
  const std::string rotopod = dynamics_example_text("examples/machines/rotopod.yaml");
  const std::string with_force = rotopod.substr(0, rotopod.find("limits: {") + 9) +
                                 "actuator_force_max: 800, " + rotopod.substr(rotopod.find("limits: {") + 9);
  EXPECT_EQ(test::machine_from_text(with_force).limits.force_N, 800.0);
}

TEST(ActuatorForceLimit, MustBePositive) {
  for (const char* value : {"0", "-5"}) {
    expect_dynamics_refused(kCh5HexapodText, std::string("limits:\n  actuator_force_max: ") + value + "\n",
                            value, "limits.actuator_force_max: must be positive");
  }
  expect_dynamics_refused(kCh5HexapodText, "limits:\n  actuator_force_max: .inf\n", ".inf",
                          "limits.actuator_force_max: expected a finite number");
}

// ---------------------------------------------------------------------------------------------------------
// What is refused

struct DynamicsBadCase {
  std::string section;  ///< appended to the ch5 hexapod
  std::string token;    ///< where the error must point
  std::string what;     ///< "key: reason" (a prefix of it)
};

TEST(DynamicsFile, BadInputsNameFileLineColumnAndKey) {
  const std::string head = std::string("dynamics:\n") + kDynamicsPlatform;
  const std::string lower = "  struts:\n    lower: {mass_kg: 15, com_mm: 150}\n";
  std::vector<DynamicsBadCase> cases = {
      // masses
      {"dynamics:\n  platform: {mass_kg: -60}\n", "-60",
       "dynamics.platform.mass_kg: a mass cannot be negative, got -60 kg"},
      {"dynamics:\n  platform: {com_mm: [0, 0, 0]}\n", "{com_mm",
       "dynamics.platform.mass_kg: missing (expected a mass in kg)"},
      {"dynamics:\n  struts: {lower: {mass_kg: 15, com_mm: 150}}\n", "struts",
       "dynamics.platform: missing (expected a mapping with mass_kg)"},
      {"dynamics:\n", "dynamics", "dynamics: expected a mapping with platform:, got nothing"},
      {"dynamics:\n  platform:\n", "platform", "dynamics.platform: expected a mapping of keys, got nothing"},
      {head + "  payload: {mass_kg: -1}\n", "-1", "dynamics.payload.mass_kg: a mass cannot be negative"},
      {head + "  struts:\n    lower: {mass_kg: -15, com_mm: 150}\n", "-15",
       "dynamics.struts.lower.mass_kg: a mass cannot be negative, got -15 kg"},
      {head + "  struts:\n    lower: {com_mm: 150}\n", "{com_mm", "dynamics.struts.lower.mass_kg: missing"},
      {head + "  struts:\n    lower: {mass_kg: 15}\n", "{mass_kg: 15}",
       "dynamics.struts.lower.com_mm: missing"},
      {head + "  struts:\n    stiffness_N_mm: 100\n", "stiffness", "dynamics.struts.lower: missing"},
      {head + lower + "    upper: {mass_kg: 10, com_mm: 150, inertia_kg_m2: -0.4}\n", "-0.4",
       "dynamics.struts.upper.inertia_kg_m2: a moment of inertia cannot be negative"},
      {head + lower + "    carriage_kg: -1\n", "-1",
       "dynamics.struts.carriage_kg: a mass cannot be negative"},
      // inertia tensors
      {"dynamics:\n  platform: {mass_kg: 60, inertia_kg_m2: [1, 1, -1]}\n", "[1, 1, -1]",
       "dynamics.platform.inertia_kg_m2: not positive semi-definite: principal moment -1 kg·m² is negative"},
      {"dynamics:\n  platform: {mass_kg: 60, inertia_kg_m2: [1, 1, 5]}\n", "[1, 1, 5]",
       "dynamics.platform.inertia_kg_m2: not the inertia of a real body: principal moment 5 kg·m² exceeds "
       "the "
       "sum of the other two, 2 kg·m²"},
      {"dynamics:\n  platform: {mass_kg: 60, inertia_kg_m2: [5, 1, 1]}\n", "[5, 1, 1]",
       "dynamics.platform.inertia_kg_m2: not the inertia of a real body"},
      // Diagonal entries all positive, but eigenvalues -1, 1, 3.
      {"dynamics:\n  platform: {mass_kg: 60, inertia_kg_m2: [1, 1, 1, 2, 0, 0]}\n", "[1, 1, 1, 2",
       "dynamics.platform.inertia_kg_m2: not positive semi-definite"},
      {"dynamics:\n  platform: {mass_kg: 60, inertia_kg_m2: [1, 1]}\n", "[1, 1]",
       "dynamics.platform.inertia_kg_m2: expected 3 principal moments [Ixx, Iyy, Izz] or 6 tensor "
       "components"},
      {head + "  payload: {mass_kg: 1, inertia_kg_m2: [0.1, 0.1, 0.3]}\n", "[0.1, 0.1, 0.3]",
       "dynamics.payload.inertia_kg_m2: not the inertia of a real body"},
      // stiffness and friction
      {head + lower + "    stiffness_N_mm: 0\n", "0\n",
       "dynamics.struts.stiffness_N_mm: must be positive, got 0 N/mm"},
      {head + lower + "    stiffness_N_mm: -200000\n", "-200000",
       "dynamics.struts.stiffness_N_mm: must be positive, got -200000 N/mm"},
      {head + lower + "    stiffness_N_mm: 1e5\n    damping: {model: cubic, coefficient: 1}\n", "cubic",
       "dynamics.struts.damping.model: unknown damping model 'cubic' (known: none | viscous | quadratic | "
       "coulomb)"},
      {head + lower + "    stiffness_N_mm: 1e5\n    damping: {model: quadratic, coefficient: -0.5}\n", "-0.5",
       "dynamics.struts.damping.coefficient: a friction coefficient cannot be negative"},
      {head + lower + "    stiffness_N_mm: 1e5\n    damping: {model: quadratic}\n", "{model",
       "dynamics.struts.damping.coefficient: missing"},
      {head + lower + "    damping: {model: quadratic, coefficient: 0.5}\n", "damping",
       "dynamics.struts.damping: the friction of an elastic element needs stiffness_N_mm"},
      {head + lower + "    stiffness_N_mm: 1e5\n    damping: {model: none, coefficient: 0.5}\n",
       "coefficient", "dynamics.struts.damping.coefficient: model none has no coefficient"},
      // unknown keys
      {"dynamics:\n  platfrom: {mass_kg: 60}\n", "platfrom", "dynamics.platfrom: unknown key"},
      {"dynamics:\n  platform: {mass_kg: 60, inertia: [1, 1, 1]}\n", "inertia",
       "dynamics.platform.inertia: unknown key"},
      {head + "  struts:\n    lower: {mass: 15, com_mm: 150}\n",
       "mass:", "dynamics.struts.lower.mass: unknown key"},
      {head + lower + "    stifness_N_mm: 5\n", "stifness", "dynamics.struts.stifness_N_mm: unknown key"},
      // struts as a list
      {head + "  struts:\n"
              "    - {lower: {mass_kg: 1, com_mm: 1}}\n    - {lower: {mass_kg: 1, com_mm: 1}}\n"
              "    - {lower: {mass_kg: 1, com_mm: 1}}\n    - {lower: {mass_kg: 1, com_mm: 1}}\n"
              "    - {lower: {mass_kg: 1, com_mm: 1}}\n",
       "- {",
       "dynamics.struts: expected one mapping for every strut or a list of 6 mappings (one per actuator), "
       "got a list of 5"},
      {head + "  struts: 5\n", "5\n", "dynamics.struts: expected one mapping for every strut or a list of 6"},
      {head + "  struts:\n    - {lower: {mass_kg: 1, com_mm: 1}}\n    - {lower: {mass_kg: 1, com_mm: 1}}\n"
              "    - {lower: {mass_kg: 1, com_mm: 1}}\n    - {lower: {mass_kg: 1, com_mm: 1}}\n"
              "    - {lower: {mass_kg: 1, com_mm: 1}}\n    - {lower: {mass_kg: -1, com_mm: 1}}\n",
       "-1", "dynamics.struts[5].lower.mass_kg: a mass cannot be negative"},
      // numbers
      {"dynamics:\n  platform: {mass_kg: heavy}\n", "heavy",
       "dynamics.platform.mass_kg: expected a number, got 'heavy'"},
      {"dynamics:\n  platform: {mass_kg: .nan}\n", ".nan",
       "dynamics.platform.mass_kg: expected a finite number"},
      {"dynamics:\n  platform: {mass_kg: 1, inertia_kg_m2: [1, .inf, 1]}\n", ".inf",
       "dynamics.platform.inertia_kg_m2[1]: expected a finite number"},
      {head + "  struts:\n    lower: {mass_kg: 15, com_mm: -.inf}\n", "-.inf",
       "dynamics.struts.lower.com_mm: expected a finite number"},
      {head + "  gravity_mm_s2: [0, 0]\n", "[0, 0]", "dynamics.gravity_mm_s2: expected 3 numbers, got 2"},
      {"dynamics:\n  platform: {mass_kg: 1, com_mm: [0, 0]}\n", "[0, 0]",
       "dynamics.platform.com_mm: expected 3 numbers, got 2"},
      // drives
      {head + "  drive: {model: lag, tau_s: 0.0}\n", "0.0}",
       "dynamics.drive.tau_s: must be positive, got 0 s"},
      {head + "  drive: {model: lag, tau_s: -0.005}\n", "-0.005", "dynamics.drive.tau_s: must be positive"},
      {head + "  drive: {model: lag}\n", "{model",
       "dynamics.drive.tau_s: missing (expected the time constant"},
      {head + "  drive: {model: ideal, tau_s: 0.005}\n", "tau_s",
       "dynamics.drive.tau_s: model ideal has no tau_s"},
      {head + "  drive: {model: servo}\n", "servo",
       "dynamics.drive.model: unknown drive model 'servo' (known: ideal | lag | static)"},
      {head + "  drive: {model: static, speed_gain_N_s_mm: -1}\n", "-1",
       "dynamics.drive.speed_gain_N_s_mm: cannot be negative"},
  };
  for (const DynamicsBadCase& c : cases) {
    SCOPED_TRACE(c.section);
    expect_dynamics_refused(kCh5HexapodText, c.section, c.token, c.what);
  }
}

}  // namespace
}  // namespace pkm
