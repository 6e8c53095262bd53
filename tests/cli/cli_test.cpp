// Golden scenarios of the pkm command line, including the ones that must fail: the exit code, the JSON, and a
// one-line message naming the file, line and key.
#include <gtest/gtest.h>
#include <sys/wait.h>

#include <array>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>

#include "cli/cli_support.hpp"
#include "source_paths.hpp"

namespace {

using pkm::test::CliRun;

CliRun cli_run(const std::string& args) {
  return pkm::test::run_pkm(args);
}

std::string example(const std::string& name) {
  return pkm::test::source_path("examples/machines/" + std::string(name));
}

std::string cli_write_temp(const std::string& name, const std::string& text) {
  return pkm::test::write_temp_file(name, text);
}

const char* kCh5 = "hexapod_ch5.yaml";

// Appends ",value" (or "value" to an empty list) with full precision.
void append_number(std::string& list, double value) {
  char text[64];
  std::snprintf(text, sizeof text, "%.12f", value);
  if (!list.empty()) list.push_back(',');
  list.append(text);
}

TEST(Cli, IkReproducesE2) {
  const CliRun r = cli_run("ik --machine " + example(kCh5) + " --pose=-50,0,700,0,0,0 --json");
  ASSERT_EQ(r.exit_code, 0) << r.out;
  const auto j = nlohmann::json::parse(r.out);
  const double expected[6] = {623.7911728445, 607.5487036598, 603.1222458757,
                              586.3074649620, 588.5880863511, 621.6397151039};
  ASSERT_EQ(j["actuators"].size(), 6u);
  for (int i = 0; i < 6; ++i) EXPECT_NEAR(j["actuators"][i].get<double>(), expected[i], 1e-9);
  EXPECT_EQ(j["unit"], "mm");
}

TEST(Cli, FkReproducesE3) {
  const CliRun r =
      cli_run("fk --machine " + example(kCh5) +
              " --actuators 623.791,607.548,603.122,586.307,588.588,621.639 --guess=-50,0,700,0,0,0 --json");
  ASSERT_EQ(r.exit_code, 0) << r.out;
  const auto j = nlohmann::json::parse(r.out);
  EXPECT_NEAR(j["pose"][0].get<double>(), -49.99972591, 1e-7);
  EXPECT_NEAR(j["pose"][2].get<double>(), 699.99958614, 1e-7);
  EXPECT_NEAR(j["pose"][3].get<double>(), -1.99990e-4, 1e-9);  // degrees
  EXPECT_GT(j["iterations"].get<int>(), 0);
  EXPECT_LE(j["residual_mm"].get<double>(), 1e-9);
}

TEST(Cli, FkAllListsAssemblyModesNearestFirst) {
  const CliRun r =
      cli_run("fk --machine " + example(kCh5) +
              " --actuators 623.7911728445,607.5487036598,603.1222458757,586.3074649620,588.5880863511,"
              "621.6397151039 --all --json");
  ASSERT_EQ(r.exit_code, 0) << r.out;
  const auto j = nlohmann::json::parse(r.out);
  ASSERT_GE(j["solutions"].size(), 2u);
  EXPECT_NEAR(j["solutions"][0]["pose"][0].get<double>(), -50.0, 1e-8);
  EXPECT_NEAR(j["solutions"][0]["pose"][2].get<double>(), 700.0, 1e-8);
}

// `pkm ik` of a pose on a shipped machine, as an --actuators list ("" when ik fails).
std::string ik_actuators(const std::string& machine, const std::string& pose) {
  const CliRun ik = cli_run("ik --machine " + example(machine) + " --pose " + pose + " --json");
  if (ik.exit_code != 0) return "";
  std::string actuators;
  const auto lengths =
      nlohmann::json::parse(ik.out)["actuators"];  // a copy: the parsed document is a temporary
  for (const auto& v : lengths) append_number(actuators, v.get<double>());
  return actuators;
}

TEST(Cli, FkAllOnASixSixHexapodListsEveryModeWithWhatTheHomotopySaw) {
  // hexapod_ch3_delta30.yaml: platform joints 30° apart, a 6-6 layout. The home pose's lengths.
  const std::string actuators = ik_actuators("hexapod_ch3_delta30.yaml", "0,0,700,0,0,0");
  ASSERT_FALSE(actuators.empty());
  const CliRun r = cli_run("fk --machine " + example("hexapod_ch3_delta30.yaml") + " --actuators " +
                           actuators + " --all --json");
  ASSERT_EQ(r.exit_code, 0) << r.out;
  const auto j = nlohmann::json::parse(r.out);
  ASSERT_GE(j["solutions"].size(), 2u);
  EXPECT_EQ(j["solutions"].size() % 2, 0u);
  // Nearest to home first: the home pose itself, in the home mode.
  EXPECT_NEAR(j["solutions"][0]["pose"][2].get<double>(), 700.0, 1e-8);
  EXPECT_EQ(j["solutions"][0]["branch"].get<int>(), 0);
  const auto& report = j["report"];
  EXPECT_NE(report["method"].get<std::string>().find("homotopy"), std::string::npos);
  EXPECT_EQ(report["real"].get<int>() + report["complex"].get<int>() + report["at_infinity"].get<int>() +
                report["failed"].get<int>(),
            40);
  const CliRun text =
      cli_run("fk --machine " + example("hexapod_ch3_delta30.yaml") + " --actuators " + actuators + " --all");
  ASSERT_EQ(text.exit_code, 0) << text.out;
  EXPECT_NE(text.out.find("complex"), std::string::npos) << text.out;
}

TEST(Cli, FkAllOnGenhexkinsScansTheInverseMotion) {
  // LinuxCNC's genhexkins layout has its base joints merged in pairs (3-6).
  const std::string actuators = ik_actuators("hexapod_genhexkins.yaml", "10,-20,520,3,-2,5");
  ASSERT_FALSE(actuators.empty());
  const CliRun r = cli_run("fk --machine " + example("hexapod_genhexkins.yaml") + " --actuators " +
                           actuators + " --all --json");
  ASSERT_EQ(r.exit_code, 0) << r.out;
  const auto j = nlohmann::json::parse(r.out);
  EXPECT_NE(j["report"]["method"].get<std::string>().find("3-6"), std::string::npos) << r.out;
  EXPECT_NEAR(j["solutions"][0]["pose"][0].get<double>(), 10.0, 1e-8);
  EXPECT_NEAR(j["solutions"][0]["pose"][5].get<double>(), 5.0, 1e-8);
}

TEST(Cli, PlanarPoseTakesPhi) {
  const CliRun ik = cli_run("ik --machine " + example("planar3.yaml") + " --pose 10,-5,20 --json");
  ASSERT_EQ(ik.exit_code, 0) << ik.out;
  const auto q = nlohmann::json::parse(ik.out)["actuators"];
  std::string actuators;
  for (const auto& v : q) append_number(actuators, v.get<double>());
  const CliRun all =
      cli_run("fk --machine " + example("planar3.yaml") + " --actuators " + actuators + " --all --json");
  ASSERT_EQ(all.exit_code, 0) << all.out;
  bool found = false;
  const auto parsed = nlohmann::json::parse(all.out);
  for (const auto& s : parsed["solutions"]) {
    found = found || (std::abs(s["pose"][0].get<double>() - 10) < 1e-4 &&
                      std::abs(s["pose"][2].get<double>() - 20) < 1e-4);
  }
  EXPECT_TRUE(found) << all.out;
}

TEST(Cli, UnreachablePoseNamesTheLimitAndItsLine) {
  const CliRun r = cli_run("ik --machine " + example(kCh5) + " --pose 0,0,1200,0,0,0");
  EXPECT_EQ(r.exit_code, 3);
  EXPECT_NE(r.out.find("actuator_max"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("hexapod_ch5.yaml:"), std::string::npos) << r.out;
}

TEST(Cli, BadNumberNamesTheField) {
  const CliRun r = cli_run("ik --machine " + example(kCh5) + " --pose 0,0,x,0,0,0");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.out.find("--pose"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("'x'"), std::string::npos) << r.out;
}

TEST(Cli, WrongPointCountNamesFileLineAndKey) {
  const std::string path =
      cli_write_temp("short.yaml",
                     "type: hexapod\n"
                     "angles: abc\n"
                     "base_joints:\n"
                     "  - [400, 0, 0]\n"
                     "  - [200, 346, 0]\n"
                     "platform_joints: [[1,2,3],[1,2,3],[1,2,3],[1,2,3],[1,2,3],[1,2,3]]\n");
  const CliRun r = cli_run("check " + path);
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.out.find("pkm_cli_test_short.yaml:4:3: base_joints"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("got 2 points"), std::string::npos) << r.out;
}

TEST(Cli, MisspeltKeyIsAnError) {
  const std::string path = cli_write_temp("typo.yaml",
                                          "type: hexapod\n"
                                          "angles: abc\n"
                                          "base_joint: []\n");
  const CliRun r = cli_run("check " + path);
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.out.find("pkm_cli_test_typo.yaml:3:1: base_joint: unknown key"), std::string::npos) << r.out;
}

TEST(Cli, MissingFileIsAnError) {
  const CliRun r = cli_run("check /nonexistent/machine.yaml");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.out.find("/nonexistent/machine.yaml: cannot read machine file"), std::string::npos) << r.out;
}

