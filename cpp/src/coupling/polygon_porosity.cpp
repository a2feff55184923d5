// Porosity of the cells from convex polygon stones: exact polygon-cell areas (see porosity_map.h).
//
// A polygon is clipped to each column of its bounding box (two axis-aligned half-planes), and each
// column strip to each row: the pieces partition the polygon, so the areas sum to its area up to
// round-off, and eq. (11) maps them as it maps the discs' areas.
#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include "vofdem/common/check.h"
#include "vofdem/stones/polygon.h"
#include "vofdem/coupling/porosity_map.h"

namespace vofdem {

int PorosityMapper::add_polygon(const double* world, int count, int p) {
  double xmin = INFINITY, xmax = -INFINITY, zmin = INFINITY, zmax = -INFINITY;
  for (int k = 0; k < count; ++k) {
    xmin = std::min(xmin, world[2 * k]);
    xmax = std::max(xmax, world[2 * k]);
    zmin = std::min(zmin, world[2 * k + 1]);
    zmax = std::max(zmax, world[2 * k + 1]);
  }
  const double xend = grid_.x_face(grid_.nx());
  const double z0 = grid_.z_face(0), zend = grid_.z_face(grid_.nz());
  if (xmax <= grid_.x0() || xmin >= xend || zmax <= z0 || zmin >= zend) return p;
  const int i0 = grid_.locate_x(xmin), i1 = grid_.locate_x(xmax);
  const int k0 = grid_.locate_z(zmin), k1 = grid_.locate_z(zmax);
  if ((i1 - i0 + 1) * (k1 - k0 + 1) > max_cells_per_disc_)
    throw std::logic_error("porosity_map: polygon stencil larger than its bound");
  // scratch: a column strip (count + 2 vertices at most), then two clip buffers for the rows
  double* strip = poly_scratch_.data() + 2 * kPolygonMaxVertices;
  double* tmp = strip + 2 * (kPolygonMaxVertices + 2);
  double* piece = tmp + 2 * (kPolygonMaxVertices + 4);
  for (int i = i0; i <= i1; ++i) {
    int m = clip_polygon_axis(world, count, 0, grid_.x_face(i), -1.0, tmp);
    m = clip_polygon_axis(tmp, m, 0, grid_.x_face(i + 1), 1.0, strip);
    if (m == 0) continue;
    for (int k = k0; k <= k1; ++k) {
      int q = clip_polygon_axis(strip, m, 1, grid_.z_face(k), -1.0, tmp);
      q = clip_polygon_axis(tmp, q, 1, grid_.z_face(k + 1), 1.0, piece);
      if (q == 0) continue;
      const double area = std::clamp(polygon_area(piece, q), 0.0, grid_.cell_area(k));
      if (area <= 0.0) continue;
      const int c = grid_.cell(i, k);
      p = append_cell(c, area, p);
    }
  }
  return p;
}

void PorosityMapper::map_polygons(int n, const double* x, const double* z, const double* angle,
                                  const double* poly_vertex, const int* poly_offset, const std::uint8_t* active) {
  if (params_.method == PorosityMethod::kLookup)
    throw std::invalid_argument(
        "method = 1 (lookup): the paper's lookup table holds disc areas; polygon stones need method = 0 (exact)");
  double* world = poly_scratch_.data();
  map_each(
      n, active,
      [&](int j) {
        require_finite("x", x[j]);
        require_finite("z", z[j]);
        require_finite("angle", angle[j]);
        const int count = poly_offset[j + 1] - poly_offset[j];
        if (count < 3 || count > kPolygonMaxVertices)
          throw std::invalid_argument("polygon " + std::to_string(j) + " has " + std::to_string(count) +
                                      " vertices: allowed range [3, " + std::to_string(kPolygonMaxVertices) + "]");
        double r2 = 0.0;
        for (int k = poly_offset[j]; k < poly_offset[j + 1]; ++k)
          r2 = std::max(r2, poly_vertex[2 * k] * poly_vertex[2 * k] + poly_vertex[2 * k + 1] * poly_vertex[2 * k + 1]);
        require_in_closed("polygon bounding radius", std::sqrt(r2), 0.0, params_.r_max * (1.0 + 1e-12));
      },
      [&](int j, int p) {
        const int o = poly_offset[j], count = poly_offset[j + 1] - o;
        polygon_to_world(poly_vertex + 2 * o, count, x[j], z[j], angle[j], world);
        return add_polygon(world, count, p);
      });
}

}  // namespace vofdem
