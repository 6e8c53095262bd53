// pkm stiffness: the deflection at every point of a program (points.csv, summary.json), the pre-compensated
// program, per-line CSV loads, and the inputs it refuses.
//  - the summary's largest and rms normal error are those of points.csv;
//  - the deflected point is the nominal one plus the deflection, the strut forces balance the load;
//  - running the pre-compensated program again puts the deflected tool on the original nominal points;
//  - a per-line CSV load deflects only the lines it names;
//  - bad input: an unknown model, a load file with an unknown column (file:line:column), no output left.
#include <fmt/format.h>
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>

#include "cli/cli_support.hpp"

namespace pkm {
namespace {

namespace fs = std::filesystem;

struct PointsTable {
  std::vector<std::string> columns;
  std::vector<std::vector<double>> rows;
  int column(const std::string& name) const {
    for (std::size_t c = 0; c < columns.size(); ++c)
      if (columns[c] == name) return static_cast<int>(c);
    ADD_FAILURE() << "no column " << name;
    return 0;
  }
};

PointsTable read_points_table(const fs::path& path) {
  PointsTable table;
  std::ifstream in(path);
  std::string line;
  std::getline(in, line);
  std::stringstream header(line);
  for (std::string c; std::getline(header, c, ',');) table.columns.push_back(c);
  while (std::getline(in, line)) {
    std::stringstream row(line);
    std::vector<double> values;
    for (std::string v; std::getline(row, v, ',');) values.push_back(std::stod(v));
    EXPECT_EQ(values.size(), table.columns.size());
    table.rows.push_back(values);
  }
  return table;
}

fs::path stiffness_cli_dir(const std::string& name) {
  const fs::path dir = fs::temp_directory_path() / ("pkm_stiffness_cli_" + name);
  fs::remove_all(dir);
  return dir;
}

const std::string kStiffnessMachine = test::source_path("examples/machines/hexapod_ch5.yaml");
const std::string kStiffnessProgram = test::source_path("examples/programs/ball_end_5axis.cl");

struct CompensationCheck {
  double largest_deflection_mm = 0.0;  ///< of the original program
  double worst_landing_mm = 0.0;       ///< of the corrected program's deflected tool from the nominal points
};

// Runs `load` on the example, pre-compensated, checks the summary against points.csv, runs the corrected
// program again with the same load and measures where its deflected tool lands.
CompensationCheck check_compensation(const std::string& load, const std::string& name) {
  CompensationCheck check;
  const fs::path dir = stiffness_cli_dir(name);
  const fs::path compensated = dir / "compensated.cl";
  const auto run =
      test::run_pkm("stiffness " + kStiffnessProgram + " --machine " + kStiffnessMachine + " --load " + load +
                        " --out " + dir.string() + " --compensate " + compensated.string() + " --json",
                    false);
  EXPECT_EQ(run.exit_code, 0) << run.out;
  if (run.exit_code != 0) return check;
  const auto summary = nlohmann::json::parse(run.out);
  const PointsTable points = read_points_table(dir / "points.csv");
  EXPECT_EQ(static_cast<long>(points.rows.size()), summary["points"].get<long>());
  double largest = 0.0, square_sum = 0.0;
  long cutting = 0;
  for (const auto& row : points.rows) {
    const double normal = row[points.column("normal_mm")];
    largest = std::max(largest, std::abs(normal));
    if (row[points.column("cutting")] == 1) {
      square_sum += normal * normal;
      ++cutting;
    }
    double moved_square = 0.0;
    for (const char* axis : {"x", "y", "z"}) {
      const double nominal = row[points.column(std::string(axis) + "_mm")];
      const double moved = row[points.column(std::string("d") + axis + "_mm")];
      moved_square += moved * moved;
      EXPECT_NEAR(row[points.column(std::string("deflected_") + axis + "_mm")], nominal + moved, 2e-9);
    }
    check.largest_deflection_mm = std::max(check.largest_deflection_mm, std::sqrt(moved_square));
  }
  EXPECT_GT(largest, 1e-4);  // micrometres: the checks below would be empty otherwise
  EXPECT_NEAR(summary["max_normal_deflection_mm"].get<double>(), largest, 1e-8 * largest + 1e-12);
  EXPECT_NEAR(summary["rms_normal_deflection_mm"].get<double>(), std::sqrt(square_sum / cutting),
              1e-6 * largest);
  EXPECT_LE(summary["compensation"]["max_residual_mm"].get<double>(), 1e-6);

  const fs::path again = stiffness_cli_dir(name + "_again");
  const auto rerun =
      test::run_pkm("stiffness " + compensated.string() + " --machine " + kStiffnessMachine + " --load " +
                        load + " --step-mm 1000 --out " + again.string() + " --json",
                    false);
  EXPECT_EQ(rerun.exit_code, 0) << rerun.out;
  const PointsTable corrected = read_points_table(again / "points.csv");
  // One point per corrected part: the original's points after its first one, in order.
  EXPECT_EQ(corrected.rows.size(), points.rows.size());
  for (std::size_t k = 1; k < std::min(points.rows.size(), corrected.rows.size()); ++k) {
    for (const char* axis : {"x", "y", "z"}) {
      const double nominal = points.rows[k][points.column(std::string(axis) + "_mm")];
      const double landed = corrected.rows[k][corrected.column(std::string("deflected_") + axis + "_mm")];
      check.worst_landing_mm = std::max(check.worst_landing_mm, std::abs(landed - nominal));
    }
  }
  fs::remove_all(dir);
  fs::remove_all(again);
  return check;
}

// A constant force: the corrected program's deflected tool lands on the nominal points to the program's
// 10⁻⁶ mm decimals, where the deflection itself is micrometres.
TEST(StiffnessCli, TheCompensatedProgramPutsTheToolOnThePathUnderAConstantForce) {
  const CompensationCheck check = check_compensation("force=300:-200:-500", "constant");
  EXPECT_GT(check.largest_deflection_mm, 1e-3);
  EXPECT_LT(check.worst_landing_mm, 1e-5) << "largest deflection " << check.largest_deflection_mm;
}

// A cutting force along the travel: the corrected program's travel turns by the change of the correction
// between points (10⁻² rad at the ends of the passes, where the force turns), and the force with it, so what
// is left is second order: 1 % of the deflection. No normal force: on the program's plunges (travel along the
// tool axis) the side of the cut is undefined and the normal force left out, while a corrected plunge leans
// by the correction, so a normal force would act there in full: a different load, not a different
// compensation.
TEST(StiffnessCli, TheCompensatedProgramRemovesMostOfTheDeflectionUnderACuttingForce) {
  const CompensationCheck check = check_compensation("tangential=600,axial=80", "cutting");
  EXPECT_GT(check.largest_deflection_mm, 1e-3);
  EXPECT_LT(check.worst_landing_mm, 0.02 * check.largest_deflection_mm);
}

// The frame of beams through `pkm stiffness`: the machine file's fullest model is the frame; the frame only
// adds compliance (every point deflects more than with the struts alone), and the six struts' tensions are
// statics' whatever gives way.
TEST(StiffnessCli, TheFrameModelAddsComplianceButNotStrutForce) {
  const std::string machine = test::source_path("examples/machines/hexapod_ch5_frame.yaml");
  PointsTable tables[2];
  const char* models[2] = {"", " --model struts"};
  for (int m = 0; m < 2; ++m) {
    const fs::path dir = stiffness_cli_dir(fmt::format("frame_{}", m));
    const auto run = test::run_pkm("stiffness " + kStiffnessProgram + " --machine " + machine +
                                       " --load tangential=600,normal=150" + models[m] + " --out " +
                                       dir.string() + " --json",
                                   false);
    ASSERT_EQ(run.exit_code, 0) << run.out;
    EXPECT_EQ(nlohmann::json::parse(run.out)["model"], m == 0 ? "frame" : "struts");
    tables[m] = read_points_table(dir / "points.csv");
    fs::remove_all(dir);
  }
  const PointsTable& frame = tables[0];
  const PointsTable& struts = tables[1];
  ASSERT_EQ(frame.rows.size(), struts.rows.size());
  int softer = 0;
  for (std::size_t k = 0; k < frame.rows.size(); ++k) {
    double moved[2] = {0.0, 0.0};
    for (int m = 0; m < 2; ++m)
      for (const char* axis : {"dx_mm", "dy_mm", "dz_mm"})
        moved[m] += std::pow(tables[m].rows[k][tables[m].column(axis)], 2);
    if (moved[1] == 0.0) continue;
    EXPECT_GE(moved[0], moved[1] * (1.0 - 1e-9)) << "point " << k;
    softer += moved[0] > moved[1] * 1.001;
    for (int j = 1; j <= 6; ++j) {
      // fmt rather than "F" + std::to_string(j): GCC 12 warns falsely (stringop-overflow) on the latter here.
      const std::string f = fmt::format("F{}_N", j);
      const double expected = struts.rows[k][struts.column(f)];
      EXPECT_NEAR(frame.rows[k][frame.column(f)], expected, 1e-6 * std::abs(expected) + 1e-6)
          << "point " << k;
    }
  }
  EXPECT_GT(softer, 0);
}

TEST(StiffnessCli, APerLineCsvLoadDeflectsOnlyItsLines) {
  const fs::path dir = stiffness_cli_dir("csv_load");
  const std::string loads = test::write_temp_file("stiffness_loads.csv", "line,fx_N,fz_N\n22,300,-500\n");
  const auto run = test::run_pkm("stiffness " + kStiffnessProgram + " --machine " + kStiffnessMachine +
                                     " --load @" + loads + " --out " + dir.string() + " --json",
                                 false);
  ASSERT_EQ(run.exit_code, 0) << run.out;
  const PointsTable points = read_points_table(dir / "points.csv");
  int loaded = 0;
  for (const auto& row : points.rows) {
    const double force = std::abs(row[points.column("fx_N")]) + std::abs(row[points.column("fz_N")]);
    const double moved = std::abs(row[points.column("dx_mm")]) + std::abs(row[points.column("dz_mm")]);
    if (row[points.column("line")] == 22) {
      ++loaded;
      EXPECT_EQ(force, 800.0);
      EXPECT_GT(moved, 0.0);
    } else {
      EXPECT_EQ(force, 0.0);
      EXPECT_EQ(moved, 0.0);
    }
  }
  EXPECT_GT(loaded, 0);
  fs::remove_all(dir);
}

TEST(StiffnessCli, RefusesBadInputWithoutWritingAnything) {
  const fs::path dir = stiffness_cli_dir("bad");
  auto run = test::run_pkm("stiffness " + kStiffnessProgram + " --machine " + kStiffnessMachine +
                           " --load tangential=100 --model springs --out " + dir.string());
  EXPECT_NE(run.exit_code, 0);
  EXPECT_NE(run.out.find("--model"), std::string::npos) << run.out;
  const std::string loads = test::write_temp_file("stiffness_bad_loads.csv", "line,fx_N,torque\n3,1,2\n");
  run = test::run_pkm("stiffness " + kStiffnessProgram + " --machine " + kStiffnessMachine + " --load @" +
                      loads + " --out " + dir.string());
  EXPECT_NE(run.exit_code, 0);
  EXPECT_NE(run.out.find(loads + ":1:11"), std::string::npos) << run.out;
  EXPECT_NE(run.out.find("torque"), std::string::npos) << run.out;
  // Turned 90° about z on its axis the ch5 hexapod is singular (strut_compliance_test): the program's line,
  // not a huge number.
  const std::string singular =
      test::write_temp_file("stiffness_singular.ngc", "G1 X0 Y0 Z0.5 C90 F100\nM2\n");
  run = test::run_pkm("stiffness " + singular + " --machine " + kStiffnessMachine +
                      " --load tangential=100 --out " + dir.string());
  EXPECT_EQ(run.exit_code, 4) << run.out;
  EXPECT_NE(run.out.find(singular + ":1:"), std::string::npos) << run.out;
  EXPECT_NE(run.out.find("unbounded compliance"), std::string::npos) << run.out;
  EXPECT_FALSE(fs::exists(dir));
}

}  // namespace
}  // namespace pkm
