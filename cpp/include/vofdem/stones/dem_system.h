// DEM of the stones: discs in the vertical x-z plane, Maeno & Tomita (2008) sec. 2.2, eqs. (8)-(10):
//
//   (M_i + M'_i) x_i''  = sum_j {-f_n cos a_ij + f_s sin a_ij}_j + F_x                           (8)
//   (M_i + M'_i) z_i''  = sum_j {-f_n sin a_ij + f_s cos a_ij}_j - (M_i - rho_w V_i) g + F_z        (9)
//   I_i theta_i''      = (d_i / 2) sum_j {f_s}_j                                                (10)
//
// with M_i = rho_s V_i, V_i = pi d_i^3 / 6 (a sphere of the disc's diameter, the paper's V_i; its
// projected area A_pi = pi d_i^2 / 4), added mass M'_i = rho_w C_M V_i, and I_i = inertia_factor M_i
// (d_i/2)^2 (0.4: a sphere, the default; 0.5: a disc). The wet fraction w_i in [0, 1] of each stone
// scales buoyancy and added mass: (M_i - rho_w V_i w_i) g and rho_w C_M V_i w_i. When w_i grows, the
// water taken on as added mass starts at rest: (M_i + M'_i) v_i is kept (the stone slows as it enters
// the water; as it leaves, v_i is kept and the water left behind takes its momentum with it), so a
// change of w_i never adds kinetic energy. Contacts: dem_contact.h; rolling resistance (a moment added
// to eq. 10, effect kDEMRollingResistance): rolling_resistance.h.
// F_x, F_z: stone_force_ext, set by the coupler (the fluid's pressure-gradient force, and the drag when it
// is held), plus a linear drag c_i (U_i - v_i) in the stone's own velocity (stone_drag_coef c_i, stone_drag_vel
// U_i: the coupler's drag linearised at the last exchange), evaluated at every substep.
//
// Stone shape: a stone model (stone_model.h), registered by name: discs (disc_model.h, the default),
// convex polygons (polygon_model.h, set_polygons()) or 3D spheres across the flume (sphere_model.h). The model gives V_i, I_i and the areas, the contact
// forces with their histories and their stable step; DEMSystem never asks which model it holds. For
// polygons stone_radius is the bounding radius (neighbour search), stone_angle the orientation of the
// body-frame vertices poly_vertex.
// Integration: velocity Verlet (kick-drift-kick; forces from the half-step velocity), one force
// evaluation per step. The linear drag is integrated exactly in each half kick (exponential integrator):
// a half kick of h with the total acceleration a (drag included) adds h a phi(h k), k = c / (M + M'),
// phi(x) = (1 - e^-x) / x, which is the exact solution of dv/dt = a_other + k (U - v) over h for a_other
// held; so the drag never overshoots U, at any step and any c (phi = 1 without drag: plain Verlet). A
// wet fraction that follows a water level changes M' within a step: k follows it at once (the momentum
// kept as above), so the kicks after the change integrate the drag with the mass the stone has.
// Walls are half-planes (the flume bed, its end walls); fixed stones are discs that never move.
// 3D stones (a model of dimensions() == 3) keep the plane's arrays for x and z (what the 2D flow sees and
// acts on) and add the out-of-plane state: y across the flume of width `width` between two side walls,
// its velocity and force, and the rotation as a unit quaternion with a world angular velocity, advanced
// by the same kick-drift-kick with rotation_step's splitting (quaternion.h; one exact turn about the spin
// for spheres, whose moments are equal) in place of the angle; their
// in-plane angle arrays stay zero. Gravity and the flow's forces lie in the plane; the linear drag pulls
// v_y towards 0 (the width-averaged flow has no velocity across the flume).
// Neighbours: a Verlet list with a skin built from a cell grid (O(N)), its pairs kept sorted by (i, j) so
// that contact histories and force sums are evaluated in one fixed order: runs are bit-for-bit
// reproducible, and export_state()/import_state() restart them bit-for-bit. 3D stones are binned in x, y
// and z (unless plane_neighbour_list); the pairs that touch are the same, so the forces are the same bits.
//
// References: Maeno, S. & Tomita, A. (2008), ICHE 2008, Nagoya. Gotoh, H. & Sakai, T. (1997), J. Waterway
// Port Coastal Ocean Eng. 123(6), 329-336. Cundall, P. A. & Strack, O. D. L. (1979), Geotechnique 29, 47-65.
#pragma once

