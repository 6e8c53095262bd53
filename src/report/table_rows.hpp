#pragma once
// A servo-rate table of a planned run (formats/plan_tables.hpp) read row by row, whichever form holds it: the
// CSV file DIR/<table>.csv (CsvReader, a line at a time) or the group <table> of DIR/ticks.h5
// (formats/hdf5_table_reader.hpp, a block of rows at a time). Either way the memory does not grow with the
// run, and the readers (the report, pkm servo) see the same named columns in the same order. The form is the
// one the folder holds: ticks.h5 when it is there (pkm plan writes one form and removes the other run's).
#include <memory>
#include <string>
#include <string_view>
#include <vector>

#include "core/result.hpp"
#include "formats/plan_tables.hpp"

namespace pkm::report {

class TableRows {
 public:
  virtual ~TableRows() = default;
  /// The columns' names, in the table's order.
  virtual const std::vector<std::string>& columns() const = 0;
  /// The next row's numbers (as many as columns): true, false after the last row, or an error naming the
  /// file and the row.
  virtual Result<bool> next(std::vector<double>& row) = 0;
  /// Where the row last read is, for messages: "DIR/path.csv:12" (file and line), "DIR/ticks.h5: path row
  /// 11"; `ahead` rows further on.
  virtual std::string where(long ahead = 0) const = 0;
  /// The number of rows (a CSV file is counted through once, fast; an HDF5 table knows it).
  virtual Result<long> count_rows() const = 0;
  /// The table as messages name it: "DIR/path.csv", "DIR/ticks.h5 (path)".
  virtual const std::string& name() const = 0;

  /// The index of a column, or −1.
  int column(std::string_view name) const;
  /// The index of a column that must be there (an error naming the table otherwise).
  Result<int> require(std::string_view name) const;
};

/// A tick's time as a table holds it, to the microsecond. The ticks' times are multiples of the servo period:
/// the CSV prints them to the µs, ticks.h5 keeps them to 2^-20 s (formats/plan_tables.hpp). Read back to the
/// µs (the CSV's times as they are), a tick has the same time, period, speed and acceleration whichever form
/// the run wrote.
double tick_time_s(double stored_s);

/// The form of the servo-rate tables in `directory`: hdf5 when it holds ticks.h5, else csv.
formats::TickTables tick_tables_in(const std::string& directory);
/// The tables' file(s) of that form are in `directory` (ticks.h5; actuators.csv and path.csv).
bool has_tick_tables(const std::string& directory);

/// Opens the table `table` ("actuators", "path", "forces", "response", "deflection") of the run in
/// `directory`, in the form `tables`. `block_rows`: the rows an HDF5 table reads at a time.
Result<std::unique_ptr<TableRows>> open_tick_table(const std::string& directory, formats::TickTables tables,
                                                   const std::string& table, long block_rows = 16384);

/// The next rows of two tables written side by side (one row per tick each): true with both rows, false
/// when both have ended; an error if either has one or they end at different rows.
Result<bool> next_in_step(TableRows& a, std::vector<double>& row_a, TableRows& b, std::vector<double>& row_b);

}  // namespace pkm::report
