// Batch kinematics as methods of pkm.Machine (registered by bind_machine): IK, FK, Jacobians, conditioning,
// and the conversion of G-code's A B C to and from the machine's convention.
#include "batch_bindings.hpp"
#include "bindings.hpp"

namespace pkm::python {

void bind_batch(py::module_& m) {
  MachineClass cls = machine_class(m);
  bind_ik(cls, m);
  bind_fk(cls);
  bind_jacobian(cls);
  bind_abc(cls);
}

}  // namespace pkm::python