#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "vofdem/common/medium.h"
#include "vofdem/common/profile.h"
#include "vofdem/stones/stone_model.h"

namespace vofdem {

// effect flags of DEMParams::flags; each stage checks its bit first
enum DEMFlag : unsigned {
  kDEMGravity = 1u << 0,        // gravity (and buoyancy if kDEMBuoyancy)
  kDEMRotation = 1u << 1,       // eq. (10): stones spin; off: omega stays 0
  kDEMFriction = 1u << 2,       // Coulomb cap of the tangential spring; off: tangential force 0
  kDEMAddedMass = 1u << 3,      // M' = rho_w C_M V w in eqs. (8)-(9)
  kDEMBuoyancy = 1u << 4,       // rho_w V w g in eq. (9)
  kDEMSleeping = 1u << 5,       // stones at rest under small forces are not integrated (Box2D-like)
  kDEMDamping = 1u << 6,        // contact dashpots
  kDEMExternalForce = 1u << 7,  // stone_force_ext (fluid forces from the coupler)
  kDEMRemoval = 1u << 8,        // stones leaving the domain box are deactivated and counted
  kDEMRollingResistance = 1u << 9,  // rolling moment of rolling_resistance.h (costs nothing while mu_r = 0)
  kDEMAllEffects = (1u << 10) - 1u - (1u << 5),  // everything but sleeping
};

// a half-plane wall: the solid lies on the side opposite to `normal`
struct DEMWall {
  std::array<double, 2> point{0.0, 0.0};   // a point of the wall line (x, z) [m]
  std::array<double, 2> normal{0.0, 1.0};  // unit normal pointing into the flow (normalised on use)
  double friction = 0.176;                 // stone-wall Coulomb coefficient [-] (paper: 0.176)
};

// constant parameters of a DEM run (SI units)
struct DEMParams {
  Medium medium;          // water and gravity (medium.h); a Coupler hands the flow's to the stones
  bool submerged = false;  // the stones lie in the medium's water (buoyancy, added mass); false: dry
  // rho_w of buoyancy and added mass [kg/m^3]: the medium's water when submerged, else 0
  double water_density() const { return submerged ? medium.rho_water : 0.0; }
  double added_mass_coefficient = 1.0;        // C_M [-]; paper's run 1.0 (its text 0.5)
  double dt = 1e-4;                           // DEM step [s]; advance() substeps never exceed it (paper 1e-4)
  double stiffness_normal = 0.0;              // k_n [N/m]; 0 = automatic (Gotoh & Sakai): see dem_contact.h
  double contact_steps = 20.0;                // automatic k_n: steps per undamped contact of mean stones [-]
  double stiffness_ratio = 2.0 / 7.0;         // k_t / k_n [-]; 2/7 usual
  double restitution = 0.0;                   // normal restitution e [-] in [0, 1]; 0 = critical damping
  double tangential_damping_factor = 0.5;     // c_t / c_n [-]; 0.5 usual (LAMMPS default)
  double friction_stone = 0.577;              // stone-stone Coulomb coefficient [-] (paper 0.577)
  double inertia_factor = 0.4;                // I = factor M r^2 [-]; 0.4 sphere, 0.5 disc
  // rolling resistance (rolling_resistance.h; only with kDEMRollingResistance): M_r <= mu_r R* f_n
  double rolling_friction_stone = 0.0;        // mu_r stone-stone [-], >= 0; 0 = none (discs only: polygons refuse > 0)
  double rolling_friction_wall = 0.0;         // mu_r stone-wall [-], >= 0; 0 = none (discs only)
  double rolling_damping = 0.3;               // eta_r = C_r / (2 sqrt(I_r k_r)) [-] in [0, 1]; off at full mobilisation
  std::array<double, 2> domain_min{-1e30, -1e30};  // removal box, lower corner (x, z) [m]
  std::array<double, 2> domain_max{1e30, 1e30};    // removal box, upper corner (x, z) [m]
  double neighbour_skin = 0.0;                // Verlet-list skin [m]; 0 = 0.1 x the largest diameter
  double sleep_velocity = 1e-3;               // a stone may sleep below this speed (and omega r) [m/s]
  double sleep_time = 0.2;                    // ... held for this long [s]
  double wake_acceleration = 0.2;             // a sleeping stone wakes when its net force gives more [m/s^2]
  std::vector<DEMWall> walls;                 // half-plane walls (bed, end walls)
  // 3D stones only (models of dimensions() == 3): the flume's width between its side walls y = 0 and
  // y = width, and the stone-side wall friction (the paper's glass: 0.176)
  double width = 0.0;                         // [m], > 0 for 3D stones (then larger than every stone)
  double side_wall_friction = 0.176;          // Coulomb coefficient stone-side wall [-], >= 0
  // true: 3D stones' neighbours by their x-z projections whatever their y (the plane's list: more pairs,
  // the same forces); false: cells in x, y and z
  bool plane_neighbour_list = false;
  unsigned flags = kDEMAllEffects;            // DEMFlag bits

