// pkm.calibrate_plan, pkm.calibrate_simulate, pkm.calibrate_identify: `pkm calibrate plan | simulate |
// identify` (pipeline/calibration_run.hpp, docs/calibration.md). The library runs write an output set, so
// they run into `out_dir` or a temporary directory; the summary comes back as a dict, the key numbers from
// the typed result at full precision, and the CSV tables as dicts of numpy columns (pkm/_tables.py).
#include <fmt/format.h>

#include <array>
#include <optional>

#include "analysis_bindings.hpp"
#include "bindings.hpp"
#include "calibration/calibration_parameters.hpp"
#include "json_to_python.hpp"
#include "machine_handle.hpp"
#include "pipeline/calibration_run.hpp"
#include "pipeline/calibration_setup.hpp"
#include "pipeline_support.hpp"
#include "run_directory.hpp"

namespace pkm::python {

namespace {

using OptionalPoint = std::optional<std::array<double, 3>>;

/// The plan options (checked by the library: pipeline/calibration_checks.hpp).
struct CalibPlanArguments {
  std::string method = "d-optimal";
  std::optional<int> poses;
  double box_mm = 50.0, box_deg = 10.0, strut_change_mm = 10.0;
  int candidates = 400, held_out = 50;
  std::uint64_t seed = 1;
};

struct CalibInstrumentArguments {
  py::object fixture_path;
  double plate_radius_mm = 100.0;
  OptionalPoint ballbar_centre_mm;
  double sigma_mm = 0.01;
};

void calib_check(bool ok, const std::string& message) {
  if (!ok) throw py::value_error(message);
}

pipeline::CalibrationPlanSpec calib_plan_spec(const CalibPlanArguments& a) {
  pipeline::CalibrationPlanSpec spec;
  const auto method = pipeline::calibration_plan_method(a.method);
  calib_check(method.has_value(),
              fmt::format("method '{}': expected 'seven-pose', 'random' or 'd-optimal'", a.method));
  spec.method = *method;
  // As the CLI: 12 poses unless given; the seven-pose plan's n + 1 when not given.
  spec.poses = a.poses.value_or(spec.method == pipeline::CalibrationPlanMethod::seven_pose ? 0 : 12);
  spec.box_mm = a.box_mm;
  spec.box_deg = a.box_deg;
  spec.strut_change_mm = a.strut_change_mm;
  spec.candidates = a.candidates;
  spec.held_out = a.held_out;
  spec.seed = a.seed;
  return spec;
}

pipeline::CalibrationInstrument calib_instrument(const CalibInstrumentArguments& a) {
  pipeline::CalibrationInstrument instrument;
  instrument.fixture_path = optional_path(a.fixture_path);
  instrument.plate_radius_mm = a.plate_radius_mm;
  instrument.sigma_mm = a.sigma_mm;
  if (a.ballbar_centre_mm) {
    const auto& c = *a.ballbar_centre_mm;
    instrument.ballbar_centre_mm = Eigen::Vector3d(c[0], c[1], c[2]);
  }
  return instrument;
}

/// The names of the parameters the machine's calibration identifies (its geometry and drive offsets).
py::object calib_parameter_names(const Machine& machine) {
  auto model = pipeline::calibration_model(machine);
  if (!model) raise_error(model.error());
  return numpy_strings(unwrap(calibration::parameter_layout(**model)).names);
}

py::dict calib_table(const RunDirectory& directory, const char* name) {
  return py::module_::import("pkm._tables").attr("read_csv_table")(directory.file(name));
}

py::array_t<double> calib_vector(const Eigen::VectorXd& values) {
  return numpy_from(std::vector<double>(values.data(), values.data() + values.size()));
}

py::array_t<double> calib_poses(const Mechanism& mechanism, const std::vector<Pose>& poses) {
  std::vector<double> values;
  values.reserve(poses.size() * 6);
  for (const Pose& pose : poses) {
    const PoseVector v = pose_vector(mechanism, pose);
    values.insert(values.end(), v.data(), v.data() + 6);
  }
  return numpy_from(std::move(values), {static_cast<py::ssize_t>(poses.size()), 6});
}

py::dict calibrate_plan(const Machine& machine, const CalibPlanArguments& plan,
                        const CalibInstrumentArguments& instrument, bool strict, const py::object& out_dir) {
  pipeline::CalibrationPlanJob job;
  job.plan = calib_plan_spec(plan);
  job.instrument = calib_instrument(instrument);
  job.strict = strict;
  const RunDirectory directory(out_dir);
  job.out_directory = directory.path();
  const pipeline::CalibrationPlanResult r =
      unwrap_released([&] { return pipeline::calibration_plan(machine, job); });
  py::dict out;
  out["summary"] = python_from_json(r.summary);
  out["plan"] = calib_table(directory, "plan.csv");
  out["poses"] = calib_poses(*machine.mechanism, r.plan.poses);
  out["parameter_names"] = calib_parameter_names(machine);
  out["predicted_sigma"] = calib_vector(r.prediction.identifiability.standard_deviation);
  out["predicted_tool_error_mm"] = numpy_from(std::vector<double>(r.prediction.tool_sd_mm));
  return out;
}

py::dict calibrate_simulate(const Machine& machine, const CalibPlanArguments& plan,
                            const CalibInstrumentArguments& instrument, int trials, double joint_error_mm,
                            double offset_error_mm, const py::object& write_measurements, bool noise_free,
                            const py::object& out_dir) {
  pipeline::CalibrationSimulateJob job;
  job.plan = calib_plan_spec(plan);
  job.instrument = calib_instrument(instrument);
  job.trials = trials;
  job.joint_error_mm = joint_error_mm;
  job.offset_error_mm = offset_error_mm;
  job.measurements_path = optional_path(write_measurements);
  job.noise = !noise_free;
  const RunDirectory directory(out_dir);
  job.out_directory = directory.path();
  const pipeline::CalibrationSimulateResult r =
      unwrap_released([&] { return pipeline::calibration_simulate(machine, job); });
  py::dict out;
  out["summary"] = python_from_json(r.summary);
  out["trials"] = calib_table(directory, "trials.csv");
  if (!job.measurements_path.empty()) out["true_parameters"] = calib_table(directory, "true_parameters.csv");
  return out;
}

py::dict calibrate_identify(const Machine& machine, const py::object& measurements_path,
                            const py::object& fixture_path, int holdout, bool strict,
                            const py::object& calibrated_path, const py::object& report_path,
                            const py::object& out_dir) {
  pipeline::CalibrationIdentifyJob job;
  job.measurements_path = optional_path(measurements_path);
  job.fixture_path = optional_path(fixture_path);
  job.holdout = holdout;
  job.strict = strict;
  job.report_path = optional_path(report_path);
  const RunDirectory directory(out_dir);
  job.out_directory = directory.path();
  job.calibrated_path =
      calibrated_path.is_none() ? directory.file("calibrated.yaml") : optional_path(calibrated_path);
  const pipeline::CalibrationIdentifyResult r =
      unwrap_released([&] { return pipeline::calibration_identify(machine, job); });
  const calibration::IdentificationResult& id = r.identification;
  py::dict out;
  out["summary"] = python_from_json(r.summary);
  out["parameter_names"] = numpy_strings(id.layout.names);
  out["parameter_units"] = numpy_strings(id.layout.units);
  out["nominal"] = calib_vector(id.nominal);
  out["identified"] = calib_vector(id.identified);
  out["sigma"] = calib_vector(id.at_solution.standard_deviation);
  const py::dict parameters = calib_table(directory, "parameters.csv");
  out["identifiable"] = parameters["identifiable"].attr("__eq__")(py::str("yes"));
  const py::dict residuals = calib_table(directory, "residuals.csv");
  out["residuals_before_mm"] = residuals["before_mm"];
  out["residuals_after_mm"] = residuals["after_mm"];
  out["residuals"] = residuals;
  out["poses"] = calib_table(directory, "poses.csv");
  const std::string text = py::module_::import("pathlib")
                               .attr("Path")(job.calibrated_path)
                               .attr("read_text")(py::arg("encoding") = "utf-8")
                               .cast<std::string>();
  out["calibrated_text"] = text;
  out["calibrated_machine"] =
      py::cast(machine_from_text(text, calibrated_path.is_none() ? "calibrated.yaml" : job.calibrated_path));
  return out;
}

constexpr const char* kPlanOptions =
    R"doc(Plan options (the CLI's): method 'seven-pose' | 'random' | 'd-optimal'; poses (default 12; seven-pose:
n + 1); box_mm, box_deg: random and D-optimal poses within ± this (mm on x, y, z; deg on each angle) around
home; strut_change_mm: seven-pose, each actuator's change from home (mm, or deg for turning actuators);
candidates: D-optimal, random poses to choose from; held_out: random poses where the tool error is
predicted or judged; seed: of every random draw (the same seed, the same run).
Instrument: fixture_path (the tracker's targets, CSV in the tool frame; default the triangular plate of
plate_radius_mm about the tool point), or ballbar_centre_mm (x, y, z) in the base frame for a ballbar;
sigma_mm: the deviation of every measured coordinate or length, mm.)doc";

