#include "io/fixture_file.hpp"

#include <fmt/format.h>

#include <array>
#include <optional>

#include "io/csv_text.hpp"
#include "io/input_file.hpp"
#include "io/printable_text.hpp"

namespace pkm {
namespace {

namespace csv = csv_text;

constexpr std::array<std::string_view, 4> kFixtureColumns = {"target", "x", "y", "z"};

// A header line's value where the file must say exactly `expected` (units mm, frame tool).
Status fixture_expect_value(const std::string& source, int line, const csv::Directive& d,
                            std::string_view expected, std::string_view why) {
  if (d.value == expected) return ok_status();
  return csv::error_at(source, line, d.value_column, d.key,
                       fmt::format("expected {}, got '{}' ({})", expected, printable_text(d.value, 80), why));
}

}  // namespace

bool is_calibration_name(std::string_view name) {
  if (name.empty() || name.size() > 200 || name.front() == '#') return false;
  if (csv::trim(name) != name || name.find(',') != std::string_view::npos) return false;
  return printable_text(name) == name;
}

Result<std::vector<calibration::FixtureTarget>> parse_fixture_csv(std::string_view text,
                                                                  const std::string& source) {
  csv::Lines lines(text);
  std::string_view row;
  int units_line = 0, frame_line = 0;
  bool have_header = false;
  std::vector<calibration::FixtureTarget> targets;
  std::vector<int> target_lines;
  while (lines.next(row)) {
    const int line = lines.number();
    if (csv::is_blank(row)) continue;
    csv::Directive d;
    if (csv::directive(row, d)) {
      if (have_header)
        return csv::error_at(source, line, d.key_column, d.key, "header lines come before the column row");
      if (d.key == "units") {
        if (units_line > 0)
          return csv::error_at(source, line, d.key_column, d.key,
                               fmt::format("given twice (line {})", units_line));
        if (Status s = fixture_expect_value(source, line, d, "mm", "fixture positions are read in mm only");
            !s)
          return s.error();
        units_line = line;
      } else if (d.key == "frame") {
        if (frame_line > 0)
          return csv::error_at(source, line, d.key_column, d.key,
                               fmt::format("given twice (line {})", frame_line));
        if (Status s = fixture_expect_value(
                source, line, d, "tool", "targets are given from the tool point along the platform's axes");
            !s)
          return s.error();
        frame_line = line;
      } else if (d.key != "note") {
        return csv::error_at(
            source, line, d.key_column, d.key,
            "unknown header key (units, frame, note); a free comment must not start with 'word:'");
      }
      continue;
    }
    if (csv::trim(row).front() == '#') continue;
    const std::vector<csv::Field> fields = csv::split_row(row);
    if (!have_header) {
      if (units_line == 0)
        return csv::error_at(source, line, 1, "units",
                             "missing: the file must say '# units: mm' before the columns");
      if (frame_line == 0)
        return csv::error_at(source, line, 1, "frame",
                             "missing: the file must say '# frame: tool' before the columns");
      for (std::size_t c = 0; c < std::max(fields.size(), kFixtureColumns.size()); ++c) {
        if (c < fields.size() && c < kFixtureColumns.size() && fields[c].text == kFixtureColumns[c]) continue;
        const int column = c < fields.size() ? fields[c].column : static_cast<int>(row.size()) + 1;
        const std::string got =
            c < fields.size() ? printable_text(fields[c].text, 80) : std::string("nothing");
        if (c >= kFixtureColumns.size())
          return csv::error_at(source, line, column, got, "extra column: the columns are target,x,y,z");
        return csv::error_at(
            source, line, column, kFixtureColumns[c],
            fmt::format("expected column '{}' (target,x,y,z), got '{}'", kFixtureColumns[c], got));
      }
      have_header = true;
      continue;
    }
    if (fields.size() != kFixtureColumns.size()) {
      const bool extra = fields.size() > kFixtureColumns.size();
      return csv::error_at(source, line,
                           extra ? fields[kFixtureColumns.size()].column : static_cast<int>(row.size()) + 1,
                           extra ? std::string_view("(extra)") : kFixtureColumns[fields.size()],
                           fmt::format("expected 4 fields (target,x,y,z), got {}", fields.size()));
    }
    calibration::FixtureTarget target;
    if (!is_calibration_name(fields[0].text)) {
      return csv::error_at(
          source, line, fields[0].column, "target",
          fmt::format("'{}' is not a target name (printable, no comma)", printable_text(fields[0].text, 80)));
    }
    target.name = std::string(fields[0].text);
    for (std::size_t k = 0; k < targets.size(); ++k) {
      if (targets[k].name == target.name) {
        return csv::error_at(source, line, fields[0].column, "target",
                             fmt::format("'{}' is given twice (line {})", target.name, target_lines[k]));
      }
    }
    for (int axis = 0; axis < 3; ++axis) {
      auto value = csv::number(source, line, fields[static_cast<std::size_t>(axis) + 1],
                               kFixtureColumns[static_cast<std::size_t>(axis) + 1], "mm");
      if (!value) return value.error();
      target.position_mm[axis] = *value;
    }
    targets.push_back(std::move(target));
    target_lines.push_back(line);
  }
  if (!have_header) {
    return csv::error_at(source, std::max(1, lines.number()), 1, "target",
                         "no column row: expected '# units: mm', '# frame: tool' and 'target,x,y,z'");
  }
  if (targets.empty())
    return csv::error_at(source, lines.number(), 1, "target", "no targets after the column row");
  return targets;
}

Result<std::vector<calibration::FixtureTarget>> read_fixture_file(const std::string& path) {
  auto text = read_text_input(path, "fixture file");
  if (!text) return text.error();
  return parse_fixture_csv(*text, path);
}

std::string fixture_file_text(const std::vector<calibration::FixtureTarget>& targets) {
  std::string text = "# units: mm\n# frame: tool\ntarget,x,y,z\n";
  for (const calibration::FixtureTarget& t : targets) {
    text += fmt::format("{},{},{},{}\n", t.name, t.position_mm.x(), t.position_mm.y(), t.position_mm.z());
  }
  return text;
}

}  // namespace pkm
