// The volume of a sphere or a clump inside the slabs of the flow cells (slab_volume.h): the corner
// primitive P evaluated at the grid nodes around the sphere and differenced.
#include "vofdem/coupling/slab_volume.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace vofdem {

namespace {

void require(bool ok, const std::string& what) {
  if (!ok) throw std::invalid_argument(what);
}

void check_radius(double r) {
  require(std::isfinite(r) && r > 0.0, "r: the sphere radius must be finite and > 0 [m], got " + std::to_string(r));
}

void check_edges(const std::vector<double>& e, const char* name) {
  require(e.size() >= 2, std::string(name) + ": at least 2 edges are needed");
  for (std::size_t k = 0; k < e.size(); ++k) {
    require(std::isfinite(e[k]), std::string(name) + ": every edge must be finite [m]");
    if (k > 0) require(e[k] > e[k - 1], std::string(name) + ": edges must be strictly increasing [m]");
  }
}

// the index range [first, last) of cells of edges e that [lo, hi] reaches
void cell_range(const std::vector<double>& e, double lo, double hi, int& first, int& last) {
  const auto a = std::upper_bound(e.begin(), e.end(), lo);
  const auto b = std::lower_bound(e.begin(), e.end(), hi);
  first = std::max(0, static_cast<int>(a - e.begin()) - 1);
  last = std::min(static_cast<int>(e.size()) - 1, static_cast<int>(b - e.begin()));
}

// the sphere's parts in cells [i0, i1) x [k0, k1), by P at the nodes, into a dense patch (column-major
// in k), each multiplied by scale
void patch_volumes(double xc, double zc, double r, const std::vector<double>& xe, const std::vector<double>& ze,
                   int i0, int i1, int k0, int k1, double scale, std::vector<double>& patch, int patch_i0,
                   int patch_k0, int patch_nk) {
  const int nk = k1 - k0;
  std::vector<double> prev(static_cast<std::size_t>(nk + 1)), next(prev.size());
  for (int k = 0; k <= nk; ++k) prev[static_cast<std::size_t>(k)] = sphere_corner_volume(xe[i0] - xc, ze[k0 + k] - zc, r);
  for (int i = i0; i < i1; ++i) {
    for (int k = 0; k <= nk; ++k) next[static_cast<std::size_t>(k)] = sphere_corner_volume(xe[i + 1] - xc, ze[k0 + k] - zc, r);
    for (int k = 0; k < nk; ++k) {
      const std::size_t a = static_cast<std::size_t>(k);
      const double v = (next[a + 1] - prev[a + 1]) - (next[a] - prev[a]);
      patch[static_cast<std::size_t>((i - patch_i0) * patch_nk + (k0 + k - patch_k0))] += scale * v;
    }
    prev.swap(next);
  }
}

}  // namespace

double sphere_corner_volume(double u, double w, double r) {
  u = std::clamp(u, -r, r);
  w = std::clamp(w, -r, r);
  const double r2 = r * r;
  const double q = std::sqrt(std::max(r2 - u * u - w * w, 0.0));
  return (2.0 * u * w * q + u * (3.0 * r2 - u * u) * std::atan2(w, q) + w * (3.0 * r2 - w * w) * std::atan2(u, q) -
          2.0 * r2 * r * std::atan2(u * w, r * q)) /
         3.0;
}

double sphere_slab_volume(double xc, double zc, double r, double x0, double x1, double z0, double z1) {
  check_radius(r);
  require(std::isfinite(xc) && std::isfinite(zc), "xc, zc: the sphere centre must be finite [m]");
  require(std::isfinite(x0) && std::isfinite(x1) && x1 >= x0, "x0, x1: finite with x1 >= x0 [m]");
  require(std::isfinite(z0) && std::isfinite(z1) && z1 >= z0, "z0, z1: finite with z1 >= z0 [m]");
  const double u0 = x0 - xc, u1 = x1 - xc, w0 = z0 - zc, w1 = z1 - zc;
  return (sphere_corner_volume(u1, w1, r) - sphere_corner_volume(u0, w1, r)) -
         (sphere_corner_volume(u1, w0, r) - sphere_corner_volume(u0, w0, r));
}

