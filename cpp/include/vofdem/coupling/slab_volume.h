// Volume of a 3D sphere inside the slab a flow cell stands for: the 2D vertical (x, z) flow's cell
// dx x dz stands for the slab dx x dz x B across the flume width B, and its solid fraction is the
// stones' volume in that slab over dx dz B (as MFiX's 2D flow over a slab of spheres). A sphere lies
// between the side walls, so the slab never cuts it in y, and
//
//   V_cell = int_x0^x1 int_z0^z1 2 sqrt(R^2 - (x - x_c)^2 - (z - z_c)^2)_+ dz dx.
//
// Closed form, by the corner primitive (u = x - x_c, w = z - z_c, both clamped to [-R, R]):
//   P(u, w) = int_0^u int_0^w 2 sqrt(R^2 - x^2 - z^2)_+ dz dx
//           = [2 u w q + u (3R^2 - u^2) atan2(w, q) + w (3R^2 - w^2) atan2(u, q) - 2 R^3 atan2(u w, R q)] / 3,
//   q = sqrt(max(R^2 - u^2 - w^2, 0)),
// odd in u and in w, so that inclusion-exclusion over the four corners gives
//   V_cell = P(u1, w1) - P(u0, w1) - P(u1, w0) + P(u0, w0).
// Derivation: int sqrt(q0^2 - z^2) dz = z q/2 + (q0^2/2) atan(z/q) (q0^2 = R^2 - x^2) integrated once
// more in x; outside the disk u^2 + w^2 > R^2, q = 0 makes the atan2 terms pi/2, and the same
// expression is the integral over the rectangle's part inside the disk (each column then reaches the
// circle). The quarter-space volume of the brief, the sphere with x < a and z < b, is
//   F(a, b) = P(a, b) + P(a, R) + P(R, b) + P(R, R),   F(R, R) = 4/3 pi R^3.
// Evaluated at the grid nodes and differenced (sphere_cell_volumes), the parts of a sphere telescope to
// its volume inside the grid to round-off.
//
// A clump's sub-spheres overlap, so their sum counts each overlap more than once. The standard
// approximation is used: each sub-sphere's parts are scaled by V_union / sum_k V_k (clump.h), so a
// clump's parts sum to its union volume exactly while the overlap is spread over its sub-spheres; the
// local error is measured in test_slab_volume (Clump.ScaledPartsAgainstUnionByBruteForce).
//
// Reference: MFiX, model/des/check_solids_common_discrete.f (a 2D flow over a slab of 3D spheres:
// solid fraction = particle volume / (cell area x slab depth)). The closed form above is derived here and
// checked against a brute-force integration in the tests.
#pragma once

#include <vector>

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "vofdem/stones/clump.h"

namespace vofdem {

// P(u, w) [m^3]: the sphere of radius r [m] centred at the origin, integrated over [0, u] x [0, w] in
// (x, z) (signed: odd in u and in w); any u, w
double sphere_corner_volume(double u, double w, double r);

// volume [m^3] of the sphere (centre x_c, z_c [m], radius r [m]) inside [x0, x1] x [z0, z1] x (all y).
// Throws std::invalid_argument if r is not finite and > 0 or a bound is not finite or x1 < x0, z1 < z0.
double sphere_slab_volume(double xc, double zc, double r, double x0, double x1, double z0, double z1);

// one cell of a tensor grid and the volume in it
struct CellVolume {
  int i = 0;            // column, [0, nx)
  int k = 0;            // row, [0, nz)
  double volume = 0.0;  // [m^3]
};

// appends the cells of the grid (edges x_edges, z_edges [m], strictly increasing, at least 2 each) that
// the sphere meets, column by column, with the sphere's volume in each; the part outside the grid is
// not counted. Throws std::invalid_argument for bad edges or radius.
void sphere_cell_volumes(double xc, double zc, double r, const std::vector<double>& x_edges,
                         const std::vector<double>& z_edges, std::vector<CellVolume>& out);

// the same for a clump at position (its centroid) [m] and orientation (principal frame to world): each
// sub-sphere's parts scaled by V_union / sum V_k, summed per cell
void clump_cell_volumes(const Clump& clump, const Eigen::Vector3d& position, const Eigen::Quaterniond& orientation,
                        const std::vector<double>& x_edges, const std::vector<double>& z_edges,
                        std::vector<CellVolume>& out);

// the clump's (scaled) volume inside one slab [x0, x1] x [z0, z1] [m^3]
double clump_slab_volume(const Clump& clump, const Eigen::Vector3d& position, const Eigen::Quaterniond& orientation,
                         double x0, double x1, double z0, double z1);

}  // namespace vofdem
