#include "bindings.hpp"

namespace pkm::python {

void bind_batch(py::module_& /*m*/) {}

}  // namespace pkm::python
