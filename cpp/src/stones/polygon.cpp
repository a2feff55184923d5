// Convex polygon stones: shape generation and properties (see polygon.h).
#include "vofdem/stones/polygon.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include "stones/polygon_kernels.h"
#include "vofdem/common/check.h"
#include "vofdem/common/numbers.h"

namespace vofdem {

namespace {
double cross(double ax, double az, double bx, double bz) { return ax * bz - az * bx; }

// convex hull of points (x, z pairs), counter-clockwise, collinear points dropped (monotone chain)
std::vector<double> convex_hull(const std::vector<double>& pts) {
  const int n = static_cast<int>(pts.size() / 2);
  std::vector<int> idx(n);
  for (int k = 0; k < n; ++k) idx[k] = k;
  std::sort(idx.begin(), idx.end(), [&pts](int a, int b) {
    return pts[2 * a] < pts[2 * b] || (pts[2 * a] == pts[2 * b] && pts[2 * a + 1] < pts[2 * b + 1]);
  });
  std::vector<int> h(2 * static_cast<std::size_t>(n) + 1);
  int m = 0;
  auto turn = [&pts](int o, int a, int b) {
    return cross(pts[2 * a] - pts[2 * o], pts[2 * a + 1] - pts[2 * o + 1], pts[2 * b] - pts[2 * o],
                 pts[2 * b + 1] - pts[2 * o + 1]);
  };
  for (int k = 0; k < n; ++k) {  // lower hull
    while (m >= 2 && turn(h[m - 2], h[m - 1], idx[k]) <= 0.0) --m;
    h[m++] = idx[k];
  }
  for (int k = n - 2, lo = m + 1; k >= 0; --k) {  // upper hull
    while (m >= lo && turn(h[m - 2], h[m - 1], idx[k]) <= 0.0) --m;
    h[m++] = idx[k];
  }
  std::vector<double> out;
  for (int k = 0; k < m - 1; ++k) {
    out.push_back(pts[2 * h[k]]);
    out.push_back(pts[2 * h[k] + 1]);
  }
  return out;
}
}  // namespace

void PolygonSpec::validate() const {
  if (vertices_min < 3 || vertices_min > kPolygonMaxVertices)
    throw std::invalid_argument("vertices_min = " + std::to_string(vertices_min) + " is outside the allowed range [3, " +
                                std::to_string(kPolygonMaxVertices) + "]");
  if (vertices_max < vertices_min || vertices_max > kPolygonMaxVertices)
    throw std::invalid_argument("vertices_max = " + std::to_string(vertices_max) + " is outside the allowed range [" +
                                std::to_string(vertices_min) + ", " + std::to_string(kPolygonMaxVertices) +
                                "] (vertices_min .. " + std::to_string(kPolygonMaxVertices) + ")");
  require_in_closed("aspect_ratio", aspect_ratio, 1.0, 3.0);
  require_in_closed("radial_jitter", radial_jitter, 0.0, 0.5);
}

double polygon_area(const double* v, int n) {
  double a = 0.0;
  for (int k = 0; k < n; ++k) {
    const int l = k + 1 == n ? 0 : k + 1;
    a += cross(v[2 * k], v[2 * k + 1], v[2 * l], v[2 * l + 1]);
  }
  return 0.5 * a;
}

PolygonProperties polygon_properties(const double* v, int n) {
  PolygonProperties p;
  if (n < 3) return p;
  // about the vertex mean first: fewer digits lost than about the world origin
  double ox = 0.0, oz = 0.0;
  for (int k = 0; k < n; ++k) ox += v[2 * k], oz += v[2 * k + 1];
  ox /= n, oz /= n;
  double a2 = 0.0, cx = 0.0, cz = 0.0, j = 0.0, per = 0.0;
  for (int k = 0; k < n; ++k) {
    const int l = k + 1 == n ? 0 : k + 1;
    const double x0 = v[2 * k] - ox, z0 = v[2 * k + 1] - oz, x1 = v[2 * l] - ox, z1 = v[2 * l + 1] - oz;
    const double c = cross(x0, z0, x1, z1);
    a2 += c;
    cx += (x0 + x1) * c;
    cz += (z0 + z1) * c;
    j += c * (x0 * x0 + x0 * x1 + x1 * x1 + z0 * z0 + z0 * z1 + z1 * z1);
    per += std::hypot(x1 - x0, z1 - z0);
  }
  p.area = 0.5 * a2;
  const double gx = cx / (3.0 * a2), gz = cz / (3.0 * a2);
  p.centroid[0] = ox + gx;
  p.centroid[1] = oz + gz;
  // J about the vertex mean, moved to the centroid (parallel axes)
  p.polar_moment = j / 12.0 - p.area * (gx * gx + gz * gz);
  p.perimeter = per;
  double r2 = 0.0;
  for (int k = 0; k < n; ++k) {
    const double dx = v[2 * k] - p.centroid[0], dz = v[2 * k + 1] - p.centroid[1];
    r2 = std::max(r2, dx * dx + dz * dz);
  }
  p.bounding_radius = std::sqrt(r2);
  return p;
}

bool polygon_is_convex_ccw(const double* v, int n) {
  if (n < 3) return false;
  for (int k = 0; k < n; ++k) {
    const int l = (k + 1) % n, m = (k + 2) % n;
    const double c = cross(v[2 * l] - v[2 * k], v[2 * l + 1] - v[2 * k + 1], v[2 * m] - v[2 * l],
                           v[2 * m + 1] - v[2 * l + 1]);
    if (!(c > 0.0)) return false;
  }
  // a convex polygon winds once: the turning angles sum to 2 pi
  double turn = 0.0;
  for (int k = 0; k < n; ++k) {
    const int l = (k + 1) % n, m = (k + 2) % n;
    const double ax = v[2 * l] - v[2 * k], az = v[2 * l + 1] - v[2 * k + 1];
    const double bx = v[2 * m] - v[2 * l], bz = v[2 * m + 1] - v[2 * l + 1];
    turn += std::atan2(cross(ax, az, bx, bz), ax * bx + az * bz);
  }
  return std::fabs(turn - 2.0 * kPi) < 1e-6;
}

std::vector<double> random_convex_polygon(std::mt19937_64& rng, const PolygonSpec& spec, double d) {
  spec.validate();
  require_positive("d", d);
  std::vector<double> hull;
  for (int attempt = 0; attempt < 64; ++attempt) {
    const int span = spec.vertices_max - spec.vertices_min + 1;
    const int n = spec.vertices_min + std::min(span - 1, static_cast<int>(rng_uniform01(rng) * span));
    const double phase = 2.0 * kPi * rng_uniform01(rng);
    std::vector<double> pts;
    for (int k = 0; k < n; ++k) {
      const double a = phase + 2.0 * kPi * (k + 0.35 * (2.0 * rng_uniform01(rng) - 1.0)) / n;
      const double r = 1.0 + spec.radial_jitter * (2.0 * rng_uniform01(rng) - 1.0);
      pts.push_back(r * std::cos(a));
      pts.push_back(r * std::sin(a));
    }
    hull = convex_hull(pts);
    if (static_cast<int>(hull.size() / 2) >= spec.vertices_min) break;
  }
  const int m = static_cast<int>(hull.size() / 2);
  const double sx = std::sqrt(spec.aspect_ratio), sz = 1.0 / sx;
  for (int k = 0; k < m; ++k) hull[2 * k] *= sx, hull[2 * k + 1] *= sz;
  const PolygonProperties p = polygon_properties(hull.data(), m);
  const double scale = std::sqrt(0.25 * kPi * d * d / p.area);
  for (int k = 0; k < m; ++k) {
    hull[2 * k] = (hull[2 * k] - p.centroid[0]) * scale;
    hull[2 * k + 1] = (hull[2 * k + 1] - p.centroid[1]) * scale;
  }
  return hull;
}

void random_polygon_set(std::uint64_t seed, const PolygonSpec& spec, const std::vector<double>& d,
                        std::vector<double>& vertex, std::vector<int>& offset) {
  std::mt19937_64 rng(seed);
  vertex.clear();
  offset.assign(1, 0);
  for (double di : d) {
    const std::vector<double> v = random_convex_polygon(rng, spec, di);
    vertex.insert(vertex.end(), v.begin(), v.end());
    offset.push_back(offset.back() + static_cast<int>(v.size() / 2));
  }
}

double polygon_stone_volume(double area) { return 4.0 / 3.0 * area * std::sqrt(area / kPi); }

double polygon_nominal_diameter(double area) { return 2.0 * std::sqrt(area / kPi); }

double polygon_width_across(const double* v, int n, double angle, double ux, double uz) {
  // the direction across u, turned into the body frame
  const double len = std::hypot(ux, uz);
  const double tx = -uz / len, tz = ux / len;
  const double c = std::cos(angle), s = std::sin(angle);
  const double bx = c * tx + s * tz, bz = -s * tx + c * tz;
  double lo = INFINITY, hi = -INFINITY;
  for (int k = 0; k < n; ++k) {
    const double p = v[2 * k] * bx + v[2 * k + 1] * bz;
    lo = std::min(lo, p);
    hi = std::max(hi, p);
  }
  return hi - lo;
}

void polygon_to_world(const double* v, int n, double x, double z, double angle, double* out) {
  polygon_to_world(v, n, x, z, std::cos(angle), std::sin(angle), out);
}

void polygon_to_world(const double* v, int n, double x, double z, double c, double s, double* out) {
  detail::to_world(v, n, x, z, c, s, out);
}

bool polygon_contains(const double* w, int n, double x, double z) {
  for (int k = 0; k < n; ++k) {
    const int l = k + 1 == n ? 0 : k + 1;
    if (cross(w[2 * l] - w[2 * k], w[2 * l + 1] - w[2 * k + 1], x - w[2 * k], z - w[2 * k + 1]) < 0.0) return false;
  }
  return true;
}

double polygon_distance(const double* w, int n, double x, double z) {
  if (polygon_contains(w, n, x, z)) return 0.0;
  double d2 = INFINITY;
  for (int k = 0; k < n; ++k) {
    const int l = k + 1 == n ? 0 : k + 1;
    const double ex = w[2 * l] - w[2 * k], ez = w[2 * l + 1] - w[2 * k + 1];
    const double px = x - w[2 * k], pz = z - w[2 * k + 1];
    const double t = std::clamp((px * ex + pz * ez) / (ex * ex + ez * ez), 0.0, 1.0);
    const double dx = px - t * ex, dz = pz - t * ez;
    d2 = std::min(d2, dx * dx + dz * dz);
  }
  return std::sqrt(d2);
}

double polygon_rest_angle(const double* v, int n) {
  int best = 0;
  double longest = -1.0;
  for (int k = 0; k < n; ++k) {
    const int l = k + 1 == n ? 0 : k + 1;
    const double len = std::hypot(v[2 * l] - v[2 * k], v[2 * l + 1] - v[2 * k + 1]);
    if (len > longest) longest = len, best = k;
  }
  const int l = best + 1 == n ? 0 : best + 1;
  // the edge's outward normal (right perpendicular of a CCW edge) turned to point down
  const double nx = v[2 * l + 1] - v[2 * best + 1], nz = -(v[2 * l] - v[2 * best]);
  return -0.5 * kPi - std::atan2(nz, nx);
}

int clip_polygon_axis(const double* in, int n, int axis, double c, double s, double* out) {
  int m = 0;
  for (int k = 0; k < n; ++k) {
    const int l = k + 1 == n ? 0 : k + 1;
    const double* a = in + 2 * k;
    const double* b = in + 2 * l;
    const double da = s * (a[axis] - c), db = s * (b[axis] - c);  // <= 0: kept
    if (da <= 0.0) {
      out[2 * m] = a[0];
      out[2 * m + 1] = a[1];
      ++m;
    }
    if ((da < 0.0 && db > 0.0) || (da > 0.0 && db < 0.0)) {
      const double t = da / (da - db);
      out[2 * m] = a[0] + t * (b[0] - a[0]);
      out[2 * m + 1] = a[1] + t * (b[1] - a[1]);
      out[2 * m + axis] = c;  // exactly on the line
      ++m;
    }
  }
  return m < 3 ? 0 : m;
}

double polygon_rect_area(const double* v, int n, double x0, double x1, double z0, double z1, double* scratch) {
  double* a = scratch;
  double* b = scratch + 2 * (n + 4);
  int m = clip_polygon_axis(v, n, 0, x0, -1.0, a);
  m = clip_polygon_axis(a, m, 0, x1, 1.0, b);
  m = clip_polygon_axis(b, m, 1, z0, -1.0, a);
  m = clip_polygon_axis(a, m, 1, z1, 1.0, b);
  return m > 0 ? std::max(0.0, polygon_area(b, m)) : 0.0;
}

}  // namespace vofdem
