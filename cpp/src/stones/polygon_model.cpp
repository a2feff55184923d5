// Polygon stones (polygon_model.h): their shapes, contact forces, stable step, state and footprint.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <memory>
#include <stdexcept>
#include <string>

#include "vofdem/common/check.h"
#include "vofdem/common/numbers.h"
#include "vofdem/stones/dem_contact.h"
#include "vofdem/coupling/drag_exchange.h"
#include "vofdem/coupling/fluid_forces.h"
#include "vofdem/coupling/porosity_map.h"
#include "vofdem/stones/dem_system.h"
#include "vofdem/stones/polygon.h"
#include "vofdem/stones/polygon_model.h"
#include "common/state_fields.h"
#include "stones/polygon_kernels.h"

namespace vofdem {

namespace {
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
  auto model = std::make_unique<PolygonModel>();
  model->set_shapes(*this, vertex, offset);
  model_ = std::move(model);
}

void PolygonModel::set_shapes(DEMSystem& s, const std::vector<double>& vertex, const std::vector<int>& offset) {
  check_polygons(vertex, offset, s.n());
  check_params(s.params());
  s.poly_vertex = vertex;
  s.poly_offset = offset;
  update_properties(s);
  wall_point_springs(s).assign(static_cast<std::size_t>(s.n()) * s.params().walls.size(), PointSprings{});
  shapes_changed(s);
}

void PolygonModel::update_properties(DEMSystem& s) {
  const std::vector<double>& vertex = s.poly_vertex;
  const std::vector<int>& offset = s.poly_offset;
  const int n = s.n();
  check_polygons(vertex, offset, n);
  const std::size_t un = static_cast<std::size_t>(n);
  area_.assign(un, 0.0);
  jratio_.assign(un, 0.0);
  normal_.assign(vertex.size(), 0.0);
  world_.assign(vertex.size(), 0.0);
  world_normal_.assign(vertex.size(), 0.0);
  world_stamp_.assign(un, -1);
  todo_.assign(un, 0);
  cs_.assign(2 * un, 0.0);
  sat_cache_.clear();  // its axes belong to the old shapes
  for (int i = 0; i < n; ++i) {
    const int o = offset[i], c = offset[i + 1] - o;
    const PolygonProperties q = polygon_properties(&vertex[2 * o], c);
    area_[i] = q.area;
    jratio_[i] = q.polar_moment / q.area;
    s.stone_radius[i] = q.bounding_radius;
    polygon_edge_normals(&vertex[2 * o], c, &normal_[2 * o]);
  }
  cached_vertex_ = vertex;
}

// the law is a disc's: a polygon resists rolling by its shape, and a moment capped on its bounding
// radius would have no physical basis, so polygon stones refuse mu_r > 0
void PolygonModel::check_params(const DEMParams& p) const {
  for (const auto& [name, value] : {std::pair<const char*, double>{"rolling_friction_stone", p.rolling_friction_stone},
                                    {"rolling_friction_wall", p.rolling_friction_wall}}) {
    if (value > 0.0)
      throw std::invalid_argument(std::string(name) + " = " + std::to_string(value) +
                                  " is outside the allowed range [0, 0] for polygon stones (the rolling resistance "
                                  "is a law for discs; polygons resist rolling by their shape)");
  }
}

// vertices edited through the views: their sections are derived again; and poses: no world geometry of
// a still stone is kept from before
void PolygonModel::prepare(DEMSystem& s) {
  if (cached_vertex_ != s.poly_vertex) update_properties(s);
  eval_ += 1;
}

double PolygonModel::volume(const DEMSystem&, int i) const { return polygon_stone_volume(area_[i]); }

double PolygonModel::inertia(const DEMSystem& s, int i, double mass) const {
  return 2.0 * s.params().inertia_factor * mass * jratio_[i];
}

double PolygonModel::nominal_diameter(const DEMSystem&, int i) const { return polygon_nominal_diameter(area_[i]); }

double PolygonModel::projected_area(const DEMSystem& s, int i) const {
  const int o = s.poly_offset[i];
  const PolygonProperties q = polygon_properties(&s.poly_vertex[2 * o], s.poly_offset[i + 1] - o);
  return 0.25 * polygon_nominal_diameter(area_[i]) * q.perimeter;
}

double PolygonModel::projected_area(const DEMSystem& s, int i, double ux, double uz) const {
  if (ux == 0.0 && uz == 0.0) return projected_area(s, i);
  const int o = s.poly_offset[i];
  const double w = polygon_width_across(&s.poly_vertex[2 * o], s.poly_offset[i + 1] - o, s.stone_angle[i], ux, uz);
  return 0.25 * kPi * polygon_nominal_diameter(area_[i]) * w;
}

double PolygonModel::stable_dt(const DEMSystem& s) const {
  const bool rot = s.params().flags & kDEMRotation;
  double lam = 0.0;
  for (int i = 0; i < s.n(); ++i) {
    if (!s.stone_active[i] || s.stone_fixed[i]) continue;
    const double m = s.mass(i), r = s.stone_radius[i];
    lam = std::max(lam, 1.0 / m + (rot ? r * r / inertia(s, i, m) : 0.0));
  }
  const double kn = s.stiffness_normal(), kt = s.stiffness_tangential();
  if (!(lam > 0.0) || kn <= 0.0) return INFINITY;
  const double w = std::sqrt(4.0 * std::max(kn, kt) * lam);
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

// the narrow phase of every listed pair: the touching ones' manifolds into contacts_ (in the pairs'
// order), their count returned; the springs of the others cleared, their energy (kt [N/m]) added to opened
std::size_t PolygonModel::touching(DEMSystem& s, double kt, double& opened) {
  ++eval_;  // the world geometry of the last evaluation is stale
  std::vector<ContactPair>& list = pairs(s);
  if (sat_builds_ != s.neighbour_builds() || sat_cache_.size() != list.size()) {
    sat_cache_.assign(list.size(), PairCache{});  // a new list: new pairs
    sat_builds_ = s.neighbour_builds();
  }
  PolygonFrame f{s.poly_offset.data(), s.poly_vertex.data(), normal_.data(),       world_.data(),
                 world_normal_.data(), world_stamp_.data(),  eval_,                s.stone_pos.data(),
                 s.stone_angle.data(),  inv_mass(s).data(),   s.stone_asleep.data()};
  // the stones that needed their world geometry at the last evaluation need it now, most likely: made
  // first (the pair loop then finds them made), their cosines and sines in one pass (the calls back to
  // back) and their vertices and normals in another
  int* todo = todo_.data();
  double* cs = cs_.data();
  int ntodo = 0;
  for (int i = 0; i < s.n(); ++i) {
    if (world_stamp_[i] != eval_ - 1) continue;
    if (f.kept(i)) {
      world_stamp_[i] = eval_;
      continue;
    }
    todo[ntodo++] = i;
  }
  for (int k = 0; k < ntodo; ++k) {
    const double a = s.stone_angle[todo[k]];
    cs[2 * k] = std::cos(a);
    cs[2 * k + 1] = std::sin(a);
  }
  for (int k = 0; k < ntodo; ++k) f.make(todo[k], cs[2 * k], cs[2 * k + 1]);
  const double* pos = s.stone_pos.data();
  const double* radius = s.stone_radius.data();
  PairCache* caches = sat_cache_.data();
  const std::size_t npairs = list.size();
  if (contacts_.size() < npairs) contacts_.resize(npairs);
  detail::PolygonContact* contacts = contacts_.data();
  std::size_t ntouch = 0;
  for (std::size_t pc = 0; pc < npairs; ++pc) {
    ContactPair& c = list[pc];
    PairCache& cache = caches[pc];
    const int i = c.i, j = c.j;
    const double dx = pos[2 * j] - pos[2 * i], dz = pos[2 * j + 1] - pos[2 * i + 1], rs = radius[i] + radius[j];
    auto clear = [&] {
      opened += c.points.dropped_energy(PointSprings{}, kt);
      c.points = PointSprings{};
    };
    if (dx * dx + dz * dz >= rs * rs) {  // bounding discs apart
      clear();
      cache.flip = -1;
      continue;
    }
    int flip = 0, edge = 0;
    if (!pair_reference(f, cache, i, j, dx, dz, rs, flip, edge)) {  // apart: cleared in place, no manifold
      clear();
      continue;
    }
    detail::PolygonContact& r = contacts[ntouch];
    pair_manifold(f, i, j, flip, edge, pair_incident(f, cache, i, j, flip, edge), r.m);
    if (r.m.count == 0) {  // overlapping by no point of the clipped edge: no spring kept
      clear();
      continue;
    }
    r.pair = static_cast<int>(pc);
    ++ntouch;
  }
  return ntouch;
}

// the forces of the touching pairs, in the pairs' order (a function of its own: fewer values live at once)
ContactTally PolygonModel::contact_forces(DEMSystem& s, double dt) {
  const DEMParams& p = s.params();
  const auto [friction, damp, kt] = contact_law(s);
  const double ct_factor = p.tangential_damping_factor;
  const double kn = s.stiffness_normal(), mu = p.friction_stone;
  ContactTally tally;
  const std::size_t ntouch = touching(s, kt, tally.dissipated);
  const double *pos = s.stone_pos.data(), *vel = s.stone_vel.data(), *omega = s.stone_omega.data();
  double *force = s.stone_force.data(), *torque = s.stone_torque.data();
  std::vector<ContactPair>& list = pairs(s);
  const detail::PolygonContact* contacts = contacts_.data();
  for (std::size_t t = 0; t < ntouch; ++t) {
    const detail::PolygonContact& r = contacts[t];
    const ContactManifold& m = r.m;
    ContactPair& c = list[static_cast<std::size_t>(r.pair)];
    const int i = c.i, j = c.j;
    const double xi0 = pos[2 * i], zi0 = pos[2 * i + 1], xj0 = pos[2 * j], zj0 = pos[2 * j + 1];
    const PointSprings prev = c.points;
    c.points = PointSprings{};  // written field by field below: no copy of a just-stored struct
    ++tally.count;
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
      c.points.id[k] = q.id;
      c.points.xi[k] = xi;
      tally.elastic += fc.energy_spring;
      tally.dissipated += fc.power_damp * dt + fc.energy_slip;
    }
    tally.dissipated += prev.dropped_energy(c.points, kt);
  }
  return tally;
}

ContactTally PolygonModel::wall_forces(DEMSystem& s, double dt) {
  const DEMParams& p = s.params();
  const auto [friction, damp, kt] = contact_law(s);
  const double kn = s.stiffness_normal();
  const std::size_t nw = p.walls.size();
  const WallCandidates cand = wall_candidates(s);
  const std::vector<double>& inv_m = inv_mass(s);
  const std::vector<double>& m_eff = mass_eff(s);
  std::vector<PointSprings>& springs = wall_point_springs(s);
  PolygonFrame f{s.poly_offset.data(), s.poly_vertex.data(), normal_.data(),       world_.data(),
                 world_normal_.data(), world_stamp_.data(),  eval_,                s.stone_pos.data(),
                 s.stone_angle.data(),  inv_m.data(),         s.stone_asleep.data()};
  ContactTally tally;
  for (std::size_t w = 0; w < nw; ++w) {
    const DEMWall& wall = p.walls[w];
    const auto [wx, wz] = DEMSystem::wall_unit_normal(wall);
    for (int c = cand.start[w]; c < cand.start[w + 1]; ++c) {
      const int i = cand.index[c];
      if (inv_m[i] == 0.0) continue;
      PointSprings& hist = springs[static_cast<std::size_t>(i) * nw + w];
      const double x0 = s.stone_pos[2 * i], z0 = s.stone_pos[2 * i + 1];
      const double d = (x0 - wall.point[0]) * wx + (z0 - wall.point[1]) * wz;
      const int o = s.poly_offset[i];
      if (d < s.stone_radius[i]) f.update(i);
      const ContactManifold m =
          d >= s.stone_radius[i] ? ContactManifold{}
                                : collide_polygon_wall(&world_[2 * o], &world_normal_[2 * o], s.poly_offset[i + 1] - o,
                                                       wall.point[0], wall.point[1], wx, wz);
      const PointSprings prev = hist;
      hist = PointSprings{};
      if (m.count > 0) ++tally.count;
      const double nx = m.normal[0], nz = m.normal[1];
      const double cn = m.count == 2 ? damp * std::sqrt(m_eff[i]) * kSqrtHalf : damp * std::sqrt(m_eff[i]);
      for (int k = 0; k < m.count; ++k) {
        const ContactManifold::Point& q = m.point[k];
        const double rx = q.x - x0, rz = q.z - z0;
        const double vx = s.stone_vel[2 * i] - s.stone_omega[i] * rz, vz = s.stone_vel[2 * i + 1] + s.stone_omega[i] * rx;
        const double vn = vx * nx + vz * nz;
        const double vt = -vx * nz + vz * nx;
        double xi = prev.spring(q.id);
        const ContactForce fc = friction ? linear_contact(q.depth, vn, vt, xi, dt, kn, kt, cn,
                                                          p.tangential_damping_factor * cn, wall.friction, true)
                                         : linear_contact(q.depth, vn, 0.0, xi, dt, kn, 0.0, cn, 0.0, 0.0, false);
        const double fx = -fc.fn * nx - fc.ft * nz, fz = -fc.fn * nz + fc.ft * nx;
        s.stone_force[2 * i] += fx;
        s.stone_force[2 * i + 1] += fz;
        s.stone_torque[i] += cross(rx, rz, fx, fz);
        hist.id[k] = q.id;
        hist.xi[k] = xi;
        tally.elastic += fc.energy_spring;
        tally.dissipated += fc.power_damp * dt + fc.energy_slip;
      }
      tally.dissipated += prev.dropped_energy(hist, kt);
    }
  }
  return tally;
}

// ---- state: the shapes and the manifold points' springs

void PolygonModel::export_state(const DEMSystem& s, DEMState& t) const {
  t.poly_vertex = s.poly_vertex;
  t.poly_offset = s.poly_offset;
  for (const ContactPair& c : StoneModel::pairs(const_cast<DEMSystem&>(s))) {
    if (c.points.id[0] < 0 && c.points.id[1] < 0) continue;
    t.poly_contact_i.push_back(c.i);
    t.poly_contact_j.push_back(c.j);
    for (int k = 0; k < 2; ++k) t.poly_contact_id.push_back(c.points.id[k]), t.poly_contact_xi.push_back(c.points.xi[k]);
  }
  for (const PointSprings& h : wall_point_springs(const_cast<DEMSystem&>(s)))
    for (int k = 0; k < 2; ++k) t.poly_wall_id.push_back(h.id[k]), t.poly_wall_xi.push_back(h.xi[k]);
}

// checked before anything is written
void PolygonModel::check_state(const DEMSystem& s, const DEMState& t) const {
  const std::size_t n = t.stone_radius.size(), nw = n * s.params().walls.size(), np = t.poly_contact_i.size();
  require_size("poly_offset", t.poly_offset, n + 1);
  check_polygons(t.poly_vertex, t.poly_offset, static_cast<int>(n));
  check_params(s.params());
  require_size("poly_contact_j", t.poly_contact_j, np);
  require_size("poly_contact_id", t.poly_contact_id, 2 * np);
  require_size("poly_contact_xi", t.poly_contact_xi, 2 * np);
  require_size("poly_wall_id", t.poly_wall_id, 2 * nw);
  require_size("poly_wall_xi", t.poly_wall_xi, 2 * nw);
  state::check_sorted_pairs("polygon contact", t.poly_contact_i, t.poly_contact_j, n);
}

// after check_state (the pair list is made anew)
void PolygonModel::import_state(DEMSystem& s, const DEMState& t) {
  set_shapes(s, t.poly_vertex, t.poly_offset);
  std::vector<ContactPair>& list = pairs(s);
  for (std::size_t k = 0; k < t.poly_contact_i.size(); ++k) {
    ContactPair c{t.poly_contact_i[k], t.poly_contact_j[k], 0.0, 0.0};
    for (int q = 0; q < 2; ++q) c.points.id[q] = t.poly_contact_id[2 * k + q], c.points.xi[q] = t.poly_contact_xi[2 * k + q];
    list.push_back(c);
  }
  std::vector<PointSprings>& springs = wall_point_springs(s);
  for (std::size_t k = 0; k < springs.size(); ++k)
    for (int q = 0; q < 2; ++q) springs[k].id[q] = t.poly_wall_id[2 * k + q], springs[k].xi[q] = t.poly_wall_xi[2 * k + q];
}

void PolygonModel::state_to_map(DEMState& t, StateMap& m) const {
  using state::to_double;
  m["poly_vertex"] = std::move(t.poly_vertex);
  m["poly_offset"] = to_double(t.poly_offset);
  m["poly_contact_i"] = to_double(t.poly_contact_i);
  m["poly_contact_j"] = to_double(t.poly_contact_j);
  m["poly_contact_id"] = to_double(t.poly_contact_id);
  m["poly_contact_xi"] = std::move(t.poly_contact_xi);
  m["poly_wall_id"] = to_double(t.poly_wall_id);
  m["poly_wall_xi"] = std::move(t.poly_wall_xi);
}

void PolygonModel::state_from_map(const StateMap& m, std::size_t n, std::size_t nwalls, DEMState& t) const {
  using state::entry;
  using state::from_double;
  const std::size_t nw = n * nwalls;
  t.poly_vertex = m.at("poly_vertex");
  from_double(t.poly_offset, entry(m, "poly_offset", n + 1));
  const auto& pi = entry(m, "poly_contact_i", state::kAnySize);
  from_double(t.poly_contact_i, pi);
  from_double(t.poly_contact_j, entry(m, "poly_contact_j", pi.size()));
  from_double(t.poly_contact_id, entry(m, "poly_contact_id", 2 * pi.size()));
  t.poly_contact_xi = entry(m, "poly_contact_xi", 2 * pi.size());
  from_double(t.poly_wall_id, entry(m, "poly_wall_id", 2 * nw));
  t.poly_wall_xi = entry(m, "poly_wall_xi", 2 * nw);
}

// ---- the flow's view

void PolygonModel::map_footprint(const DEMSystem& s, PorosityMapper& m, const double* x, const double* z) const {
  m.map_polygons(s.n(), x, z, s.stone_angle.data(), s.poly_vertex.data(), s.poly_offset.data(), s.stone_active.data());
}

// the 3D stone's projected area across the relative velocity
DragForce PolygonModel::drag(const DEMSystem& s, int i, const StoneFlowSample& f, double up, double wp, double rho,
                             double nu, DragLaw law, double* slope) const {
  const double a = projected_area(s, i, f.u - up, f.w_vel - wp), d = nominal_diameter(s, i);
  if (slope) *slope = stone_drag_slope_area(f, up, wp, d, a, rho, nu, law);
  return stone_drag_area(f, up, wp, d, a, rho, nu, law);
}

// the mean projected area and the nominal diameter
double PolygonModel::drag_relaxation_dt(const DEMSystem& s, int i, double relaxation, double mass, double vrel,
                                        double w, double rho, double nu) const {
  const double slope = drag_slope(vrel, nominal_diameter(s, i), w * 0.5 * rho * projected_area(s, i), nu, DragLaw::kPaper);
  return relaxation * mass / slope;
}

// ---- outline

int PolygonModel::world_vertices(const DEMSystem& s, int i, double* out) const {
  const int o = s.poly_offset[i], count = s.poly_offset[i + 1] - o;
  polygon_to_world(&s.poly_vertex[2 * o], count, s.stone_pos[2 * i], s.stone_pos[2 * i + 1], s.stone_angle[i], out);
  return count;
}

double PolygonModel::gap(const DEMSystem& s, int i, double x, double z) const {
  const double g = std::hypot(x - s.stone_pos[2 * i], z - s.stone_pos[2 * i + 1]) - s.stone_radius[i];
  if (g > 0.0) return g;  // a polygon lies inside its bounding disc
  double w[2 * kPolygonMaxVertices];
  const int count = world_vertices(s, i, w);
  return polygon_distance(w, count, x, z);
}

bool PolygonModel::covers(const DEMSystem& s, int i, double x, double z) const {
  const double dx = x - s.stone_pos[2 * i], dz = z - s.stone_pos[2 * i + 1];
  const double r = s.stone_radius[i];
  if (!(dx * dx + dz * dz < r * r)) return false;
  double w[2 * kPolygonMaxVertices];
  const int count = world_vertices(s, i, w);
  return polygon_contains(w, count, x, z);
}

double PolygonModel::outline_max(const DEMSystem& s, int i, const std::function<double(double, double)>& f) const {
  double w[2 * kPolygonMaxVertices];
  const int count = world_vertices(s, i, w);
  double out = -INFINITY;
  for (int k = 0; k < count; ++k) out = std::max(out, f(w[2 * k], w[2 * k + 1]));
  return out;
}

}  // namespace vofdem
