// pkm.optimize: Smirnov's post-processor, §3.6 (redundancy/optimize_program.hpp), as `pkm optimize` runs it:
// the free coordinates chosen by a drive control law at every point, the metrics against holding them
// constant, and the rewritten program.
#include <fmt/format.h>

#include <limits>

#include "bindings.hpp"
#include "json_to_python.hpp"
#include "pipeline/optimize_job.hpp"
#include "pipeline_bindings.hpp"
#include "pipeline_law_options.hpp"
#include "pipeline_program_arrays.hpp"
#include "pipeline_support.hpp"

namespace pkm::python {

namespace {

struct OptimizeRun {
  redundancy::OptimizeResult result;
  nlohmann::json summary;
};

// The library's optimize (pipeline/optimize_job.hpp, as `pkm optimize` runs it).
Result<OptimizeRun> run_optimize(const Machine& machine, const std::string& program_path,
                                 const pipeline::ProgramOptions& program_options,
                                 const LawArguments& arguments, const std::string& out_path) {
  auto options = optimize_options(arguments);
  if (!options) return options.error();
  auto done = pipeline::run_optimize_job(
      machine, {program_path, program_options, std::move(*options), out_path, {}, {}});
  if (!done) return done.error();
  return OptimizeRun{std::move(done->result), std::move(done->summary)};
}

py::dict metrics_arrays(const redundancy::TrajectoryMetrics& metrics) {
  py::dict out;
  out["feasible"] = metrics.feasible;
  out["increment_sum_mm"] = metrics.increment_sum_mm;
  out["peak_force_N"] = metrics.peak_force_N;
  out["energy_J"] = metrics.energy_J;
  out["required_work_J"] = metrics.required_work_J;
  out["rotation_sum_deg"] = metrics.rotation_sum_deg;
  out["min_limit_margin"] = metrics.min_limit_margin;  // NaN without actuator limits
  out["max_increment_mm"] = numpy_from(std::vector<double>(metrics.max_increment_mm));
  out["max_force_N"] = numpy_from(std::vector<double>(metrics.max_force_N));
  out["cumulative_energy_J"] = numpy_from(std::vector<double>(metrics.cumulative_energy_J));
  return out;
}

py::dict optimize_result(const Machine& machine, OptimizeRun&& run) {
  const redundancy::OptimizeResult& r = run.result;
  const redundancy::Trajectory& chosen = r.chosen().trajectory;
  const auto points = static_cast<py::ssize_t>(r.points.points.size());
  const int k = r.free_count;
  const int n = machine.mechanism->actuator_count();
  std::vector<double> free_rad, position_mm, actuators;
  std::vector<std::int32_t> line;
  for (std::size_t i = 0; i < r.points.points.size(); ++i) {
    const redundancy::PathPoint& p = r.points.points[i];
    line.push_back(p.line);
    position_mm.insert(position_mm.end(), p.position_mm.data(), p.position_mm.data() + 3);
    for (int c = 0; c < k; ++c) free_rad.push_back(i < chosen.values.size() ? chosen.values[i][c] : 0.0);
    const bool has_node = i < chosen.nodes.size() && chosen.nodes[i].valid;
    for (int j = 0; j < n; ++j)
      actuators.push_back(has_node ? chosen.nodes[i].lengths[j] : std::numeric_limits<double>::quiet_NaN());
  }
  py::dict out;
  out["summary"] = python_from_json(run.summary);
  out["free_coordinates"] = py::cast(r.free_names);
  out["line"] = numpy_from(std::move(line));
  out["position_mm"] = numpy_from(std::move(position_mm), {points, 3});
  out["free_rad"] = numpy_from(std::move(free_rad), {points, static_cast<py::ssize_t>(k)});
  out[py::str("actuators_" + actuator_unit(*machine.mechanism))] =
      numpy_from(std::move(actuators), {points, static_cast<py::ssize_t>(n)});
  out["chosen"] = metrics_arrays(r.chosen().metrics);
  out["constant"] = metrics_arrays(r.constant);
  out["program"] = program_arrays(r.program);
  return out;
}

}  // namespace

void bind_optimize(py::module_& m) {
  m.def(
      "optimize",
      [](const Machine& machine, const py::object& program_path, const std::string& law,
         const std::string& free, const py::object& bounds_deg, double step_mm, const std::string& solver,
         const std::string& energy_accounting, const std::string& force_model,
         std::optional<double> force_limit_N, std::optional<double> max_rate_deg_per_mm,
         const std::string& load, const std::string& parts, double improvement, double min_part_mm,
         int patience, const py::object& tool_table, const py::object& subroutine_path,
         const py::object& parameter_file, const py::object& out_path) {
        const LawArguments arguments{
            law,         free,          free_bounds(bounds_deg), step_mm, solver, energy_accounting,
            force_model, force_limit_N, max_rate_deg_per_mm,     load,    parts,  improvement,
            min_part_mm, patience};
        const std::string path = optional_path(program_path);
        const pipeline::ProgramOptions read = program_options(tool_table, subroutine_path, parameter_file);
        const std::string out = optional_path(out_path);
        return optimize_result(
            machine, unwrap_released([&] { return run_optimize(machine, path, read, arguments, out); }));
      },
      py::arg("machine"), py::arg("program_path"), py::arg("law"), py::kw_only(), py::arg("free") = "spin",
      py::arg("bounds_deg") = py::none(), py::arg("step_mm") = 1.0, py::arg("solver") = "greedy",
      py::arg("energy_accounting") = "no-recovery", py::arg("force_model") = "statics",
      py::arg("force_limit_N") = py::none(), py::arg("max_rate_deg_per_mm") = py::none(),
      py::arg("load") = "", py::arg("parts") = "fixed", py::arg("improvement") = 0.01,
      py::arg("min_part_mm") = 1.0, py::arg("patience") = 3, py::arg("tool_table") = py::none(),
      py::arg("subroutine_path") = py::none(), py::arg("parameter_file") = py::none(),
      py::arg("out_path") = py::none(),
      R"doc(Chooses the coordinates a program leaves free by a drive control law, as `pkm optimize`.

law: 'increment' (Σ of the largest strut increments), 'force' or 'energy'; free: 'spin' (about the tool axis;
planar: phi) or 'all'; bounds_deg (lo, hi) of every free coordinate or ((lo, hi), ...) of each (default start ± 30°); step_mm between
optimised points; solver 'greedy' or 'global'; energy_accounting 'no-recovery' | 'braking-free' | 'recovery';
force_model 'statics' | 'dynamics'; force_limit_N; max_rate_deg_per_mm (global solver); load: the CLI's
--load text (e.g. 'tangential=200,normal=50' or '@FILE.yaml'); parts 'fixed' (every block cut at step_mm) or
'adaptive' (each block cut into N = 1, 2, ... parts until a finer cut lowers the criterion by at most the share
`improvement` for `patience` cuts in a row, parts no shorter than min_part_mm; step_mm is then the step the
criterion is measured along);
out_path: also write the rewritten G-code.

Returns a dict: summary (the JSON `pkm optimize --json` prints: const_sum_mm, opt_sum_mm, peak forces,
energies, ranges...), free_coordinates (names), and per optimised point (K points): line (K,) int32,
position_mm (K, 3) tool point (base frame), free_rad (K, F) the chosen free coordinates, actuators_mm (K, n)
(actuators_rad for angular actuators; NaN where unreachable); chosen and constant: the metrics of the law's
trajectory and of holding the free coordinates constant (increment_sum_mm, peak_force_N, energy_J,
required_work_J, rotation_sum_deg, min_limit_margin (NaN without actuator limits), feasible, and per point max_increment_mm, max_force_N, cumulative_energy_J (K,));
program: the rewritten program as pkm.interpret returns it.)doc");
}

}  // namespace pkm::python
