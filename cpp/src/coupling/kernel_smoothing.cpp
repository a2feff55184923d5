#include "vofdem/coupling/kernel_smoothing.h"

#include <cmath>
#include <stdexcept>
#include <string>

#include "vofdem/common/check.h"

namespace vofdem {

void KernelParams::validate() const {
  require_in_open_closed("bandwidth", bandwidth, 0.0, 1.0);
  if (steps < 1 || steps > 64)
    throw std::invalid_argument("steps = " + std::to_string(steps) + " is outside the allowed range [1, 64]");
}

KernelSmoother::KernelSmoother(const Grid2D& grid, const KernelParams& params,
                               const std::vector<std::uint8_t>* cell_solid)
    : nx_(grid.nx()), nz_(grid.nz()), params_(params) {
  params_.validate();
  const std::size_t nc = static_cast<std::size_t>(grid.ncell());
  if (cell_solid && cell_solid->size() != nc)
    throw std::invalid_argument("cell_solid has " + std::to_string(cell_solid->size()) + " values, expected ncell = " +
                                std::to_string(nc));
  const std::vector<std::uint8_t> none(nc, 0);
  const std::vector<std::uint8_t>& solid = cell_solid ? *cell_solid : none;
  const double tau = pseudo_time() / params_.steps;
  // x: per unit row height (the row's dz scales V and K alike); z: the rows' own heights
  const double dx = grid.dx();
  auto x_line = [&](double t, LineOp& op) {
    op.lo.assign(nc, 0.0), op.cp.assign(nc, 0.0), op.inv.assign(nc, 0.0), op.w.assign(nc, 0.0);
    for (int k = 0; k < nz_; ++k) {
      auto cond = [&](int i) {  // conductance of the face between cells i - 1 and i of row k
        if (i <= 0 || i >= nx_ || solid[grid.cell(i - 1, k)] || solid[grid.cell(i, k)]) return 0.0;
        return t / dx;
      };
      double cp_prev = 0.0;
      for (int i = 0; i < nx_; ++i) {
        const int c = grid.cell(i, k);
        const double gl = cond(i), gr = cond(i + 1), w = solid[c] ? 1.0 : dx;
        const double den = w + gl + gr + gl * cp_prev;
        op.lo[c] = -gl, op.w[c] = w, op.inv[c] = 1.0 / den, op.cp[c] = -gr / den;
        cp_prev = op.cp[c];
      }
    }
  };
  auto z_line = [&](double t, LineOp& op) {
    op.lo.assign(nc, 0.0), op.cp.assign(nc, 0.0), op.inv.assign(nc, 0.0), op.w.assign(nc, 0.0);
    for (int i = 0; i < nx_; ++i) {
      auto cond = [&](int k) {  // conductance of the face between rows k - 1 and k of column i
        if (k <= 0 || k >= nz_ || solid[grid.cell(i, k - 1)] || solid[grid.cell(i, k)]) return 0.0;
        return t / (grid.z_center(k) - grid.z_center(k - 1));
      };
      double cp_prev = 0.0;
      for (int k = 0; k < nz_; ++k) {
        const int c = grid.cell(i, k);
        const double gl = cond(k), gr = cond(k + 1), w = solid[c] ? 1.0 : grid.dz(k);
        const double den = w + gl + gr + gl * cp_prev;
        op.lo[c] = -gl, op.w[c] = w, op.inv[c] = 1.0 / den, op.cp[c] = -gr / den;
        cp_prev = op.cp[c];
      }
    }
  };
  x_line(0.5 * tau, x_half_);
  x_line(tau, x_full_);
  z_line(tau, z_full_);
}

double KernelSmoother::sigma() const { return params_.bandwidth / std::sqrt(2.0); }

// Thomas along each row, in place: forward d_i = (w_i a_i - lo_i d_(i-1)) / den_i, back x_i = d_i - cp_i x_(i+1).
// The rows side by side (column index outer): each row's recurrence is a chain of dependent operations, and
// interleaving the independent rows hides their latency (3 times faster than row after row, measured)
void KernelSmoother::sweep_x(const LineOp& op, double* f) {
  const double *lo = op.lo.data(), *inv = op.inv.data(), *w = op.w.data(), *cp = op.cp.data();
  const int nx = nx_, nz = nz_;
  for (int k = 0; k < nz; ++k) f[nx * k] = w[nx * k] * f[nx * k] * inv[nx * k];
  for (int i = 1; i < nx; ++i)
    for (int k = 0; k < nz; ++k) {
      const int c = i + nx * k;
      f[c] = (w[c] * f[c] - lo[c] * f[c - 1]) * inv[c];
    }
  for (int i = nx - 2; i >= 0; --i)
    for (int k = 0; k < nz; ++k) {
      const int c = i + nx * k;
      f[c] -= cp[c] * f[c + 1];
    }
}

// the same along the columns, all columns at once row by row (unit stride)
void KernelSmoother::sweep_z(const LineOp& op, double* f) {
  const double *lo = op.lo.data(), *inv = op.inv.data(), *w = op.w.data(), *cp = op.cp.data();
  for (int i = 0; i < nx_; ++i) f[i] = w[i] * f[i] * inv[i];
  for (int k = 1; k < nz_; ++k) {
    const int c0 = nx_ * k;
    for (int c = c0; c < c0 + nx_; ++c) f[c] = (w[c] * f[c] - lo[c] * f[c - nx_]) * inv[c];
  }
  for (int k = nz_ - 2; k >= 0; --k) {
    const int c0 = nx_ * k;
    for (int c = c0; c < c0 + nx_; ++c) f[c] -= cp[c] * f[c + nx_];
  }
}

void KernelSmoother::smooth(double* field) {
  sweep_x(x_half_, field);
  for (int s = 0; s < params_.steps; ++s) {
    sweep_z(z_full_, field);
    sweep_x(s + 1 < params_.steps ? x_full_ : x_half_, field);
  }
}

void KernelSmoother::smooth(std::vector<double>& field) {
  if (static_cast<int>(field.size()) != ncell())
    throw std::invalid_argument("field has " + std::to_string(field.size()) + " values, expected ncell = " +
                                std::to_string(ncell()));
  smooth(field.data());
}

}  // namespace vofdem
