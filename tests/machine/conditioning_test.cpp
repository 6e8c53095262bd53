// Error amplification δρ (Smirnov 2019, §5.2.2, eqs. 144–146) on the ch5 hexapod: recomputed values, within
// the published δρ < 10.
#include "machine/conditioning.hpp"

#include <gtest/gtest.h>

#include <fstream>

#include "core/units.hpp"
#include "source_paths.hpp"
#include "test_support.hpp"

namespace pkm {
namespace {

Pose level_pose(double x, double y, double z) {
  Pose p;
  p.position_mm = {x, y, z};
  return p;
}

// The ch5 hexapod with the pose at the pole C (no tool) and home at z = 500 mm: the file's lines replaced.
std::string ch5_without_tool() {
  std::ifstream in(test::source_path("examples/machines/hexapod_ch5.yaml"));
  std::string yaml, line;
  while (std::getline(in, line)) {
    if (line.rfind("tool:", 0) == 0) line = "tool: [0, 0, 0]";
    if (line.rfind("home:", 0) == 0) line = "home: [0, 0, 500, 0, 0, 0]";
    yaml += line + "\n";
  }
  return yaml;
}

TEST(ErrorAmplification, Ch5HexapodPoleAtZ500) {
  // Recomputed: outputs of C (no tool) at (0,0,500): δρ = 5.05 with S = (3.72, 3.22, 1.12).
  const Machine m = test::machine_from_text(ch5_without_tool());
  const auto measures = jacobian_measures(*m.mechanism, level_pose(0, 0, 500));
  ASSERT_TRUE(measures.ok());
  EXPECT_NEAR(measures->error_amplification, 5.05, 0.005);
  EXPECT_NEAR(measures->sensitivity_sums.x(), 3.72, 0.005);
  EXPECT_NEAR(measures->sensitivity_sums.y(), 3.22, 0.005);
  EXPECT_NEAR(measures->sensitivity_sums.z(), 1.12, 0.005);
}

TEST(ErrorAmplification, Ch5HexapodPoleRangesOverTheSquare) {
  // Recomputed: over |x|, |y| ≤ 200 mm at z = 500, δρ ranges from 5.05 to 5.92 (and stays below δρ_MAX = 10).
  const Machine m = test::machine_from_text(ch5_without_tool());
  double lo = 1e9, hi = 0;
  for (int i = -20; i <= 20; ++i) {
    for (int k = -20; k <= 20; ++k) {
      const auto measures = jacobian_measures(*m.mechanism, level_pose(10.0 * i, 10.0 * k, 500));
      ASSERT_TRUE(measures.ok());
      lo = std::min(lo, measures->error_amplification);
      hi = std::max(hi, measures->error_amplification);
    }
  }
  EXPECT_NEAR(lo, 5.05, 0.005);
  EXPECT_NEAR(hi, 5.92, 0.01);
}

TEST(ErrorAmplification, Ch5HexapodToolPointAtZ700) {
  // Recomputed: outputs of P (150 mm tool) at z = 700: δρ = 4.76 at the centre.
  const Machine m = test::machine_from_example("examples/machines/hexapod_ch5.yaml");
  const auto measures = jacobian_measures(*m.mechanism, level_pose(0, 0, 700));
  ASSERT_TRUE(measures.ok());
  EXPECT_NEAR(measures->error_amplification, 4.76, 0.005);
}

TEST(ErrorAmplification, SingularPoseIsReported) {
  const Machine m = test::machine_from_example("examples/machines/hexapod_ch5.yaml");
  const auto measures = jacobian_measures(*m.mechanism, level_pose(0, 0, 150));  // joints in the base plane
  ASSERT_FALSE(measures.ok());
  EXPECT_EQ(measures.error().code, ErrorCode::singular);
}

TEST(WorkspaceSample, CountsOutOfRangeAndReportsActuatorSpan) {
  const Machine m = test::machine_from_example("examples/machines/hexapod_ch5.yaml");
  WorkspaceBox box;
  box.centre = m.mechanism->home();
  box.translation_half_range_mm = 50;
  box.samples_per_axis = 3;
  const WorkspaceSummary s = sample_workspace(m, box);
  EXPECT_EQ(s.poses, 729);
  EXPECT_EQ(s.out_of_range, 0);
  EXPECT_FALSE(s.determinant_changes_sign);
  for (int j = 0; j < 6; ++j) EXPECT_LT(s.actuator_min[j], s.actuator_max[j]);
  // A box reaching above the 900 mm actuator limit must be counted.
  box.translation_half_range_mm = 400;
  const WorkspaceSummary far = sample_workspace(m, box);
  EXPECT_GT(far.out_of_range, 0);
}

}  // namespace
}  // namespace pkm
