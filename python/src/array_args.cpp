#include "array_args.hpp"

#include <fmt/format.h>

namespace pkm::python {
namespace {

std::string expected_shapes(std::size_t width) {
  return fmt::format("(N, {}) or ({},)", width, width);
}

std::vector<py::ssize_t> shape_of(const py::array& array) {
  return {array.shape(), array.shape() + array.ndim()};
}

// Real numbers that float64 holds exactly enough: floats up to 64 bits and integers. Booleans are refused
// because True as 1.0 mm is almost always a mistake; extended precision because it would be rounded.
void check_dtype(const py::array& array, std::size_t width, const char* name) {
  const py::dtype dtype = array.dtype();
  const char kind = dtype.kind();
  if (kind == 'i' || kind == 'u' || (kind == 'f' && dtype.itemsize() <= 8)) return;
  const auto dtype_name = dtype.attr("name").cast<std::string>();
  if (kind == 'f') {
    throw py::type_error(
        fmt::format("{} has dtype {}, which float64 would round; convert it with .astype(float) first", name,
                    dtype_name));
  }
  throw py::type_error(
      fmt::format("{} must be real numbers of shape {} (float64, or any float or integer "
                  "dtype), got dtype {}",
                  name, expected_shapes(width), dtype_name));
}

}  // namespace

std::string shape_text(const std::vector<py::ssize_t>& shape) {
  if (shape.size() == 1) return fmt::format("({},)", shape[0]);
  return fmt::format("({})", fmt::join(shape, ", "));
}

RowArray row_array(py::handle value, std::size_t width, const char* name) {
  py::array source;
  if (py::isinstance<py::array>(value)) {
    source = py::reinterpret_borrow<py::array>(value);
  } else {
    // Lists, tuples, scalars: numpy decides the dtype, then the same checks as for arrays apply.
    source = py::array::ensure(value);
    if (!source) {
      throw py::value_error(
          fmt::format("{} must be numbers of shape {}; numpy cannot make an array of the "
                      "{} given (rows of different lengths?)",
                      name, expected_shapes(width), Py_TYPE(value.ptr())->tp_name));
    }
  }
  check_dtype(source, width, name);
  const auto ndim = source.ndim();
  const auto w = static_cast<py::ssize_t>(width);
  const bool single = ndim == 1 && source.shape(0) == w;
  if (!single && !(ndim == 2 && source.shape(1) == w)) {
    throw py::value_error(fmt::format("{} must have shape {}, got {}", name, expected_shapes(width),
                                      shape_text(shape_of(source))));
  }
  using Rows = py::array_t<double, py::array::c_style>;
  RowArray out;
  constexpr int kAligned = py::detail::npy_api::NPY_ARRAY_ALIGNED_;
  if (Rows::check_(source) && (source.flags() & kAligned) != 0) {
    out.array = py::reinterpret_borrow<Rows>(source);  // float64, C order: no copy
  } else {
    out.array = py::reinterpret_steal<Rows>(
        py::array_t<double, py::array::c_style | py::array::forcecast>::ensure(source).release());
    if (!out.array) {
      throw py::type_error(fmt::format("{} of dtype {} cannot be converted to float64", name,
                                       source.dtype().attr("name").cast<std::string>()));
    }
  }
  out.rows = single ? 1 : static_cast<std::size_t>(source.shape(0));
  out.width = width;
  out.single = single;
  return out;
}

void raise_non_finite(const char* name, std::size_t row, bool single) {
  if (single) throw py::value_error(fmt::format("{} contains NaN or infinity", name));
  throw py::value_error(fmt::format("{}[{}] contains NaN or infinity", name, row));
}

py::array_t<double> new_array(const std::vector<py::ssize_t>& shape) {
  return py::array_t<double>(shape);
}

py::array_t<double> output_array(const py::object& out, const std::vector<py::ssize_t>& shape,
                                 const RowArray& input, const char* name) {
  if (out.is_none()) return new_array(shape);
  using Rows = py::array_t<double, py::array::c_style>;
  constexpr int kNeeded = py::detail::npy_api::NPY_ARRAY_ALIGNED_ | py::detail::npy_api::NPY_ARRAY_WRITEABLE_;
  if (!Rows::check_(out) || (py::reinterpret_borrow<py::array>(out).flags() & kNeeded) != kNeeded) {
    throw py::type_error(fmt::format("{} must be a writeable C-contiguous float64 array of shape {}", name,
                                     shape_text(shape)));
  }
  auto array = py::reinterpret_borrow<py::array_t<double>>(out);
  const std::vector<py::ssize_t> given(array.shape(), array.shape() + array.ndim());
  if (given != shape) {
    throw py::value_error(
        fmt::format("{} must have shape {}, got {}", name, shape_text(shape), shape_text(given)));
  }
  const double* begin = array.data();
  const double* end = begin + array.size();
  const double* input_begin = input.array.data();
  const double* input_end = input_begin + input.array.size();
  if (begin < input_end && input_begin < end) {
    throw py::value_error(fmt::format("{} must not share memory with the input", name));
  }
  return array;
}

}  // namespace pkm::python
