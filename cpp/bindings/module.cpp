// The _core extension: thin pybind11 wrappers only, no physics. One bind_*.cpp per module.
#include <pybind11/pybind11.h>

namespace py = pybind11;

namespace vofdem::bind {
void bind_common(py::module_& m);
void bind_closure(py::module_& m);
void bind_porosity(py::module_& m);
void bind_dem(py::module_& m);
void bind_vof(py::module_& m);
void bind_vof_advection(py::module_& m);
void bind_pressure(py::module_& m);
void bind_coupler(py::module_& m);
}  // namespace vofdem::bind

PYBIND11_MODULE(_core, m) {
  m.doc() = "vofdem C++ core: VOF flow, DEM stones and their coupling";
  m.attr("__version__") = VOFDEM_VERSION;
  vofdem::bind::bind_common(m);
  vofdem::bind::bind_closure(m);
  vofdem::bind::bind_porosity(m);
  vofdem::bind::bind_dem(m);
  vofdem::bind::bind_vof_advection(m);
  vofdem::bind::bind_pressure(m);
  vofdem::bind::bind_vof(m);
  vofdem::bind::bind_coupler(m);
}
