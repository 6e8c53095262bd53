// pkm compliance: the tool's compliance and principal stiffness at a pose (JSON and text), and the inputs
// it refuses: a machine without strut stiffness, a pose beyond the drives' range, a singular pose. With
// --bode: the Bode CSV (a row per frequency, its lowest frequency the static compliance) and the natural
// frequencies of `pkm modes`; a machine without a dynamics: section and bad frequencies or damping refused
// without a file. With --map: the stiffness map's CSV, its centre the single pose's weakest stiffness.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <vector>

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

/// A fresh path in the temporary directory (nothing there yet).
std::string compliance_cli_out(const std::string& name) {
  const auto path = std::filesystem::temp_directory_path() / ("pkm_compliance_cli_" + name);
  std::filesystem::remove(path);
  return path.string();
}

/// The CSV's header and its rows split at commas (an empty last cell kept).
std::pair<std::string, std::vector<std::vector<std::string>>> compliance_cli_csv(const std::string& path) {
  test::CsvRows csv = test::read_csv_rows(path);
  return {csv.header, std::move(csv.rows)};
}

/// The ch5 machine file with its dynamics: section replaced by a stiffness: section of the same springs.
std::string compliance_cli_ch5_without_dynamics() {
  std::ifstream in(compliance_cli_machine("hexapod_ch5.yaml"));
  std::stringstream text;
  text << in.rdbuf();
  std::string yaml = text.str();
  const auto from = yaml.find("dynamics:\n"), to = yaml.find("# Step drives");
  EXPECT_NE(from, std::string::npos);
  EXPECT_NE(to, std::string::npos);
  yaml = yaml.substr(0, from) + "stiffness:\n  struts: {stiffness_N_mm: 200000}\n" + yaml.substr(to);
  return test::write_temp_file("ch5_no_dynamics.yaml", yaml);
}

TEST(ComplianceCli, WritesTheBodeDataAndGivesTheNaturalFrequenciesOfModes) {
  const std::string out = compliance_cli_out("bode.csv");
  const std::string machine = compliance_cli_machine("hexapod_ch5.yaml");
  const auto run =
      test::run_pkm("compliance --machine " + machine + " --pose 0,0,700,0,0,0 --bode " + out +
                        " --f-min-hz 0.1 --f-max-hz 10000 --points 41 --damping-ratio 0.05 --json",
                    false);
  ASSERT_EQ(run.exit_code, 0) << run.out;
  const auto j = nlohmann::json::parse(run.out);
  ASSERT_TRUE(j.contains("dynamic")) << run.out;
  const auto& dynamic = j["dynamic"];
  EXPECT_EQ(dynamic["damping_model"], "modal");
  EXPECT_NE(dynamic["damping"].get<std::string>().find("0.05"), std::string::npos);
  // The natural frequencies are pkm modes' at the pose.
  const auto modes = test::run_pkm("modes --machine " + machine + " --pose 0,0,700,0,0,0 --json", false);
  ASSERT_EQ(modes.exit_code, 0) << modes.out;
  const auto m = nlohmann::json::parse(modes.out);
  ASSERT_EQ(dynamic["natural_frequencies_Hz"].size(), m["frequencies_Hz"].size());
  for (std::size_t i = 0; i < m["frequencies_Hz"].size(); ++i) {
    const double f = m["frequencies_Hz"][i].get<double>();
    EXPECT_NEAR(dynamic["natural_frequencies_Hz"][i].get<double>(), f, 1e-9 * f);
  }
  // One row per frequency, log-spaced from 0.1 to 10 kHz; at 0.1 Hz the xx and zz magnitudes are the static
  // compliance (the gravity preload moves them by ~10⁻⁵).
  const auto [header, rows] = compliance_cli_csv(out);
  EXPECT_EQ(header,
            "frequency_Hz,xx_magnitude_um_N,xx_phase_deg,yy_magnitude_um_N,yy_phase_deg,zz_magnitude_um_N,"
            "zz_phase_deg,tool_axis_magnitude_um_N,tool_axis_phase_deg");
  ASSERT_EQ(rows.size(), 41u);
  EXPECT_NEAR(std::stod(rows.front()[0]), 0.1, 1e-12);
  EXPECT_NEAR(std::stod(rows.back()[0]), 10000.0, 1e-6);
  const auto& c = j["compliance"];
  EXPECT_NEAR(std::stod(rows.front()[1]), 1e3 * c[0][0].get<double>(), 1e-3 * 1e3 * c[0][0].get<double>());
  EXPECT_NEAR(std::stod(rows.front()[5]), 1e3 * c[2][2].get<double>(), 1e-3 * 1e3 * c[2][2].get<double>());
  // The sideways peak is at the lowest mode (x and y sway), and well above the static value.
  const auto& xx = dynamic["entries"][0];
  EXPECT_EQ(xx["name"], "xx");
  EXPECT_NEAR(xx["peak_frequency_Hz"].get<double>(), m["frequencies_Hz"][0].get<double>(),
              0.15 * m["frequencies_Hz"][0].get<double>());  // the sweep's nearest point
  EXPECT_GT(xx["peak_magnitude_um_N"].get<double>(), 3 * std::stod(rows.front()[1]));
  // Text: the frequencies and the file named.
  const std::string text_out = compliance_cli_out("bode_text.csv");
  const auto text = test::run_pkm("compliance --machine " + machine + " --pose 0,0,700,0,0,0 --bode " +
                                  text_out + " --rayleigh 20,1e-5");
  ASSERT_EQ(text.exit_code, 0) << text.out;
  EXPECT_NE(text.out.find("natural frequencies (Hz)"), std::string::npos) << text.out;
  EXPECT_NE(text.out.find("Rayleigh"), std::string::npos) << text.out;
  EXPECT_NE(text.out.find(text_out), std::string::npos) << text.out;
  EXPECT_EQ(compliance_cli_csv(text_out).second.size(), 200u);  // the default points
}

