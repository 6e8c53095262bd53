#pragma once
// Servo-rate tables in one HDF5 file (the HDF Group's C library, Debian's libhdf5-dev): each table a group,
// each column a 1-D dataset that grows by chunks of rows, stored shuffled and deflated (filters every HDF5
// reader has: h5py, pandas, MATLAB, HDFView), with its unit as the attribute "unit". Rows are appended one at
// a time into per-column buffers and written a chunk at a time, so memory does not grow with the run.
//
// A column may round its values to a binary quantum (2^-20 mm ≈ 0.95 µm for positions printed to 6 decimals
// in the CSV files): the dropped low mantissa bits are zeros, which the deflate filter removes, and the
// values stay doubles that numpy reads as they are, within half the quantum of the computed ones (the CSV's 6
// decimals keep 5e-7; 2^-21 is 4.8e-7). A column the CSV prints in scientific notation keeps as many
// significant bits as its digits need, plus one. A column of integers (program lines) is stored as 64-bit
// integers.
#include <memory>
#include <string>
#include <vector>

#include "core/result.hpp"

namespace pkm::formats {

/// One column of a table.
struct Hdf5Column {
  std::string name;      ///< the dataset's name, as the CSV header's ("x_program_mm")
  std::string unit;      ///< the "unit" attribute ("mm", "deg", "s", "" for counts)
  int quantum_bits = 0;  ///< > 0: values rounded to multiples of 2^-quantum_bits; 0: kept exactly
  bool integer = false;  ///< stored as 64-bit integers (values must be whole numbers)
  /// > 0 (and quantum_bits 0): values rounded to this many significant bits, for columns the CSV prints in
  /// scientific notation; 0: kept exactly.
  int significant_bits = 0;
};

/// The binary quantum of the CSV's `decimals` digits: the largest power of two not above 10^-decimals.
int quantum_bits_for_decimals(int decimals);
/// The significant bits that keep the CSV's `digits` significant digits (one bit more than they hold).
int significant_bits_for_digits(int digits);
/// `value` rounded to `bits` significant bits (NaN, infinities and zero as they are).
double round_to_significant_bits(double value, int bits);

class Hdf5File;

/// A table being written: append rows, then finish.
class Hdf5Table {
 public:
  Hdf5Table();
  ~Hdf5Table();
  Hdf5Table(Hdf5Table&&) noexcept;
  Hdf5Table& operator=(Hdf5Table&&) noexcept;
  Hdf5Table(const Hdf5Table&) = delete;
  Hdf5Table& operator=(const Hdf5Table&) = delete;

  /// Appends one row: `values` holds one value per column, in the columns' order. Writes a chunk when one is
  /// full.
  Status append(const double* values);
  /// Writes the rows not yet written. The table stays in the file.
  Status finish();
  long rows() const;

 private:
  friend class Hdf5File;
  struct State;
  std::unique_ptr<State> state_;
};

/// An HDF5 file being written (created or truncated at `path`); closed by the destructor. Errors name the
/// path.
class Hdf5File {
 public:
  static Result<Hdf5File> create(const std::string& path);
  Hdf5File(Hdf5File&&) noexcept;
  Hdf5File& operator=(Hdf5File&&) noexcept;
  Hdf5File(const Hdf5File&) = delete;
  Hdf5File& operator=(const Hdf5File&) = delete;
  ~Hdf5File();

  /// A new table: the group `name` with one dataset per column, `chunk_rows` rows per chunk.
  Result<Hdf5Table> table(const std::string& name, const std::vector<Hdf5Column>& columns,
                          long chunk_rows = 16384);
  /// A string attribute of the file's root (what made it: "pkm_version", "program", "machine").
  Status set_attribute(const std::string& name, const std::string& value);
  /// Closes the file (every table must be finished first); its contents are then complete on disk.
  Status close();

 private:
  Hdf5File(std::string path, long long id) : path_(std::move(path)), id_(id) {}
  std::string path_;
  long long id_ = -1;
};

/// Column `column` of table `table` in the HDF5 file at `path`, as doubles (integers converted), and its
/// "unit" attribute. For readers of ticks.h5 (the report, the tests). Errors name the file and the column.
struct Hdf5ColumnData {
  std::vector<double> values;
  std::string unit;
};
Result<Hdf5ColumnData> read_hdf5_column(const std::string& path, const std::string& table,
                                        const std::string& column);

}  // namespace pkm::formats
