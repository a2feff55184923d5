// Volume moments of a union of spheres (clump.h): exact for one and two spheres, a ray quadrature over
// the spheres' power cells for more; the principal frame; the library of quarried-stone shapes.
#include "vofdem/stones/clump.h"

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include "vofdem/common/numbers.h"

namespace vofdem {

using Vec3 = Eigen::Vector3d;
using Mat3 = Eigen::Matrix3d;

namespace {

void require(bool ok, const std::string& what) {
  if (!ok) throw std::invalid_argument(what);
}

// moments moved from a frame whose origin sits at o to the frame of o: x -> x + o
VolumeMoments shifted(const VolumeMoments& m, const Vec3& o) {
  VolumeMoments r;
  r.m0 = m.m0;
  r.m1 = m.m1 + m.m0 * o;
  r.m2 = m.m2 + m.m0 * o * o.transpose() + o * m.m1.transpose() + m.m1 * o.transpose();
  return r;
}

// The cap of a sphere (centre c, radius R) beyond the plane (x - c).u = h, -R <= h <= R, by slices
// z = (x - c).u of area pi (R^2 - z^2):
//   m0 = pi int_h^R (R^2 - z^2) dz             = pi (2 R^3/3 - R^2 h + h^3/3)
//   Z1 = pi int_h^R (R^2 - z^2) z dz           = pi (R^2 - h^2)^2 / 4
//   Z2 = pi int_h^R (R^2 - z^2) z^2 dz         = pi (2 R^5/15 - R^2 h^3/3 + h^5/5)
//   P  = int (|x - c|^2 - z^2) dV = pi/2 int_h^R (R^2 - z^2)^2 dz
//                                             = pi/2 (8 R^5/15 - R^4 h + 2 R^2 h^3/3 - h^5/5)
// (a slice of radius a has int rho^2 dA = pi a^4 / 2). About c, by the axial symmetry,
//   int (x - c)(x - c)^T dV = Z2 u u^T + P/2 (1 - u u^T),
// and with x = c + (x - c): m1 = m0 c + Z1 u, m2 = m0 c c^T + Z1 (c u^T + u c^T) + Z2 u u^T + P/2 (1 - u u^T).
// h = -R gives the whole sphere: m0 = 4 pi R^3/3, Z1 = 0, Z2 = P/2 = 4 pi R^5/15.
VolumeMoments cap_moments(const Vec3& c, double r, const Vec3& u, double h) {
  const double r2 = r * r, h2 = h * h, h3 = h2 * h, h5 = h3 * h2;
  const double m0 = kPi * (2.0 * r2 * r / 3.0 - r2 * h + h3 / 3.0);
  const double z1 = 0.25 * kPi * (r2 - h2) * (r2 - h2);
  const double z2 = kPi * (2.0 * r2 * r2 * r / 15.0 - r2 * h3 / 3.0 + h5 / 5.0);
  const double p = 0.5 * kPi * (8.0 * r2 * r2 * r / 15.0 - r2 * r2 * h + 2.0 * r2 * h3 / 3.0 - h5 / 5.0);
  const Mat3 uu = u * u.transpose();
  VolumeMoments m;
  m.m0 = m0;
  m.m1 = m0 * c + z1 * u;
  m.m2 = m0 * c * c.transpose() + z1 * (c * u.transpose() + u * c.transpose()) + z2 * uu +
         0.5 * p * (Mat3::Identity() - uu);
  return m;
}

// Gauss-Legendre nodes and weights on [-1, 1] (Newton on P_n from the Chebyshev guesses)
void gauss_legendre(int n, std::vector<double>& x, std::vector<double>& w) {
  x.assign(static_cast<std::size_t>(n), 0.0);
  w.assign(static_cast<std::size_t>(n), 0.0);
  for (int i = 0; i < (n + 1) / 2; ++i) {
    double z = std::cos(kPi * (i + 0.75) / (n + 0.5)), dp = 1.0;
    for (int it = 0; it < 100; ++it) {
      double p0 = 1.0, p1 = z;
      for (int k = 2; k <= n; ++k) {
        const double p2 = ((2.0 * k - 1.0) * z * p1 - (k - 1.0) * p0) / k;
        p0 = p1;
        p1 = p2;
      }
      dp = n * (z * p1 - p0) / (z * z - 1.0);
      const double dz = p1 / dp;
      z -= dz;
      if (std::fabs(dz) < 1e-16) break;
    }
    x[static_cast<std::size_t>(i)] = -z;
    x[static_cast<std::size_t>(n - 1 - i)] = z;
    w[static_cast<std::size_t>(i)] = w[static_cast<std::size_t>(n - 1 - i)] = 2.0 / ((1.0 - z * z) * dp * dp);
  }
}

// the interval [lo, hi] of the ray p + s w (s >= 0) inside B_i and the power cell of sphere i; the cell
// faces are the planes 2 x.(c_j - c_i) = |c_j|^2 - |c_i|^2 + r_i^2 - r_j^2
bool cell_interval(const std::vector<ClumpSphere>& s, std::size_t i, const Vec3& p, const Vec3& w, double& lo,
                   double& hi) {
  const Vec3 pc = p - s[i].centre;
  const double t = -w.dot(pc), disc = t * t - pc.squaredNorm() + s[i].radius * s[i].radius;
  if (!(disc > 0.0)) return false;
  const double root = std::sqrt(disc);
  lo = std::max(0.0, t - root);
  hi = t + root;
  for (std::size_t j = 0; j < s.size(); ++j) {
    if (j == i) continue;
    const Vec3 d = s[j].centre - s[i].centre;
    const double beta = d.squaredNorm() + s[i].radius * s[i].radius - s[j].radius * s[j].radius - 2.0 * pc.dot(d);
    const double a = 2.0 * w.dot(d);
    if (a > 0.0) {
      hi = std::min(hi, beta / a);
    } else if (a < 0.0) {
      lo = std::max(lo, beta / a);
    } else if (beta < 0.0) {
      return false;
    }
  }
  return hi > lo;
}

// moments of B_i n P_i about the ray origin p by the direction quadrature (nodes and weights given)
VolumeMoments cell_moments(const std::vector<ClumpSphere>& s, std::size_t i, const Vec3& p,
                           const std::vector<double>& mu, const std::vector<double>& wmu) {
  VolumeMoments m;
  const int n = static_cast<int>(mu.size());
  const double dphi = kPi / n;
  for (int a = 0; a < n; ++a) {
    const double st = std::sqrt(std::max(0.0, 1.0 - mu[a] * mu[a]));
    for (int b = 0; b < 2 * n; ++b) {
      const double phi = (b + 0.5) * dphi;
      const Vec3 w(st * std::cos(phi), st * std::sin(phi), mu[a]);
      double lo, hi;
      if (!cell_interval(s, i, p, w, lo, hi)) continue;
      const double weight = wmu[a] * dphi;
      const double lo3 = lo * lo * lo, hi3 = hi * hi * hi;
      const double s2 = (hi3 - lo3) / 3.0, s3 = (hi3 * hi - lo3 * lo) / 4.0;
      const double s4 = (hi3 * hi * hi - lo3 * lo * lo) / 5.0;
      m.m0 += weight * s2;
      m.m1 += (weight * s3) * w;
      m.m2 += (weight * s4) * (w * w.transpose());
    }
  }
  return m;
}

// p lies inside B_i and the power cell of sphere i
bool inside_cell(const std::vector<ClumpSphere>& s, std::size_t i, const Vec3& p) {
  const double pi = (p - s[i].centre).squaredNorm() - s[i].radius * s[i].radius;
  if (!(pi < 0.0)) return false;
  for (std::size_t j = 0; j < s.size(); ++j) {
    if (j != i && !(pi < (p - s[j].centre).squaredNorm() - s[j].radius * s[j].radius)) return false;
  }
  return true;
}

// the cell's moments from a ray origin deep inside it: the cell is convex, so rays from an interior point
// leave it once, and from its (coarsely estimated) centroid no face passes close to the origin, where
// the exit distance would vary steeply with the direction (nearly coincident spheres)
VolumeMoments cell_moments_centred(const std::vector<ClumpSphere>& s, std::size_t i, int order) {
  std::vector<double> mu, wmu;
  gauss_legendre(std::min(order, 16), mu, wmu);
  const VolumeMoments coarse = cell_moments(s, i, s[i].centre, mu, wmu);
  Vec3 p = s[i].centre;
  if (coarse.m0 > 0.0) {
    const Vec3 c = s[i].centre + coarse.m1 / coarse.m0;
    if (inside_cell(s, i, c)) p = c;
  }
  if (order != static_cast<int>(mu.size())) gauss_legendre(order, mu, wmu);
  return shifted(cell_moments(s, i, p, mu, wmu), p);
}

void check_spheres(const std::vector<ClumpSphere>& spheres) {
  require(!spheres.empty(), "spheres: a clump needs at least one sphere");
  for (std::size_t k = 0; k < spheres.size(); ++k) {
    const ClumpSphere& s = spheres[k];
    require(std::isfinite(s.radius) && s.radius > 0.0,
            "spheres[" + std::to_string(k) + "].radius: must be finite and > 0 [m], got " + std::to_string(s.radius));
    require(s.centre.allFinite(), "spheres[" + std::to_string(k) + "].centre: must be finite [m]");
  }
}

Vec3 mean_centre(const std::vector<ClumpSphere>& spheres) {
  Vec3 o = Vec3::Zero();
  for (const ClumpSphere& s : spheres) o += s.centre;
  return o / static_cast<double>(spheres.size());
}

}  // namespace

VolumeMoments VolumeMoments::operator+(const VolumeMoments& o) const {
  VolumeMoments r;
  r.m0 = m0 + o.m0;
  r.m1 = m1 + o.m1;
  r.m2 = m2 + o.m2;
  return r;
}

VolumeMoments VolumeMoments::operator-(const VolumeMoments& o) const {
  VolumeMoments r;
  r.m0 = m0 - o.m0;
  r.m1 = m1 - o.m1;
  r.m2 = m2 - o.m2;
  return r;
}

Mat3 VolumeMoments::inertia_about_centroid() const {
  const Vec3 c = centroid();
  const Mat3 s = m2 - m0 * c * c.transpose();
  return s.trace() * Mat3::Identity() - s;
}

VolumeMoments sphere_moments(const ClumpSphere& s) { return cap_moments(s.centre, s.radius, Vec3::UnitZ(), -s.radius); }

// B_1 u B_2 = B_1 + B_2 - (B_1 n B_2); the lens B_1 n B_2 is the cap of B_1 beyond the plane of the
// intersection circle, at h_1 = (d^2 + r_1^2 - r_2^2) / (2 d) from c_1 along u = (c_2 - c_1) / d, plus
// the cap of B_2 beyond the same plane, at h_2 = d - h_1 from c_2 along -u (h may be negative: a cap
// larger than a hemisphere)
VolumeMoments sphere_pair_union_moments(const ClumpSphere& a, const ClumpSphere& b) {
  const Vec3 o = 0.5 * (a.centre + b.centre);  // moments about the midpoint, then moved back
  const ClumpSphere la{a.centre - o, a.radius}, lb{b.centre - o, b.radius};
  const double d = (lb.centre - la.centre).norm();
  VolumeMoments m;
  if (d >= a.radius + b.radius) {
    m = sphere_moments(la) + sphere_moments(lb);
  } else if (d <= std::fabs(a.radius - b.radius)) {
    m = sphere_moments(a.radius >= b.radius ? la : lb);
  } else {
    const Vec3 u = (lb.centre - la.centre) / d;
    const double h1 = (d * d + a.radius * a.radius - b.radius * b.radius) / (2.0 * d);
    const VolumeMoments lens = cap_moments(la.centre, a.radius, u, h1) + cap_moments(lb.centre, b.radius, -u, d - h1);
    m = sphere_moments(la) + sphere_moments(lb) - lens;
  }
  return shifted(m, o);
}

VolumeMoments union_moments_quadrature(const std::vector<ClumpSphere>& spheres, int order) {
  check_spheres(spheres);
  require(order >= 2 && order <= 4096, "order: the quadrature order must be in [2, 4096], got " + std::to_string(order));
  const Vec3 o = mean_centre(spheres);
  std::vector<ClumpSphere> local = spheres;
  for (ClumpSphere& s : local) s.centre -= o;
  VolumeMoments total;
  for (std::size_t i = 0; i < local.size(); ++i) total = total + cell_moments_centred(local, i, order);
  return shifted(total, o);
}

VolumeMoments union_moments(const std::vector<ClumpSphere>& spheres, int order) {
  check_spheres(spheres);
  if (spheres.size() == 1) return sphere_moments(spheres[0]);
  if (spheres.size() == 2) return sphere_pair_union_moments(spheres[0], spheres[1]);
  return union_moments_quadrature(spheres, order);
}

double bounding_radius(const std::vector<ClumpSphere>& spheres) {
  double b = 0.0;
  for (const ClumpSphere& s : spheres) b = std::max(b, s.centre.norm() + s.radius);
  return b;
}

Clump::Clump(const std::vector<ClumpSphere>& spheres, int order) {
  check_spheres(spheres);
  // moments about the mean centre (no cancellation far from the origin)
  const Vec3 o = mean_centre(spheres);
  std::vector<ClumpSphere> local = spheres;
  for (ClumpSphere& s : local) s.centre -= o;
  const VolumeMoments m = union_moments(local, order);
  const Vec3 c = m.centroid();
  Eigen::SelfAdjointEigenSolver<Mat3> eig(m.inertia_about_centroid());
  Mat3 r = eig.eigenvectors();
  if (r.determinant() < 0.0) r.col(2) = -r.col(2);  // a proper rotation
  volume_ = m.m0;
  inertia_ = eig.eigenvalues();
  centroid_ = o + c;
  orientation_ = Eigen::Quaterniond(r);
  orientation_.normalize();
  spheres_ = local;
  for (ClumpSphere& s : spheres_) s.centre = r.transpose() * (s.centre - c);
}

double Clump::sphere_volume_sum() const {
  double v = 0.0;
  for (const ClumpSphere& s : spheres_) v += 4.0 / 3.0 * kPi * s.radius * s.radius * s.radius;
  return v;
}

double Clump::equivalent_diameter() const { return std::cbrt(6.0 * volume_ / kPi); }

double Clump::bounding_radius() const { return vofdem::bounding_radius(spheres_); }

Vec3 Clump::principal_extents() const {
  Vec3 lo = Vec3::Constant(INFINITY), hi = Vec3::Constant(-INFINITY);
  for (const ClumpSphere& s : spheres_) {
    lo = lo.cwiseMin(s.centre - Vec3::Constant(s.radius));
    hi = hi.cwiseMax(s.centre + Vec3::Constant(s.radius));
  }
  return hi - lo;
}

Vec3 Clump::aspect_ratios() const {
  Vec3 e = principal_extents();
  std::sort(e.data(), e.data() + 3, [](double a, double b) { return a > b; });
  return e / e[0];
}

Clump Clump::scaled(double factor) const {
  require(std::isfinite(factor) && factor > 0.0,
          "factor: the scale must be finite and > 0 [-], got " + std::to_string(factor));
  Clump c = *this;
  for (ClumpSphere& s : c.spheres_) {
    s.centre *= factor;
    s.radius *= factor;
  }
  c.volume_ *= factor * factor * factor;
  c.inertia_ *= factor * factor * factor * factor * factor;
  c.centroid_ *= factor;
  return c;
}

void check_clump_mix(const ClumpMix& mix) {
  const std::vector<std::string> known = quarried_stone_names();
  std::string list;
  for (const std::string& n : known) list += (list.empty() ? "" : ", ") + n;
  require(!mix.names.empty(), "clump_names: at least one library shape is needed (" + list + ")");
  for (const std::string& n : mix.names)
    require(std::find(known.begin(), known.end(), n) != known.end(),
            "clump_names: unknown library shape '" + n + "'; allowed: " + list);
  require(mix.ratio_short >= 0.55 && mix.ratio_short <= 1.0,
          "clump_ratio_short: short / long must be in [0.55, 1] [-], got " + std::to_string(mix.ratio_short));
  require(mix.ratio_intermediate >= mix.ratio_short && mix.ratio_intermediate <= 1.0,
          "clump_ratio_intermediate: intermediate / long must be in [clump_ratio_short, 1] [-], got " +
              std::to_string(mix.ratio_intermediate));
}

std::vector<std::string> quarried_stone_names() { return {"pair_2", "triangle_3", "tetra_4", "box_8"}; }

namespace {

// the shape with a long axis of 1 along x, intermediate p along y, short q along z
std::vector<ClumpSphere> unit_shape(const std::string& name, double p, double q) {
  if (name == "pair_2") {
    const double r = 0.5 * q;
    return {{Vec3(-(0.5 - r), 0.0, 0.0), r}, {Vec3(0.5 - r, 0.0, 0.0), r}};
  }
  if (name == "triangle_3") {
    const double r = 0.5 * q, b = 0.5 * (p - q);
    return {{Vec3(-(0.5 - r), -b, 0.0), r}, {Vec3(0.5 - r, -b, 0.0), r}, {Vec3(0.0, b, 0.0), r}};
  }
  // tetra_4 and box_8: radius between 1/4 (neighbours along the long axis touch) and q/2
  const double r = 0.25 * q + 0.125, a = 0.5 - r, b = 0.5 * p - r, h = 0.5 * q - r;
  if (name == "tetra_4") {
    return {{Vec3(-a, 0.0, -h), r}, {Vec3(a, 0.0, -h), r}, {Vec3(0.0, -b, h), r}, {Vec3(0.0, b, h), r}};
  }
  if (name == "box_8") {
    std::vector<ClumpSphere> s;
    for (int k = 0; k < 8; ++k) {
      s.push_back({Vec3((k & 1) ? a : -a, (k & 2) ? b : -b, (k & 4) ? h : -h), r});
    }
    return s;
  }
  std::string names;
  for (const std::string& n : quarried_stone_names()) names += (names.empty() ? "" : ", ") + n;
  throw std::invalid_argument("name: unknown quarried-stone shape '" + name + "'; one of " + names);
}

}  // namespace

Clump quarried_stone(const std::string& name, double d_eq, double ratio_intermediate, double ratio_short, int order) {
  require(std::isfinite(d_eq) && d_eq > 0.0, "d_eq: the volume-equivalent diameter must be finite and > 0 [m], got " +
                                                 std::to_string(d_eq));
  require(ratio_short >= 0.55 && ratio_short <= 1.0,
          "ratio_short: short / long must be in [0.55, 1] [-], got " + std::to_string(ratio_short));
  require(ratio_intermediate >= ratio_short && ratio_intermediate <= 1.0,
          "ratio_intermediate: intermediate / long must be in [ratio_short, 1] [-], got " +
              std::to_string(ratio_intermediate));
  std::vector<ClumpSphere> s = unit_shape(name, ratio_intermediate, ratio_short);
  const double v0 = union_moments(s, order).m0;
  const double scale = d_eq / std::cbrt(6.0 * v0 / kPi);
  for (ClumpSphere& c : s) {
    c.centre *= scale;
    c.radius *= scale;
  }
  return Clump(s, order);
}

}  // namespace vofdem
