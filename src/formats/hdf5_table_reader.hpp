#pragma once
// Reading a table of an HDF5 file written by Hdf5File (formats/hdf5_table.hpp) back row by row: every column
// of the group, in the order they were written, read a block of rows at a time (hyperslab selections of
// `block_rows` rows per column), so that memory stays the same however long the table is. The report reads
// a run's ticks.h5 this way, as it reads the CSV files a line at a time. Columns stored as Hdf5File writes
// them (shuffled and deflated chunks, all chunked alike) are read a whole chunk at a time, raw, and inflated
// by libdeflate on a thread of their own while the caller reads the chunk before (three to four times faster
// than HDF5's zlib pipeline); any other table is read through HDF5's own filters.
#include <memory>
#include <string>
#include <vector>

#include "core/result.hpp"

namespace pkm::formats {

class Hdf5TableReader {
 public:
  /// Opens the group `table` of the HDF5 file at `path`; its datasets must be 1-D columns of the same
  /// length. Errors name the file and the table. `block_rows` is the chunk's rows for a table read raw.
  static Result<Hdf5TableReader> open(const std::string& path, const std::string& table,
                                      long block_rows = 16384);
  Hdf5TableReader(Hdf5TableReader&&) noexcept;
  Hdf5TableReader& operator=(Hdf5TableReader&&) noexcept;
  Hdf5TableReader(const Hdf5TableReader&) = delete;
  Hdf5TableReader& operator=(const Hdf5TableReader&) = delete;
  ~Hdf5TableReader();

  /// The columns' names, in the order they were written (by name for files that did not track it).
  const std::vector<std::string>& columns() const;
  const std::vector<std::string>& units() const;
  long rows() const;
  /// Rows read so far by next().
  long rows_read() const;
  /// The next row (one value per column, integers as doubles) into `row`: true, or false after the last.
  Result<bool> next(std::vector<double>& row);

 private:
  struct State;
  explicit Hdf5TableReader(std::unique_ptr<State> state);
  std::unique_ptr<State> state_;
};

}  // namespace pkm::formats
