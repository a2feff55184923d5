// A stone model: what the shape of the stones decides, behind one interface, registered by name.
//
// DEMSystem keeps what every stone shares (velocity-Verlet integration, the neighbour search, sleeping,
// removal, buoyancy and added mass, the energy account, the stage profile) and asks its model for the
// rest, never which model it holds:
//
//   mass properties      V_i, I_i, the nominal diameter and projected areas of the 3D stone it stands for
//   contacts             stone-stone and stone-wall forces and torques with their histories, and the
//                        stable step of those contacts
//   state                the model's part of the state and the checkpoint (its shapes, its histories)
//   footprint            which cells of the flow grid a stone covers and how much solid it puts in each
//                        (PorosityMapper), and the drag of the flow on it (its diameter and areas)
//   outline              the point queries of the packing diagnostics (distance, cover, reach)
//   packing              how the weir's packing generator draws and places its stones
//   dimensions           2: stones in the flume's plane (x, z and one angle); 3: stones that also move
//                        across the flume (DEMSystem's out-of-plane state: y, a quaternion, a 3D spin)
//
// A model is a class derived from StoneModel in a header/source pair of its own under stones/, and one
// line in the registry (stone_model.cpp: kBuiltinModels) or a call of register_stone_model() by a program
// that brings its own: the scene's `stones.shape` choices and the binding's names come from the registry.
// How to add one: docs/stone_models.md. As in LAMMPS's and LIGGGHTS's styles, the core loop holds a
// pointer to the interface and calls it once per stage (not per stone), so a model costs one indirect call
// per stage.
#pragma once

#include <array>
#include <cstddef>
#include <functional>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "vofdem/stones/wet_fraction.h"

namespace vofdem {

class DEMSystem;
struct DEMParams;
struct DEMState;
class PorosityMapper;
struct PorosityParams;
struct StoneFlowSample;
struct DragForce;
class StonePacking;
struct WeirSpec;
enum class DragLaw;

// the checkpoint's named flat arrays
using StateMap = std::map<std::string, std::vector<double>>;

// tangential springs of up to two contact points of a pair, by feature id (-1: empty): the history of
// the models whose contacts have several points (polygons' manifolds)
struct PointSprings {
  int id[2] = {-1, -1};
  double xi[2] = {0.0, 0.0};
  double spring(int feature) const { return id[0] == feature ? xi[0] : (id[1] == feature ? xi[1] : 0.0); }
  // the energy of the springs whose points `now` does not have [J] (kt [N/m]): dropped with them, dissipated
  double dropped_energy(const PointSprings& now, double kt) const {
    double e = 0.0;
    for (int k = 0; k < 2; ++k)
      if (id[k] >= 0 && now.id[0] != id[k] && now.id[1] != id[k]) e += 0.5 * kt * xi[k] * xi[k];
    return e;
  }
};

// a stone pair of the neighbour list (i < j) with its contact history, carried over the list's rebuilds
struct ContactPair {
  int i, j;
  double xi;            // tangential spring [m] (one-point contacts)
  double sqrt_m;        // sqrt of the pair's reduced mass [kg^0.5], set at each build
  double mr = 0.0;      // rolling spring moment M_r^k on i [N m] (rolling resistance only)
  double roll_c = 0.0;  // 2 R* sqrt(I_r) [kg^0.5 m^2]: C_r = eta_r sqrt(k_t) roll_c (rolling resistance only)
  double roll_r = 0.0;  // R* = r_i r_j / (r_i + r_j) [m] (rolling resistance only)
  PointSprings points{};  // several-point contacts: the springs of the points
};

// the constants of the contact law (dem_contact.h) in a force evaluation, the same for every contact:
// the Coulomb cap on (kDEMFriction), c_n / sqrt(m*) = 2 zeta sqrt(k_n) (0 with the dashpots off), k_t
// (0 without friction)
struct ContactLaw {
  bool friction;
  double damp, kt;
};

// what a contact loop adds to the energy account [J] and its count of touching contacts
struct ContactTally {
  double elastic = 0.0, dissipated = 0.0;
  int count = 0;
};

class StoneModel {
 public:
  virtual ~StoneModel() = default;
  // the registry's name of the model (the scene's `stones.shape`)
  virtual const char* name() const = 0;

