#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>

#include "vofdem/coupling/drag.h"
#include "vofdem/flow/porous_resistance.h"

namespace py = pybind11;

namespace vofdem::bind {

void bind_closure(py::module_& m) {
  py::enum_<DragLaw>(m, "DragLaw", "Drag coefficient C_D [-] of a stone against its Reynolds number (drag.h).")
      .value("PAPER", DragLaw::kPaper, "C_D = 0.4 + 24/Re (seed eq. 18)")
      .value("SCHILLER_NAUMANN", DragLaw::kSchillerNaumann, "C_D = 24/Re (1 + 0.15 Re^0.687), 0.44 above Re=1000");

  m.attr("PAPER_K1") = kPaperK1;
  m.attr("PAPER_K2") = kPaperK2;
  m.attr("ERGUN_K1") = kErgunK1;
  m.attr("ERGUN_K2") = kErgunK2;

  m.def("permeability", py::vectorize(&permeability), py::arg("n"), py::arg("d"), py::arg("k1") = kPaperK1,
        "Intrinsic permeability K = n^3 d^2 / (k1 (1-n)^2) [m^2] (seed eq. 7); n porosity, d stone diameter [m].");
  m.def("forchheimer_coefficient", py::vectorize(&forchheimer_coefficient), py::arg("n"), py::arg("k1") = kPaperK1,
        py::arg("k2") = kPaperK2, "Forchheimer coefficient C = k2 / sqrt(k1 n^3) [-] (seed eq. 7).");

  auto rx = [](double u, double w, double n, double d, double nu, double k1, double k2) {
    return porous_resistance(u, w, n, d, nu, k1, k2).rx;
  };
  auto rz = [](double u, double w, double n, double d, double nu, double k1, double k2) {
    return porous_resistance(u, w, n, d, nu, k1, k2).rz;
  };
  m.def("_porous_resistance_x", py::vectorize(rx));
  m.def("_porous_resistance_z", py::vectorize(rz));

  m.def("drag_coefficient", py::vectorize([](double re, DragLaw law) { return drag_coefficient(re, law); }),
        py::arg("re"), py::arg("law") = DragLaw::kPaper, "Drag coefficient C_D [-] at Reynolds number re > 0.");
  auto fx = [](double u, double w, double up, double wp, double d, double rho, double nu, DragLaw law) {
    return drag_force(u, w, up, wp, d, rho, nu, law).fx;
  };
  auto fz = [](double u, double w, double up, double wp, double d, double rho, double nu, DragLaw law) {
    return drag_force(u, w, up, wp, d, rho, nu, law).fz;
  };
  m.def("_drag_force_x", py::vectorize(fx));
  m.def("_drag_force_z", py::vectorize(fz));
}

}  // namespace vofdem::bind