  // adds the flume: bed z = z_bed and end walls x = x_min, x_max [m], all with stone-wall friction mu
  void add_flume(double x_min, double x_max, double z_bed, double mu = 0.176);
  // throws std::invalid_argument naming the first bad parameter (the shape's own limits: DEMSystem)
  void validate() const;
};

// named stages of a DEM step (StageProfile indices). `integrate` is one pass over the stones: kick, drift,
// body forces, escape and neighbour-list checks; `removal` and `neighbours` run only when needed;
// `body_forces` is timed apart only for the initial accelerations; `checks` is the second kick with
// its finiteness check.
enum DEMStage : int { kStageIntegrate = 0, kStageRemoval, kStageNeighbours, kStageBodyForces, kStageContacts,
                      kStageWalls, kStageSleep, kStageChecks, kDEMStageCount };

// energy bookkeeping [J]: kinetic + potential + elastic - work_external + dissipated is conserved
struct DEMEnergy {
  double kinetic = 0.0;        // sum 1/2 (M + M') v^2 + 1/2 I omega^2 [J]
  double potential = 0.0;      // sum -(M - rho_w V w) g . x [J] (zero at the origin)
  double elastic = 0.0;        // energy in the contact springs (rolling ones too) at the last evaluation [J]
  double dissipated = 0.0;     // dashpots + Coulomb and rolling slip + sleeping, accumulated [J]
  double work_external = 0.0;  // work of stone_force_ext, accumulated [J]
  double total() const { return kinetic + potential + elastic + dissipated - work_external; }
};

// the whole state of a DEMSystem as one typed value (export_state / import_state): what a run needs to
// continue bit-for-bit. Copying it is a copy of arrays (a reused DEMState allocates nothing once sized)
struct DEMState {
  std::vector<double> stone_pos, stone_vel, stone_angle, stone_omega, stone_radius, stone_density;
  std::vector<std::uint8_t> stone_fixed, stone_active, stone_asleep;
  std::vector<double> stone_force_ext, stone_drag_coef, stone_drag_vel, stone_wet, stone_water_level, stone_force,
      stone_torque, stone_acc, stone_alpha, stone_sleep_timer;
  // the contact histories that are not zero, sorted by (i, j); the rest is rebuilt by the neighbour search
  std::vector<int> contact_i, contact_j;
  std::vector<double> contact_xi, contact_mr;  // tangential spring [m], rolling spring moment [N m]
  std::vector<double> wall_xi, wall_mr;        // per (stone, wall)
  // the stone model (stone_model.h) and its part: polygon stones' shapes and manifold points' springs
  std::string model = "disc";
  std::vector<double> poly_vertex;
  std::vector<int> poly_offset, poly_contact_i, poly_contact_j, poly_contact_id, poly_wall_id;
  std::vector<double> poly_contact_xi, poly_wall_xi;
  // the out-of-plane state of 3D stones (empty for the plane's models) and the sphere model's histories:
  // per listed pair (i, j) and per (stone, wall) (the walls, then the side walls y = 0 and y = width), the
  // tangential spring and the rolling spring moment (x, y, z each)
  std::vector<double> stone_y, stone_vel_y, stone_force_y, stone_acc_y, stone_quat, stone_omega_3d,
      stone_torque_3d;
  std::vector<int> sphere_contact_i, sphere_contact_j;
  std::vector<double> sphere_contact_spring, sphere_contact_rolling, sphere_wall_spring, sphere_wall_rolling;
  // clump stones (clump_model.h): spheres (x, y, z, r) in the principal frames, offsets (n + 1), the
  // union's volume and principal moments per unit density (4 per stone); per touching sub-sphere pair
  // (i, j, a, b) and per (sub-sphere, plane) the tangential spring and the rolling spring moment
  std::vector<double> clump_sphere, clump_property;
  std::vector<int> clump_offset, clump_contact;
  std::vector<double> clump_contact_spring, clump_contact_rolling, clump_wall_spring, clump_wall_rolling;
  double time = 0.0;  // [s]
  long long steps = 0;
  int removed = 0, ncontact = 0, nwall_contact = 0;
  double dissipated = 0.0, work_external = 0.0, elastic = 0.0;  // energy accumulators [J]
  bool forces_valid = false;
  // empties the stone model's part (a model's export_state fills what it holds)
  void clear_model_part();
};

// a DEMState as the checkpoint's named flat arrays, and back (nwalls: the system's wall count; entries
// added since are optional on the way back, with what older runs had)
std::map<std::string, std::vector<double>> dem_state_to_map(DEMState s);
DEMState dem_state_from_map(const std::map<std::string, std::vector<double>>& s, std::size_t nwalls);

class DEMSystem {
 public:
  // n stones, all at the origin with zero radius and density: fill the arrays before stepping
  DEMSystem(const DEMParams& params, int n);
  // stones at pos (x, z pairs) [m] with radius [m], density [kg/m^3], fixed flags (empty: none fixed)
  DEMSystem(const DEMParams& params, const std::vector<double>& pos, const std::vector<double>& radius,
            const std::vector<double>& density, const std::vector<std::uint8_t>& fixed = {});

