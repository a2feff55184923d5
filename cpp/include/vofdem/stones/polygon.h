// Convex polygon stones: shape generation and the properties of the matching 3D stone.
//
// A stone of polygon shape is a convex polygon in the vertical x-z plane, its vertices stored
// counter-clockwise in the body frame whose origin is the polygon's centroid. Its size is the
// nominal diameter d, the diameter of the disc of equal area:
//
//   A = pi d^2 / 4,   r_A = sqrt(A / pi) = d / 2                                   (size)
//
// The matching 3D stone is the body whose mid-section is the polygon and whose third semi-axis is
// r_A (the stone's thickness normal to the flume's plane is its equal-area diameter d):
//
//   V = (4/3) A r_A                                                                 (volume)
//   I = 2 f M J_A / A,   J_A = int_A (x^2 + z^2) dA (about the centroid)            (inertia)
//
// with f = DEMParams::inertia_factor (0.4 default). Why: for an ellipsoid of semi-axes a, b (in the
// plane) and c (normal to it), A = pi a b and V = (4/3) pi a b c = (4/3) A c exactly, and its moment
// about the c-axis is M (a^2 + b^2) / 5 = 0.8 M J_A / A since J_A / A = (a^2 + b^2) / 4. Taking c = r_A
// (the geometric mean sqrt(a b) of an ellipse) makes a disc of diameter d the sphere of diameter d
// (V = pi d^3 / 6, I = 0.4 M r^2), so a polygon stone has the mass of the sphere of its nominal
// diameter and the disc stones are the special case of a round section. f = 0.5 gives the 2D prism
// (I = M J_A / A), as it gives the cylinder for discs. d is then the diameter of the sphere of equal
// volume, (6 V / pi)^(1/3) = D_n / 0.806 with rock sizing's nominal diameter D_n = V^(1/3); with the
// usual D_n50 ~ 0.84 D_50 (sieve size) d is about 0.96 of the sieve size, so the paper's mean size
// (4.8 cm) is taken as d.
//
// Generation (random_convex_polygon): n vertices, n uniform in [vertices_min, vertices_max]; polar
// angles 2 pi k / n + phase, each jittered by up to +-0.35 of the angular pitch; radii 1 +- jitter
// (uniform); the convex hull of these points (drawn again if it keeps fewer than vertices_min
// vertices); stretched by sqrt(aspect) along x and 1/sqrt(aspect) along z (aspect: length over
// thickness of the section, >= 1); moved to its centroid; scaled to the area pi d^2 / 4. Random numbers
// come from std::mt19937_64 through our own [0, 1) conversion, so a seed gives the same stones with
// any standard library.
//
// Reference for the ellipsoid's moments: e.g. Goldstein, Classical Mechanics, moments of inertia of a
// homogeneous ellipsoid.
#pragma once

#include <cstdint>
#include <random>
#include <vector>

namespace vofdem {

// largest vertex count of a polygon stone
constexpr int kPolygonMaxVertices = 16;

// how random polygon stones are drawn
struct PolygonSpec {
  int vertices_min = 5;        // fewest vertices [-]; 5 (3 .. 16)
  int vertices_max = 8;        // most vertices [-]; 8 (vertices_min .. 16)
  double aspect_ratio = 1.5;   // length / thickness of the section [-]; 1 (round) .. 3, usual 1.5
  double radial_jitter = 0.2;  // vertex radii 1 +- jitter before the hull [-]; 0 .. 0.5, usual 0.2

  // throws std::invalid_argument naming the first bad field
  void validate() const;
};

// area, centroid, polar second moment and bounding radius of a simple polygon (x, z pairs, CCW)
struct PolygonProperties {
  double area = 0.0;             // A [m^2] (> 0 for counter-clockwise vertices)
  double centroid[2] = {0, 0};   // centroid (x, z) [m]
  double polar_moment = 0.0;     // J_A about the centroid [m^4]
  double bounding_radius = 0.0;  // largest vertex distance from the centroid [m]
  double perimeter = 0.0;        // [m]
};

// properties of the polygon of n vertices v (x, z pairs) [m]; n >= 3
PolygonProperties polygon_properties(const double* v, int n);

// true if the n vertices form a strictly convex counter-clockwise polygon (no collinear triples)
bool polygon_is_convex_ccw(const double* v, int n);

// uniform in [0, 1) from the top 53 bits of g (the same on every standard library)
inline double rng_uniform01(std::mt19937_64& g) { return static_cast<double>(g() >> 11) * 0x1.0p-53; }

// a random convex polygon of nominal diameter d [m] (equal-area disc) drawn from rng: body-frame
// vertices (x, z pairs, CCW, centroid at the origin, long axis along x)
std::vector<double> random_convex_polygon(std::mt19937_64& rng, const PolygonSpec& spec, double d);

// polygons of nominal diameters d [m], one per stone, drawn from one generator seeded with seed:
// body-frame vertices (x, z pairs) and the offset of each stone's first vertex (n + 1 entries)
void random_polygon_set(std::uint64_t seed, const PolygonSpec& spec, const std::vector<double>& d,
                        std::vector<double>& vertex, std::vector<int>& offset);

// the matching 3D stone (see above): volume [m^3] of a section of area A [m^2]
double polygon_stone_volume(double area);
// nominal diameter d [m] of a section of area A [m^2]: the disc of equal area
double polygon_nominal_diameter(double area);

// width [m] of the polygon (n body vertices v, rotated by angle [rad]) across the direction (ux, uz)
// (its caliper width normal to that direction); (ux, uz) need not be unit, must not be zero
double polygon_width_across(const double* v, int n, double angle, double ux, double uz);

// the polygon's vertices in the world frame: centre (x, z) [m], angle [rad] counter-clockwise
void polygon_to_world(const double* v, int n, double x, double z, double angle, double* out);
// the same with the angle's cosine c and sine s given
void polygon_to_world(const double* v, int n, double x, double z, double c, double s, double* out);

// Sutherland-Hodgman clip of the convex polygon in (n vertices, x, z pairs) to the half-plane
// s * coordinate[axis] <= s * c (s = +1: keep below c; s = -1: keep above c); writes to out (room
// for n + 1 vertices) and returns the vertex count (0 if nothing is left)
int clip_polygon_axis(const double* in, int n, int axis, double c, double s, double* out);

// true if (x, z) lies inside the convex CCW polygon w (n world vertices) or on its boundary
bool polygon_contains(const double* w, int n, double x, double z);
// distance [m] from (x, z) to the convex CCW polygon w (n world vertices); 0 inside
double polygon_distance(const double* w, int n, double x, double z);
// the rotation [rad] that lays the polygon's longest edge flat at the bottom (outward normal -z)
double polygon_rest_angle(const double* v, int n);

// area [m^2] of the polygon (n vertices, x, z pairs) by the shoelace formula (signed: > 0 if CCW)
double polygon_area(const double* v, int n);

// area [m^2] of the convex polygon (n vertices) inside the rectangle [x0, x1] x [z0, z1] (exact up to
// round-off); scratch needs room for 2 (n + 4) pairs
double polygon_rect_area(const double* v, int n, double x0, double x1, double z0, double z1, double* scratch);

}  // namespace vofdem
