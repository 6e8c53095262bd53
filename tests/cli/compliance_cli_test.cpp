// pkm compliance: the tool's compliance and principal stiffness at a pose (JSON and text), and the inputs
// it refuses: a machine without strut stiffness, a pose beyond the drives' range, a singular pose.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>

#include "cli/cli_support.hpp"

namespace pkm {
namespace {

std::string compliance_cli_machine(const std::string& file) {
  return test::source_path("examples/machines/" + file);
}

TEST(ComplianceCli, PrintsTheMatrixAndThePrincipalStiffnessAsJson) {
  const auto run = test::run_pkm(
      "compliance --machine " + compliance_cli_machine("hexapod_ch5.yaml") + " --pose 0,0,700,0,0,0 --json",
      false);
  ASSERT_EQ(run.exit_code, 0) << run.out;
  const auto j = nlohmann::json::parse(run.out);
  EXPECT_EQ(j["dof"], 6);
  const auto& t = j["translational"];
  ASSERT_EQ(t.size(), 3u);
  // Three-fold symmetric about z: equal in x and y, the weakest; stiffest along z, the struts' main
  // direction.
  const double weakest = t[0]["stiffness_N_um"].get<double>();
  EXPECT_NEAR(t[1]["stiffness_N_um"].get<double>(), weakest, 1e-9 * weakest);
  EXPECT_GT(t[2]["stiffness_N_um"].get<double>(), 5 * weakest);
  EXPECT_NEAR(std::abs(t[2]["direction"][2].get<double>()), 1.0, 1e-9);
  // The matrix is symmetric and its x entry is the weakest stiffness's inverse (mm/N ↔ N/µm).
  const auto& c = j["compliance"];
  for (int r = 0; r < 6; ++r)
    for (int k = 0; k < 6; ++k) EXPECT_NEAR(c[r][k].get<double>(), c[k][r].get<double>(), 1e-15);
  EXPECT_NEAR(c[0][0].get<double>(), 1e-3 / weakest, 1e-9 / weakest);
  EXPECT_EQ(j["strut_stiffness_N_mm"].size(), 6u);
}

TEST(ComplianceCli, TheTripodHasThreeAllowedMotions) {
  const auto run = test::run_pkm(
      "compliance --machine " + compliance_cli_machine("tripod.yaml") + " --pose 0,0,800,0,0,0 --json",
      false);
  ASSERT_EQ(run.exit_code, 0) << run.out;
  const auto j = nlohmann::json::parse(run.out);
  EXPECT_EQ(j["dof"], 3);
}

TEST(ComplianceCli, RefusesAMachineWithoutStiffnessAPoseOutOfRangeAndASingularPose) {
  const auto bare = test::run_pkm(
      "compliance --machine " + compliance_cli_machine("hexapod_genhexkins.yaml") + " --pose 0,0,508,0,0,0");
  EXPECT_EQ(bare.exit_code, 2) << bare.out;
  EXPECT_NE(bare.out.find("stiffness.struts: not given"), std::string::npos) << bare.out;
  const auto far = test::run_pkm("compliance --machine " + compliance_cli_machine("hexapod_ch5.yaml") +
                                 " --pose 0,0,5000,0,0,0");
  EXPECT_NE(far.exit_code, 0);
  EXPECT_NE(far.out.find("--pose 0,0,5000,0,0,0"), std::string::npos) << far.out;
  // Turned 90° about z (abc angles; the drives' range widened to reach it): Fichter's singularity.
  std::ifstream in(compliance_cli_machine("hexapod_ch5.yaml"));
  std::stringstream text;
  text << in.rdbuf();
  std::string machine = text.str();
  for (const auto& [from, to] : {std::pair<std::string, std::string>{"angles: krylov", "angles: abc"},
                                 {"actuator_max: 900", "actuator_max: 1900"}}) {
    ASSERT_NE(machine.find(from), std::string::npos) << from;
    machine.replace(machine.find(from), from.size(), to);
  }
  const auto singular =
      test::run_pkm("compliance --machine " + test::write_temp_file("ch5_abc_wide.yaml", machine) +
                    " --pose 0,0,700,0,0,90");
  EXPECT_EQ(singular.exit_code, 4) << singular.out;
  EXPECT_NE(singular.out.find("unbounded compliance"), std::string::npos) << singular.out;
}

}  // namespace
}  // namespace pkm
