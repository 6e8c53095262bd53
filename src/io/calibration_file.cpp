#include "io/calibration_file.hpp"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <algorithm>
#include <iterator>
#include <optional>

#include "core/units.hpp"
#include "machine/actuator_offsets.hpp"

namespace pkm {
namespace {

constexpr std::string_view kCalibrationKey = "calibration";
constexpr std::string_view kCalibrationNoteKey = "note";

// Files give angles in degrees (docs/machine-file.md); groups keep radians.
bool calibration_group_in_degrees(const GeometryGroup& group) {
  return group.unit == "rad";
}
std::string calibration_file_unit(const GeometryGroup& group) {
  return calibration_group_in_degrees(group) ? std::string("deg") : group.unit;
}
bool calibration_group_is_column(const GeometryGroup& group) {
  return group.columns() == 1 && group.column_names.front().empty();
}

// "A1..A6: x, y, z (mm)" or "dL1..dL6 (mm)": a group's rows and columns, for messages and comments.
std::string calibration_group_shape(const GeometryGroup& group) {
  const std::string rows = group.rows == 1
                               ? fmt::format("{}1", group.row_symbol)
                               : fmt::format("{}1..{}{}", group.row_symbol, group.row_symbol, group.rows);
  if (calibration_group_is_column(group)) return fmt::format("{} ({})", rows, calibration_file_unit(group));
  return fmt::format("{}: {} ({})", rows, fmt::join(group.column_names, ", "), calibration_file_unit(group));
}

// What a group's value must look like, for messages.
std::string calibration_group_expectation(const GeometryGroup& group) {
  if (calibration_group_is_column(group)) {
    return fmt::format("a list of {} numbers, {}", group.rows, calibration_group_shape(group));
  }
  return fmt::format("a list of {} rows of {} numbers, {}", group.rows, group.columns(),
                     calibration_group_shape(group));
}

// The key node of `key` in a mapping (errors about a value that is not there point at its key).
YAML::Node calibration_key_node(const YAML::Node& mapping, std::string_view key) {
  for (const auto& item : mapping) {
    if (item.first.IsScalar() && item.first.Scalar() == key) return item.first;
  }
  return mapping;
}

// The values of `group` from `node` (a list of rows; a one-column group may give a plain list of numbers), in
// the group's units.
Result<std::vector<double>> read_calibration_group(const YAML::Node& section, const YAML::Node& node,
                                                   const GeometryGroup& group, const YamlReader& reader) {
  const std::string key = fmt::format("{}.{}", kCalibrationKey, group.key);
  const std::string expected = calibration_group_expectation(group);
  if (node.IsNull()) {
    return reader.error_at(calibration_key_node(section, group.key), key,
                           fmt::format("expected {}, got nothing", expected));
  }
  if (!node.IsSequence()) return reader.error_at(node, key, fmt::format("expected {}", expected));
  if (static_cast<int>(node.size()) != group.rows) {
    return reader.error_at(node, key,
                           fmt::format("expected {}, got {}{}", expected, node.size(),
                                       calibration_group_is_column(group) ? "" : " rows"));
  }
  const double scale = calibration_group_in_degrees(group) ? rad_from_deg(1.0) : 1.0;
  std::vector<double> values;
  values.reserve(group.values.size());
  for (std::size_t r = 0; r < node.size(); ++r) {
    const YAML::Node row = node[r];
    const std::string row_key = fmt::format("{}[{}]", key, r);
    if (calibration_group_is_column(group)) {
      // A number, or a row of one number.
      const bool single = row.IsSequence() && row.size() == 1;
      if (!row.IsScalar() && !single) return reader.error_at(row, row_key, "expected a number");
      auto v = reader.number(single ? row[0] : row, single ? fmt::format("{}[0]", row_key) : row_key);
      if (!v) return v.error();
      values.push_back(*v * scale);
      continue;
    }
    if (!row.IsSequence() || static_cast<int>(row.size()) != group.columns()) {
      return reader.error_at(
          row, row_key,
          fmt::format("expected a row of {} numbers ({}), got {}", group.columns(),
                      fmt::join(group.column_names, ", "),
                      row.IsSequence() ? fmt::format("{}", row.size()) : std::string("no list")));
    }
    for (std::size_t c = 0; c < row.size(); ++c) {
      auto v = reader.number(row[c], fmt::format("{}[{}]", row_key, c));
      if (!v) return v.error();
      values.push_back(*v * scale);
    }
  }
  return values;
}

}  // namespace

Result<std::unique_ptr<Mechanism>> apply_calibration_section(const YAML::Node& root, const YamlReader& reader,
                                                             std::unique_ptr<Mechanism> mechanism) {
  const YAML::Node section = root[std::string(kCalibrationKey)];
  if (!section) return Result<std::unique_ptr<Mechanism>>(std::move(mechanism));
  std::vector<GeometryGroup> groups = mechanism->geometry_parameters();
  const bool has_offsets = std::any_of(groups.begin(), groups.end(),
                                       [](const GeometryGroup& g) { return g.key == kActuatorOffsetsKey; });
  // The groups the section may give: the mechanism's and, if it has none yet, the drive offsets.
  std::vector<GeometryGroup> allowed = groups;
  if (!has_offsets) {
    allowed.push_back(actuator_offsets_group(ActuatorVector::Zero(mechanism->actuator_count()),
                                             mechanism->actuators_are_angles()));
  }
  std::string allowed_list(kCalibrationNoteKey);
  for (const GeometryGroup& g : allowed) allowed_list += fmt::format(", {}", g.key);
  if (!section.IsMap()) {
    return reader.error_at(section.IsNull() ? calibration_key_node(root, kCalibrationKey) : section,
                           kCalibrationKey, fmt::format("expected a mapping with some of: {}", allowed_list));
  }
  for (const auto& item : section) {
    const std::string key = item.first.Scalar();  // a scalar: parse_yaml_document checked every key
    const bool known =
        key == kCalibrationNoteKey ||
        std::any_of(allowed.begin(), allowed.end(), [&](const GeometryGroup& g) { return g.key == key; });
    if (!known) {
      return reader.error_at(
          item.first, fmt::format("{}.{}", kCalibrationKey, key),
          fmt::format("unknown key for a {} (allowed here: {})", to_string(mechanism->type()), allowed_list));
    }
  }
  if (const YAML::Node note = section[std::string(kCalibrationNoteKey)]; note && !note.IsScalar()) {
    return reader.error_at(note.IsNull() ? calibration_key_node(section, kCalibrationNoteKey) : note,
                           fmt::format("{}.{}", kCalibrationKey, kCalibrationNoteKey),
                           note.IsNull() ? "expected a word or a text, got nothing"
                                         : "expected a word or a text, not a list or a mapping");
  }

  bool geometry_given = false;
  for (GeometryGroup& group : groups) {
    const YAML::Node node = section[group.key];
    if (!node) continue;
    auto values = read_calibration_group(section, node, group, reader);
    if (!values) return values.error();
    group.values = std::move(values.value());
    geometry_given = true;
  }
  std::optional<ActuatorVector> offsets;
  if (!has_offsets) {
    if (const YAML::Node node = section[std::string(kActuatorOffsetsKey)]) {
      auto values = read_calibration_group(section, node, allowed.back(), reader);
      if (!values) return values.error();
      offsets = ActuatorVector(
          Eigen::Map<const ActuatorVector>(values->data(), static_cast<Eigen::Index>(values->size())));
    }
  }

  if (geometry_given) {
    auto calibrated = mechanism->with_geometry(groups);
    if (!calibrated) {
      return reader.error_at(calibration_key_node(root, kCalibrationKey), kCalibrationKey,
                             fmt::format("the calibrated values do not make a valid {}: {}",
                                         to_string(mechanism->type()), calibrated.error().message));
    }
    mechanism = std::move(calibrated.value());
  }
  if (offsets) mechanism = with_actuator_offsets(std::move(mechanism), *offsets);
  return Result<std::unique_ptr<Mechanism>>(std::move(mechanism));
}

namespace {

// The text without its top-level `calibration:` block: from that key's line to the last indented line after
// it (its values, comments and blank lines among them). Blank lines and comments at column 0 after the block
// belong to the next key, and stay.
std::string without_calibration_block(std::string_view text) {
  std::vector<std::string_view> lines;
  for (std::size_t at = 0; at < text.size();) {
    const std::size_t end = text.find('\n', at);
    const std::size_t next = end == std::string_view::npos ? text.size() : end + 1;
    lines.push_back(text.substr(at, next - at));
    at = next;
  }
  const auto starts_block = [](std::string_view line) {
    if (line.substr(0, kCalibrationKey.size()) != kCalibrationKey) return false;
    std::size_t i = kCalibrationKey.size();
    while (i < line.size() && (line[i] == ' ' || line[i] == '\t')) ++i;
    return i < line.size() && line[i] == ':';
  };
  const auto is_blank = [](std::string_view line) {
    return line.find_first_not_of(" \t\r\n") == std::string_view::npos;
  };
  std::string out;
  out.reserve(text.size());
  for (std::size_t i = 0; i < lines.size(); ++i) {
    if (!starts_block(lines[i])) {
      out += lines[i];
      continue;
    }
    std::size_t last = i;
    for (std::size_t j = i + 1; j < lines.size(); ++j) {
      const std::string_view line = lines[j];
      if (is_blank(line) || line[0] == '#') continue;
      if (line[0] != ' ' && line[0] != '\t') break;
      last = j;
    }
    i = last;
  }
  return out;
}

// A YAML double-quoted scalar (escapes as JSON's, which YAML shares).
std::string yaml_quoted(std::string_view text) {
  std::string out = "\"";
  for (const char c : text) {
    switch (c) {
      case '"':
        out += "\\\"";
        break;
      case '\\':
        out += "\\\\";
        break;
      case '\n':
        out += "\\n";
        break;
      case '\t':
        out += "\\t";
        break;
      default:
        if (static_cast<unsigned char>(c) < 0x20 || c == 0x7f) {
          out += fmt::format("\\x{:02x}", static_cast<unsigned char>(c));
        } else {
          out += c;
        }
    }
  }
  out += '"';
  return out;
}

}  // namespace

std::string calibrated_machine_text(std::string_view original_yaml, const std::vector<GeometryGroup>& groups,
                                    std::string_view note) {
  // Keep the file's own line ends, so that the appended block does not mix them.
  const std::string_view eol = original_yaml.find("\r\n") != std::string_view::npos ? "\r\n" : "\n";
  std::string text = without_calibration_block(original_yaml);
  if (!text.empty() && text.back() != '\n') text += eol;
  fmt::format_to(std::back_inserter(text), "{}:{}", kCalibrationKey, eol);
  fmt::format_to(std::back_inserter(text),
                 "  # Written by pkm calibrate: these values replace the drawing's above "
                 "(docs/machine-file.md, Calibration).{}",
                 eol);
  if (!note.empty())
    fmt::format_to(std::back_inserter(text), "  {}: {}{}", kCalibrationNoteKey, yaml_quoted(note), eol);
  for (const GeometryGroup& group : groups) {
    // Shortest round-trip text of each double ({}): reading it back gives the same bits.
    const double scale = calibration_group_in_degrees(group) ? deg_from_rad(1.0) : 1.0;
    const auto value = [&](std::size_t i) { return group.values[i] * scale; };
    if (calibration_group_is_column(group)) {
      std::vector<double> column(group.values.size());
      for (std::size_t i = 0; i < column.size(); ++i) column[i] = value(i);
      fmt::format_to(std::back_inserter(text), "  {}: [{}]  # {}{}", group.key, fmt::join(column, ", "),
                     calibration_group_shape(group), eol);
      continue;
    }
    fmt::format_to(std::back_inserter(text), "  {}:  # {}{}", group.key, calibration_group_shape(group), eol);
    const auto columns = static_cast<std::size_t>(group.columns());
    for (std::size_t r = 0; r < static_cast<std::size_t>(group.rows); ++r) {
      std::vector<double> row(columns);
      for (std::size_t c = 0; c < columns; ++c) row[c] = value(r * columns + c);
      fmt::format_to(std::back_inserter(text), "    - [{}]{}", fmt::join(row, ", "), eol);
    }
  }
  return text;
}

}  // namespace pkm
