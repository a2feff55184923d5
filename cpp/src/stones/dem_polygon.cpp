// Polygon stones in DEMSystem: their shape, contact forces, stable step and checkpoint.
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
// tangential spring xi_p is kept from step to step by its feature id; a point that is new starts at 0.
// k_n is the disc's (the same automatic stiffness from the mean stone's mass): a vertex touching a
// face has the disc's stiffness, a face lying on a face twice (two points).
//
// Stable step: the largest eigenvalue of one pair's two points is bounded by the trace,
//   omega^2 <= 2 N k (1/m + R^2 / I)  with N = 2 points and two equal stones,
// R the bounding radius (the largest lever arm); the step is pi / (10 omega) as for discs.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <stdexcept>
#include <string>

#include "vofdem/common/check.h"
#include "vofdem/stones/dem_contact.h"
#include "vofdem/stones/dem_system.h"
#include "vofdem/stones/polygon_contact.h"
#include "stones/polygon_kernels.h"

namespace vofdem {

namespace {
constexpr double kPi = 3.14159265358979323846;
constexpr double kSqrtHalf = 0.70710678118654752440;  // a point's share of the pair's mass: sqrt(1 / N), N = 2

// checks the polygon arrays of n stones; throws std::invalid_argument naming the stone
void check_polygons(const std::vector<double>& vertex, const std::vector<int>& offset, int n) {
  if (offset.size() != static_cast<std::size_t>(n) + 1)
    throw std::invalid_argument("poly_offset has " + std::to_string(offset.size()) + " entries, expected n + 1 = " +
                                std::to_string(n + 1));
  if (offset[0] != 0) throw std::invalid_argument("poly_offset[0] = " + std::to_string(offset[0]) + ", expected 0");
  for (int i = 0; i < n; ++i) {
    const int c = offset[i + 1] - offset[i];
    if (c < 3 || c > kPolygonMaxVertices)
      throw std::invalid_argument("stone " + std::to_string(i) + " has " + std::to_string(c) +
                                  " vertices: allowed range [3, " + std::to_string(kPolygonMaxVertices) + "]");
  }
  if (vertex.size() != 2 * static_cast<std::size_t>(offset[n]))
    throw std::invalid_argument("poly_vertex has " + std::to_string(vertex.size()) + " values, expected 2 x " +
                                std::to_string(offset[n]) + " (x, z pairs)");
  for (int i = 0; i < n; ++i) {
    const double* v = &vertex[2 * static_cast<std::size_t>(offset[i])];
    const int c = offset[i + 1] - offset[i];
    for (int k = 0; k < 2 * c; ++k) require_finite("poly_vertex", v[k]);
    if (!polygon_is_convex_ccw(v, c))
      throw std::invalid_argument("stone " + std::to_string(i) +
                                  ": its polygon is not strictly convex and counter-clockwise");
    const PolygonProperties q = polygon_properties(v, c);
    if (std::hypot(q.centroid[0], q.centroid[1]) > 1e-6 * q.bounding_radius)
      throw std::invalid_argument("stone " + std::to_string(i) + ": its polygon's centroid (" +
                                  format_value(q.centroid[0]) + ", " + format_value(q.centroid[1]) +
                                  ") m is not at the body origin (allowed |c| <= 1e-6 R)");
  }
}

// cross product of 2D vectors: the torque of force (fx, fz) at lever (rx, rz)
inline double cross(double rx, double rz, double fx, double fz) { return rx * fz - rz * fx; }
}  // namespace

void DEMSystem::set_polygons(const std::vector<double>& vertex, const std::vector<int>& offset) {
  check_polygons(vertex, offset, n_);
  check_rolling_shape(StoneShape::kPolygon, params_);
  poly_vertex = vertex;
  poly_offset = offset;
  shape_ = StoneShape::kPolygon;
  update_polygon_properties();
  pairs_.clear();
  poly_wall_hist_.assign(static_cast<std::size_t>(n_) * params_.walls.size(), PolygonHistory{});
  rebuild_ = true;
  prepared_ = false;
  forces_valid_ = false;
}

// section area, J/A, edge normals and bounding radius (disc_radius) of every polygon
void DEMSystem::update_polygon_properties() {
  check_polygons(poly_vertex, poly_offset, n_);
  const std::size_t un = static_cast<std::size_t>(n_);
  poly_area_.assign(un, 0.0);
  poly_jratio_.assign(un, 0.0);
  poly_normal_.assign(poly_vertex.size(), 0.0);
  poly_world_.assign(poly_vertex.size(), 0.0);
  poly_world_normal_.assign(poly_vertex.size(), 0.0);
  poly_world_stamp_.assign(un, -1);
  poly_todo_.assign(un, 0);
  poly_cs_.assign(2 * un, 0.0);
  poly_sat_cache_.clear();  // its axes belong to the old shapes
  for (int i = 0; i < n_; ++i) {
    const int o = poly_offset[i], c = poly_offset[i + 1] - o;
    const PolygonProperties q = polygon_properties(&poly_vertex[2 * o], c);
    poly_area_[i] = q.area;
    poly_jratio_[i] = q.polar_moment / q.area;
    disc_radius[i] = q.bounding_radius;
    polygon_edge_normals(&poly_vertex[2 * o], c, &poly_normal_[2 * o]);
  }
  cached_poly_vertex_ = poly_vertex;
}

double DEMSystem::nominal_diameter(int i) const {
  if (shape_ == StoneShape::kPolygon) return polygon_nominal_diameter(poly_area_[i]);
  return 2.0 * disc_radius[i];
}

double DEMSystem::projected_area(int i, double ux, double uz) const {
  if (shape_ != StoneShape::kPolygon || (ux == 0.0 && uz == 0.0)) return projected_area(i);
  const int o = poly_offset[i];
  const double w = polygon_width_across(&poly_vertex[2 * o], poly_offset[i + 1] - o, disc_angle[i], ux, uz);
  return 0.25 * kPi * polygon_nominal_diameter(poly_area_[i]) * w;
}

double DEMSystem::polygon_stable_dt() const {
  const bool rot = params_.flags & kDEMRotation;
  double lam = 0.0;
  for (int i = 0; i < n_; ++i) {
    if (!disc_active[i] || disc_fixed[i]) continue;
    const double m = mass(i), r = disc_radius[i];
    lam = std::max(lam, 1.0 / m + (rot ? r * r / inertia_of(i, m) : 0.0));
  }
  if (!(lam > 0.0) || kn_ <= 0.0) return INFINITY;
  const double w = std::sqrt(4.0 * std::max(kn_, kt_) * lam);
  return kPi / (10.0 * w);
}

namespace {

using PairCache = detail::PolygonPairCache;

// the polygons of one force evaluation by raw pointers: body geometry, poses and the world geometry
// made from them. World-frame vertices and edge normals are computed once per force evaluation and
// only for the stones whose bounding disc touches another's or a wall (free-flying stones cost nothing);
// a stone that has not moved since the last evaluation keeps what that one made.
struct PolygonFrame {
  const int* offset;
  const double *vertex, *normal;  // body frame
  double *world, *world_normal;   // world frame
  long long* stamp;               // the evaluation whose world geometry a stone holds
  long long eval;
  const double *pos, *angle;
  const double* inv_mass;         // 0: fixed
  const std::uint8_t* asleep;

