#include "redundancy/optimize_program.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <cmath>

#include "core/units.hpp"

namespace pkm::redundancy {

using program::CanonicalMove;
using program::MoveKind;

std::optional<Solver> solver_from_string(std::string_view name) {
  if (name == "greedy") return Solver::greedy;
  if (name == "global") return Solver::global;
  return std::nullopt;
}

namespace {

double seconds_since(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

// The trajectory's nodes evaluated again with forces, for the report.
Trajectory with_forces(const Problem& report, const Trajectory& trajectory) {
  Trajectory out = trajectory;
  for (std::size_t k = 0; k < out.nodes.size(); ++k) {
    report.law->evaluate(report.points[k], report.loads[k], out.values[k], out.nodes[k], false);
  }
  return out;
}

}  // namespace

program::CanonicalProgram rebuild_program(const program::CanonicalProgram& program,
                                          const ProgramPoints& points, const Trajectory& trajectory,
                                          const FreeCoordinates& free) {
  std::vector<Pose> poses(points.points.size());
  for (std::size_t k = 0; k < poses.size(); ++k) poses[k] = free.pose(points.points[k], trajectory.values[k]);
  return program_through_poses(program, points, poses, false);
}

namespace {

Status check_machine_for(const Machine& machine, const OptimizeOptions& options) {
  if (options.law.forces == ForceModel::dynamics && !machine.dynamics.given()) {
    return Error{ErrorCode::bad_input,
                 fmt::format("{}: the dynamic force model needs the machine file's dynamics: section (masses "
                             "and inertias of the platform and the struts, docs/machine-file.md)",
                             machine.source),
                 ErrorLocation{machine.source, 0, 0, "dynamics"}};
  }
  if (options.law.law == Law::potential &&
      !(machine.limits.min && machine.limits.max && *machine.limits.max > *machine.limits.min)) {
    return Error{
        ErrorCode::bad_input,
        fmt::format("{}: the potential law keeps the actuators away from their limits and needs both: "
                    "limits.actuator_min and limits.actuator_max",
                    machine.source),
        ErrorLocation{machine.source, 0, 0, "limits"}};
  }
  if (options.subdivision && options.solver == Solver::global) {
    return make_error(ErrorCode::bad_input,
                      "adaptive parts choose the free coordinates part by part (greedy, Smirnov 2019 §3.6); "
                      "the global solver needs fixed parts (--parts fixed)");
  }
  return ok_status();
}

int count_parts(const ProgramPoints& points) {
  int count = 0;
  for (int parts : points.parts) count += parts;
  return count;
}

// Fixed parts: the greedy (and the whole-path) solver over the parts' ends.
Status solve_fixed(const program::CanonicalProgram& program, const OptimizeOptions& options,
                   const Problem& problem, const Problem& report_problem, const FreeCoordinates& free,
                   OptimizeResult& result) {
  auto clock = std::chrono::steady_clock::now();
  auto greedy = solve_greedy(problem, options.greedy, program.source);
  if (!greedy) return greedy.error();
  result.greedy.seconds = seconds_since(clock);
  result.greedy.trajectory = std::move(*greedy);
  result.greedy.metrics = measure(report_problem, with_forces(report_problem, result.greedy.trajectory));
  if (options.solver == Solver::global) {
    clock = std::chrono::steady_clock::now();
    auto whole = solve_whole_path(problem, result.greedy.trajectory, options.whole_path);
    if (!whole) {
      return make_error(whole.error().code, fmt::format("{}: {}", program.source, whole.error().message));
    }
    SolverReport report;
    report.seconds = seconds_since(clock);
    report.trajectory = std::move(*whole);
    report.metrics = measure(report_problem, with_forces(report_problem, report.trajectory));
    result.whole_path = std::move(report);
  }
  result.program = rebuild_program(program, result.points, result.chosen().trajectory, free);
  result.parts_written = count_parts(result.points);
  result.largest_parts = *std::max_element(result.points.parts.begin(), result.points.parts.end());
  return ok_status();
}

// Adaptive parts: each block cut as §3.6 says; the laws measured along the motion between the parts' ends.
Status solve_adaptive(const program::CanonicalProgram& program, const OptimizeOptions& options,
                      const ProgramCurves& curves, const LawEvaluator& law, Problem& report_problem,
                      const FreeCoordinates& free, const Eigen::Vector3d& tool_axis_platform,
                      OptimizeResult& result) {
  const auto clock = std::chrono::steady_clock::now();
  auto cut =
      subdivide_blocks(curves, law, options.loads, options.step_mm, *options.subdivision, options.greedy);
  if (!cut) return cut.error();
  result.greedy.seconds = seconds_since(clock);
  result.points = std::move(cut->motion);
  report_problem.points = result.points.points;
  report_problem.loads = point_loads(result.points, options.loads, tool_axis_platform);
  result.constant = measure(report_problem, constant_trajectory(report_problem));
  Trajectory motion;
  motion.values = std::move(cut->motion_values);
  motion.nodes.resize(motion.values.size());
  result.greedy.trajectory = with_forces(report_problem, motion);
  result.greedy.metrics = measure(report_problem, result.greedy.trajectory);
  std::vector<Pose> poses(cut->nodes.points.size());
  for (std::size_t k = 0; k < poses.size(); ++k)
    poses[k] = free.pose(cut->nodes.points[k], cut->node_values[k]);
  result.program = program_through_poses(program, cut->nodes, poses, false);
  result.parts_written = count_parts(cut->nodes);
  result.largest_parts = cut->largest_parts;
  return ok_status();
}

}  // namespace

Result<OptimizeResult> optimize_program(const program::CanonicalProgram& program, const Machine& machine,
                                        const OptimizeOptions& options) {
  if (Status s = check_machine_for(machine, options); !s) return s.error();
  if (!(options.step_mm > 0.0)) {
    return make_error(ErrorCode::bad_input,
                      fmt::format("path step: must be a positive length in mm, got {}", options.step_mm));
  }
  auto curves = program_curves(program, machine);
  if (!curves) return curves.error();
  OptimizeResult result;
  result.points = options.subdivision ? curves->start : sample_curves(*curves, options.step_mm);
  const Mechanism& mechanism = *machine.mechanism;
  auto kind = FreeCoordinates::kind_for(mechanism, options.free);
  if (!kind) return kind.error();
  const Eigen::Vector3d tool_axis_platform = mechanism.home().rotation.transpose() * Eigen::Vector3d::UnitZ();
  const FreeValues start = FreeCoordinates::values_for(*kind, mechanism.convention(), tool_axis_platform,
                                                       result.points.start_rotation, result.points.points[0]);
  auto free = FreeCoordinates::create(mechanism, options.free, options.bounds_deg, start);
  if (!free) return free.error();

  // Two evaluators: the solvers' computes only what the law needs (the increment law needs no statics, which
  // is most of a hexapod candidate's cost); the report's adds forces and energy for every law.
  LawEvaluator law(machine, *free, options.law, false);
  LawEvaluator report_law(machine, *free, options.law, true);
  Problem problem;
  problem.law = &law;
  problem.points = result.points.points;
  problem.loads = point_loads(result.points, options.loads, tool_axis_platform);
  const Pose start_pose = free->pose(problem.points[0], start);
  if (!law.set_start(start_pose) || !report_law.set_start(start_pose)) {
    return make_error(ErrorCode::singular, fmt::format("{}:{}: the program starts in a singular position",
                                                       program.source, problem.points[0].line));
  }
  Problem report_problem = problem;
  report_problem.law = &report_law;
  result.free_count = free->count();
  for (int i = 0; i < free->count(); ++i) {
    result.free_names.push_back(free->name(i));
    result.lower_rad[i] = free->lower_rad(i);
    result.upper_rad[i] = free->upper_rad(i);
  }
  result.start_rad = start;
  if (options.subdivision) {
    if (Status s =
            solve_adaptive(program, options, *curves, law, report_problem, *free, tool_axis_platform, result);
        !s)
      return s.error();
    return result;
  }
  result.constant = measure(report_problem, constant_trajectory(report_problem));
  if (Status s = solve_fixed(program, options, problem, report_problem, *free, result); !s) return s.error();
  return result;
}

}  // namespace pkm::redundancy