  // ---- mass properties of stone i: those of the 3D stone the model stands for
  virtual double volume(const DEMSystem& s, int i) const = 0;                // V_i [m^3]
  virtual double inertia(const DEMSystem& s, int i, double mass) const = 0;  // I_i about the plane's normal [kg m^2]
  virtual double nominal_diameter(const DEMSystem& s, int i) const = 0;      // [m]
  virtual double projected_area(const DEMSystem& s, int i) const = 0;        // mean over directions [m^2]
  // seen along the direction (ux, uz) of the flume's plane [m^2] ((0, 0): the mean)
  virtual double projected_area(const DEMSystem& s, int i, double ux, double uz) const = 0;

  // ---- dimensions: 2, or 3 for stones with DEMSystem's out-of-plane state (stone_y, stone_quat,
  // stone_omega_3d; dem_system.h), whose principal moments of inertia [kg m^2] the model gives
  virtual int dimensions() const { return 2; }
  // the share of the stone below a water level as a function of s = (level - z) / r (wet_fraction.h): the
  // disc's area share for the plane's models, a cap's volume for spheres
  virtual WetLaw wet_law() const { return kDiscWetLaw; }
  // the radius [m] that scales s in the wet law for stone i: stone_radius (the stone's own, or its bounding
  // radius); a clump's that of the volume-equivalent sphere
  virtual double wet_radius(const DEMSystem& s, int i) const;
  virtual std::array<double, 3> principal_inertia(const DEMSystem& s, int i, double mass) const {
    const double inertia_i = inertia(s, i, mass);
    return {inertia_i, inertia_i, inertia_i};
  }
  // true if every stone's three principal moments are equal (spheres): DEMSystem then turns it by one exact
  // rotation about its spin (quaternion.h, spherical_rotation) instead of the principal axes' splitting
  virtual bool spherical_inertia() const { return false; }

  // ---- contacts: the stable step [s] of the stones' contacts (prepared system), and the force loops,
  // which add forces to stone_force and torques to stone_torque and keep their histories
  virtual double stable_dt(const DEMSystem& s) const = 0;
  virtual ContactTally contact_forces(DEMSystem& s, double dt) = 0;
  virtual ContactTally wall_forces(DEMSystem& s, double dt) = 0;

  // ---- lifecycle: the model's own limits on the parameters (throws std::invalid_argument); its
  // per-stone and per-wall storage after a resize or a new wall count; before the steps of a call
  // (shapes edited through the views); a stone that left the domain
  virtual void check_params(const DEMParams&) const {}
  virtual void resize(DEMSystem&) {}
  virtual void prepare(DEMSystem&) {}
  virtual void remove_stone(DEMSystem&, int) {}
  // a model that keeps its own history per listed pair (own_pair_history()) hears of each rebuild of the
  // neighbour list: new pair k was pair from[k] of the former list (-1: a new pair)
  virtual bool own_pair_history() const { return false; }
  virtual void pairs_rebuilt(DEMSystem&, const std::vector<int>& /*from*/) {}

  // ---- state: the model's part (typed, reused without allocation once sized), checked before anything
  // is written; and in the checkpoint's map of named arrays. checkpoint_key(): a key only this model's
  // checkpoints hold (empty: the model keeps nothing of its own), by which a checkpoint names its model
  virtual void export_state(const DEMSystem&, DEMState&) const {}
  virtual void check_state(const DEMSystem&, const DEMState&) const {}
  virtual void import_state(DEMSystem&, const DEMState&) {}
  virtual const char* checkpoint_key() const { return ""; }
  // the model's part of a typed state into the map (its arrays moved), and back for n stones and nwalls
  // walls (checked for their sizes: std::invalid_argument)
  virtual void state_to_map(DEMState&, StateMap&) const {}
  virtual void state_from_map(const StateMap&, std::size_t /*n*/, std::size_t /*nwalls*/, DEMState&) const {}

