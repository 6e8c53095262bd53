#include "formats/plan_tables.hpp"

#include <fmt/format.h>

namespace pkm::formats {

namespace {

constexpr int kExact = 0;

// A column the CSV prints with `decimals` digits after the point.
Hdf5Column fixed(std::string name, std::string unit, int decimals) {
  return {std::move(name), std::move(unit), quantum_bits_for_decimals(decimals), false};
}

// A column the CSV prints in scientific notation with `digits` significant digits.
Hdf5Column significant(std::string name, std::string unit, int digits) {
  return {std::move(name), std::move(unit), kExact, false, significant_bits_for_digits(digits)};
}

Hdf5Column program_line() {
  return {"line", "", kExact, true};
}

}  // namespace

std::vector<Hdf5Column> actuator_columns(int actuators, bool angular) {
  const std::string unit = angular ? "deg" : "mm";
  std::vector<Hdf5Column> columns{fixed("time_s", "s", 6)};
  for (int j = 1; j <= actuators; ++j) columns.push_back(fixed(fmt::format("q{}_{}", j, unit), unit, 6));
  return columns;
}

std::vector<Hdf5Column> path_columns() {
  return {fixed("time_s", "s", 6),
          program_line(),
          fixed("s", "mm", 6),
          fixed("x_program_mm", "mm", 6),
          fixed("y_program_mm", "mm", 6),
          fixed("z_program_mm", "mm", 6),
          fixed("a_abc_deg", "deg", 6),
          fixed("b_abc_deg", "deg", 6),
          fixed("c_abc_deg", "deg", 6),
          fixed("path_speed_mm_s", "mm/s", 4),
          fixed("feed_mm_s", "mm/s", 4),
          significant("path_error_mm", "mm", 4)};
}

std::vector<Hdf5Column> force_columns(int actuators, bool angular, bool commands) {
  const std::string unit = angular ? "Nmm" : "N";
  std::vector<Hdf5Column> columns{fixed("time_s", "s", 6), program_line()};
  for (int j = 1; j <= actuators; ++j) {
    columns.push_back(fixed(fmt::format("P{}_{}", j, unit), unit, 4));
    columns.push_back(fixed(fmt::format("P{}_static_{}", j, unit), unit, 4));
    columns.push_back(fixed(fmt::format("P{}_dynamic_{}", j, unit), unit, 4));
  }
  for (int j = 1; j <= actuators; ++j) columns.push_back(fixed(fmt::format("power{}_W", j), "W", 5));
  // A drive that is not ideal needs another command than the force: u_j, what to feed forward.
  for (int j = 1; j <= actuators && commands; ++j)
    columns.push_back(fixed(fmt::format("u{}_{}", j, unit), unit, 4));
  return columns;
}

std::vector<Hdf5Column> response_columns() {
  return {fixed("time_s", "s", 6),
          program_line(),
          significant("dx_mm", "mm", 5),
          significant("dy_mm", "mm", 5),
          significant("dz_mm", "mm", 5),
          significant("rotation_deg", "deg", 5),
          significant("tool_error_mm", "mm", 5)};
}

std::vector<Hdf5Column> deflection_columns() {
  return {fixed("time_s", "s", 6),
          program_line(),
          significant("dx_mm", "mm", 5),
          significant("dy_mm", "mm", 5),
          significant("dz_mm", "mm", 5),
          significant("normal_mm", "mm", 5),
          significant("rotation_rad", "rad", 5)};
}

std::string csv_header(const std::vector<Hdf5Column>& columns) {
  std::string header;
  for (const Hdf5Column& column : columns) {
    if (!header.empty()) header += ',';
    header += column.name;
  }
  return header + '\n';
}

}  // namespace pkm::formats
