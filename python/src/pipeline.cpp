#include "bindings.hpp"

namespace pkm::python {

void bind_pipeline(py::module_& /*m*/) {}

}  // namespace pkm::python
