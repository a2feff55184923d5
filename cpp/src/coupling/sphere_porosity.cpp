// Porosity of the cells from 3D spheres across the flume (see porosity_map.h): the exact volume of each
// sphere in each cell's slab dx x dz x (the flume's width), through the corner primitive of slab_volume.h
// evaluated once per grid node around the sphere, over the width: an area per unit width [m^2] as the
// discs' and polygons' are, so that the parts of a sphere inside the grid sum to its volume / width.
#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include "vofdem/common/check.h"
#include "vofdem/coupling/porosity_map.h"
#include "vofdem/coupling/slab_volume.h"

namespace vofdem {

int PorosityMapper::add_sphere(double x, double z, double r, double width, int p) {
  const double xend = grid_.x_face(grid_.nx());
  const double z0 = grid_.z_face(0), zend = grid_.z_face(grid_.nz());
  if (x + r <= grid_.x0() || x - r >= xend || z + r <= z0 || z - r >= zend) return p;
  const int i0 = grid_.locate_x(x - r), i1 = grid_.locate_x(x + r);
  const int k0 = grid_.locate_z(z - r), k1 = grid_.locate_z(z + r);
  const int ni = i1 - i0 + 1, nk = k1 - k0 + 1;
  if (static_cast<std::size_t>(ni + 1) * (nk + 1) > node_phi_.size() || ni * nk > max_cells_per_disc_)
    throw std::logic_error("porosity_map: sphere stencil larger than its bound (r = " + format_value(r) + ")");
  // the primitive at every node: each cell's volume is then four reads (and the parts telescope)
  for (int k = 0; k <= nk; ++k)
    for (int i = 0; i <= ni; ++i)
      node_phi_[k * (ni + 1) + i] = sphere_corner_volume(grid_.x_face(i0 + i) - x, grid_.z_face(k0 + k) - z, r);
  for (int k = 0; k < nk; ++k) {
    for (int i = 0; i < ni; ++i) {
      const double* lo = &node_phi_[k * (ni + 1) + i];
      const double* hi = lo + (ni + 1);
      const double area = std::max(0.0, (hi[1] - hi[0]) - (lo[1] - lo[0])) / width;
      if (area <= 0.0) continue;
      p = append_cell(grid_.cell(i0 + i, k0 + k), area, p);
    }
  }
  return p;
}

void PorosityMapper::map_spheres(int n, const double* x, const double* z, const double* r, double width,
                                 const std::uint8_t* active) {
  if (params_.method == PorosityMethod::kLookup)
    throw std::invalid_argument(
        "method = 1 (lookup): the paper's lookup table holds disc areas; 3D spheres need method = 0 (exact)");
  if (!(width > 0.0) || !std::isfinite(width))
    throw std::invalid_argument("width = " + format_value(width) + " m is outside the allowed range (0, inf)");
  map_each(
      n, active,
      [&](int j) {
        require_finite("x", x[j]);
        require_finite("z", z[j]);
        require_in_closed("sphere radius", r[j], params_.r_min, params_.r_max);
      },
      [&](int j, int p) { return add_sphere(x[j], z[j], r[j], width, p); });
}

}  // namespace vofdem
