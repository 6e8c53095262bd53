#pragma once
// The analysis functions of the module (analyses.cpp registers them): one file each.
#include <pybind11/pybind11.h>

namespace pkm::python {

void bind_modes(pybind11::module_& m);
void bind_compliance(pybind11::module_& m);
void bind_workspace(pybind11::module_& m);
void bind_file_runs(pybind11::module_& m);    ///< pkm.stiffness, pkm.servo
void bind_calibration(pybind11::module_& m);  ///< pkm.calibrate_plan, _simulate, _identify
void bind_dynamics(pybind11::module_& m);     ///< pkm.inverse_dynamics

}  // namespace pkm::python
