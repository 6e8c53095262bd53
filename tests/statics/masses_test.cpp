// The machine file's `masses:` section (docs/machine-file.md).
#include <gtest/gtest.h>

#include <string>

#include "machine/limits_test_support.hpp"
#include "test_support.hpp"

namespace pkm {
namespace {

using test::appended_line;
using test::kCh5HexapodText;

const char* kPlanar3Text = R"(type: planar3
base_joints: [[0.0, 200.0], [-173.20508075688772, -100.0], [173.20508075688772, -100.0]]
platform_joints: [[0.0, 100.0], [-86.60254037844386, -50.0], [86.60254037844386, -50.0]]
home: [0.0, 0.0, 15.0]
)";

TEST(Masses, NoneWithoutTheSection) {
  const Machine m = test::machine_from_text(kCh5HexapodText);
  EXPECT_EQ(m.masses.platform_kg, 0.0);
  EXPECT_EQ(m.masses.strut_kg, 0.0);
  EXPECT_EQ(m.masses.platform_com_mm, Eigen::Vector3d::Zero());
  EXPECT_EQ(m.masses.gravity_mm_s2, Eigen::Vector3d(0, 0, -9810));
  EXPECT_EQ(m.masses.line, 0);
  EXPECT_FALSE(m.masses.has_mass());
}

TEST(Masses, ReadsEveryKeyWithItsLine) {
  const std::string extra = R"(masses:
  platform_kg: 60
  platform_com_mm: [0, 0, -150]
  strut_kg: 25
  gravity_mm_s2: [0, 0, 9810]
)";
  const Machine m = test::machine_from_text(kCh5HexapodText + extra);
  const int first = appended_line(kCh5HexapodText);
  EXPECT_EQ(m.masses.platform_kg, 60.0);
  EXPECT_EQ(m.masses.platform_com_mm, Eigen::Vector3d(0, 0, -150));
  EXPECT_EQ(m.masses.strut_kg, 25.0);
  EXPECT_EQ(m.masses.gravity_mm_s2, Eigen::Vector3d(0, 0, 9810));
  EXPECT_TRUE(m.masses.has_mass());
  EXPECT_EQ(m.masses.line, first);
  EXPECT_EQ(m.masses.platform_kg_line, first + 1);
  EXPECT_EQ(m.masses.platform_com_line, first + 2);
  EXPECT_EQ(m.masses.strut_kg_line, first + 3);
  EXPECT_EQ(m.masses.gravity_line, first + 4);
}

TEST(Masses, MissingKeysKeepTheirDefaults) {
  const Machine m = test::machine_from_text(std::string(kCh5HexapodText) + "masses: {platform_kg: 12.5}\n");
  EXPECT_EQ(m.masses.platform_kg, 12.5);
  EXPECT_EQ(m.masses.strut_kg, 0.0);
  EXPECT_EQ(m.masses.gravity_mm_s2, Eigen::Vector3d(0, 0, -9810));
}

TEST(Masses, NegativeMassNamesFileLineAndKey) {
  const int line = appended_line(kCh5HexapodText) + 2;
  const std::string message =
      test::appended_section_error(kCh5HexapodText, "masses:\n  platform_kg: 10\n  strut_kg: -3\n");
  EXPECT_NE(message.find("test.yaml:" + std::to_string(line) + ":13: masses.strut_kg"), std::string::npos)
      << message;
  EXPECT_NE(message.find("negative"), std::string::npos) << message;
}

TEST(Masses, WrongVectorLengthNamesTheKey) {
  const int line = appended_line(kCh5HexapodText) + 1;
  std::string message = test::appended_section_error(kCh5HexapodText, "masses:\n  platform_com_mm: [1, 2]\n");
  EXPECT_NE(message.find("test.yaml:" + std::to_string(line) + ":20: masses.platform_com_mm"),
            std::string::npos)
      << message;
  EXPECT_NE(message.find("expected 3 numbers, got 2"), std::string::npos) << message;
  message = test::appended_section_error(kCh5HexapodText, "masses:\n  gravity_mm_s2: [0, 0, -9810, 1]\n");
  EXPECT_NE(message.find(": masses.gravity_mm_s2: expected 3 numbers, got 4"), std::string::npos) << message;
}

TEST(Masses, NotANumberUnknownKeyOrNotAMapping) {
  std::string message = test::appended_section_error(kCh5HexapodText, "masses:\n  platform_kg: heavy\n");
  EXPECT_NE(message.find("masses.platform_kg: expected a number, got 'heavy'"), std::string::npos) << message;
  message = test::appended_section_error(kCh5HexapodText, "masses:\n  strut_mass: 3\n");
  EXPECT_NE(message.find("masses.strut_mass: unknown key"), std::string::npos) << message;
  message = test::appended_section_error(kCh5HexapodText, "masses: 60\n");
  EXPECT_NE(message.find("masses: expected a mapping"), std::string::npos) << message;
}

TEST(Masses, PlanarMachinesMayGiveTheCentreOfMassAsXY) {
  // Appended in place: GCC 12 reports a false -Warray-bounds for `std::string(literal) + literal` in some
  // unity batches.
  std::string text = kPlanar3Text;
  text.append("masses: {platform_kg: 5, platform_com_mm: [10, -4]}\n");
  const Machine m = test::machine_from_text(text);
  EXPECT_EQ(m.masses.platform_com_mm, Eigen::Vector3d(10, -4, 0));
  const std::string message =
      test::appended_section_error(kPlanar3Text, "masses: {platform_com_mm: [1, 2, 3, 4]}\n");
  EXPECT_NE(message.find("expected [x, y] or [x, y, z], got 4 numbers"), std::string::npos) << message;
}

}  // namespace
}  // namespace pkm
