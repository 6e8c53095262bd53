#pragma once
// `pkm strategies` as one library call (Rusanov et al., Fig. 9; docs/strategies.md): the five machining
// strategies over an ellipsoid cap (path/surface_strategies.hpp) and any given part programs, each planned on
// the machine with the tool's deflection under the cutting load (pkm plan --stiffness), scored by the error
// it leaves along the surface normal, and ranked by kStrategyCriterion.
//
// Output directory DIR: strategies.csv (the table), strategies.svg (the maps and the bars), and per strategy
// DIR/<name>/ with its run (actuators.csv, path.csv, summary.json, deflection.csv), its surface error map
// surface_error.csv, and for a generated strategy its program.cl. Everything is written as one output set
// (io/output_set.hpp): after a failure DIR holds the previous complete comparison, or nothing from this one.
#include <optional>
#include <string>
#include <vector>

#include "core/progress.hpp"
#include "machine/machine.hpp"
#include "path/surface_strategies.hpp"
#include "pipeline/strategy_outputs.hpp"
#include "planning/motion_plan.hpp"
#include "statics/load_model.hpp"

namespace pkm::pipeline {

struct StrategyComparisonJob {
  /// The five strategies over this cap (program coordinates); none: only `programs`.
  std::optional<path::EllipsoidCap> surface;
  path::StrategyOptions strategy;     ///< step-over and point spacing on the surface
  double feed_mm_min = 1200.0;        ///< of the generated programs
  std::vector<std::string> programs;  ///< more part programs to rank: CL data (tool axis = normal) or G-code
  statics::LoadModel load;            ///< the cutting load (empty: no load, zero errors)
  planning::PlanOptions plan;         ///< servo rate, override, blending tolerance
  std::string out_directory;
  std::size_t map_points_in_plot = 1500;  ///< per strategy in strategies.svg
  /// Told each case's phases as "NAME (k of N): phase", with the plan's fraction and program line.
  ProgressSink progress;
};

struct StrategyComparison {
  std::vector<StrategyScore> ranking;  ///< best first (rank 1, 2, …)
};

/// Checks the job before anything is written (the cap, step-over, spacing, feed, that there is something to
/// compare, the struts' stiffness), then generates, plans and ranks. A failing plan names the strategy.
Result<StrategyComparison> compare_strategies(const Machine& machine, const StrategyComparisonJob& job);

}  // namespace pkm::pipeline
