// pkm plan --dynamics: forces.csv beside the other outputs, the dynamics block of the summary, and the
// failures (no dynamics section, a drive force above actuator_force_max) that name their cause and write
// nothing.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>

#include "cli/cli_support.hpp"

namespace pkm {
namespace {

namespace fs = std::filesystem;

std::string fresh_dynamics_dir(const std::string& name) {
  const fs::path dir = fs::temp_directory_path() / ("pkm_plan_dynamics_cli_" + name);
  fs::remove_all(dir);
  return dir.string();
}

std::string text_of(const std::string& path) {
  std::ifstream in(path);
  std::stringstream buffer;
  buffer << in.rdbuf();
  return buffer.str();
}

TEST(PlanDynamicsCli, WritesForcesAndTheDynamicsSummary) {
  const std::string out = fresh_dynamics_dir("helix");
  const auto run = test::run_pkm("plan " + test::source_path("examples/programs/circle.ngc") + " --machine " +
                                     test::source_path("examples/machines/hexapod_ch5.yaml") +
                                     " --dynamics --out " + out + " --json",
                                 false);
  ASSERT_EQ(run.exit_code, 0) << run.out;
  const auto summary = nlohmann::json::parse(run.out);
  ASSERT_TRUE(summary.contains("dynamics"));
  const auto& d = summary["dynamics"];
  ASSERT_EQ(d["drives"].size(), 6u);
  for (const auto& drive : d["drives"]) {
    // At least the static share of 60 + 6·25 kg on six struts, and more while moving.
    EXPECT_GT(drive["peak_force_N"].get<double>(), drive["peak_static_N"].get<double>() * (1 - 1e-12));
    EXPECT_GT(drive["peak_static_N"].get<double>(), 100.0);
    EXPECT_GT(drive["peak_force_line"].get<int>(), 0);
  }
  EXPECT_GE(d["energy_no_recovery_J"].get<double>(), d["energy_braking_free_J"].get<double>());
  EXPECT_GE(d["energy_braking_free_J"].get<double>(), d["energy_recovery_J"].get<double>());
  // One row per tick plus the header; each total is its static plus its dynamic part.
  std::ifstream forces(fs::path(out) / "forces.csv");
  std::string header;
  std::getline(forces, header);
  EXPECT_EQ(header.rfind("time_s,line,P1_N,P1_static_N,P1_dynamic_N,P2_N", 0), 0u) << header;
  long rows = 0;
  for (std::string line; std::getline(forces, line); ++rows) {
    std::stringstream fields(line);
    std::vector<double> v;
    for (std::string field; std::getline(fields, field, ',');) v.push_back(std::stod(field));
    ASSERT_EQ(v.size(), 2u + 6 * 3 + 6);
    for (int j = 0; j < 6; ++j) EXPECT_NEAR(v[2 + 3 * j], v[3 + 3 * j] + v[4 + 3 * j], 2e-4);
  }
  EXPECT_EQ(rows, summary["ticks"].get<long>());
}

TEST(PlanDynamicsCli, WithoutADynamicsSectionItSaysSoAndWritesNothing) {
  const std::string out = fresh_dynamics_dir("none");
  const auto run =
      test::run_pkm("plan " + test::source_path("examples/programs/circle.ngc") + " --machine " +
                    test::source_path("examples/machines/hexaglide.yaml") + " --dynamics --out " + out);
  EXPECT_NE(run.exit_code, 0);
  EXPECT_NE(run.out.find("hexaglide.yaml: the machine file has no dynamics: section"), std::string::npos)
      << run.out;
  EXPECT_FALSE(fs::exists(fs::path(out) / "forces.csv"));
  EXPECT_FALSE(fs::exists(fs::path(out) / "summary.json"));
}

TEST(PlanDynamicsCli, AForceAboveTheDrivesLimitNamesTheLineAndWritesNothing) {
  std::string machine = text_of(test::source_path("examples/machines/hexapod_ch5.yaml"));
  const std::string key = "  actuator_accel: 2000    # mm/s^2\n";
  ASSERT_NE(machine.find(key), std::string::npos);
  machine.replace(machine.find(key), key.size(), key + "  actuator_force_max: 250\n");
  const std::string machine_path = test::write_temp_file("force_limited.yaml", machine);
  const std::string out = fresh_dynamics_dir("limit");
  const auto run = test::run_pkm("plan " + test::source_path("examples/programs/circle.ngc") + " --machine " +
                                 machine_path + " --dynamics --out " + out);
  EXPECT_NE(run.exit_code, 0);
  EXPECT_NE(run.out.find("circle.ngc:"), std::string::npos) << run.out;
  EXPECT_NE(run.out.find("above actuator_force_max 250.0 N (" + machine_path + ":"), std::string::npos)
      << run.out;
  EXPECT_FALSE(fs::exists(fs::path(out) / "forces.csv"));
}

}  // namespace
}  // namespace pkm
