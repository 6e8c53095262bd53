// The measurement file reader (measurement_file.hpp): the `# key: value` header, the column row checked
// against the machine's actuator count and the file's kind, then one observation per row, grouped by pose_id.
#include "io/measurement_file.hpp"

#include <fmt/format.h>

#include <filesystem>
#include <unordered_map>

#include "core/units.hpp"
#include "io/csv_text.hpp"
#include "io/fixture_file.hpp"
#include "io/input_file.hpp"
#include "io/printable_text.hpp"

namespace pkm {
namespace {

namespace csv = csv_text;
using calibration::MeasuredPose;
using calibration::MeasurementKind;
using calibration::MeasurementSet;

// What the header lines said, with where (line 0: not given).
struct MeasHeader {
  MeasurementKind kind = MeasurementKind::targets;
  int kind_line = 0, units_line = 0, frame_line = 0, sigma_line = 0, centre_line = 0, fixture_line = 0;
  int fixture_column = 0;
  std::string actuator_unit = "mm";
  int actuator_units_line = 0;
  double sigma_mm = 0.0;
  Eigen::Vector3d centre_mm = Eigen::Vector3d::Zero();
  std::string fixture;
};

constexpr std::string_view kMeasKeys =
    "kind, units, actuator_units, frame, sigma_mm, ballbar_centre_mm, fixture, machine, note";

Status meas_expect(const std::string& source, int line, const csv::Directive& d,
                   std::initializer_list<std::string_view> allowed, std::string_view why) {
  for (std::string_view a : allowed)
    if (d.value == a) return ok_status();
  std::string list;
  for (std::string_view a : allowed) {
    if (!list.empty()) list += " or ";
    list += a;
  }
  return csv::error_at(source, line, d.value_column, d.key,
                       fmt::format("expected {}, got '{}' ({})", list, printable_text(d.value, 80), why));
}

Result<Eigen::Vector3d> meas_centre(const std::string& source, int line, const csv::Directive& d) {
  Eigen::Vector3d centre;
  int count = 0;
  std::size_t at = 0;
  const std::string_view v = d.value;
  while (at < v.size()) {
    while (at < v.size() && (v[at] == ' ' || v[at] == '\t' || v[at] == ',')) ++at;
    if (at == v.size()) break;
    std::size_t end = at;
    while (end < v.size() && v[end] != ' ' && v[end] != '\t' && v[end] != ',') ++end;
    const csv::Field field{v.substr(at, end - at), d.value_column + static_cast<int>(at)};
    if (count == 3)
      return csv::error_at(source, line, field.column, d.key, "expected 3 numbers (x y z, mm), got more");
    auto number = csv::number(source, line, field, d.key, "mm");
    if (!number) return number.error();
    centre[count++] = *number;
    at = end;
  }
  if (count != 3)
    return csv::error_at(source, line, d.value_column, d.key,
                         fmt::format("expected 3 numbers (x y z, mm), got {}", count));
  return centre;
}

// One header line into `h`; `seen` keeps the line of each key, which may be given once (note: any number).
Status meas_directive(const std::string& source, int line, const csv::Directive& d, MeasHeader& h,
                      std::vector<std::pair<std::string_view, int>>& seen) {
  if (d.key == "note" || d.key == "machine") return ok_status();
  for (const auto& [key, first] : seen)
    if (key == d.key)
      return csv::error_at(source, line, d.key_column, d.key, fmt::format("given twice (line {})", first));
  seen.emplace_back(d.key, line);
  if (d.key == "kind") {
    if (Status s = meas_expect(source, line, d, {"tracker", "ballbar"}, "what was measured"); !s) return s;
    h.kind = d.value == "tracker" ? MeasurementKind::targets : MeasurementKind::ballbar;
    h.kind_line = line;
  } else if (d.key == "units") {
    if (Status s =
            meas_expect(source, line, d, {"mm"}, "positions, distances and sigmas are read in mm only");
        !s)
      return s;
    h.units_line = line;
  } else if (d.key == "actuator_units") {
    if (Status s = meas_expect(source, line, d, {"mm", "deg", "rad"}, "the unit of L1..Ln"); !s) return s;
    h.actuator_unit = std::string(d.value);
    h.actuator_units_line = line;
  } else if (d.key == "frame") {
    if (Status s =
            meas_expect(source, line, d, {"base"}, "measured positions are read in the machine's base frame");
        !s)
      return s;
    h.frame_line = line;
  } else if (d.key == "sigma_mm") {
    auto sigma = csv::number(source, line, {d.value, d.value_column}, d.key, "mm");
    if (!sigma) return sigma.error();
    if (!(*sigma > 0.0))
      return csv::error_at(source, line, d.value_column, d.key, "a standard deviation must be above 0 mm");
    h.sigma_mm = *sigma;
    h.sigma_line = line;
  } else if (d.key == "ballbar_centre_mm") {
    auto centre = meas_centre(source, line, d);
    if (!centre) return centre.error();
    h.centre_mm = *centre;
    h.centre_line = line;
  } else if (d.key == "fixture") {
    if (d.value.empty()) return csv::error_at(source, line, d.value_column, d.key, "expected a file name");
    h.fixture = std::string(d.value);
    h.fixture_line = line;
    h.fixture_column = d.value_column;
  } else {
    return csv::error_at(
        source, line, d.key_column, d.key,
        fmt::format("unknown header key ({}); a free comment must not start with 'word:'", kMeasKeys));
  }
  return ok_status();
}

// What must have been said before the column row (on line `line`), and what must not for this kind.
Status meas_check_header(const std::string& source, int line, const MeasHeader& h,
                         const MeasurementReadOptions& options) {
  if (h.kind_line == 0)
    return csv::error_at(source, line, 1, "kind",
                         "missing: '# kind: tracker' or '# kind: ballbar' before the columns");
  if (h.units_line == 0)
    return csv::error_at(source, line, 1, "units",
                         "missing: the file must say '# units: mm' before the columns");
  if (h.frame_line == 0)
    return csv::error_at(source, line, 1, "frame",
                         "missing: the file must say '# frame: base' before the columns");
  if (options.actuators_are_angles && h.actuator_units_line == 0) {
    return csv::error_at(source, line, 1, "actuator_units",
                         "missing: the machine's actuators turn; say '# actuator_units: deg' (or rad)");
  }
  if (!options.actuators_are_angles && h.actuator_unit != "mm") {
    return csv::error_at(source, h.actuator_units_line, 1, "actuator_units",
                         fmt::format("{}: the machine's actuators are lengths, read in mm", h.actuator_unit));
  }
  if (options.actuators_are_angles && h.actuator_unit == "mm") {
    return csv::error_at(source, h.actuator_units_line, 1, "actuator_units",
                         "mm: the machine's actuators turn; expected deg or rad");
  }
  const bool ballbar = h.kind == MeasurementKind::ballbar;
  if (ballbar && h.centre_line == 0) {
    return csv::error_at(source, line, 1, "ballbar_centre_mm",
                         "missing: a ballbar file gives its ball's centre, '# ballbar_centre_mm: x y z'");
  }
  if (!ballbar && h.centre_line > 0)
    return csv::error_at(source, h.centre_line, 1, "ballbar_centre_mm", "only for '# kind: ballbar'");
  if (ballbar && h.fixture_line > 0)
    return csv::error_at(source, h.fixture_line, 1, "fixture", "only for '# kind: tracker'");
  return ok_status();
}

// The column row against the kind and the actuator count; true in `sigma` when a sigma column ends it.
Status meas_columns(const std::string& source, int line, std::string_view row,
                    const std::vector<csv::Field>& fields, const MeasHeader& h, int n, bool& sigma) {
  std::vector<std::string> expected = {"pose_id"};
  for (int j = 1; j <= n; ++j) expected.push_back(fmt::format("L{}", j));
  if (h.kind == MeasurementKind::targets)
    expected.insert(expected.end(), {"target", "x", "y", "z"});
  else
    expected.emplace_back("distance");
  const std::string what = h.kind == MeasurementKind::targets
                               ? fmt::format("pose_id,L1..L{},target,x,y,z[,sigma]", n)
                               : fmt::format("pose_id,L1..L{},distance[,sigma]", n);
  sigma = fields.size() == expected.size() + 1 && fields.back().text == "sigma";
  const std::size_t count = std::max(fields.size(), expected.size() + (sigma ? 1 : 0));
  for (std::size_t c = 0; c < count; ++c) {
    if (c < expected.size() && c < fields.size() && fields[c].text == expected[c]) continue;
    if (sigma && c == expected.size()) continue;
    const int column = c < fields.size() ? fields[c].column : static_cast<int>(row.size()) + 1;
    const std::string got = c < fields.size() ? printable_text(fields[c].text, 80) : std::string("nothing");
    if (c >= expected.size())
      return csv::error_at(source, line, column, got, fmt::format("extra column: the columns are {}", what));
    const bool actuator_expected = c >= 1 && c <= static_cast<std::size_t>(n);
    const bool actuator_given = c < fields.size() && fields[c].text.size() > 1 &&
                                fields[c].text.front() == 'L' &&
                                fields[c].text.find_first_not_of("0123456789", 1) == std::string_view::npos;
    if (actuator_expected || actuator_given) {
      return csv::error_at(
          source, line, column, expected[c],
          fmt::format("expected column '{}', got '{}': the machine has {} actuators, so the file "
                      "gives L1..L{}",
                      expected[c], got, n, n));
    }
    return csv::error_at(source, line, column, expected[c],
                         fmt::format("expected column '{}', got '{}' (kind {}: {})", expected[c], got,
                                     h.kind == MeasurementKind::targets ? "tracker" : "ballbar", what));
  }
  return ok_status();
}

// The sigma of a row: its own (sigma column, not empty) or the header's default.
Result<double> meas_sigma(const std::string& source, int line, const std::vector<csv::Field>& fields,
                          bool sigma_column, const MeasHeader& h) {
  if (sigma_column && !fields.back().text.empty()) {
    auto sigma = csv::number(source, line, fields.back(), "sigma", "mm");
    if (!sigma) return sigma.error();
    if (!(*sigma > 0.0))
      return csv::error_at(source, line, fields.back().column, "sigma",
                           "a standard deviation must be above 0 mm");
    return *sigma;
  }
  if (h.sigma_line > 0) return h.sigma_mm;
  const int column = sigma_column ? fields.back().column : 1;
  return csv::error_at(source, line, column, "sigma",
                       "no standard deviation: give a sigma column or a '# sigma_mm: S' header line");
}

// The readings of a row in the machine's units (mm or rad), checked against its travel.
Result<ActuatorVector> meas_readings(const std::string& source, int line,
                                     const std::vector<csv::Field>& fields, int n, const MeasHeader& h,
                                     const MeasurementReadOptions& options) {
  ActuatorVector readings(n);
  const bool degrees = h.actuator_unit == "deg";
  const auto file_units = [&](double internal) { return degrees ? deg_from_rad(internal) : internal; };
  for (int j = 0; j < n; ++j) {
    const csv::Field& field = fields[static_cast<std::size_t>(j) + 1];
    const std::string key = fmt::format("L{}", j + 1);
    auto value = csv::number(source, line, field, key, h.actuator_unit);
    if (!value) return value.error();
    const double internal = degrees ? rad_from_deg(*value) : *value;
    const bool below = options.actuator_min && internal < *options.actuator_min;
    const bool above = options.actuator_max && internal > *options.actuator_max;
    if (below || above) {
      return csv::error_at(
          source, line, field.column, key,
          fmt::format("{} {} is {} the machine's travel ({} {:g} {}): the pose cannot have been reached",
                      field.text, h.actuator_unit, below ? "below" : "above", below ? "min" : "max",
                      file_units(below ? *options.actuator_min : *options.actuator_max), h.actuator_unit));
    }
    readings[j] = internal;
  }
  return readings;
}

struct MeasReader {
  const std::string& source;
  const MeasurementReadOptions& options;
  const FixtureLoader& load_fixture;
  MeasHeader header;
  bool sigma_column = false;
  MeasurementSet set;
  std::unordered_map<std::string, std::size_t> pose_of_id;