  // ---- the flow's view of the stones (the coupling): whether the paper's lookup table can map them;
  // their footprint (positions x, z [m]: the coupler's copies) onto the mapper's cells; the drag of the
  // flow sample f on stone i moving at (up, wp) [m/s], with its slope in the stone's velocity if asked
  // (slope != nullptr); the drag's relaxation bound on the exchange step [s] (drag_relaxation times
  // (M + M') / slope, slope that of eq. 18 at the relative speed vrel [m/s] and wet fraction w)
  virtual bool lookup_footprint() const { return false; }
  virtual void map_footprint(const DEMSystem& s, PorosityMapper& m, const double* x, const double* z) const = 0;
  virtual DragForce drag(const DEMSystem& s, int i, const StoneFlowSample& f, double up, double wp, double rho,
                         double nu, DragLaw law, double* slope) const = 0;
  virtual double drag_relaxation_dt(const DEMSystem& s, int i, double relaxation, double mass, double vrel, double w,
                                    double rho, double nu) const = 0;

  // ---- outline, for the packing diagnostics: distance [m] from (x, z) to stone i (0 inside); whether it
  // covers (x, z); the largest value over its outline of f, a convex 1-Lipschitz function (a signed
  // distance to a convex region)
  virtual double gap(const DEMSystem& s, int i, double x, double z) const = 0;
  virtual bool covers(const DEMSystem& s, int i, double x, double z) const = 0;
  virtual double outline_max(const DEMSystem& s, int i, const std::function<double(double, double)>& f) const = 0;

  // ---- the weir's packing generator (stone_packing.h): how this model's stones are drawn and placed;
  // nullptr: the generator cannot pack it
  virtual std::unique_ptr<StonePacking> packing(const WeirSpec&) const;

 protected:
  // DEMSystem's working arrays and constants for the models' loops (DEMSystem befriends StoneModel alone)
  static std::vector<ContactPair>& pairs(DEMSystem& s);
  static const std::vector<double>& inv_mass(const DEMSystem& s);
  static const std::vector<double>& mass_eff(const DEMSystem& s);
  // 1 / (M + M') at the step's start (the contacts' dashpot masses; 0: fixed or inactive)
  static const std::vector<double>& contact_inv_mass(const DEMSystem& s);
  // principal moments of inertia of 3D stones, 3n [kg m^2] (infinite: fixed, inactive or not turning)
  static const std::vector<double>& inertia_3d(const DEMSystem& s);
  static std::vector<double>& wall_spring(DEMSystem& s);          // tangential spring per (stone, wall) [m]
  static std::vector<double>& wall_rolling_spring(DEMSystem& s);  // rolling moment per (stone, wall) [N m]
  static std::vector<PointSprings>& wall_point_springs(DEMSystem& s);  // points' springs per (stone, wall)
  static ContactLaw contact_law(const DEMSystem& s);
  // the stones near wall w: wall_candidates(s)[start[w] .. start[w + 1]) (ascending)
  struct WallCandidates {
    const int* start;
    const int* index;
  };
  static WallCandidates wall_candidates(const DEMSystem& s);
  // rolling resistance (rolling_resistance.h): whether a contact kind has it, its moments on one contact
  // (energies added to the tally), and what it adds to the spin's omega^2 [1/s^2]
  static bool rolling_stones(const DEMSystem& s);
  static bool rolling_walls(const DEMSystem& s);
  static void rolling_contact(DEMSystem& s, ContactPair& c, double fn, double dt, ContactTally& t);
  static void rolling_wall(DEMSystem& s, int i, double& mr, double fn, double dt, ContactTally& t);
  static double rolling_spin_stiffness(const DEMSystem& s, double m_min);
  // the shapes changed: the neighbour list, the derived masses and the accelerations are made again
  static void shapes_changed(DEMSystem& s);
};

// ---- the registry

using StoneModelFactory = std::function<std::unique_ptr<StoneModel>()>;
// adds a model under `name` (a program's own models; the built-in ones are listed in stone_model.cpp);
// throws std::invalid_argument for an empty name or one taken
void register_stone_model(const std::string& name, StoneModelFactory make);
// a new model of that name; throws std::invalid_argument naming the registered ones
std::unique_ptr<StoneModel> make_stone_model(const std::string& name);
// the registered names, the built-in ones first ("disc", "polygon")
std::vector<std::string> stone_model_names();
// the model whose checkpoint_key() the checkpoint holds ("disc" if none)
std::string stone_model_of_checkpoint(const std::function<bool(const std::string&)>& has_key);

}  // namespace vofdem
