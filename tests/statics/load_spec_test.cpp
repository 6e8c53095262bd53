// The CLI's --load text and load files (statics/load_model.hpp).
#include <fmt/format.h>
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "statics/load_model.hpp"

namespace pkm::statics {
namespace {

std::string spec_error(std::string_view spec) {
  auto model = parse_load_spec(spec);
  if (model) {
    ADD_FAILURE() << "expected an error for '" << spec << "'";
    return {};
  }
  EXPECT_EQ(model.error().code, ErrorCode::bad_input);
  return model.error().message;
}

std::string yaml_error(const std::string& text) {
  auto model = parse_load_yaml(text, "load.yaml");
  if (model) {
    ADD_FAILURE() << "expected an error for:\n" << text;
    return {};
  }
  EXPECT_EQ(model.error().code, ErrorCode::bad_input);
  return model.error().message;
}

TEST(LoadSpec, ReadsEveryKey) {
  auto model = parse_load_spec(
      "tangential=1000, normal=100,axial=-20.5,cutter_radius=5,contact=right,force=1:2:3,moment=-4:5e3:+6");
  ASSERT_TRUE(model.ok()) << model.error().message;
  const CuttingLoad& l = model->default_load;
  EXPECT_EQ(l.tangential_N, 1000);
  EXPECT_EQ(l.normal_N, 100);
  EXPECT_EQ(l.axial_N, -20.5);
  EXPECT_EQ(l.cutter_radius_mm, 5);
  EXPECT_EQ(l.contact_side, -1);
  EXPECT_EQ(l.force_N, Eigen::Vector3d(1, 2, 3));
  EXPECT_EQ(l.moment_Nmm, Eigen::Vector3d(-4, 5000, 6));
  EXPECT_TRUE(model->blocks.empty());
}

TEST(LoadSpec, DefaultsForKeysNotGiven) {
  auto model = parse_load_spec("tangential=1000,normal=100,cutter_radius=5");
  ASSERT_TRUE(model.ok());
  EXPECT_EQ(model->default_load.axial_N, 0);
  EXPECT_EQ(model->default_load.contact_side, +1);
  EXPECT_TRUE(model->default_load.force_N.isZero());
  EXPECT_FALSE(model->empty());
}

TEST(LoadSpec, ErrorsQuoteTheOffendingText) {
  std::string message = spec_error("tangential=1000,torque=5");
  EXPECT_NE(message.find("'torque=5'"), std::string::npos) << message;
  EXPECT_NE(message.find("unknown key 'torque'"), std::string::npos) << message;
  message = spec_error("tangential=1k");
  EXPECT_NE(message.find("expected a number, got '1k'"), std::string::npos) << message;
  message = spec_error("normal=");
  EXPECT_NE(message.find("expected a number, got ''"), std::string::npos) << message;
  message = spec_error("tangential");
  EXPECT_NE(message.find("'tangential': expected key=value"), std::string::npos) << message;
  message = spec_error("force=1:2");
  EXPECT_NE(message.find("force: expected three numbers X:Y:Z, got '1:2'"), std::string::npos) << message;
  message = spec_error("moment=1:x:3");
  EXPECT_NE(message.find("moment: expected a number, got 'x'"), std::string::npos) << message;
  message = spec_error("contact=above");
  EXPECT_NE(message.find("expected left or right, got 'above'"), std::string::npos) << message;
  message = spec_error("cutter_radius=-5");
  EXPECT_NE(message.find("cannot be negative"), std::string::npos) << message;
  message = spec_error("tangential=1,tangential=2");
  EXPECT_NE(message.find("given twice"), std::string::npos) << message;
  message = spec_error("tangential=1,,normal=2");
  EXPECT_NE(message.find("empty item"), std::string::npos) << message;
  message = spec_error("");
  EXPECT_NE(message.find("empty"), std::string::npos) << message;
  message = spec_error("tangential=nan");
  EXPECT_NE(message.find("got 'nan'"), std::string::npos) << message;
}

TEST(LoadFile, DefaultAndBlocks) {
  auto model = parse_load_yaml(R"(# a pocket: roughing, then a finishing pass with a lighter cut
default: {tangential: 800, normal: 80, cutter_radius: 6, contact: right}
blocks:
  - {lines: [10, 20], tangential: 1200, force: [0, 0, -50]}
  - lines: [15, 15]
    axial: 40
    contact: left
)",
                               "load.yaml");
  ASSERT_TRUE(model.ok()) << model.error().message;
  EXPECT_EQ(model->default_load.tangential_N, 800);
  EXPECT_EQ(model->default_load.contact_side, -1);
  ASSERT_EQ(model->blocks.size(), 2u);
  EXPECT_EQ(model->blocks[0].first_line, 10);
  EXPECT_EQ(model->blocks[0].last_line, 20);
  // Blocks start from the default.
  EXPECT_EQ(model->blocks[0].load.tangential_N, 1200);
  EXPECT_EQ(model->blocks[0].load.normal_N, 80);
  EXPECT_EQ(model->blocks[0].load.cutter_radius_mm, 6);
  EXPECT_EQ(model->blocks[0].load.force_N, Eigen::Vector3d(0, 0, -50));
  EXPECT_EQ(model->blocks[1].load.tangential_N, 800);
  EXPECT_EQ(model->blocks[1].load.axial_N, 40);
  EXPECT_EQ(model->blocks[1].load.contact_side, +1);
  EXPECT_EQ(model->load_for_line(15).axial_N, 40);
  EXPECT_EQ(model->load_for_line(16).tangential_N, 1200);
}

TEST(LoadFile, DefaultMayComeAfterTheBlocks) {
  auto model =
      parse_load_yaml("blocks:\n  - {lines: [1, 2], normal: 5}\ndefault: {tangential: 7}\n", "load.yaml");
  ASSERT_TRUE(model.ok()) << model.error().message;
  EXPECT_EQ(model->blocks[0].load.tangential_N, 7);
  EXPECT_EQ(model->blocks[0].load.normal_N, 5);
}

TEST(LoadFile, ErrorsNameFileLineColumnAndKey) {
  std::string message = yaml_error("default:\n  tangential: 100\n  torque: 5\n");
  EXPECT_NE(message.find("load.yaml:3:3: default.torque: unknown key"), std::string::npos) << message;
  message = yaml_error("default: {tangential: lots}\n");
  EXPECT_NE(message.find("load.yaml:1:23: default.tangential: expected a number, got 'lots'"),
            std::string::npos)
      << message;
  message = yaml_error("blocks:\n  - {lines: [5, 2], normal: 1}\n");
  EXPECT_NE(message.find("load.yaml:2:13: blocks[0].lines: FIRST must not be after LAST"), std::string::npos)
      << message;
  message = yaml_error("blocks:\n  - {normal: 1}\n");
  EXPECT_NE(message.find("load.yaml:2:5: blocks[0].lines: missing"), std::string::npos) << message;
  message = yaml_error("blocks:\n  - {lines: [1.5, 2]}\n");
  EXPECT_NE(message.find("blocks[0].lines: expected a program line number"), std::string::npos) << message;
  message = yaml_error("default: {force: [1, 2]}\n");
  EXPECT_NE(message.find("default.force: expected [x, y, z]"), std::string::npos) << message;
  message = yaml_error("default: {contact: middle}\n");
  EXPECT_NE(message.find("default.contact: expected left or right, got 'middle'"), std::string::npos)
      << message;
  message = yaml_error("default: {cutter_radius: -1}\n");
  EXPECT_NE(message.find("cannot be negative"), std::string::npos) << message;
  message = yaml_error("loads: {}\n");
  EXPECT_NE(message.find("load.yaml:1:1: loads: unknown key (allowed: default, blocks)"), std::string::npos)
      << message;
  message = yaml_error("default: [1, 2\n");
  EXPECT_NE(message.find("load.yaml:"), std::string::npos) << message;
  EXPECT_NE(message.find("not valid YAML"), std::string::npos) << message;
  message = yaml_error("blocks: {lines: [1, 2]}\n");
  EXPECT_NE(message.find("blocks: expected a list"), std::string::npos) << message;
}

TEST(LoadFile, AtFileReadsTheFile) {
  const std::filesystem::path path =
      std::filesystem::temp_directory_path() / "pkm_statics_load_spec_test.yaml";
  // fmt rather than operator+: GCC 12 warns falsely (-Wstringop-overflow) on "@" + path.string().
  const std::string spec = fmt::format("@{}", path.string());
  {
    std::ofstream out(path);
    out << "default: {tangential: 900}\nblocks:\n  - {lines: [3, 4], tangential: 950, torque: 1}\n";
  }
  auto model = parse_load_spec(spec);
  ASSERT_FALSE(model.ok());
  EXPECT_NE(model.error().message.find(fmt::format("{}:3:", path.string())), std::string::npos)
      << model.error().message;
  {
    std::ofstream out(path);
    out << "default: {tangential: 900}\nblocks:\n  - {lines: [3, 4], tangential: 950}\n";
  }
  model = parse_load_spec(spec);
  ASSERT_TRUE(model.ok()) << model.error().message;
  EXPECT_EQ(model->default_load.tangential_N, 900);
  EXPECT_EQ(model->load_for_line(3).tangential_N, 950);
  std::filesystem::remove(path);

  auto missing = parse_load_spec("@/nonexistent/pkm_load.yaml");
  ASSERT_FALSE(missing.ok());
  EXPECT_EQ(missing.error().code, ErrorCode::io);
  EXPECT_NE(missing.error().message.find("/nonexistent/pkm_load.yaml"), std::string::npos);
}

}  // namespace
}  // namespace pkm::statics
