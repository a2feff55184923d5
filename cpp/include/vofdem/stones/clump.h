// A clump: a rigid stone made of overlapping spheres (Favier et al. 1999; Ferellec & McDowell 2010), its
// volume, centre of mass and inertia tensor integrated over the UNION of the spheres (each overlap
// counted once), its principal frame, and a small library of quarried-stone shapes.
//
// Moments of a region Omega (per unit density):  m0 = int dV,  m1 = int x dV,  m2 = int x x^T dV
//   centroid  X = m1 / m0;   second moment about it  S = m2 - m0 X X^T
//   inertia   J = rho (tr(S) 1 - S)   [kg m^2];   principal frame: J = R diag(J1 <= J2 <= J3) R^T
//
// The union is split exactly into the power (Laguerre) cells of its spheres (Edelsbrunner 1995):
//   union = U_i (B_i n P_i),  P_i = {x : |x - c_i|^2 - r_i^2 <= |x - c_j|^2 - r_j^2 for all j},
// whose faces are the planes of the spheres' intersection circles. Along a ray x = c_i + s w from a
// sphere's centre, B_i n P_i is one interval [s_lo, s_hi] (each j bounds s by
// 2 s w.(c_j - c_i) <= |c_j - c_i|^2 + r_i^2 - r_j^2), so the radial integrals of s^2, s^3, s^4 are exact
// and only the directions are summed: Gauss-Legendre in cos(theta) (n nodes) times the trapezoidal rule
// in phi (2n nodes), per cell. The rays start at the cell's centroid (estimated at n = 16; any interior
// point of the convex cell will do), so that no face passes close to their origin. The integrand is
// continuous with kinks where the exit face changes, and the rule converges about as n^-2: at the default
// n = 128 the relative errors of the volume are <= 1e-5 and of the inertia tensor <= 4e-5 for the library
// shapes and for two overlapping spheres (test_clump checks 2e-5 and 1e-4, against the exact formula or
// n = 512). The partition is symmetric under any symmetry of the spheres that the grid shares (mirrors in
// x, y, z), so symmetric clumps have exact principal axes.
//
// Two spheres (and one) are integrated exactly instead: union = B_1 + B_2 - lens, the lens being the
// two caps cut off by the plane of the intersection circle (derivation in clump.cpp).
//
// References: Favier, J. F., Abbaspour-Fard, M. H., Kremmer, M. & Raji, A. O. (1999), Eng. Computations
// 16(4), 467-480 (multi-sphere particles). Ferellec, J.-F. & McDowell, G. R. (2010), Granular Matter 12,
// 459-467 (clumps of overlapping spheres for ballast). Edelsbrunner, H. (1995), The union of balls and
// its dual shape, Discrete Comput. Geom. 13, 415-440.
#pragma once

#include <string>
#include <vector>

#include <Eigen/Core>
#include <Eigen/Geometry>

namespace vofdem {

// one sphere of a clump: centre [m] and radius [m]
struct ClumpSphere {
  Eigen::Vector3d centre = Eigen::Vector3d::Zero();
  double radius = 0.0;
};

// the moments m0 [m^3], m1 [m^4], m2 [m^5] of a region (per unit density); additive over disjoint parts
struct VolumeMoments {
  double m0 = 0.0;
  Eigen::Vector3d m1 = Eigen::Vector3d::Zero();
  Eigen::Matrix3d m2 = Eigen::Matrix3d::Zero();
  VolumeMoments operator+(const VolumeMoments& o) const;
  VolumeMoments operator-(const VolumeMoments& o) const;
  Eigen::Vector3d centroid() const { return m1 / m0; }
  // inertia tensor per unit density about the centroid, tr(S) 1 - S [m^5]
  Eigen::Matrix3d inertia_about_centroid() const;
};

// default order n of the direction quadrature (n x 2n directions per sphere)
inline constexpr int kClumpQuadratureOrder = 128;

// moments of one sphere (exact)
VolumeMoments sphere_moments(const ClumpSphere& s);

// moments of the union of two spheres (exact: B_1 + B_2 - lens; a sphere inside the other: the larger)
VolumeMoments sphere_pair_union_moments(const ClumpSphere& a, const ClumpSphere& b);

// moments of the union of any number of spheres by the power-cell ray quadrature of order n >= 2
VolumeMoments union_moments_quadrature(const std::vector<ClumpSphere>& spheres, int order = kClumpQuadratureOrder);

// moments of the union: exact for one or two spheres, the quadrature of order n otherwise
VolumeMoments union_moments(const std::vector<ClumpSphere>& spheres, int order = kClumpQuadratureOrder);

// the bounding radius [m] about the origin, max_k |c_k| + r_k: a clump stone's stone_radius (ClumpModel,
// its restart and the packing generator all take it from here, so their radii are the same bits)
double bounding_radius(const std::vector<ClumpSphere>& spheres);

// a clump stored in its principal frame: centroid at the origin, principal moments ascending
class Clump {
 public:
  // spheres in any frame (each radius finite and > 0, at least one; centres finite); throws
  // std::invalid_argument naming the offending sphere otherwise
  explicit Clump(const std::vector<ClumpSphere>& spheres, int order = kClumpQuadratureOrder);