  // resizes every per-stone array to n stones (new ones zeroed); invalidates views and histories
  void resize(int n);

  int n() const { return n_; }
  const DEMParams& params() const { return params_; }
  // replaces the parameters (walls, flags, stiffness...) after checking them (a refused set changes
  // nothing); the derived constants follow on the next step
  void set_params(const DEMParams& p);

  // holds every stone in place (true) or lets them go (false). A held system's steps only advance its
  // time: no stone moves, and the contact pairs with their tangential and rolling springs stay as they
  // were, so that stones held while the flow spins up are released with the friction their packing
  // built (fixing them instead would drop the pairs of two fixed stones, and their springs). Holding
  // stops every stone; letting go recomputes the accelerations on the next step. Not in the state
  // (export_state): the caller that holds records it (the run's checkpoint does).
  void set_held(bool held);
  bool held() const { return held_; }

  // the contact's stable step [s]: 1/10 of the shortest undamped contact duration pi / omega_max
  // (normal and tangential-rotational modes of the lightest stone, the latter with the rolling spring),
  // and no more than the explicit dashpots allow in a packing (kPackedContacts contacts per stone; binds
  // for restitution below ~0.12)
  double stable_dt();
  // contacts per stone assumed by stable_dt() for the highest mode of a packing [-]
  static constexpr double kPackedContacts = 5.0;
  // one DEM step of dt [s] (0 < dt <= stable_dt(); refused otherwise). Each call first copies the
  // state (export_state) so that a failure can restore it: call advance() with long durations.
  void step(double dt);
  // advances by duration [s] in equal substeps no larger than params().dt
  void advance(double duration);

