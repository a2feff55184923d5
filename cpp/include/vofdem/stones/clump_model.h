// Clump stones: rigid 3D stones of 1 to 8 overlapping spheres (clump.h) across the flume of width B
// (DEMParams::width), between the side walls y = 0 and y = B, in DEMSystem's out-of-plane state.
//
// Mass properties, from the union of the spheres (each overlap counted once; clump.h):
//
//   M = rho_s V_union,   J_k = rho_s (tr S - S)_k (principal moments, ascending),
//   d_eq = (6 V_union / pi)^(1/3) (nominal diameter),   A_p = pi d_eq^2 / 4
//
// Each stone's spheres are kept in its principal frame (centroid at the origin), so stone_pos / stone_y
// hold the centre of mass and stone_quat turns the principal frame into the world; stone_radius holds the
// bounding radius max(|c_k| + r_k), which the neighbour search and the wall candidates read.
//
// Contacts: every sub-sphere pair (a of i, b of j) of a listed stone pair whose spheres overlap, through
// the sphere_contact.h kernel at the contact point of the two rigid bodies (lever arms from each stone's
// centre of mass), each with its own tangential-spring and rolling history (several contacts per stone
// pair); and each sub-sphere against each plane (the walls of DEMParams across the flume, the side walls
// with side_wall_friction) with its history. Rolling resistance, where it is on: per sub-sphere contact
// with the sub-spheres' radii (R* = r_a r_b / (r_a + r_b)) and the stone's smallest principal moment for
// the damper's I_r; Yade's and LAMMPS's clumps have none, and with the rolling friction 0 (the default)
// neither have these.
//
// Stable step: the highest mode of one contact, bounded over every contact point of every sub-sphere.
// A contact at rho = c + r n from the centre of mass (sub-sphere centre c, radius r, normal n) has the
// stiffness K = k_n n n^T + k_t (1 - n n^T) on the point's velocity, whose inverse mass is
// W = 1/M + [rho]x^T J^-1 [rho]x, so omega^2 = lambda_max(K^1/2 W K^1/2). As rho x n = c x n, with
//   a_n^2 = lambda_max([c]x^T J^-1 [c]x)   and   a_t = a_n + r / sqrt(J_1)
// (the largest J^-1-norms of c x u and of c x u + r n x u over unit u), the triangle inequality gives for
// a unit x = x_n n + x_t t:  x^T K^1/2 W K^1/2 x <= (k_n x_n^2 + k_t x_t^2) / M + (sqrt(k_n) |x_n| a_n +
// sqrt(k_t) |x_t| a_t)^2, so omega^2 is at most the largest eigenvalue of
//   [ k_n (1/M + a_n^2)             sqrt(k_n k_t) a_n a_t ]
//   [ sqrt(k_n k_t) a_n a_t          k_t (1/M + a_t^2)    ]    per stone, twice that for a pair of them,
// plus the rolling spring's mode; the disc model's dashpot bound on top. A sub-sphere has no mass of its
// own: every contact loads the whole rigid body. One centred sphere (c = 0) has the sphere's modes
// exactly. Measured on beds of 300 clumps of 4.3-5.3 cm in a 0.2 m flume at the Maeno scenes' stiffness
// under critical damping, stepped beyond this bound: box_8 clumps settled at 1.1 times it and were kept
// moving at 1.25; the default mix, still settling, gained energy at 1.9 times it, not at 1.4. The runs
// take 0.9 of it (calibration_3d.ClumpMix.step_margin).
//
// Coupling to the 2D vertical flow (as the sphere model's, width-averaged): each cell's slab dx x dz x B
// holds the stone's volume, each sub-sphere's exact slab volumes (slab_volume.h) scaled by
//
//   V_union / sum_k (4/3) pi r_k^3,
//
// so a stone's parts sum to its union volume (the overlaps spread over its sub-spheres), summed per cell
// into one cell list per stone (PorosityMapper::map_clumps; n_exp = 0 required, the porosity the true void
// fraction). The drag is the volume-equivalent sphere's (d_eq, A_p = pi d_eq^2 / 4, in x and z); buoyancy,
// added mass and the pressure-gradient force act on V_union; the wet fraction at the free surface is a
// sphere cap's with r_eq = d_eq / 2 (wet_radius: the level scaled by r_eq, not by the bounding radius).
// The kernel mapping takes the same cell lists. The 3D packing generator packs them (ClumpPacking,
// clump_packing.cpp: a mix of library shapes, WeirSpec::clump); its diagnostics read the stone's x-z outline
// as the union of its sub-spheres' discs (gap, covers, outline_max).
//
// References: Favier, J. F., Abbaspour-Fard, M. H., Kremmer, M. & Raji, A. O. (1999), Eng. Computations
// 16(4), 467-480. Ferellec, J.-F. & McDowell, G. R. (2010), Granular Matter 12, 459-467. Cundall, P. A.
// & Strack, O. D. L. (1979), Geotechnique 29(1), 47-65.
#pragma once

#include <array>
#include <cstddef>
#include <functional>
#include <string>
#include <vector>

#include "vofdem/stones/disc_model.h"
#include "vofdem/stones/sphere_contact.h"

