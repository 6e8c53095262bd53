// Per-line CSV load files (statics/load_model.hpp parse_load_csv).
#include <fmt/format.h>
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <random>
#include <string>

#include "statics/load_model.hpp"

namespace pkm::statics {
namespace {

Error load_csv_failure(const std::string& text) {
  auto model = parse_load_csv(text, "loads.csv");
  if (model) {
    ADD_FAILURE() << "expected an error for:\n" << text;
    return Error{ErrorCode::io, "", {}};
  }
  EXPECT_EQ(model.error().code, ErrorCode::bad_input);
  return model.error();
}

TEST(LoadCsv, ReadsEveryColumnPerLine) {
  auto model = parse_load_csv(
      "line, fx_N,fy_N,fz_N,mx_Nmm,my_Nmm,mz_Nmm,tangential_N,normal_N,axial_N\r\n"
      "# a comment\n"
      "7,1,2,3,4,5,6,7,8,9\n"
      "\n"
      "12, -1e3 ,+2.5,0,0,0,0,0,0,-1\n",
      "loads.csv");
  ASSERT_TRUE(model.ok()) << model.error().message;
  ASSERT_EQ(model->blocks.size(), 2u);
  const CuttingLoad& seven = model->load_for_line(7);
  EXPECT_EQ(seven.force_N, Eigen::Vector3d(1, 2, 3));
  EXPECT_EQ(seven.moment_Nmm, Eigen::Vector3d(4, 5, 6));
  EXPECT_EQ(seven.tangential_N, 7);
  EXPECT_EQ(seven.normal_N, 8);
  EXPECT_EQ(seven.axial_N, 9);
  EXPECT_EQ(model->load_for_line(12).force_N, Eigen::Vector3d(-1e3, 2.5, 0));
  EXPECT_EQ(model->load_for_line(12).axial_N, -1);
  // Lines not listed carry no load.
  for (int line : {1, 6, 8, 11, 13, 1000}) EXPECT_TRUE(model->load_for_line(line).is_zero()) << line;
}

// The bisection over ascending rows finds what the general last-block-wins search finds, on random files.
TEST(LoadCsv, BisectionAgreesWithTheLinearSearchOnRandomFiles) {
  std::mt19937 rng(1501);
  for (int trial = 0; trial < 20; ++trial) {
    std::string text = "line,fx_N,tangential_N\n";
    int line = 0;
    const int rows = std::uniform_int_distribution<int>(1, 200)(rng);
    for (int r = 0; r < rows; ++r) {
      line += std::uniform_int_distribution<int>(1, 5)(rng);
      text += fmt::format("{},{},{}\n", line, std::normal_distribution<double>(0, 500)(rng),
                          std::uniform_real_distribution<double>(0, 900)(rng));
    }
    auto fast = parse_load_csv(text, "random.csv");
    ASSERT_TRUE(fast.ok()) << fast.error().message;
    ASSERT_TRUE(fast->blocks_ascending);
    LoadModel slow = *fast;
    slow.blocks_ascending = false;
    for (int l = 0; l <= line + 3; ++l) {
      const CuttingLoad& a = fast->load_for_line(l);
      const CuttingLoad& b = slow.load_for_line(l);
      ASSERT_EQ(a.force_N, b.force_N) << "line " << l;
      ASSERT_EQ(a.tangential_N, b.tangential_N) << "line " << l;
    }
  }
}

TEST(LoadCsv, NamesFileLineColumnAndKeyOfBadInput) {
  Error e = load_csv_failure("line,fx_N,force\n1,2,3\n");
  EXPECT_EQ(e.location.line, 1);
  EXPECT_EQ(e.location.column, 11);
  EXPECT_EQ(e.location.key, "force");
  EXPECT_NE(e.message.find("loads.csv:1:11"), std::string::npos) << e.message;

  e = load_csv_failure("line,fx_N,fy_N\n1,2,3\n2,5\n");
  EXPECT_EQ(e.location.line, 3);
  EXPECT_EQ(e.location.key, "fy_N");
  EXPECT_NE(e.message.find("expected 3 fields"), std::string::npos) << e.message;

  e = load_csv_failure("line,fx_N\n1,2,3\n");
  EXPECT_EQ(e.location.line, 2);
  EXPECT_EQ(e.location.column, 5);

  e = load_csv_failure("line,fx_N,fy_N\n1,2,abc\n");
  EXPECT_EQ(e.location.line, 2);
  EXPECT_EQ(e.location.column, 5);
  EXPECT_EQ(e.location.key, "fy_N");

  e = load_csv_failure("line,fx_N\n1,nan\n");
  EXPECT_EQ(e.location.key, "fx_N");
  e = load_csv_failure("line,fx_N\n1,1e400\n");
  EXPECT_EQ(e.location.key, "fx_N");
  e = load_csv_failure("line,fx_N\n0,1\n");
  EXPECT_EQ(e.location.key, "line");
  e = load_csv_failure("line,fx_N\n2.5,1\n");
  EXPECT_EQ(e.location.key, "line");
  e = load_csv_failure("line,fx_N\n5,1\n5,2\n");
  EXPECT_EQ(e.location.line, 3);
  EXPECT_NE(e.message.find("ascending"), std::string::npos) << e.message;
  e = load_csv_failure("fx_N,line\n1,2\n");
  EXPECT_NE(e.message.find("first column must be line"), std::string::npos) << e.message;
  e = load_csv_failure("line\n1\n");
  EXPECT_NE(e.message.find("no load column"), std::string::npos) << e.message;
  e = load_csv_failure("line,fx_N,fx_N\n");
  EXPECT_NE(e.message.find("twice"), std::string::npos) << e.message;
  e = load_csv_failure("# only a comment\n\n");
  EXPECT_NE(e.message.find("empty"), std::string::npos) << e.message;
}

// `--load @FILE.csv` picks the CSV reader by the extension.
TEST(LoadCsv, LoadSpecReadsCsvFilesByExtension) {
  const auto path = std::filesystem::temp_directory_path() / "pkm_load_csv_test_loads.csv";
  {
    std::ofstream out(path);
    out << "line,fz_N\n3,-250\n";
  }
  // Appended rather than "@" + path: GCC 12 warns falsely (stringop-overflow) on the latter here.
  std::string spec = "@";
  spec += path.string();
  auto model = parse_load_spec(spec);
  std::filesystem::remove(path);
  ASSERT_TRUE(model.ok()) << model.error().message;
  EXPECT_EQ(model->load_for_line(3).force_N.z(), -250);
  EXPECT_TRUE(model->load_for_line(4).is_zero());
}

}  // namespace
}  // namespace pkm::statics