TEST(Cli, SingularActuatorValuesExitWithFour) {
  // All platform joints in the base plane (tool point 150 mm above it): every strut horizontal.
  const CliRun ik = cli_run("ik --machine " + example(kCh5) + " --pose 0,0,150,0,0,0 --json");
  ASSERT_EQ(ik.exit_code, 3) << ik.out;  // outside the 350..900 mm range
  const std::string path =
      cli_write_temp("no_limits.yaml",
                     "type: hexapod\nangles: krylov\n"
                     "base_joints: [[400,0,0],[200,346.41016151377545,0],[-200,346.41016151377545,0],"
                     "[-400,0,0],[-200,-346.41016151377545,0],[200,-346.41016151377545,0]]\n"
                     "platform_joints: [[173.20508075688772,100,0],[173.20508075688772,100,0],"
                     "[-173.20508075688772,100,0],[-173.20508075688772,100,0],[0,-200,0],[0,-200,0]]\n"
                     "home: [0, 0, 550, 0, 0, 0]\n");
  const CliRun flat = cli_run("ik --machine " + path + " --pose 0,0,0,0,0,0 --json");
  ASSERT_EQ(flat.exit_code, 0) << flat.out;
  std::string q;
  const auto flat_json = nlohmann::json::parse(flat.out);
  for (const auto& v : flat_json["actuators"]) append_number(q, v.get<double>());
  const CliRun fk = cli_run("fk --machine " + path + " --actuators " + q + " --guess 0,0,0,0,0,0");
  EXPECT_EQ(fk.exit_code, 4) << fk.out;
  EXPECT_NE(fk.out.find("singular"), std::string::npos) << fk.out;
}

