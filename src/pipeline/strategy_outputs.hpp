#pragma once
// What a strategy comparison (strategy_comparison.hpp) reports per strategy, and the files it writes from
// that: the table strategies.csv, each run's surface error map surface_error.csv (the commanded tool tip of
// every cutting tick with its deflection along the tool axis), and strategies.svg (the maps seen from above
// and a bar chart of the rms and largest normal error), a page without scripts or outside references.
#include <map>
#include <string>
#include <string_view>
#include <vector>

#include "core/result.hpp"

namespace pkm::pipeline {

struct StrategyScore {
  std::string name;             ///< the strategy (zigzag, …), or the stem of a given program's file name
  std::string program_path;     ///< the program that was planned (as the output directory will hold it)
  long points = 0;              ///< end points of fed moves
  double path_length_mm = 0.0;  ///< length of the fed path
  double cutting_time_s = 0.0;  ///< time on fed moves (cutting ticks / servo rate)
  double max_normal_mm = 0.0;   ///< largest |deflection along the tool axis| of the run
  int max_normal_line = 0;      ///< its program line
  double rms_normal_mm = 0.0;   ///< rms over the cutting ticks
  int rank = 0;                 ///< 1: the most accurate
};

/// The ranking criterion, in words (the table, the plot and the docs say it).
inline constexpr std::string_view kStrategyCriterion =
    "rms normal error over the cutting ticks, ties (within 1e-12 mm) by the largest normal error";

/// Sorts best first by kStrategyCriterion (stable: full ties keep their order) and numbers the ranks 1, 2, ….
void rank_strategies(std::vector<StrategyScore>& scores);

/// strategies.csv: strategy, points, path_length_mm, time_s, max_normal_um, max_line, rms_normal_um, rank;
/// one row per strategy in the order given.
std::string strategies_csv(const std::vector<StrategyScore>& scores);

/// The fed parts of a planned path: per program line the path-parameter intervals of its segments that are
/// not rapids (blends included). A tick of path.csv (line, s) is a cutting tick when s lies in one of its
/// line's intervals: the tick's segment is not a rapid, as `pkm plan --stiffness` counts them, to the six
/// decimals of s in path.csv.
class FedSegments {
 public:
  void add(int line, double s_start, double s_end);
  bool contains(int line, double s) const;

 private:
  std::map<int, std::vector<std::pair<double, double>>> ranges_;
};

struct ErrorMapPoint {
  double x_mm = 0.0, y_mm = 0.0, z_mm = 0.0;  ///< the commanded tool tip, program coordinates
  double normal_mm = 0.0;                     ///< its deflection along the tool axis
};

struct SurfaceErrorMap {
  std::string csv;                    ///< surface_error.csv: time_s,line,x_mm,y_mm,z_mm,normal_um
  std::vector<ErrorMapPoint> sample;  ///< every k-th row, at most the number asked for (for the plot)
  long rows = 0;
};

/// Reads path.csv and deflection.csv of a `pkm plan --stiffness` run side by side and keeps the cutting
/// ticks. Errors name the file and line.
Result<SurfaceErrorMap> surface_error_map(const std::string& run_directory, const FedSegments& fed,
                                          std::size_t max_sample);

/// strategies.svg: one panel per strategy (its map from above, coloured by the normal error on one scale
/// for all) and the bar chart, `scores` and `maps` in the same order.
std::string strategies_svg(const std::vector<StrategyScore>& scores,
                           const std::vector<std::vector<ErrorMapPoint>>& maps);

}  // namespace pkm::pipeline
