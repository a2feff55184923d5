// Contact manifolds of convex polygon stones, in the manner of Box2D v3 (E. Catto, manifold.c):
// separating axes, a reference face and an incident face, the incident face clipped to the reference
// face's side planes, giving a manifold of up to two points.
//
//   separation  s_A = max_k min_j  u_k . (w_j - v_k)      (u_k: outward normal of A's edge k from
//                                                          vertex v_k; w_j: B's vertices)
//   contact     max(s_A, s_B) < 0; reference polygon A unless s_B > s_A (ties keep A: deterministic)
//   incident    the edge of the other polygon whose normal is most anti-parallel to the reference normal
//   points      the incident edge clipped to the reference edge's extent; each clipped vertex with
//               s = (p - v_ref) . n < 0 is a manifold point of depth delta = -s, placed half-way
//               between the incident vertex and the reference face (the middle of the overlap)
//   feature id  (vertex of A, vertex of B) of the reference and incident edges' ends that make the
//               point: the same contact point keeps its id from step to step, also when the reference
//               face changes sides (two faces lying on each other), so its tangential spring is carried
//               over (DEMSystem)
//
// A polygon against a half-plane wall is the same with the wall line as the reference face: the
// incident edge is the polygon's edge most anti-parallel to the wall normal (it holds the deepest
// vertex), its vertices below the wall line are the points.
//
// At each point DEMSystem applies the disc's spring-dashpot normal force and Coulomb-capped tangential
// spring (dem_contact.h) with the point's depth and relative velocity.
//
// No rounding radius: the polygons are sharp, so the porosity mapping stays an exact polygon clip
// and the depth is the SAT penetration. The normal can jump where two separations tie (two corners
// meeting); with the soft contact's overlaps (~1e-5 m for 5 cm stones) this is rare and the force
// stays bounded by k_n delta.
//
// Reference: E. Catto, Box2D v3 (2024), src/manifold.c (b2CollidePolygons, b2ClipPolygons), MIT licence;
// our own code.
#pragma once

#include <cmath>

namespace vofdem {

struct ContactManifold {
  struct Point {
    double x = 0.0, z = 0.0;  // contact point (world) [m]
    double depth = 0.0;       // overlap delta > 0 [m]
    int id = 0;               // feature id (stable while the same features touch)
  };
  int count = 0;              // points in contact: 0, 1 or 2
  double normal[2] = {0, 0};  // unit normal from the first body to the second
  Point point[2];
};

// outward unit normals of the n edges of a CCW polygon (edge k from vertex k to k + 1)
void polygon_edge_normals(const double* v, int n, double* out);

// manifold of two convex CCW polygons given in the world frame: na vertices va with edge normals ua,
// nb vertices vb with normals ub; normal from A to B. It is polygon_sat, then polygon_manifold.
ContactManifold collide_polygons(const double* va, const double* ua, int na, const double* vb, const double* ub,
                                 int nb);

// the separating-axis test of two polygons (arguments as collide_polygons)
struct SatResult {
  double value = -INFINITY;  // the largest separation over both polygons' edge normals [m] (>= 0: apart)
  int flip = 0;              // 0: that axis is an edge normal of A (the reference face), 1: of B
  int edge = 0;              // its edge
  double margin = 0.0;       // value minus the largest separation of every other axis [m]; 0 if apart
};
SatResult polygon_sat(const double* va, const double* ua, int na, const double* vb, const double* ub, int nb);
// the separation along polygon 1's edge normal `edge` alone [m] (the same arithmetic as polygon_sat)
double polygon_axis_separation(const double* v1, const double* u1, int edge, const double* v2, int n2);
// the manifold clipped from the reference face `edge` of A (flip 0) or of B (flip 1); `incident`: the
// other polygon's incident edge if known (polygon_incident_edge), -1 to find it
ContactManifold polygon_manifold(const double* va, const double* ua, int na, const double* vb, const double* ub, int nb,
                                 int flip, int edge, int incident = -1);
// the incident edge of polygon 2 (n2 edge normals u2) for the reference normal n: the edge whose normal
// is most anti-parallel to n (the first of equals); margin (if given): the next smallest n . u minus the
// smallest [-], how far the choice is from changing
int polygon_incident_edge(const double* u2, int n2, double nx, double nz, double* margin = nullptr);

// the larger of the two separations s_A, s_B [m]: > 0 apart (by at least that much along some axis),
// < 0 overlapping (by that depth along the best axis)
double polygon_separation(const double* va, const double* ua, int na, const double* vb, const double* ub, int nb);

// manifold of a convex CCW polygon (n vertices v, edge normals u, world frame) with the half-plane wall
// through (px, pz) whose unit normal (wx, wz) points out of the solid; normal from the polygon into the wall
ContactManifold collide_polygon_wall(const double* v, const double* u, int n, double px, double pz, double wx,
                                     double wz);

}  // namespace vofdem
