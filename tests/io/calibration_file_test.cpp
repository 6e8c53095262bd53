// The machine file's `calibration:` section (docs/machine-file.md, "Calibration"): calibrated_machine_text
// writes a section that loads back as the calibrated mechanism, a second calibration replaces the first, the
// section's groups are in the frames and units the documentation gives, and every refused input is named by
// file, line, column and key.
#include "io/calibration_file.hpp"

#include <fmt/format.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <random>
#include <string>
#include <vector>

#include "io/input_file.hpp"
#include "machine/actuator_offsets.hpp"
#include "machine/limits_test_support.hpp"
#include "test_support.hpp"

namespace pkm {
namespace {

using test::appended_line;
using test::kCh5HexapodText;

std::vector<std::string> calfile_example_files() {
  std::vector<std::string> files;
  for (const auto& entry : std::filesystem::directory_iterator(test::source_path("examples/machines"))) {
    if (entry.path().extension() == ".yaml") files.push_back(entry.path().string());
  }
  std::sort(files.begin(), files.end());
  return files;
}

// Poses near home the mechanism reaches (controlled coordinates moved by up to ±5 mm, ±1°).
std::vector<Pose> calfile_poses(const Mechanism& mech, unsigned seed) {
  std::mt19937_64 rng(seed);
  std::vector<Pose> poses{mech.home()};
  const AxisMask mask = mech.controlled_axes();
  for (int attempt = 0; attempt < 50 && poses.size() < 6; ++attempt) {
    PoseVector c = vector_from_pose(mech.convention(), mech.home());
    for (int axis = 0; axis < 6; ++axis) {
      if (mask.controlled[axis])
        c[axis] += axis < 3 ? test::uniform(rng, -5, 5) : rad_from_deg(test::uniform(rng, -1, 1));
    }
    auto pose = mech.complete_pose(pose_from_vector(mech.convention(), c));
    if (pose && mech.inverse(*pose)) poses.push_back(*pose);
  }
  return poses;
}

double calfile_ik_difference(const Mechanism& a, const Mechanism& b, const std::vector<Pose>& poses) {
  double worst = 0.0;
  for (const Pose& pose : poses) {
    auto qa = a.inverse(pose);
    auto qb = b.inverse(pose);
    if (!qa || !qb) return 1e300;
    worst = std::max(worst, (*qa - *qb).cwiseAbs().maxCoeff());
  }
  return worst;
}

// `m` with every value of every group (the drive offsets included) moved by a random calibration-size amount.
std::unique_ptr<Mechanism> calfile_calibrated(const Mechanism& m, unsigned seed) {
  auto wrapped = with_actuator_offset_parameters(m);
  EXPECT_TRUE(wrapped.ok());
  auto groups = (*wrapped)->geometry_parameters();
  std::mt19937_64 rng(seed);
  for (auto& g : groups) {
    const double size = g.unit == "rad" ? 1e-3 : 0.2;
    for (double& v : g.values) v += test::uniform(rng, -size, size);
  }
  auto calibrated = (*wrapped)->with_geometry(groups);
  EXPECT_TRUE(calibrated.ok()) << calibrated.error().message;
  return std::move(calibrated.value());
}

std::string calfile_text(const std::string& path) {
  auto text = read_text_input(path, "machine file");
  EXPECT_TRUE(text.ok());
  return *text;
}

TEST(CalibrationFile, WrittenSectionLoadsAsTheCalibratedMechanismForEveryShippedMachine) {
  for (const auto& file : calfile_example_files()) {
    const std::string original = calfile_text(file);
    auto drawing = parse_machine_text(original, file);
    ASSERT_TRUE(drawing.ok()) << drawing.error().message;
    const auto calibrated = calfile_calibrated(*drawing->mechanism, 7);
    const std::string text = calibrated_machine_text(original, calibrated->geometry_parameters(),
                                                     "trial: 40 poses, laser tracker");
    auto loaded = parse_machine_text(text, file);
    ASSERT_TRUE(loaded.ok()) << file << ": " << loaded.error().message << "\n" << text;
    const auto poses = calfile_poses(*calibrated, 3);
    ASSERT_GE(poses.size(), 4u) << file;
    EXPECT_LT(calfile_ik_difference(*loaded->mechanism, *calibrated, poses), 1e-12) << file;
    // ... and differs from the drawing's (the section is read, not ignored).
    EXPECT_GT(calfile_ik_difference(*loaded->mechanism, *drawing->mechanism, poses), 1e-5) << file;
    // The groups come back with every bit.
    const auto want = calibrated->geometry_parameters();
    const auto got = loaded->mechanism->geometry_parameters();
    ASSERT_EQ(got.size(), want.size()) << file;
    for (std::size_t g = 0; g < got.size(); ++g) {
      for (std::size_t i = 0; i < got[g].values.size(); ++i) {
        if (want[g].unit == "rad") {
          EXPECT_NEAR(got[g].values[i], want[g].values[i], 1e-17) << file << " " << want[g].key;
        } else {
          EXPECT_EQ(got[g].values[i], want[g].values[i]) << file << " " << want[g].key;
        }
      }
    }
  }
}

TEST(CalibrationFile, SecondCalibrationReplacesTheFirst) {
  const std::string path = test::source_path("examples/machines/hexapod_ch5.yaml");
  const std::string original = calfile_text(path);
  auto drawing = parse_machine_text(original, path);
  ASSERT_TRUE(drawing.ok());
  const auto first = calfile_calibrated(*drawing->mechanism, 1);
  const auto second = calfile_calibrated(*drawing->mechanism, 2);
  const std::string once = calibrated_machine_text(original, first->geometry_parameters(), "note-one-qx");
  const std::string twice = calibrated_machine_text(once, second->geometry_parameters(), "note-two-qx");
  // The earlier block is gone whole: the same text as calibrating the drawing once.
  EXPECT_EQ(twice, calibrated_machine_text(original, second->geometry_parameters(), "note-two-qx"));
  EXPECT_EQ(twice.find("note-one-qx"), std::string::npos);
  auto loaded = parse_machine_text(twice, path);
  ASSERT_TRUE(loaded.ok()) << loaded.error().message;
  EXPECT_LT(calfile_ik_difference(*loaded->mechanism, *second, calfile_poses(*second, 4)), 1e-12);
}

TEST(CalibrationFile, EarlierBlockInTheMiddleIsRemovedAndKeysAfterItKept) {
  const std::string head = "type: hexapod\nangles: krylov\n";
  const std::string block =
      "calibration:\n  note: hand-written\n\n  actuator_offsets: [1, 1, 1, 1, 1, 1]\n# a comment on the "
      "base\n";
  const std::string rest =
      std::string(test::kCh5HexapodGeometry).substr(std::string("angles: krylov\n").size());
  const std::string text = head + block + rest;
  ASSERT_TRUE(parse_machine_text(text, "test.yaml").ok());
  auto drawing = parse_machine_text(kCh5HexapodText, "test.yaml");
  ASSERT_TRUE(drawing.ok());
  const std::string out = calibrated_machine_text(text, drawing->mechanism->geometry_parameters(), "");
  EXPECT_EQ(out.find("hand-written"), std::string::npos);
  EXPECT_NE(out.find("# a comment on the base\nbase_joints:"), std::string::npos) << out;
  EXPECT_EQ(out.find("calibration:"), out.rfind("calibration:"));
  auto loaded = parse_machine_text(out, "test.yaml");
  ASSERT_TRUE(loaded.ok()) << loaded.error().message;
  EXPECT_LT(
      calfile_ik_difference(*loaded->mechanism, *drawing->mechanism, calfile_poses(*drawing->mechanism, 5)),
      1e-12);
}

TEST(CalibrationFile, NoteWithQuotesAndLineBreaksAndCrLfLineEnds) {
  std::string crlf;
  for (char c : kCh5HexapodText) {
    if (c == '\n') crlf += '\r';
    crlf += c;
  }
  auto drawing = parse_machine_text(kCh5HexapodText, "test.yaml");
  ASSERT_TRUE(drawing.ok());
  const std::string note = "operator \"A\": 2 runs\\3 poses\n\tsecond line";
  const std::string out = calibrated_machine_text(crlf, drawing->mechanism->geometry_parameters(), note);
  // Every line end of the appended block is CR LF, as the file's.
  EXPECT_EQ(std::count(out.begin(), out.end(), '\n'), std::count(out.begin(), out.end(), '\r'));
  auto root = parse_yaml_document(out, "test.yaml");
  ASSERT_TRUE(root.ok()) << root.error().message;
  EXPECT_EQ((*root)["calibration"]["note"].as<std::string>(), note);
  EXPECT_TRUE(parse_machine_text(out, "test.yaml").ok());
}

TEST(CalibrationFile, GroupsNotGivenKeepTheDrawingsValues) {
  const Machine drawing = test::machine_from_text(kCh5HexapodText);
  // platform_joints_from_tool is in the tool frame: the drawing's platform joints less the tool [0, 0, 150].
  const Machine same = test::machine_from_text(kCh5HexapodText +
                                               "calibration:\n"
                                               "  platform_joints_from_tool:\n"
                                               "    - [173.20508075688772, 100, -150]\n"
                                               "    - [173.20508075688772, 100, -150]\n"
                                               "    - [-173.20508075688772, 100, -150]\n"
                                               "    - [-173.20508075688772, 100, -150]\n"
                                               "    - [0, -200, -150]\n"
                                               "    - [0, -200, -150]\n");
  const auto poses = calfile_poses(*drawing.mechanism, 9);
  EXPECT_LT(calfile_ik_difference(*same.mechanism, *drawing.mechanism, poses), 1e-12);

  // Only the offsets: readings are the drawing's lengths less them.
  const Machine offset = test::machine_from_text(
      kCh5HexapodText + "calibration:\n  actuator_offsets: [0.5, 0, 0, 0, 0, -0.25]\n");
  for (const Pose& pose : poses) {
    const auto q = *drawing.mechanism->inverse(pose);
    const auto r = *offset.mechanism->inverse(pose);
    EXPECT_NEAR(r[0], q[0] - 0.5, 1e-12);
    EXPECT_NEAR(r[3], q[3], 1e-12);
    EXPECT_NEAR(r[5], q[5] + 0.25, 1e-12);
  }
  // Rows of one number may be given as one-element lists too.
  const Machine rows = test::machine_from_text(
      kCh5HexapodText + "calibration:\n  actuator_offsets: [[0.5], [0], [0], [0], [0], [-0.25]]\n");
  EXPECT_LT(calfile_ik_difference(*rows.mechanism, *offset.mechanism, poses), 1e-15);
}

TEST(CalibrationFile, RotopodOffsetsAreDegreesInTheFile) {
  const std::string path = test::source_path("examples/machines/rotopod.yaml");
  const std::string text = calfile_text(path);
  auto drawing = parse_machine_text(text, path);
  ASSERT_TRUE(drawing.ok());
  auto offset = parse_machine_text(text + "calibration:\n  actuator_offsets: [1, 0, 0, 0, 0, 0]\n", path);
  ASSERT_TRUE(offset.ok()) << offset.error().message;
  const Pose& home = drawing->mechanism->home();
  EXPECT_NEAR((*offset->mechanism->inverse(home))[0],
              (*drawing->mechanism->inverse(home))[0] - rad_from_deg(1.0), 1e-15);
}

TEST(CalibrationFile, InvalidCalibratedGeometryIsRefusedAtTheSection) {
  const std::string path = test::source_path("examples/machines/triglide.yaml");
  const std::string text = calfile_text(path);
  const int line = appended_line(text);
  auto bad = parse_machine_text(text + "calibration:\n  strut_lengths: [450, -450, 450]\n", "test.yaml");
  ASSERT_FALSE(bad.ok());
  EXPECT_NE(
      bad.error().message.find(fmt::format("test.yaml:{}:1: calibration: the calibrated values do not make a "
                                           "valid glide: strut length L2 must be positive",
                                           line)),
      std::string::npos)
      << bad.error().message;
  // Values that build but put the home out of reach fail the home check that follows.
  auto far = parse_machine_text(text + "calibration:\n  strut_lengths: [45, 450, 450]\n", "test.yaml");
  ASSERT_FALSE(far.ok());
  EXPECT_NE(far.error().message.find("home"), std::string::npos) << far.error().message;
}

// "test.yaml:LINE:COLUMN: KEY: TEXT" for `section` appended to the ch5 hexapod, with `token` at LINE:COLUMN.
void expect_calibration_refused(const std::string& section, const std::string& token, const std::string& key,
                                const std::string& text) {
  auto m = parse_machine_text(kCh5HexapodText + section, "test.yaml");
  ASSERT_FALSE(m.ok()) << section;
  const std::size_t at = section.find(token);
  ASSERT_NE(at, std::string::npos) << token;
  const std::size_t line_start = section.rfind('\n', at);
  const int line = appended_line(kCh5HexapodText) +
                   static_cast<int>(std::count(section.begin(), section.begin() + at, '\n'));
  const int column = static_cast<int>(at - (line_start == std::string::npos ? 0 : line_start + 1)) + 1;
  const std::string expected = fmt::format("test.yaml:{}:{}: {}: {}", line, column, key, text);
  EXPECT_NE(m.error().message.find(expected), std::string::npos)
      << "expected: " << expected << "\ngot:      " << m.error().message;
  EXPECT_EQ(m.error().location.line, line);
  EXPECT_EQ(m.error().location.column, column);
  EXPECT_EQ(m.error().location.key, key);
}

TEST(CalibrationFile, BadSectionsNameLineColumnAndKey) {
  expect_calibration_refused(
      "calibration:\n  base_joint: [[0, 0, 0]]\n", "base_joint", "calibration.base_joint",
      "unknown key for a hexapod (allowed here: note, base_joints, platform_joints_from_tool, "
      "actuator_offsets)");
  expect_calibration_refused("calibration: [1, 2]\n", "[1, 2]", "calibration",
                             "expected a mapping with some of: note");
  expect_calibration_refused("calibration:\n", "calibration", "calibration", "expected a mapping");
  expect_calibration_refused("calibration:\n  base_joints: [[1, 2, 3], [1, 2, 3]]\n", "[[",
                             "calibration.base_joints",
                             "expected a list of 6 rows of 3 numbers, A1..A6: x, y, z (mm), got 2 rows");
  expect_calibration_refused("calibration:\n  base_joints: 3\n", "3", "calibration.base_joints",
                             "expected a list of 6 rows");
  expect_calibration_refused("calibration:\n  base_joints:\n", "base_joints", "calibration.base_joints",
                             "expected a list of 6 rows of 3 numbers, A1..A6: x, y, z (mm), got nothing");
  const std::string rows = "calibration:\n  base_joints:\n    - [400, 0, 0]\n    - [200, 346.4]\n";
  expect_calibration_refused(rows + "    - [0, 0, 0]\n    - [0, 0, 0]\n    - [0, 0, 0]\n    - [0, 0, 0]\n",
                             "[200, 346.4]", "calibration.base_joints[1]",
                             "expected a row of 3 numbers (x, y, z), got 2");
  expect_calibration_refused(
      "calibration:\n  base_joints: [[1, 2, 3], [1, 2, 3], [1, 2, 3], [1, 2, 3], [1, two, 3], [1, 2, 3]]\n",
      "two", "calibration.base_joints[4][1]", "expected a number, got 'two'");
  expect_calibration_refused(
      "calibration:\n  base_joints: [[1, 2, 3], [1, 2, 3], [1, 2, .inf], [1, 2, 3], [1, 2, 3], [1, 2, 3]]\n",
      ".inf", "calibration.base_joints[2][2]", "expected a finite number");
  expect_calibration_refused("calibration:\n  actuator_offsets: [0, 0, 0, 0, 0]\n", "[0, 0",
                             "calibration.actuator_offsets",
                             "expected a list of 6 numbers, dL1..dL6 (mm), got 5");
  expect_calibration_refused("calibration:\n  actuator_offsets: [0, 0, 0, [0, 1], 0, 0]\n", "[0, 1]",
                             "calibration.actuator_offsets[3]", "expected a number");
  expect_calibration_refused("calibration:\n  note: [a, b]\n", "[a, b]", "calibration.note",
                             "expected a word or a text");
}

TEST(CalibrationFile, AllowedKeysAreTheBuiltMechanismsGroups) {
  const std::string path = test::source_path("examples/machines/tricept.yaml");
  auto m = parse_machine_text(calfile_text(path) + "calibration:\n  cardan_offset1: []\n", "test.yaml");
  ASSERT_FALSE(m.ok());
  EXPECT_NE(m.error().message.find(
                "unknown key for a tricept (allowed here: note, base_joints, platform_joints, center_joint, "
                "actuator_offsets)"),
            std::string::npos)
      << m.error().message;
}

}  // namespace
}  // namespace pkm
