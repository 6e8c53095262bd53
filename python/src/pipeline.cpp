// The part-program pipeline from Python: interpret, plan, interpolate, optimize (pipeline_*.cpp).
#include "bindings.hpp"
#include "pipeline_bindings.hpp"

namespace pkm::python {

void bind_pipeline(py::module_& m) {
  bind_interpret(m);
  bind_plan(m);
  bind_interpolate(m);
  bind_optimize(m);
}

}  // namespace pkm::python
