#include "report/stiffness_plots.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <charconv>
#include <cmath>
#include <filesystem>
#include <limits>
#include <map>
#include <sstream>

#include "io/input_file.hpp"
#include "report/csv_table.hpp"
#include "report/decimator.hpp"

namespace pkm::report {
namespace {

constexpr double kStiffnessPlotNone = std::numeric_limits<double>::quiet_NaN();

std::vector<std::string> stiffness_plot_fields(const std::string& line) {
  std::vector<std::string> fields;
  std::stringstream text(line);
  for (std::string field; std::getline(text, field, ',');) fields.push_back(field);
  if (!line.empty() && line.back() == ',') fields.emplace_back();
  return fields;
}

// An empty field is no value (NaN); anything else must be a whole number.
bool stiffness_plot_number(const std::string& field, double& value) {
  if (field.empty()) {
    value = kStiffnessPlotNone;
    return true;
  }
  const auto [end, error] = std::from_chars(field.data(), field.data() + field.size(), value);
  return error == std::errc() && end == field.data() + field.size();
}

// Every k-th of n indices so that at most `most` remain (all of them when n ≤ most).
std::vector<int> stiffness_plot_stride(int n, int most) {
  const int k = std::max(1, (n + most - 1) / std::max(1, most));
  std::vector<int> kept;
  for (int i = 0; i < n; i += k) kept.push_back(i);
  return kept;
}

}  // namespace

Result<nlohmann::json> frequency_response_json(const std::string& path) {
  CsvReader reader;
  if (Status s = reader.open(path); !s) return s.error();
  auto frequency = reader.require("frequency_Hz");
  if (!frequency) return frequency.error();
  struct Entry {
    std::string name;
    int magnitude = -1, phase = -1;
    std::vector<double> magnitudes, phases;
  };
  std::vector<Entry> entries;
  const std::string suffix = "_magnitude_um_N";
  for (const std::string& column : reader.columns()) {
    if (column.size() <= suffix.size() ||
        column.compare(column.size() - suffix.size(), suffix.size(), suffix))
      continue;
    Entry e;
    e.name = column.substr(0, column.size() - suffix.size());
    e.magnitude = reader.column(column);
    e.phase = reader.column(e.name + "_phase_deg");
    if (e.phase < 0) {
      return make_error(ErrorCode::bad_input,
                        fmt::format("{}: {} has no column {}_phase_deg", path, column, e.name));
    }
    entries.push_back(std::move(e));
  }
  std::vector<double> frequencies, row;
  while (reader.next(row)) {
    frequencies.push_back(row[*frequency]);
    for (Entry& e : entries) {
      e.magnitudes.push_back(row[e.magnitude]);
      e.phases.push_back(row[e.phase]);
    }
  }
  if (reader.error()) return *reader.error();
  nlohmann::json list = nlohmann::json::array();
  for (const Entry& e : entries) {
    list.push_back({{"name", e.name},
                    {"magnitude_um_N", json_numbers(e.magnitudes)},
                    {"phase_deg", json_numbers(e.phases, 5)}});
  }
  return nlohmann::json{{"file", std::filesystem::path(path).filename().string()},
                        {"frequency_Hz", json_numbers(frequencies, 7)},
                        {"entries", list}};
}

Result<nlohmann::json> stiffness_map_json(const std::string& path, int max_per_axis) {
  auto text = read_text_input(path, "stiffness map");
  if (!text) return text.error();
  std::stringstream in(*text);
  std::string line;
  std::getline(in, line);
  if (!line.empty() && line.back() == '\r') line.pop_back();
  const std::vector<std::string> columns = stiffness_plot_fields(line);
  const auto index_of = [&](const std::string& name) {
    const auto at = std::find(columns.begin(), columns.end(), name);
    return at == columns.end() ? -1 : static_cast<int>(at - columns.begin());
  };
  const int value_column = index_of("lowest_stiffness_N_um");
  if (value_column < 0) {
    return make_error(ErrorCode::bad_input, fmt::format("{}: no column lowest_stiffness_N_um", path));
  }
  std::vector<int> position;  // x_mm, y_mm, z_mm that are there
  for (const char* name : {"x_mm", "y_mm", "z_mm"})
    if (index_of(name) >= 0) position.push_back(index_of(name));
  std::vector<std::vector<double>> rows;
  for (long number = 2; std::getline(in, line); ++number) {
    if (!line.empty() && line.back() == '\r') line.pop_back();
    if (line.empty()) continue;
    const std::vector<std::string> fields = stiffness_plot_fields(line);
    if (fields.size() != columns.size()) {
      return make_error(ErrorCode::bad_input, fmt::format("{}:{}: {} fields, the header has {}", path, number,
                                                          fields.size(), columns.size()));
    }
    std::vector<double> r(position.size());
    for (std::size_t c = 0; c < position.size(); ++c) {
      if (!stiffness_plot_number(fields[position[c]], r[c]) || std::isnan(r[c])) {
        return make_error(ErrorCode::bad_input, fmt::format("{}:{}: {}: not a number: {}", path, number,
                                                            columns[position[c]], fields[position[c]]));
      }
    }
    double value = 0.0;
    if (!stiffness_plot_number(fields[value_column], value)) {
      return make_error(ErrorCode::bad_input, fmt::format("{}:{}: lowest_stiffness_N_um: not a number: {}",
                                                          path, number, fields[value_column]));
    }
    r.push_back(value);
    rows.push_back(std::move(r));
  }
  // The grid's axes: the position columns that vary (the first two), else the first two there are.
  std::vector<std::vector<double>> distinct(position.size());
  for (std::size_t c = 0; c < position.size(); ++c) {
    for (const auto& r : rows) distinct[c].push_back(r[c]);
    std::sort(distinct[c].begin(), distinct[c].end());
    distinct[c].erase(std::unique(distinct[c].begin(), distinct[c].end()), distinct[c].end());
  }
  std::vector<std::size_t> axes;
  for (std::size_t c = 0; c < position.size() && axes.size() < 2; ++c)
    if (distinct[c].size() > 1) axes.push_back(c);
  for (std::size_t c = 0; c < position.size() && axes.size() < 2; ++c)
    if (std::find(axes.begin(), axes.end(), c) == axes.end()) axes.push_back(c);
  if (axes.size() < 2) {
    return make_error(ErrorCode::bad_input, fmt::format("{}: fewer than two of x_mm, y_mm, z_mm", path));
  }
  std::sort(axes.begin(), axes.end());
  const auto& xs = distinct[axes[0]];
  const auto& ys = distinct[axes[1]];
  std::map<std::pair<double, double>, double> cells;
  for (const auto& r : rows) cells[{r[axes[0]], r[axes[1]]}] = r.back();
  const std::vector<int> keep_x = stiffness_plot_stride(static_cast<int>(xs.size()), max_per_axis);
  const std::vector<int> keep_y = stiffness_plot_stride(static_cast<int>(ys.size()), max_per_axis);
  std::vector<double> x_values, y_values;
  for (int i : keep_x) x_values.push_back(xs[i]);
  for (int j : keep_y) y_values.push_back(ys[j]);
  nlohmann::json values = nlohmann::json::array();
  for (double y : y_values) {
    std::vector<double> row;
    for (double x : x_values) {
      const auto at = cells.find({x, y});
      row.push_back(at == cells.end() ? kStiffnessPlotNone : at->second);
    }
    values.push_back(json_numbers(row));
  }
  return nlohmann::json{{"file", std::filesystem::path(path).filename().string()},
                        {"x_label", columns[position[axes[0]]]},
                        {"y_label", columns[position[axes[1]]]},
                        {"x", json_numbers(x_values, 9)},
                        {"y", json_numbers(y_values, 9)},
                        {"value_label", "lowest translational stiffness"},
                        {"value_unit", "N/µm"},
                        {"values", values}};
}

Status add_stiffness_plots(const std::string& directory, nlohmann::json& report) {
  namespace fs = std::filesystem;
  std::error_code ignored;
  const fs::path bode = fs::path(directory) / kBodeCsv;
  if (fs::exists(bode, ignored)) {
    auto json = frequency_response_json(bode.string());
    if (!json) return json.error();
    report["frequency_response"] = std::move(*json);
  }
  const fs::path map = fs::path(directory) / kStiffnessMapCsv;
  if (fs::exists(map, ignored)) {
    auto json = stiffness_map_json(map.string());
    if (!json) return json.error();
    report["stiffness_map"] = std::move(*json);
  }
  return ok_status();
}

}  // namespace pkm::report
