// The machine file's `drives:` section (docs/machine-file.md): resolution, step rate and servo period, with
// the resolution's unit in its key (mm for struts and carriages, deg for a rotopod's carriage angles).
#include <gtest/gtest.h>

#include <fstream>
#include <sstream>

#include "limits_test_support.hpp"
#include "test_support.hpp"

namespace pkm {
namespace {

using test::appended_line;
using test::kCh5HexapodText;

std::string example_text(const std::string& relative_path) {
  std::ifstream in(test::source_path(relative_path));
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

TEST(DriveSettings, NothingWithoutTheSection) {
  const Machine m = test::machine_from_text(kCh5HexapodText);
  EXPECT_FALSE(m.drives.step.has_value());
  EXPECT_FALSE(m.drives.max_step_rate_hz.has_value());
  EXPECT_FALSE(m.drives.period_ms.has_value());
  EXPECT_EQ(m.drives.line, 0);
}

TEST(DriveSettings, ReadsEveryKeyWithItsLine) {
  const Machine m = test::machine_from_text(kCh5HexapodText +
                                            "drives:\n  step_mm: 0.0005\n  max_step_rate_hz: 50000\n"
                                            "  period_ms: 0.5\n");
  EXPECT_EQ(m.drives.step, 0.0005);
  EXPECT_EQ(m.drives.max_step_rate_hz, 50000.0);
  EXPECT_EQ(m.drives.period_ms, 0.5);
  EXPECT_EQ(m.drives.line, appended_line(kCh5HexapodText));
}

TEST(DriveSettings, TheShippedCh5HexapodHasTheSeedsStepDrives) {
  const Machine m = test::machine_from_example("examples/machines/hexapod_ch5.yaml");
  EXPECT_EQ(m.drives.step, 0.001);  // Δ of Smirnov 2019, §5.2.5
  EXPECT_EQ(m.drives.period_ms, 1.0);
  ASSERT_TRUE(m.drives.max_step_rate_hz.has_value());
  // At least what the struts' speed limit needs.
  EXPECT_GE(*m.drives.max_step_rate_hz, *m.limits.speed / *m.drives.step);
}

TEST(DriveSettings, BadValuesNameTheKeyAndLine) {
  const int line = appended_line(kCh5HexapodText);
  struct Case {
    std::string extra;
    std::string expected;
  };
  for (const Case& c :
       std::vector<Case>{{"drives: {step_mm: 0}\n", "drives.step_mm: must be positive"},
                         {"drives: {max_step_rate_hz: -5}\n", "drives.max_step_rate_hz: must be positive"},
                         {"drives: {period_ms: 50}\n", "drives.period_ms: 50 ms is outside 0.1…20 ms"},
                         {"drives: {step_mm: fast}\n", "drives.step_mm"},
                         {"drives: {step: 0.001}\n", "step"},
                         // A hexapod's drives move struts: a resolution in degrees is a unit mix-up.
                         {"drives: {step_deg: 0.001}\n", "step_deg"}}) {
    const std::string message = test::appended_section_error(kCh5HexapodText, c.extra);
    EXPECT_NE(message.find(c.expected), std::string::npos) << message;
    EXPECT_NE(message.find("test.yaml:" + std::to_string(line)), std::string::npos) << message;
  }
}

TEST(DriveSettings, AngularActuatorsTakeTheirResolutionInDegrees) {
  const std::string rotopod = example_text("examples/machines/rotopod.yaml");
  const Machine m = test::machine_from_text(rotopod + "drives: {step_deg: 0.01}\n");
  EXPECT_EQ(m.drives.step, 0.01);
  const std::string message = test::appended_section_error(rotopod, "drives: {step_mm: 0.01}\n");
  EXPECT_NE(message.find("step_mm"), std::string::npos) << message;
}

}  // namespace
}  // namespace pkm
