// Python binding of the VOF-DEM coupler: thin wrappers only (see coupler.h).
#include <pybind11/native_enum.h>
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <cstring>
#include <string>

#include "fields.h"
#include "flags.h"
#include "state.h"
#include "views.h"
#include "vofdem/coupling/coupler.h"

namespace py = pybind11;

namespace vofdem::bind {

void bind_coupler(py::module_& m) {
  py::native_enum<CouplerEffect>(m, "CouplerEffect", "enum.IntFlag",
                                 "Bit flags of the coupling's effects (CouplerParams.flags).")
      .value("DEM", kCoupleDEM, "step the stones")
      .value("FLUID", kCoupleFluid, "step the flow (off: a frozen flow still acts on the stones)")
      .value("POROSITY", kCouplePorosity, "two-way: the flow's porosity follows the stones")
      .value("DRAG", kCoupleDrag, "drag on the stones, eqs. (16)-(18)")
      .value("PRESSURE_GRADIENT", kCouplePressureGradient, "F_S = -V (grad p - rho_w F g) on the stones")
      .value("WET_FRACTION", kCoupleWetFraction, "stone_wet from the water fraction")
      .value("CHECKS", kCoupleChecks, "non-finite forces and stone states checked every step")
      .value("LOOKUP_POROSITY", kCoupleLookupPorosity, "the paper's lookup table instead of exact areas")
      .value("DISPLACE_FLOW", kCoupleDisplaceFlow, "porosity changes drive the flow (dn/dt + div u = 0)")
      .value("OVERFLOW_LOAD", kCoupleOverflowLoad,
             "drag and lift of the overflow on the stones' exposed parts, the reaction taken from the flow")
      .value("FORCES", kCoupleForces, "DRAG and PRESSURE_GRADIENT")
      .value("ONE_WAY", kCoupleOneWay, "the stones feel the flow, the flow ignores them")
      .value("TWO_WAY", kCoupleTwoWay, "ONE_WAY and POROSITY")
      .value("DEFAULT", kCoupleDefault, "TWO_WAY")
      .finalize();
  export_flag_members(m, "CouplerEffect", "COUPLE_");  // the older module constants

  py::enum_<StoneDragModel>(m, "StoneDragModel", "Drag on the stones (one of the two, never both).")
      .value("SPHERE", StoneDragModel::kSphere, "single sphere in the pore velocity, eqs. (16)-(18) (the paper's)")
      .value("BED", StoneDragModel::kBed, "reaction of the flow's porous resistance, rho n R per bulk volume");

  py::enum_<CouplingMapping>(m, "CouplingMapping", "How the stones and the flow exchange cell fields.")
      .value("CELL", CouplingMapping::kCell, "each stone's exact footprint over the raw cells (the paper's)")
      .value("KERNEL", CouplingMapping::kKernel,
             "footprints and flow smoothed by a Gaussian exp(-r^2/b^2) of physical width b (kernel_smoothing.h)");

  py::class_<SettleReport>(m, "SettleReport", "What Coupler.settle() did.")
      .def_readonly("time", &SettleReport::time, "simulated time the stones stepped [s]")
      .def_readonly("max_speed", &SettleReport::max_speed, "the largest free stone's speed at its end [m/s]")
      .def_readonly("rested", &SettleReport::rested, "ended by the rest criterion (False: at max_time)")
      .def("__repr__", [](const SettleReport& r) {
        return "SettleReport(time=" + std::to_string(r.time) + ", max_speed=" + std::to_string(r.max_speed) +
               ", rested=" + (r.rested ? std::string("True") : std::string("False")) + ")";
      });

  py::class_<CouplerParams>(m, "CouplerParams", "Parameters of the VOF-DEM coupling (SI units; see coupler.h).")
      .def(py::init<>())
      .def_readwrite("flags", &CouplerParams::flags, "CouplerEffect bits")
      .def_readwrite("n_exp", &CouplerParams::n_exp, with_default("packing porosity of eq. (11) [-]", &CouplerParams::n_exp).c_str())
      .def_readwrite("lookup_m", &CouplerParams::lookup_m, with_default("sub-areas per side of the lookup table [-]", &CouplerParams::lookup_m).c_str())
      .def_readwrite("lookup_dr", &CouplerParams::lookup_dr, with_default("radius spacing of the lookup tables [m]", &CouplerParams::lookup_dr).c_str())
      .def_readwrite("drag_law", &CouplerParams::drag_law, "DragLaw of the sphere drag")
      .def_readwrite("stone_drag", &CouplerParams::stone_drag, with_default("StoneDragModel of the drag on the stones", &CouplerParams::stone_drag).c_str())
      .def_readwrite("max_dt", &CouplerParams::max_dt, with_default("largest exchange step [s]", &CouplerParams::max_dt).c_str())
      .def_readwrite("stone_cfl", &CouplerParams::stone_cfl, with_default("cells a stone crosses per step at most [-]", &CouplerParams::stone_cfl).c_str())
      .def_readwrite("implicit_drag", &CouplerParams::implicit_drag,
                     with_default("drag linearised in the stone's velocity and integrated implicitly by the DEM (True) or held "
                                  "over the step, bounded by drag_relaxation (False)",
                                  &CouplerParams::implicit_drag)
                         .c_str())
      .def_readwrite("drag_relaxation", &CouplerParams::drag_relaxation,
                     with_default("held drag: step at most this fraction of its relaxation time [-]",
                                  &CouplerParams::drag_relaxation)
                         .c_str())
      .def_readwrite("min_dt", &CouplerParams::min_dt, with_default("a stable step below this is a failure [s]", &CouplerParams::min_dt).c_str())
      .def_readwrite("wet_fraction_tolerance", &CouplerParams::wet_fraction_tolerance,
                     with_default("a stone measured this close to wet (dry) is taken as under water (in the air) [-], "
                                  "[0, 0.5]; 0: every measured wet fraction is followed",
                                  &CouplerParams::wet_fraction_tolerance)
                         .c_str())
      .def_readwrite("max_snapshot_interval", &CouplerParams::max_snapshot_interval,
                     with_default("within advance(), the guard's snapshot at most this many steps apart [steps], [1, 4096]; "
                                  "a failing step replays the steps since it (the same bits); 1: every step",
                                  &CouplerParams::max_snapshot_interval)
                         .c_str())
      .def_readwrite("mapping", &CouplerParams::mapping, with_default("CouplingMapping of the exchanged fields", &CouplerParams::mapping).c_str())
      .def_readwrite("bandwidth", &CouplerParams::bandwidth,
                     "KERNEL: the Gaussian's width b in exp(-r^2/b^2) [m], (0, 1], sigma = b / sqrt(2); 0 = unset: "
                     "1.0 x the stones' mean nominal diameter")
      .def_property(
          "overflow_drag_coefficient", [](const CouplerParams& p) { return p.overflow.drag_coefficient; },
          [](CouplerParams& p, double v) { p.overflow.drag_coefficient = v; },
          with_default("OVERFLOW_LOAD: drag coefficient C_D of a stone's exposed part [-], (0, 5] (Schmeeckle et al. 2007)",
                       &CouplerParams::overflow, &OverflowLoadParams::drag_coefficient)
              .c_str())
      .def_property(
          "overflow_lift_coefficient", [](const CouplerParams& p) { return p.overflow.lift_coefficient; },
          [](CouplerParams& p, double v) { p.overflow.lift_coefficient = v; },
          with_default("OVERFLOW_LOAD: lift coefficient C_L [-], [0, 5] (Einstein and El-Samni 1949)", &CouplerParams::overflow,
                       &OverflowLoadParams::lift_coefficient)
              .c_str())
      .def_property(
          "overflow_band_height", [](const CouplerParams& p) { return p.overflow.band_height; },
          [](CouplerParams& p, double v) { p.overflow.band_height = v; },
          with_default("OVERFLOW_LOAD: height of the approach band above a stone's top, in stone diameters [-], (0, 5]",
                       &CouplerParams::overflow, &OverflowLoadParams::band_height)
              .c_str())
      .def("validate", &CouplerParams::validate, "ValueError naming the first parameter outside its range.");

  bind_state_class<CouplerState>(m, "CouplerState",
                                  "A copy of a coupled simulation's whole state (Coupler.copy_state): the flow's, "
                                  "the stones' and the coupler's own; set_state() returns to it.",
                                  "steps", &CouplerState::steps);

  py::class_<Coupler> cls(m, "Coupler",
                          "Two-way VOF-DEM coupling of a VOFGrid and a DEMSystem (either may be None); keeps both alive.");
  cls.def(py::init([](const py::object& fluid, const py::object& stones, const CouplerParams& p) {
             return new Coupler(fluid.is_none() ? nullptr : fluid.cast<VOFGrid*>(),
                                stones.is_none() ? nullptr : stones.cast<DEMSystem*>(), p);
           }),
           py::arg("fluid"), py::arg("stones"),
           py::arg("params") = CouplerParams(), py::keep_alive<1, 2>(), py::keep_alive<1, 3>())
      .def_property_readonly("fluid", py::overload_cast<>(&Coupler::fluid), py::return_value_policy::reference_internal,
           "the flow (VOFGrid) this coupler steps")
      .def_property_readonly("stones", py::overload_cast<>(&Coupler::stones), py::return_value_policy::reference_internal,
           "the stones (DEMSystem) this coupler steps")
      .def_property(
          "params", [](const Coupler& c) { return c.params(); }, &Coupler::set_params,
          "a copy (editing it changes nothing); assign a modified copy to change them, checked, with the porosity "
          "mapper following them")
      .def_property_readonly("n", &Coupler::n,
           "number of stones")
      .def_property_readonly("time", &Coupler::time,
           "simulated time [s]")
      .def_property_readonly("step_count", &Coupler::step_count,
           "coupled steps taken")
      .def("stable_dt", &Coupler::stable_dt, py::call_guard<py::gil_scoped_release>(),
           "the coupled step [s]: the flow's stable step and the stones' exchange bounds; the GIL is released")
      .def("step_limits", &Coupler::step_limits,
           "steps of advance() bound by each limit, {term: steps} (a diagnostic, not checkpointed)")
      .def(
          "step_limit_cells",
          [](const Coupler& c) {
            py::dict d;
            for (const auto& kv : c.step_limit_cells())
              d[py::str(kv.first)] = py::array_t<long long>(kv.second.size(), kv.second.data());
            return d;
          },
          "{term: steps bound in each cell (ncell counts, a copy)}")
      .def("clear_step_limits", &Coupler::clear_step_limits,
           "forgets the counts of which limit bound each step (step_limits)")
      .def_property_readonly("replayed_steps", &Coupler::replayed_steps,
                             "steps taken again from the guard's snapshot after a failure (a diagnostic)")
      .def("step", py::overload_cast<>(&Coupler::step), py::call_guard<py::gil_scoped_release>())
      .def("step", py::overload_cast<double>(&Coupler::step), py::arg("dt"), py::call_guard<py::gil_scoped_release>())
      .def("advance", [](Coupler& c, double t_end) { return c.advance(t_end); }, py::arg("t_end"),
           py::call_guard<py::gil_scoped_release>(),
           "coupled steps of stable_dt() until time reaches t_end [s]; returns the steps; the GIL is released")
      .def("set_inflow_table", &Coupler::set_inflow_table, py::arg("times"), py::arg("discharge"),
           "inflow hydrograph Q(t): times [s] (increasing), discharge Q [m^3/s] (forwarded to the flow)")
      .def(
          "settle",
          [](Coupler& c, double max_time, double rest_speed, double hold, double chunk) {
            SettleParams p;
            p.max_time = max_time, p.rest_speed = rest_speed, p.hold = hold, p.chunk = chunk;
            return c.settle(p);
          },
          py::arg("max_time") = SettleParams().max_time, py::arg("rest_speed") = SettleParams().rest_speed,
          py::arg("hold") = SettleParams().hold, py::arg("chunk") = SettleParams().chunk,
          py::call_guard<py::gil_scoped_release>(),
          "the stones settle in the still water before the first step: the DEM alone steps, each stone buoyant by "
          "the water it sits in, the flow frozen, until every free stone has been slower than rest_speed [m/s], "
          "(0, 1], for hold [s], [0, 10] (checked every chunk [s], (0, 1]) or for max_time [s], (0, 600]. Returns a "
          "SettleReport; call update_porosity() after it to map the settled stones")
      .def("update_porosity", &Coupler::update_porosity, py::arg("keep_water_volume") = true,
           "maps the stones onto the porosity now; keep_water_volume: True keeps n F V per cell (displaced water moves to neighbours), False keeps F (scene set-up)")
      .def("update_fluid_forces", &Coupler::update_fluid_forces,
           "recomputes the fluid forces on the stones now (stone_force_drag, stone_force_pressure, the stones' wet fractions and external forces)")
      .def("water_volume", &Coupler::water_volume,
           "the flow's water volume sum(n F V) per unit width [m^2]")
      .def_property_readonly("redistributed_volume", &Coupler::redistributed_volume,
           "water moved between cells by the redistribution, accumulated [m^2 per unit width]")
      .def_property_readonly("kernel_bandwidth", &Coupler::kernel_bandwidth,
                             "the kernel's width b [m] in use (0 with the CELL mapping)")
      .def_property_readonly("floored_solid_area", &Coupler::floored_solid_area,
                             "KERNEL: solid area per unit width [m^2] the porosity floor n >= n_exp removed at the "
                             "last mapping (0: the flow sees all of the stones' solid volume)");
  def_checkpoint_state(cls, "restores export_state() exactly (every part checked first; written into the arrays in place)");
  def_copy_state<CouplerState>(cls,
                               "a copy of the whole coupled state (CouplerState), to branch from: set_state(copy) "
                               "continues from it bit for bit",
                               "returns to a copy_state() copy (every part checked first; written into the arrays in place)");
  cls.def_property_readonly("profile", &Coupler::profile, py::return_value_policy::reference_internal,
           "wall-clock seconds per coupled stage (StageProfile)")
      .def_property_readonly("cpu_profile", &Coupler::cpu_profile, py::return_value_policy::reference_internal,
           "the process's CPU seconds (all threads) per coupled stage, the stages and calls of `profile` "
           "(StageProfile): unchanged by other work on a shared machine; reset apart")
      .def_property_readonly("stone_force_drag",
                             [](py::object self) { return view_pairs(self.cast<Coupler&>().stone_force_drag, self); },
           "drag on each stone (sphere or bed drag) (n, 2) [N], zero-copy view")
      .def_property_readonly("stone_force_pressure",
                             [](py::object self) { return view_pairs(self.cast<Coupler&>().stone_force_pressure, self); },
           "pressure-gradient force on each stone (n, 2) [N], zero-copy view")
      .def_property_readonly("stone_force_overflow",
                             [](py::object self) { return view_pairs(self.cast<Coupler&>().stone_force_overflow, self); },
           "OVERFLOW_LOAD: the overflow's drag and lift on each stone (n, 2) [N] (zeros while off), zero-copy view")
      .def_property_readonly("stone_exposed_share",
                             [](py::object self) { return view(self.cast<Coupler&>().stone_exposed_share, self); },
           "OVERFLOW_LOAD: each stone's projected area share loaded by the overflow (n) [-], zero-copy view")
      .def_property_readonly("cell_overflow_reaction",
                             [](py::object self) { return view_pairs(self.cast<Coupler&>().cell_overflow_reaction, self); },
           "OVERFLOW_LOAD: the reaction taken from each cell (ncell, 2) [N per metre of flume width], zero-copy view")
      .def_property_readonly("cell_base_porosity",
                             [](py::object self) { return view(self.cast<Coupler&>().cell_base_porosity, self); },
           "porosity without the stones per cell (ncell) [-] (from the flow at construction), zero-copy view")
      .def_property_readonly("cell_base_diameter",
                             [](py::object self) { return view(self.cast<Coupler&>().cell_base_diameter, self); },
           "stone diameter of the base porosity per cell (ncell) [m], zero-copy view");
}

}  // namespace vofdem::bind