  const std::vector<ClumpSphere>& spheres() const { return spheres_; }  // principal frame [m]
  double volume() const { return volume_; }                             // union volume [m^3]
  double sphere_volume_sum() const;                                     // sum of the spheres [m^3]
  double equivalent_diameter() const;                                   // (6 V / pi)^(1/3) [m]
  double bounding_radius() const;                                       // about the centroid [m]
  const Eigen::Vector3d& principal_inertia() const { return inertia_; }  // per unit density [m^5]
  const Eigen::Vector3d& input_centroid() const { return centroid_; }   // centroid in the input frame [m]
  // the principal frame in the input frame: x_input = input_centroid() + orientation() * x_principal
  const Eigen::Quaterniond& orientation() const { return orientation_; }
  // lengths along the principal axes, max - min of c_k +- r over the spheres [m]
  Eigen::Vector3d principal_extents() const;
  // the same sorted long >= intermediate >= short, over the long one (1, p, q) [-]
  Eigen::Vector3d aspect_ratios() const;
  // the same clump scaled by factor > 0 about its centroid: lengths times f, volume f^3, moments f^5 (no
  // new integration: the packing generator draws many sizes of a few shapes)
  Clump scaled(double factor) const;

 private:
  std::vector<ClumpSphere> spheres_;
  double volume_ = 0.0;
  Eigen::Vector3d inertia_ = Eigen::Vector3d::Zero();
  Eigen::Vector3d centroid_ = Eigen::Vector3d::Zero();
  Eigen::Quaterniond orientation_ = Eigen::Quaterniond::Identity();
};

// the library of quarried-stone shapes, long : intermediate : short = 1 : p : q
//   pair_2      two equal spheres on the long axis            (1 : q : q, p is not used)
//   triangle_3  three equal spheres in the long-intermediate plane, an isosceles triangle
//   tetra_4     two spheres on the long axis below, two on the intermediate axis above
//   box_8       eight spheres at the corners of a box
// scaled so that the union volume is pi d_eq^3 / 6. Ranges: d_eq > 0 [m], q in [0.55, 1] (the spheres
// overlap their neighbours), p in [q, 1]. Throws std::invalid_argument naming the parameter otherwise.
Clump quarried_stone(const std::string& name, double d_eq, double ratio_intermediate = 0.8,
                     double ratio_short = 0.6, int order = kClumpQuadratureOrder);

// the names quarried_stone() accepts
std::vector<std::string> quarried_stone_names();

// a mix of library shapes for the weir's packing generator (weir_packing_3d.h, shape "clump"): each stone
// draws one of `names` with equal chances, aspect ratios 1 : p : q. The default, the 2-, 3- and 4-sphere
// shapes, spans elongated to blocky stones at 3 spheres per stone on average (box_8 doubles the contact
// cost for a shape that tetra_4 already makes blocky)
struct ClumpMix {
  std::vector<std::string> names{"pair_2", "triangle_3", "tetra_4"};  // each one of quarried_stone_names()
  double ratio_intermediate = 0.8;  // p [-], in [ratio_short, 1]
  double ratio_short = 0.6;         // q [-], in [0.55, 1]
};

// throws std::invalid_argument naming the field (clump_names, clump_ratio_intermediate, clump_ratio_short)
void check_clump_mix(const ClumpMix& mix);

}  // namespace vofdem
