// The files of a workspace map and their report: workspace.csv has a row per cell with the library's values
// and the limit that stops it, summary.json the summary's counts and extremes, and the report's heat maps
// (report/workspace_report.hpp) hold the files' cells, thinned about the centre where the grid is fine.
#include "formats/workspace_output.hpp"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>

#include "report/workspace_report.hpp"
#include "workspace_support.hpp"

namespace pkm {
namespace {

namespace fs = std::filesystem;
using workspace::CellStatus;

std::vector<std::string> ws_output_fields(const std::string& line) {
  std::vector<std::string> fields;
  std::stringstream text(line);
  for (std::string field; std::getline(text, field, ',');) fields.push_back(field);
  if (!line.empty() && line.back() == ',') fields.emplace_back();
  return fields;
}

// The map's files written into a fresh directory, as pkm workspace writes them.
std::string ws_output_directory(const Machine& m, const workspace::WorkspaceMap& map,
                                const std::string& name) {
  const fs::path dir = fs::temp_directory_path() / ("pkm_workspace_output_" + name);
  fs::remove_all(dir);
  OutputSet outputs;
  EXPECT_TRUE(outputs.use_directory(dir.string()).ok());
  EXPECT_TRUE(formats::stage_workspace_files(outputs, m, map, workspace::summarise_workspace_map(map)).ok());
  EXPECT_TRUE(outputs.commit().ok());
  return dir.string();
}

TEST(WorkspaceOutput, CsvHasARowPerCellWithTheLibrarysValues) {
  const Machine m = test::machine_from_example("examples/machines/hexapod_ch5.yaml");
  const auto grid = workspace::plane_section(m.mechanism->home(), dynamics::GridPlane::xz, 400, 100);
  workspace::WorkspaceMapOptions options;
  options.stiffness = true;
  const workspace::WorkspaceMap map = test::ws_map_of(m, grid, options);
  std::stringstream csv(formats::workspace_csv(*m.mechanism, map));
  std::string line;
  std::getline(csv, line);
  EXPECT_EQ(
      line,
      "x_mm,y_mm,z_mm,psi_deg,theta_deg,gamma_deg,status,limit,det_sign,condition_number,delta_rho,S_x,S_y,"
      "S_z,lowest_stiffness_N_um");
  std::size_t row = 0;
  for (; std::getline(csv, line); ++row) {
    ASSERT_LT(row, map.cells.size());
    const workspace::WorkspaceCell& cell = map.cells[row];
    const std::vector<std::string> f = ws_output_fields(line);
    ASSERT_EQ(f.size(), 15u) << line;
    EXPECT_EQ(f[6], workspace::to_string(cell.status));
    EXPECT_EQ(f[7], formats::limit_text(cell));
    EXPECT_EQ(std::stoi(f[8]), cell.determinant_sign);
    EXPECT_NEAR(std::stod(f[10]), cell.error_amplification, 1e-8 * cell.error_amplification) << line;
    if (cell.status == CellStatus::ok) {
      EXPECT_EQ(f[7], "");
      EXPECT_NEAR(std::stod(f[14]), cell.lowest_stiffness_N_um, 1e-8 * cell.lowest_stiffness_N_um);
    } else {
      EXPECT_EQ(f[14], "") << line;
    }
    if (cell.limit == workspace::CellLimit::actuator_max) {
      EXPECT_EQ(f[7], "q" + std::to_string(cell.limit_index + 1) + "_max");
    }
  }
  EXPECT_EQ(row, 81u);
}

TEST(WorkspaceOutput, SummaryJsonHasTheCountsAndExtremes) {
  const Machine m = test::machine_from_example("examples/machines/hexapod_ch5.yaml");
  const auto grid = workspace::plane_section(m.mechanism->home(), dynamics::GridPlane::xz, 400, 100);
  const workspace::WorkspaceMap map = test::ws_map_of(m, grid);
  const workspace::WorkspaceMapSummary s = workspace::summarise_workspace_map(map);
  const nlohmann::json j = formats::workspace_summary_json(m, map, s);
  EXPECT_EQ(j["kind"], "workspace");
  EXPECT_EQ(j["grid"]["kind"], "section");
  EXPECT_EQ(j["grid"]["axes"][1]["column"], "z_mm");
  EXPECT_EQ(j["grid"]["axes"][1]["points"], 9);
  EXPECT_EQ(j["cells"], 81);
  EXPECT_EQ(j["status"]["ok"], s.status_cells[0]);
  EXPECT_EQ(j["status"]["actuator_range"],
            s.status_cells[static_cast<std::size_t>(CellStatus::actuator_range)]);
  EXPECT_FALSE(j["layers"].contains("lowest_stiffness_N_um"));
  const auto& delta_rho = j["layers"]["delta_rho"];
  EXPECT_EQ(delta_rho["min"].get<double>(), s.layers[1].min);
  EXPECT_EQ(delta_rho["max_pose"].size(), 6u);
  // An angle axis is given in degrees, as users give it.
  workspace::WorkspaceGrid tilted{m.mechanism->home(), {{0, 100.0, 50.0}, {4, 0.2, 0.1}}};
  const workspace::WorkspaceMap tilted_map = test::ws_map_of(m, tilted);
  const nlohmann::json t =
      formats::workspace_summary_json(m, tilted_map, workspace::summarise_workspace_map(tilted_map));
  EXPECT_EQ(t["grid"]["axes"][1]["column"], "theta_deg");
  EXPECT_NEAR(t["grid"]["axes"][1]["step"].get<double>(), 5.729578, 1e-6);
}

TEST(WorkspaceOutput, ReportHeatMapsHoldTheFilesCells) {
  const Machine m = test::machine_from_example("examples/machines/hexapod_ch5.yaml");
  const auto grid = workspace::plane_section(m.mechanism->home(), dynamics::GridPlane::xz, 400, 100);
  const workspace::WorkspaceMap map = test::ws_map_of(m, grid);
  const std::string dir = ws_output_directory(m, map, "report");
  std::ifstream summary_file(dir + "/summary.json");
  const nlohmann::json summary = nlohmann::json::parse(summary_file);
  auto heat = report::workspace_map_json(dir + "/workspace.csv", summary);
  ASSERT_TRUE(heat.ok()) << heat.error().message;
  EXPECT_EQ((*heat)["x_label"], "x_mm");
  EXPECT_EQ((*heat)["y_label"], "z_mm");
  EXPECT_EQ((*heat)["x"].size(), 9u);
  EXPECT_TRUE((*heat)["slices"].empty());
  const nlohmann::json& layers = (*heat)["layers"];
  ASSERT_EQ(layers[0]["id"], "status");
  EXPECT_EQ(layers[2]["id"], "delta_rho");
  for (std::size_t i = 0; i < map.cells.size(); ++i) {
    const auto& cell = map.cells[i];
    const std::size_t x = i % 9, z = i / 9;
    EXPECT_EQ(layers[0]["values"][0][z][x].get<int>(), static_cast<int>(cell.status)) << i;
    EXPECT_NEAR(layers[2]["values"][0][z][x].get<double>(), cell.error_amplification,
                1e-5 * cell.error_amplification);
  }
  // The whole report: kind, table, the map.
  report::ReportOptions options;
  auto page = report::report_from_directory(dir, options);
  ASSERT_TRUE(page.ok()) << page.error().message;
  EXPECT_EQ((*page)["kind"], "workspace");
  EXPECT_TRUE((*page).contains("workspace_map"));
  EXPECT_EQ((*page)["scene"]["frames"]["time_s"].size(), 1u);
}

TEST(WorkspaceOutput, FineGridsAreThinnedAboutTheCentre) {
  const Machine m = test::machine_from_example("examples/machines/hexapod_ch5.yaml");
  const auto grid = workspace::position_grid(m.mechanism->home(), 21, 1);  // 43³ cells
  const workspace::WorkspaceMap map = test::ws_map_of(m, grid);
  const std::string dir = ws_output_directory(m, map, "grid3d");
  std::ifstream summary_file(dir + "/summary.json");
  const nlohmann::json summary = nlohmann::json::parse(summary_file);
  EXPECT_EQ(summary["grid"]["kind"], "grid3d");
  auto heat = report::workspace_map_json(dir + "/workspace.csv", summary);
  ASSERT_TRUE(heat.ok()) << heat.error().message;
  // Every 2nd of 43 points (at most 41 are shown), the centre among them.
  for (const char* axis : {"x", "y", "slices"}) {
    const nlohmann::json& values = (*heat)[axis];
    ASSERT_EQ(values.size(), 21u) << axis;
    bool centre = false;
    for (const auto& v : values)
      centre = centre || std::abs(v.get<double>() - (axis[0] == 's' ? 700.0 : 0.0)) < 1e-9;
    EXPECT_TRUE(centre) << axis;
  }
  EXPECT_EQ((*heat)["slice_label"], "z_mm");
  EXPECT_EQ((*heat)["layers"][0]["values"].size(), (*heat)["slices"].size());
}

TEST(WorkspaceOutput, MalformedFilesAreRefusedWithTheirPlace) {
  const Machine m = test::machine_from_example("examples/machines/hexapod_ch5.yaml");
  const auto grid = workspace::plane_section(m.mechanism->home(), dynamics::GridPlane::xz, 100, 100);
  const workspace::WorkspaceMap map = test::ws_map_of(m, grid);
  const std::string dir = ws_output_directory(m, map, "malformed");
  std::ifstream summary_file(dir + "/summary.json");
  const nlohmann::json summary = nlohmann::json::parse(summary_file);
  std::ifstream in(dir + "/workspace.csv");
  std::stringstream text;
  text << in.rdbuf();
  std::string csv = text.str();
  const std::string bad = dir + "/bad.csv";
  std::ofstream(bad) << csv.substr(0, csv.rfind('\n', csv.size() - 2) + 1);  // the last row missing
  auto short_map = report::workspace_map_json(bad, summary);
  ASSERT_FALSE(short_map.ok());
  EXPECT_NE(short_map.error().message.find("8 rows for a grid of 9 cells"), std::string::npos)
      << short_map.error().message;
  std::string wrong = csv;
  wrong.replace(wrong.find(",ok,"), 4, ",maybe,");
  std::ofstream(bad) << wrong;
  auto word = report::workspace_map_json(bad, summary);
  ASSERT_FALSE(word.ok());
  EXPECT_NE(word.error().message.find("bad.csv:2: status: unknown word 'maybe'"), std::string::npos)
      << word.error().message;
}

}  // namespace
}  // namespace pkm