void bind_calibrate_plan(py::module_& m) {
  m.def(
      "calibrate_plan",
      [](const Machine& machine, const std::string& method, std::optional<int> poses, double box_mm,
         double box_deg, double strut_change_mm, int candidates, int held_out, std::uint64_t seed,
         const py::object& fixture_path, double plate_radius_mm, OptionalPoint ballbar_centre_mm,
         double sigma_mm, bool strict, const py::object& out_dir) {
        return calibrate_plan(machine,
                              {method, poses, box_mm, box_deg, strut_change_mm, candidates, held_out, seed},
                              {fixture_path, plate_radius_mm, ballbar_centre_mm, sigma_mm}, strict, out_dir);
      },
      py::arg("machine"), py::kw_only(), py::arg("method") = "d-optimal", py::arg("poses") = py::none(),
      py::arg("box_mm") = 50.0, py::arg("box_deg") = 10.0, py::arg("strut_change_mm") = 10.0,
      py::arg("candidates") = 400, py::arg("held_out") = 50, py::arg("seed") = 1,
      py::arg("fixture_path") = py::none(), py::arg("plate_radius_mm") = 100.0,
      py::arg("ballbar_centre_mm") = py::none(), py::arg("sigma_mm") = 0.01, py::arg("strict") = false,
      py::arg("out_dir") = py::none(),
      (std::string(
           R"doc(The poses to measure for calibrating `machine`, within its limits, and the accuracy they
predict, as `pkm calibrate plan`.

)doc") +
       kPlanOptions + R"doc(
strict: a plan that cannot identify every parameter raises pkm.SingularError; out_dir: keep plan.csv and
summary.json there (default: a temporary directory, removed).

Returns a dict: summary (summary.json as a dict: method, poses, identifiability, predicted tool error, ...);
plan: the columns of plan.csv (pose_id, x_mm, y_mm, z_mm, a1_deg, a2_deg, a3_deg, L1 ... readings in mm or
deg); poses: (P, 6) [x_mm, y_mm, z_mm, a_rad, b_rad, c_rad] in the machine's convention; parameter_names
(k,) the identified parameters ('A1.x', 'dL3', ...); predicted_sigma (k,) their standard deviations from
measuring the plan (the parameters' units: mm, or rad); predicted_tool_error_mm (held_out,) the tool point's
predicted error at each held-out pose (measurement noise only).)doc")
          .c_str());
}

void bind_calibrate_simulate(py::module_& m) {
  m.def(
      "calibrate_simulate",
      [](const Machine& machine, const std::string& method, std::optional<int> poses, double box_mm,
         double box_deg, double strut_change_mm, int candidates, int held_out, std::uint64_t seed,
         const py::object& fixture_path, double plate_radius_mm, OptionalPoint ballbar_centre_mm,
         double sigma_mm, int trials, double joint_error_mm, double offset_error_mm,
         const py::object& write_measurements, bool noise_free, const py::object& out_dir) {
        return calibrate_simulate(
            machine, {method, poses, box_mm, box_deg, strut_change_mm, candidates, held_out, seed},
            {fixture_path, plate_radius_mm, ballbar_centre_mm, sigma_mm}, trials, joint_error_mm,
            offset_error_mm, write_measurements, noise_free, out_dir);
      },
      py::arg("machine"), py::kw_only(), py::arg("method") = "d-optimal", py::arg("poses") = py::none(),
      py::arg("box_mm") = 50.0, py::arg("box_deg") = 10.0, py::arg("strut_change_mm") = 10.0,
      py::arg("candidates") = 400, py::arg("held_out") = 50, py::arg("seed") = 1,
      py::arg("fixture_path") = py::none(), py::arg("plate_radius_mm") = 100.0,
      py::arg("ballbar_centre_mm") = py::none(), py::arg("sigma_mm") = 0.01, py::arg("trials") = 20,
      py::arg("joint_error_mm") = 0.1, py::arg("offset_error_mm") = 0.1,
      py::arg("write_measurements") = py::none(), py::arg("noise_free") = false,
      py::arg("out_dir") = py::none(),
      (std::string(
           R"doc(Monte-Carlo trials of a calibration, as `pkm calibrate simulate`: machines perturbed from
the drawing (joints uniform ± joint_error_mm, drive offsets ± offset_error_mm), measured along the plan with
noise, identified, and judged at the held-out poses.

)doc") +
       kPlanOptions + R"doc(
trials: how many; write_measurements: also write one simulated measurement file there (a machine drawn from
the seed; its true parameters in true_parameters.csv), without noise when noise_free; out_dir: keep
trials.csv, summary.json (and true_parameters.csv) there (default: a temporary directory, removed).

Returns a dict: summary (summary.json as a dict: medians and 90th percentiles of the held-out tool error and
the parameter error, mm); trials: the columns of trials.csv (trial, seed, ok, status, rank,
condition_number, iterations, parameter_error_max_mm, parameter_error_rms_mm, held_out_max_mm,
held_out_rms_mm, error); with write_measurements, true_parameters: the columns of true_parameters.csv (name,
unit, nominal, true, change).)doc")
          .c_str());
}

}  // namespace

