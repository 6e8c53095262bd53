#include "bindings.hpp"

namespace pkm::python {

void bind_analyses(py::module_& /*m*/) {}

}  // namespace pkm::python
