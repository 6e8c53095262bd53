#pragma once
// What a `pkm plan --dynamics [--elastic]` run adds to its report (docs/report.md): the drive forces (total,
// static and dynamic part), the drive powers and the cumulative energy of the forces table, and the elastic
// machine's dynamic tool error of the response table (forces.csv and response.csv, or their groups of
// ticks.h5: report/table_rows.hpp). Both have one row per servo tick like the path table, so they are read
// tick by tick in step with it (memory does not grow with the run) and decimated like every plot.
#include <memory>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "core/result.hpp"
#include "machine/machine.hpp"
#include "report/decimator.hpp"
#include "report/table_rows.hpp"

namespace pkm::report {

class DynamicsTrace {
 public:
  /// Opens the forces table (and the response table when the run was elastic) of DIR, in the form `tables`,
  /// if the summary has a "dynamics" block: the summary says what the last run wrote, whereas the directory
  /// may still hold an earlier run's forces.csv. Without the block the trace stays inactive. A table the
  /// summary promises but that is missing or lacks a drive's columns is an error naming it.
  Status open(const std::string& directory, formats::TickTables tables, const nlohmann::json& summary,
              int drives, long expected_rows, int buckets);
  bool active() const { return active_; }
  bool elastic() const { return elastic_; }

  /// Reads the next row of each table, which must be the tick the path has at `time_s` (path length `s_mm`).
  Status next(double time_s, double s_mm);
  /// After the last tick: the tables must end there too; closes the decimation.
  Status finish();

  /// Each drive's total force at the tick last read (positive: the drive pushes, strut in compression).
  const std::vector<double>& forces() const { return total_; }
  /// The largest |total force| of any drive over every tick, not only the kept ones.
  double peak_force() const;
  /// "N", or "N·mm" for angular drives (the forces table's P1_Nmm).
  const std::string& force_unit() const { return force_unit_; }

  /// The plots: drive forces (total, static, dynamic part), drive power, cumulative energy and, when elastic,
  /// the dynamic tool error. `force_limit` draws ± the drives' force limit on the force plot.
  nlohmann::json charts(const std::optional<double>& force_limit) const;

 private:
  bool active_ = false, elastic_ = false;
  int drives_ = 0;
  double period_s_ = 0.0;
  std::string force_unit_ = "N";
  std::unique_ptr<TableRows> forces_, response_;
  std::vector<int> total_col_, static_col_, dynamic_col_, power_col_, response_col_;
  int forces_time_col_ = 0, response_time_col_ = 0;
  std::vector<double> row_, total_, static_part_, dynamic_part_, power_, energy_J_, error_;
  double previous_time_s_ = 0.0;
  long rows_ = 0;
  std::vector<MinMaxDecimator> plots_;  // total, static, dynamic, power, energy, dynamic error
};

}  // namespace pkm::report