void bind_calibration(py::module_& m) {
  bind_calibrate_plan(m);
  bind_calibrate_simulate(m);
  m.def("calibrate_identify", &calibrate_identify, py::arg("machine"), py::arg("measurements_path"),
        py::kw_only(), py::arg("fixture_path") = py::none(), py::arg("holdout") = 0,
        py::arg("strict") = false, py::arg("calibrated_path") = py::none(),
        py::arg("report_path") = py::none(), py::arg("out_dir") = py::none(),
        R"doc(The machine's geometry and drive offsets identified from a measurement file (tracker or
ballbar CSV, docs/calibration.md), as `pkm calibrate identify`. `machine` must have been read from a file
(the calibrated file is that file's text with a calibration: section).

fixture_path: instead of the file's '# fixture:'; holdout: poses kept aside (spread over the file) to judge
the result; strict: a partial identification raises pkm.SingularError; calibrated_path: write the
calibrated machine file there (default: OUT_DIR/calibrated.yaml); report_path: also the HTML report;
out_dir: keep parameters.csv, residuals.csv, poses.csv, summary.json (and calibrated.yaml) there (default: a
temporary directory, removed).

Returns a dict: summary (summary.json as a dict); per identified parameter (k): parameter_names,
parameter_units ('mm', 'rad', ...), nominal, identified (the drawing's and the identified values, in those
units), sigma (the identified values' standard deviations), identifiable (bool); per residual of the
identification (r): residuals_before_mm, residuals_after_mm (the drawing's, the identified model's); residuals:
all columns of residuals.csv; poses: the columns of poses.csv; calibrated_text: the calibrated machine file;
calibrated_machine: it as a pkm.Machine.
Raises pkm.InputError (file, line, column, key set) for a malformed measurement file or one that cannot
identify the parameters, pkm.NotConvergedError when the identification does not converge.)doc");
}

}  // namespace pkm::python
