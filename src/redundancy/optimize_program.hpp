#pragma once
// Smirnov's post-processor (§3.6): a part program whose operation leaves coordinates free (X Y Z only, or CL
// tool point + axis) in, the same program with the free coordinates chosen by a law out — blocks cut into
// equal parts of the same kind, the feed of every part the feed of its block (the contour speed is kept).
#include <array>
#include <optional>

#include "machine/machine.hpp"
#include "program/canonical_program.hpp"
#include "redundancy/block_subdivision.hpp"
#include "redundancy/greedy_solver.hpp"
#include "redundancy/program_points.hpp"
#include "redundancy/trajectory_metrics.hpp"
#include "redundancy/whole_path_solver.hpp"
#include "statics/load_model.hpp"

namespace pkm::redundancy {

enum class Solver { greedy, global };
std::optional<Solver> solver_from_string(std::string_view name);

struct OptimizeOptions {
  LawOptions law;
  FreeSet free = FreeSet::spin;
  FreeBounds bounds_deg;
  /// Fixed parts: every block cut into parts no longer than this. Adaptive parts (`subdivision`): the step
  /// along which each part's criterion is measured.
  double step_mm = 1.0;
  /// Cut each block adaptively (§3.6, block_subdivision.hpp) instead of into fixed steps; greedy solver only.
  std::optional<SubdivisionSettings> subdivision;
  Solver solver = Solver::greedy;
  statics::LoadModel loads;
  GreedySettings greedy;
  WholePathSettings whole_path;
};

struct SolverReport {
  Trajectory trajectory;
  TrajectoryMetrics metrics;
  double seconds = 0.0;
};

struct OptimizeResult {
  program::CanonicalProgram program;  ///< the post-processed program (A B C on every move)
  /// The points the laws are measured at: the parts' ends (fixed parts), or the motion between them sampled
  /// at the step (adaptive parts).
  ProgramPoints points;
  int parts_written = 0;  ///< blocks of the output program cut from the feed moves
  int largest_parts = 0;  ///< the most parts one block was cut into
  std::vector<std::string> free_names;
  FreeValues lower_rad = FreeValues::Zero();
  FreeValues upper_rad = FreeValues::Zero();
  FreeValues start_rad = FreeValues::Zero();
  int free_count = 0;
  TrajectoryMetrics constant;
  SolverReport greedy;
  std::optional<SolverReport> whole_path;
  const SolverReport& chosen() const { return whole_path ? *whole_path : greedy; }
};

Result<OptimizeResult> optimize_program(const program::CanonicalProgram& program, const Machine& machine,
                                        const OptimizeOptions& options);

/// The program with the free coordinates of `trajectory` written as A B C (planar: C = φ).
program::CanonicalProgram rebuild_program(const program::CanonicalProgram& program,
                                          const ProgramPoints& points, const Trajectory& trajectory,
                                          const FreeCoordinates& free);

}  // namespace pkm::redundancy
