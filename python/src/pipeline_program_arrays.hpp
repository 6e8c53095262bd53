#pragma once
// A canonical program (program/canonical_program.hpp) as a dict of numpy arrays, one row per move: what
// pkm.interpret returns, and the post-processed program pkm.optimize returns.
#include <pybind11/pybind11.h>

#include "program/canonical_program.hpp"

namespace pkm::python {

pybind11::dict program_arrays(const program::CanonicalProgram& program);

}  // namespace pkm::python
