// Contact manifolds of convex polygons (see polygon_contact.h).
#include "vofdem/polygon_contact.h"

#include <algorithm>
#include <cmath>
#include <initializer_list>

namespace vofdem {

namespace {

// min_j n . (w_j - o) over the n2 vertices w of polygon 2, in two independent chains (even and odd j)
// that the processor overlaps; each term is the same expression, and a minimum does not depend on the
// order (but for the sign of a zero, which no comparison sees), so the value is the plain loop's
inline double min_projection(double nx, double nz, double ox, double oz, const double* v2, int n2) {
  double s0 = INFINITY, s1 = INFINITY;
  int j = 0;
  for (; j + 1 < n2; j += 2) {
    s0 = std::min(s0, nx * (v2[2 * j] - ox) + nz * (v2[2 * j + 1] - oz));
    s1 = std::min(s1, nx * (v2[2 * j + 2] - ox) + nz * (v2[2 * j + 3] - oz));
  }
  if (j < n2) s0 = std::min(s0, nx * (v2[2 * j] - ox) + nz * (v2[2 * j + 1] - oz));
  return std::min(s0, s1);
}

struct Separation {
  int edge = 0;
  double value = -INFINITY;
  double second = -INFINITY;  // the largest separation of the other edges
};

// the edge of polygon 1 whose normal separates polygon 2 the most (branch-free inner minimum: faster on
// these small polygons than walking the support vertex round, whose branches are unpredictable)
Separation max_separation(const double* v1, const double* u1, int n1, const double* v2, int n2) {
  Separation best;
  for (int k = 0; k < n1; ++k) {
    const double nx = u1[2 * k], nz = u1[2 * k + 1];
    const double ox = v1[2 * k], oz = v1[2 * k + 1];
    const double s = min_projection(nx, nz, ox, oz, v2, n2);
    if (s > best.value) {
      best.second = best.value;
      best.value = s;
      best.edge = k;
    } else if (s > best.second) {
      best.second = s;
    }
  }
  return best;
}

// the edge of polygon 2 most anti-parallel to n
int incident_edge(const double* u2, int n2, double nx, double nz) { return polygon_incident_edge(u2, n2, nx, nz); }

// the id of a point: the vertex of A and the vertex of B that make it, whichever face is the reference
// (a face-on-face point keeps its id when the reference face changes sides)
int make_id(int flip, int ref_vertex, int inc_vertex) {
  return flip ? (inc_vertex << 8) | ref_vertex : (ref_vertex << 8) | inc_vertex;
}

// adds the point p (separation s from the reference face of normal n) if it penetrates
void add_point(ContactManifold& m, double px, double pz, double s, double nx, double nz, int id) {
  if (!(s < 0.0)) return;
  ContactManifold::Point& q = m.point[m.count++];
  q.x = px - 0.5 * s * nx;
  q.z = pz - 0.5 * s * nz;
  q.depth = -s;
  q.id = id;
}

}  // namespace

int polygon_incident_edge(const double* u2, int n2, double nx, double nz, double* margin) {
  int edge = 0;
  double lo = INFINITY, next = INFINITY;
  for (int k = 0; k < n2; ++k) {
    const double d = nx * u2[2 * k] + nz * u2[2 * k + 1];
    if (d < lo) {
      next = lo;
      lo = d;
      edge = k;
    } else if (d < next) {
      next = d;
    }
  }
  if (margin) *margin = next - lo;
  return edge;
}

void polygon_edge_normals(const double* v, int n, double* out) {
  for (int k = 0; k < n; ++k) {
    const int l = k + 1 == n ? 0 : k + 1;
    const double ex = v[2 * l] - v[2 * k], ez = v[2 * l + 1] - v[2 * k + 1];
    const double len = std::hypot(ex, ez);
    // the right perpendicular of a counter-clockwise edge points outwards
    out[2 * k] = ez / len;
    out[2 * k + 1] = -ex / len;
  }
}

SatResult polygon_sat(const double* va, const double* ua, int na, const double* vb, const double* ub, int nb) {
  SatResult r;
  const Separation sa = max_separation(va, ua, na, vb, nb);
  if (!(sa.value < 0.0)) return {sa.value, 0, sa.edge, 0.0};
  const Separation sb = max_separation(vb, ub, nb, va, na);
  if (!(sb.value < 0.0)) return {sb.value, 1, sb.edge, 0.0};
  r.flip = sb.value > sa.value ? 1 : 0;
  r.value = r.flip ? sb.value : sa.value;
  r.edge = r.flip ? sb.edge : sa.edge;
  r.margin = r.value - (r.flip ? std::max(sb.second, sa.value) : std::max(sa.second, sb.value));
  return r;
}

double polygon_axis_separation(const double* v1, const double* u1, int edge, const double* v2, int n2) {
  const double nx = u1[2 * edge], nz = u1[2 * edge + 1];
  return min_projection(nx, nz, v1[2 * edge], v1[2 * edge + 1], v2, n2);
}

ContactManifold collide_polygons(const double* va, const double* ua, int na, const double* vb, const double* ub,
                                 int nb) {
  const SatResult sat = polygon_sat(va, ua, na, vb, ub, nb);
  if (!(sat.value < 0.0)) return ContactManifold{};
  return polygon_manifold(va, ua, na, vb, ub, nb, sat.flip, sat.edge);
}

ContactManifold polygon_manifold(const double* va, const double* ua, int na, const double* vb, const double* ub, int nb,
                                 int flip, int edge, int incident) {
  ContactManifold m;
  const double* v1 = flip ? vb : va;
  const double* u1 = flip ? ub : ua;
  const int n1 = flip ? nb : na;
  const double* v2 = flip ? va : vb;
  const double* u2 = flip ? ua : ub;
  const int n2 = flip ? na : nb;
  const int i11 = edge, i12 = i11 + 1 == n1 ? 0 : i11 + 1;
  const double nx = u1[2 * i11], nz = u1[2 * i11 + 1];
  const int i21 = incident >= 0 ? incident : incident_edge(u2, n2, nx, nz), i22 = i21 + 1 == n2 ? 0 : i21 + 1;
  // along the reference edge from v11 to v12; the incident edge runs the other way (v22 near v11)
  const double tx = -nz, tz = nx;
  const double* v11 = v1 + 2 * i11;
  const double* v12 = v1 + 2 * i12;
  const double* v21 = v2 + 2 * i21;
  const double* v22 = v2 + 2 * i22;
  const double upper1 = (v12[0] - v11[0]) * tx + (v12[1] - v11[1]) * tz;
  const double upper2 = (v21[0] - v11[0]) * tx + (v21[1] - v11[1]) * tz;
  const double lower2 = (v22[0] - v11[0]) * tx + (v22[1] - v11[1]) * tz;
  double lx = v22[0], lz = v22[1], hx = v21[0], hz = v21[1];
  const double span = upper2 - lower2;
  if (span > 1e-12 * upper1) {
    if (lower2 < 0.0) {
      const double t = -lower2 / span;
      lx = v22[0] + t * (v21[0] - v22[0]);
      lz = v22[1] + t * (v21[1] - v22[1]);
    }
    if (upper2 > upper1) {
      const double t = (upper1 - lower2) / span;
      hx = v22[0] + t * (v21[0] - v22[0]);
      hz = v22[1] + t * (v21[1] - v22[1]);
    }
  }
  const double sl = (lx - v11[0]) * nx + (lz - v11[1]) * nz;
  const double sh = (hx - v11[0]) * nx + (hz - v11[1]) * nz;
  add_point(m, lx, lz, sl, nx, nz, make_id(flip, i11, i22));
  add_point(m, hx, hz, sh, nx, nz, make_id(flip, i12, i21));
  // the normal from A to B
  m.normal[0] = flip ? -nx : nx;
  m.normal[1] = flip ? -nz : nz;
  return m;
}

double polygon_separation(const double* va, const double* ua, int na, const double* vb, const double* ub, int nb) {
  return std::max(max_separation(va, ua, na, vb, nb).value, max_separation(vb, ub, nb, va, na).value);
}

ContactManifold collide_polygon_wall(const double* v, const double* u, int n, double px, double pz, double wx,
                                     double wz) {
  ContactManifold m;
  const int i1 = incident_edge(u, n, wx, wz), i2 = i1 + 1 == n ? 0 : i1 + 1;
  for (int k : {i1, i2}) {
    const double s = (v[2 * k] - px) * wx + (v[2 * k + 1] - pz) * wz;
    add_point(m, v[2 * k], v[2 * k + 1], s, wx, wz, k);
  }
  m.normal[0] = -wx;
  m.normal[1] = -wz;
  return m;
}

}  // namespace vofdem
