#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <cstdint>

#include "fields.h"
#include "views.h"
#include "vofdem/coupling/porosity_map.h"

namespace py = pybind11;

namespace vofdem::bind {

namespace {
using InArray = py::array_t<double, py::array::c_style | py::array::forcecast>;
using MaskArray = py::array_t<std::uint8_t, py::array::c_style | py::array::forcecast>;

void map_discs(PorosityMapper& self, const InArray& x, const InArray& z, const InArray& r, const py::object& active) {
  const py::ssize_t n = x.size();
  if (z.size() != n || r.size() != n)
    throw py::value_error("disc_x, disc_z and disc_r must have the same length");
  MaskArray mask;
  if (!active.is_none()) {
    mask = MaskArray::ensure(active);
    if (!mask || mask.size() != n) throw py::value_error("active must be a mask of the same length as disc_x");
  }
  const std::uint8_t* m = active.is_none() ? nullptr : mask.data();
  py::gil_scoped_release release;
  self.map(static_cast<int>(n), x.data(), z.data(), r.data(), m);
}
}  // namespace

void bind_porosity(py::module_& m) {
  m.def("stone_cell_area", py::vectorize(&disc_rect_area), py::arg("cx"), py::arg("cz"), py::arg("r"), py::arg("x0"),
        py::arg("x1"), py::arg("z0"), py::arg("z1"),
        "Exact area [m^2] of the disc of centre (cx, cz) [m] and radius r [m] inside [x0, x1] x [z0, z1] [m].");
  m.def("porosity_eq11", py::vectorize(&porosity_eq11), py::arg("a_s"), py::arg("a_c"), py::arg("n_exp") = 0.41,
        "Porosity of seed eq. (11) from stone area a_s [m^2] (capped at a_c) and cell area a_c [m^2].");

  py::enum_<PorosityMethod>(m, "PorosityMethod", "How the stones' solid area [m^2] in each cell is found (porosity_map.h, eq. 11).")
      .value("EXACT", PorosityMethod::kExact, "closed-form disc-rectangle areas")
      .value("LOOKUP", PorosityMethod::kLookup, "the paper's precomputed sub-area tables");

  py::class_<PorosityParams>(m, "PorosityParams", "Parameters of the porosity mapping (SI units).")
      .def(py::init<>())
      .def_readwrite("method", &PorosityParams::method,
                     with_default("PorosityMethod of the solid areas", &PorosityParams::method).c_str())
      .def_readwrite("m", &PorosityParams::m, with_default("sub-areas per side of the centre cell (lookup) [-]", &PorosityParams::m).c_str())
      .def_readwrite("n_exp", &PorosityParams::n_exp, with_default("packing porosity of the stones [-]", &PorosityParams::n_exp).c_str())
      .def_readwrite("r_min", &PorosityParams::r_min, "smallest disc radius [m]")
      .def_readwrite("r_max", &PorosityParams::r_max, "largest disc radius [m]")
      .def_readwrite("dr", &PorosityParams::dr, with_default("radius node spacing of the lookup tables [m]", &PorosityParams::dr).c_str())
      .def_readwrite("max_discs", &PorosityParams::max_discs, "largest number of discs of one call [-]");

  py::class_<PorosityMapper>(m, "PorosityMapper",
                             "Cell porosity (seed eq. 11) from stone discs, exact or by the paper's lookup table.")
      .def(py::init<const Grid2D&, const PorosityParams&>(), py::arg("grid"), py::arg("params"))
      .def("map", &map_discs, py::arg("disc_x"), py::arg("disc_z"), py::arg("disc_r"), py::arg("active") = py::none(),
           "Maps disc centres [m] and radii [m] onto cell_solid_area and cell_porosity (no allocation).")
      .def_property_readonly("grid", &PorosityMapper::grid,
           "the flow grid the mapper maps onto (Grid2D)")
      .def_property_readonly(
          "params", [](const PorosityMapper& p) { return p.params(); }, "a copy: fixed at construction")
      .def_property_readonly("ndisc", &PorosityMapper::ndisc,
           "number of discs of the last map() call [-]")
      .def_property_readonly("table_count", &PorosityMapper::table_count,
           "distinct lookup tables (row classes x radius nodes) [-]; 0 with the exact method")
      .def_property_readonly("table_bytes", &PorosityMapper::table_bytes,
           "memory of the lookup tables [bytes]")
      .def_property_readonly("row_class", &PorosityMapper::row_class,
           "row class of each grid row for the lookup tables (rows with equal z-faces within reach share one)")
      .def_property_readonly(
          "cell_solid_area",
          [](py::object self) {
            auto& p = self.cast<PorosityMapper&>();
            return view2d(p.cell_solid_area().data(), p.grid().nz(), p.grid().nx(), self);
          },
          "stone area A_s of each cell [m^2], capped at the cell area; (nz, nx) view")
      .def_property_readonly(
          "cell_porosity",
          [](py::object self) {
            auto& p = self.cast<PorosityMapper&>();
            return view2d(p.cell_porosity().data(), p.grid().nz(), p.grid().nx(), self);
          },
          "porosity n of each cell [-]; (nz, nx) view")
      .def_property_readonly(
          "stone_cell_offsets",
          [](py::object self) {
            auto& p = self.cast<PorosityMapper&>();
            return view(p.stone_cell_offsets().data(), p.ndisc() + 1, self);
          },
          "CSR offsets (ndisc + 1) of the cells each disc covers")
      .def_property_readonly(
          "stone_cell_index",
          [](py::object self) {
            auto& p = self.cast<PorosityMapper&>();
            return view(p.stone_cell_index().data(), p.stone_cell_offsets()[p.ndisc()], self);
          },
          "flat cell index i + nx k of each (disc, cell) pair")
      .def_property_readonly(
          "stone_cell_area",
          [](py::object self) {
            auto& p = self.cast<PorosityMapper&>();
            return view(p.stone_cell_area().data(), p.stone_cell_offsets()[p.ndisc()], self);
          },
          "area [m^2] of each (disc, cell) pair, uncapped")
      .def_property_readonly("profile", [](PorosityMapper& p) -> StageProfile& { return p.profile(); },
                             py::return_value_policy::reference_internal,
           "wall-clock seconds per mapping stage (StageProfile)");
}

}  // namespace vofdem::bind
