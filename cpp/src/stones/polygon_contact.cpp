// Contact manifolds of convex polygons (see polygon_contact.h).
#include "vofdem/stones/polygon_contact.h"

#include <algorithm>
#include <cmath>
#include <initializer_list>

#include "stones/polygon_kernels.h"

namespace vofdem {

namespace {

using detail::max_separation;

// the edge of polygon 2 most anti-parallel to n
int incident_edge(const double* u2, int n2, double nx, double nz) {
  return detail::incident_edge(u2, n2, nx, nz, nullptr);
}

}  // namespace

int polygon_incident_edge(const double* u2, int n2, double nx, double nz, double* margin) {
  return detail::incident_edge(u2, n2, nx, nz, margin);
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
  return detail::sat_top2(va, ua, na, vb, ub, nb).best;
}

double polygon_axis_separation(const double* v1, const double* u1, int edge, const double* v2, int n2) {
  const double nx = u1[2 * edge], nz = u1[2 * edge + 1];
  return detail::min_projection(nx, nz, v1[2 * edge], v1[2 * edge + 1], v2, n2);
}

ContactManifold collide_polygons(const double* va, const double* ua, int na, const double* vb, const double* ub,
                                 int nb) {
  const SatResult sat = polygon_sat(va, ua, na, vb, ub, nb);
  if (!(sat.value < 0.0)) return ContactManifold{};
  return polygon_manifold(va, ua, na, vb, ub, nb, sat.flip, sat.edge);
}

ContactManifold polygon_manifold(const double* va, const double* ua, int na, const double* vb, const double* ub, int nb,
                                 int flip, int edge, int incident) {
  const double* v1 = flip ? vb : va;
  const double* u1 = flip ? ub : ua;
  const int n1 = flip ? nb : na;
  const double* v2 = flip ? va : vb;
  const double* u2 = flip ? ua : ub;
  const int n2 = flip ? na : nb;
  const int i11 = edge, i12 = i11 + 1 == n1 ? 0 : i11 + 1;
  const double nx = u1[2 * i11], nz = u1[2 * i11 + 1];
  const int i21 = incident >= 0 ? incident : incident_edge(u2, n2, nx, nz), i22 = i21 + 1 == n2 ? 0 : i21 + 1;
  ContactManifold m;
  detail::clip_manifold(v1 + 2 * i11, v1 + 2 * i12, v2 + 2 * i21, v2 + 2 * i22, nx, nz, flip, i11, i12, i21, i22, m);
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
    detail::add_point(m, v[2 * k], v[2 * k + 1], s, wx, wz, k);
  }
  m.normal[0] = -wx;
  m.normal[1] = -wz;
  return m;
}

}  // namespace vofdem
