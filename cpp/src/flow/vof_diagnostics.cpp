// The flow's diagnostics (vof_grid.h): pore velocity and pressure gradient at the cell centres (read by
// the coupler's fluid forces), the water volume, the discharge through a column of faces and at the
// inlet. None of them changes the state.
#include <stdexcept>
#include <string>
#include <vector>

#include "vofdem/flow/vof_grid.h"

namespace vofdem {

void VOFGrid::pore_velocity_at(int c, double& U, double& W) const {
  const double n = cell_porosity[c];
  if (n <= 0.0) return;
  const int nx = grid_.nx(), i = c % nx, k = c / nx;
  U = 0.5 * (face_u[grid_.face_x(i, k)] + face_u[grid_.face_x(i + 1, k)]) / n;
  W = 0.5 * (face_w[grid_.face_z_below(c)] + face_w[grid_.face_z_above(c)]) / n;
}

void VOFGrid::pressure_gradient_at(int c, double& dpdx, double& dpdz) const {
  const int nx = grid_.nx(), nz = grid_.nz(), i = c % nx, k = c / nx;
  auto active = [&](int ii, int kk) {
    return ii >= 0 && ii < nx && kk >= 0 && kk < nz && cell_porosity[grid_.cell(ii, kk)] > 0.0;
  };
  if (!active(i, k)) return;
  // central where both neighbours are fluid, one-sided next to a wall or a solid
  const bool l = active(i - 1, k), r = active(i + 1, k);
  if (l && r) dpdx = (cell_p[c + 1] - cell_p[c - 1]) / (2.0 * grid_.dx());
  else if (r) dpdx = (cell_p[c + 1] - cell_p[c]) / grid_.dx();
  else if (l) dpdx = (cell_p[c] - cell_p[c - 1]) / grid_.dx();
  const bool b = active(i, k - 1), t = active(i, k + 1);
  const int above = grid_.cell_above(c), below = grid_.cell_below(c);
  if (b && t) dpdz = (cell_p[above] - cell_p[below]) / (grid_.z_center(k + 1) - grid_.z_center(k - 1));
  else if (t) dpdz = (cell_p[above] - cell_p[c]) / (grid_.z_center(k + 1) - grid_.z_center(k));
  else if (b) dpdz = (cell_p[c] - cell_p[below]) / (grid_.z_center(k) - grid_.z_center(k - 1));
}

void VOFGrid::pore_velocity_at_cells(std::vector<double>& U, std::vector<double>& W) const {
  U.assign(grid_.ncell(), 0.0);
  W.assign(grid_.ncell(), 0.0);
  for (int c = 0; c < grid_.ncell(); ++c) pore_velocity_at(c, U[c], W[c]);
}

void VOFGrid::pressure_gradient_at_cells(std::vector<double>& dpdx, std::vector<double>& dpdz) const {
  dpdx.assign(grid_.ncell(), 0.0);
  dpdz.assign(grid_.ncell(), 0.0);
  for (int c = 0; c < grid_.ncell(); ++c) pressure_gradient_at(c, dpdx[c], dpdz[c]);
}

namespace {
// the two values of each listed cell from at(c, x, y), zeroed first (a solid cell's stay 0)
template <class At>
void at_listed_cells(int ncell, int count, const int* cells, std::vector<double>& x, std::vector<double>& y, At at) {
  x.resize(ncell, 0.0);
  y.resize(ncell, 0.0);
  for (int m = 0; m < count; ++m) {
    const int c = cells[m];
    x[c] = y[c] = 0.0;
    at(c, x[c], y[c]);
  }
}
}  // namespace

void VOFGrid::pore_velocity_at_cells(int count, const int* cells, std::vector<double>& U,
                                     std::vector<double>& W) const {
  at_listed_cells(grid_.ncell(), count, cells, U, W, [this](int c, double& u, double& w) { pore_velocity_at(c, u, w); });
}

void VOFGrid::pressure_gradient_at_cells(int count, const int* cells, std::vector<double>& dpdx,
                                         std::vector<double>& dpdz) const {
  at_listed_cells(grid_.ncell(), count, cells, dpdx, dpdz,
                  [this](int c, double& gx, double& gz) { pressure_gradient_at(c, gx, gz); });
}

double VOFGrid::water_volume() const {
  const int nx = grid_.nx();
  double v = 0.0;
  for (int k = 0; k < grid_.nz(); ++k) {
    double row = 0.0;
    for (int i = 0; i < nx; ++i) row += cell_porosity[grid_.cell(i, k)] * cell_F[grid_.cell(i, k)];
    v += row * grid_.cell_area(k);
  }
  return v;
}

double VOFGrid::discharge_through(int i) const {
  if (i < 0 || i > grid_.nx())
    throw std::invalid_argument("i = " + std::to_string(i) + " is outside the allowed range [0, " +
                                std::to_string(grid_.nx()) + "]");
  const int nx = grid_.nx();
  double q = 0.0;
  const std::vector<double>& flux = vof_scratch_.face_flux_x;
  if (flux_dt_ > 0.0 && flux.size() == static_cast<std::size_t>(grid_.nface_x())) {
    for (int k = 0; k < grid_.nz(); ++k) q += flux[grid_.face_x(i, k)];
    return q / flux_dt_;
  }
  for (int k = 0; k < grid_.nz(); ++k) {
    const double u = face_u[grid_.face_x(i, k)];
    // the fraction of the cell the flow leaves (the inflow fraction 1 at the inlet)
    double f;
    if (u >= 0.0) f = i > 0 ? cell_F[grid_.cell(i - 1, k)] : 1.0;
    else f = i < nx ? cell_F[grid_.cell(i, k)] : 0.0;
    q += u * f * grid_.dz(k);
  }
  return q;
}

double VOFGrid::inlet_discharge_per_width() const {
  return params_.inlet == InletBoundary::kDischarge ? discharge_.at(time_) / params_.flume_width : 0.0;
}

}  // namespace vofdem