TEST(Cli, JacobianGivesErrorAmplificationAndInverse) {
  const CliRun r = cli_run("jacobian --machine " + example(kCh5) + " --pose 0,0,700,0,0,0 --json");
  ASSERT_EQ(r.exit_code, 0) << r.out;
  const auto j = nlohmann::json::parse(r.out);
  EXPECT_NEAR(j["error_amplification"].get<double>(), 4.76, 0.005);  // Smirnov 2019, §5.2.2
  // J · J⁻¹ = I
  for (int row = 0; row < 6; ++row) {
    for (int col = 0; col < 6; ++col) {
      double sum = 0;
      for (int k = 0; k < 6; ++k)
        sum += j["jacobian"][row][k].get<double>() * j["inverse"][k][col].get<double>();
      EXPECT_NEAR(sum, row == col ? 1.0 : 0.0, 1e-9);
    }
  }
  const CliRun singular = cli_run("jacobian --machine " + example(kCh5) + " --pose 0,0,150,0,0,0");
  EXPECT_EQ(singular.exit_code, 4) << singular.out;
}

TEST(Cli, FkThatCannotConvergeSaysSo) {
  const CliRun r = cli_run("fk --machine " + example(kCh5) + " --actuators 360,890,360,890,360,890");
  EXPECT_TRUE(r.exit_code == 3 || r.exit_code == 4) << r.out;
  EXPECT_NE(r.out.find("pkm fk: error:"), std::string::npos) << r.out;
}

TEST(Cli, CheckReportsMobilityAndRange) {
  const CliRun r = cli_run("check " + example(kCh5) + " --json");
  ASSERT_EQ(r.exit_code, 0) << r.out;
  const auto j = nlohmann::json::parse(r.out);
  EXPECT_EQ(j["mobility"], 6);
  EXPECT_EQ(j["structure"], "6-UPS");
  EXPECT_EQ(j["sample"]["out_of_range"], 0);
  EXPECT_GT(j["sample"]["error_amplification_max"].get<double>(), 4.0);
}

TEST(Cli, BenchKinematicsReportsEveryFigure) {
  const CliRun r = cli_run("bench kinematics --machine " + example(kCh5) +
                           " --ik-poses 2000 --path-poses 500 --cold-poses 500 --json");
  ASSERT_EQ(r.exit_code, 0) << r.out;
  const auto j = nlohmann::json::parse(r.out);
  for (const char* key : {"ik_ns_per_pose", "fk_us_per_solve_warm", "fk_iterations_warm",
                          "fk_us_per_solve_cold", "fk_converged_cold"}) {
    ASSERT_TRUE(j.contains(key)) << key;
    EXPECT_GT(j[key].get<double>(), 0.0) << key;
  }
  EXPECT_EQ(j["fk_converged_warm"].get<double>(), 1.0);
  EXPECT_GE(j["fk_converged_cold"].get<double>(), 0.999);
}

TEST(Cli, DemoRunsOnEveryShippedMachine) {
  for (const char* file : {"hexapod_ch5.yaml", "planar2.yaml", "planar3.yaml", "tripod.yaml", "tricept.yaml",
                           "hexaglide.yaml", "triglide.yaml", "rotopod.yaml", "hexapod_refined.yaml"}) {
    const CliRun r = cli_run(std::string("demo --machine ") + example(file));
    EXPECT_EQ(r.exit_code, 0) << file << "\n" << r.out;
  }
}

}  // namespace
