#include <pybind11/native_enum.h>
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <string>
#include <vector>

#include "fields.h"
#include "state.h"
#include "views.h"
#include "vofdem/flow/vof_grid.h"

namespace py = pybind11;

namespace vofdem::bind {

namespace {

using DoubleArray = py::array_t<double, py::array::c_style | py::array::forcecast>;

py::array_t<double> cells(py::object owner, std::vector<double>& v) {
  const Grid2D& g = owner.cast<VOFGrid&>().grid();
  return view2d(v.data(), g.nz(), g.nx(), owner);
}
py::array_t<double> xfaces(py::object owner, std::vector<double>& v) {
  const Grid2D& g = owner.cast<VOFGrid&>().grid();
  return view2d(v.data(), g.nz(), g.nx() + 1, owner);
}
py::array_t<double> zfaces(py::object owner, std::vector<double>& v) {
  const Grid2D& g = owner.cast<VOFGrid&>().grid();
  return view2d(v.data(), g.nz() + 1, g.nx(), owner);
}

// a fresh (nz, nx) array from a flat cell vector
py::array_t<double> cell_copy(const Grid2D& g, const std::vector<double>& v) {
  py::array_t<double> a({g.nz(), g.nx()});
  std::copy(v.begin(), v.end(), a.mutable_data());
  return a;
}

}  // namespace

void bind_vof(py::module_& m) {
  py::native_enum<FlowEffect>(m, "FlowEffect", "enum.IntFlag", "Bit flags of the flow solver's physical effects.")
      .value("FREE_SURFACE", kFlowFreeSurface, "two phases and VOF advection (off: water everywhere)")
      .value("POROUS_DARCY", kFlowPorousDarcy, "linear porous resistance nu/K")
      .value("POROUS_FORCHHEIMER", kFlowPorousForchheimer, "quadratic porous resistance C/sqrt(K) |u|")
      .value("TURBULENCE", kFlowTurbulence, "k-epsilon eddy viscosity")
      .value("VISCOSITY", kFlowViscosity, "viscous stresses")
      .value("GRAVITY", kFlowGravity, "gravity")
      .value("RELATIVE_VELOCITY", kFlowRelativeVelocity, "porous resistance on the velocity relative to the stones")
      .value("CONVECTION", kFlowConvection, "momentum convection")
      .value("POROUS_RESISTANCE", kFlowPorousResistance, "Darcy and Forchheimer terms")
      .value("DEFAULT", kFlowDefault, "free surface, porous resistance, viscosity, gravity, convection")
      .finalize();

  py::enum_<InletBoundary>(m, "InletBoundary", "The upstream end x = 0 of the flume (FlowParams.inlet).")
      .value("WALL", InletBoundary::kWall, "a closed wall")
      .value("DISCHARGE", InletBoundary::kDischarge, "prescribed discharge Q(t) over the wetted inlet");
  py::enum_<InletProfile>(m, "InletProfile", "How the inlet spreads the discharge [m^3/s] over its rows (FlowParams.inlet_profile).")
      .value("EQUIVALENT_DEPTH", InletProfile::kEquivalentDepth, "the rows below the inlet's level h = sum(F dz)")
      .value("WATER_FRACTION", InletProfile::kWaterFraction, "every row by its water fraction (the former profile)");
  py::enum_<OutletBoundary>(m, "OutletBoundary", "The downstream end of the flume (FlowParams.outlet).")
      .value("WALL", OutletBoundary::kWall, "a closed wall")
      .value("FREE_OVERFALL", OutletBoundary::kFreeOverfall, "the end face is a brink open to still air (hydrostatic air pressure)")
      .value("TAILWATER", OutletBoundary::kTailwater, "hydrostatic pressure below FlowParams.tailwater_level");
  py::enum_<TopBoundary>(m, "TopBoundary", "The top of the domain (FlowParams.top).")
      .value("OPEN", TopBoundary::kOpen, "open to the atmosphere, p = 0")
      .value("WALL", TopBoundary::kWall, "a slip lid");
  py::enum_<WallCondition>(m, "WallCondition", "Tangential velocity at the bed and the closed walls (FlowParams.walls).")
      .value("SLIP", WallCondition::kSlip, "no shear stress: the tangential velocity slips")
      .value("NO_SLIP", WallCondition::kNoSlip, "zero tangential velocity at the wall");
  py::enum_<ViscousScheme>(m, "ViscousScheme",
                            "Time stepping of the viscous (molecular + eddy) stresses (FlowParams.viscous_scheme).")
      .value("EXPLICIT", ViscousScheme::kExplicit, "forward Euler of every stress: the step limit dz^2 / (4 nu)")
      .value("IMPLICIT_VERTICAL", ViscousScheme::kImplicitVertical,
             "the vertical diffusion by backward Euler per column, from the velocities after the explicit part")
      .value("IMPLICIT_VERTICAL_FROM_START", ViscousScheme::kImplicitVerticalFromStart,
             "the former scheme: the columns from u^n beside the explicit part (unstable above 0.7 of its limit)")
      .value("IMPLICIT", ViscousScheme::kImplicit, "rows and columns implicit, the cross terms explicit: no step bound");
  py::enum_<ViscousBound>(m, "ViscousBound", "Bound of the viscous step limit [s] (FlowParams.viscous_bound).")
      .value("ENERGY", ViscousBound::kEnergy, "the split scheme's energy bound: no cross terms (a proof)")
      .value("ROW_SUM", ViscousBound::kRowSum, "Gershgorin row sums of the explicit stresses, cross terms in");
  py::enum_<KEpsilonPoreStrain>(m, "KEpsilonPoreStrain",
                                  "Which velocity's cross derivatives dU/dz, dW/dx [1/s] enter the k-epsilon production in "
                                  "porous cells (FlowParams.turbulence_pore_strain).")
      .value("NEIGHBOURS", KEpsilonPoreStrain::kNeighbours, "each neighbour's own pore velocity u / n")
      .value("LOCAL", KEpsilonPoreStrain::kLocal, "the neighbours' superficial velocities over this cell's porosity")
      .value("FILTERED", KEpsilonPoreStrain::kFiltered,
             "the pore velocity over the porosity averaged over a box of turbulence_pore_filter_length [m]");
  py::enum_<KEpsilonProduction>(m, "KEpsilonProduction",
                                  "Production term P [m^2/s^3] of k (FlowParams.turbulence_production).")
      .value("STRAIN", KEpsilonProduction::kStrain, "P = nu_t S^2 (the standard term)")
      .value("KATO_LAUNDER", KEpsilonProduction::kKatoLaunder, "P = nu_t S Omega: none in irrotational strain");
  py::enum_<KEpsilonTimeScheme>(m, "KEpsilonTimeScheme", "Time stepping of the k-epsilon transport (FlowParams.turbulence_time_scheme).")
      .value("POINT_IMPLICIT", KEpsilonTimeScheme::kPointImplicit,
             "predictor and Jacobi sweeps; the step bounded by the explicit limit of all faces")
      .value("VERTICAL_LINES", KEpsilonTimeScheme::kVerticalLines,
             "columns backward Euler by tridiagonal solves; the step bounded by the horizontal faces only")
      .value("ALTERNATING_LINES", KEpsilonTimeScheme::kAlternatingLines,
             "rows then columns backward Euler by tridiagonal solves; the step bounded by the horizontal "
             "advection only");
  py::enum_<MomentumTimeScheme>(m, "MomentumTimeScheme", "Time integration of the convective term (FlowParams.time_scheme).")
      .value("EULER", MomentumTimeScheme::kEuler, "forward Euler of the explicit momentum terms (first order)")
      .value("ADAMS_BASHFORTH2", MomentumTimeScheme::kAdamsBashforth2,
             "variable-step Adams-Bashforth 2 of the explicit momentum terms (second order)");
  py::enum_<StepControl>(m, "StepControl", "The advective limit a flow step is taken under (FlowParams.step_control).")
      .value("THIS_STEP", StepControl::kThisStep, "the limit of the step's start")
      .value("TWO_STEPS", StepControl::kTwoSteps,
             "the smaller of the limits of this step's start and the last step's: a two-step flicker is not chased");
  py::enum_<CornerViscosity>(m, "CornerViscosity",
                               "Viscosity [Pa s] of a cell corner, where the shear stress lives, from its four cells "
                               "(FlowParams.corner_viscosity).")
      .value("ARITHMETIC", CornerViscosity::kArithmetic, "the arithmetic mean of the four cells")
      .value("HARMONIC", CornerViscosity::kHarmonic,
             "the molecular part by arithmetic, the eddy part by harmonic mean (none next to air or solid)");

  py::class_<FlowParams> fp(m, "FlowParams", "Flow parameters, constant while stepping (SI units).");
  fp.def(py::init<>())
      .def_readwrite("medium", &FlowParams::medium, "water, air and gravity (Medium), shared with the stones")
      .def_readwrite("cfl", &FlowParams::cfl, with_default("target Courant number of the pore velocity [-]", &FlowParams::cfl).c_str())
      .def_readwrite("max_dt", &FlowParams::max_dt, with_default("largest time step [s]", &FlowParams::max_dt).c_str())
      .def_readwrite("initial_dt", &FlowParams::initial_dt, with_default("first time step [s]", &FlowParams::initial_dt).c_str())
      .def_readwrite("max_dt_growth", &FlowParams::max_dt_growth, with_default("dt <= max_dt_growth * the last step [-]", &FlowParams::max_dt_growth).c_str())
      .def_readwrite("min_dt", &FlowParams::min_dt, with_default("a stable step below this is a failure [s]", &FlowParams::min_dt).c_str())
      .def_readwrite("k1", &FlowParams::k1, with_default("linear resistance coefficient of eq. (7) [-]", &FlowParams::k1).c_str())
      .def_readwrite("k2", &FlowParams::k2, with_default("quadratic resistance coefficient of eq. (7) [-]", &FlowParams::k2).c_str())
      .def_readwrite("flume_width", &FlowParams::flume_width, with_default("flume width B [m]", &FlowParams::flume_width).c_str())
      .def_readwrite("pressure_solver", &FlowParams::pressure_solver,
                     with_default("PressureSolverKind of the projection", &FlowParams::pressure_solver).c_str())
      .def_readwrite("pressure_tol", &FlowParams::pressure_tol, "relative residual of the pressure solve [-]")
      .def_readwrite("inlet", &FlowParams::inlet,
                     with_default("InletBoundary of the left end (x = x0)", &FlowParams::inlet).c_str())
      .def_readwrite("inlet_profile", &FlowParams::inlet_profile, "InletProfile of the discharge over the inlet rows")
      .def_readwrite("outlet", &FlowParams::outlet,
                     with_default("OutletBoundary of the right end", &FlowParams::outlet).c_str())
      .def_readwrite("tailwater_level", &FlowParams::tailwater_level, "tailwater level [m] for OutletBoundary.TAILWATER")
      .def_readwrite("top", &FlowParams::top, with_default("TopBoundary of the domain", &FlowParams::top).c_str())
      .def_readwrite("walls", &FlowParams::walls,
                     with_default("WallCondition of the bed and the end walls", &FlowParams::walls).c_str())
      .def_readwrite("viscous_scheme", &FlowParams::viscous_scheme,
                     with_default("ViscousScheme of the viscous stresses (EXPLICIT: the forward-Euler reference)",
                                  &FlowParams::viscous_scheme)
                         .c_str())
      .def_readwrite("viscous_substeps", &FlowParams::viscous_substeps,
                     with_default("the viscous stresses in up to this many substeps of a flow step [-], [1, 64]; "
                                  "1: one explicit step",
                                  &FlowParams::viscous_substeps)
                         .c_str())
      .def_readwrite("viscous_bound", &FlowParams::viscous_bound,
                     "ViscousBound of the viscous step (IMPLICIT_VERTICAL only; the other schemes: ROW_SUM)")
      .def_readwrite("corner_viscosity", &FlowParams::corner_viscosity,
                     with_default("CornerViscosity of the shear stress at a cell corner", &FlowParams::corner_viscosity)
                         .c_str())
      .def_readwrite("time_scheme", &FlowParams::time_scheme, "MomentumTimeScheme of the explicit momentum terms")
      .def_readwrite("step_control", &FlowParams::step_control, "StepControl: the advective limit of one step or the last two")
      .def_readwrite("flags", &FlowParams::flags, "FlowEffect bits of the effects that are on")
      .def("validate", &FlowParams::validate, "ValueError naming the first parameter outside its range.");

  // the k-epsilon settings most runs touch (the rest keep the model's standard values)
  const auto k_eps = &FlowParams::turbulence;
  def_part_field(fp, "turbulence_production", k_eps, &KEpsilonParams::production,
                 "production of k: STRAIN (nu_t S^2) or KATO_LAUNDER (nu_t S Omega)");
  def_part_field(fp, "turbulence_production_limit", k_eps, &KEpsilonParams::production_limit,
                 "P_k <= limit * eps (Menter 1994: 10), 0 = off [-]");
  def_part_field(fp, "turbulence_pore_strain", k_eps, &KEpsilonParams::pore_strain,
                 "k-epsilon strain's cross derivatives: NEIGHBOURS' pore velocities, superficial over this cell's n "
                 "(LOCAL), or FILTERED (pore velocities over a box-filtered n)");
  def_part_field(fp, "turbulence_pore_filter_length", k_eps, &KEpsilonParams::pore_filter_length,
                 "side of the FILTERED pore strain's averaging box [m]");
  def_part_field(fp, "turbulence_time_scheme", k_eps, &KEpsilonParams::time_scheme,
                 "k-epsilon time stepping: POINT_IMPLICIT, VERTICAL_LINES or ALTERNATING_LINES");
  def_part_default(fp, "turbulence_cfl", k_eps, &KEpsilonParams::cfl,
                   "safety factor of the k-epsilon step limit [-], (0, 1]");
  def_part_field(fp, "turbulence_limit_step", k_eps, &KEpsilonParams::limit_step,
                 "VERTICAL_LINES, ALTERNATING_LINES: the explicit part's limit (the horizontal faces', or the "
                 "horizontal advection's alone) bounds the step (True) or not (False: not accurate in the weir, "
                 "docs/k_epsilon.md); POINT_IMPLICIT always limits the step and refuses False");
  def_part_field(fp, "turbulence_bed_roughness", k_eps, &KEpsilonParams::bed_roughness,
                 "equivalent sand roughness k_s of the bed [m]");
  def_part_field(fp, "turbulence_wall_roughness", k_eps, &KEpsilonParams::wall_roughness,
                 "k_s of end walls and solid cells [m]");
  def_part_default(fp, "turbulence_inflow_intensity", k_eps, &KEpsilonParams::inflow_intensity,
                   "inflow turbulence intensity [-]");
  def_part_default(fp, "turbulence_inflow_length_scale", k_eps, &KEpsilonParams::inflow_length_scale,
                   "inflow length scale [m]");
  // older scripts' names of the medium's fields
  const auto medium = &FlowParams::medium;
  def_part_field(fp, "rho_water", medium, &Medium::rho_water, "alias of medium.rho_water [kg/m^3]");
  def_part_field(fp, "rho_air", medium, &Medium::rho_air, "alias of medium.rho_air [kg/m^3]");
  def_part_field(fp, "nu_water", medium, &Medium::nu_water, "alias of medium.nu_water [m^2/s]");
  def_part_field(fp, "nu_air", medium, &Medium::nu_air, "alias of medium.nu_air [m^2/s]");
  def_part_element(fp, "gravity_x", medium, &Medium::gravity, 0, "alias of medium.gravity[0] [m/s^2]");
  def_part_element(fp, "gravity_z", medium, &Medium::gravity, 1, "alias of medium.gravity[1] [m/s^2]");

  py::class_<DischargeTable>(m, "DischargeTable", "Piecewise-linear discharge Q(t): times [s], discharge [m^3/s].")
      .def(py::init([](std::vector<double> t, std::vector<double> q) {
             DischargeTable d{std::move(t), std::move(q)};
             d.validate();
             return d;
           }),
           py::arg("times"), py::arg("discharge"))
      .def_readonly("times", &DischargeTable::times,
           "times [s], strictly increasing")
      .def_readonly("discharge", &DischargeTable::discharge,
           "discharge Q at each time [m^3/s], >= 0")
      .def("at", &DischargeTable::at, py::arg("t"), "Q [m^3/s] at time t [s]")
      .def_static("ramp", &DischargeTable::ramp, py::arg("q0"), py::arg("q1"), py::arg("t0"), py::arg("t1"),
                  "linear ramp from q0 to q1 [m^3/s] over [t0, t1] [s]")
      .def_static("constant", &DischargeTable::constant, py::arg("q"));

  py::class_<FlowStableDt>(m, "FlowStableDt", "Largest stable time step [s] of each term (inf: no limit).")
      .def_readonly("advective", &FlowStableDt::advective,
           "cfl times the smallest h / abs(u / n) over the faces (pore velocity) [s]")
      .def_readonly("viscous", &FlowStableDt::viscous,
           "the explicit viscous stresses' bound times viscous_substeps [s] (inf with the implicit scheme)")
      .def_readonly("gravity", &FlowStableDt::gravity,
           "cfl times sqrt(2 h_min / abs(g)): a cell crossed by a fall from rest [s]")
      .def_readonly("turbulence", &FlowStableDt::turbulence,
           "the k-epsilon model's limit [s] (inf when off)")
      .def_readonly("max_dt", &FlowStableDt::max_dt,
           "FlowParams.max_dt [s]")
      .def_readonly("growth", &FlowStableDt::growth,
           "initial_dt before the first step, then max_dt_growth times the last step [s]")
      .def_readonly("advective_cell", &FlowStableDt::advective_cell,
                    "the cell beside the face that binds the advective limit (-1: none)")
      .def_readonly("turbulence_cell", &FlowStableDt::turbulence_cell,
                    "the cell that binds the k-epsilon limit (-1: none)")
      .def_readonly("viscous_cell", &FlowStableDt::viscous_cell,
                    "the cell beside the face that binds the viscous limit (-1: none)")
      .def("min", &FlowStableDt::min,
           "the smallest of the terms: the stable step [s]");

  bind_state_class<FlowState>(m, "FlowState",
                               "A copy of a VOFGrid's whole state (VOFGrid.copy_state); set_state() returns to it.",
                               "step_count", &FlowState::step_count);

  py::class_<VOFGrid> cls(m, "VOFGrid",
                          "2D vertical free-surface flow through porous media (seed eqs. 1-4). State arrays are "
                          "zero-copy numpy views: cells (nz, nx), x-faces (nz, nx+1), z-faces (nz+1, nx).");
  cls.def(py::init<const Grid2D&, const FlowParams&>(), py::arg("grid"), py::arg("params") = FlowParams())
      .def_property_readonly("grid", &VOFGrid::grid, py::return_value_policy::reference_internal,
           "the grid (Grid2D), owned by this flow")
      .def_property(
          "params", [](const VOFGrid& f) { return f.params(); }, &VOFGrid::set_params,
          "a copy (editing it changes nothing); assign a modified copy to change them, checked, with the pressure "
          "solver and the k-epsilon model rebuilt")
      .def_property("discharge", &VOFGrid::discharge, &VOFGrid::set_discharge, "DischargeTable Q(t) [m^3/s]")
      .def_property_readonly("face_u", [](py::object s) { return xfaces(s, s.cast<VOFGrid&>().face_u); },
                             "superficial x-velocity [m/s]")
      .def_property_readonly("face_w", [](py::object s) { return zfaces(s, s.cast<VOFGrid&>().face_w); },
                             "superficial z-velocity [m/s]")
      .def_property_readonly("cell_p", [](py::object s) { return cells(s, s.cast<VOFGrid&>().cell_p); }, "pressure [Pa]")
      .def_property_readonly("cell_F", [](py::object s) { return cells(s, s.cast<VOFGrid&>().cell_F); },
                             "water fraction [-]")
      .def_property_readonly("cell_porosity", [](py::object s) { return cells(s, s.cast<VOFGrid&>().cell_porosity); },
                             "porosity [-] (0 = solid); call update_face_porosity() after writing")
      .def_property_readonly("face_x_porosity",
                             [](py::object s) { return xfaces(s, s.cast<VOFGrid&>().face_x_porosity); },
           "porosity n_f on the x-faces (nz, nx + 1) [-] (derived: the smaller of the two cells'), zero-copy view")
      .def_property_readonly("face_z_porosity",
                             [](py::object s) { return zfaces(s, s.cast<VOFGrid&>().face_z_porosity); },
           "porosity n_f on the z-faces (nz + 1, nx) [-] (derived), zero-copy view")
      .def_property_readonly("cell_stone_diameter",
                             [](py::object s) { return cells(s, s.cast<VOFGrid&>().cell_stone_diameter); },
                             "stone diameter D_sp [m]")
      .def_property_readonly("cell_nut", [](py::object s) { return cells(s, s.cast<VOFGrid&>().cell_nut); },
                             "eddy viscosity [m^2/s]")
      .def_property_readonly("cell_k", [](py::object s) { return cells(s, s.cast<VOFGrid&>().turbulence().cell_k); },
                             "turbulent kinetic energy [m^2/s^2] (k-epsilon)")
      .def_property_readonly("cell_eps", [](py::object s) { return cells(s, s.cast<VOFGrid&>().turbulence().cell_eps); },
                             "dissipation rate [m^2/s^3] (k-epsilon)")
      .def_property_readonly("face_x_solid_u", [](py::object s) { return xfaces(s, s.cast<VOFGrid&>().face_x_solid_u); },
                             "stones' x-velocity at x-faces [m/s]")
      .def_property_readonly("face_z_solid_w", [](py::object s) { return zfaces(s, s.cast<VOFGrid&>().face_z_solid_w); },
                             "stones' z-velocity at z-faces [m/s]")
      .def(
          "set_porosity",
          [](VOFGrid& f, const DoubleArray& n, bool displace) {
            f.set_porosity(std::vector<double>(n.data(), n.data() + n.size()), displace);
          },
          py::arg("porosity"), py::arg("displace") = false,
          "sets the cell porosity (ncell values in [0, 1]) and the face porosities; displace=True: the change "
          "is a source of the next step's continuity (dn/dt + div u = 0), so displaced water flows away")
      .def("update_face_porosity", &VOFGrid::update_face_porosity, py::arg("displace") = false,
           "recomputes the face porosities after writing cell_porosity / cell_stone_diameter")
      .def("fill_water_below", &VOFGrid::fill_water_below, py::arg("level"),
           "water fraction F = 1 below level [m] (a partial fraction in the cut row), 0 above")
      .def("fill_water_box", &VOFGrid::fill_water_box, py::arg("x0"), py::arg("x1"), py::arg("z0"), py::arg("z1"),
           py::arg("value") = 1.0,
           "F = value in the cells whose centre lies in [x0, x1] x [z0, z1] [m], untouched elsewhere")
      .def("set_porosity_box", &VOFGrid::set_porosity_box, py::arg("x0"), py::arg("x1"), py::arg("z0"), py::arg("z1"),
           py::arg("n"), py::arg("d"),
           "porosity n [-] and stone diameter d [m] in the cells whose centre lies in [x0, x1] x [z0, z1] [m]; n = 0 makes solid cells")
      .def("set_hydrostatic_pressure", &VOFGrid::set_hydrostatic_pressure,
           "hydrostatic pressure [Pa] from the water fraction, p = 0 at the top")
      .def_property("time", &VOFGrid::time, &VOFGrid::set_time, "simulated time [s]")
      .def_property_readonly("step_count", &VOFGrid::step_count,
           "flow steps taken")
      .def_property("last_dt", &VOFGrid::last_dt, &VOFGrid::set_last_dt,
                    "the last step [s] the growth limit starts from (0: none yet, initial_dt applies)")
      .def_property_readonly("last_advective", &VOFGrid::last_advective,
                             "the advective limit [s] measured at the last step's start (0: none)")
      .def_property_readonly("retried_steps", &VOFGrid::retried_steps,
                             "steps advance() took again, shorter, after a CFL breach")
      .def_property_readonly("prev_dt", &VOFGrid::prev_dt,
                             "the last step [s] of the Adams-Bashforth history (0: none, the next step is Euler)")
      .def("clear_step_history", &VOFGrid::clear_step_history,
           "forget the last step (the next one is forward Euler): after velocities were set by hand")
      .def("stable_dt", &VOFGrid::stable_dt,
           "the stable step [s]: the smallest of stable_dt_terms()")
      .def("stable_dt_terms", &VOFGrid::stable_dt_terms,
           "the stable step's terms (FlowStableDt) [s], with the cells that bind them");
  def_copy_state<FlowState>(cls, "a copy of the whole state (FlowState): set_state(copy) continues from it bit for bit",
                            "returns to a copy_state() copy (checked first; written into the arrays in place: views "
                            "stay valid)");
  cls.def("step", &VOFGrid::step, py::arg("dt"), py::call_guard<py::gil_scoped_release>(),
           "one flow step of dt [s]; RuntimeError naming the stage, cell and time after restoring the step's start; the GIL is released")
      .def("advance", &VOFGrid::advance, py::arg("t_end"), py::call_guard<py::gil_scoped_release>(),
           "steps of stable_dt() until time reaches t_end [s] (a step that breaches the CFL taken again shorter); returns the steps; the GIL is released")
      .def("pore_velocity_at_cells",
           [](const VOFGrid& f) {
             std::vector<double> U, W;
             f.pore_velocity_at_cells(U, W);
             return py::make_tuple(cell_copy(f.grid(), U), cell_copy(f.grid(), W));
           },
           "(U, W) = (u / n, w / n) at the cell centres (nz, nx) [m/s], 0 in solid cells, copied")
      .def("pressure_gradient_at_cells",
           [](const VOFGrid& f) {
             std::vector<double> gx, gz;
             f.pressure_gradient_at_cells(gx, gz);
             return py::make_tuple(cell_copy(f.grid(), gx), cell_copy(f.grid(), gz));
           },
           "(dp/dx, dp/dz) at the cell centres (nz, nx) [Pa/m] (central, one-sided at walls and solids), copied")
      .def("water_volume", &VOFGrid::water_volume, "sum(n F V) per metre of width [m^2]")
      .def("discharge_through", &VOFGrid::discharge_through, py::arg("i"), "water discharge per width [m^2/s]")
      .def("inlet_discharge_per_width", &VOFGrid::inlet_discharge_per_width, "q = Q(t) / B now [m^2/s]")
      .def_property_readonly("inlet_volume", &VOFGrid::inlet_volume,
                             "water volume per width [m^2] that entered through the inlet")
      .def_property_readonly("net_inflow_volume", &VOFGrid::net_inflow_volume,
                             "water volume per width [m^2] in through the boundary faces minus out, since "
                             "construction (the VOF advection's fluxes)")
      .def_property_readonly("dilatation_volume", &VOFGrid::dilatation_volume,
                             "water volume per width [m^2] made by the advection's divergence correction where "
                             "the velocity is not divergence-free (the pressure solve's residual), since construction")
      .def_property_readonly("profile", py::overload_cast<>(&VOFGrid::profile),
                             py::return_value_policy::reference_internal,
           "wall-clock seconds per flow stage (StageProfile)")
      .def_property_readonly("turbulence_profile", [](VOFGrid& f) -> StageProfile& { return f.turbulence().profile(); },
                             py::return_value_policy::reference_internal,
                             "the k-epsilon model's own stages (setup, wall functions, production, transport, eddy "
                             "viscosity, checks): the parts of the 'turbulence' stage")
      .def_property_readonly("last_pressure_stats", &VOFGrid::last_pressure_stats,
           "the last pressure solve's outcome (PressureSolveStats: iterations, residual)")
      .def_property_readonly("pressure_fallbacks", &VOFGrid::pressure_fallbacks,
                             "multigrid-CG solves redone by the direct solver (no convergence)")
      .def_property_readonly("pressure_iterations", &VOFGrid::pressure_iterations,
                             "CG iterations of every pressure solve since construction (a fallback counts "
                             "max_iterations); per solve: over the 'pressure' stage's calls in profile")
      .def("__repr__", [](const VOFGrid& f) {
        return "VOFGrid(nx=" + std::to_string(f.grid().nx()) + ", nz=" + std::to_string(f.grid().nz()) +
               ", t=" + std::to_string(f.time()) + ")";
      });
}

}  // namespace vofdem::bind
