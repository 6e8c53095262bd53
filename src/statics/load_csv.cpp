// A per-line load file in CSV: the cutting load of each program line, as
// a CAM system's force prediction or a measurement gives it. The header names the columns:
//   line, then any of fx_N fy_N fz_N mx_Nmm my_Nmm mz_Nmm (a constant force and moment on the tool, base
//   frame) and tangential_N normal_N axial_N (split along the travel, as the --load keys)
// and each row is one program line's load; lines not listed carry none. Errors name file:line:column and the
// column's key.
#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <charconv>
#include <cmath>
#include <string>
#include <vector>

#include "io/csv_text.hpp"
#include "statics/load_keys.hpp"
#include "statics/load_model.hpp"

namespace pkm::statics {
namespace {

constexpr std::array<std::string_view, 10> kLoadCsvColumns = {
    "line", "fx_N", "fy_N", "fz_N", "mx_Nmm", "my_Nmm", "mz_Nmm", "tangential_N", "normal_N", "axial_N"};

// The field of `load` a column sets (line: none).
double* load_csv_field(CuttingLoad& load, std::string_view column) {
  if (column == "fx_N") return &load.force_N.x();
  if (column == "fy_N") return &load.force_N.y();
  if (column == "fz_N") return &load.force_N.z();
  if (column == "mx_Nmm") return &load.moment_Nmm.x();
  if (column == "my_Nmm") return &load.moment_Nmm.y();
  if (column == "mz_Nmm") return &load.moment_Nmm.z();
  if (column == "tangential_N") return &load.tangential_N;
  if (column == "normal_N") return &load.normal_N;
  if (column == "axial_N") return &load.axial_N;
  return nullptr;
}

// The load key whose checks a column's numbers get (load_keys.hpp).
std::string_view load_csv_key(std::string_view column) {
  if (column.front() == 'f') return "force";
  if (column.front() == 'm') return "moment";
  return column.substr(0, column.find('_'));  // tangential_N -> tangential
}

Error load_csv_error(const std::string& source, int line, int column, std::string_view key,
                     std::string_view message) {
  return Error{ErrorCode::bad_input, fmt::format("{}:{}:{}: {}: {}", source, line, column, key, message),
               ErrorLocation{source, line, column, std::string(key)}};
}

}  // namespace

Result<LoadModel> parse_load_csv(std::string_view text, const std::string& source_name) {
  std::vector<std::string_view> columns;
  LoadModel model;
  int file_line = 0;
  std::size_t at = 0;
  while (at <= text.size()) {
    const std::size_t end = std::min(text.find('\n', at), text.size());
    const std::string_view row = text.substr(at, end - at);
    at = end + 1;
    ++file_line;
    const std::string_view trimmed = csv_text::trim(row);
    if (trimmed.empty() || trimmed.front() == '#') {
      if (end == text.size()) break;
      continue;
    }
    const std::vector<csv_text::Field> fields = csv_text::split_row(row);
    if (columns.empty()) {
      for (const csv_text::Field& field : fields) {
        if (std::find(kLoadCsvColumns.begin(), kLoadCsvColumns.end(), field.text) == kLoadCsvColumns.end()) {
          return load_csv_error(source_name, file_line, field.column, field.text,
                                "unknown column (line, fx_N, fy_N, fz_N, mx_Nmm, my_Nmm, mz_Nmm, "
                                "tangential_N, normal_N, axial_N)");
        }
        if (std::find(columns.begin(), columns.end(), field.text) != columns.end())
          return load_csv_error(source_name, file_line, field.column, field.text, "column given twice");
        columns.push_back(field.text);
      }
      if (columns.front() != "line") {
        return load_csv_error(source_name, file_line, fields.front().column, columns.front(),
                              "the first column must be line (the program line the load is for)");
      }
      if (columns.size() < 2)
        return load_csv_error(source_name, file_line, 1, "line", "no load column after line");
      if (end == text.size()) break;
      continue;
    }
    if (fields.size() != columns.size()) {
      const int column =
          fields.size() > columns.size() ? fields[columns.size()].column : static_cast<int>(row.size()) + 1;
      return load_csv_error(
          source_name, file_line, column,
          fields.size() > columns.size() ? std::string_view("(extra)") : columns[fields.size()],
          fmt::format("expected {} fields as the header names, got {}", columns.size(), fields.size()));
    }
    BlockLoad block;
    for (std::size_t c = 0; c < columns.size(); ++c) {
      const csv_text::Field& field = fields[c];
      double value = 0.0;
      std::string_view number = field.text;
      if (number.size() > 1 && number.front() == '+') number.remove_prefix(1);
      const auto [stop, ec] = std::from_chars(number.data(), number.data() + number.size(), value);
      if (number.empty() || ec != std::errc() || stop != number.data() + number.size() ||
          !std::isfinite(value))
        return load_csv_error(source_name, file_line, field.column, columns[c],
                              fmt::format("expected a finite number, got '{}'", field.text));
      if (c == 0) {
        if (value < 1.0 || value != std::floor(value) || value > 1e9)
          return load_csv_error(source_name, file_line, field.column, "line",
                                fmt::format("expected a program line number ≥ 1, got '{}'", field.text));
        block.first_line = block.last_line = static_cast<int>(value);
        block.location = ErrorLocation{source_name, file_line, field.column, "line"};
        continue;
      }
      if (auto problem = load_number_problem(load_csv_key(columns[c]), value))
        return load_csv_error(source_name, file_line, field.column, columns[c], *problem);
      *load_csv_field(block.load, columns[c]) = value;
    }
    if (!model.blocks.empty() && block.first_line <= model.blocks.back().last_line) {
      return load_csv_error(source_name, file_line, fields.front().column, "line",
                            fmt::format("line {} after line {}: rows must be in ascending line order, "
                                        "each line once",
                                        block.first_line, model.blocks.back().last_line));
    }
    model.blocks.push_back(block);
    if (end == text.size()) break;
  }
  if (columns.empty())
    return load_csv_error(source_name, 1, 1, "line", "empty: expected a header (line,fx_N,fy_N,fz_N…)");
  model.blocks_ascending = true;
  return model;
}

}  // namespace pkm::statics
