#include "redundancy/placement_study.hpp"

#include <fmt/format.h>

#include <cmath>
#include <limits>

#include "redundancy/greedy_solver.hpp"
#include "redundancy/program_points.hpp"
#include "redundancy/trajectory.hpp"
#include "redundancy/trajectory_metrics.hpp"

namespace pkm::redundancy {
namespace {

program::CanonicalProgram moved_along_z(const program::CanonicalProgram& program, double offset_mm) {
  program::CanonicalProgram moved = program;
  const Eigen::Vector3d shift(0.0, 0.0, offset_mm);
  moved.start_mm += shift;
  for (program::CanonicalMove& move : moved.moves) {
    move.end_mm += shift;
    if (move.kind == program::MoveKind::arc) move.center_mm += shift;
  }
  return moved;
}

// The plane of every point (−1: a rapid, which belongs to none): a new plane wherever a feed move ends at
// another Z. `planes` gets each plane's Z and first line.
std::vector<int> plane_of_points(const program::CanonicalProgram& moved, const std::vector<PathPoint>& points,
                                 std::vector<PlaneEnergy>& planes) {
  constexpr double kSameZ_mm = 1e-6;
  std::vector<int> plane(points.size(), -1);
  for (std::size_t k = 1; k < points.size(); ++k) {
    if (!points[k].cutting) continue;  // the retract, the rapids between passes
    const double z = moved.moves[static_cast<std::size_t>(points[k].move_index)].end_mm.z();
    if (planes.empty() || std::abs(planes.back().z_mm - z) > kSameZ_mm) planes.push_back({z, points[k].line});
    plane[k] = static_cast<int>(planes.size()) - 1;
  }
  return plane;
}

// The energy of each step into a point of a plane, summed per plane.
std::vector<double> energy_per_plane(const std::vector<int>& plane_of, std::size_t planes,
                                     const TrajectoryMetrics& metrics) {
  std::vector<double> energy(planes, 0.0);
  for (std::size_t k = 1; k < plane_of.size() && k < metrics.cumulative_energy_J.size(); ++k) {
    if (plane_of[k] >= 0)
      energy[static_cast<std::size_t>(plane_of[k])] +=
          metrics.cumulative_energy_J[k] - metrics.cumulative_energy_J[k - 1];
  }
  return energy;
}

// The free coordinates for `set` at the program's start, bounded as asked.
Result<FreeCoordinates> free_at_start(const Mechanism& mechanism, FreeSet set, const FreeBounds& bounds,
                                      const ProgramPoints& points) {
  auto kind = FreeCoordinates::kind_for(mechanism, set);
  if (!kind) {
    return make_error(kind.error().code, fmt::format("the placement study holds the platform's angles as "
                                                     "programmed: {}",
                                                     kind.error().message));
  }
  const Eigen::Vector3d tool_axis_platform = mechanism.home().rotation.transpose() * Eigen::Vector3d::UnitZ();
  const FreeValues start = FreeCoordinates::values_for(*kind, mechanism.convention(), tool_axis_platform,
                                                       points.start_rotation, points.points[0]);
  return FreeCoordinates::create(mechanism, set, bounds, start);
}

// Between two returns of the angles (each plane, with the step into the next), the law's choice or the angles
// held, whichever costs less by the law's own measure: both start the plane at the programmed angles and
// return to them, so the pieces join. The greedy step never loses to holding on one step, but over a plane it
// can (it turns where one step is cheap towards poses where the next are dearer), and a law that costs more
// than holding is no law to report.
Trajectory better_per_plane(const Problem& problem, Trajectory chosen, const Trajectory& held) {
  const LawEvaluator& law = *problem.law;
  const std::size_t count = chosen.nodes.size();
  std::size_t begin = 0;
  while (begin < count) {
    std::size_t end = begin + 1;
    while (end < count && !problem.reset[end]) ++end;
    // Steps begin+1 … end (the step into the next plane's first point included where there is one).
    double by_law = 0.0, by_holding = 0.0;
    for (std::size_t k = begin + 1; k <= std::min(end, count - 1); ++k) {
      by_law += chosen.nodes[k].valid && chosen.nodes[k - 1].valid
                    ? law.step_cost(chosen.nodes[k - 1], chosen.nodes[k])
                    : std::numeric_limits<double>::infinity();
      by_holding += held.nodes[k].valid && held.nodes[k - 1].valid
                        ? law.step_cost(held.nodes[k - 1], held.nodes[k])
                        : std::numeric_limits<double>::infinity();
    }
    if (by_holding < by_law) {
      for (std::size_t k = begin + 1; k < end; ++k) {
        chosen.values[k] = held.values[k];
        chosen.nodes[k] = held.nodes[k];
      }
    }
    begin = end;
  }
  return chosen;
}

// The law's choice of the angles along the path, returned to the programmed ones at the first point of every
// plane (Smirnov 2019, §3.8.1: "at the transition to each next plane the angles were returned to zero").
Result<TrajectoryMetrics> law_metrics(const Machine& machine, const PlacementOptions& options,
                                      const ProgramPoints& points, const std::vector<int>& plane_of,
                                      const std::vector<statics::Wrench>& loads, const std::string& source) {
  auto free = free_at_start(*machine.mechanism, FreeSet::all, options.law_bounds_deg, points);
  if (!free) return free.error();
  LawOptions law_options;
  law_options.law = *options.law;
  law_options.energy = options.accounting;
  LawEvaluator law(machine, *free, law_options, true);
  if (!law.set_start(free->pose(points.points[0], free->start())))
    return make_error(ErrorCode::singular,
                      fmt::format("{}: the program starts in a singular position", source));
  Problem problem{&law, points.points, loads, std::vector<char>(points.points.size(), 0)};
  for (std::size_t k = 1; k < plane_of.size(); ++k)
    problem.reset[k] = plane_of[k] >= 0 && plane_of[k] != plane_of[k - 1];
  auto trajectory = solve_greedy(problem, options.greedy, source);
  if (!trajectory) return trajectory.error();
  return measure(problem, better_per_plane(problem, std::move(*trajectory), constant_trajectory(problem)));
}

Result<Placement> place(const program::CanonicalProgram& program, const Machine& machine,
                        const PlacementOptions& options, double z1_mm, double offset_mm) {
  const program::CanonicalProgram moved = moved_along_z(program, offset_mm);
  auto points = sample_program(moved, machine, options.step_mm);
  if (!points) return points.error();
  auto free = free_at_start(*machine.mechanism, FreeSet::spin, {}, *points);
  if (!free) return free.error();
  LawOptions law_options;
  law_options.law = Law::energy;
  law_options.energy = options.accounting;
  LawEvaluator law(machine, *free, law_options, true);
  if (!law.set_start(free->pose(points->points[0], free->start()))) {
    return make_error(ErrorCode::singular,
                      fmt::format("{}:{}: with its first plane at Z{:g} the program starts in a singular "
                                  "position",
                                  program.source, points->points[0].line, z1_mm));
  }
  const Eigen::Vector3d tool_axis_platform =
      machine.mechanism->home().rotation.transpose() * Eigen::Vector3d::UnitZ();
  Problem problem{&law, points->points, point_loads(*points, options.loads, tool_axis_platform), {}};
  const TrajectoryMetrics metrics = measure(problem, constant_trajectory(problem));
  Placement out;
  out.z1_mm = z1_mm;
  out.offset_mm = offset_mm;
  out.feasible = metrics.feasible;
  out.first_infeasible_line = metrics.first_infeasible_line;
  out.energy_J = metrics.energy_J;
  out.required_work_J = metrics.required_work_J;
  out.peak_force_N = metrics.peak_force_N;
  const std::vector<int> plane_of = plane_of_points(moved, problem.points, out.planes);
  const std::vector<double> held = energy_per_plane(plane_of, out.planes.size(), metrics);
  for (std::size_t i = 0; i < held.size(); ++i) out.planes[i].energy_J = held[i];
  if (!options.law || !out.feasible) return out;
  auto chosen = law_metrics(machine, options, *points, plane_of, problem.loads, program.source);
  if (!chosen) {
    return make_error(chosen.error().code,
                      fmt::format("with the first plane at Z{:g}: {}", z1_mm, chosen.error().message));
  }
  out.law_energy_J = chosen->energy_J;
  const std::vector<double> by_law = energy_per_plane(plane_of, out.planes.size(), *chosen);
  for (std::size_t i = 0; i < by_law.size(); ++i) out.planes[i].law_energy_J = by_law[i];
  return out;
}

}  // namespace

Result<double> first_plane_z_mm(const program::CanonicalProgram& program) {
  for (const program::CanonicalMove& move : program.moves) {
    if (move.kind == program::MoveKind::line || move.kind == program::MoveKind::arc) return move.end_mm.z();
  }
  return make_error(ErrorCode::bad_input,
                    fmt::format("{}: the program has no feed move (G1, G2, G3 or GOTO): there is no path to "
                                "place",
                                program.source));
}

Result<std::vector<Placement>> placement_study(const program::CanonicalProgram& program,
                                               const Machine& machine, const PlacementOptions& options) {
  auto first = first_plane_z_mm(program);
  if (!first) return first.error();
  if (options.z1_mm.empty()) return make_error(ErrorCode::bad_input, "the placement study needs a height");
  std::vector<Placement> placements;
  for (double z1 : options.z1_mm) {
    auto placed = place(program, machine, options, z1, z1 - *first);
    if (!placed) return placed.error();
    placements.push_back(std::move(*placed));
  }
  return placements;
}

}  // namespace pkm::redundancy
