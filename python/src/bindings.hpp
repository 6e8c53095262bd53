#pragma once
// What the binding files share: the registration function of each, and the one way a library error becomes a
// typed Python exception (pkm/_errors.py holds the exception classes; raise_error builds one from an Error).
#include <pybind11/pybind11.h>

#include <optional>
#include <utility>

#include "core/result.hpp"

namespace pkm::python {

namespace py = pybind11;

void bind_errors(py::module_& m);
void bind_machine(py::module_& m);
void bind_batch(py::module_& m);
void bind_pipeline(py::module_& m);
void bind_analyses(py::module_& m);

/// The code's name as pkm/_errors.py spells it ("bad_input", "not_converged", "wrong_branch", "io", ...): the
/// enumerator's name, unlike to_string(), which is the message's words ("bad input").
const char* error_code_name(ErrorCode code);

/// Raises the pkm exception for `error` (its class from the error code and location: pkm.MachineFileError for
/// a located error in a machine file, pkm.UnreachableError, ...), with `file`, `line`, `column` and `key`
/// set.
[[noreturn]] void raise_error(const Error& error);

template <class T>
T unwrap(Result<T>&& result) {
  if (!result) raise_error(result.error());
  return std::move(result).value();
}

/// Runs the library call `work` (returning a Result) with the GIL released, so that other Python threads run
/// meanwhile; returns its value or raises its error once the GIL is held again.
template <class Work>
auto unwrap_released(Work&& work) {
  std::optional<decltype(work())> result;
  {
    py::gil_scoped_release released;
    result.emplace(work());
  }
  return unwrap(std::move(*result));
}

}  // namespace pkm::python
