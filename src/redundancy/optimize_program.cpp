#include "redundancy/optimize_program.hpp"

#include <fmt/format.h>

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

std::vector<statics::Wrench> point_loads(const ProgramPoints& points, const statics::LoadModel& loads,
                                         const Eigen::Vector3d& tool_axis_platform) {
  std::vector<statics::Wrench> wrenches(points.points.size());
  for (std::size_t k = 0; k < points.points.size(); ++k) {
    const PathPoint& point = points.points[k];
    statics::LoadPoint load_point;
    // The start point takes the direction of the first step: the load that acts as the cut begins.
    const PathPoint& travel = k == 0 && points.points.size() > 1 ? points.points[1] : point;
    load_point.tangent = travel.tangent;
    load_point.tool_axis = point.axis_rotation * tool_axis_platform;
    load_point.line = travel.line;
    load_point.cutting = travel.cutting;
    wrenches[k] = loads.wrench_at(load_point);
  }
  return wrenches;
}

}  // namespace

program::CanonicalProgram rebuild_program(const program::CanonicalProgram& program,
                                          const ProgramPoints& points, const Trajectory& trajectory,
                                          const FreeCoordinates& free) {
  std::vector<Pose> poses(points.points.size());
  for (std::size_t k = 0; k < poses.size(); ++k) poses[k] = free.pose(points.points[k], trajectory.values[k]);
  return program_through_poses(program, points, poses, false);
}

Result<OptimizeResult> optimize_program(const program::CanonicalProgram& program, const Machine& machine,
                                        const OptimizeOptions& options) {
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
  auto sampled = sample_program(program, machine, options.step_mm);
  if (!sampled) return sampled.error();
  OptimizeResult result;
  result.points = std::move(*sampled);
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
  result.constant = measure(report_problem, constant_trajectory(report_problem));

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
  result.program = rebuild_program(program, result.points, result.chosen().trajectory, *free);
  return result;
}

}  // namespace pkm::redundancy
