// Polygon stones: convex polygons in the x-z plane, each standing for the 3D stone whose mid-section it
// is (polygon.h gives V, I and the projected areas of that stone; polygon_contact.h the contact manifolds).
//
// Each manifold point of polygon_contact.h carries the disc's contact law (dem_contact.h) with the
// point's depth delta_p and the relative velocity of the two bodies at the point:
//
//   v_rel = (v_i + omega_i x r_i) - (v_j + omega_j x r_j),   r = p - x (lever arm to the centre)
//   f_n,p = k_n delta_p + c_n,p d(delta_p)/dt,   f_s,p = -k_t xi_p - c_t,p v_t,p,  |f_s,p| <= mu max(f_n,p, 0)
//   c_n,p = 2 zeta sqrt(m* k_n / N)   (N points: each carries its share of the pair's mass, so a flat face
//                                      striking flat on N points has the restitution e of the disc)
//
// and the force -f_n n + f_s t at p acts on i (its opposite on j), with the torque r x F. Each point's
// tangential spring xi_p is kept from step to step by its feature id (ContactPair::points, and per
// (stone, wall)); a point that is new starts at 0. k_n is the disc's (the same automatic stiffness from
// the mean stone's mass): a vertex touching a face has the disc's stiffness, a face lying on a face twice.
//
// Stable step: the largest eigenvalue of one pair's two points is bounded by the trace,
//   omega^2 <= 2 N k (1/m + R^2 / I)  with N = 2 points and two equal stones,
// R the bounding radius (the largest lever arm); the step is pi / (10 omega) as for discs.
//
// The shapes live in DEMSystem::poly_vertex / poly_offset (set_polygons); stone_radius holds each stone's
// bounding radius (the neighbour search's). Footprint: the exact polygon-cell areas (the paper's lookup
// table holds disc areas: refused). Drag: eqs. (16)-(18) with the projected area across the relative
// velocity and the nominal diameter. The rolling resistance is refused (mu_r > 0): a polygon resists
// rolling by its shape.
#pragma once

#include <cstddef>
#include <vector>

#include "vofdem/stones/polygon_contact.h"
#include "vofdem/stones/stone_model.h"

namespace vofdem {

namespace detail {
// a touching polygon pair of one force evaluation: its index in the pair list and its manifold
struct PolygonContact {
  int pair = 0;
  ContactManifold m;
};

// separating-axis cache of one polygon pair (polygon_model.cpp): saves the full test while the pose has
// not moved enough to change its answer; never changes a result, so it is no part of the state
struct PolygonPairCache {
  int flip = -1, edge = 0;  // the axis (flip -1: none)
  int flip2 = 0, edge2 = 0; // overlapping: the runner-up axis
  double margin = -1.0;     // overlapping: the axis's lead over every other [m] (>= 0); < 0: a separating axis
  double margin2 = 0.0;     // overlapping: the runner-up's lead over every other axis but the first [m]
  double sep = 0.0;         // a separating axis: its separation at the pose below [m]
  double dx = 0.0, dz = 0.0, ai = 0.0, aj = 0.0;  // the pose it was found at
  double s = 0.0;           // a reference axis: its separation [m] (< 0: the depth) at the pose below
  double sx = 0.0, sz = 0.0, sai = 0.0, saj = 0.0;
  // the incident edge found for the reference face (inc_flip, inc_edge) at angles (inc_ai, inc_aj), and
  // its lead over the next edge (in n . u) [-]; inc -1: none
  int inc = -1, inc_flip = 0, inc_edge = 0;
  double inc_margin = 0.0, inc_ai = 0.0, inc_aj = 0.0;
};
}  // namespace detail

class PolygonModel final : public StoneModel {
 public:
  const char* name() const override { return "polygon"; }
  double volume(const DEMSystem& s, int i) const override;
  double inertia(const DEMSystem& s, int i, double mass) const override;
  double nominal_diameter(const DEMSystem& s, int i) const override;
  double projected_area(const DEMSystem& s, int i) const override;
  double projected_area(const DEMSystem& s, int i, double ux, double uz) const override;
  double stable_dt(const DEMSystem& s) const override;
  ContactTally contact_forces(DEMSystem& s, double dt) override;
  ContactTally wall_forces(DEMSystem& s, double dt) override;
  void check_params(const DEMParams& p) const override;
  void prepare(DEMSystem& s) override;
  void export_state(const DEMSystem& s, DEMState& t) const override;
  void check_state(const DEMSystem& s, const DEMState& t) const override;
  void import_state(DEMSystem& s, const DEMState& t) override;
  const char* checkpoint_key() const override { return "poly_vertex"; }
  void state_to_map(DEMState& t, StateMap& m) const override;
  void state_from_map(const StateMap& m, std::size_t n, std::size_t nwalls, DEMState& t) const override;
  void map_footprint(const DEMSystem& s, PorosityMapper& m, const double* x, const double* z) const override;
  DragForce drag(const DEMSystem& s, int i, const StoneFlowSample& f, double up, double wp, double rho, double nu,
                 DragLaw law, double* slope) const override;
  double drag_relaxation_dt(const DEMSystem& s, int i, double relaxation, double mass, double vrel, double w,
                            double rho, double nu) const override;
  double gap(const DEMSystem& s, int i, double x, double z) const override;
  bool covers(const DEMSystem& s, int i, double x, double z) const override;
  double outline_max(const DEMSystem& s, int i, const std::function<double(double, double)>& f) const override;
  std::unique_ptr<StonePacking> packing(const WeirSpec& spec) const override;

  // makes the stones of s these polygons (DEMSystem::set_polygons), checked first: a refused set
  // changes nothing
  void set_shapes(DEMSystem& s, const std::vector<double>& vertex, const std::vector<int>& offset);
  // section area, J/A, edge normals and bounding radius (stone_radius) of every stone from the shapes;
  // throws std::invalid_argument for a bad polygon (naming the stone)
  void update_properties(DEMSystem& s);

 private:
  std::size_t touching(DEMSystem& s, double kt, double& opened);
  // the world-frame vertices of stone i into out (at most kPolygonMaxVertices pairs)
  int world_vertices(const DEMSystem& s, int i, double* out) const;

  // derived section properties and per-evaluation world geometry
  std::vector<double> area_;     // section area A [m^2], n
  std::vector<double> jratio_;   // J_A / A [m^2], n
  std::vector<double> normal_;   // body-frame edge normals, as poly_vertex
  std::vector<double> world_, world_normal_;  // world-frame vertices and normals
  std::vector<long long> world_stamp_;  // the force evaluation whose world geometry a stone holds
  std::vector<int> todo_;               // scratch: the stones whose world geometry is made first
  std::vector<double> cs_;              // scratch: their cosines and sines
  long long eval_ = 0;                  // force evaluations so far (a cache key, not state)
  std::vector<detail::PolygonPairCache> sat_cache_;  // separating-axis cache of each pair
  std::vector<detail::PolygonContact> contacts_;     // the touching pairs of a force evaluation (scratch)
  int sat_builds_ = -1;  // the neighbour build the cache belongs to
  std::vector<double> cached_vertex_;
};

}  // namespace vofdem
