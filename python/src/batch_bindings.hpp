#pragma once
// The batch kinematics bindings, one file each (bind_batch in batch.cpp calls them): methods of pkm.Machine
// on (N, 6) pose and (N, n) actuator arrays.
#include "machine_handle.hpp"

namespace pkm::python {

void bind_ik(MachineClass& cls, py::module_& m);  // batch_ik.cpp: ik, set_threads, get_threads
void bind_fk(MachineClass& cls);                  // batch_fk.cpp: fk, fk_all
void bind_jacobian(MachineClass& cls);            // batch_jacobian.cpp: jacobian, conditioning
void bind_abc(MachineClass& cls);                 // batch_abc.cpp: pose_from_abc, abc_from_pose

}  // namespace pkm::python