TEST(ComplianceCli, RefusesBodeWithoutDynamicsAndBadFrequenciesOrDampingWritingNothing) {
  // A machine with struts' stiffness but no dynamics: section: the static compliance exists, the Bode
  // data does not; the message names the file and the key, and no file appears.
  const std::string out = compliance_cli_out("refused_bode.csv");
  const std::string machine = compliance_cli_ch5_without_dynamics();
  const auto bare = test::run_pkm("compliance --machine " + machine + " --pose 0,0,700,0,0,0 --bode " + out);
  EXPECT_EQ(bare.exit_code, 2) << bare.out;
  EXPECT_NE(bare.out.find("ch5_no_dynamics.yaml"), std::string::npos) << bare.out;
  EXPECT_NE(bare.out.find("dynamics:"), std::string::npos) << bare.out;
  EXPECT_FALSE(std::filesystem::exists(out));
  EXPECT_EQ(test::run_pkm("compliance --machine " + machine + " --pose 0,0,700,0,0,0").exit_code, 0);
  const std::string ch5 = compliance_cli_machine("hexapod_ch5.yaml");
  for (const char* flags :
       {"--f-min-hz 0", "--f-min-hz -5", "--f-min-hz nan", "--f-max-hz 0", "--f-min-hz 100 --f-max-hz 50",
        "--points 1", "--points 2.5", "--damping-ratio -0.1", "--rayleigh 1,2,3", "--rayleigh -1,0",
        "--rayleigh 1,1e-5 --damping-ratio 0.1"}) {
    const auto run =
        test::run_pkm("compliance --machine " + ch5 + " --pose 0,0,700,0,0,0 --bode " + out + " " + flags);
    EXPECT_EQ(run.exit_code, 2) << flags << "\n" << run.out;
    EXPECT_FALSE(std::filesystem::exists(out)) << flags;
  }
  // The Bode options need --bode, and --bode needs a pose.
  EXPECT_NE(test::run_pkm("compliance --machine " + ch5 + " --pose 0,0,700,0,0,0 --points 20").exit_code, 0);
  EXPECT_NE(test::run_pkm("compliance --machine " + ch5 + " --bode " + out).exit_code, 0);
  EXPECT_FALSE(std::filesystem::exists(out));
}

