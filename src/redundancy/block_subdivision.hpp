#pragma once
// Smirnov 2019, §3.6 as the seeds give it: every block of the program is cut into N equal parts of its own
// kind (lines into lines, arcs into arcs of the same radius) for N = N₀, N₀ + 1, …; for each N the free
// coordinates at the end of every part are chosen by the law from the part's start (the greedy step), and
// the block's criterion is summed over its parts. N grows until a finer partition lowers the criterion by no
// more than a share of it, or the parts would be shorter than a length (§3.6 step 3g); the best partition
// found is written, one G-code block per part, each with A B C at its end.
//
// Between the ends of a part the controller interpolates A B C linearly (a piecewise-linear angle law), so a
// part's criterion is that of this motion, sampled along the part at most `step_mm` apart, not of its two
// ends alone: a coarse partition measured only at its ends would look cheaper than it is (a whole circle's
// strut lengths end where they began). The loads of a part are those at its start, held along it (§3.6
// step 3b). Step laws (increment, energy, rotation) sum their steps; pointwise laws (force, potential) take
// the part's, and the block's, largest value (a sum would grow with N by construction).
//
// N₀ is 1 for lines and two per turn for arcs (a part under one turn); the seeds begin at 2, which a block
// too short to be worth cutting never needs. The free coordinates carry over from block to block.
#include <vector>

#include "core/result.hpp"
#include "redundancy/program_points.hpp"
#include "redundancy/step_minimiser.hpp"
#include "redundancy/trajectory.hpp"
#include "statics/load_model.hpp"

namespace pkm::redundancy {

struct SubdivisionSettings {
  /// A finer partition must lower the block's criterion by more than this share of it to go on (§3.6's
  /// ε_crit, relative so that it means the same for millimetres, newtons and joules).
  double improvement = 0.01;
  double min_part_mm = 1.0;  ///< parts are never cut shorter than this (§3.6's minimum segment length)
  int max_parts = 1000;      ///< per block, whatever the two rules say
  /// How many finer cuts in a row may fail to pay before the search stops (the seeds stop at the first: 1).
  int patience = 3;
};

/// The program cut block by block, and the motion it makes.
struct SubdividedProgram {
  ProgramPoints nodes;                    ///< the written parts' ends (points[0] the start), parts per move
  std::vector<FreeValues> node_values;    ///< rad, one per node
  ProgramPoints motion;                   ///< the motion between the nodes, points at most the step apart
  std::vector<FreeValues> motion_values;  ///< rad, linear between the nodes
  int largest_parts = 0;                  ///< the most parts any block was cut into
};

/// `law` must have its start set (LawEvaluator::set_start) at the start values of its free coordinates.
/// Errors name the program line where no admissible values exist for any partition.
Result<SubdividedProgram> subdivide_blocks(const ProgramCurves& curves, const LawEvaluator& law,
                                           const statics::LoadModel& loads, double step_mm,
                                           const SubdivisionSettings& settings, const GreedySettings& greedy);

/// The motion between given nodes (one value per node, linear between them), sampled along every part at
/// most `step_mm` apart; for measuring a partition made some other way on the same terms.
void sample_between_nodes(const ProgramCurves& curves, const ProgramPoints& nodes,
                          const std::vector<FreeValues>& node_values, double step_mm, ProgramPoints& motion,
                          std::vector<FreeValues>& motion_values);

}  // namespace pkm::redundancy
