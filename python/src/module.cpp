// The compiled module pkm._pkm; the package pkm (pkm/__init__.py) re-exports it with the pure-Python parts.
#include "bindings.hpp"
#include "io/version.hpp"

PYBIND11_MODULE(_pkm, m) {
  m.doc() = "pkm: kinematics, motion planning and analyses of parallel-kinematic machines (compiled core).";
  // The version of the pkm this module was built from (CMake's project version, as pkm --version prints).
  m.attr("__version__") = std::string(pkm::pkm_version());
  pkm::python::bind_errors(m);
  pkm::python::bind_machine(m);
  pkm::python::bind_batch(m);
  pkm::python::bind_pipeline(m);
  pkm::python::bind_analyses(m);
}
