#pragma once
// Reading a run's CSV outputs back (actuators.csv, path.csv, steps.csv, contour.csv) for the report: a header
// of column names, then rows of numbers. Rows are read one at a time, so a run of any length fits; an empty
// field is NaN. A malformed row is an error naming the file, the line and the column.
#include <fstream>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "core/result.hpp"

namespace pkm::report {

class CsvReader {
 public:
  /// Opens the file and reads its header line.
  Status open(const std::string& path);
  const std::vector<std::string>& columns() const { return columns_; }
  /// The index of a column, or −1.
  int column(std::string_view name) const;
  /// The index of a column that must be there (error naming the file otherwise).
  Result<int> require(std::string_view name) const;
  /// The next row's numbers (as many as columns); false at the end or on an error (see error()).
  bool next(std::vector<double>& row);
  const std::optional<Error>& error() const { return error_; }
  long line() const { return line_; }
  const std::string& path() const { return path_; }

 private:
  std::string path_;
  std::ifstream in_;
  std::vector<std::string> columns_;
  std::string text_;
  long line_ = 0;
  std::optional<Error> error_;
};

/// The next rows of two files written side by side (one row per tick or period each): true with both rows,
/// false when both have ended; an error if either file has one or they end at different rows.
Result<bool> next_in_step(CsvReader& a, std::vector<double>& row_a, CsvReader& b, std::vector<double>& row_b);

/// Counts the lines of a file after the first (the rows of a CSV with a header), fast.
Result<long> count_csv_rows(const std::string& path);

}  // namespace pkm::report
