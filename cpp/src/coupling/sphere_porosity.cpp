// Porosity of the cells from 3D spheres across the flume (see porosity_map.h): the exact volume of each
// sphere in each cell's slab dx x dz x (the flume's width), through the corner primitive of slab_volume.h
// evaluated once per grid node around the sphere, over the width: an area per unit width [m^2] as the
// discs' and polygons' are, so that the parts of a sphere inside the grid sum to its volume / width.
// Clumps: each sub-sphere's parts scaled by V_union / sum_k V_k (slab_volume.h) and summed per cell of the
// stone's stencil, one cell list per stone.
#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include "vofdem/common/check.h"
#include "vofdem/common/numbers.h"
#include "vofdem/coupling/porosity_map.h"
#include "vofdem/coupling/slab_volume.h"
#include "vofdem/stones/clump_model.h"

namespace vofdem {

namespace {
// the sphere (x, z, r)'s volume [m^3] in the slab of each of the ni x nk cells from (i0, k0), handed to
// visit(i, k, volume): the primitive at every node, so that each cell's volume is four reads and the parts
// telescope; phi is the nodes' scratch
template <class Visit>
void sphere_cell_parts(const Grid2D& grid, std::vector<double>& phi, double x, double z, double r, int i0, int k0,
                       int ni, int nk, Visit&& visit) {
  for (int k = 0; k <= nk; ++k)
    for (int i = 0; i <= ni; ++i)
      phi[k * (ni + 1) + i] = sphere_corner_volume(grid.x_face(i0 + i) - x, grid.z_face(k0 + k) - z, r);
  for (int k = 0; k < nk; ++k) {
    for (int i = 0; i < ni; ++i) {
      const double* lo = &phi[k * (ni + 1) + i];
      const double* hi = lo + (ni + 1);
      visit(i, k, std::max(0.0, (hi[1] - hi[0]) - (lo[1] - lo[0])));
    }
  }
}
}  // namespace

int PorosityMapper::add_sphere(double x, double z, double r, double width, int p) {
  const CellBox box = grid_.circle_cells(x, z, r);
  if (box.empty()) return p;
  const int i0 = box.i0, k0 = box.k0, ni = box.ni, nk = box.nk;
  if (static_cast<std::size_t>(ni + 1) * (nk + 1) > node_phi_.size() || ni * nk > max_cells_per_disc_)
    throw std::logic_error("porosity_map: sphere stencil larger than its bound (r = " + format_value(r) + ")");
  sphere_cell_parts(grid_, node_phi_, x, z, r, i0, k0, ni, nk, [&](int i, int k, double volume) {
    const double area = volume / width;
    if (area > 0.0) p = append_cell(grid_.cell(i0 + i, k0 + k), area, p);
  });
  return p;
}

void PorosityMapper::require_slab_mapping(const char* shape, double width) const {
  if (params_.method == PorosityMethod::kLookup)
    throw std::invalid_argument(std::string("method = 1 (lookup): the paper's lookup table holds disc areas; 3D ") +
                                shape + " need method = 0 (exact)");
  if (!(width > 0.0) || !std::isfinite(width))
    throw std::invalid_argument("width = " + format_value(width) + " m is outside the allowed range (0, inf)");
}

void PorosityMapper::map_spheres(int n, const double* x, const double* z, const double* r, double width,
                                 const std::uint8_t* active) {
  require_slab_mapping("spheres", width);
  map_each(
      n, active,
      [&](int j) {
        require_finite("x", x[j]);
        require_finite("z", z[j]);
        require_in_closed("sphere radius", r[j], params_.r_min, params_.r_max);
      },
      [&](int j, int p) { return add_sphere(x[j], z[j], r[j], width, p); });
}

// the stencil is the box of the sub-spheres' boxes (cells reached by none are skipped as empty); each
// sub-sphere's primitive at its own nodes, its parts scaled and added to the patch; the cells then in
// the order of add_sphere (rows, then columns), so a one-sphere clump gives the sphere's entries
int PorosityMapper::add_clump(double x, double z, const double* quat, const double* sphere, int count, double volume,
                              double width, int p) {
  const Eigen::Matrix3d rot = Eigen::Quaterniond(quat[0], quat[1], quat[2], quat[3]).toRotationMatrix();
  double cx[kClumpMaxSpheres], cz[kClumpMaxSpheres], sum = 0.0;
  int i0 = grid_.nx(), i1 = -1, k0 = grid_.nz(), k1 = -1;
  for (int g = 0; g < count; ++g) {
    const double* c = sphere + 4 * g;
    const Eigen::Vector3d w = rot * Eigen::Vector3d(c[0], c[1], c[2]);
    const double r = c[3];
    cx[g] = x + w[0], cz[g] = z + w[2];
    sum += 4.0 / 3.0 * kPi * r * r * r;
    const CellBox b = grid_.circle_cells(cx[g], cz[g], r);
    if (b.empty()) continue;
    i0 = std::min(i0, b.i0), i1 = std::max(i1, b.i0 + b.ni - 1);
    k0 = std::min(k0, b.k0), k1 = std::max(k1, b.k0 + b.nk - 1);
  }
  if (i1 < i0) return p;  // wholly outside the grid
  const int ni = i1 - i0 + 1, nk = k1 - k0 + 1;
  if (ni * nk > max_cells_per_disc_)
    throw std::logic_error("porosity_map: clump stencil larger than its bound (" + std::to_string(ni) + " x " +
                           std::to_string(nk) + " cells)");
  const double scale = volume / sum;
  std::fill(clump_patch_.begin(), clump_patch_.begin() + ni * nk, 0.0);
  for (int g = 0; g < count; ++g) {
    const double r = sphere[4 * g + 3];
    const CellBox b = grid_.circle_cells(cx[g], cz[g], r);
    if (b.empty()) continue;
    const int a0 = b.i0, b0 = b.k0, na = b.ni, nb = b.nk;
    if (static_cast<std::size_t>(na + 1) * (nb + 1) > node_phi_.size())
      throw std::logic_error("porosity_map: sub-sphere stencil larger than its bound (r = " + format_value(r) + ")");
    sphere_cell_parts(grid_, node_phi_, cx[g], cz[g], r, a0, b0, na, nb, [&](int i, int k, double volume) {
      clump_patch_[(b0 + k - k0) * ni + (a0 + i - i0)] += scale * volume;
    });
  }
  for (int k = 0; k < nk; ++k) {
    for (int i = 0; i < ni; ++i) {
      const double area = clump_patch_[k * ni + i] / width;
      if (area <= 0.0) continue;
      p = append_cell(grid_.cell(i0 + i, k0 + k), area, p);
    }
  }
  return p;
}

void PorosityMapper::map_clumps(int n, const double* x, const double* z, const double* quat, const double* sphere,
                                const int* offset, const double* volume, double width, const std::uint8_t* active) {
  require_slab_mapping("clumps", width);
  map_each(
      n, active,
      [&](int j) {
        require_finite("x", x[j]);
        require_finite("z", z[j]);
        for (int q = 0; q < 4; ++q) require_finite("quaternion", quat[4 * j + q]);
        require_positive("clump volume", volume[j]);
        const int count = offset[j + 1] - offset[j];
        if (count < 1 || count > kClumpMaxSpheres)
          throw std::invalid_argument("clump " + std::to_string(j) + " has " + std::to_string(count) +
                                      " spheres, allowed range [1, " + std::to_string(kClumpMaxSpheres) + "]");
        // the stencil's bound: every sub-sphere within r_max of the centre (the coupler's r_max is the
        // largest bounding radius)
        for (int g = offset[j]; g < offset[j + 1]; ++g) {
          const double* c = sphere + 4 * g;
          require_in_closed("clump bounding radius", std::sqrt(c[0] * c[0] + c[1] * c[1] + c[2] * c[2]) + c[3], 0.0,
                            params_.r_max * (1.0 + 1e-12));
        }
      },
      [&](int j, int p) {
        return add_clump(x[j], z[j], quat + 4 * j, sphere + 4 * offset[j], offset[j + 1] - offset[j], volume[j],
                         width, p);
      });
}

}  // namespace vofdem
