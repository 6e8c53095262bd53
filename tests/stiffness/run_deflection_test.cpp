// The tool's deflection along a run (src/stiffness/run_deflection.hpp): on a straight feed at constant speed
// the deflection of a tick is the compliance there times the cutting load with the direction of travel; it
// is linear in the load; rapids carry no cut; and pkm plan --stiffness writes it and refuses what it cannot
// do.
#include "stiffness/run_deflection.hpp"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <vector>

#include "cli/cli_support.hpp"
#include "test_support.hpp"

namespace pkm {
namespace {

std::vector<stiffness::DeflectionTick> deflection_along_x(const Machine& machine,
                                                          const statics::LoadModel& load, bool cutting) {
  std::vector<stiffness::DeflectionTick> ticks;
  auto run = stiffness::RunDeflection::make(machine, load, [&ticks](const stiffness::DeflectionTick& t) {
    ticks.push_back(t);
    return ok_status();
  });
  EXPECT_TRUE(run.ok()) << run.error().message;
  if (!run) return ticks;
  for (int k = 0; k <= 100; ++k) {  // 50 mm/s along +x from x = −2.5 mm, 1 ms ticks
    Pose pose = machine.mechanism->home();
    pose.position_mm.x() += -2.5 + 0.05 * k;
    EXPECT_TRUE(run->add(0.001 * k, 7, pose, cutting).ok());
  }
  EXPECT_TRUE(run->finish().ok());
  return ticks;
}

TEST(RunDeflection, ATickDeflectsByTheComplianceTimesTheCutAlongTheTravel) {
  const Machine machine = test::machine_from_example("examples/machines/hexapod_ch5.yaml");
  auto load = statics::parse_load_spec("tangential=500,axial=200");
  ASSERT_TRUE(load.ok());
  const auto ticks = deflection_along_x(machine, *load, true);
  ASSERT_EQ(ticks.size(), 101u);
  // Tick 50: at home, travelling +x: the cut pushes back along −x and the spindle along the tool axis (+z).
  Pose at = machine.mechanism->home();
  at.position_mm.x() += -2.5 + 0.05 * 50;
  auto parameters = stiffness::strut_stiffness_of(machine);
  ASSERT_TRUE(parameters.ok());
  auto compliance = stiffness::strut_compliance(*machine.mechanism, *parameters, at);
  ASSERT_TRUE(compliance.ok());
  Eigen::Matrix<double, 6, 1> w;
  w << -500, 0, 200, 0, 0, 0;
  const Eigen::Matrix<double, 6, 1> expected = compliance->compliance * w;
  EXPECT_LE((ticks[50].deflection_mm - expected.head<3>()).norm(), 1e-12);
  EXPECT_NEAR(ticks[50].normal_mm, expected.z(), 1e-12);  // the tool axis is +z at home
  EXPECT_NEAR(ticks[50].rotation_rad, expected.tail<3>().norm(), 1e-15);
  EXPECT_LT(ticks[50].deflection_mm.x(), -1e-3);  // several µm against the feed
  EXPECT_EQ(ticks[50].line, 7);
}

TEST(RunDeflection, IsLinearInTheLoadAndRapidsCarryNoCut) {
  const Machine machine = test::machine_from_example("examples/machines/hexapod_ch5.yaml");
  auto single = statics::parse_load_spec("tangential=300,normal=100");
  auto twice = statics::parse_load_spec("tangential=600,normal=200");
  ASSERT_TRUE(single.ok() && twice.ok());
  const auto one = deflection_along_x(machine, *single, true);
  const auto two = deflection_along_x(machine, *twice, true);
  ASSERT_EQ(one.size(), two.size());
  for (std::size_t k = 0; k < one.size(); ++k)
    EXPECT_LE((two[k].deflection_mm - 2 * one[k].deflection_mm).norm(),
              1e-15 + 1e-12 * one[k].deflection_mm.norm());
  const auto rapid = deflection_along_x(machine, *single, false);
  for (const auto& t : rapid) EXPECT_EQ(t.deflection_mm.norm(), 0.0);
}

std::string deflection_dir(const std::string& name) {
  const auto dir = std::filesystem::temp_directory_path() / ("pkm_deflection_" + name);
  std::filesystem::remove_all(dir);
  return dir.string();
}

TEST(RunDeflection, PlanWritesTheDeflectionAndItsSummary) {
  const std::string out = deflection_dir("circle");
  const std::string args = "plan " + test::source_path("examples/programs/circle.ngc") + " --machine " +
                           test::source_path("examples/machines/hexapod_ch5.yaml") +
                           " --stiffness --json --tables csv --out ";
  const auto run = test::run_pkm(args + out + " --load tangential=500", false);
  ASSERT_EQ(run.exit_code, 0) << run.out;
  const auto summary = nlohmann::json::parse(run.out);
  const auto& s = summary["stiffness"];
  std::ifstream csv(std::filesystem::path(out) / "deflection.csv");
  std::string header;
  std::getline(csv, header);
  EXPECT_EQ(header, "time_s,line,dx_mm,dy_mm,dz_mm,normal_mm,rotation_rad");
  long rows = 0;
  double largest_normal = 0.0;
  for (std::string line; std::getline(csv, line); ++rows) {
    std::stringstream fields(line);
    std::vector<double> v;
    for (std::string field; std::getline(fields, field, ',');) v.push_back(std::stod(field));
    ASSERT_EQ(v.size(), 7u);
    largest_normal = std::max(largest_normal, std::abs(v[5]));
  }
  EXPECT_EQ(rows, summary["ticks"].get<long>());
  EXPECT_NEAR(largest_normal, s["max_normal_deflection_mm"].get<double>(), 1e-4 * largest_normal);
  EXPECT_GT(s["max_deflection_mm"].get<double>(), 1e-3);  // 500 N on 92 N/µm sideways: ~5 µm
  EXPECT_GT(s["max_normal_deflection_line"].get<int>(), 0);
  // Twice the load, twice the deflection.
  const auto doubled = test::run_pkm(args + deflection_dir("circle2") + " --load tangential=1000", false);
  ASSERT_EQ(doubled.exit_code, 0) << doubled.out;
  const auto doubled_summary = nlohmann::json::parse(doubled.out);
  const auto& d = doubled_summary["stiffness"];
  EXPECT_NEAR(d["max_deflection_mm"].get<double>(), 2 * s["max_deflection_mm"].get<double>(),
              1e-9 * s["max_deflection_mm"].get<double>());
}

TEST(RunDeflection, PlanRefusesStiffnessWithoutALoadOrWithoutStrutStiffness) {
  const std::string out = deflection_dir("refused");
  const auto no_load =
      test::run_pkm("plan " + test::source_path("examples/programs/circle.ngc") + " --machine " +
                    test::source_path("examples/machines/hexapod_ch5.yaml") + " --stiffness --out " + out);
  EXPECT_EQ(no_load.exit_code, 2) << no_load.out;
  EXPECT_NE(no_load.out.find("--stiffness needs --load"), std::string::npos) << no_load.out;
  const auto bare =
      test::run_pkm("plan " + test::source_path("examples/programs/circle.ngc") + " --machine " +
                    test::source_path("examples/machines/hexapod_genhexkins.yaml") +
                    " --stiffness --load tangential=100 --out " + out);
  EXPECT_EQ(bare.exit_code, 2) << bare.out;
  EXPECT_NE(bare.out.find("stiffness.struts: not given"), std::string::npos) << bare.out;
  EXPECT_FALSE(std::filesystem::exists(out));
}

}  // namespace
}  // namespace pkm
