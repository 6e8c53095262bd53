#pragma once
// How a pkm::Machine lives in Python: as pkm.Machine, held by a std::shared_ptr (non-copyable; binding
// functions take `const pkm::Machine&`). What the machine file says that pkm::Machine does not keep (the tool
// point, and the text itself for pickling) rides in the shared pointer's deleter, where std::get_deleter
// finds it; a machine made by other C++ code has no such facts, and the properties that need them say so.
#include <pybind11/pybind11.h>

#include <Eigen/Core>
#include <memory>
#include <string>

#include "core/result.hpp"
#include "machine/machine.hpp"

namespace pkm::python {

namespace py = pybind11;

struct MachineFileFacts {
  Eigen::Vector3d tool_mm = Eigen::Vector3d::Zero();  ///< the tool point in the platform frame (`tool:`)
  std::string text;                                   ///< the YAML (or JSON) the machine was read from
  void operator()(Machine* machine) const { delete machine; }
};

using MachineHolder = std::shared_ptr<Machine>;
using MachineClass = py::class_<Machine, MachineHolder>;

/// The machine described by `text` (YAML, or JSON, which is YAML), named `source` in errors; raises
/// pkm.MachineFileError (with file, line, column, key) when the text is not a valid machine.
MachineHolder machine_from_text(const std::string& text, const std::string& source);

/// The facts kept with `machine`, or nullptr for a machine not made by machine_from_text.
const MachineFileFacts* machine_file_facts(const MachineHolder& machine);

/// The registered class pkm.Machine of module `m` (bind_machine registers it; bind_batch adds methods).
MachineClass machine_class(py::module_& m);

/// Registers pkm.read_machine_dict (machine_dict.cpp).
void bind_machine_dict(py::module_& m);

/// Raises the exception for an error of reading a machine: pkm.MachineFileError for every bad_input error
/// (also a syntax error, which names no key), else as raise_error does.
[[noreturn]] void raise_machine_error(const Error& error);

}  // namespace pkm::python