namespace vofdem {

class Clump;

// the most spheres one clump stone may have
inline constexpr int kClumpMaxSpheres = 8;

class ClumpModel final : public DiscModel {
 public:
  const char* name() const override { return "clump"; }
  int dimensions() const override { return 3; }
  WetLaw wet_law() const override { return kSphereWetLaw; }
  double wet_radius(const DEMSystem& s, int i) const override { return 0.5 * nominal_diameter(s, i); }
  double volume(const DEMSystem& s, int i) const override;
  double inertia(const DEMSystem& s, int i, double mass) const override;
  std::array<double, 3> principal_inertia(const DEMSystem& s, int i, double mass) const override;
  double nominal_diameter(const DEMSystem& s, int i) const override;
  double projected_area(const DEMSystem& s, int i) const override;
  double projected_area(const DEMSystem& s, int i, double ux, double uz) const override;
  double stable_dt(const DEMSystem& s) const override;
  void check_params(const DEMParams& p) const override;
  void prepare(DEMSystem& s) override;
  ContactTally contact_forces(DEMSystem& s, double dt) override;
  ContactTally wall_forces(DEMSystem& s, double dt) override;
  bool own_pair_history() const override { return true; }
  void pairs_rebuilt(DEMSystem& s, const std::vector<int>& from) override;

  void export_state(const DEMSystem& s, DEMState& t) const override;
  void check_state(const DEMSystem& s, const DEMState& t) const override;
  void import_state(DEMSystem& s, const DEMState& t) override;
  const char* checkpoint_key() const override { return "clump_sphere"; }
  void state_to_map(DEMState& t, StateMap& m) const override;
  void state_from_map(const StateMap& m, std::size_t n, std::size_t nwalls, DEMState& t) const override;

  bool lookup_footprint() const override { return false; }
  void map_footprint(const DEMSystem& s, PorosityMapper& m, const double* x, const double* z) const override;
  DragForce drag(const DEMSystem& s, int i, const StoneFlowSample& f, double up, double wp, double rho, double nu,
                 DragLaw law, double* slope) const override;
  double drag_relaxation_dt(const DEMSystem& s, int i, double relaxation, double mass, double vrel, double w,
                            double rho, double nu) const override;
  std::unique_ptr<StonePacking> packing(const WeirSpec& spec) const override;
  double gap(const DEMSystem& s, int i, double x, double z) const override;
  bool covers(const DEMSystem& s, int i, double x, double z) const override;
  double outline_max(const DEMSystem& s, int i, const std::function<double(double, double)>& f) const override;

  // the stones' shapes: sphere holds (x, y, z, r) per sphere [m] in any frame, stone i owning spheres
  // offset[i] .. offset[i+1]-1 (1 to kClumpMaxSpheres); each is stored in its principal frame. Checked
  // first (std::invalid_argument naming the stone); the stones' radii become the bounding radii
  void set_shapes(int n, const std::vector<double>& sphere, const std::vector<int>& offset);
  // the same from clumps already integrated (one per stone, their principal frames kept)
  void set_shapes(const std::vector<Clump>& clumps);
  const std::vector<double>& spheres() const { return sphere_; }  // principal frames, (x, y, z, r) each
  const std::vector<int>& offsets() const { return offset_; }
  const std::vector<double>& bounding_radii() const { return bound_; }

 private:
  struct SubContact {
    int a, b;  // the sub-spheres of i and of j (their rank in the stone)
    bool touched;
    SphereContactHistory h;
  };
  void default_shapes(const DEMSystem& s);
  void adopt(const std::vector<const Clump*>& of);
  void derive_levers();
  bool outlined(const DEMSystem& s) const;
  std::array<double, 2> world_xz(const DEMSystem& s, int i, int g) const;
  void world_spheres(const DEMSystem& s);
  SphereOfBody body(const DEMSystem& s, int i, int g, double mass) const;
  double open_untouched(int i, int j, std::vector<SubContact>& hist, const SphereContactLaw& law) const;
  std::size_t np() const { return planes_.size(); }

  bool shaped_ = false;          // shapes set (else one sphere of stone_radius per stone, made at prepare)
  std::vector<double> sphere_;   // (x, y, z, r) per sub-sphere, principal frame [m]
  std::vector<int> offset_;      // n + 1
  std::vector<double> volume_;   // union volume [m^3], n
  std::vector<double> moment_;   // principal moments per unit density (J / rho) [m^5], 3n
  std::vector<double> bound_;    // bounding radius [m], n
  std::vector<double> lever_;    // a_n^2 and a_t^2 per unit density (rho a^2) [m^-3], 2n (stable_dt)
  std::vector<double> world_;    // sub-sphere centres in the world [m], 3 per sub-sphere (scratch)
  std::vector<std::vector<SubContact>> pair_history_;  // per listed pair, its touching sub-sphere pairs
  std::vector<SphereContactHistory> wall_history_;     // per (sub-sphere, plane of planes_)
  std::vector<ContactPlane> planes_;
};

// makes every stone of s a clump of these spheres (ClumpModel::set_shapes; the model set anew, the
// stones' radii their bounding radii). A refused set changes nothing
void set_clumps(DEMSystem& s, const std::vector<double>& sphere, const std::vector<int>& offset);
// the same from clumps already integrated, one per stone (std::invalid_argument naming clumps otherwise)
void set_clumps(DEMSystem& s, const std::vector<Clump>& clumps);

}  // namespace vofdem