  // The fixture of a tracker file, once the header is complete (the column row is on `line`). The loader
  // decides what a missing name means; its errors without a place of their own (a file that cannot be read)
  // get the place of the `# fixture:` line.
  Status fixture(int line) {
    if (header.kind != MeasurementKind::targets) return ok_status();
    const bool given = !options.fixture_path.empty();
    auto targets = load_fixture(given ? options.fixture_path : header.fixture);
    if (!targets) {
      if (given || !targets.error().location.file.empty()) return targets.error();
      const bool named = header.fixture_line > 0;
      Error error = csv::error_at(source, named ? header.fixture_line : line,
                                  named ? header.fixture_column : 1, "fixture", targets.error().message);
      error.code = targets.error().code;
      return error;
    }
    set.fixture = std::move(*targets);
    return ok_status();
  }

  // One data row.
  Status row(int line, std::string_view text, const std::vector<csv::Field>& fields) {
    const int n = options.actuator_count;
    const std::size_t columns = static_cast<std::size_t>(n) +
                                (header.kind == MeasurementKind::targets ? 5 : 2) + (sigma_column ? 1 : 0);
    if (fields.size() != columns) {
      const bool extra = fields.size() > columns;
      return csv::error_at(
          source, line, extra ? fields[columns].column : static_cast<int>(text.size()) + 1,
          extra ? "(extra)" : "(missing)",
          fmt::format("expected {} fields as the column row names, got {}", columns, fields.size()));
    }
    if (!is_calibration_name(fields[0].text)) {
      return csv::error_at(
          source, line, fields[0].column, "pose_id",
          fmt::format("'{}' is not a pose name (printable, no comma)", printable_text(fields[0].text, 80)));
    }
    auto readings = meas_readings(source, line, fields, n, header, options);
    if (!readings) return readings.error();
    auto sigma = meas_sigma(source, line, fields, sigma_column, header);
    if (!sigma) return sigma.error();
    const std::string id(fields[0].text);
    auto [found, inserted] = pose_of_id.try_emplace(id, set.poses.size());
    if (inserted) {
      MeasuredPose pose;
      pose.id = id;
      pose.readings = *readings;
      pose.line = line;
      set.poses.push_back(std::move(pose));
    }
    MeasuredPose& pose = set.poses[found->second];
    for (int j = 0; j < n; ++j) {
      if (pose.readings[j] != (*readings)[j]) {
        const csv::Field& field = fields[static_cast<std::size_t>(j) + 1];
        return csv::error_at(
            source, line, field.column, fmt::format("L{}", j + 1),
            fmt::format("pose {} reads {} here but differently on line {}: the rows of one pose "
                        "repeat its readings",
                        id, field.text, pose.line));
      }
    }
    const std::size_t first = static_cast<std::size_t>(n) + 1;
    if (header.kind == MeasurementKind::ballbar) {
      auto distance = csv::number(source, line, fields[first], "distance", "mm");
      if (!distance) return distance.error();
      if (!(*distance > 0.0))
        return csv::error_at(source, line, fields[first].column, "distance",
                             "a ballbar length must be above 0 mm");
      pose.distances.push_back({*distance, *sigma, line});
      return ok_status();
    }
    const csv::Field& name = fields[first];
    int target = -1;
    for (std::size_t k = 0; k < set.fixture.size(); ++k)
      if (set.fixture[k].name == name.text) target = static_cast<int>(k);
    if (target < 0) {
      std::string names;
      for (std::size_t k = 0; k < set.fixture.size() && k < 12; ++k) {
        if (k > 0) names += ", ";
        names += set.fixture[k].name;
      }
      return csv::error_at(
          source, line, name.column, "target",
          fmt::format("'{}' is not a target of the fixture ({}{})", printable_text(name.text, 80), names,
                      set.fixture.size() > 12 ? ", …" : ""));
    }
    for (const calibration::TargetObservation& seen : pose.targets) {
      if (seen.target == target) {
        return csv::error_at(source, line, name.column, "target",
                             fmt::format("pose {} measures {} twice (line {})", id, name.text, seen.line));
      }
    }
    calibration::TargetObservation observation;
    observation.target = target;
    observation.sigma_mm = *sigma;
    observation.line = line;
    static constexpr std::string_view kAxes[3] = {"x", "y", "z"};
    for (int axis = 0; axis < 3; ++axis) {
      auto value = csv::number(source, line, fields[first + 1 + static_cast<std::size_t>(axis)],
                               kAxes[static_cast<std::size_t>(axis)], "mm");
      if (!value) return value.error();
      observation.position_mm[axis] = *value;
    }
    pose.targets.push_back(observation);
    return ok_status();
  }
};

}  // namespace

MeasurementReadOptions measurement_options_for(const Machine& machine, int min_poses) {
  MeasurementReadOptions options;
  options.actuator_count = machine.mechanism->actuator_count();
  options.actuators_are_angles = machine.mechanism->actuators_are_angles();
  options.actuator_min = machine.limits.min;
  options.actuator_max = machine.limits.max;
  options.min_poses = min_poses;
  return options;
}

Result<MeasurementSet> parse_measurement_csv(std::string_view text, const std::string& source,
                                             const MeasurementReadOptions& options,
                                             const FixtureLoader& load_fixture) {
  MeasReader reader{source, options, load_fixture, {}, false, {}, {}};
  reader.set.source = source;
  std::vector<std::pair<std::string_view, int>> seen;
  csv::Lines lines(text);
  std::string_view row;
  int header_line = 0, last_row_line = 0;
  while (lines.next(row)) {
    const int line = lines.number();
    if (csv::is_blank(row)) continue;
    csv::Directive d;
    if (csv::directive(row, d)) {
      if (header_line > 0)
        return csv::error_at(source, line, d.key_column, d.key, "header lines come before the column row");
      if (Status s = meas_directive(source, line, d, reader.header, seen); !s) return s.error();
      continue;
    }
    if (csv::trim(row).front() == '#') continue;
    const std::vector<csv::Field> fields = csv::split_row(row);
    if (header_line == 0) {
      if (Status s = meas_check_header(source, line, reader.header, options); !s) return s.error();
      if (Status s = meas_columns(source, line, row, fields, reader.header, options.actuator_count,
                                  reader.sigma_column);
          !s)
        return s.error();
      if (Status s = reader.fixture(line); !s) return s.error();
      reader.set.kind = reader.header.kind;
      reader.set.ballbar_centre_mm = reader.header.centre_mm;
      header_line = line;
      continue;
    }
    if (Status s = reader.row(line, row, fields); !s) return s.error();
    last_row_line = line;
  }
  if (header_line == 0) {
    return csv::error_at(source, std::max(1, lines.number()), 1, "pose_id",
                         "no column row: expected the header lines (# kind, # units, # frame) and "
                         "'pose_id,L1,…' (docs/calibration.md)");
  }
  if (reader.set.poses.empty())
    return csv::error_at(source, header_line, 1, "pose_id", "no measurements after the column row");
  if (static_cast<int>(reader.set.poses.size()) < options.min_poses) {
    return csv::error_at(source, last_row_line, 1, "pose_id",
                         fmt::format("{} poses, at least {} needed to identify the parameters",
                                     reader.set.poses.size(), options.min_poses));
  }
  return std::move(reader.set);
}

Result<MeasurementSet> parse_measurement_csv(std::string_view text, const std::string& source,
                                             const MeasurementReadOptions& options,
                                             const std::vector<calibration::FixtureTarget>& fixture) {
  return parse_measurement_csv(text, source, options, [&fixture](const std::string&) {
    return Result<std::vector<calibration::FixtureTarget>>(fixture);
  });
}

Result<MeasurementSet> read_measurement_file(const std::string& path, const MeasurementReadOptions& options) {
  auto text = read_text_input(path, "measurement file");
  if (!text) return text.error();
  const FixtureLoader loader = [&](const std::string& name) {
    if (name.empty()) {
      return Result<std::vector<calibration::FixtureTarget>>(
          make_error(ErrorCode::bad_input,
                     "missing: a tracker file needs the targets' positions on the platform, '# fixture: "
                     "FILE' (or a fixture "
                     "file given with it)"));
    }
    std::filesystem::path fixture(name);
    // The file's own `# fixture:` name is relative to the file, so that a folder of measurements moves whole.
    if (options.fixture_path.empty() && fixture.is_relative())
      fixture = std::filesystem::path(path).parent_path() / fixture;
    return read_fixture_file(fixture.string());
  };
  return parse_measurement_csv(*text, path, options, loader);
}

}  // namespace pkm
