// Sphere stones: 3D spheres across the flume of width B (DEMParams::width), between two side walls y = 0
// and y = B, under the 2D vertical flow. The sphere of diameter d = 2 r is the stone the paper's discs
// stand for (Maeno & Tomita 2008, sec. 2.2), so its mass properties are the disc model's:
//
//   V = pi d^3 / 6,   I = f M r^2 about every axis (f = DEMParams::inertia_factor, 0.4 a sphere),
//   A_p = pi r^2
//
// but it moves in 3D: DEMSystem's out-of-plane state (y, the quaternion, the 3D spin; dem_system.h).
// Contacts: the linear spring-dashpot law of sphere_contact.h with the 3D tangential spring and the
// type-C rolling resistance (rolling_friction_stone, rolling_friction_wall with kDEMRollingResistance),
// with the same stiffness, damping and friction as the plane's models; the walls of DEMParams (the bed,
// the end walls) as planes across the flume, and the two side walls with side_wall_friction (the
// paper's glass: 0.176). The neighbour list is the plane's (pairs whose projections on the x-z plane are
// within reach): it holds every pair that can touch, whatever their y. Stable step: the disc model's (the
// same normal and tangential-rotational modes). Footprint on the 2D flow: each cell's slab dx x dz x B
// holds the sphere's exact volume (porosity_map.h, map_spheres), and the porosity is the true void
// fraction (n_exp = 0 required: no packing porosity inside the stones); the fluid's forces act in x and z
// (the width-averaged flow has no velocity across the flume), the drag on the sphere's pi r^2; at the free
// surface the wet fraction is the cap's volume, (1 + s)^2 (2 - s) / 4 (wet_fraction.h). The weir's packing
// generator packs them in 3D (weir_packing_3d.h).
//
// References: Cundall, P. A. & Strack, O. D. L. (1979), Geotechnique 29(1), 47-65. Ai, J., Chen, J.-F.,
// Rotter, J. M. & Ooi, J. Y. (2011), Powder Technology 206, 269-282.
#pragma once

#include <vector>

#include "vofdem/stones/disc_model.h"
#include "vofdem/stones/sphere_contact.h"

namespace vofdem {

class SphereModel final : public DiscModel {
 public:
  const char* name() const override { return "sphere"; }
  int dimensions() const override { return 3; }
  WetLaw wet_law() const override { return kSphereWetLaw; }
  bool spherical_inertia() const override { return true; }
  void check_params(const DEMParams& p) const override;
  void prepare(DEMSystem& s) override;
  ContactTally contact_forces(DEMSystem& s, double dt) override;
  ContactTally wall_forces(DEMSystem& s, double dt) override;
  bool own_pair_history() const override { return true; }
  void pairs_rebuilt(DEMSystem& s, const std::vector<int>& from) override;

  void export_state(const DEMSystem& s, DEMState& t) const override;
  void check_state(const DEMSystem& s, const DEMState& t) const override;
  void import_state(DEMSystem& s, const DEMState& t) override;
  const char* checkpoint_key() const override { return "sphere_wall_spring"; }
  void state_to_map(DEMState& t, StateMap& m) const override;
  void state_from_map(const StateMap& m, std::size_t n, std::size_t nwalls, DEMState& t) const override;

  bool lookup_footprint() const override { return false; }
  void map_footprint(const DEMSystem& s, PorosityMapper& m, const double* x, const double* z) const override;
  std::unique_ptr<StonePacking> packing(const WeirSpec& spec) const override;

  // the planes the stones touch: DEMParams::walls across the flume, then y = 0 and y = width
  static std::vector<ContactPlane> planes(const DEMParams& p);
  // 3D stones' footprint is their volume: refuses a mapper with a packing porosity (n_exp != 0), naming
  // the key and stones.shape = shape
  static void require_true_void_fraction(const PorosityMapper& m, const char* shape);

 private:
  SphereOfBody body(const DEMSystem& s, int i, double mass) const;
  void update_pair_constants(DEMSystem& s, const SphereContactLaw& law, double zeta);
  std::vector<SphereContactHistory> pair_history_;  // one per listed pair, in the list's order
  // per listed pair: the law's parts from the masses, radii and inertia (sphere_contact.h), kept from
  // the call's start or the last neighbour build, whichever is later
  std::vector<SpherePairConstants> pair_constants_;
  bool pair_constants_current_ = false;
  std::vector<SphereContactHistory> wall_history_;  // per (stone, plane of planes())
  std::vector<ContactPlane> planes_;                // planes() of the parameters in use (prepare)
  // contact_forces' passes over the listed pairs whose spheres overlap: their geometry, their loads (the
  // law), then the loads added to the stones in the list's order. Short loops without a store into the
  // stones' arrays, so that the processor overlaps the square roots and divisions of many contacts; the
  // loads and their sums are those of one pass, bit for bit.
  struct Overlap {
    std::size_t k = 0;       // the pair's place in the list
    bool touching = false;   // false: the centres' distance, rounded, leaves no overlap
    SphereContactGeometry g;
    Eigen::Vector3d arm_i, arm_j;
  };
  struct PairLoads {
    Eigen::Vector3d force_i, torque_i, torque_j;
    double energy_spring, power_damp, energy_slip;
  };
  std::vector<Overlap> overlap_;
  std::vector<PairLoads> loads_;
};

}  // namespace vofdem
