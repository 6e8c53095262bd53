// The report of a `pkm plan --dynamics [--elastic]` run (docs/report.md, report/dynamics_trace.hpp): force,
// power, energy and dynamic-error plots and per-frame drive forces when the summary has a dynamics block and
// forces.csv is there, none otherwise; decimation keeps the peaks; the files must be the run's own.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <numbers>
#include <string>

#include "cli/cli_support.hpp"
#include "report/report_data.hpp"

namespace pkm {
namespace {

namespace fs = std::filesystem;

constexpr int kDynReportDrives = 6;
constexpr double kDynReportRateHz = 1000.0;
constexpr long kDynReportSpikeTick = 4321;  // drive 3 pulls hard for one tick
constexpr long kDynReportErrorTick = 1234;  // the elastic machine's error jumps for one tick
constexpr double kDynReportSpikeN = -750.0;
constexpr double kDynReportErrorSpikeMm = 0.02;

struct DynReportRunSpec {
  long ticks = 20000;
  bool summary_has_dynamics = true;
  bool elastic = true;
  bool write_forces = true;
  long forces_rows_missing = 0;  ///< rows left off the end of forces.csv
};

struct DynReportRun {
  std::string dir;
  double energy_no_recovery_J = 0, energy_braking_free_J = 0, energy_recovery_J = 0;
};

double dyn_report_static_N(int j) {
  return 200.0 + 10.0 * j;
}

double dyn_report_total_N(int j, long k) {
  if (j == 2 && k == kDynReportSpikeTick) return kDynReportSpikeN;
  return dyn_report_static_N(j) +
         20.0 * std::sin(2.0 * std::numbers::pi * static_cast<double>(k) / 2000.0 + j);
}

double dyn_report_power_W(int j, long k) {
  return (j + 1) * 0.5 * std::sin(2.0 * std::numbers::pi * static_cast<double>(k) / 3000.0 + 0.7 * j);
}

/// A synthetic `pkm plan --dynamics [--elastic]` run directory on the ch5 hexapod (at home throughout), with
/// the energies the page should accumulate.
DynReportRun dyn_report_write_run(const std::string& name, const DynReportRunSpec& spec) {
  DynReportRun run;
  run.dir = (fs::temp_directory_path() / ("pkm_dynamics_report_" + name)).string();
  fs::remove_all(run.dir);
  fs::create_directories(run.dir);
  std::ofstream path(run.dir + "/path.csv"), actuators(run.dir + "/actuators.csv");
  path
      << "time_s,line,s,x_program_mm,y_program_mm,z_program_mm,a_abc_deg,b_abc_deg,c_abc_deg,path_speed_mm_s,"
         "feed_mm_s,path_error_mm\n";
  actuators << "time_s,q1,q2,q3,q4,q5,q6\n";
  std::ofstream forces, response;
  if (spec.write_forces) {
    forces.open(run.dir + "/forces.csv");
    forces << "time_s,line";
    for (int j = 1; j <= kDynReportDrives; ++j)
      forces << fmt::format(",P{0}_N,P{0}_static_N,P{0}_dynamic_N", j);
    for (int j = 1; j <= kDynReportDrives; ++j) forces << fmt::format(",power{}_W", j);
    forces << "\n";
  }
  if (spec.elastic) {
    response.open(run.dir + "/response.csv");
    response << "time_s,line,dx_mm,dy_mm,dz_mm,rotation_deg,tool_error_mm\n";
  }
  const double h = 1.0 / kDynReportRateHz;
  for (long k = 0; k < spec.ticks; ++k) {
    const double t = static_cast<double>(k) * h;
    const int line = 1 + static_cast<int>(k / 1000);
    path << fmt::format("{:.6f},{},{:.6f},0,0,0,0,0,0,10,10,0\n", t, line, 0.01 * static_cast<double>(k));
    actuators << fmt::format("{:.6f},600,600,600,600,600,600\n", t);
    if (spec.write_forces && k < spec.ticks - spec.forces_rows_missing) {
      forces << fmt::format("{:.6f},{}", t, line);
      for (int j = 0; j < kDynReportDrives; ++j) {
        const double total = dyn_report_total_N(j, k);
        forces << fmt::format(",{:.4f},{:.4f},{:.4f}", total, dyn_report_static_N(j),
                              total - dyn_report_static_N(j));
      }
      double sum_W = 0.0;
      for (int j = 0; j < kDynReportDrives; ++j) {
        const double p = dyn_report_power_W(j, k);
        forces << fmt::format(",{:.5f}", p);
        const double written = std::stod(fmt::format("{:.5f}", p));
        run.energy_no_recovery_J += std::abs(written) * h;
        run.energy_braking_free_J += std::max(0.0, written) * h;
        sum_W += written;
      }
      run.energy_recovery_J += std::max(0.0, sum_W) * h;
      forces << "\n";
    }
    if (spec.elastic) {
      const double error = k == kDynReportErrorTick ? kDynReportErrorSpikeMm : 0.001;
      response << fmt::format("{:.6f},{},{:.4e},0,0,0,{:.4e}\n", t, line, error, error);
    }
  }
  nlohmann::json drives = nlohmann::json::array();
  for (int j = 0; j < kDynReportDrives; ++j) {
    drives.push_back({{"peak_force_N", j == 2 ? 750.0 : dyn_report_static_N(j) + 20.0},
                      {"peak_force_line", j == 2 ? 5 : 2},
                      {"peak_force_time_s", j == 2 ? 4.321 : 0.5},
                      {"peak_static_N", dyn_report_static_N(j)},
                      {"peak_dynamic_N", 20.0},
                      {"peak_power_W", (j + 1) * 0.5}});
  }
  nlohmann::json summary = {{"machine", test::source_path("examples/machines/hexapod_ch5.yaml")},
                            {"program", ""},
                            {"duration_s", static_cast<double>(spec.ticks - 1) * h},
                            {"ticks", spec.ticks},
                            {"rate_hz", kDynReportRateHz}};
  if (spec.summary_has_dynamics) {
    summary["dynamics"] = {{"model", "rigid"},
                           {"drives", drives},
                           {"peak_total_power_W", 9.0},
                           {"peak_total_power_line", 7},
                           {"energy_no_recovery_J", run.energy_no_recovery_J},
                           {"energy_braking_free_J", run.energy_braking_free_J},
                           {"energy_recovery_J", run.energy_recovery_J}};
    if (spec.elastic) {
      summary["dynamics"]["lowest_natural_frequency_Hz"] = 120.0;
      summary["dynamics"]["static_deflection_at_start_mm"] = 0.001;
      summary["dynamics"]["max_dynamic_tool_error_mm"] = kDynReportErrorSpikeMm;
      summary["dynamics"]["max_dynamic_tool_error_line"] = 2;
      summary["dynamics"]["max_dynamic_tool_error_time_s"] = 1.234;
      summary["dynamics"]["max_dynamic_rotation_deg"] = 0.0;
    }
  }
  std::ofstream(run.dir + "/summary.json") << summary.dump(1);
  return run;
}

const nlohmann::json* dyn_report_chart(const nlohmann::json& data, const std::string& id) {
  for (const auto& c : data["charts"])
    if (c["id"] == id) return &c;
  return nullptr;
}

const nlohmann::json* dyn_report_series(const nlohmann::json& chart, const std::string& name) {
  for (const auto& s : chart["series"])
    if (s["name"] == name) return &s["values"];
  return nullptr;
}

double dyn_report_min(const nlohmann::json& values) {
  double low = INFINITY;
  for (const auto& v : values)
    if (v.is_number()) low = std::min(low, v.get<double>());
  return low;
}

double dyn_report_max(const nlohmann::json& values) {
  double high = -INFINITY;
  for (const auto& v : values)
    if (v.is_number()) high = std::max(high, v.get<double>());
  return high;
}

bool dyn_report_has_row(const nlohmann::json& data, const std::string& label_start) {
  for (const auto& row : data["table"])
    if (row["label"].get<std::string>().rfind(label_start, 0) == 0) return true;
  return false;
}

report::ReportOptions dyn_report_coarse() {
  report::ReportOptions options;
  options.chart_buckets = 100;  // 20000 ticks: buckets of 200, so decimation has to keep the spikes
  options.frames = 150;
  return options;
}

TEST(DynamicsReport, ForcePowerEnergyAndErrorPlotsKeepTheirPeaks) {
  const DynReportRun run = dyn_report_write_run("full", {});
  auto data = report::report_from_directory(run.dir, dyn_report_coarse());
  ASSERT_TRUE(data) << data.error().message;
  for (const char* id : {"drive_forces", "drive_forces_static", "drive_forces_dynamic", "drive_power",
                         "drive_energy", "dynamic_error"})
    ASSERT_NE(dyn_report_chart(*data, id), nullptr) << id;

  const nlohmann::json& forces = *dyn_report_chart(*data, "drive_forces");
  EXPECT_EQ(forces["y_unit"], "N");
  const std::size_t points = forces["x"]["time_s"].size();
  EXPECT_LE(points, 2u * 100u + 2u);  // decimated, bounded by the buckets
  ASSERT_EQ(forces["x"]["s_mm"].size(), points);
  // The one-tick pull of drive 3 survives a bucket of 200 ticks, and so do the sine's extremes of the others.
  EXPECT_EQ(dyn_report_min(*dyn_report_series(forces, "P3 [N]")), kDynReportSpikeN);
  EXPECT_NEAR(dyn_report_max(*dyn_report_series(forces, "P1 [N]")), 220.0, 1e-3);
  EXPECT_NEAR(
      dyn_report_min(*dyn_report_series(*dyn_report_chart(*data, "drive_forces_dynamic"), "P3 dynamic [N]")),
      kDynReportSpikeN - dyn_report_static_N(2), 1e-9);
  EXPECT_NEAR(
      dyn_report_max(*dyn_report_series(*dyn_report_chart(*data, "drive_forces_static"), "P6 static [N]")),
      dyn_report_static_N(5), 1e-9);
  // Power per drive and the total; the total's peak is the sum of the drives' at the same tick.
  const nlohmann::json& power = *dyn_report_chart(*data, "drive_power");
  ASSERT_NE(dyn_report_series(power, "total [W]"), nullptr);
  EXPECT_NEAR(dyn_report_max(*dyn_report_series(power, "power 6 [W]")), 3.0, 1e-4);

  // The cumulative energy ends at the summary's energies, in each accounting.
  const nlohmann::json& energy = *dyn_report_chart(*data, "drive_energy");
  const auto last = [&](const char* name) { return dyn_report_series(energy, name)->back().get<double>(); };
  EXPECT_NEAR(last("no recovery [J]"), run.energy_no_recovery_J, 1e-5 * run.energy_no_recovery_J);
  EXPECT_NEAR(last("braking free [J]"), run.energy_braking_free_J, 1e-5 * run.energy_braking_free_J);
  EXPECT_NEAR(last("recovery [J]"), run.energy_recovery_J, 1e-5 * run.energy_recovery_J);
  EXPECT_GT(run.energy_no_recovery_J, run.energy_braking_free_J);
  EXPECT_GT(run.energy_braking_free_J, run.energy_recovery_J);

  const nlohmann::json& error = *dyn_report_chart(*data, "dynamic_error");
  EXPECT_EQ(dyn_report_max(*dyn_report_series(error, "|d| [mm]")), kDynReportErrorSpikeMm);

  // Every frame carries the drive forces of its tick; the colour scale is the run's peak |force|.
  const nlohmann::json& scene = (*data)["scene"];
  const nlohmann::json& frames = scene["frames"];
  ASSERT_TRUE(frames.contains("drive_force"));
  ASSERT_EQ(frames["drive_force"].size(), frames["time_s"].size());
  EXPECT_GT(frames["time_s"].size(), 100u);
  for (std::size_t f = 0; f < frames["time_s"].size(); f += 37) {
    const long k = std::lround(frames["time_s"][f].get<double>() * kDynReportRateHz);
    ASSERT_EQ(frames["drive_force"][f].size(), static_cast<std::size_t>(kDynReportDrives));
    for (int j = 0; j < kDynReportDrives; ++j)
      EXPECT_NEAR(frames["drive_force"][f][j].get<double>(), dyn_report_total_N(j, k), 0.06) << f << " " << j;
  }
  EXPECT_EQ(scene["drive_force_scale"], 750.0);
  EXPECT_EQ(scene["drive_force_unit"], "N");

  // The summary table shows the dynamics figures with their program lines.
  bool drive3 = false;
  for (const auto& row : (*data)["table"]) {
    if (row["label"] == "Peak force, drive 3") {
      drive3 = true;
      EXPECT_EQ(row["line"], 5);
      EXPECT_NE(row["value"].get<std::string>().find("750 N"), std::string::npos) << row["value"];
    }
    if (row["label"] == "Max dynamic tool error") {
      EXPECT_EQ(row["line"], 2);
    }
  }
  EXPECT_TRUE(drive3);
  EXPECT_TRUE(dyn_report_has_row(*data, "Energy: no recovery"));
  EXPECT_TRUE(dyn_report_has_row(*data, "Lowest natural frequency"));
  EXPECT_TRUE(dyn_report_has_row(*data, "Peak total power"));
}

TEST(DynamicsReport, ARigidRunHasNoDynamicErrorPlot) {
  DynReportRunSpec spec;
  spec.elastic = false;
  const DynReportRun run = dyn_report_write_run("rigid", spec);
  auto data = report::report_from_directory(run.dir, dyn_report_coarse());
  ASSERT_TRUE(data) << data.error().message;
  EXPECT_NE(dyn_report_chart(*data, "drive_forces"), nullptr);
  EXPECT_EQ(dyn_report_chart(*data, "dynamic_error"), nullptr);
  EXPECT_FALSE(dyn_report_has_row(*data, "Max dynamic tool error"));
  EXPECT_TRUE((*data)["scene"]["frames"].contains("drive_force"));
}

TEST(DynamicsReport, WithoutADynamicsSummaryAnEarlierRunsForcesCsvIsIgnored) {
  // A plan without --dynamics into a directory that still holds an earlier run's forces.csv and response.csv.
  DynReportRunSpec spec;
  spec.summary_has_dynamics = false;
  const DynReportRun run = dyn_report_write_run("stale", spec);
  ASSERT_TRUE(fs::exists(run.dir + "/forces.csv"));
  auto data = report::report_from_directory(run.dir, dyn_report_coarse());
  ASSERT_TRUE(data) << data.error().message;
  for (const auto& c : (*data)["charts"]) {
    const std::string id = c["id"];
    EXPECT_TRUE(id.rfind("drive_", 0) != 0 && id != "dynamic_error") << id;
  }
  EXPECT_EQ((*data)["charts"].size(), 5u);  // the plan's own plots, as before
  EXPECT_FALSE((*data)["scene"]["frames"].contains("drive_force"));
  EXPECT_FALSE((*data)["scene"].contains("drive_force_scale"));
  EXPECT_FALSE(dyn_report_has_row(*data, "Peak force"));
}

TEST(DynamicsReport, ForcesOfAnotherRunOrMissingAreErrorsNamingTheFile) {
  DynReportRunSpec short_spec;
  short_spec.forces_rows_missing = 3;
  const DynReportRun short_run = dyn_report_write_run("short", short_spec);
  auto cut = report::report_from_directory(short_run.dir, dyn_report_coarse());
  ASSERT_FALSE(cut);
  EXPECT_NE(cut.error().message.find("forces.csv"), std::string::npos) << cut.error().message;

  DynReportRunSpec missing_spec;
  missing_spec.write_forces = false;
  const DynReportRun missing_run = dyn_report_write_run("missing", missing_spec);
  auto missing = report::report_from_directory(missing_run.dir, dyn_report_coarse());
  ASSERT_FALSE(missing);
  EXPECT_NE(missing.error().message.find("forces.csv"), std::string::npos) << missing.error().message;

  // More rows than path.csv: a forces.csv of a longer run.
  const DynReportRun long_run = dyn_report_write_run("long", {});
  const DynReportRun other = dyn_report_write_run("other", {.ticks = 19000});
  fs::copy_file(long_run.dir + "/forces.csv", other.dir + "/forces.csv",
                fs::copy_options::overwrite_existing);
  auto longer = report::report_from_directory(other.dir, dyn_report_coarse());
  ASSERT_FALSE(longer);
  EXPECT_NE(longer.error().message.find("forces.csv"), std::string::npos) << longer.error().message;
}

TEST(DynamicsReport, APlannedCircleShowsTheSummarysPeaksAndEnergy) {
  const std::string dir = (fs::temp_directory_path() / "pkm_dynamics_report_helix").string();
  fs::remove_all(dir);
  // circle.ngc (12.8 s of motion) rather than the 40.8 s helix: the sanitizer run of CI pays for every tick.
  const auto run = test::run_pkm("plan " + test::source_path("examples/programs/circle.ngc") + " --machine " +
                                 test::source_path("examples/machines/hexapod_ch5.yaml") +
                                 " --dynamics --elastic --out " + dir);
  ASSERT_EQ(run.exit_code, 0) << run.out;
  auto data = report::report_from_directory(dir);
  ASSERT_TRUE(data) << data.error().message;
  const nlohmann::json& d = (*data)["summary"]["dynamics"];

  // The plots' extremes are the summary's peaks (decimated 12 829 ticks to 2 000 buckets): to the files'
  // digits.
  const nlohmann::json& forces = *dyn_report_chart(*data, "drive_forces");
  EXPECT_LT(forces["x"]["time_s"].size(), 4100u);
  for (int j = 0; j < 6; ++j) {
    const nlohmann::json& values = *dyn_report_series(forces, fmt::format("P{} [N]", j + 1));
    const double peak = std::max(dyn_report_max(values), -dyn_report_min(values));
    EXPECT_NEAR(peak, d["drives"][j]["peak_force_N"].get<double>(), 1e-3) << "drive " << j + 1;
  }
  const nlohmann::json& energy = *dyn_report_chart(*data, "drive_energy");
  const double no_recovery = dyn_report_series(energy, "no recovery [J]")->back().get<double>();
  const double recovery = dyn_report_series(energy, "recovery [J]")->back().get<double>();
  EXPECT_NEAR(no_recovery, d["energy_no_recovery_J"].get<double>(),
              1e-4 * d["energy_no_recovery_J"].get<double>());
  EXPECT_NEAR(recovery, d["energy_recovery_J"].get<double>(), 1e-4 * d["energy_recovery_J"].get<double>());
  const nlohmann::json& error = *dyn_report_chart(*data, "dynamic_error");
  EXPECT_NEAR(dyn_report_max(*dyn_report_series(error, "|d| [mm]")),
              d["max_dynamic_tool_error_mm"].get<double>(),
              1e-4 * d["max_dynamic_tool_error_mm"].get<double>());
  double peak_N = 0.0;
  for (const auto& drive : d["drives"]) peak_N = std::max(peak_N, drive["peak_force_N"].get<double>());
  EXPECT_NEAR((*data)["scene"]["drive_force_scale"].get<double>(), peak_N, 0.05);
}

}  // namespace
}  // namespace pkm
