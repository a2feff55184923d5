#include <pybind11/pybind11.h>

namespace py = pybind11;

namespace vofdem::bind {

// the pressure module registers its classes and functions here
void bind_pressure(py::module_& /*m*/) {}

}  // namespace vofdem::bind
