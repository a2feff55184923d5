// Thin bindings of the DEM of the stones (dem_system.h) and the weir packing (weir_packing.h).
#include <pybind11/native_enum.h>
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <cstring>
#include <memory>
#include <string>
#include <tuple>

#include "fields.h"
#include "flags.h"
#include "state.h"
#include "views.h"
#include "vofdem/stones/clump.h"
#include "vofdem/stones/clump_model.h"
#include "vofdem/stones/dem_contact.h"
#include "vofdem/stones/dem_system.h"
#include "vofdem/stones/weir_packing.h"

namespace py = pybind11;

namespace vofdem::bind {

namespace {

std::vector<double> flat_pos(const py::array_t<double, py::array::c_style | py::array::forcecast>& pos) {
  return std::vector<double>(pos.data(), pos.data() + pos.size());
}

void bind_params(py::module_& m) {
  py::class_<DEMWall>(m, "DEMWall", "Half-plane wall: the solid lies opposite to `normal` (SI units).")
      .def(py::init([](std::array<double, 2> point, std::array<double, 2> normal, double friction) {
             return DEMWall{point, normal, friction};
           }),
           py::arg("point"), py::arg("normal"), py::arg("friction") = 0.176)
      .def_readwrite("point", &DEMWall::point,
           "a point of the wall's line (x, z) [m]")
      .def_readwrite("normal", &DEMWall::normal,
           "the wall's normal (x, z) into the stones' side [-]; scaled to unit length")
      .def_readwrite("friction", &DEMWall::friction,
           "stone-wall Coulomb coefficient [-] (paper 0.176)");

  py::class_<DEMParams> dp(m, "DEMParams", "Constant parameters of the DEM of the stones (SI units; see dem_system.h).");
  dp.def(py::init<>())
      .def_readwrite("medium", &DEMParams::medium, "water and gravity (Medium); a Coupler sets the flow's")
      .def_readwrite("submerged", &DEMParams::submerged,
                     "the stones lie in the medium's water (buoyancy, added mass); False: dry")
      .def_property_readonly("water_density", &DEMParams::water_density,
                             "rho_w of buoyancy and added mass [kg/m^3]: medium.rho_water if submerged, else 0")
      .def_readwrite("domain_min", &DEMParams::domain_min, "removal box, lower corner (x, z) [m]")
      .def_readwrite("domain_max", &DEMParams::domain_max, "removal box, upper corner (x, z) [m]")
      .def_readwrite("walls", &DEMParams::walls, "half-plane walls (DEMWall: the bed, the end walls)")
      .def_readwrite("flags", &DEMParams::flags, "DEMFlag bits of the effects that are on")
      .def("add_flume", &DEMParams::add_flume, py::arg("x_min"), py::arg("x_max"), py::arg("z_bed") = 0.0,
           py::arg("mu") = 0.176,
           "Adds the flume's walls: the bed z = z_bed and the end walls x = x_min, x_max [m], each with the "
           "stone-wall Coulomb coefficient mu [-].");
  def_field(dp, "added_mass_coefficient", &DEMParams::added_mass_coefficient,
            "added-mass coefficient C_M [-] (the paper's run 1.0, its text 0.5)");
  def_field(dp, "dt", &DEMParams::dt, "DEM step [s]; advance() substeps never exceed it (the paper's 1e-4)");
  def_field(dp, "stiffness_normal", &DEMParams::stiffness_normal,
            "normal spring stiffness k_n [N/m]; 0 = automatic from contact_steps (Gotoh & Sakai 1997)");
  def_field(dp, "contact_steps", &DEMParams::contact_steps,
            "automatic k_n: DEM steps per undamped contact of two mean stones [-]");
  def_field(dp, "stiffness_ratio", &DEMParams::stiffness_ratio, "tangential to normal stiffness k_t / k_n [-]");
  def_field(dp, "restitution", &DEMParams::restitution,
            "normal restitution coefficient e [-], [0, 1]; 0 = critical damping");
  def_field(dp, "tangential_damping_factor", &DEMParams::tangential_damping_factor,
            "tangential to normal dashpot c_t / c_n [-] (LAMMPS's default)");
  def_field(dp, "friction_stone", &DEMParams::friction_stone,
            "stone-stone Coulomb coefficient mu [-] (the paper's 0.577)");
  def_field(dp, "inertia_factor", &DEMParams::inertia_factor,
            "moment of inertia I = factor M r^2 [-] (a sphere 0.4, a disc 0.5)");
  def_field(dp, "rolling_friction_stone", &DEMParams::rolling_friction_stone,
            "rolling friction mu_r stone-stone [-], >= 0 (with ROLLING_RESISTANCE; discs and 3D stones)");
  def_field(dp, "rolling_friction_wall", &DEMParams::rolling_friction_wall,
            "rolling friction mu_r stone-wall [-], >= 0 (with ROLLING_RESISTANCE)");
  def_field(dp, "rolling_damping", &DEMParams::rolling_damping,
            "rolling damper ratio eta_r = C_r / (2 sqrt(I_r k_r)) [-], [0, 1]");
  def_field(dp, "neighbour_skin", &DEMParams::neighbour_skin,
            "Verlet-list skin [m]; 0 = a tenth of the largest diameter");
  def_field(dp, "sleep_velocity", &DEMParams::sleep_velocity,
            "a stone may sleep below this speed (and omega r) [m/s] (with SLEEPING)");
  def_field(dp, "sleep_time", &DEMParams::sleep_time, "... held for this long [s]");
  def_field(dp, "wake_acceleration", &DEMParams::wake_acceleration,
            "a sleeping stone wakes when its net force gives more [m/s^2]");
  def_field(dp, "width", &DEMParams::width,
            "3D stones: the flume's width between the side walls y = 0 and y = width [m], > 0 for them");
  def_field(dp, "side_wall_friction", &DEMParams::side_wall_friction,
            "3D stones: stone-side wall Coulomb coefficient [-], >= 0 (the paper's glass 0.176)");
  def_field(dp, "plane_neighbour_list", &DEMParams::plane_neighbour_list,
            "3D stones: neighbours by their x-z projections whatever their y (True: more pairs, the same forces) "
            "or by cells in x, y and z (False)");

  py::native_enum<DEMFlag>(m, "DEMFlag", "enum.IntFlag", "Bit flags of the DEM's physical effects (DEMParams.flags).")
      .value("GRAVITY", kDEMGravity, "gravity (and buoyancy with BUOYANCY)")
      .value("ROTATION", kDEMRotation, "stones spin, eq. (10)")
      .value("FRICTION", kDEMFriction, "Coulomb cap of the tangential spring")
      .value("ADDED_MASS", kDEMAddedMass, "M' = rho_w C_M V w")
      .value("BUOYANCY", kDEMBuoyancy, "rho_w V w g")
      .value("SLEEPING", kDEMSleeping, "stones at rest under small forces are not integrated")
      .value("DAMPING", kDEMDamping, "contact dashpots")
      .value("EXTERNAL_FORCE", kDEMExternalForce, "stone_force_ext (the fluid's forces)")
      .value("REMOVAL", kDEMRemoval, "stones leaving the domain box are deactivated")
      .value("ROLLING_RESISTANCE", kDEMRollingResistance, "rolling moment (rolling_resistance.h)")
      .value("ALL_EFFECTS", kDEMAllEffects, "everything but sleeping")
      .finalize();
  export_flag_members(m, "DEMFlag", "DEM_");  // the older module constants

  py::class_<DEMEnergy>(m, "DEMEnergy", "Energy bookkeeping of the DEM [J].")
      .def_readonly("kinetic", &DEMEnergy::kinetic,
           "sum of 1/2 (M + M') v^2 + 1/2 I omega^2 [J]")
      .def_readonly("potential", &DEMEnergy::potential,
           "sum of -(M - rho_w V w) g . x [J], zero at the origin")
      .def_readonly("elastic", &DEMEnergy::elastic,
           "energy in the contact springs (the rolling ones too) at the last evaluation [J]")
      .def_readonly("dissipated", &DEMEnergy::dissipated,
           "dashpots, Coulomb and rolling slip and sleeping, accumulated [J]")
      .def_readonly("work_external", &DEMEnergy::work_external,
           "work of the external (fluid) forces stone_force_ext, accumulated [J]")
      .def_property_readonly("total", &DEMEnergy::total,
           "kinetic + potential + elastic + dissipated - work_external [J]: constant but for round-off and the step's error");

  m.def("damping_ratio_from_restitution", &damping_ratio_from_restitution, py::arg("e"),
        "Damping ratio zeta [-] of a linear spring-dashpot that gives the restitution coefficient e [-] (e = 0: zeta = 1).");
  m.def("restitution_from_damping_ratio", &restitution_from_damping_ratio, py::arg("zeta"),
        "Restitution coefficient e [-] of a linear spring-dashpot of damping ratio zeta [-] (0 for zeta >= 1).");
  m.def("stone_model_names", &stone_model_names,
        "the registered stone models' names (DEMSystem.shape, the scene's stones.shape), the built-in ones first");
  m.def(
      "quarried_stone",
      [](const std::string& name, double d_eq, double ratio_intermediate, double ratio_short) {
        const Clump c = quarried_stone(name, d_eq, ratio_intermediate, ratio_short);
        py::array_t<double> out({static_cast<py::ssize_t>(c.spheres().size()), py::ssize_t{4}});
        for (std::size_t k = 0; k < c.spheres().size(); ++k) {
          for (int d = 0; d < 3; ++d) out.mutable_at(k, d) = c.spheres()[k].centre[d];
          out.mutable_at(k, 3) = c.spheres()[k].radius;
        }
        return out;
      },
      py::arg("name"), py::arg("d_eq"), py::arg("ratio_intermediate") = 0.8, py::arg("ratio_short") = 0.6,
      "The spheres (k, 4) of a library clump (x, y, z, r) [m] in its principal frame: name one of "
      "quarried_stone_names(), d_eq [m] in (0, inf) its volume-equivalent diameter, the aspect ratios "
      "intermediate/long in [ratio_short, 1] and short/long in [0.55, 1] [-].");
  m.def("quarried_stone_names", &quarried_stone_names, "the library clumps' names (quarried_stone)");
  m.def("contact_duration", &contact_duration, py::arg("k"), py::arg("m_reduced"), py::arg("zeta"),
        "Contact duration t_c [s] of a linear spring-dashpot: stiffness k [N/m], reduced mass m_reduced [kg], damping "
        "ratio zeta [-] (inf for zeta >= 1).");
}

void bind_system(py::module_& m) {
  using A = py::array_t<double, py::array::c_style | py::array::forcecast>;
  bind_state_class<DEMState>(m, "DEMState",
                              "A copy of a DEMSystem's whole state (DEMSystem.copy_state); set_state() returns to it.",
                              "steps", &DEMState::steps);

  py::class_<DEMSystem> cls(m, "DEMSystem", "Stones as discs (sphere masses), eqs. (8)-(10) of Maeno & Tomita (2008).");
  cls.def(py::init<const DEMParams&, int>(), py::arg("params"), py::arg("n"))
      .def(py::init([](const DEMParams& p, const A& pos, const A& radius, const A& density,
                       const std::vector<std::uint8_t>& fixed) {
             return new DEMSystem(p, flat_pos(pos), flat_pos(radius), flat_pos(density), fixed);
           }),
           py::arg("params"), py::arg("pos"), py::arg("radius"), py::arg("density"),
           py::arg("fixed") = std::vector<std::uint8_t>{})
      .def_property_readonly("n", &DEMSystem::n,
           "number of stones (removed ones included; see stone_active)")
      .def_property(
          "params", [](const DEMSystem& s) { return s.params(); }, &DEMSystem::set_params,
          "a copy (editing it changes nothing); assign a modified copy to change them, checked")
      .def_property("held", &DEMSystem::held, &DEMSystem::set_held,
                    "True: every stone held in place, steps advance the time alone and the contacts keep their "
                    "springs (a run's spin-up); False lets them go. Holding stops the stones. Not in export_state()")
      .def("resize", &DEMSystem::resize, py::arg("n"),
           "n stones, all arrays zeroed (discs again); invalidates every earlier view and the contact histories")
      .def("stable_dt", &DEMSystem::stable_dt,
           "the stable DEM step [s] of the stones' contacts (the stone model's bound); advance() substeps never exceed min(params.dt, it)")
      .def("step", &DEMSystem::step, py::arg("dt"), py::call_guard<py::gil_scoped_release>(),
           "one DEM step of dt [s] (checked against the stable step); the GIL is released")
      .def("advance", &DEMSystem::advance, py::arg("duration"), py::call_guard<py::gil_scoped_release>(),
           "advances by duration [s] in steps of at most params.dt and the stable step; the GIL is released")
      .def_property_readonly("stiffness_normal", &DEMSystem::stiffness_normal,
           "normal contact stiffness k_n in use [N/m] (params.stiffness_normal, or the automatic value)")
      .def_property_readonly("stiffness_tangential", &DEMSystem::stiffness_tangential,
           "tangential contact stiffness k_t = stiffness_ratio k_n [N/m]")
      .def_property_readonly("damping_ratio", &DEMSystem::damping_ratio,
           "normal damping ratio zeta [-] from params.restitution")
      .def_property_readonly("time", &DEMSystem::time,
           "simulated time of the stones [s]")
      .def_property_readonly("steps", &DEMSystem::steps,
           "DEM steps taken")
      .def_property_readonly("removed_count", &DEMSystem::removed_count,
           "stones that left the domain (stone_active = 0)")
      .def_property_readonly("contact_count", &DEMSystem::contact_count,
           "touching stone-stone contacts at the last force evaluation")
      .def_property_readonly("wall_contact_count", &DEMSystem::wall_contact_count,
           "touching stone-wall contacts at the last force evaluation")
      .def_property_readonly("neighbour_builds", &DEMSystem::neighbour_builds,
           "how often the neighbour (Verlet) list was built")
      .def("max_speed", &DEMSystem::max_speed,
           "the largest speed of a free, active stone [m/s]: its centre's or its spin times its radius (3D stones: "
           "across the flume and about every axis too)")
      .def("energy", &DEMSystem::energy,
           "the energy account (DEMEnergy) [J] at the last evaluation")
      .def("mass", &DEMSystem::mass, py::arg("i"),
           "M_i = rho_s V_i [kg] of stone i")
      .def("set_wet_fraction", &DEMSystem::set_wet_fraction, py::arg("i"), py::arg("w"),
           "wet fraction of stone i; when it grows, (M + M') v is kept")
      .def("volume", &DEMSystem::volume, py::arg("i"),
           "V_i [m^3] of stone i: that of the 3D stone its model stands for")
      .def("projected_area", py::overload_cast<int>(&DEMSystem::projected_area, py::const_), py::arg("i"))
      .def("projected_area", py::overload_cast<int, double, double>(&DEMSystem::projected_area, py::const_),
           py::arg("i"), py::arg("ux"), py::arg("uz"))
      .def("nominal_diameter", &DEMSystem::nominal_diameter, py::arg("i"),
           "nominal diameter [m] of stone i (a disc's 2 r, a polygon's equal-area disc's)")
      .def("inertia", &DEMSystem::inertia, py::arg("i"),
           "moment of inertia I_i [kg m^2] of stone i about the plane's normal")
      .def_property_readonly("shape", [](const DEMSystem& s) { return std::string(s.model().name()); },
                             "the stone model's registered name (stone_model_names())")
      .def("set_model", py::overload_cast<const std::string&>(&DEMSystem::set_model), py::arg("name"),
           "Makes every stone of the registered stone model `name` (stone_model_names()); shape arrays and "
           "contact histories are made anew. Invalidates the poly_* views.")
      .def("set_polygons",
           [](DEMSystem& s, const A& vertex, const std::vector<int>& offset) { s.set_polygons(flat_pos(vertex), offset); },
           py::arg("vertex"), py::arg("offset"),
           "Makes every stone a convex polygon: body-frame vertices (x, z) [m], CCW, centroid at the origin; "
           "stone i owns vertices offset[i]:offset[i+1]. Invalidates the poly_* views.")
      .def(
          "set_clumps",
          [](DEMSystem& s, const A& sphere, const std::vector<int>& offset) { set_clumps(s, flat_pos(sphere), offset); },
          py::arg("sphere"), py::arg("offset"),
          "Makes every stone a clump of overlapping spheres (the model 'clump'): sphere (m, 4) rows (x, y, z, r) "
          "[m] in any frame, each stone's stored in its principal frame (stone_pos, stone_y: its centre of mass); "
          "stone i owns rows offset[i]:offset[i+1] (1 to 8); stone_radius becomes each bounding radius. The "
          "out-of-plane state is made anew.")
      .def_property_readonly(
          "clump_sphere",
          [](const DEMSystem& s) {
            // empty for stones of another model, as poly_vertex is for discs
            const auto* m = dynamic_cast<const ClumpModel*>(&s.model());
            const std::vector<double> none;
            const std::vector<double>& b = m ? m->spheres() : none;
            py::array_t<double> out({static_cast<py::ssize_t>(b.size() / 4), py::ssize_t{4}});
            std::copy(b.begin(), b.end(), out.mutable_data());
            return out;
          },
          "clump stones' spheres (m, 4) rows (x, y, z, r) [m] in each stone's principal frame (a copy; empty for "
          "other stones); stone i owns rows clump_offset[i]:clump_offset[i + 1]")
      .def_property_readonly(
          "clump_offset",
          [](const DEMSystem& s) {
            const auto* m = dynamic_cast<const ClumpModel*>(&s.model());
            return m ? m->offsets() : std::vector<int>{};
          },
          "clump stones' first rows of clump_sphere (n + 1), a copy; empty for other stones")
      .def_property_readonly("poly_vertex",
                             [](py::object self) { return view_pairs(self.cast<DEMSystem&>().poly_vertex, self); },
           "polygon stones' body-frame vertices (m, 2) [m], zero-copy view (set_polygons reallocates it)")
      .def_property_readonly("poly_offset",
                             [](py::object self) { return view(self.cast<DEMSystem&>().poly_offset, self); },
           "stone i owns poly_vertex[poly_offset[i]:poly_offset[i + 1]] (n + 1), zero-copy view")
      .def("neighbour_pairs", &DEMSystem::neighbour_pairs,
           "the neighbour list's pairs (i, j), i < j")
      .def("overlapping_pairs", &DEMSystem::overlapping_pairs,
           "the pairs (i, j) that touch now, from the neighbour list")
      .def("overlapping_pairs_reference", &DEMSystem::overlapping_pairs_reference,
           "the pairs that touch now by testing every pair (the slow reference of overlapping_pairs)");
  def_checkpoint_state(cls,
                       "restores export_state() exactly, written into the arrays in place; a state of another stone "
                       "count (or, for polygons, vertex count) resizes and so invalidates earlier views");
  def_copy_state<DEMState>(cls, "a copy of the whole state (DEMState): set_state(copy) continues from it bit for bit",
                           "returns to a copy_state() copy (checked first; written in place unless the stone or "
                           "vertex count differs, which invalidates earlier views)");
  cls.def_property_readonly("profile", &DEMSystem::profile, py::return_value_policy::reference_internal,
           "wall-clock seconds per DEM stage (StageProfile)")
      .def_property_readonly("stone_pos", [](py::object self) { return view_pairs(self.cast<DEMSystem&>().stone_pos, self); },
           "centres (x along the flume, z up) (n, 2) [m], zero-copy view")
      .def_property_readonly("stone_vel", [](py::object self) { return view_pairs(self.cast<DEMSystem&>().stone_vel, self); },
           "velocities (n, 2) [m/s], zero-copy view")
      .def_property_readonly("stone_force_ext",
                             [](py::object self) { return view_pairs(self.cast<DEMSystem&>().stone_force_ext, self); },
           "external (fluid) forces (n, 2) [N], held until changed; zero-copy view")
      .def_property_readonly("stone_drag_coef",
                             [](py::object self) { return view(self.cast<DEMSystem&>().stone_drag_coef, self); },
           "linear drag coefficient c >= 0 per stone (n) [N s/m], zero-copy view")
      .def_property_readonly("stone_drag_vel",
                             [](py::object self) { return view_pairs(self.cast<DEMSystem&>().stone_drag_vel, self); },
           "velocity U the linear drag c (U - v) pulls towards (n, 2) [m/s], zero-copy view")
      .def_property_readonly("stone_force", [](py::object self) { return view_pairs(self.cast<DEMSystem&>().stone_force, self); },
           "total force of the last evaluation (n, 2) [N], zero-copy view")
      .def_property_readonly("stone_acc", [](py::object self) { return view_pairs(self.cast<DEMSystem&>().stone_acc, self); },
           "acceleration of the last evaluation (n, 2) [m/s^2], zero-copy view")
      .def_property_readonly("stone_y", [](py::object self) { return view(self.cast<DEMSystem&>().stone_y, self); },
           "3D stones: centre across the flume, 0 <= y <= width (n) [m] (empty for the plane's models), zero-copy view")
      .def_property_readonly("stone_vel_y", [](py::object self) { return view(self.cast<DEMSystem&>().stone_vel_y, self); },
           "3D stones: velocity across the flume (n) [m/s] (empty for the plane's models), zero-copy view")
      .def_property_readonly("stone_force_y",
                             [](py::object self) { return view(self.cast<DEMSystem&>().stone_force_y, self); },
           "3D stones: total force across the flume of the last evaluation (n) [N], zero-copy view")
      .def_property_readonly("stone_acc_y", [](py::object self) { return view(self.cast<DEMSystem&>().stone_acc_y, self); },
           "3D stones: acceleration across the flume of the last evaluation (n) [m/s^2], zero-copy view")
      .def_property_readonly("stone_quat",
                             [](py::object self) {
                               auto& v = self.cast<DEMSystem&>().stone_quat;
                               return view2d(v.data(), static_cast<py::ssize_t>(v.size() / 4), 4, self);
                             },
           "3D stones: orientation, unit quaternions (w, x, y, z) body -> world (n, 4) [-], zero-copy view")
      .def_property_readonly("stone_omega_3d",
                             [](py::object self) {
                               auto& v = self.cast<DEMSystem&>().stone_omega_3d;
                               return view2d(v.data(), static_cast<py::ssize_t>(v.size() / 3), 3, self);
                             },
           "3D stones: angular velocity in the world frame (x, y, z) (n, 3) [rad/s], zero-copy view")
      .def_property_readonly("stone_torque_3d",
                             [](py::object self) {
                               auto& v = self.cast<DEMSystem&>().stone_torque_3d;
                               return view2d(v.data(), static_cast<py::ssize_t>(v.size() / 3), 3, self);
                             },
           "3D stones: total torque about the centre of the last evaluation, world frame (n, 3) [N m], zero-copy view")
      .def_property_readonly("stone_angle", [](py::object self) { return view(self.cast<DEMSystem&>().stone_angle, self); },
           "rotation angle, counter-clockwise in (x, z) (n) [rad], zero-copy view")
      .def_property_readonly("stone_omega", [](py::object self) { return view(self.cast<DEMSystem&>().stone_omega, self); },
           "angular velocity (n) [rad/s], zero-copy view")
      .def_property_readonly("stone_radius",
                             [](py::object self) { return view(self.cast<DEMSystem&>().stone_radius, self); },
           "radius (n) [m] (a disc's d / 2, a polygon's nominal one), zero-copy view")
      .def_property_readonly("stone_density",
                             [](py::object self) { return view(self.cast<DEMSystem&>().stone_density, self); },
           "stone density rho_s (n) [kg/m^3], zero-copy view")
      .def_property_readonly("stone_fixed", [](py::object self) { return view(self.cast<DEMSystem&>().stone_fixed, self); },
           "1: the stone never moves (bed layer) (n), zero-copy view")
      .def_property_readonly("stone_active",
                             [](py::object self) { return view(self.cast<DEMSystem&>().stone_active, self); },
           "0: the stone left the domain (kept, not integrated) (n), zero-copy view")
      .def_property_readonly("stone_wet", [](py::object self) { return view(self.cast<DEMSystem&>().stone_wet, self); },
           "wet fraction in [0, 1] (n) [-], zero-copy view")
      .def_property_readonly("stone_water_level",
                             [](py::object self) { return view(self.cast<DEMSystem&>().stone_water_level, self); },
                             "free-surface level at each stone [m]; NaN: stone_wet held as set")
      .def_property_readonly("stone_torque",
                             [](py::object self) { return view(self.cast<DEMSystem&>().stone_torque, self); },
           "total torque of the last evaluation (n) [N m], zero-copy view")
      .def_property_readonly("stone_alpha", [](py::object self) { return view(self.cast<DEMSystem&>().stone_alpha, self); },
           "angular acceleration of the last evaluation (n) [rad/s^2], zero-copy view")
      .def_property_readonly("stone_asleep",
                             [](py::object self) { return view(self.cast<DEMSystem&>().stone_asleep, self); },
           "1: the stone sleeps (not integrated) (n), zero-copy view");
}

void bind_packing(py::module_& m) {
  using A = py::array_t<double, py::array::c_style | py::array::forcecast>;
  py::class_<WeirSpec> ws(m, "WeirSpec", "Trapezoidal rubble mound weir to pack (SI units; see weir_packing.h).");
  ws.def(py::init<>())
      .def("x_end", &WeirSpec::x_end, "The downstream toe [m] along the flume.")
      .def("top", &WeirSpec::top, py::arg("x"), "The trapezoid's height above the bed [m] at x [m] (0 outside).")
      .def("area", &WeirSpec::area, "The trapezoid's area [m^2].");
  def_field(ws, "height", &WeirSpec::height, "crest height H above the bed [m]");
  def_field(ws, "crest", &WeirSpec::crest, "crest length L_c [m]");
  def_field(ws, "slope_up_deg", &WeirSpec::slope_up_deg, "upstream slope [deg]");
  def_field(ws, "slope_down_deg", &WeirSpec::slope_down_deg, "downstream slope [deg]");
  def_field(ws, "x_toe", &WeirSpec::x_toe, "upstream toe along the flume [m]");
  def_field(ws, "z_bed", &WeirSpec::z_bed, "bed height [m]");
  def_field(ws, "d_mean", &WeirSpec::d_mean, "mean stone diameter [m], > 0, required (0: unset)");
  def_field(ws, "d_spread", &WeirSpec::d_spread, "half-width of the uniform diameter distribution, relative [-]");
  def_field(ws, "density", &WeirSpec::density, "stone density [kg/m^3], > 0, required (0: unset)");
  def_field(ws, "seed", &WeirSpec::seed, "random seed of the diameters, shapes and lattice jitter [-]");
  def_field(ws, "settle_time_max", &WeirSpec::settle_time_max, "simulated time allowed each settling phase [s]");
  def_field(ws, "rest_speed", &WeirSpec::rest_speed, "the packing is at rest when every stone is slower [m/s]");
  def_field(ws, "compaction_friction", &WeirSpec::compaction_friction,
            "3D models: the stone-stone friction of the pour's rounds, a compaction before the weir's own friction "
            "returns [-], in [0, 2]; -1: the stone model's own (clumps 0.1, spheres none)");
  ws.def_property(
      "shape", [](const WeirSpec& w) { return w.shape; }, [](WeirSpec& w, const std::string& name) { w.shape = name; },
      ("the stone model drawn, by its registered name (stone_model_names()), default '" + WeirSpec{}.shape + "'").c_str());
  const auto polygon = &WeirSpec::polygon;
  def_part_default(ws, "polygon_vertices_min", polygon, &PolygonSpec::vertices_min,
                   "fewest vertices of a polygon stone [-], [3, 16]");
  def_part_default(ws, "polygon_vertices_max", polygon, &PolygonSpec::vertices_max,
                   "most vertices of a polygon stone [-], [polygon_vertices_min, 16]");
  def_part_default(ws, "aspect_ratio", polygon, &PolygonSpec::aspect_ratio,
                   "length / thickness of a polygon stone's section [-], [1, 3]");
  def_part_default(ws, "radial_jitter", polygon, &PolygonSpec::radial_jitter,
                   "polygon vertex radii 1 +- jitter before the hull [-], [0, 0.5]");
  const auto clump = &WeirSpec::clump;
  def_part_field(ws, "clump_names", clump, &ClumpMix::names,
                 "library shapes clump stones draw with equal chances (shape 'clump'; quarried_stone_names())");
  def_part_default(ws, "clump_ratio_intermediate", clump, &ClumpMix::ratio_intermediate,
                   "clumps' intermediate / long axis p [-], in [clump_ratio_short, 1]");
  def_part_default(ws, "clump_ratio_short", clump, &ClumpMix::ratio_short,
                   "clumps' short / long axis q [-], in [0.55, 1]");
  py::class_<WeirPackingReport>(m, "WeirPackingReport", "What pack_weir produced.")
      .def_readonly("n_stones", &WeirPackingReport::n_stones,
           "stones in the weir, the fixed ones included")
      .def_readonly("n_fixed", &WeirPackingReport::n_fixed,
           "fixed bottom stones")
      .def_readonly("porosity", &WeirPackingReport::porosity,
           "porosity of the trapezoid [-]: 1 - (stone area inside) / area in the plane; for 3D stones that of "
           "the prism across the width, 1 - (stone volume inside) / (area B)")
      .def_readonly("stones_across", &WeirPackingReport::stones_across,
           "3D stones: the mean number of stones a line across the flume through the trapezoid crosses [-] "
           "(0 in the plane)")
      .def_readonly("max_speed", &WeirPackingReport::max_speed,
           "largest stone speed at the end [m/s]")
      .def_readonly("settle_time", &WeirPackingReport::settle_time,
           "simulated time of the settling phases [s]")
      .def_readonly("outline_error", &WeirPackingReport::outline_error,
           "weir_outline_error() of the result [m]")
      .def_readonly("wall_seconds", &WeirPackingReport::wall_seconds,
           "wall-clock time of the packing [s]")
      .def("__repr__", [](const WeirPackingReport& r) {
        return "WeirPackingReport(n_stones=" + std::to_string(r.n_stones) + ", n_fixed=" + std::to_string(r.n_fixed) +
               ", porosity=" + std::to_string(r.porosity) + ", stones_across=" + std::to_string(r.stones_across) +
               ", max_speed=" + std::to_string(r.max_speed) +
               ", outline_error=" + std::to_string(r.outline_error) + ")";
      });
  // the weir packer: one C++ packer, a WeirSpec in (its defaults written once, in weir_packing.h)
  auto pack = [](const WeirSpec& spec, const DEMParams& params) {
    WeirPackingReport report;
    std::unique_ptr<DEMSystem> sys;
    {
      py::gil_scoped_release release;
      sys = std::make_unique<DEMSystem>(pack_weir(spec, params, report));
    }
    return std::make_pair(std::move(sys), report);
  };
  m.def(
      "pack_weir",
      [pack](const WeirSpec& spec, const DEMParams& params) {
        auto [sys, report] = pack(spec, params);
        return std::make_tuple(std::move(sys), report);
      },
      "Packs the trapezoidal rubble mound weir `spec` with the contact law of `params`; returns (DEMSystem, "
      "WeirPackingReport).",
      py::arg("spec"), py::arg("params") = DEMParams());
  m.def(
      "random_polygons",
      [](const A& diameters, std::uint64_t seed, int vertices_min, int vertices_max, double aspect_ratio,
         double radial_jitter) {
        PolygonSpec spec;
        spec.vertices_min = vertices_min;
        spec.vertices_max = vertices_max;
        spec.aspect_ratio = aspect_ratio;
        spec.radial_jitter = radial_jitter;
        std::vector<double> vertex;
        std::vector<int> offset;
        random_polygon_set(seed, spec, flat_pos(diameters), vertex, offset);
        py::array_t<double> v({static_cast<py::ssize_t>(vertex.size() / 2), py::ssize_t{2}});
        if (!vertex.empty()) std::memcpy(v.mutable_data(), vertex.data(), vertex.size() * sizeof(double));
        return py::make_tuple(v, offset);
      },
      "Random convex polygon stones of the given nominal diameters [m] (equal-area discs) from one seed: "
      "(vertices (m, 2) body frame [m], offsets (n + 1)). See polygon.h.",
      py::arg("diameters"), py::arg("seed") = 0, py::arg("vertices_min") = 5, py::arg("vertices_max") = 8,
      py::arg("aspect_ratio") = 1.5, py::arg("radial_jitter") = 0.2);
  m.def("weir_porosity", &weir_porosity, py::arg("system"), py::arg("spec"), py::arg("h") = 0.002,
        "2D porosity [-] of the weir's trapezoid filled by the stones (discs or polygons), sampled on a grid of spacing "
        "h [m].");
  m.def("weir_outline_error", &weir_outline_error, py::arg("system"), py::arg("spec"),
        "Largest deviation [m] of the packing from the trapezoid: how far a stone reaches outside it, or how far a "
        "point of its slopes and crest lies from the nearest stone, whichever is larger.");
}

}  // namespace

// the dem module registers its classes and functions here
void bind_dem(py::module_& m) {
  bind_params(m);
  bind_system(m);
  bind_packing(m);
}

}  // namespace vofdem::bind
