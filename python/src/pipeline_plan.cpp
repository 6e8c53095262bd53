// pkm.plan: a part program planned on a machine, its servo-rate motion in memory (numpy arrays) and the same
// summary `pkm plan` writes to summary.json: the pipeline's plan (pipeline/plan_program.hpp) with the arrays
// listening to its ticks, so the two agree exactly.
#include <fmt/format.h>

#include <cmath>
#include <optional>

#include "bindings.hpp"
#include "core/rotation.hpp"
#include "core/units.hpp"
#include "json_to_python.hpp"
#include "pipeline/plan_program.hpp"
#include "pipeline_bindings.hpp"
#include "pipeline_law_options.hpp"
#include "pipeline_support.hpp"

namespace pkm::python {

namespace {

struct PlanArguments {
  std::string program_path;
  pipeline::ProgramOptions program_options;
  planning::PlanOptions plan;
  std::optional<LawArguments> law;
  bool dynamics = false;
  bool elastic = false;  ///< with dynamics: the elastic machine's response (dynamics/run_elastic.hpp)
  std::string load;
  bool evaluate_path_error = true;
  std::string out_dir;
  formats::TickTables tables = formats::TickTables::csv;
};

/// The drive forces per tick (RunDynamics hands them on in order).
struct DynamicsArrays {
  std::vector<double> time_s, total, static_part, dynamic_part, power_W, command;
};

/// The elastic machine's response per tick, as response.csv (RunElastic hands it on in order).
struct ElasticArrays {
  std::vector<double> time_s, deviation_mm, rotation_deg, tool_error_mm;
  std::vector<std::int32_t> line;
};

struct PlanRun {
  analyses::PlanRun run;
  double planning_s = 0.0;
  nlohmann::json summary, law_summary;
  int actuators = 0;
  // pose_machine: base frame, the machine's convention (rad); xyz_program/abc: program coordinates, as
  // path.csv.
  std::vector<double> time_s, s, path_speed, feed_cap, path_error, actuator_values, pose_machine, xyz_program,
      abc;
  std::vector<std::int32_t> line, segment;
  std::optional<DynamicsArrays> dynamics;
  std::optional<ElasticArrays> elastic;
};

void append(std::vector<double>& out, const ActuatorVector& values, int n) {
  for (int j = 0; j < n; ++j) out.push_back(values[j]);
}

/// Every tick of the run kept in the arrays, as the CLI writes path.csv and actuators.csv.
class ArrayListener final : public planning::TickObserver {
 public:
  ArrayListener(const Machine& machine, PlanRun& run)
      : machine_(machine), r_(run), n_(machine.mechanism->actuator_count()) {
    r_.actuators = n_;
  }
  // The arrays are as long as the run: one allocation each where the count is known (a whole plan), not the
  // doubling of push_back (whose peak is twice the final size). A streamed plan's ticks are counted only at
  // its end (0 here): its arrays grow as the ticks come.
  Status on_start(long tick_count) override {
    const auto ticks = static_cast<std::size_t>(tick_count);
    for (auto* column : {&r_.time_s, &r_.s, &r_.path_speed, &r_.feed_cap, &r_.path_error})
      column->reserve(ticks);
    r_.line.reserve(ticks);
    r_.segment.reserve(ticks);
    r_.actuator_values.reserve(ticks * static_cast<std::size_t>(n_));
    r_.pose_machine.reserve(ticks * 6);
    r_.xyz_program.reserve(ticks * 3);
    r_.abc.reserve(ticks * 3);
    if (r_.dynamics) {
      for (auto* column : {&r_.dynamics->total, &r_.dynamics->static_part, &r_.dynamics->dynamic_part,
                           &r_.dynamics->power_W, &r_.dynamics->command})
        column->reserve(ticks * static_cast<std::size_t>(n_));
      r_.dynamics->time_s.reserve(ticks);
    }
    if (r_.elastic) {
      for (auto* column : {&r_.elastic->time_s, &r_.elastic->rotation_deg, &r_.elastic->tool_error_mm})
        column->reserve(ticks);
      r_.elastic->line.reserve(ticks);
      r_.elastic->deviation_mm.reserve(ticks * 3);
    }
    return ok_status();
  }
  Status on_tick(const planning::ServoTick& tick, const planning::RunMonitor& monitor) override {
    r_.time_s.push_back(tick.time_s);
    r_.line.push_back(tick.line);
    r_.segment.push_back(tick.segment);
    r_.s.push_back(tick.s);
    r_.path_speed.push_back(tick.path_speed);
    r_.feed_cap.push_back(monitor.last_feed_cap());
    r_.path_error.push_back(monitor.last_path_error_mm());
    append(r_.actuator_values, tick.actuators, n_);
    const PoseVector v = vector_from_pose(machine_.mechanism->convention(), tick.pose);
    r_.pose_machine.insert(r_.pose_machine.end(), v.data(), v.data() + 6);
    const Eigen::Vector3d p = tick.pose.position_mm - machine_.motion.program_origin_mm;
    r_.xyz_program.insert(r_.xyz_program.end(), p.data(), p.data() + 3);
    const Eigen::Vector3d abc =
        deg_from_rad(1.0) * angles_from_rotation(AngleConvention::abc, tick.pose.rotation);
    r_.abc.insert(r_.abc.end(), abc.data(), abc.data() + 3);
    return ok_status();
  }