  // sets the wet fraction w [-] in [0, 1] of stone i: buoyancy and added mass follow at once, and when
  // w grows the stone's velocity drops so that (M + M') v is kept (the water taken on starts at rest)
  void set_wet_fraction(int i, double w);

  // contact constants in use (after the automatic choice) [N/m]
  double stiffness_normal() const { return kn_; }
  double stiffness_tangential() const { return kt_; }
  // damping ratio zeta [-] from the restitution coefficient
  double damping_ratio() const { return zeta_; }

  double time() const { return time_; }
  long long steps() const { return steps_; }
  int removed_count() const { return removed_; }   // stones deactivated by leaving the domain box
  int contact_count() const { return ncontact_; }  // stone-stone contacts at the last force evaluation
  int wall_contact_count() const { return nwall_contact_; }
  int neighbour_builds() const { return nbuilds_; }
  DEMEnergy energy() const;
  // the largest speed of a free, active stone [m/s]: its centre's, or its spin times its radius (3D stones:
  // the velocity across the flume and the spin about every axis included); 0 without one
  double max_speed() const;

  // ---- the stone model (stone_model.h): the shape of every stone ----
  const StoneModel& model() const { return *model_; }
  // makes every stone of the registered model `name` ("disc", "polygon", or a program's own): its shape
  // arrays and contact histories are made anew (a model with shapes needs them set: set_polygons()).
  // Throws std::invalid_argument for an unknown name or parameters the model refuses (nothing changed)
  void set_model(const std::string& name);
  void set_model(std::unique_ptr<StoneModel> model);
  // makes every stone a convex polygon (polygon_model.h): body-frame vertices (x, z pairs,
  // counter-clockwise, centroid at the origin) [m], stone i owning vertices offset[i] .. offset[i+1]-1
  // (3 to 16 each); sets stone_radius to each bounding radius. Throws std::invalid_argument for a bad
  // polygon (naming the stone).
  void set_polygons(const std::vector<double>& vertex, const std::vector<int>& offset);

  // derived per-stone properties of the 3D stone the model stands for (read-only for users)
  double mass(int i) const { return stone_density[i] * model_->volume(*this, i); }  // M_i [kg]
  double volume(int i) const { return model_->volume(*this, i); }                    // V_i [m^3]
  // A_pi, the mean over directions [m^2]: pi d^2 / 4 for a disc; r_A P / 2 for a polygon
  double projected_area(int i) const { return model_->projected_area(*this, i); }
  // nominal diameter [m]: 2 r for a disc, the equal-area disc's diameter for a polygon
  double nominal_diameter(int i) const { return model_->nominal_diameter(*this, i); }
  double wet_radius(int i) const { return model_->wet_radius(*this, i); }  // the wet law's radius [m]
  // projected area [m^2] of the 3D stone seen along the direction (ux, uz) in the flume's plane: pi r^2
  // for a disc; (pi / 2) r_A W for a polygon, W its width across the direction (an ellipsoid's exact rule)
  double projected_area(int i, double ux, double uz) const { return model_->projected_area(*this, i, ux, uz); }
  // moment of inertia I_i [kg m^2] about the axis normal to the flume's plane
  double inertia(int i) const { return model_->inertia(*this, i, mass(i)); }
  // a wall's unit normal (wx, wz), out of the solid
  static std::array<double, 2> wall_unit_normal(const DEMWall& wall) {
    const double len = std::hypot(wall.normal[0], wall.normal[1]);
    return {wall.normal[0] / len, wall.normal[1] / len};
  }
  // stone-stone pairs currently in the neighbour list, as (i, j) with i < j (for tests)
  std::vector<std::array<int, 2>> neighbour_pairs() const;
  // pairs (i, j), i < j, that overlap now, by the O(N^2) reference search (for tests; for polygon stones,
  // pairs whose bounding discs overlap)
  std::vector<std::array<int, 2>> overlapping_pairs_reference() const;
  // pairs that overlap now, from the fast neighbour search
  std::vector<std::array<int, 2>> overlapping_pairs();

