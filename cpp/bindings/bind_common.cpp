#include <pybind11/pybind11.h>
#include <pybind11/operators.h>
#include <pybind11/stl.h>

#include "fields.h"
#include "vofdem/common/grid.h"
#include "vofdem/common/medium.h"
#include "vofdem/common/profile.h"
#include "vofdem/common/threads.h"

namespace py = pybind11;

namespace vofdem::bind {

void bind_common(py::module_& m) {
  m.attr("GRADED_MERGE_FRACTION") = kGradedMergeFraction;  // Grid2D.graded's default [-]
  py::class_<Grid2D>(m, "Grid2D", "Staggered 2D vertical grid: uniform in x, free spacing in z (SI units).")
      .def(py::init<int, double, std::vector<double>, double>(), py::arg("nx"), py::arg("dx"), py::arg("z_faces"),
           py::arg("x0") = 0.0)
      .def_static("uniform", &Grid2D::uniform, py::arg("nx"), py::arg("nz"), py::arg("length_x"),
                  py::arg("height_z"), py::arg("x0") = 0.0, py::arg("z0") = 0.0)
      .def_static("graded", &Grid2D::graded, py::arg("nx"), py::arg("length_x"), py::arg("height_z"), py::arg("dz"),
                  py::arg("dz_bed"), py::arg("z_bed_top"), py::arg("merge_fraction") = kGradedMergeFraction)
      .def_property_readonly("nx", &Grid2D::nx,
           "columns [-]")
      .def_property_readonly("nz", &Grid2D::nz,
           "rows [-]")
      .def_property_readonly("ncell", &Grid2D::ncell,
           "cells nx nz [-]")
      .def_property_readonly("dx", &Grid2D::dx,
           "column width [m] (uniform in x)")
      .def_property_readonly("x0", &Grid2D::x0,
           "x of the first column's left face [m]")
      .def_property_readonly("length_x", &Grid2D::length_x,
           "length of the domain along the flume [m]")
      .def_property_readonly("height_z", &Grid2D::height_z,
           "height of the domain [m]")
      .def_property_readonly("z_faces", &Grid2D::z_faces,
           "heights of the nz + 1 row faces [m], increasing from the bed")
      .def("__repr__", [](const Grid2D& g) {
        return "Grid2D(nx=" + std::to_string(g.nx()) + ", nz=" + std::to_string(g.nz()) + ")";
      });

  py::class_<Medium>(m, "Medium",
                     "Water, air and gravity (SI units), one value for the flow and the stones: FlowParams.medium "
                     "owns it, a Coupler hands it to the stones (DEMParams.medium).")
      .def(py::init<>())
      .def_readwrite("rho_water", &Medium::rho_water, with_default("water density [kg/m^3]", &Medium::rho_water).c_str())
      .def_readwrite("rho_air", &Medium::rho_air, with_default("air density [kg/m^3]", &Medium::rho_air).c_str())
      .def_readwrite("nu_water", &Medium::nu_water, with_default("water kinematic viscosity [m^2/s]", &Medium::nu_water).c_str())
      .def_readwrite("nu_air", &Medium::nu_air, with_default("air kinematic viscosity [m^2/s]", &Medium::nu_air).c_str())
      .def_readwrite("gravity", &Medium::gravity, "gravitational acceleration (x along the flume, z up) [m/s^2]")
      .def("validate", &Medium::validate,
           "ValueError naming the field unless the densities are positive, the viscosities non-negative and the gravity finite")
      .def(py::self == py::self)
      .def(py::self != py::self)
      .def("__repr__", [](const Medium& d) {
        return "Medium(rho_water=" + std::to_string(d.rho_water) + ", gravity=(" + std::to_string(d.gravity[0]) +
               ", " + std::to_string(d.gravity[1]) + "))";
      });

  m.def("set_threads", &set_threads, py::arg("n"),
        "Threads of the next steps of every solver in this process [-], in [1, max_threads()]; the results are the "
        "same bits for any count (docs/threads.md). ValueError outside the range.");
  m.def("threads", &threads,
        "Threads of the solvers' parallel stages [-] (default: OMP_NUM_THREADS, else every core).");
  m.def("max_threads", &max_threads, "The most threads set_threads accepts (1 when built without OpenMP).");
  m.def("set_thread_min_cells", &set_thread_min_cells, py::arg("n"),
        "The fewest cells a thread is given [-], in [1, 1e9], default 2048: smaller loops run on fewer threads; 1 "
        "splits every loop (the determinism tests). ValueError outside the range.");
  m.def("thread_min_cells", &thread_min_cells, "The fewest cells a thread is given [-].");
  m.def("built_with_openmp", &built_with_openmp, "True if the solvers can run on several threads.");

  py::class_<StageProfile>(m, "StageProfile", "Accumulated wall time [s] and calls of each named solver stage.")
      .def_property_readonly("names", &StageProfile::names,
           "the stages' names, in the order they first ran")
      .def_property_readonly("seconds", &StageProfile::seconds,
           "accumulated wall time of each stage [s]")
      .def_property_readonly("calls", &StageProfile::calls,
           "how often each stage ran [-]")
      .def_property_readonly("total_seconds", &StageProfile::total_seconds,
           "the stages' summed wall time [s]")
      .def("reset", &StageProfile::reset,
           "zeroes every stage's time and calls");
}

}  // namespace vofdem::bind
