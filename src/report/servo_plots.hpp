#pragma once
// The servo plots of a plan's report: when the servo directory (the plan's own, or where `pkm servo --out`
// wrote) holds servo_summary.json, servo.csv and servo_bode.csv (pipeline/servo_program.hpp), the report gets
//   - two more charts over time and path length, read tick by tick in step with path.csv and decimated like
//     every plot (as dynamics_trace.hpp does): each drive's following error (e1, e2, …) and the contour
//     error at the tool;
//   - rows of the summary table: the largest contour error with its line, the largest lag, the largest
//     following error with its drive and line, where the loops' limits acted, the coupling check, the loops'
//     margins; the limits that acted among the limits reached, and drives at the coupling ratio limit among
//     the warnings;
//   - a `servo` object (docs/report-data.md) with servo_summary.json and each drive's loops as Bode data
//     (servo_bode.csv), which the page draws as a Bode plot per loop (web/src/servo.js).
// A servo_summary.json of another run (a different number of ticks than the plan's: the plan was run again
// since) is not shown; the table and the warnings say so.
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "core/result.hpp"
#include "machine/machine.hpp"
#include "report/csv_table.hpp"
#include "report/decimator.hpp"

namespace pkm::report {

/// The files of a `pkm servo` run.
inline constexpr const char* kServoSummaryJson = "servo_summary.json";
inline constexpr const char* kServoTicksCsv = "servo.csv";
inline constexpr const char* kServoBodeCsv = "servo_bode.csv";

/// `servo.bode` from a servo_bode.csv of `drives` drives: one object per drive, {"drive", "frequency_hz":
/// [...]} and an array per column of the file (null where a sampled column is empty, above the Nyquist
/// frequency). Errors name the file (and line) where it is malformed or lacks a drive.
Result<nlohmann::json> servo_bode_json(const std::string& path, int drives);

class ServoTrace {
 public:
  /// Opens DIR/servo.csv when DIR holds servo_summary.json (DIR: `servo_directory`, or the plan's `directory`
  /// when that is empty); without it the trace stays inactive. The summary must be a servo run of `drives`
  /// drives; one of another number of ticks than `plan_summary`'s stays inactive with a note for the table.
  Status open(const std::string& directory, const std::string& servo_directory,
              const nlohmann::json& plan_summary, int drives, long expected_rows, int buckets);
  bool active() const { return active_; }

  /// Reads the next row of servo.csv, which must be the tick path.csv has at `time_s` (path length `s_mm`).
  Status next(double time_s, double s_mm);
  /// After the last tick: servo.csv must end there too; closes the decimation.
  Status finish();

  /// The plots: following error per drive (with ± e_max where every drive of `machine` has the same) and
  /// contour error.
  nlohmann::json charts(const Machine& machine) const;
  /// Rows of the summary table (also the note on a servo run of another plan).
  nlohmann::json table_rows() const;
  /// The report's warnings of the servo run: drives at or above the coupling ratio limit, a servo run of
  /// another plan (not shown).
  nlohmann::json warnings() const;
  /// The limits of the loops that acted (e_max, u_max), one entry per drive, for `limits_reached`.
  nlohmann::json limit_entries() const;
  /// The `servo` object: {"directory", "files", "summary", "nyquist_hz", "charts", "bode"}.
  Result<nlohmann::json> object() const;

 private:
  bool active_ = false;
  int drives_ = 0;
  std::string directory_, unit_ = "mm", note_;
  nlohmann::json summary_;
  CsvReader csv_;
  int time_col_ = 0, contour_col_ = 0;
  std::vector<int> error_cols_;
  std::vector<double> row_, error_;
  std::vector<MinMaxDecimator> plots_;  // following error, contour error
};

}  // namespace pkm::report
