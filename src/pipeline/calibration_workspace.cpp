#include "pipeline/calibration_workspace.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <charconv>
#include <cmath>
#include <filesystem>
#include <limits>
#include <nlohmann/json.hpp>
#include <string_view>
#include <system_error>

#include "calibration/plan_jacobian.hpp"
#include "io/csv_text.hpp"
#include "io/input_file.hpp"
#include "io/output_manifest.hpp"
#include "io/pose_input.hpp"
#include "pipeline/calibration_setup.hpp"

namespace pkm::pipeline {
namespace {

namespace fs = std::filesystem;

// Readings of plan.csv are written with 9 decimals (mm or deg): beyond this they are another machine's.
constexpr double kCalwsReadingTolerance = 1e-6;

// "FILE: KEY: message" (or "FILE: message" without a key), bad_input, with the file and key as fields.
Error calws_error(const std::string& file, std::string_view key, const std::string& message) {
  return Error{
      ErrorCode::bad_input,
      key.empty() ? fmt::format("{}: {}", file, message) : fmt::format("{}: {}: {}", file, key, message),
      ErrorLocation{file, 0, 0, std::string(key)}};
}

const nlohmann::json* calws_member(const nlohmann::json& object, const char* key) {
  const auto it = object.find(key);
  return it == object.end() ? nullptr : &*it;
}

// A reading column's name "L<k>": k, else 0.
int calws_reading_column(std::string_view name) {
  if (name.size() < 2 || name[0] != 'L') return 0;
  int k = 0;
  const auto [end, ec] = std::from_chars(name.data() + 1, name.data() + name.size(), k);
  return ec == std::errc() && end == name.data() + name.size() && k > 0 ? k : 0;
}

std::vector<std::string> calws_split_names(const std::string& text) {
  std::vector<std::string> names;
  for (const csv_text::Field& f : csv_text::split_row(text)) names.emplace_back(f.text);
  return names;
}

// The summary of `pkm calibrate plan`, as a JSON object.
Result<nlohmann::json> calws_read_summary(const std::string& path) {
  auto text = read_text_input(path, "calibration plan summary");
  if (!text) return text.error();
  nlohmann::json summary = nlohmann::json::parse(*text, nullptr, false);
  if (summary.is_discarded() || !summary.is_object())
    return calws_error(path, "", "not JSON: expected the summary.json that `pkm calibrate plan` writes");
  const nlohmann::json* command = calws_member(summary, "command");
  if (!command || !command->is_string() || command->get<std::string>() != "calibrate plan") {
    return calws_error(path, "command",
                       fmt::format("this is not the summary of `pkm calibrate plan` (command {}): give the "
                                   "directory `pkm calibrate plan --out DIR` wrote",
                                   command ? command->dump() : std::string("missing")));
  }
  return summary;
}

// The plan's parameters (summary.json `parameters`) must be this machine's: another list means another
// mechanism type (or another actuator count: the drive offsets are per actuator).
Status calws_check_parameters(const std::string& path, const nlohmann::json& summary,
                              const calibration::ParameterLayout& layout, const Machine& machine) {
  const nlohmann::json* parameters = calws_member(summary, "parameters");
  if (!parameters || !parameters->is_array())
    return calws_error(path, "parameters", "missing: expected the list of the plan's parameters");
  std::vector<std::string> names;
  for (const nlohmann::json& p : *parameters) {
    const nlohmann::json* name = p.is_object() ? calws_member(p, "name") : nullptr;
    if (!name || !name->is_string())
      return calws_error(path, "parameters", "an entry without a name: expected {\"name\": ..., ...}");
    names.push_back(name->get<std::string>());
  }
  const std::string type(to_string(machine.mechanism->type()));
  const auto span = [](const std::vector<std::string>& list) {
    return list.empty() ? std::string("none") : fmt::format("{} … {}", list.front(), list.back());
  };
  if (names.size() != layout.names.size()) {
    return calws_error(
        path, "parameters",
        fmt::format("the plan was made for a machine with {} calibration parameters ({}), this "
                    "{} has {} ({}): a plan made for another machine type",
                    names.size(), span(names), type, layout.names.size(), span(layout.names)));
  }
  for (std::size_t i = 0; i < names.size(); ++i) {
    if (names[i] != layout.names[i]) {
      return calws_error(
          path, "parameters",
          fmt::format("parameter {} of the plan is {}, this {}'s is {}: a plan made for another "
                      "machine type",
                      i + 1, names[i], type, layout.names[i]));
    }
  }
  return ok_status();
}

// "triangular plate, radius 100 mm" (calibration_instrument_json): the radius, 0 when the text is not that.
double calws_plate_radius(std::string_view text) {
  constexpr std::string_view kPrefix = "triangular plate, radius ";
  constexpr std::string_view kSuffix = " mm";
  if (text.size() <= kPrefix.size() + kSuffix.size() || text.substr(0, kPrefix.size()) != kPrefix ||
      text.substr(text.size() - kSuffix.size()) != kSuffix)
    return 0.0;
  const std::string_view number = text.substr(kPrefix.size(), text.size() - kPrefix.size() - kSuffix.size());
  double radius = 0.0;
  const auto [end, ec] = std::from_chars(number.data(), number.data() + number.size(), radius);
  return ec == std::errc() && end == number.data() + number.size() && std::isfinite(radius) ? radius : 0.0;
}

// The instrument of summary.json: σ, and the ballbar's centre or the tracker's targets. A fixture file is
// taken as the plan named it (relative to the directory pkm ran in), else relative to the plan's directory.
Result<CalibrationInstrument> calws_instrument(const std::string& path, const std::string& directory,
                                               const nlohmann::json& summary) {
  const nlohmann::json* instrument = calws_member(summary, "instrument");
  if (!instrument || !instrument->is_object())
    return calws_error(path, "instrument", "missing: expected the instrument the plan is measured with");
  CalibrationInstrument out;
  const nlohmann::json* sigma = calws_member(*instrument, "sigma_mm");
  if (!sigma || !sigma->is_number() || !(sigma->get<double>() > 0.0) || !std::isfinite(sigma->get<double>()))
    return calws_error(path, "instrument.sigma_mm", "expected the measurement's standard deviation, mm, > 0");
  out.sigma_mm = sigma->get<double>();
  const nlohmann::json* kind = calws_member(*instrument, "kind");
  const std::string kind_text = kind && kind->is_string() ? kind->get<std::string>() : std::string();
  if (kind_text == "ballbar") {
    const nlohmann::json* centre = calws_member(*instrument, "ballbar_centre_mm");
    if (!centre || !centre->is_array() || centre->size() != 3 ||
        !std::all_of(centre->begin(), centre->end(), [](const nlohmann::json& v) { return v.is_number(); }))
      return calws_error(path, "instrument.ballbar_centre_mm",
                         "expected the ball's centre as three numbers, mm");
    out.ballbar_centre_mm =
        Eigen::Vector3d((*centre)[0].get<double>(), (*centre)[1].get<double>(), (*centre)[2].get<double>());
    return out;
  }
  if (kind_text != "tracker")
    return calws_error(path, "instrument.kind", "expected \"tracker\" or \"ballbar\"");
  const nlohmann::json* fixture = calws_member(*instrument, "fixture");
  if (!fixture || !fixture->is_string())
    return calws_error(path, "instrument.fixture", "expected the plate or the fixture file the plan names");
  const std::string fixture_text = fixture->get<std::string>();
  if (const double radius = calws_plate_radius(fixture_text); radius > 0.0) {
    out.plate_radius_mm = radius;
    return out;
  }
  fs::path file(fixture_text);
  std::error_code ec;
  if (file.is_relative() && !fs::exists(file, ec)) {
    const fs::path beside = fs::path(directory) / file;
    if (fs::exists(beside, ec)) file = beside;
  }
  if (!fs::exists(file, ec)) {
    return calws_error(path, "instrument.fixture",
                       fmt::format("the fixture file {} is not there (neither from the current directory nor "
                                   "from {})",
                                   fixture_text, directory));
  }
  out.fixture_path = file.string();
  return out;
}

// plan.csv's column row against this machine's: "pose_id", its pose columns, L1..Ln.
Status calws_check_columns(const std::string& path, int line, std::string_view row,
                           const Mechanism& mechanism) {
  const std::vector<csv_text::Field> fields = csv_text::split_row(row);
  if (fields.empty() || fields[0].text != "pose_id") {
    return csv_text::error_at(path, line, 1, "pose_id",
                              "expected the column row of `pkm calibrate plan` (pose_id, the pose, L1..Ln)");
  }
  const std::vector<std::string> expected = calws_split_names(calibration_pose_header(mechanism));
  std::size_t pose_columns = 1;
  while (pose_columns < fields.size() && calws_reading_column(fields[pose_columns].text) == 0) ++pose_columns;
  std::vector<std::string> got;
  for (std::size_t i = 1; i < pose_columns; ++i) got.emplace_back(fields[i].text);
  if (got != expected) {
    return csv_text::error_at(
        path, line, fields.size() > 1 ? fields[1].column : 1, "pose",
        fmt::format("the plan's poses are ({}), a {}'s are ({}): a plan made for another machine type",
                    fmt::join(got, ","), to_string(mechanism.type()), fmt::join(expected, ",")));
  }
  const int n = mechanism.actuator_count();
  const int readings = static_cast<int>(fields.size() - pose_columns);
  for (int k = 1; k <= readings; ++k) {
    const csv_text::Field& f = fields[pose_columns + static_cast<std::size_t>(k - 1)];
    if (calws_reading_column(f.text) != k)
      return csv_text::error_at(path, line, f.column, f.text, fmt::format("expected column 'L{}'", k));
  }
  if (readings != n) {
    const csv_text::Field& at = readings > 0 ? fields.back() : fields[pose_columns - 1];
    return csv_text::error_at(
        path, line, at.column, readings > 0 ? at.text : "L1",
        fmt::format(
            "the plan has {} actuator columns, the {} has {} actuators: a plan made for another machine",
            readings, to_string(mechanism.type()), n));
  }
  return ok_status();
}

// The rows of plan.csv: each pose completed by `model`, which must reach it; readings compared with its IK.
Status calws_read_rows(const std::string& path, const std::string& text, const Mechanism& model,
                       CalibrationPlanFiles& plan) {
  csv_text::Lines lines(text);
  std::string_view row;
  bool header = false;
  double worst = 0.0;
  std::string worst_id;
  const char* unit = actuator_unit_name(model);
  std::vector<std::string> columns = calws_split_names(calibration_pose_header(model));
  const std::size_t pose_count = columns.size();
  for (int j = 1; j <= model.actuator_count(); ++j) columns.push_back(fmt::format("L{}", j));
  while (lines.next(row)) {
    if (csv_text::is_blank(row)) continue;
    if (!header) {
      if (Status ok = calws_check_columns(path, lines.number(), row, model); !ok) return ok;
      header = true;
      continue;
    }
    const std::vector<csv_text::Field> fields = csv_text::split_row(row);
    if (fields.size() != columns.size() + 1) {
      return csv_text::error_at(
          path, lines.number(), 1, "row",
          fmt::format("{} fields, the column row has {}", fields.size(), columns.size() + 1));
    }
    const std::string id(fields[0].text);
    if (id.empty()) return csv_text::error_at(path, lines.number(), 1, "pose_id", "empty");
    std::vector<double> pose_values, readings;
    for (std::size_t i = 1; i < fields.size(); ++i) {
      const std::string& column = columns[i - 1];
      const bool reading = i > pose_count;
      const bool angle = column.size() > 4 && column.compare(column.size() - 4, 4, "_deg") == 0;
      const char* value_unit = angle ? "deg" : "mm";
      auto value = csv_text::number(path, lines.number(), fields[i], column, reading ? unit : value_unit);
      if (!value) return value.error();
      (reading ? readings : pose_values).push_back(*value);
    }
    auto pose = pose_from_user(model, pose_values, "pose");
    if (!pose) return csv_text::error_at(path, lines.number(), 1, id, pose.error().message);
    auto ik = model.inverse(*pose);
    if (!ik) {
      return csv_text::error_at(
          path, lines.number(), 1, id,
          fmt::format("this machine cannot reach the planned pose ({}): a plan made for another machine",
                      ik.error().message));
    }
    const std::vector<double> own = user_from_actuators(model, *ik);
    for (std::size_t j = 0; j < own.size(); ++j) {
      const double difference = std::abs(own[j] - readings[j]);
      if (!(difference <= worst) && std::isfinite(difference)) {
        worst = difference;
        worst_id = id;
      }
    }
    plan.pose_ids.push_back(id);
    plan.poses.push_back(*pose);
    plan.lines.push_back(lines.number());
  }
  if (!header) return calws_error(path, "", "empty: expected the column row and the planned poses");
  if (plan.poses.empty()) return calws_error(path, "", "no planned poses");
  if (worst > kCalwsReadingTolerance) {
    plan.warnings.push_back(fmt::format(
        "{}: the readings differ from this machine's inverse kinematics of the planned poses by up to {:.4g} "
        "{} "
        "(pose {}): the plan was made for another geometry, or before a calibration; its poses are used",
        path, worst, unit, worst_id));
  }
  return ok_status();
}

}  // namespace

Result<CalibrationPlanFiles> read_calibration_plan(const Machine& machine, const std::string& directory) {
  std::error_code ec;
  if (!fs::is_directory(directory, ec)) {
    return Error{
        ErrorCode::io,
        fmt::format("{}: not a directory: expected the output directory of `pkm calibrate plan`", directory),
        ErrorLocation{directory, 0, 0, ""}};
  }
  const std::string summary_path = (fs::path(directory) / "summary.json").string();
  const std::string plan_path = (fs::path(directory) / "plan.csv").string();
  auto summary = calws_read_summary(summary_path);
  if (!summary) return summary.error();
  auto plan_text = read_text_input(plan_path, "calibration plan");
  if (!plan_text) return plan_text.error();
  auto model = calibration_model(machine);
  if (!model) return model.error();
  auto layout = calibration::parameter_layout(**model);
  if (!layout) return layout.error();

  CalibrationPlanFiles plan;
  plan.directory = directory;
  // The column row first: it tells another actuator count or pose more plainly than the parameters' names.
  {
    csv_text::Lines lines(*plan_text);
    std::string_view row;
    while (lines.next(row) && csv_text::is_blank(row)) {
    }
    if (!csv_text::is_blank(row)) {
      if (Status ok = calws_check_columns(plan_path, lines.number(), row, **model); !ok) return ok.error();
    }
  }
  if (Status ok = calws_check_parameters(summary_path, *summary, *layout, machine); !ok) return ok.error();
  const nlohmann::json* angles = calws_member(*summary, "angles");
  const std::string convention(to_string((*model)->convention()));
  if (!angles || !angles->is_string() || angles->get<std::string>() != convention) {
    return calws_error(
        summary_path, "angles",
        fmt::format("the plan's poses are in the {} convention, this machine's in {}: a plan made "
                    "for another machine",
                    angles ? angles->dump() : std::string("(missing)"), convention));
  }
  if (const nlohmann::json* method = calws_member(*summary, "method"); method && method->is_string())
    plan.method = method->get<std::string>();
  auto instrument = calws_instrument(summary_path, directory, *summary);
  if (!instrument) return instrument.error();
  plan.instrument = *instrument;
  auto setup = calibration_setup(plan.instrument);
  if (!setup) return setup.error();
  plan.setup = std::move(*setup);
  if (plan.setup.kind == calibration::MeasurementKind::targets) {
    const nlohmann::json* targets = calws_member(*calws_member(*summary, "instrument"), "targets");
    if (targets && targets->is_number_integer() &&
        targets->get<long>() != static_cast<long>(plan.setup.fixture.size())) {
      return calws_error(summary_path, "instrument.targets",
                         fmt::format("the plan was made with {} targets, {} has {}", targets->get<long>(),
                                     plan.instrument.fixture_path, plan.setup.fixture.size()));
    }
  }
  if (Status ok = calws_read_rows(plan_path, *plan_text, **model, plan); !ok) return ok.error();
  if (const nlohmann::json* poses = calws_member(*summary, "poses");
      poses && poses->is_number_integer() && poses->get<long>() != static_cast<long>(plan.poses.size())) {
    return calws_error(plan_path, "",
                       fmt::format("{} planned poses, but {} says {}: the files are of different runs",
                                   plan.poses.size(), summary_path, poses->get<long>()));
  }
  return plan;
}

Result<CalibratedErrorPrediction> CalibratedErrorPrediction::make(
    const Machine& machine, const std::vector<Pose>& plan, const calibration::MeasurementSetup& setup) {
  auto model = calibration_model(machine);
  if (!model) return model.error();
  // As calibration::predict_plan: the plan's Jacobian at the drawing, its identifiability with the default
  // threshold, and G of the same model at the same parameters.
  auto plan_j = calibration::plan_jacobian(**model, plan, setup);
  if (!plan_j) return plan_j.error();
  CalibratedErrorPrediction out;
  out.identifiability_ = calibration::analyse_identifiability(plan_j->jacobian, plan_j->layout);
  auto sensitivity = calibration::ToolSensitivityModel::make(
      **model, plan_j->layout, calibration::parameter_vector(plan_j->layout.groups));
  if (!sensitivity) return sensitivity.error();
  out.sensitivity_ = std::move(*sensitivity);
  return out;
}

Result<double> CalibratedErrorPrediction::at(const Pose& pose) const {
  auto g = sensitivity_.at(pose);
  if (!g) return g.error();
  const calibration::ToolSensitivity& gp = *g;
  const Eigen::Matrix3d tool_covariance = gp * identifiability_.covariance * gp.transpose();
  return std::sqrt(std::max(0.0, tool_covariance.trace()));
}

Result<CalibrationWorkspaceLayer> calibration_workspace_layer(const Machine& machine,
                                                              const std::string& directory) {
  auto plan = read_calibration_plan(machine, directory);
  if (!plan) return plan.error();
  if (Status checked = check_output_set(directory, {"calibrate plan"}); !checked) return checked.error();
  auto prediction = CalibratedErrorPrediction::make(machine, plan->poses, plan->setup);
  if (!prediction) {
    return make_error(prediction.error().code,
                      fmt::format("{}: the plan's prediction: {}", directory, prediction.error().message));
  }
  CalibrationWorkspaceLayer layer;
  layer.plan = std::move(*plan);
  auto shared = std::make_shared<const CalibratedErrorPrediction>(std::move(*prediction));
  layer.prediction = shared;
  layer.error_at_pose = [shared](const Pose& pose) {
    auto value = shared->at(pose);
    return value ? *value : std::numeric_limits<double>::quiet_NaN();
  };
  return layer;
}

}  // namespace pkm::pipeline
