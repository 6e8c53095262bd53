// Library errors as the typed exceptions of pkm/_errors.py.
#include <pybind11/pybind11.h>

#include "bindings.hpp"

namespace pkm::python {

const char* error_code_name(ErrorCode code) {
  switch (code) {
    case ErrorCode::bad_input:
      return "bad_input";
    case ErrorCode::unreachable:
      return "unreachable";
    case ErrorCode::not_converged:
      return "not_converged";
    case ErrorCode::singular:
      return "singular";
    case ErrorCode::wrong_branch:
      return "wrong_branch";
    case ErrorCode::limit_exceeded:
      return "limit_exceeded";
    case ErrorCode::unsupported:
      return "unsupported";
    case ErrorCode::io:
      return "io";
  }
  return "error";
}

void raise_error(const Error& error) {
  const py::object make = py::module_::import("pkm._errors").attr("from_error");
  const ErrorLocation& at = error.location;
  const py::object exception =
      make(error_code_name(error.code), error.message, at.file, at.line, at.column, at.key);
  PyErr_SetObject(reinterpret_cast<PyObject*>(Py_TYPE(exception.ptr())), exception.ptr());
  throw py::error_already_set();
}

void bind_errors(py::module_& m) {
  m.def(
      "_raise_test_error",
      [](const std::string& code, const std::string& message) {
        ErrorCode value = ErrorCode::bad_input;
        for (ErrorCode c :
             {ErrorCode::bad_input, ErrorCode::unreachable, ErrorCode::not_converged, ErrorCode::singular,
              ErrorCode::wrong_branch, ErrorCode::limit_exceeded, ErrorCode::unsupported, ErrorCode::io}) {
          if (code == error_code_name(c)) value = c;
        }
        raise_error(make_error(value, message));
      },
      "Raises the exception a library error of `code` becomes (for the tests of the error mapping).");
}

}  // namespace pkm::python