 private:
  const Machine& machine_;
  PlanRun& r_;
  int n_;
};

/// The analyses' ticks kept in the arrays, as forces.csv and response.csv.
analyses::PlanAnalysisSinks array_sinks(const PlanArguments& a, int n, PlanRun& r) {
  analyses::PlanAnalysisSinks sinks;
  if (a.dynamics) {
    r.dynamics.emplace();
    sinks.dynamics = [&d = *r.dynamics, n](const dynamics::TickDynamics& t) -> Status {
      d.time_s.push_back(t.time_s);
      append(d.total, t.forces.total, n);
      append(d.static_part, t.forces.static_part, n);
      append(d.dynamic_part, t.forces.dynamic_part, n);
      append(d.power_W, t.power_W, n);
      append(d.command, t.command_N, n);
      return ok_status();
    };
  }
  if (a.dynamics && a.elastic) {
    r.elastic.emplace();
    sinks.elastic = [&e = *r.elastic](const dynamics::ElasticTick& t) -> Status {
      e.time_s.push_back(t.time_s);
      e.line.push_back(t.line);
      e.deviation_mm.insert(e.deviation_mm.end(), t.deviation_mm.data(), t.deviation_mm.data() + 3);
      e.rotation_deg.push_back(t.rotation_deg);
      e.tool_error_mm.push_back(t.tool_error_mm);
      return ok_status();
    };
  }
  return sinks;
}

// The library's plan (pipeline::plan_program, as `pkm plan` runs it), streamed once, with every tick kept in
// arrays and, with out_dir, the CLI's files written as well.
Result<PlanRun> run_plan(const Machine& machine, const PlanArguments& a) {
  pipeline::PlanJob job;
  if (a.law) {
    auto options = optimize_options(*a.law);
    if (!options) return options.error();
    job.law = std::move(*options);
  }
  auto load = load_model(a.load);
  if (!load) return load.error();
  job.program_path = a.program_path;
  job.program_options = a.program_options;
  job.plan = a.plan;
  job.evaluate_path_error = a.evaluate_path_error;
  job.dynamics = a.dynamics;
  job.elastic = a.dynamics && a.elastic;
  job.dynamics_load = std::move(*load);
  job.out_directory = a.out_dir;
  job.tick_tables = a.tables;
  PlanRun r;
  ArrayListener listener(machine, r);
  job.listener = &listener;
  job.listener_sinks = array_sinks(a, machine.mechanism->actuator_count(), r);
  auto planned = pipeline::plan_program(machine, job);
  if (!planned) return planned.error();
  r.run = std::move(planned->run);
  r.planning_s = planned->planning_s;
  r.summary = std::move(planned->summary);
  r.law_summary = std::move(planned->law_summary);
  return r;
}

py::dict plan_result(const Machine& machine, PlanRun&& r) {
  const auto ticks = static_cast<py::ssize_t>(r.time_s.size());
  const auto n = static_cast<py::ssize_t>(r.actuators);
  py::dict out;
  out["summary"] = python_from_json(r.summary);
  out["planning_time_s"] = r.planning_s;
  if (!r.law_summary.is_null()) out["law"] = python_from_json(r.law_summary);
  out["time_s"] = numpy_from(std::move(r.time_s));
  out["line"] = numpy_from(std::move(r.line));
  out["segment"] = numpy_from(std::move(r.segment));
  out["s"] = numpy_from(std::move(r.s));
  out["path_speed_mm_s"] = numpy_from(std::move(r.path_speed));
  out["feed_cap_mm_s"] = numpy_from(std::move(r.feed_cap));
  out["path_error_mm"] = numpy_from(std::move(r.path_error));
  out[py::str("actuators_" + actuator_unit(*machine.mechanism))] =
      numpy_from(std::move(r.actuator_values), {ticks, n});
  out["pose_machine"] = numpy_from(std::move(r.pose_machine), {ticks, 6});
  out["xyz_program_mm"] = numpy_from(std::move(r.xyz_program), {ticks, 3});
  out["abc_deg"] = numpy_from(std::move(r.abc), {ticks, 3});
  if (r.dynamics) {
    DynamicsArrays& d = *r.dynamics;
    const auto rows = static_cast<py::ssize_t>(d.time_s.size());
    const std::string unit = drive_force_unit(*machine.mechanism);
    py::dict forces;
    forces["time_s"] = numpy_from(std::move(d.time_s));
    forces[py::str("force_" + unit)] = numpy_from(std::move(d.total), {rows, n});
    forces[py::str("static_force_" + unit)] = numpy_from(std::move(d.static_part), {rows, n});
    forces[py::str("dynamic_force_" + unit)] = numpy_from(std::move(d.dynamic_part), {rows, n});
    forces["power_W"] = numpy_from(std::move(d.power_W), {rows, n});
    forces[py::str("command_" + unit)] = numpy_from(std::move(d.command), {rows, n});
    if (r.elastic) {
      ElasticArrays& e = *r.elastic;
      const auto rows_e = static_cast<py::ssize_t>(e.time_s.size());
      py::dict response;
      response["time_s"] = numpy_from(std::move(e.time_s));
      response["line"] = numpy_from(std::move(e.line));
      response["deviation_mm"] = numpy_from(std::move(e.deviation_mm), {rows_e, 3});
      response["rotation_deg"] = numpy_from(std::move(e.rotation_deg));
      response["tool_error_mm"] = numpy_from(std::move(e.tool_error_mm));
      out["elastic"] = response;
    }
    out["dynamics"] = forces;
  }
  return out;
}

}  // namespace

/// pkm.plan's planning options, checked as the CLI checks its flags.
planning::PlanOptions plan_options(std::optional<double> servo_period_ms, double feed_override_pct,
                                   std::optional<double> blend_tolerance_mm, double lookahead_mm,
                                   int lookahead_moves) {
  planning::PlanOptions plan;
  if (servo_period_ms) {
    if (!(*servo_period_ms >= 0.01 && *servo_period_ms <= 1000.0))
      throw py::value_error(fmt::format("servo_period_ms {}: expected 0.01 … 1000 ms", *servo_period_ms));
    plan.rate_hz = 1000.0 / *servo_period_ms;
  }
  if (!(feed_override_pct > 0.0 && feed_override_pct <= 200.0))
    throw py::value_error(fmt::format("feed_override_pct {}: expected > 0 and ≤ 200 %", feed_override_pct));
  plan.override_pct = feed_override_pct;
  if (blend_tolerance_mm) {
    if (!(*blend_tolerance_mm >= 0.0 && *blend_tolerance_mm <= 100.0))
      throw py::value_error(fmt::format("blend_tolerance_mm {}: expected 0 … 100 mm", *blend_tolerance_mm));
    plan.path_tolerance_mm = blend_tolerance_mm;
  }
  if (!(lookahead_mm > 0.0) || lookahead_moves < 1)
    throw py::value_error(
        fmt::format("lookahead_mm {}, lookahead_moves {}: expected a length > 0 mm and at least 1 move",
                    lookahead_mm, lookahead_moves));
  plan.lookahead_mm = lookahead_mm;
  plan.lookahead_moves = lookahead_moves;
  return plan;
}

void bind_plan(py::module_& m) {
  m.def(
      "plan",
      [](const Machine& machine, const py::object& program_path, std::optional<double> servo_period_ms,
         double feed_override_pct, std::optional<double> blend_tolerance_mm, std::optional<std::string> law,
         const std::string& free, const py::object& bounds_deg, double law_step_mm, const std::string& solver,
         const std::string& energy_accounting, const std::string& force_model,
         std::optional<double> force_limit_N, std::optional<double> max_rate_deg_per_mm,
         const std::string& load, bool dynamics, bool elastic, bool path_error, const py::object& tool_table,
         const py::object& subroutine_path, const py::object& parameter_file, const py::object& out_dir,
         const std::string& tables, double lookahead_mm, int lookahead_moves) {
        PlanArguments a;
        if (tables != "csv" && tables != "hdf5")
          throw py::value_error(fmt::format("tables '{}': expected 'csv' or 'hdf5'", tables));
        a.tables = tables == "hdf5" ? formats::TickTables::hdf5 : formats::TickTables::csv;
        a.program_path = optional_path(program_path);
        a.program_options = program_options(tool_table, subroutine_path, parameter_file);
        a.out_dir = optional_path(out_dir);
        a.plan = plan_options(servo_period_ms, feed_override_pct, blend_tolerance_mm, lookahead_mm,
                              lookahead_moves);
        if (law) {
          a.law = LawArguments{
              *law,        free,          free_bounds(bounds_deg), law_step_mm, solver, energy_accounting,
              force_model, force_limit_N, max_rate_deg_per_mm,     load};
        }
        if (elastic && !dynamics)
          throw py::value_error("elastic=True: only with dynamics=True (the elastic machine's masses)");
        a.dynamics = dynamics;
        a.elastic = elastic;
        a.load = load;
        a.evaluate_path_error = path_error;
        return plan_result(machine, unwrap_released([&] { return run_plan(machine, a); }));
      },
      py::arg("machine"), py::arg("program_path"), py::kw_only(), py::arg("servo_period_ms") = py::none(),
      py::arg("feed_override_pct") = 100.0, py::arg("blend_tolerance_mm") = py::none(),
      py::arg("law") = py::none(), py::arg("free") = "spin", py::arg("bounds_deg") = py::none(),
      py::arg("law_step_mm") = 1.0, py::arg("solver") = "greedy",
      py::arg("energy_accounting") = "no-recovery", py::arg("force_model") = "statics",
      py::arg("force_limit_N") = py::none(), py::arg("max_rate_deg_per_mm") = py::none(),
      py::arg("load") = "", py::arg("dynamics") = false, py::arg("elastic") = false,
      py::arg("path_error") = true, py::arg("tool_table") = py::none(),
      py::arg("subroutine_path") = py::none(), py::arg("parameter_file") = py::none(),
      py::arg("out_dir") = py::none(), py::arg("tables") = "hdf5",
      py::arg("lookahead_mm") = planning::PlanOptions{}.lookahead_mm,
      py::arg("lookahead_moves") = planning::PlanOptions{}.lookahead_moves,
      R"doc(Plans a part program on `machine` and returns its servo-rate motion, as `pkm plan` does.

Arguments (the CLI's options): servo_period_ms (default 1 ms, --rate 1000/period), feed_override_pct (0 < … ≤
200), blend_tolerance_mm (corner blending; default the machine file's; 0: exact stop), path_error (FK of the
actuators at every mid-period, as without --no-path-error), tool_table (G43), subroutine_path and parameter_file
(as pkm.interpret), out_dir (also write the CLI's
files there: the servo-rate tables and summary.json), tables ('hdf5', the default: the tables as the groups of
out_dir/ticks.h5; 'csv': as actuators.csv, path.csv and with dynamics forces.csv; as `pkm plan --tables`),
lookahead_mm and lookahead_moves (the look-ahead window of the speed planning, as --lookahead-mm and
--lookahead-moves: within them the plan equals the whole program's; summary['lookahead_binding'] counts the
places where the window set the speed).
law ('increment' | 'force' | 'energy'): first choose the coordinates the program leaves free by that drive
control law, as pkm.optimize does, with free, bounds_deg (lo, hi), law_step_mm, solver, energy_accounting,
force_model, force_limit_N, max_rate_deg_per_mm and load (the CLI's --load text, e.g.
'tangential=200,normal=50'; also the process load of the dynamics).
dynamics: also the drive forces, power and energy at every tick (the machine file's dynamics: section).
elastic (with dynamics): also the elastic machine's response to the planned drive motion (struts'
stiffness_N_mm, docs/dynamics_elastic.md), as `pkm plan --dynamics --elastic`: the summary's dynamics gain
lowest_natural_frequency_Hz, static_deflection_at_start_mm, max_dynamic_tool_error_mm (_line, _time_s) and
max_dynamic_rotation_deg.

Returns a dict:
  summary: the summary.json of `pkm plan` as a dict (same keys and numbers); law: the law's summary (with law);
  planning_time_s; per servo tick (T ticks, n actuators):
  time_s (T,), line (T,) int32 source line, segment (T,) int32, s (T,) path parameter,
  path_speed_mm_s (T,), feed_cap_mm_s (T,) the speed the programmed feed allows,
  path_error_mm (T,) (NaN where not evaluated), actuators_mm (T, n) (actuators_rad for angular actuators),
  pose_machine (T, 6) the commanded pose [x_mm, y_mm, z_mm, a_rad, b_rad, c_rad] in the base frame and the
  machine's own angle convention (Machine.angle_convention), as Machine.ik takes it; the same pose in program
  coordinates, as path.csv's columns: xyz_program_mm (T, 3) the tool point from program zero and abc_deg (T, 3)
  G-code's A B C, R = Rz(C)·Ry(B)·Rx(A) (Machine.pose_from_abc converts);
  with dynamics, dynamics: a dict with time_s, force_N, static_force_N, dynamic_force_N, command_N (T, n)
  (_Nmm for angular drives) and power_W (T, n); with elastic also elastic: the columns of
  response.csv per tick, time_s (T,), line (T,) int32, deviation_mm (T, 3) the tool point's actual − commanded
  position [dx, dy, dz] (base frame), rotation_deg (T,) and tool_error_mm (T,) = |deviation_mm|.
Raises pkm.ProgramError for a malformed program, pkm.LimitExceededError / pkm.UnreachableError where the
program leaves the machine's limits, pkm.InputError (ValueError) for a bad option, and for dynamics on a
machine without a dynamics: section (key 'dynamics').)doc");
}

}  // namespace pkm::python