  // every piece of the state (stone arrays, accelerations, contact histories, counters, time) as
  // named flat arrays; import_state() restores it exactly (bit-for-bit restart)
  std::map<std::string, std::vector<double>> export_state() const;
  void import_state(const std::map<std::string, std::vector<double>>& state);
  // the same state typed: copied into s (its arrays reused: no allocation once sized); checked; and
  // restored (checked first: a refused state changes nothing), written into the arrays in place (the
  // numpy views stay valid) unless the state has another stone or polygon vertex count
  void export_state(DEMState& s) const;
  void check_state(const DEMState& s) const;
  void import_state(const DEMState& s);

  StageProfile& profile() { return profile_; }

  // ---- state arrays (flat; vectors stored as (x, z) pairs) ----
  std::vector<double> stone_pos;             // centre (x along the flume, z up) [m], 2n
  std::vector<double> stone_vel;             // velocity [m/s], 2n
  std::vector<double> stone_angle;           // rotation angle, counter-clockwise in (x, z) [rad], n
  std::vector<double> stone_omega;           // angular velocity [rad/s], n
  std::vector<double> stone_radius;          // radius d/2 [m], n (usual 0.024)
  std::vector<double> stone_density;         // rho_s [kg/m^3], n, > 0 (given; usual 2650)
  std::vector<std::uint8_t> stone_fixed;     // 1: never moves (bed layer), n
  std::vector<std::uint8_t> stone_active;    // 0: left the domain (kept, not integrated), n
  std::vector<double> stone_force_ext;       // external (fluid) force F_x, F_z [N], 2n; held until changed
  std::vector<double> stone_drag_coef;       // linear drag coefficient c >= 0 [N s/m], n; 0 (with kDEMExternalForce)
  std::vector<double> stone_drag_vel;        // velocity U the linear drag c (U - v) pulls towards [m/s], 2n
  std::vector<double> stone_wet;             // wet fraction in [0, 1], n; set to 1 at construction/resize
                                            // when submerged, else 0 (set_params keeps it)
  std::vector<double> stone_water_level;     // free-surface level at each stone [m], n; NaN (default): stone_wet
                                            // is held as set; else stone_wet follows the stone's height over the
                                            // substeps, its share below the level (the model's wet law)
  std::vector<double> stone_force;           // total force of the last evaluation [N], 2n (output)
  std::vector<double> stone_torque;          // total torque of the last evaluation [N m], n (output)
  std::vector<double> stone_acc;             // acceleration of the last evaluation [m/s^2], 2n
  std::vector<double> stone_alpha;           // angular acceleration of the last evaluation [rad/s^2], n
  std::vector<std::uint8_t> stone_asleep;    // 1: sleeping (not integrated), n
  std::vector<double> stone_sleep_timer;     // time spent below the sleep speed [s], n
  // shape arrays of the models that have them (empty for discs): polygons' body-frame vertices (x, z
  // pairs, CCW) [m] and the index of each stone's first vertex, n + 1 (set_polygons)
  std::vector<double> poly_vertex;
  std::vector<int> poly_offset;
  // ---- the out-of-plane state of 3D stones (sized n for a model of dimensions() == 3, else empty) ----
  std::vector<double> stone_y;          // centre across the flume, in [radius, width - radius] [m], n
  std::vector<double> stone_vel_y;      // velocity across the flume [m/s], n
  std::vector<double> stone_force_y;    // total force across the flume of the last evaluation [N], n
  std::vector<double> stone_acc_y;      // acceleration across the flume of the last evaluation [m/s^2], n
  std::vector<double> stone_quat;       // orientation: unit quaternion (w, x, y, z), body -> world, 4n
  std::vector<double> stone_omega_3d;   // angular velocity, world frame (x, y, z) [rad/s], 3n
  std::vector<double> stone_torque_3d;  // total torque about the centre, last evaluation (world) [N m], 3n
  bool three_d() const { return three_d_; }

