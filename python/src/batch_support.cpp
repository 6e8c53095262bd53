#include "batch_support.hpp"

#include <fmt/format.h>

#include "bindings.hpp"

namespace pkm::python {

OnError on_error_mode(const std::string& errors) {
  if (errors == "raise") return OnError::raise;
  if (errors == "nan") return OnError::nan;
  throw py::value_error(fmt::format("errors must be 'raise' or 'nan', got '{}'", errors));
}

Error unreachable_error(const Machine& machine, const Pose& pose, bool check_limits) {
  auto q = machine.mechanism->inverse(pose);
  if (!q) return q.error();
  if (check_limits) {
    if (auto range = check_actuator_range(machine, *q); !range) {
      return make_error(ErrorCode::unreachable,
                        "pose unreachable within the actuator range: " + range.error().message);
    }
  }
  return make_error(ErrorCode::unreachable, "the pose has no finite actuator values");
}

void raise_row_error(const Error& error, const char* name, std::size_t row, bool single) {
  const std::string message = single ? error.message : fmt::format("{}[{}]: {}", name, row, error.message);
  const ErrorLocation& at = error.location;
  const py::object exception =
      py::module_::import("pkm._errors")
          .attr("from_error")(error_code_name(error.code), message, at.file, at.line, at.column, at.key);
  exception.attr("row") = single ? py::object(py::none()) : py::object(py::int_(row));
  PyErr_SetObject(reinterpret_cast<PyObject*>(Py_TYPE(exception.ptr())), exception.ptr());
  throw py::error_already_set();
}

}  // namespace pkm::python
