#pragma once
// The points at which the redundancy laws choose the free coordinates: every motion block of the program cut
// into equal parts of the same kind (lines into lines, arcs into arcs of the same radius), no longer than the
// step (Smirnov 2019, §3.6 step 3: split the block into N equal parts; Smirnov 2010's circle uses 1° steps).
//
// Moves before the first feed move (the rapids that bring the tool to the part) are kept as programmed: the
// optimisation starts where they end, with the free coordinates the program has there (`G0 X40 Y0 C15` starts
// a planar machine at φ = 15°).
#include <optional>
#include <vector>

#include "core/result.hpp"
#include "machine/machine.hpp"
#include "path/path_builder.hpp"
#include "program/canonical_program.hpp"
#include "redundancy/free_coordinates.hpp"
#include "statics/load_model.hpp"

namespace pkm::redundancy {

struct ProgramPoints {
  std::vector<PathPoint> points;  ///< points[0]: where the optimisation starts
  /// Per move: into how many equal parts it is cut (one point at the end of each); 0 for moves kept as
  /// programmed (leading moves, dwells, moves that only rotate).
  std::vector<int> parts;
  int first_move = 0;                                            ///< moves before it are kept as programmed
  Eigen::Matrix3d start_rotation = Eigen::Matrix3d::Identity();  ///< programmed rotation at points[0]
  path::PathFrame frame;
};

/// The program's motion from the first feed move on, as curves: what the points are cut from.
struct ProgramCurves {
  const program::CanonicalProgram* program = nullptr;
  /// The start point alone (where the leading moves end), with the frame, first move and start rotation;
  /// parts all 0.
  ProgramPoints start;
  /// Per move: its curve, or none for moves that are not cut (leading moves, dwells, pure turns).
  std::vector<std::optional<path::Curve>> curves;

  /// The fewest equal parts move m may be cut into: 1, or two per turn for arcs (a part under one turn).
  int fewest_parts(int m) const;
  /// The point at fraction f of move m; `previous_mm` is the point before it (for the step and tangent).
  PathPoint point(int m, double f, const Eigen::Vector3d& previous_mm) const;
  /// Appends the ends of move m's `parts` equal parts; `points` ends at the move's start.
  void append_parts(int m, int parts, std::vector<PathPoint>& points) const;
};

/// The program's curves; errors as sample_program's. The program must outlive the result.
Result<ProgramCurves> program_curves(const program::CanonicalProgram& program, const Machine& machine);

/// The process load at every point (about the tool point, base frame): the start point takes the direction
/// of the first step, the load that acts as the cut begins.
std::vector<statics::Wrench> point_loads(const ProgramPoints& points, const statics::LoadModel& loads,
                                         const Eigen::Vector3d& tool_axis_platform);

/// Every cut move of `curves` in equal parts no longer than `step_mm` (> 0).
ProgramPoints sample_curves(const ProgramCurves& curves, double step_mm);

/// The machine's frame for program coordinates (origin, home rotation, planar), as the planner uses it.
path::PathFrame program_frame(const Machine& machine);

/// Cuts the program's motion into parts no longer than `step_mm`. Errors name the source line: tool-length
/// offsets (G43) are not supported here, and a program without feed moves has nothing to optimise.
Result<ProgramPoints> sample_program(const program::CanonicalProgram& program, const Machine& machine,
                                     double step_mm);

/// The program again, through `poses` (one per point of `points`, base frame; the tool point and the
/// platform's rotation): the moves before `points.first_move` as programmed (the last of them ending at
/// poses[0]), every other move cut into its parts, each part ending at its pose; dwells kept in place; moves
/// that only turn left out (the poses own the orientation). Each part states its orientation as A B C
/// (planar: C = φ), continuous from part to part, or, with `keep_tool_axes`, as the tool axis where the move
/// gave one (CL data: the spin stays free). Arcs stay arcs when the poses keep the points on them (a law
/// choosing only the rotation); `arcs_as_lines` writes each part as a line (poses moved off the arc).
program::CanonicalProgram program_through_poses(const program::CanonicalProgram& program,
                                                const ProgramPoints& points, const std::vector<Pose>& poses,
                                                bool keep_tool_axes, bool arcs_as_lines = false);

}  // namespace pkm::redundancy