 private:
  friend class StoneModel;  // the models' loops reach the arrays below through StoneModel's accessors
  using Pair = ContactPair;
  void prepare();
  // the shapes changed: the neighbour list, the derived masses and the accelerations are made again
  void shapes_changed();
  void check_params() const;
  void check_stones() const;
  void update_properties();
  void update_stone_properties(int i);
  double update_stone_masses(int i);
  void change_wet_fraction(int i, double w);
  void follow_water_level(int i);
  void build_neighbours();
  bool neighbours_stale() const;
  bool moved_half_skin(int i) const;
  bool neighbours_3d() const { return three_d_ && !params_.plane_neighbour_list; }
  void list_pairs_plane(int nact, double h, double xmin, double zmin, int ncx, int ncz);
  void list_pairs_3d(int nact, double h, double xmin, double zmin, int ncx, int ncz);
  void advance_checked(double dt, long long nsub);
  void substep(double dt, StageLaps& laps);
  void evaluate_forces(double dt, bool body, StageLaps& laps);
  bool moving(int i) const { return inv_mass_[i] > 0.0 && !stone_asleep[i]; }
  void build_wall_candidates();
  struct FirstHalf {
    bool stale = false, escaped = false;
  };
  FirstHalf integrate_first_half(double dt);
  void integrate_second_half(double dt);
  void update_kick_scale(double dt);
  double drag_kick_scale(int i, double dt) const;
  void remove_escaped();
  void body_forces(double dt);
  // the constants of the contact law in a force evaluation (ContactLaw, stone_model.h)
  ContactLaw contact_law() const {
    const bool friction = params_.flags & kDEMFriction;
    return {friction, (params_.flags & kDEMDamping) ? 2.0 * zeta_ * std::sqrt(kn_) : 0.0, friction ? kt_ : 0.0};
  }
  // rolling resistance (dem_rolling.cpp, law in rolling_resistance.h): whether a contact kind has it,
  // its term of stable_dt(), and the moments of one stone-stone or stone-wall contact (applied to
  // stone_torque; the energies returned)
  bool rolling_stones() const;
  bool rolling_walls() const;
  double rolling_spin_stiffness(double m_min) const;
  void update_rolling_inertia();
  void update_pair_rolling();  // Pair::roll_c of every listed pair
  struct RollingEnergy {
    double elastic = 0.0, dissipated = 0.0;
  };
  RollingEnergy rolling_contact(Pair& c, double fn, double dt);
  RollingEnergy rolling_wall(int i, double& mr, double fn, double dt);
  void sleep_update(double dt);
  // the out-of-plane state (dem_out_of_plane.cpp): sized and checked with the model, kicked, drifted,
  // loaded and accounted as the plane's part is
  void size_out_of_plane();
  void check_out_of_plane() const;
  void update_inertia_3d();
  void out_of_plane_body_forces(double dt);
  double out_of_plane_body_force(int i, bool ext);
  // the kick-drift across the flume, the body forces there and, with the 3D list (stale_3d), whether a
  // stone has moved half the skin since the list's build (moved_half_skin, in the same pass)
  bool out_of_plane_first_half(double dt, bool stale_3d);
  void out_of_plane_turn(int i, double h, double dt, bool spherical);
  void out_of_plane_second_half(double dt);
  void out_of_plane_accelerations();
  void out_of_plane_removed(int i);
  double out_of_plane_speed2(int i) const;
  void out_of_plane_sleep(int i);
  double out_of_plane_kinetic(int i, double mass_eff) const;
  double reduced_stiffness_mass() const;
  DEMParams params_;
  std::unique_ptr<StoneModel> model_;  // the stones' shape (stone_model.h)
  int n_ = 0;
  bool prepared_ = false;
  bool forces_valid_ = false;  // stone_acc holds the accelerations of the current state
  bool held_ = false;          // set_held
  double kn_ = 0.0, kt_ = 0.0, zeta_ = 0.0;
  double time_ = 0.0;
  long long steps_ = 0;
  int removed_ = 0;
  int ncontact_ = 0, nwall_contact_ = 0, nbuilds_ = 0;
  double elastic_ = 0.0, dissipated_ = 0.0, work_external_ = 0.0;

