// The machine file's `stiffness:` section (docs/machine-file.md): both forms of a strut's stiffness, one
// mapping for all struts or one per strut, and every refused input named by file, line, column and key.
#include <gtest/gtest.h>

#include <algorithm>
#include <string>

#include "machine/limits_test_support.hpp"
#include "test_support.hpp"

namespace pkm {
namespace {

using test::appended_line;
using test::kCh5HexapodText;

// "test.yaml:LINE:COLUMN" of the first `token` in `section` appended to the ch5 hexapod's text.
std::string stiffness_error_place(const std::string& section, const std::string& token) {
  const std::size_t at = section.find(token);
  EXPECT_NE(at, std::string::npos) << token;
  const std::size_t line_start = section.rfind('\n', at);
  const int line = appended_line(kCh5HexapodText) +
                   static_cast<int>(std::count(section.begin(), section.begin() + at, '\n'));
  const std::size_t column = at - (line_start == std::string::npos ? 0 : line_start + 1) + 1;
  return "test.yaml:" + std::to_string(line) + ":" + std::to_string(column);
}

void expect_stiffness_refused(const std::string& section, const std::string& token, const std::string& what) {
  const std::string message = test::appended_section_error(kCh5HexapodText, section);
  const std::string expected = stiffness_error_place(section, token) + ": " + what;
  EXPECT_NE(message.find(expected), std::string::npos)
      << "expected: " << expected << "\ngot:      " << message;
}

TEST(StiffnessFile, OneMappingForEveryStrutOrOnePerStrut) {
  const Machine none = test::machine_from_text(kCh5HexapodText);
  EXPECT_FALSE(none.stiffness.given());
  const Machine all =
      test::machine_from_text(kCh5HexapodText + "stiffness:\n  struts: {stiffness_N_mm: 150000}\n");
  ASSERT_TRUE(all.stiffness.given());
  EXPECT_EQ(all.stiffness.line, appended_line(kCh5HexapodText));
  EXPECT_EQ(all.stiffness.strut_count, 6);
  for (int j = 0; j < 6; ++j) EXPECT_DOUBLE_EQ(all.stiffness.struts[j].at_length(600.0), 150000.0);
  std::string list = "stiffness:\n  struts:\n";
  for (int j = 0; j < 6; ++j)
    list += "    - {modulus_N_mm2: 210000, area_mm2: " + std::to_string(100 * (j + 1)) + "}\n";
  const Machine each = test::machine_from_text(kCh5HexapodText + list);
  for (int j = 0; j < 6; ++j)
    EXPECT_DOUBLE_EQ(each.stiffness.struts[j].at_length(700.0), 210000.0 * 100 * (j + 1) / 700.0);
}

TEST(StiffnessFile, BadValuesAreNamedByPlaceAndKey) {
  expect_stiffness_refused("stiffness:\n  struts: {stiffness_N_mm: -5}\n", "-5",
                           "stiffness.struts.stiffness_N_mm: must be positive, got -5");
  expect_stiffness_refused("stiffness:\n  struts: {stiffness_N_mm: 0}\n", "0}",
                           "stiffness.struts.stiffness_N_mm: must be positive, got 0");
  expect_stiffness_refused("stiffness:\n  struts: {modulus_N_mm2: 210000, area_mm2: -1}\n", "-1",
                           "stiffness.struts.area_mm2: must be positive, got -1");
  expect_stiffness_refused("stiffness:\n  struts: {stiffness_N_mm: 5, area_mm2: 1}\n", "{stiffness",
                           "stiffness.struts: give stiffness_N_mm or modulus_N_mm2 with area_mm2, not both");
  expect_stiffness_refused("stiffness:\n  struts: [{stiffness_N_mm: 5}, {stiffness_N_mm: 5}]\n", "[{",
                           "stiffness.struts: expected one mapping for every strut or a list of 6");
  expect_stiffness_refused("stiffness:\n  struts: {stifness_N_mm: 5}\n", "stifness", "stiffness.struts");
  expect_stiffness_refused("stiffness:\n  joints: {k: 5}\n", "joints", "stiffness");
}

}  // namespace
}  // namespace pkm