TEST(ComplianceCli, TheStiffnessMapHasARowPerPointAndItsCentreIsThePosesWeakestStiffness) {
  const std::string out = compliance_cli_out("map.csv");
  const std::string ch5 = compliance_cli_machine("hexapod_ch5.yaml");
  const auto run = test::run_pkm(
      "compliance --machine " + ch5 +
          " --map --centre 10,-20,690,0,0,0 --plane xz --range-mm 300 --step-mm 100 --out " + out + " --json",
      false);
  ASSERT_EQ(run.exit_code, 0) << run.out;
  const auto summary = nlohmann::json::parse(run.out);
  const auto [header, rows] = compliance_cli_csv(out);
  EXPECT_EQ(header,
            "x_mm,y_mm,z_mm,psi_deg,theta_deg,gamma_deg,lowest_stiffness_N_um,direction_x,direction_y,"
            "direction_z,status");
  ASSERT_EQ(rows.size(), 49u);
  EXPECT_EQ(summary["points"], 49);
  int ok = 0;
  for (const auto& row : rows) {
    ASSERT_EQ(row.size(), 11u);
    if (row[10] == "ok") {
      ++ok;
      EXPECT_GT(std::stod(row[6]), 0.0);
    } else {
      EXPECT_TRUE(row[6].empty());
    }
  }
  EXPECT_EQ(summary["with_stiffness"], ok);
  EXPECT_GT(summary["out_of_range"].get<int>(), 0);  // ±300 mm in z leaves the drives' range
  // The centre (index 24) is `pkm compliance --pose` there.
  const auto& centre = rows[24];
  EXPECT_EQ(centre[0], "10.000000");
  const auto single = test::run_pkm("compliance --machine " + ch5 + " --pose 10,-20,690,0,0,0 --json", false);
  ASSERT_EQ(single.exit_code, 0);
  const double weakest =
      nlohmann::json::parse(single.out)["translational"][0]["stiffness_N_um"].get<double>();
  EXPECT_NEAR(std::stod(centre[6]), weakest, 1e-8 * weakest);
  EXPECT_NEAR(
      summary["min_stiffness_N_um"].get<double>(),
      [&map_rows = rows] {  // named capture: clang 14 cannot capture a structured binding
        double lowest = 1e300;
        for (const auto& row : map_rows)
          if (row[10] == "ok") lowest = std::min(lowest, std::stod(row[6]));
        return lowest;
      }(),
      1e-6 * weakest);
  // Text, and the refusals: --map without --out, with --pose, a bad step, a machine without stiffness.
  const auto text = test::run_pkm("compliance --machine " + ch5 + " --map --out " + out);
  EXPECT_EQ(text.exit_code, 0) << text.out;
  EXPECT_NE(text.out.find("weakest"), std::string::npos) << text.out;
  const std::string refused = compliance_cli_out("refused_map.csv");
  EXPECT_NE(test::run_pkm("compliance --machine " + ch5 + " --map").exit_code, 0);
  EXPECT_NE(
      test::run_pkm("compliance --machine " + ch5 + " --map --pose 0,0,700,0,0,0 --out " + refused).exit_code,
      0);
  EXPECT_EQ(test::run_pkm("compliance --machine " + ch5 + " --map --step-mm 0 --out " + refused).exit_code,
            2);
  const auto huge = test::run_pkm("compliance --machine " + ch5 + " --map --step-mm 0.01 --out " + refused);
  EXPECT_EQ(huge.exit_code, 2) << huge.out;
  EXPECT_NE(huge.out.find("--step-mm"), std::string::npos) << huge.out;
  const auto bare =
      test::run_pkm("compliance --machine " + compliance_cli_machine("hexapod_genhexkins.yaml") +
                    " --map --out " + refused);
  EXPECT_EQ(bare.exit_code, 2) << bare.out;
  EXPECT_NE(bare.out.find("stiffness.struts: not given"), std::string::npos) << bare.out;
  EXPECT_FALSE(std::filesystem::exists(refused));
}

}  // namespace
}  // namespace pkm
