// The machine's analyses from Python: natural frequencies, compliance, workspace maps, deflection along a
// program, servo runs, calibration, inverse dynamics (analysis_*.cpp). The drive forces along a program are
// pkm.plan(..., dynamics=True).
#include "analysis_bindings.hpp"
#include "bindings.hpp"

namespace pkm::python {

void bind_analyses(py::module_& m) {
  bind_modes(m);
  bind_compliance(m);
  bind_workspace(m);
  bind_file_runs(m);
  bind_calibration(m);
  bind_dynamics(m);
}

}  // namespace pkm::python
