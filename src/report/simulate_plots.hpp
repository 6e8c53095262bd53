#pragma once
// The machine simulation's plots in a plan's report: when the plan's folder holds simulate_summary.json and
// simulate.csv (pipeline/simulate_program.hpp, `pkm simulate` joined to the plan), the report gets
//   - two more charts over time and path length, read tick by tick in step with the path table and decimated
//     like every plot: the contour error of the machine in the loop with its servo, elastic, load and drives
//     parts, and the tool's actual point less the commanded one (x, y, z): where and how the actual path
//     leaves the commanded one;
//   - rows of the summary table: the largest contour error with its line, and each part's largest.
// A simulation of another run (a different number of ticks than the plan's) is not shown; the table says so.
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "core/result.hpp"
#include "report/csv_table.hpp"
#include "report/decimator.hpp"

namespace pkm::report {

inline constexpr const char* kSimulateSummaryJson = "simulate_summary.json";
inline constexpr const char* kSimulateTicksCsv = "simulate.csv";

class SimulateTrace {
 public:
  /// Opens DIR/simulate.csv when DIR holds simulate_summary.json; without it the trace stays inactive.
  Status open(const std::string& directory, const nlohmann::json& plan_summary, long expected_rows,
              int buckets);
  bool active() const { return active_; }
  /// Reads the next row, which must be the tick the path table has at `time_s` (path length `s_mm`).
  Status next(double time_s, double s_mm);
  /// After the last tick: simulate.csv must end there too.
  Status finish();
  nlohmann::json charts() const;
  nlohmann::json table_rows() const;

 private:
  bool active_ = false;
  bool split_ = false;
  std::string note_;
  nlohmann::json summary_;
  CsvReader csv_;
  int time_col_ = 0;
  std::vector<int> error_cols_;      // contour error, then the parts
  std::vector<int> deviation_cols_;  // actual x y z, then commanded x y z
  std::vector<double> row_, values_;
  std::vector<MinMaxDecimator> plots_;  // contour error and parts, deviation
};

}  // namespace pkm::report
