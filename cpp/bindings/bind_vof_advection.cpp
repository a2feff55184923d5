#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <stdexcept>
#include <string>

#include "views.h"
#include "vofdem/flow/vof_advection.h"

namespace py = pybind11;

namespace vofdem::bind {

namespace {

using InArray = py::array_t<double, py::array::c_style | py::array::forcecast>;
using InOutArray = py::array_t<double, py::array::c_style>;

void require_size(const char* name, py::ssize_t size, int allowed) {
  if (size != allowed)
    throw std::invalid_argument(std::string(name) + " has size " + std::to_string(size) +
                                "; allowed: " + std::to_string(allowed));
}

// a boundary array: numpy view of the vector, writable in place
void def_side(py::class_<VofBoundaryInflow>& cls, const char* name, std::vector<double> VofBoundaryInflow::*side,
              const char* doc) {
  cls.def_property(
      name, [side](py::object self) { return view(self.cast<VofBoundaryInflow&>().*side, self); },
      [side](VofBoundaryInflow& b, std::vector<double> v) { b.*side = std::move(v); }, doc);
}

}  // namespace

void bind_vof_advection(py::module_& m) {
  py::class_<VofBoundaryInflow> inflow(
      m, "VofBoundaryInflow",
      "Water fraction [-] entering through each boundary face where the flow enters (left/right: nz, "
      "bottom/top: nx); empty = 0. The arrays are numpy views, writable in place; assigning a whole side "
      "replaces its array (earlier views of it are invalidated).");
  inflow.def(py::init<>())
      .def(py::init([](const Grid2D& g, double value) {
             VofBoundaryInflow b;
             b.resize(g, value);
             return b;
           }),
           py::arg("grid"), py::arg("value") = 0.0)
      .def("resize", &VofBoundaryInflow::resize, py::arg("grid"), py::arg("value") = 0.0,
           "Sizes the four sides for `grid` filled with `value`; invalidates earlier views.");
  def_side(inflow, "left", &VofBoundaryInflow::left, "fraction entering at x = x0, per row (nz)");
  def_side(inflow, "right", &VofBoundaryInflow::right, "fraction entering at the right end, per row (nz)");
  def_side(inflow, "bottom", &VofBoundaryInflow::bottom, "fraction entering through the bottom, per column (nx)");
  def_side(inflow, "top", &VofBoundaryInflow::top, "fraction entering through the top, per column (nx)");

  py::enum_<VofNormal>(m, "VofNormal", "Interface normal of the PLIC reconstruction.")
      .value("YOUNGS", VofNormal::kYoungs, "Youngs (1982): weighted 3x3 gradient of F (default)")
      .value("MIXED_YOUNGS_CENTERED", VofNormal::kMixedYoungsCentered,
             "Aulisa et al. (2007): height-function normal of the 3x3 block, else Youngs");

  py::class_<VofScratch>(m, "VofScratch", "Work arrays of advect_vof, its water fluxes and clipping report.")
      .def(py::init<>())
      .def_property_readonly(
          "face_flux_x", [](py::object self) { return const_view(self.cast<VofScratch&>().face_flux_x, self); },
          "water volume [m^2 per m of width] through each x-face in the last step, along +x (read-only view; "
          "empty before the first step)")
      .def_property_readonly(
          "face_flux_z", [](py::object self) { return const_view(self.cast<VofScratch&>().face_flux_z, self); },
          "water volume [m^2 per m of width] through each z-face in the last step, along +z (read-only view)")
      .def_readwrite("clip_count", &VofScratch::clip_count,
                     "cell updates clipped by more than VOF_CLIP_TOLERANCE (0 when the CFL limit holds)")
      .def_readwrite("clip_max", &VofScratch::clip_max, "largest such excursion of F outside [0, 1]");
  m.attr("VOF_CLIP_TOLERANCE") = kVofClipTolerance;

  m.def(
      "advect_vof",
      [](const Grid2D& g, const InArray& cell_porosity, const InArray& face_u, const InArray& face_w,
         const VofBoundaryInflow& inflow, double dt, bool x_first, InOutArray cell_F, VofScratch& scratch,
         VofNormal normal) {
        require_size("cell_porosity", cell_porosity.size(), g.ncell());
        require_size("face_u", face_u.size(), g.nface_x());
        require_size("face_w", face_w.size(), g.nface_z());
        require_size("cell_F", cell_F.size(), g.ncell());
        if (!cell_F.writeable()) throw std::invalid_argument("cell_F is read-only; allowed: a writeable array");
        double* f = cell_F.mutable_data();
        py::gil_scoped_release release;
        advect_vof(g, cell_porosity.data(), face_u.data(), face_w.data(), inflow, dt, x_first, f, scratch, normal);
      },
      py::arg("grid"), py::arg("cell_porosity"), py::arg("face_u"), py::arg("face_w"), py::arg("inflow"),
      py::arg("dt"), py::arg("x_first"), py::arg("cell_F").noconvert(), py::arg("scratch"),
      py::arg("normal") = VofNormal::kYoungs,
      "Advances the water fraction cell_F (float64, C-contiguous, size ncell; updated in place) by dt [s] "
      "with the superficial face velocities face_u, face_w [m/s] (seed eq. 4, PLIC, split with the "
      "Weymouth-Yue correction). Raises RuntimeError above CFL 1 (F untouched).");

  m.def(
      "vof_stable_dt",
      [](const Grid2D& g, const InArray& cell_porosity, const InArray& face_u, const InArray& face_w, double cfl) {
        require_size("cell_porosity", cell_porosity.size(), g.ncell());
        require_size("face_u", face_u.size(), g.nface_x());
        require_size("face_w", face_w.size(), g.nface_z());
        return vof_stable_dt(g, cell_porosity.data(), face_u.data(), face_w.data(), cfl);
      },
      py::arg("grid"), py::arg("cell_porosity"), py::arg("face_u"), py::arg("face_w"), py::arg("cfl") = 0.45,
      "Largest advection step [s] at CFL number cfl: per cell and direction the inflow CFL numbers "
      "abs(v) dt / (n h) add up to <= cfl, the outflow ones to <= 2 cfl (cfl <= 0.5 keeps F in [0, 1]); inf if at rest.");

  m.def("plic_line_constant", py::vectorize(&plic_line_constant), py::arg("mx"), py::arg("mz"), py::arg("dx"),
        py::arg("dz"), py::arg("f"),
        "Line constant alpha with area{m.x <= alpha} in [0,dx]x[0,dz] = f dx dz (normal m out of the water).");
  m.def("plic_area_below", py::vectorize(&plic_area_below), py::arg("mx"), py::arg("mz"), py::arg("dx"),
        py::arg("dz"), py::arg("alpha"), "Area [m^2] of {m.x <= alpha} inside the rectangle [0,dx]x[0,dz].");
}

}  // namespace vofdem::bind
