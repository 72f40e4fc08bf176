// Placeholder registered by the lead; the owner replaces it.
#include "common.hpp"

namespace packlab::python {

void bind_shear(py::module_& /*m*/) {}

}  // namespace packlab::python
