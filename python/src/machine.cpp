#include "bindings.hpp"

namespace pkm::python {

void bind_machine(py::module_& /*m*/) {}

}  // namespace pkm::python
