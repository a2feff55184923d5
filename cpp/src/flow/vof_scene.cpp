// The flow's scene helpers (vof_grid.h): water and porosity set in rectangles or below a level, and the
// hydrostatic pressure of the water set, so that a scene starts at rest.
#include <algorithm>
#include <cmath>

#include "vofdem/common/check.h"
#include "vofdem/flow/vof_grid.h"

namespace vofdem {

namespace {
// the cells whose centre lies inside [x0, x1] x [z0, z1]
template <class F>
void for_cells_in_box(const Grid2D& g, double x0, double x1, double z0, double z1, F&& f) {
  for (int k = 0; k < g.nz(); ++k) {
    const double z = g.z_center(k);
    if (z < z0 || z > z1) continue;
    for (int i = 0; i < g.nx(); ++i) {
      const double x = g.x_center(i);
      if (x >= x0 && x <= x1) f(g.cell(i, k));
    }
  }
}
}  // namespace

void VOFGrid::fill_water_below(double level) {
  require_finite("level", level);
  for (int k = 0; k < grid_.nz(); ++k) {
    const double f = std::clamp((level - grid_.z_face(k)) / grid_.dz(k), 0.0, 1.0);
    for (int i = 0; i < grid_.nx(); ++i) cell_F[grid_.cell(i, k)] = f;
  }
}

void VOFGrid::fill_water_box(double x0, double x1, double z0, double z1, double value) {
  require_in_closed("value", value, 0.0, 1.0);
  for_cells_in_box(grid_, x0, x1, z0, z1, [&](int c) { cell_F[c] = value; });
}

void VOFGrid::set_porosity_box(double x0, double x1, double z0, double z1, double n, double d) {
  require_in_closed("n", n, 0.0, 1.0);
  require_positive("d", d);
  for_cells_in_box(grid_, x0, x1, z0, z1, [&](int c) {
    cell_porosity[c] = n;
    cell_stone_diameter[c] = d;
  });
  update_face_porosity();
}

void VOFGrid::set_hydrostatic_pressure() {
  update_phase_properties();
  const double g = std::abs(params_.medium.gravity[1]);
  const int nx = grid_.nx(), nz = grid_.nz();
  for (int i = 0; i < nx; ++i) {
    // the discrete balance of the projection: p_k - p_{k+1} = rho_face g (z_{k+1} - z_k), p = 0 on top
    double p = cell_rho_[grid_.cell(i, nz - 1)] * g * 0.5 * grid_.dz(nz - 1);
    cell_p[grid_.cell(i, nz - 1)] = p;
    for (int k = nz - 2; k >= 0; --k) {
      p += face_z_rho_[grid_.face_z(i, k + 1)] * g * (grid_.z_center(k + 1) - grid_.z_center(k));
      cell_p[grid_.cell(i, k)] = p;
    }
  }
  for (int c = 0; c < grid_.ncell(); ++c)
    if (cell_porosity[c] <= 0.0) cell_p[c] = 0.0;
}

}  // namespace vofdem
