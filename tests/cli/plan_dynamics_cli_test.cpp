// pkm plan --dynamics: forces.csv beside the other outputs, the dynamics block of the summary, and the
// failures (no dynamics section, a drive force above actuator_force_max) that name their cause and write
// nothing.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <vector>

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
                                     " --dynamics --tables csv --out " + out + " --json",
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
  const auto run = test::run_pkm("plan " + test::source_path("examples/programs/circle.ngc") + " --machine " +
                                 test::source_path("examples/machines/hexaglide.yaml") +
                                 " --dynamics --tables csv --out " + out);
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
                                 machine_path + " --dynamics --tables csv --out " + out);
  EXPECT_NE(run.exit_code, 0);
  EXPECT_NE(run.out.find("circle.ngc:"), std::string::npos) << run.out;
  EXPECT_NE(run.out.find("above actuator_force_max 250.0 N (" + machine_path + ":"), std::string::npos)
      << run.out;
  EXPECT_FALSE(fs::exists(fs::path(out) / "forces.csv"));
}

TEST(PlanDynamicsCli, ALaggingDriveGetsTheCommandThatGivesItsForce) {
  std::string machine = text_of(test::source_path("examples/machines/hexapod_ch5.yaml"));
  const std::string key = "  drive: {model: ideal}\n";
  ASSERT_NE(machine.find(key), std::string::npos);
  machine.replace(machine.find(key), key.size(), "  drive: {model: lag, tau_s: 0.005}\n");
  const std::string machine_path = test::write_temp_file("lagging_drives.yaml", machine);
  const std::string out = fresh_dynamics_dir("lag");
  const auto run = test::run_pkm("plan " + test::source_path("examples/programs/circle.ngc") + " --machine " +
                                 machine_path + " --dynamics --tables csv --out " + out);
  ASSERT_EQ(run.exit_code, 0) << run.out;
  std::ifstream forces(fs::path(out) / "forces.csv");
  std::string header;
  std::getline(forces, header);
  ASSERT_NE(header.find(",power6_W,u1_N,u2_N,u3_N,u4_N,u5_N,u6_N"), std::string::npos) << header;
  std::vector<std::vector<double>> rows;
  for (std::string line; std::getline(forces, line);) {
    std::stringstream fields(line);
    std::vector<double> v;
    for (std::string field; std::getline(fields, field, ',');) v.push_back(std::stod(field));
    ASSERT_EQ(v.size(), 2u + 6 * 3 + 6 + 6) << line;
    rows.push_back(std::move(v));
  }
  ASSERT_GT(rows.size(), 100u);
  // u = P + τ Ṗ, Ṗ the central difference of the rows either side; the rows print 4 decimals.
  double largest_lead = 0.0;
  for (std::size_t k = 1; k + 1 < rows.size(); ++k) {
    for (int j = 0; j < 6; ++j) {
      const double force = rows[k][2 + 3 * j];
      const double rate =
          (rows[k + 1][2 + 3 * j] - rows[k - 1][2 + 3 * j]) / (rows[k + 1][0] - rows[k - 1][0]);
      const double command = rows[k][2 + 24 + j];
      EXPECT_NEAR(command, force + 0.005 * rate, 2e-3) << "row " << k << " drive " << j + 1;
      largest_lead = std::max(largest_lead, std::abs(command - force));
    }
  }
  EXPECT_GT(largest_lead, 0.1);  // the lag matters somewhere along the circle
  // Ideal drives: no command columns (the command is the force).
  const std::string ideal_out = fresh_dynamics_dir("ideal");
  const auto ideal = test::run_pkm("plan " + test::source_path("examples/programs/circle.ngc") +
                                   " --machine " + test::source_path("examples/machines/hexapod_ch5.yaml") +
                                   " --dynamics --tables csv --out " + ideal_out);
  ASSERT_EQ(ideal.exit_code, 0) << ideal.out;
  const std::string ideal_forces = text_of((fs::path(ideal_out) / "forces.csv").string());
  EXPECT_NE(ideal_forces.find("power6_W\n"), std::string::npos);
  EXPECT_EQ(ideal_forces.find("u1_N"), std::string::npos);
}

}  // namespace
}  // namespace pkm
