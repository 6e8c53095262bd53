#pragma once
// The columns of a planned run's servo-rate tables, one list for both forms (formats/plan_files.hpp): the CSV
// files' header rows and the HDF5 file's datasets have the same names, in the same order, so that
// pandas.read_csv("DIR/path.csv") and the "path" group of DIR/ticks.h5 give the same columns.
#include <string>
#include <vector>

#include "formats/hdf5_table.hpp"

namespace pkm::formats {

/// Where a planned run's servo-rate tables go: CSV files (actuators.csv, path.csv, …) or one HDF5 file,
/// ticks.h5, a group per table.
enum class TickTables { csv, hdf5 };

/// Each column's HDF5 quantum is that of the digits the CSV prints (6 decimals: 2^-20; 4: 2^-14); columns the
/// CSV prints in scientific notation are kept exactly.
std::vector<Hdf5Column> actuator_columns(int actuators, bool angular);
std::vector<Hdf5Column> path_columns();
std::vector<Hdf5Column> force_columns(int actuators, bool angular, bool commands);
std::vector<Hdf5Column> response_columns();
std::vector<Hdf5Column> deflection_columns();

/// The CSV header row of `columns` (their names, comma-separated, and a newline).
std::string csv_header(const std::vector<Hdf5Column>& columns);

}  // namespace pkm::formats
