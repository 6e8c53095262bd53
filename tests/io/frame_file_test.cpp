// The machine file's `stiffness.frame` (src/io/frame_file.cpp, docs/stiffness_frame.md): what a frame reads
// as (named and in-place sections, supports, the default and given section axes, the base-joint nodes), and
// every refused input (unknown node or section, non-positive constants, a beam of zero length, a section axis
// along the beam, a wrong key, a name given twice, the wrong number of base-joint nodes) named by file, line,
// column and key.
#include <fmt/format.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <string>

#include "machine/limits_test_support.hpp"
#include "test_support.hpp"

namespace pkm {
namespace {

// A frame of three columns under the ch5 hexapod's base-joint pairs, joined at the top.
const std::string kFrameSection = R"(stiffness:
  struts: {stiffness_N_mm: 200000}
  frame:
    sections:
      column: {modulus_N_mm2: 210000, shear_modulus_N_mm2: 81000, area_mm2: 5000, second_moment_x_mm4: 2.0e7, second_moment_y_mm4: 3.0e7, torsion_constant_mm4: 4.0e7}
    nodes:
      - {name: foot1, position_mm: [300, 170, -600], fixed: true}
      - {name: top1, position_mm: [300, 170, -40]}
      - {name: foot2, position_mm: [-300, 170, -600], fixed: true}
      - {name: top2, position_mm: [-300, 170, -40]}
      - {name: top3, position_mm: [0, -346, -40], fixed: false}
      - {name: foot3, position_mm: [0, -346, -600], fixed: yes}
    beams:
      - {from: foot1, to: top1, section: column, section_x: [1, 0, 0]}
      - {from: foot2, to: top2, section: column}
      - {from: foot3, to: top3, section: {modulus_N_mm2: 70000, shear_modulus_N_mm2: 26000, area_mm2: 3000, second_moment_x_mm4: 1.0e7, second_moment_y_mm4: 1.0e7, torsion_constant_mm4: 2.0e7}}
      - {from: top1, to: top2, section: column}
      - {from: top2, to: top3, section: column, section_x: [0, 0, 2]}
    base_joint_nodes: [top1, top1, top2, top2, top3, top3]
)";

// kFrameSection with `from` replaced by `to` (the first occurrence), which must be there.
std::string frame_file_variant(const std::string& from, const std::string& to) {
  const std::size_t at = kFrameSection.find(from);
  EXPECT_NE(at, std::string::npos) << from;
  if (at == std::string::npos) return kFrameSection;
  return kFrameSection.substr(0, at) + to + kFrameSection.substr(at + from.size());
}

// "test.yaml:LINE:COLUMN" of the first `token` in `section` appended to the ch5 hexapod's text.
std::string frame_file_place(const std::string& section, const std::string& token) {
  const std::size_t at = section.find(token);
  EXPECT_NE(at, std::string::npos) << token;
  const std::size_t line_start = section.rfind('\n', at);
  const int line = test::appended_line(test::kCh5HexapodText) +
                   static_cast<int>(std::count(section.begin(), section.begin() + at, '\n'));
  const std::size_t column = at - (line_start == std::string::npos ? 0 : line_start + 1) + 1;
  return fmt::format("test.yaml:{}:{}", line, column);
}

void expect_frame_refused(const std::string& section, const std::string& token, const std::string& what) {
  const std::string message = test::appended_section_error(test::kCh5HexapodText, section);
  const std::string expected = frame_file_place(section, token) + ": " + what;
  EXPECT_NE(message.find(expected), std::string::npos)
      << "expected: " << expected << "\ngot:      " << message;
}

TEST(FrameFile, ReadsNodesBeamsSectionsAndTheBaseJointNodes) {
  const Machine machine = test::machine_from_text(test::kCh5HexapodText + kFrameSection);
  const FrameParameters& frame = machine.stiffness.frame;
  ASSERT_FALSE(frame.empty());
  EXPECT_EQ(machine.stiffness.model, StiffnessModel::frame);
  EXPECT_EQ(frame.source, "test.yaml");
  EXPECT_EQ(frame.line, test::appended_line(test::kCh5HexapodText) + 2);
  ASSERT_EQ(frame.nodes.size(), 6u);
  EXPECT_EQ(frame.nodes[1].name, "top1");
  EXPECT_EQ(frame.nodes[1].position_mm, Eigen::Vector3d(300, 170, -40));
  const bool fixed[6] = {true, false, true, false, false, true};
  for (int n = 0; n < 6; ++n) EXPECT_EQ(frame.nodes[n].fixed, fixed[n]) << n;
  EXPECT_EQ(frame.nodes[0].line, test::appended_line(test::kCh5HexapodText) + 6);
  ASSERT_EQ(frame.beams.size(), 5u);
  EXPECT_EQ(frame.beams[0].from, 0);
  EXPECT_EQ(frame.beams[0].to, 1);
  EXPECT_EQ(frame.beams[0].section.modulus_N_mm2, 210000);
  EXPECT_EQ(frame.beams[0].section.shear_modulus_N_mm2, 81000);
  EXPECT_EQ(frame.beams[0].section.area_mm2, 5000);
  EXPECT_EQ(frame.beams[0].section.second_moment_x_mm4, 2.0e7);
  EXPECT_EQ(frame.beams[0].section.second_moment_y_mm4, 3.0e7);
  EXPECT_EQ(frame.beams[0].section.torsion_constant_mm4, 4.0e7);
  EXPECT_EQ(frame.beams[2].section.modulus_N_mm2, 70000);  // in place
  EXPECT_EQ(frame.beams[0].section_x, Eigen::Vector3d(1, 0, 0));
  // Default section axes: the base z axis, the base x axis for a beam along z.
  EXPECT_EQ(frame.beams[1].section_x, Eigen::Vector3d::UnitX());
  EXPECT_EQ(frame.beams[3].section_x, Eigen::Vector3d::UnitZ());
  EXPECT_EQ(frame.beams[4].section_x, Eigen::Vector3d(0, 0, 2));
  EXPECT_EQ(frame.strut_nodes, (std::vector<int>{1, 1, 3, 3, 4, 4}));
  // Without frame: an empty one, and the model from what is given.
  const Machine bare =
      test::machine_from_text(test::kCh5HexapodText + "stiffness:\n  struts: {stiffness_N_mm: 200000}\n");
  EXPECT_TRUE(bare.stiffness.frame.empty());
}

TEST(FrameFile, UnknownNodesAndSectionsAreNamedByPlaceAndKey) {
  std::string s = frame_file_variant("to: top2, section: column}", "to: top9, section: column}");
  expect_frame_refused(s, "top9", "stiffness.frame.beams[1].to: unknown node 'top9'");
  s = frame_file_variant("base_joint_nodes: [top1, top1, top2", "base_joint_nodes: [top1, top1, topp");
  expect_frame_refused(s, "topp", "stiffness.frame.base_joint_nodes[2]: unknown node 'topp'");
  s = frame_file_variant("to: top1, section: column", "to: top1, section: colum");
  expect_frame_refused(s, "colum,", "stiffness.frame.beams[0].section: unknown section 'colum'");
  s = frame_file_variant("{name: top2,", "{name: top1,");
  expect_frame_refused(s, "top1, position_mm: [-300",
                       "stiffness.frame.nodes[3].name: node 'top1' is named twice");
}

TEST(FrameFile, NonPositiveConstantsAreRefused) {
  std::string s = frame_file_variant("column: {modulus_N_mm2: 210000", "column: {modulus_N_mm2: 0");
  expect_frame_refused(s, "0, shear",
                       "stiffness.frame.sections.column.modulus_N_mm2: must be positive, got 0");
  s = frame_file_variant("second_moment_y_mm4: 1.0e7", "second_moment_y_mm4: -1.0e7");
  expect_frame_refused(s, "-1.0e7",
                       "stiffness.frame.beams[2].section.second_moment_y_mm4: must be positive, got -1");
  s = frame_file_variant("shear_modulus_N_mm2: 81000, ", "");
  expect_frame_refused(s, "{modulus_N_mm2: 210000",
                       "stiffness.frame.sections.column.shear_modulus_N_mm2: missing");
}

TEST(FrameFile, BeamsOfZeroLengthOrWithTheirSectionAxisAlongThemAreRefused) {
  std::string s = frame_file_variant("{from: top1, to: top2,", "{from: top1, to: top1,");
  expect_frame_refused(s, "{from: top1, to: top1,",
                       "stiffness.frame.beams[3]: the beam from 'top1' to 'top1' has zero length");
  s = frame_file_variant("[-300, 170, -40]", "[300, 170, -40]");
  expect_frame_refused(s, "{from: top1, to: top2,",
                       "stiffness.frame.beams[3]: the beam from 'top1' to 'top2' has zero length");
  s = frame_file_variant("section_x: [1, 0, 0]", "section_x: [0, 0, -3]");
  expect_frame_refused(s, "[0, 0, -3]",
                       "stiffness.frame.beams[0].section_x: must not be parallel to the beam");
}

TEST(FrameFile, WrongKeysAndShapesAreRefused) {
  std::string s = frame_file_variant("section: column, section_x: [0", "sectoin: column, section_x: [0");
  expect_frame_refused(s, "sectoin", "stiffness.frame.beams[4].sectoin: unknown key");
  s = frame_file_variant("    nodes:", "    node:");
  expect_frame_refused(s, "node:", "stiffness.frame.node: unknown key");
  s = frame_file_variant("area_mm2: 5000,", "area: 5000,");
  expect_frame_refused(s, "area:", "stiffness.frame.sections.column.area: unknown key");
  s = frame_file_variant("fixed: yes", "fixed: maybe");
  expect_frame_refused(s, "maybe", "stiffness.frame.nodes[5].fixed: expected true or false");
  s = frame_file_variant("[top1, top1, top2, top2, top3, top3]", "[top1, top1, top2, top2, top3]");
  expect_frame_refused(s, "[top1, top1, top2, top2, top3]",
                       "stiffness.frame.base_joint_nodes: expected a list of 6 node names (one per strut)");
  s = frame_file_variant("position_mm: [0, -346, -40]", "position_mm: [0, -346]");
  expect_frame_refused(s, "[0, -346]", "stiffness.frame.nodes[4].position_mm: expected 3 numbers, got 2");
  expect_frame_refused("stiffness:\n  struts: {stiffness_N_mm: 5}\n  frame: [1, 2]\n", "[1, 2]",
                       "stiffness.frame: expected a mapping");
}

}  // namespace
}  // namespace pkm