  // derived per stone (refreshed by prepare())
  std::vector<double> mass_eff_;     // M + M' [kg]
  std::vector<double> inv_mass_;     // 1 / (M + M'), 0 if fixed or inactive [1/kg]
  std::vector<double> inv_inertia_;  // 1 / I [1/(kg m^2)]
  std::vector<double> weight_;       // (M - rho_w V w) [kg]: multiplies g
  std::vector<double> kick_scale_;   // phi(h c / (M + M')) of the linear drag for the substep in use [-]
  double kick_dt_ = 0.0;             // the substep kick_scale_ was computed for [s]
  std::vector<double> inv_roll_inertia_;  // 1 / (I + (M + M') r^2), 0 if it does not turn [1/(kg m^2)]
  std::vector<double> wall_roll_c_;       // 2 r sqrt(I + (M + M') r^2) per stone: roll_c of its wall contacts
  double roll_eta_sqrt_kt_ = 0.0;         // eta_r sqrt(k_t) [N^0.5 m^-0.5], 0 with the dampers off
  std::vector<double> contact_inv_mass_;  // inv_mass_ at the step's start: the contacts' dashpot masses
  bool three_d_ = false;                  // the model's dimensions() == 3
  WetLaw wet_law_ = kDiscWetLaw;          // the model's wet fraction law (a plain pair: no virtual call per substep)
  std::vector<double> inertia_3d_;        // 3D stones' principal moments, 3n [kg m^2]; +inf: does not turn
  std::vector<int> carried_;              // the former index of each new pair (models with own pair histories)

  // neighbour list and contact histories
  std::vector<Pair> pairs_;
  std::vector<double> wall_xi_;      // tangential spring per (stone, wall) [m], n * nwall
  std::vector<double> wall_mr_;      // rolling spring moment per (stone, wall) [N m], n * nwall
  std::vector<PointSprings> wall_points_;  // several-point contacts' springs per (stone, wall), n * nwall
  std::vector<double> build_pos_;    // positions at the last neighbour build
  std::vector<double> build_y_;      // 3D stones' y at the last build (cells in x, y and z only)
  double skin_ = 0.0;
  bool rebuild_ = true;
  struct SortedStone {
    double x, z, r;
    int index;
    bool fixed;
    double y;  // 3D cells only
  };
  std::vector<int> cell_start_, cell_next_, cell_fill_;
  std::vector<SortedStone> sorted_;  // active stones in cell order (neighbour builds)
  std::vector<int> wall_cand_, wall_cand_start_;  // stones near each wall (ascending), per wall
  std::vector<Pair> new_pairs_;
  std::vector<double> cached_radius_;
  std::vector<std::uint8_t> cached_active_, cached_fixed_;

  DEMState backup_;  // the state at the start of advance(), restored on a failure

  StageProfile profile_;
};

}  // namespace vofdem
