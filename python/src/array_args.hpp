#pragma once
// Numpy arguments of the batch calls: rows of a fixed width as float64, taken without a copy when they
// already are C-contiguous float64, converted where numpy can do so without losing information (lists,
// float32, integer arrays), and refused otherwise with a message that names the argument, the expected shape
// and what was given. Other binding files reuse these for their own (N, k) arguments.
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>

#include <cmath>
#include <cstddef>
#include <string>
#include <vector>

namespace pkm::python {

namespace py = pybind11;

/// Rows of `width` float64 numbers, row-major, kept alive by `array`.
struct RowArray {
  py::array_t<double, py::array::c_style> array;
  std::size_t rows = 0;
  std::size_t width = 0;
  bool single = false;  ///< given as one row of shape (width,): results drop their row axis
  const double* row(std::size_t index) const { return array.data() + index * width; }
};

/// `value` as rows of `width` numbers: shape (N, width) or (width,). Raises TypeError for complex, boolean,
/// object, string and extended-precision dtypes, and ValueError for any other shape, e.g. "poses must have
/// shape (N, 6) or (6,), got (3, 5)". Values are not checked here (see first_non_finite).
RowArray row_array(py::handle value, std::size_t width, const char* name);

/// "(3, 5)": a shape as numpy prints it.
std::string shape_text(const std::vector<py::ssize_t>& shape);

/// True when all `count` values are finite.
inline bool all_finite(const double* values, std::size_t count) {
  bool finite = true;
  for (std::size_t i = 0; i < count; ++i) finite &= std::isfinite(values[i]);
  return finite;
}

/// Raises ValueError "NAME[ROW] contains NaN or infinity" (rows are 0-based, as Python indexes them).
[[noreturn]] void raise_non_finite(const char* name, std::size_t row, bool single);

/// A new float64 array of `shape`, C order (results of the batch calls).
py::array_t<double> new_array(const std::vector<py::ssize_t>& shape);

/// The result array of a batch call: a new one when `out` is None, else `out` itself, which must be a
/// writeable, aligned, C-contiguous float64 array of exactly `shape` that does not overlap `input` (TypeError
/// or ValueError naming `name` otherwise). Reusing one saves the new array's first-touch page faults.
py::array_t<double> output_array(const py::object& out, const std::vector<py::ssize_t>& shape,
                                 const RowArray& input, const char* name);

}  // namespace pkm::python
