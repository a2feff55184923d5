#include <pybind11/pybind11.h>

namespace py = pybind11;

namespace vofdem::bind {

// the vof module registers its classes and functions here
void bind_vof(py::module_& /*m*/) {}

}  // namespace vofdem::bind