void sphere_cell_volumes(double xc, double zc, double r, const std::vector<double>& x_edges,
                         const std::vector<double>& z_edges, std::vector<CellVolume>& out) {
  check_radius(r);
  require(std::isfinite(xc) && std::isfinite(zc), "xc, zc: the sphere centre must be finite [m]");
  check_edges(x_edges, "x_edges");
  check_edges(z_edges, "z_edges");
  int i0, i1, k0, k1;
  cell_range(x_edges, xc - r, xc + r, i0, i1);
  cell_range(z_edges, zc - r, zc + r, k0, k1);
  if (i1 <= i0 || k1 <= k0) return;
  const int nk = k1 - k0;
  std::vector<double> patch(static_cast<std::size_t>((i1 - i0) * nk), 0.0);
  patch_volumes(xc, zc, r, x_edges, z_edges, i0, i1, k0, k1, 1.0, patch, i0, k0, nk);
  for (int i = i0; i < i1; ++i) {
    for (int k = k0; k < k1; ++k) {
      const double v = patch[static_cast<std::size_t>((i - i0) * nk + (k - k0))];
      if (v > 0.0) out.push_back({i, k, v});
    }
  }
}

void clump_cell_volumes(const Clump& clump, const Eigen::Vector3d& position, const Eigen::Quaterniond& orientation,
                        const std::vector<double>& x_edges, const std::vector<double>& z_edges,
                        std::vector<CellVolume>& out) {
  check_edges(x_edges, "x_edges");
  check_edges(z_edges, "z_edges");
  require(position.allFinite(), "position: the clump's centroid must be finite [m]");
  const double scale = clump.volume() / clump.sphere_volume_sum();
  // the cells the clump's spheres reach, then each sphere's scaled parts summed into that patch
  std::vector<Eigen::Vector3d> centres;
  double xlo = INFINITY, xhi = -INFINITY, zlo = INFINITY, zhi = -INFINITY;
  for (const ClumpSphere& s : clump.spheres()) {
    centres.push_back(position + orientation * s.centre);
    xlo = std::min(xlo, centres.back().x() - s.radius);
    xhi = std::max(xhi, centres.back().x() + s.radius);
    zlo = std::min(zlo, centres.back().z() - s.radius);
    zhi = std::max(zhi, centres.back().z() + s.radius);
  }
  int i0, i1, k0, k1;
  cell_range(x_edges, xlo, xhi, i0, i1);
  cell_range(z_edges, zlo, zhi, k0, k1);
  if (i1 <= i0 || k1 <= k0) return;
  const int nk = k1 - k0;
  std::vector<double> patch(static_cast<std::size_t>((i1 - i0) * nk), 0.0);
  for (std::size_t m = 0; m < centres.size(); ++m) {
    const double r = clump.spheres()[m].radius, xc = centres[m].x(), zc = centres[m].z();
    int a0, a1, b0, b1;
    cell_range(x_edges, xc - r, xc + r, a0, a1);
    cell_range(z_edges, zc - r, zc + r, b0, b1);
    if (a1 > a0 && b1 > b0) patch_volumes(xc, zc, r, x_edges, z_edges, a0, a1, b0, b1, scale, patch, i0, k0, nk);
  }
  for (int i = i0; i < i1; ++i) {
    for (int k = k0; k < k1; ++k) {
      const double v = patch[static_cast<std::size_t>((i - i0) * nk + (k - k0))];
      if (v > 0.0) out.push_back({i, k, v});
    }
  }
}

double clump_slab_volume(const Clump& clump, const Eigen::Vector3d& position, const Eigen::Quaterniond& orientation,
                         double x0, double x1, double z0, double z1) {
  const double scale = clump.volume() / clump.sphere_volume_sum();
  double v = 0.0;
  for (const ClumpSphere& s : clump.spheres()) {
    const Eigen::Vector3d c = position + orientation * s.centre;
    v += sphere_slab_volume(c.x(), c.z(), s.radius, x0, x1, z0, z1);
  }
  return scale * v;
}

}  // namespace vofdem
