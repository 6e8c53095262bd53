#include "pipeline_support.hpp"

#include <fmt/format.h>

#include <cmath>

#include "bindings.hpp"

namespace pkm::python {

py::object numpy_strings(const std::vector<std::string>& values) {
  py::list list;
  for (const std::string& value : values) list.append(py::str(value));
  // dtype str keeps an empty list a string array too.
  return py::module_::import("numpy").attr("array")(list, py::arg("dtype") = "str");
}

Pose pose_from_python(const Mechanism& mechanism, const py::handle& value, const char* what) {
  py::array_t<double, py::array::c_style | py::array::forcecast> coordinates;
  try {
    coordinates = py::array_t<double, py::array::c_style | py::array::forcecast>::ensure(value);
  } catch (const py::error_already_set&) {
  }
  if (!coordinates || coordinates.ndim() != 1 || coordinates.shape(0) != 6) {
    const std::string given =
        coordinates ? fmt::format("shape {}", py::str(coordinates.attr("shape")).cast<std::string>())
                    : py::str(py::type::of(value)).cast<std::string>();
    throw py::value_error(fmt::format(
        "{}: expected 6 numbers [x_mm, y_mm, z_mm, a_rad, b_rad, c_rad] ({} convention; planar: c is phi), "
        "got {}",
        what, to_string(mechanism.convention()), given));
  }
  PoseVector v;
  for (int i = 0; i < 6; ++i) {
    v[i] = coordinates.at(i);
    if (!std::isfinite(v[i])) throw py::value_error(fmt::format("{}: coordinate {} is not finite", what, i));
  }
  return unwrap(mechanism.complete_pose(pose_from_vector(mechanism.convention(), v)));
}

PoseVector pose_vector(const Mechanism& mechanism, const Pose& pose) {
  return vector_from_pose(mechanism.convention(), pose);
}

py::array_t<double> numpy_pose(const Mechanism& mechanism, const Pose& pose) {
  const PoseVector v = pose_vector(mechanism, pose);
  return numpy_from(std::vector<double>(v.data(), v.data() + 6));
}

std::string actuator_unit(const Mechanism& mechanism) {
  return mechanism.actuators_are_angles() ? "rad" : "mm";
}

std::string drive_force_unit(const Mechanism& mechanism) {
  return mechanism.actuators_are_angles() ? "Nmm" : "N";
}

std::string optional_path(const py::object& value) {
  if (value.is_none()) return {};
  return py::module_::import("os").attr("fspath")(value).cast<std::string>();
}

pipeline::ProgramOptions program_options(const py::object& tool_table, const py::object& subroutine_path,
                                         const py::object& parameter_file) {
  pipeline::ProgramOptions options;
  options.tool_table_path = optional_path(tool_table);
  options.parameter_file = optional_path(parameter_file);
  std::vector<std::string> given;
  // A str or path-like is one entry (maybe a ':' list); anything else iterable is a list of entries.
  if (!subroutine_path.is_none()) {
    if (py::isinstance<py::str>(subroutine_path) || py::hasattr(subroutine_path, "__fspath__")) {
      given.push_back(optional_path(subroutine_path));
    } else {
      for (const py::handle entry : subroutine_path)
        given.push_back(optional_path(py::reinterpret_borrow<py::object>(entry)));
    }
  }
  options.subroutine_path = pipeline::split_search_path(given);
  return options;
}

std::vector<std::array<double, 2>> free_bounds(const py::object& value) {
  if (value.is_none()) return {};
  try {
    return {value.cast<std::array<double, 2>>()};
  } catch (const py::cast_error&) {
  }
  try {
    return value.cast<std::vector<std::array<double, 2>>>();
  } catch (const py::cast_error&) {
    throw py::type_error(
        "bounds_deg: expected (lo, hi) in degrees for every free coordinate, or one (lo, hi) "
        "for each, e.g. ((-5, 5), (-5, 5), (-20, 20))");
  }
}

}  // namespace pkm::python
