#include "redundancy/placement_study.hpp"

#include <fmt/format.h>

#include <cmath>

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

// The energy of each feed step summed per plane: a new plane wherever a move ends at another Z.
std::vector<PlaneEnergy> energy_per_plane(const program::CanonicalProgram& moved,
                                          const std::vector<PathPoint>& points,
                                          const TrajectoryMetrics& metrics) {
  constexpr double kSameZ_mm = 1e-6;
  std::vector<PlaneEnergy> planes;
  for (std::size_t k = 1; k < points.size() && k < metrics.cumulative_energy_J.size(); ++k) {
    if (!points[k].cutting) continue;  // the retract, the rapids between passes
    const double step_J = metrics.cumulative_energy_J[k] - metrics.cumulative_energy_J[k - 1];
    const double z = moved.moves[static_cast<std::size_t>(points[k].move_index)].end_mm.z();
    if (planes.empty() || std::abs(planes.back().z_mm - z) > kSameZ_mm)
      planes.push_back({z, points[k].line, 0.0});
    planes.back().energy_J += step_J;
  }
  return planes;
}

Result<Placement> place(const program::CanonicalProgram& program, const Machine& machine,
                        const PlacementOptions& options, double z1_mm, double offset_mm) {
  const program::CanonicalProgram moved = moved_along_z(program, offset_mm);
  auto points = sample_program(moved, machine, options.step_mm);
  if (!points) return points.error();
  const Mechanism& mechanism = *machine.mechanism;
  auto kind = FreeCoordinates::kind_for(mechanism, FreeSet::spin);
  if (!kind) {
    return make_error(kind.error().code, fmt::format("the placement study holds the platform's angles as "
                                                     "programmed: {}",
                                                     kind.error().message));
  }
  const Eigen::Vector3d tool_axis_platform = mechanism.home().rotation.transpose() * Eigen::Vector3d::UnitZ();
  const FreeValues start = FreeCoordinates::values_for(*kind, mechanism.convention(), tool_axis_platform,
                                                       points->start_rotation, points->points[0]);
  auto free = FreeCoordinates::create(mechanism, FreeSet::spin, std::nullopt, start);
  if (!free) return free.error();
  LawOptions law_options;
  law_options.law = Law::energy;
  law_options.energy = options.accounting;
  LawEvaluator law(machine, *free, law_options, true);
  if (!law.set_start(free->pose(points->points[0], start))) {
    return make_error(ErrorCode::singular,
                      fmt::format("{}:{}: with its first plane at Z{:g} the program starts in a singular "
                                  "position",
                                  program.source, points->points[0].line, z1_mm));
  }
  Problem problem;
  problem.law = &law;
  problem.points = points->points;
  problem.loads = point_loads(*points, options.loads, tool_axis_platform);
  const TrajectoryMetrics metrics = measure(problem, constant_trajectory(problem));
  Placement out;
  out.z1_mm = z1_mm;
  out.offset_mm = offset_mm;
  out.feasible = metrics.feasible;
  out.first_infeasible_line = metrics.first_infeasible_line;
  out.energy_J = metrics.energy_J;
  out.required_work_J = metrics.required_work_J;
  out.peak_force_N = metrics.peak_force_N;
  out.planes = energy_per_plane(moved, problem.points, metrics);
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
