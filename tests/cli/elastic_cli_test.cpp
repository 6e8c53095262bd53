// pkm modes (natural frequencies and mode shapes at a pose) and pkm plan --dynamics --elastic (response.csv
// and the elastic figures in the summary), with the inputs they refuse: a machine without stiffness, a pose
// beyond the drives' range, --elastic without --dynamics.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>

#include "cli/cli_support.hpp"

namespace pkm {
namespace {

namespace fs = std::filesystem;

std::string elastic_cli_machine(const std::string& file) {
  return test::source_path("examples/machines/" + file);
}

std::string fresh_elastic_dir(const std::string& name) {
  const fs::path dir = fs::temp_directory_path() / ("pkm_elastic_cli_" + name);
  fs::remove_all(dir);
  return dir.string();
}

/// The ch5 hexapod with its masses but without the struts' stiffness and friction (rigid struts).
std::string elastic_cli_rigid_struts_machine() {
  std::ifstream in(elastic_cli_machine("hexapod_ch5.yaml"));
  std::stringstream text;
  text << in.rdbuf();
  std::string machine = text.str();
  for (const std::string key :
       {"    stiffness_N_mm: 200000\n", "    damping: {model: quadratic, coefficient: 0.4}\n"}) {
    EXPECT_NE(machine.find(key), std::string::npos) << key;
    if (machine.find(key) != std::string::npos) machine.erase(machine.find(key), key.size());
  }
  return test::write_temp_file("elastic_rigid_struts.yaml", machine);
}

TEST(ElasticCli, ModesPrintsTheFrequenciesAndShapesAsJson) {
  const auto run = test::run_pkm(
      "modes --machine " + elastic_cli_machine("hexapod_ch5.yaml") + " --pose 0,0,700,0,0,0 --json", false);
  ASSERT_EQ(run.exit_code, 0) << run.out;
  const auto out = nlohmann::json::parse(run.out);
  const auto& f = out["frequencies_Hz"];
  ASSERT_EQ(f.size(), 6u);
  for (std::size_t i = 1; i < f.size(); ++i) EXPECT_GE(f[i].get<double>(), f[i - 1].get<double>());
  // The symmetric machine sways sideways first, in x and y alike (about 120 Hz with the file's numbers).
  EXPECT_GT(f[0].get<double>(), 50.0);
  EXPECT_LT(f[0].get<double>(), 500.0);
  EXPECT_NEAR(f[0].get<double>(), f[1].get<double>(), 1e-6 * f[0].get<double>());
  ASSERT_EQ(out["modes"].size(), 6u);
  EXPECT_EQ(out["modes"][0]["shape"].size(), 6u);
  EXPECT_TRUE(out["modes"][0]["shape"].contains("rz_rad"));
  // It sags under its weight: down, by microns.
  const double sag_z = out["static_deflection_mm"][2].get<double>();
  EXPECT_LT(sag_z, 0.0);
  EXPECT_GT(sag_z, -0.01);
}

TEST(ElasticCli, ModesOfThePlanarBipedTakeXAndY) {
  const auto run =
      test::run_pkm("modes --machine " + elastic_cli_machine("planar2.yaml") + " --pose 120,250");
  ASSERT_EQ(run.exit_code, 0) << run.out;
  EXPECT_NE(run.out.find("frequency Hz"), std::string::npos) << run.out;
  EXPECT_NE(run.out.find("x_mm y_mm"), std::string::npos) << run.out;
  EXPECT_NE(run.out.find("\n     2  "), std::string::npos) << run.out;  // two modes
  EXPECT_EQ(run.out.find("\n     3  "), std::string::npos) << run.out;
}

TEST(ElasticCli, ModesRefuseAMachineWithoutStiffnessAndAPoseOutOfReach) {
  const auto none =
      test::run_pkm("modes --machine " + elastic_cli_machine("hexaglide.yaml") + " --pose 0,0,700,0,0,0");
  EXPECT_EQ(none.exit_code, 2) << none.out;
  EXPECT_NE(none.out.find("hexaglide.yaml: the machine file has no dynamics: section"), std::string::npos)
      << none.out;
  const std::string rigid = elastic_cli_rigid_struts_machine();
  const auto missing = test::run_pkm("modes --machine " + rigid + " --pose 0,0,700,0,0,0");
  EXPECT_EQ(missing.exit_code, 2) << missing.out;
  EXPECT_NE(missing.out.find(rigid + ":"), std::string::npos) << missing.out;
  EXPECT_NE(missing.out.find("dynamics.struts.stiffness_N_mm: not given for strut 1"), std::string::npos)
      << missing.out;
  const auto far =
      test::run_pkm("modes --machine " + elastic_cli_machine("hexapod_ch5.yaml") + " --pose 0,0,5000,0,0,0");
  EXPECT_EQ(far.exit_code, 3) << far.out;
  EXPECT_NE(far.out.find("--pose 0,0,5000,0,0,0: "), std::string::npos) << far.out;
  EXPECT_NE(far.out.find("above actuator_max 900 mm"), std::string::npos) << far.out;
  // One line each.
  for (const auto* r : {&none, &missing, &far})
    EXPECT_EQ(std::count(r->out.begin(), r->out.end(), '\n'), 1) << r->out;
}

TEST(ElasticCli, PlanWritesTheResponseAndTheElasticSummary) {
  const std::string out = fresh_elastic_dir("circle");
  const auto run = test::run_pkm("plan " + test::source_path("examples/programs/circle.ngc") + " --machine " +
                                     elastic_cli_machine("hexapod_ch5.yaml") +
                                     " --dynamics --elastic --tables csv --out " + out + " --json",
                                 false);
  ASSERT_EQ(run.exit_code, 0) << run.out;
  const auto summary = nlohmann::json::parse(run.out);
  const auto& d = summary["dynamics"];
  const double sag_mm = d["static_deflection_at_start_mm"].get<double>();
  const double worst_mm = d["max_dynamic_tool_error_mm"].get<double>();
  EXPECT_GT(d["lowest_natural_frequency_Hz"].get<double>(), 50.0);
  EXPECT_GT(sag_mm, 1e-4);
  EXPECT_GE(worst_mm, sag_mm * (1 - 1e-6));  // the sag is there from the start
  EXPECT_LT(worst_mm, 0.05);
  EXPECT_GT(d["max_dynamic_tool_error_line"].get<int>(), 0);
  // One row per tick; the first is the static sag; the largest error is the summary's, at its line.
  std::ifstream response(fs::path(out) / "response.csv");
  std::string header;
  std::getline(response, header);
  EXPECT_EQ(header, "time_s,line,dx_mm,dy_mm,dz_mm,rotation_deg,tool_error_mm");
  long rows = 0;
  double largest = 0.0, first = -1.0;
  int largest_line = 0;
  for (std::string line; std::getline(response, line); ++rows) {
    std::stringstream fields(line);
    std::vector<double> v;
    for (std::string field; std::getline(fields, field, ',');) v.push_back(std::stod(field));
    ASSERT_EQ(v.size(), 7u) << line;
    EXPECT_NEAR(v[6], std::sqrt(v[2] * v[2] + v[3] * v[3] + v[4] * v[4]), 1e-3 * v[6] + 1e-12);
    if (first < 0) first = v[6];
    if (v[6] > largest) largest = v[6], largest_line = static_cast<int>(v[1]);
  }
  EXPECT_EQ(rows, summary["ticks"].get<long>());
  EXPECT_NEAR(first, sag_mm, 1e-3 * sag_mm);
  EXPECT_NEAR(largest, worst_mm, 1e-3 * worst_mm);
  EXPECT_EQ(largest_line, d["max_dynamic_tool_error_line"].get<int>());
}

TEST(ElasticCli, PlanRefusesElasticWithoutDynamicsOrStiffnessAndWritesNothing) {
  const std::string out = fresh_elastic_dir("refused");
  const auto alone =
      test::run_pkm("plan " + test::source_path("examples/programs/circle.ngc") + " --machine " +
                    elastic_cli_machine("hexapod_ch5.yaml") + " --elastic --out " + out);
  EXPECT_NE(alone.exit_code, 0);
  EXPECT_NE(alone.out.find("--elastic requires --dynamics"), std::string::npos) << alone.out;
  const std::string machine = elastic_cli_rigid_struts_machine();
  const auto rigid =
      test::run_pkm("plan " + test::source_path("examples/programs/circle.ngc") + " --machine " + machine +
                    " --dynamics --elastic --tables csv --out " + out);
  EXPECT_EQ(rigid.exit_code, 2) << rigid.out;
  EXPECT_NE(rigid.out.find(machine + ":"), std::string::npos) << rigid.out;
  EXPECT_NE(rigid.out.find("dynamics.struts.stiffness_N_mm: not given"), std::string::npos) << rigid.out;
  EXPECT_FALSE(fs::exists(fs::path(out) / "response.csv"));
  EXPECT_FALSE(fs::exists(fs::path(out) / "summary.json"));
}

}  // namespace
}  // namespace pkm
