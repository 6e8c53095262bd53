#pragma once
// The pipeline functions of the module (pipeline.cpp registers them): one file each.
#include <pybind11/pybind11.h>

namespace pkm::python {

void bind_interpret(pybind11::module_& m);
void bind_plan(pybind11::module_& m);
void bind_interpolate(pybind11::module_& m);
void bind_optimize(pybind11::module_& m);

}  // namespace pkm::python
