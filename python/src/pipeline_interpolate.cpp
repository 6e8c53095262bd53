// pkm.interpolate: a part program planned and turned into whole drive steps per period (Smirnov 2019), as
// `pkm interpolate` runs it (pipeline/interpolate_program.cpp), the periods kept in memory as numpy arrays.
#include <fmt/format.h>

#include <limits>
#include <stdexcept>
#include <string>

#include "bindings.hpp"
#include "json_to_python.hpp"
#include "pipeline/interpolate_program.hpp"
#include "pipeline_bindings.hpp"
#include "pipeline_support.hpp"

namespace pkm::python {

namespace {

struct PeriodArrays {
  int actuators = 0;
  std::vector<double> time_s, contour_error_mm, tool_mm, path_mm;
  std::vector<std::int32_t> line, steps;
  std::vector<std::int64_t> position;
};

struct InterpolateRun {
  nlohmann::json summary;
  PeriodArrays periods;
};

// The library's run with the periods kept in memory; with job.out_directory it writes the CLI's files as
// well.
Result<InterpolateRun> run_interpolation(const Machine& machine, pipeline::InterpolateJob job) {
  InterpolateRun r;
  PeriodArrays& p = r.periods;
  const int n = machine.mechanism->actuator_count();
  p.actuators = n;
  job.on_period = [&p, n](const interpolation::StepPeriod& period,
                          const interpolation::PeriodContour& contour, const Eigen::Vector3d& path_mm) {
    p.time_s.push_back(period.time_s);
    p.line.push_back(period.line);
    for (int j = 0; j < n; ++j) {
      p.steps.push_back(period.steps[static_cast<std::size_t>(j)]);
      p.position.push_back(period.position[static_cast<std::size_t>(j)]);
    }
    p.contour_error_mm.push_back(contour.max_error_mm);
    const Eigen::Vector3d tool = contour.solved
                                     ? contour.tool_mm
                                     : Eigen::Vector3d::Constant(std::numeric_limits<double>::quiet_NaN());
    p.tool_mm.insert(p.tool_mm.end(), tool.data(), tool.data() + 3);
    p.path_mm.insert(p.path_mm.end(), path_mm.data(), path_mm.data() + 3);
  };
  auto run = pipeline::interpolate_program(machine, job);
  if (!run) return run.error();
  r.summary = std::move(run->json);
  return r;
}

py::dict interpolate_result(InterpolateRun&& r) {
  PeriodArrays& p = r.periods;
  const auto periods = static_cast<py::ssize_t>(p.time_s.size());
  const auto n = static_cast<py::ssize_t>(p.actuators);
  py::dict out;
  out["summary"] = python_from_json(r.summary);
  out["time_s"] = numpy_from(std::move(p.time_s));
  out["line"] = numpy_from(std::move(p.line));
  out["steps"] = numpy_from(std::move(p.steps), {periods, n});
  out["position_steps"] = numpy_from(std::move(p.position), {periods, n});
  out["contour_error_mm"] = numpy_from(std::move(p.contour_error_mm));
  out["tool_mm"] = numpy_from(std::move(p.tool_mm), {periods, 3});
  out["path_mm"] = numpy_from(std::move(p.path_mm), {periods, 3});
  return out;
}

interpolation::CandidateSet candidate_set(const std::string& text, int actuators, int& per_tact) {
  if (text == "all-six" || text == "all") return interpolation::CandidateSet::all_six;
  if (text == "one-to-all") return interpolation::CandidateSet::one_to_all;
  try {
    std::size_t used = 0;
    per_tact = std::stoi(text, &used);
    if (used == text.size() && per_tact >= 1 && per_tact <= actuators)
      return interpolation::CandidateSet::exactly_k;
  } catch (const std::exception&) {
  }
  throw py::value_error(fmt::format(
      "candidates '{}': expected all-six, one-to-all or a number of struts 1…{}", text, actuators));
}

}  // namespace

void bind_interpolate(py::module_& m) {
  m.def(
      "interpolate",
      [](const Machine& machine, const py::object& program_path, const std::string& method,
         std::optional<double> servo_period_ms, std::optional<double> step_mm,
         std::optional<double> max_step_rate_hz, double rho_max_mm, std::optional<double> delta_rho_max,
         double feed_override_pct, const std::string& override_at, const std::string& accel,
         int error_samples, bool chord_check, bool orientation_criterion, bool linearise,
         std::optional<double> deviation_mm, const std::string& candidates, const py::object& tool_table,
         const py::object& subroutine_path, const py::object& parameter_file, const py::object& out_dir) {
        pipeline::InterpolateJob job;
        interpolation::InterpolateOptions& options = job.options;
        const auto parsed_method = interpolation::method_from_string(method);
        if (!parsed_method) {
          throw py::value_error(
              fmt::format("method '{}': expected exact, carrier, carrier-corrected or estimating", method));
        }
        options.method = *parsed_method;
        job.period_ms = servo_period_ms;
        if (step_mm && !(*step_mm > 0.0))
          throw py::value_error(
              fmt::format("step_mm {}: must be a positive drive resolution (mm per step)", *step_mm));
        job.step = step_mm;
        job.max_step_rate_hz = max_step_rate_hz;
        if (!(rho_max_mm > 0.0))
          throw py::value_error(fmt::format("rho_max_mm {}: must be positive", rho_max_mm));
        options.rho_max_mm = rho_max_mm;
        options.delta_rho_max = delta_rho_max;
        if (!(feed_override_pct > 0.0 && feed_override_pct <= 200.0))
          throw py::value_error(
              fmt::format("feed_override_pct {}: expected > 0 and ≤ 200 %", feed_override_pct));
        job.override_pct = feed_override_pct;
        job.override_changes = unwrap(interpolation::parse_override_changes(override_at));
        if (accel != "linear" && accel != "s-curve")
          throw py::value_error(fmt::format("accel '{}': expected linear or s-curve", accel));
        job.accel = accel == "linear" ? interpolation::RampShape::linear : interpolation::RampShape::s_curve;
        if (error_samples < 1) throw py::value_error("error_samples must be at least 1");
        options.error_samples = error_samples;
        options.chord_check = chord_check;
        options.orientation_criterion = orientation_criterion;
        options.linearise = linearise;
        options.estimating.deviation_mm = deviation_mm ? *deviation_mm : rho_max_mm;
        options.estimating.candidates = candidate_set(candidates, machine.mechanism->actuator_count(),
                                                      options.estimating.struts_per_tact);
        job.program_path = optional_path(program_path);
        job.program_options = program_options(tool_table, subroutine_path, parameter_file);
        job.out_directory = optional_path(out_dir);
        return interpolate_result(unwrap_released([&] { return run_interpolation(machine, job); }));
      },
      py::arg("machine"), py::arg("program_path"), py::kw_only(), py::arg("method") = "carrier-corrected",
      py::arg("servo_period_ms") = py::none(), py::arg("step_mm") = py::none(),
      py::arg("max_step_rate_hz") = py::none(), py::arg("rho_max_mm") = 1e-3,
      py::arg("delta_rho_max") = py::none(), py::arg("feed_override_pct") = 100.0,
      py::arg("override_at") = "", py::arg("accel") = "s-curve", py::arg("error_samples") = 5,
      py::arg("chord_check") = true, py::arg("orientation_criterion") = false, py::arg("linearise") = true,
      py::arg("deviation_mm") = py::none(), py::arg("candidates") = "all-six",
      py::arg("tool_table") = py::none(), py::arg("subroutine_path") = py::none(),
      py::arg("parameter_file") = py::none(), py::arg("out_dir") = py::none(),
      R"doc(Plans a part program and turns it into whole drive steps per servo period, as `pkm interpolate`.

Arguments (the CLI's options): method: exact | carrier | carrier-corrected | estimating; servo_period_ms
(0.1 … 20 ms), step_mm (drive resolution, mm per step; deg for angular actuators) and max_step_rate_hz
(per drive): default the machine file's drives: section, then 1 ms, 0.001, none; rho_max_mm (contour
tolerance ρ_max); delta_rho_max (δρ_max; default the largest along the path); feed_override_pct;
override_at (the CLI's --override-at text: changes during the run); accel: s-curve | linear;
error_samples; chord_check; orientation_criterion; linearise; deviation_mm and candidates (estimating:
'all-six', 'one-to-all' or a number of struts); tool_table (G43); subroutine_path and parameter_file (as
pkm.interpret); out_dir (also write the CLI's steps.csv,
steps.bin, contour.csv and summary.json there).

Returns a dict: summary (the summary.json of `pkm interpolate`, as a dict) and per servo period (P periods,
n actuators): time_s (P,) real time at the period's end; line (P,) int32; steps (P, n) int32 signed steps
in the period; position_steps (P, n) int64 position code at its end; contour_error_mm (P,) the largest
contour error in it; tool_mm (P, 3) FK of the drives' positions at its end, base frame (NaN where FK
failed); path_mm (P, 3) the programmed point at its end, base frame.)doc");
}

}  // namespace pkm::python
