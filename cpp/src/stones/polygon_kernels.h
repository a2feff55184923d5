// Inline kernels of the polygon contact (polygon_contact.h), private to the library: the world transform,
// the vertex minimum along an edge normal, the separating-axis test with its runner-up axis, the incident
// edge, and the clipping of the incident edge against the reference face. polygon_contact.cpp and the
// DEM's contact loop (polygon_model.cpp) both call them, so the loop inlines them and both do the same
// arithmetic, operation for operation.
#pragma once

#include <algorithm>
#include <cmath>

#include "vofdem/stones/polygon_contact.h"

namespace vofdem::detail {

// the n points v (x, z pairs) turned by the angle of cosine c and sine s and moved by (x, z)
inline void to_world(const double* v, int n, double x, double z, double c, double s, double* out) {
  for (int k = 0; k < n; ++k) {
    const double bx = v[2 * k], bz = v[2 * k + 1];
    out[2 * k] = x + c * bx - s * bz;
    out[2 * k + 1] = z + s * bx + c * bz;
  }
}

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

// the edge of polygon 1 whose normal separates polygon 2 the most (the first of equals), and the next
// two separations (branch-free inner minimum: faster on these small polygons than walking the support
// vertex round, whose branches are unpredictable)
struct Separation {
  int edge = 0;
  double value = -INFINITY;
  int edge2 = 0;               // the edge of the second largest
  double second = -INFINITY;   // the largest separation of the other edges
  double third = -INFINITY;    // the largest separation of the edges other than these two
};
inline Separation max_separation(const double* v1, const double* u1, int n1, const double* v2, int n2) {
  Separation best;
  for (int k = 0; k < n1; ++k) {
    const double s = min_projection(u1[2 * k], u1[2 * k + 1], v1[2 * k], v1[2 * k + 1], v2, n2);
    if (s > best.value) {
      best.third = best.second;
      best.second = best.value;
      best.edge2 = best.edge;
      best.value = s;
      best.edge = k;
    } else if (s > best.second) {
      best.third = best.second;
      best.second = s;
      best.edge2 = k;
    } else if (s > best.third) {
      best.third = s;
    }
  }
  return best;
}

// the separating-axis test (polygon_sat), and, when the polygons overlap, the runner-up axis (flip2,
// edge2) and its lead over every other axis, margin2 [m]
struct SatTop2 {
  SatResult best;
  int flip2 = 0, edge2 = 0;
  double margin2 = 0.0;
};
inline SatTop2 sat_top2(const double* va, const double* ua, int na, const double* vb, const double* ub, int nb) {
  SatTop2 r;
  const Separation sa = max_separation(va, ua, na, vb, nb);
  if (!(sa.value < 0.0)) {
    r.best = {sa.value, 0, sa.edge, 0.0};
    return r;
  }
  const Separation sb = max_separation(vb, ub, nb, va, na);
  if (!(sb.value < 0.0)) {
    r.best = {sb.value, 1, sb.edge, 0.0};
    return r;
  }
  const int flip = sb.value > sa.value ? 1 : 0;
  const Separation& own = flip ? sb : sa;
  const Separation& other = flip ? sa : sb;
  r.best.flip = flip;
  r.best.value = own.value;
  r.best.edge = own.edge;
  r.best.margin = own.value - std::max(own.second, other.value);
  // the runner-up: the own polygon's second or the other's best; the third the best of the rest
  if (own.second > other.value) {
    r.flip2 = flip;
    r.edge2 = own.edge2;
    r.margin2 = own.second - std::max(own.third, other.value);
  } else {
    r.flip2 = 1 - flip;
    r.edge2 = other.edge;
    r.margin2 = other.value - std::max(own.second, other.second);
  }
  return r;
}

// the edge of polygon 2 (n2 edge normals u2) most anti-parallel to n, the first of equals; margin (if
// given): the next smallest n . u minus the smallest
inline int incident_edge(const double* u2, int n2, double nx, double nz, double* margin) {
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

// the id of a point: the vertex of A and the vertex of B that make it, whichever face is the reference
// (a face-on-face point keeps its id when the reference face changes sides)
inline int make_id(int flip, int ref_vertex, int inc_vertex) {
  return flip ? (inc_vertex << 8) | ref_vertex : (ref_vertex << 8) | inc_vertex;
}

// adds the point p (separation s from the reference face of normal n) if it penetrates
template <class M>
inline void add_point(M& m, double px, double pz, double s, double nx, double nz, int id) {
  if (!(s < 0.0)) return;
  ContactManifold::Point& q = m.point[m.count++];
  q.x = px - 0.5 * s * nx;
  q.z = pz - 0.5 * s * nz;
  q.depth = -s;
  q.id = id;
}

// the manifold of the reference edge v11 -> v12 (vertices i11, i12 of the reference polygon, outward
// normal n) and the incident edge v21 -> v22 (vertices i21, i22 of the other): the incident edge
// clipped to the reference edge's extent, each clipped end below the reference face a point; flip 1
// when the reference polygon is B (the normal is then turned to point from A to B); written into m (a
// ContactManifold, not zeroed first: point[k] for k >= count keeps what it held)
template <class M>
inline void clip_manifold(const double* v11, const double* v12, const double* v21, const double* v22, double nx,
                          double nz, int flip, int i11, int i12, int i21, int i22, M& m) {
  m.count = 0;
  // along the reference edge from v11 to v12; the incident edge runs the other way (v22 near v11)
  const double tx = -nz, tz = nx;
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
}

}  // namespace vofdem::detail
