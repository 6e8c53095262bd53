#pragma once
#include <array>
// What the pipeline and analysis bindings share: numpy arrays that take over a std::vector without copying
// it, poses in and out as [x_mm, y_mm, z_mm, a_rad, b_rad, c_rad] in the machine's angle convention (as the
// C++ PoseVector), and the units of a machine's actuators in the names of the keys.
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <string>
#include <vector>

#include "machine/machine.hpp"
#include "pipeline/load_program.hpp"

namespace pkm::python {

namespace py = pybind11;

/// An array of `shape` (C order) that owns `values`; their count must be the product of the shape.
template <class T>
py::array_t<T> numpy_from(std::vector<T>&& values, std::vector<py::ssize_t> shape) {
  auto* owned = new std::vector<T>(std::move(values));
  py::capsule release(owned, [](void* data) { delete static_cast<std::vector<T>*>(data); });
  return py::array_t<T>(std::move(shape), owned->data(), release);
}

template <class T>
py::array_t<T> numpy_from(std::vector<T>&& values) {
  const auto count = static_cast<py::ssize_t>(values.size());
  return numpy_from(std::move(values), {count});
}

/// A (rows, cols) array of an Eigen matrix's entries times `scale`.
template <class Matrix>
py::array_t<double> numpy_matrix(const Matrix& a, double scale = 1.0) {
  std::vector<double> values;
  values.reserve(static_cast<std::size_t>(a.rows() * a.cols()));
  for (int r = 0; r < a.rows(); ++r)
    for (int c = 0; c < a.cols(); ++c) values.push_back(a(r, c) * scale);
  return numpy_from(std::move(values),
                    {static_cast<py::ssize_t>(a.rows()), static_cast<py::ssize_t>(a.cols())});
}

/// A 1-D numpy array of str.
py::object numpy_strings(const std::vector<std::string>& values);

/// The pose of a 6-vector [x_mm, y_mm, z_mm, a_rad, b_rad, c_rad] in the mechanism's convention (planar:
/// x, y and c = φ), completed by the mechanism. A value of another shape raises ValueError naming `what`.
Pose pose_from_python(const Mechanism& mechanism, const py::handle& value, const char* what);

/// The 6 pose coordinates (mm, rad) in the mechanism's convention.
PoseVector pose_vector(const Mechanism& mechanism, const Pose& pose);
py::array_t<double> numpy_pose(const Mechanism& mechanism, const Pose& pose);

/// "mm", or "rad" for angular actuators: the unit of the library's actuator values, used in key names.
std::string actuator_unit(const Mechanism& mechanism);
/// "N", or "Nmm" for angular drives (torques): the unit of drive forces in key names.
std::string drive_force_unit(const Mechanism& mechanism);

/// The optional string argument, empty for None.
std::string optional_path(const py::object& value);

/// bounds_deg of the redundancy laws: None, (lo, hi) for every free coordinate, or ((lo, hi), ...) for each.
std::vector<std::array<double, 2>> free_bounds(const py::object& value);

/// How a program is read, from the keyword arguments every function that reads one takes: tool_table (path
/// or None), subroutine_path (None, a path, a colon-separated string as LinuxCNC's SUBROUTINE_PATH, or a
/// list of them), parameter_file (path or None; read, never written back from Python).
pipeline::ProgramOptions program_options(const py::object& tool_table, const py::object& subroutine_path,
                                         const py::object& parameter_file);

}  // namespace pkm::python