  // a stone that has not moved since the last evaluation made its world geometry (fixed, or asleep)
  bool kept(int i) const { return stamp[i] == eval - 1 && (inv_mass[i] == 0.0 || asleep[i]); }
  void make(int i, double c, double s) {
    stamp[i] = eval;
    const int o = offset[i], n = offset[i + 1] - o;
    detail::to_world(vertex + 2 * o, n, pos[2 * i], pos[2 * i + 1], c, s, world + 2 * o);
    detail::to_world(normal + 2 * o, n, 0.0, 0.0, c, s, world_normal + 2 * o);
  }
  void update(int i) {
    if (stamp[i] == eval) return;
    if (kept(i)) {
      stamp[i] = eval;
      return;
    }
    const double c = std::cos(angle[i]), s = std::sin(angle[i]);
    make(i, c, s);
  }
};

// the reference face (flip, edge) of pair (i, j), centre offset (dx, dz), and whether the two overlap.
// The cache answers when it can prove the full separating-axis test would give the same. No separation
// can have changed since a pose 0 by more than
//   b = |d - d0| + 2 (|theta_i - theta_i0| + |theta_j - theta_j0|) (R_i + R_j)
// (a vertex moves relative to the other body's frame by at most that). A cached separating axis that
// separated by sep stays one while b < sep (no vertex touched), or while it still separates. A cached
// reference axis that led every other by `margin` stays the answer while 2 b < margin; the pair then
// overlaps if the separation s along it is negative, which holds without a vertex while b (since s was
// measured) < -s, the depth. Two faces lying on each other lead the others together, by margin2, with
// little between them: while 2 b < margin2 the answer is one of the two, and their two separations
// decide it by the full test's rules. Otherwise the full test runs and refreshes the cache. Either way
// the same axis and the same arithmetic: bit-identical. It brings both stones' world geometry up to date
// whenever it may need a vertex.
inline bool pair_reference(PolygonFrame& f, PairCache& sc, int i, int j, double dx, double dz, double reach, int& flip,
                           int& edge) {
  const double ai = f.angle[i], aj = f.angle[j];
  const double tol = 1e-12 * reach;
  if (sc.flip >= 0 && sc.margin < 0.0) {
    // a separating axis that separated by sep: apart while the pose moved less than that, the bound b
    // with |e_x| + |e_z| >= |d - d0| (no sqrt); no vertex is touched
    const double b1 =
        std::fabs(dx - sc.dx) + std::fabs(dz - sc.dz) + 2.0 * (std::fabs(ai - sc.ai) + std::fabs(aj - sc.aj)) * reach;
    if (b1 < sc.sep - tol) return false;
  }
  f.update(i);
  f.update(j);
  const int oi = f.offset[i], oj = f.offset[j], ni = f.offset[i + 1] - oi, nj = f.offset[j + 1] - oj;
  const double *va = f.world + 2 * oi, *ua = f.world_normal + 2 * oi;
  const double *vb = f.world + 2 * oj, *ub = f.world_normal + 2 * oj;
  // the separation along edge k of A (flip 0) or of B (flip 1)
  auto axis = [&](int fl, int k) {
    const double* v1 = (fl ? vb : va) + 2 * k;
    const double* u1 = (fl ? ub : ua) + 2 * k;
    return detail::min_projection(u1[0], u1[1], v1[0], v1[1], fl ? va : vb, fl ? ni : nj);
  };
  if (sc.flip >= 0) {
    if (sc.margin < 0.0) {
      const double s = axis(sc.flip, sc.edge);
      if (s > 0.0) {  // still apart: its separation now is the new reference
        sc.sep = s;
        sc.dx = dx, sc.dz = dz, sc.ai = ai, sc.aj = aj;
        return false;
      }
    } else {
      // b with |e_x| + |e_z| >= |d - d0| first (no sqrt, whose latency the branch would wait for), with |d - d0|
      // itself only where that does not prove the axis (sqrt, not hypot: no overflow here, and 5x cheaper)
      const double ex = dx - sc.dx, ez = dz - sc.dz;
      const double turn = 2.0 * (std::fabs(ai - sc.ai) + std::fabs(aj - sc.aj)) * reach;
      const bool held = 2.0 * (std::fabs(ex) + std::fabs(ez) + turn) < sc.margin - tol;
      const double b = held ? 0.0 : std::sqrt(ex * ex + ez * ez) + turn;
      if (held || 2.0 * b < sc.margin - tol) {
        flip = sc.flip;
        edge = sc.edge;
        // the depth along the reference axis outlasts the motion since it was measured (|e_x| + |e_z| again)
        const double bs = std::fabs(dx - sc.sx) + std::fabs(dz - sc.sz) +
                          2.0 * (std::fabs(ai - sc.sai) + std::fabs(aj - sc.saj)) * reach;
        if (bs < -sc.s - tol) return true;
        sc.s = axis(sc.flip, sc.edge);
        sc.sx = dx, sc.sz = dz, sc.sai = ai, sc.saj = aj;
        return sc.s < 0.0;
      }
      if (2.0 * b < sc.margin2 - tol) {
        // every other axis below both: overlapping if both are negative; the larger wins, a tie going to
        // A's axis (other polygons) or to the lower edge (one polygon), as in polygon_sat
        const double s1 = axis(sc.flip, sc.edge), s2 = axis(sc.flip2, sc.edge2);
        if (!(s1 < 0.0 && s2 < 0.0)) return false;
        const bool first1 = sc.flip != sc.flip2 ? sc.flip == 0 : sc.edge < sc.edge2;  // axis 1 wins ties
        const bool take1 = first1 ? !(s2 > s1) : s1 > s2;
        flip = take1 ? sc.flip : sc.flip2;
        edge = take1 ? sc.edge : sc.edge2;
        return true;
      }
    }
  }
  const detail::SatTop2 r = detail::sat_top2(va, ua, ni, vb, ub, nj);
  const bool overlap = r.best.value < 0.0;
  sc.flip = r.best.flip;
  sc.edge = r.best.edge;
  sc.margin = overlap ? r.best.margin : -1.0;
  sc.flip2 = r.flip2;
  sc.edge2 = r.edge2;
  sc.margin2 = overlap ? r.margin2 : 0.0;
  sc.sep = r.best.value;
  sc.s = r.best.value;
  sc.dx = sc.sx = dx;
  sc.dz = sc.sz = dz;
  sc.ai = sc.sai = ai;
  sc.aj = sc.saj = aj;
  flip = r.best.flip;
  edge = r.best.edge;
  return overlap;
}

// the incident edge of pair (i, j) for the reference face (flip, edge), from the cache while no edge normal
// can have turned enough to change the choice: n . u_k changes by at most |dtheta_i| + |dtheta_j| (both
// unit normals turn with their stones), so the choice holds while 2 (|dtheta_i| + |dtheta_j|) stays below
// the lead it had. The same edge either way, so the same arithmetic follows: bit-identical.
inline int pair_incident(const PolygonFrame& f, PairCache& sc, int i, int j, int flip, int edge) {
  const double ai = f.angle[i], aj = f.angle[j];
  if (sc.inc >= 0 && sc.inc_flip == flip && sc.inc_edge == edge &&
      2.0 * (std::fabs(ai - sc.inc_ai) + std::fabs(aj - sc.inc_aj)) < sc.inc_margin - 1e-12)
    return sc.inc;
  const int ref = flip ? j : i, other = flip ? i : j;
  const double* u = f.world_normal + 2 * (f.offset[ref] + edge);
  const int o = f.offset[other];
  sc.inc = detail::incident_edge(f.world_normal + 2 * o, f.offset[other + 1] - o, u[0], u[1], &sc.inc_margin);
  sc.inc_flip = flip;
  sc.inc_edge = edge;
  sc.inc_ai = ai;
  sc.inc_aj = aj;
  return sc.inc;
}

// the manifold of pair (i, j) with reference face (flip, edge) and incident edge inc (world geometry made)
inline void pair_manifold(const PolygonFrame& f, int i, int j, int flip, int edge, int inc, ContactManifold& m) {
  const int ref = flip ? j : i, other = flip ? i : j;
  const int o1 = f.offset[ref], n1 = f.offset[ref + 1] - o1, o2 = f.offset[other], n2 = f.offset[other + 1] - o2;
  const int i12 = edge + 1 == n1 ? 0 : edge + 1, i22 = inc + 1 == n2 ? 0 : inc + 1;
  const double* v1 = f.world + 2 * o1;
  const double* v2 = f.world + 2 * o2;
  const double* u = f.world_normal + 2 * (o1 + edge);
  detail::clip_manifold(v1 + 2 * edge, v1 + 2 * i12, v2 + 2 * inc, v2 + 2 * i22, u[0], u[1], flip, edge, i12, inc, i22,
                        m);
}
}  // namespace

// the narrow phase of every listed pair: the touching ones' manifolds into poly_contacts_ (in the pairs'
// order), their count returned; the springs of the others cleared
std::size_t DEMSystem::polygon_touching() {
  ++poly_eval_;  // the world geometry of the last evaluation is stale
  if (poly_sat_builds_ != nbuilds_ || poly_sat_cache_.size() != pairs_.size()) {
    poly_sat_cache_.assign(pairs_.size(), PairCache{});  // a new list: new pairs
    poly_sat_builds_ = nbuilds_;
  }
  PolygonFrame f{poly_offset.data(), poly_vertex.data(),        poly_normal_.data(),      poly_world_.data(),
                 poly_world_normal_.data(), poly_world_stamp_.data(), poly_eval_,      disc_pos.data(),
                 disc_angle.data(),  inv_mass_.data(),           disc_asleep.data()};
  // the stones that needed their world geometry at the last evaluation need it now, most likely: made
  // first (the pair loop then finds them made), their cosines and sines in one pass (the calls back to
  // back) and their vertices and normals in another
  int* todo = poly_todo_.data();
  double* cs = poly_cs_.data();
  int ntodo = 0;
  for (int i = 0; i < n_; ++i) {
    if (poly_world_stamp_[i] != poly_eval_ - 1) continue;
    if (f.kept(i)) {
      poly_world_stamp_[i] = poly_eval_;
      continue;
    }
    todo[ntodo++] = i;
  }
  for (int k = 0; k < ntodo; ++k) {
    const double a = disc_angle[todo[k]];
    cs[2 * k] = std::cos(a);
    cs[2 * k + 1] = std::sin(a);
  }
  for (int k = 0; k < ntodo; ++k) f.make(todo[k], cs[2 * k], cs[2 * k + 1]);
  const double* pos = disc_pos.data();
  const double* radius = disc_radius.data();
  PairCache* caches = poly_sat_cache_.data();
  const std::size_t npairs = pairs_.size();
  if (poly_contacts_.size() < npairs) poly_contacts_.resize(npairs);
  detail::PolygonContact* contacts = poly_contacts_.data();
  std::size_t ntouch = 0;
  for (std::size_t pc = 0; pc < npairs; ++pc) {
    Pair& c = pairs_[pc];
    PairCache& cache = caches[pc];
    const int i = c.i, j = c.j;
    const double dx = pos[2 * j] - pos[2 * i], dz = pos[2 * j + 1] - pos[2 * i + 1], rs = radius[i] + radius[j];
    if (dx * dx + dz * dz >= rs * rs) {  // bounding discs apart
      c.poly = PolygonHistory{};
      cache.flip = -1;
      continue;
    }
    int flip = 0, edge = 0;
    if (!pair_reference(f, cache, i, j, dx, dz, rs, flip, edge)) {  // apart: cleared in place, no manifold
      c.poly = PolygonHistory{};
      continue;
    }
    detail::PolygonContact& r = contacts[ntouch];
    pair_manifold(f, i, j, flip, edge, pair_incident(f, cache, i, j, flip, edge), r.m);
    if (r.m.count == 0) {  // overlapping by no point of the clipped edge: no spring kept
      c.poly = PolygonHistory{};
      continue;
    }
    r.pair = static_cast<int>(pc);
    ++ntouch;
  }
  return ntouch;
}

// the forces of the touching pairs, in the pairs' order (a function of its own: fewer values live at once)
void DEMSystem::polygon_contact_forces(double dt) {
  const std::size_t ntouch = polygon_touching();
  const DEMParams& p = params_;
  const auto [friction, damp, kt] = contact_law();
  const double ct_factor = p.tangential_damping_factor;
  const double kn = kn_, mu = p.friction_stone;
  double elastic = 0.0, dissipated = 0.0;
  int ncontact = 0;
  const double *pos = disc_pos.data(), *vel = disc_vel.data(), *omega = disc_omega.data();
  double *force = disc_force.data(), *torque = disc_torque.data();
  const detail::PolygonContact* contacts = poly_contacts_.data();
  for (std::size_t t = 0; t < ntouch; ++t) {
    const detail::PolygonContact& r = contacts[t];
    const ContactManifold& m = r.m;
    Pair& c = pairs_[static_cast<std::size_t>(r.pair)];
    const int i = c.i, j = c.j;
    const double xi0 = pos[2 * i], zi0 = pos[2 * i + 1], xj0 = pos[2 * j], zj0 = pos[2 * j + 1];
    const PolygonHistory prev = c.poly;
    c.poly = PolygonHistory{};  // written field by field below: no copy of a just-stored struct
    ++ncontact;
    const double nx = m.normal[0], nz = m.normal[1];
    const double cn = m.count == 2 ? damp * c.sqrt_m * kSqrtHalf : damp * c.sqrt_m;
    for (int k = 0; k < m.count; ++k) {
      const ContactManifold::Point& q = m.point[k];
      const double rix = q.x - xi0, riz = q.z - zi0, rjx = q.x - xj0, rjz = q.z - zj0;
      const double vrx = vel[2 * i] - omega[i] * riz - vel[2 * j] + omega[j] * rjz;
      const double vrz = vel[2 * i + 1] + omega[i] * rix - vel[2 * j + 1] - omega[j] * rjx;
      const double vn = vrx * nx + vrz * nz;
      const double vt = -vrx * nz + vrz * nx;
      double xi = prev.spring(q.id);
      const ContactForce fc = friction ? linear_contact(q.depth, vn, vt, xi, dt, kn, kt, cn, ct_factor * cn, mu, true)
                                       : linear_contact(q.depth, vn, 0.0, xi, dt, kn, 0.0, cn, 0.0, 0.0, false);
      // force on i: -f_n n + f_s t, with t = (-n_z, n_x); its opposite on j
      const double fx = -fc.fn * nx - fc.ft * nz, fz = -fc.fn * nz + fc.ft * nx;
      force[2 * i] += fx;
      force[2 * i + 1] += fz;
      force[2 * j] -= fx;
      force[2 * j + 1] -= fz;
      torque[i] += cross(rix, riz, fx, fz);
      torque[j] -= cross(rjx, rjz, fx, fz);
      c.poly.id[k] = q.id;
      c.poly.xi[k] = xi;
      elastic += fc.energy_spring;
      dissipated += fc.power_damp * dt + fc.energy_slip;
    }
  }
  elastic_ = elastic;
  dissipated_ += dissipated;
  ncontact_ = ncontact;
}

void DEMSystem::polygon_wall_forces(double dt) {
  const DEMParams& p = params_;
  const auto [friction, damp, kt] = contact_law();
  const std::size_t nw = p.walls.size();
  PolygonFrame f{poly_offset.data(), poly_vertex.data(),        poly_normal_.data(),      poly_world_.data(),
                 poly_world_normal_.data(), poly_world_stamp_.data(), poly_eval_,      disc_pos.data(),
                 disc_angle.data(),  inv_mass_.data(),           disc_asleep.data()};
  double elastic = 0.0, dissipated = 0.0;
  int ncontact = 0;
  for (std::size_t w = 0; w < nw; ++w) {
    const DEMWall& wall = p.walls[w];
    const auto [wx, wz] = wall_unit_normal(wall);
    for (int c = wall_cand_start_[w]; c < wall_cand_start_[w + 1]; ++c) {
      const int i = wall_cand_[c];
      if (inv_mass_[i] == 0.0) continue;
      PolygonHistory& hist = poly_wall_hist_[static_cast<std::size_t>(i) * nw + w];
      const double x0 = disc_pos[2 * i], z0 = disc_pos[2 * i + 1];
      const double s = (x0 - wall.point[0]) * wx + (z0 - wall.point[1]) * wz;
      const int o = poly_offset[i];
      if (s < disc_radius[i]) f.update(i);
      const ContactManifold m =
          s >= disc_radius[i] ? ContactManifold{}
                              : collide_polygon_wall(&poly_world_[2 * o], &poly_world_normal_[2 * o],
                                                     poly_offset[i + 1] - o, wall.point[0], wall.point[1], wx, wz);
      const PolygonHistory prev = hist;
      hist = PolygonHistory{};
      if (m.count > 0) ++ncontact;
      const double nx = m.normal[0], nz = m.normal[1];
      const double cn = m.count == 2 ? damp * std::sqrt(mass_eff_[i]) * kSqrtHalf : damp * std::sqrt(mass_eff_[i]);
      for (int k = 0; k < m.count; ++k) {
        const ContactManifold::Point& q = m.point[k];
        const double rx = q.x - x0, rz = q.z - z0;
        const double vx = disc_vel[2 * i] - disc_omega[i] * rz, vz = disc_vel[2 * i + 1] + disc_omega[i] * rx;
        const double vn = vx * nx + vz * nz;
        const double vt = -vx * nz + vz * nx;
        double xi = prev.spring(q.id);
        const ContactForce f = friction ? linear_contact(q.depth, vn, vt, xi, dt, kn_, kt, cn,
                                                         p.tangential_damping_factor * cn, wall.friction, true)
                                        : linear_contact(q.depth, vn, 0.0, xi, dt, kn_, 0.0, cn, 0.0, 0.0, false);
        const double fx = -f.fn * nx - f.ft * nz, fz = -f.fn * nz + f.ft * nx;
        disc_force[2 * i] += fx;
        disc_force[2 * i + 1] += fz;
        disc_torque[i] += cross(rx, rz, fx, fz);
        hist.id[k] = q.id;
        hist.xi[k] = xi;
        elastic += f.energy_spring;
        dissipated += f.power_damp * dt + f.energy_slip;
      }
    }
  }
  elastic_ += elastic;
  dissipated_ += dissipated;
  nwall_contact_ = ncontact;
}

// ---- state: the shape and the manifold points' springs (polygon systems only)

void DEMSystem::export_polygons(DEMState& s) const {
  s.poly_contact_i.clear(), s.poly_contact_j.clear(), s.poly_contact_id.clear(), s.poly_contact_xi.clear();
  s.poly_wall_id.clear(), s.poly_wall_xi.clear();
  if (shape_ != StoneShape::kPolygon) {
    s.poly_vertex.clear(), s.poly_offset.clear();
    return;
  }
  s.poly_vertex = poly_vertex;
  s.poly_offset = poly_offset;
  for (const Pair& c : pairs_) {
    if (c.poly.id[0] < 0 && c.poly.id[1] < 0) continue;
    s.poly_contact_i.push_back(c.i);
    s.poly_contact_j.push_back(c.j);
    for (int k = 0; k < 2; ++k) s.poly_contact_id.push_back(c.poly.id[k]), s.poly_contact_xi.push_back(c.poly.xi[k]);
  }
  for (const PolygonHistory& h : poly_wall_hist_)
    for (int k = 0; k < 2; ++k) s.poly_wall_id.push_back(h.id[k]), s.poly_wall_xi.push_back(h.xi[k]);
}

// the polygon part of a state, checked before anything is written
void DEMSystem::check_polygon_state(const DEMState& s) const {
  const std::size_t n = s.disc_radius.size(), nw = n * params_.walls.size(), np = s.poly_contact_i.size();
  require_size("poly_offset", s.poly_offset, n + 1);
  check_polygons(s.poly_vertex, s.poly_offset, static_cast<int>(n));
  check_rolling_shape(StoneShape::kPolygon, params_);
  require_size("poly_contact_j", s.poly_contact_j, np);
  require_size("poly_contact_id", s.poly_contact_id, 2 * np);
  require_size("poly_contact_xi", s.poly_contact_xi, 2 * np);
  require_size("poly_wall_id", s.poly_wall_id, 2 * nw);
  require_size("poly_wall_xi", s.poly_wall_xi, 2 * nw);
  for (std::size_t k = 0; k < np; ++k) {
    const int i = s.poly_contact_i[k], j = s.poly_contact_j[k];
    const bool sorted = k == 0 || s.poly_contact_i[k - 1] < i || (s.poly_contact_i[k - 1] == i && s.poly_contact_j[k - 1] < j);
    if (!(i >= 0 && i < j && j < static_cast<int>(n)) || !sorted)
      throw std::invalid_argument("import_state: polygon contact pair (" + std::to_string(i) + ", " +
                                  std::to_string(j) + ") is outside 0 <= i < j < n or not sorted by (i, j)");
  }
}

// after check_polygon_state
void DEMSystem::import_polygons(const DEMState& s) {
  if (s.poly_offset.empty()) {  // a disc state
    shape_ = StoneShape::kDisc;
    poly_vertex.clear();
    poly_offset.clear();
    poly_wall_hist_.clear();
    return;
  }
  set_polygons(s.poly_vertex, s.poly_offset);
  for (std::size_t k = 0; k < s.poly_contact_i.size(); ++k) {
    Pair c{s.poly_contact_i[k], s.poly_contact_j[k], 0.0, 0.0};
    for (int q = 0; q < 2; ++q) c.poly.id[q] = s.poly_contact_id[2 * k + q], c.poly.xi[q] = s.poly_contact_xi[2 * k + q];
    pairs_.push_back(c);
  }
  const std::size_t nwh = static_cast<std::size_t>(n_) * params_.walls.size();
  for (std::size_t k = 0; k < nwh; ++k)
    for (int q = 0; q < 2; ++q)
      poly_wall_hist_[k].id[q] = s.poly_wall_id[2 * k + q], poly_wall_hist_[k].xi[q] = s.poly_wall_xi[2 * k + q];
}

}  // namespace vofdem
