#include "vofdem/flow/momentum.h"

#include "common/parallel.h"
#include "flow/momentum_implicit.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

namespace vofdem {

namespace {

// value carried across the side between faces j and j + 1 of a line of m faces (pore velocities p
// with stride s), advected with velocity a: upwind with a limited slope where a second upwind exists
inline double carried(const double* p, int s, int j, int m, double a) {
  if (a >= 0.0) {
    const double up = p[j * s];
    if (j - 1 < 0) return up;
    return muscl_value(p[(j - 1) * s], up, p[(j + 1) * s]);
  }
  const double up = p[(j + 1) * s];
  if (j + 2 > m - 1) return up;
  return muscl_value(p[(j + 2) * s], up, p[j * s]);
}

// van Leer's face value without a branch: the limited value computed, then kept or not (the same value
// as muscl_value, in a form the compiler vectorises)
inline double muscl_select(double far, double up, double down) {
  const double d = down - up, b = up - far;
  const double v = up + d * b / (d + b);
  return d * b <= 0.0 ? up : v;
}

// carried() where both second upwind values exist (1 <= j <= m - 3): both directions computed, one taken
inline double carried_inner(const double* p, int s, int j, double a) {
  const double pos = muscl_select(p[(j - 1) * s], p[j * s], p[(j + 1) * s]);
  const double neg = muscl_select(p[(j + 2) * s], p[(j + 1) * s], p[j * s]);
  return a >= 0.0 ? pos : neg;
}

void pore_velocities(const Grid2D& g, const MomentumFields& f, MomentumScratch& s) {
  s.pore_u.resize(g.nface_x());
  s.pore_w.resize(g.nface_z());
  // every face divided, the closed ones' quotients (inf or nan) then dropped: a division under a
  // condition is not vectorised (it could raise a flag the condition avoids)
  detail::parallel_range(g.nface_x(), [&](long long j0, long long j1) {
    for (long long j = j0; j < j1; ++j) {
      const double n = f.face_x_porosity[j], q = f.face_u[j] / n;
      s.pore_u[j] = n > 0.0 ? q : 0.0;
    }
  });
  detail::parallel_range(g.nface_z(), [&](long long j0, long long j1) {
    for (long long j = j0; j < j1; ++j) {
      const double n = f.face_z_porosity[j], q = f.face_w[j] / n;
      s.pore_w[j] = n > 0.0 ? q : 0.0;
    }
  });
}

// corner viscosity: arithmetic mean of the cells touching the corner; with an eddy part, that part by
// harmonic mean (0 when a cell has none) and the molecular rest by arithmetic mean
// cm: (nx + 1) (nz + 1) corners; inv_eddy: ncell work values
void corner_viscosity(const Grid2D& g, const double* mu, const double* eddy, double* cm, double* inv_eddy) {
  const int nx = g.nx(), nz = g.nz(), sx = nx + 1;
  // 1 / eddy once per cell rather than at each of its four corners (the same values; unused where 0)
  if (eddy)
    detail::parallel_range(g.ncell(), [&](long long c0, long long c1) {
      for (long long c = c0; c < c1; ++c) inv_eddy[c] = eddy[c] > 0.0 ? 1.0 / eddy[c] : 0.0;
    });
  // the corner between cells a0, a1 (row below) and b0, b1 (row above); the same operations for the
  // row's inner corners (a loop without branches, vectorised) and its two end corners (the cells
  // repeated). Bitwise ands: a short-circuit would be a branch
  auto mean = [&](int a0, int a1, int b0, int b1) { return 0.25 * (mu[a0] + mu[a1] + mu[b0] + mu[b1]); };
  auto with_eddy = [&](int a0, int a1, int b0, int b1) {
    const double emean = 0.25 * (eddy[a0] + eddy[a1] + eddy[b0] + eddy[b1]);
    const bool all = (eddy[a0] > 0.0) & (eddy[a1] > 0.0) & (eddy[b0] > 0.0) & (eddy[b1] > 0.0);
    const double h = 4.0 / (inv_eddy[a0] + inv_eddy[a1] + inv_eddy[b0] + inv_eddy[b1]);
    return mean(a0, a1, b0, b1) - emean + (all ? h : 0.0);
  };
  detail::parallel_for(nz + 1, sx, [&](int kk0, int kk1) {
    for (int kk = kk0; kk < kk1; ++kk) {
      const int r0 = nx * std::max(kk - 1, 0), r1 = nx * std::min(kk, nz - 1), e = nx - 1;
      double* row = cm + sx * kk;
      if (eddy) {
        row[0] = with_eddy(r0, r0, r1, r1);
        row[nx] = with_eddy(r0 + e, r0 + e, r1 + e, r1 + e);
        for (int ii = 1; ii < nx; ++ii) row[ii] = with_eddy(r0 + ii - 1, r0 + ii, r1 + ii - 1, r1 + ii);
      } else {
        row[0] = mean(r0, r0, r1, r1);
        row[nx] = mean(r0 + e, r0 + e, r1 + e, r1 + e);
        for (int ii = 1; ii < nx; ++ii) row[ii] = mean(r0 + ii - 1, r0 + ii, r1 + ii - 1, r1 + ii);
      }
    }
  });
}

// wall functions: the corner stress on the bed and end walls is the log-law shear of the wall cells
// beside it (tau = -rho tau_wall on the bed and the left wall, +rho tau_wall on the right wall, since
// the stress difference across a control volume is the force on it)
void wall_function_shear(const Grid2D& g, const MomentumFields& f, const MomentumBoundary& bc, std::vector<double>& tau) {
  const int nx = g.nx(), nz = g.nz(), sx = nx + 1;
  if (f.face_z_wall_shear) {
    for (int ii = 0; ii <= nx; ++ii) {
      const int a = std::max(ii - 1, 0), b = std::min(ii, nx - 1);
      const double rho = 0.5 * (f.cell_rho[a] + f.cell_rho[b]);
      tau[ii] = -rho * 0.5 * (f.face_z_wall_shear[a] + f.face_z_wall_shear[b]);
    }
  }
  if (f.face_x_wall_shear) {
    for (int kk = 1; kk < nz; ++kk) {
      if (!bc.left_inlet) {
        const double rho = 0.5 * (f.cell_rho[nx * (kk - 1)] + f.cell_rho[nx * kk]);
        tau[sx * kk] = -rho * 0.5 * (f.face_x_wall_shear[sx * (kk - 1)] + f.face_x_wall_shear[sx * kk]);
      }
      if (!bc.right_open) {
        const double rho = 0.5 * (f.cell_rho[nx - 1 + nx * (kk - 1)] + f.cell_rho[nx - 1 + nx * kk]);
        tau[nx + sx * kk] = rho * 0.5 * (f.face_x_wall_shear[nx + sx * (kk - 1)] + f.face_x_wall_shear[nx + sx * kk]);
      }
    }
  }
}

// shear stress mu (du/dz + dw/dx) at every corner (x-face ii, z-face kk), ghost values at boundaries
void corner_shear(const Grid2D& g, const MomentumFields& f, const MomentumBoundary& bc, MomentumScratch& s) {
  const int nx = g.nx(), nz = g.nz(), sx = nx + 1;
  const double dx = g.dx();
  s.corner_mu.resize(static_cast<size_t>(sx) * (nz + 1));
  s.cell_inv_eddy.resize(g.ncell());
  corner_viscosity(g, f.cell_mu, f.cell_mu_eddy, s.corner_mu.data(), s.cell_inv_eddy.data());
  std::vector<double>& tau = s.corner_tau;
  tau.assign(static_cast<size_t>(sx) * (nz + 1), 0.0);
  // bed: no-slip ghost -u gives du/dz = 2u/dz; a slip bed carries no shear
  if (bc.no_slip)
    for (int ii = 0; ii <= nx; ++ii) tau[ii] = s.corner_mu[ii] * 2.0 * f.face_u[ii] / g.dz(0);
  // the open top and the slip lid are stress-free (row nz stays 0)
  const bool left_shear = bc.left_inlet || bc.no_slip;
  const bool right_shear = !bc.right_open && bc.no_slip;
  detail::parallel_for(nz - 1, sx, [&, dx](int k0, int k1) {
    for (int kk = k0 + 1; kk < k1 + 1; ++kk) {
      const double inv_dzc = 1.0 / (g.z_center(kk) - g.z_center(kk - 1));
      const double* u0 = f.face_u + sx * (kk - 1);
      const double* u1 = f.face_u + sx * kk;
      const double* w = f.face_w + nx * kk;
      for (int ii = 1; ii < nx; ++ii)
        tau[ii + sx * kk] = s.corner_mu[ii + sx * kk] * ((u1[ii] - u0[ii]) * inv_dzc + (w[ii] - w[ii - 1]) / dx);
      // end walls: ghost w = -w (no-slip, and the inlet brings no vertical velocity)
      if (left_shear) tau[sx * kk] = s.corner_mu[sx * kk] * ((u1[0] - u0[0]) * inv_dzc + 2.0 * w[0] / dx);
      if (right_shear)
        tau[nx + sx * kk] = s.corner_mu[nx + sx * kk] * ((u1[nx] - u0[nx]) * inv_dzc - 2.0 * w[nx - 1] / dx);
    }
  });
  wall_function_shear(g, f, bc, tau);
}

// the corner stress of the u-equation without its vertical part mu du/dz, which the column solve
// takes implicitly (interior corners, and the no-slip bed unless a wall function gives the shear)
void explicit_part_for_u(const Grid2D& g, const MomentumFields& f, const MomentumBoundary& bc, MomentumScratch& s) {
  const int nx = g.nx(), nz = g.nz(), sx = nx + 1;
  s.corner_tau_u = s.corner_tau;
  std::vector<double>& t = s.corner_tau_u;
  if (bc.no_slip && !f.face_z_wall_shear)
    for (int ii = 1; ii < nx; ++ii) t[ii] = 0.0;
  detail::parallel_for(nz - 1, sx, [&](int k0, int k1) {
    for (int kk = k0 + 1; kk < k1 + 1; ++kk) {
      const double inv_dzc = 1.0 / (g.z_center(kk) - g.z_center(kk - 1));
      for (int ii = 1; ii < nx; ++ii)
        t[ii + sx * kk] -=
            s.corner_mu[ii + sx * kk] * (f.face_u[ii + sx * kk] - f.face_u[ii + sx * (kk - 1)]) * inv_dzc;
    }
  });
}

// the corner stress of the w-equation without its horizontal part mu dw/dx, which the row solve takes
// implicitly (interior corners, and the end corners' ghost -w)
void explicit_part_for_w(const Grid2D& g, const MomentumFields& f, const MomentumBoundary& bc, MomentumScratch& s) {
  const int nx = g.nx(), nz = g.nz(), sx = nx + 1;
  const double inv_dx = 1.0 / g.dx();
  s.corner_tau_w = s.corner_tau;
  std::vector<double>& t = s.corner_tau_w;
  const bool left = left_w_ghost(f, bc), right = right_w_ghost(f, bc);
  detail::parallel_for(nz - 1, sx, [&, inv_dx](int k0, int k1) {
    for (int kk = k0 + 1; kk < k1 + 1; ++kk) {
      const double* w = f.face_w + nx * kk;
      const double* cm = s.corner_mu.data() + sx * kk;
      double* row = t.data() + sx * kk;
      for (int ii = 1; ii < nx; ++ii) row[ii] -= cm[ii] * (w[ii] - w[ii - 1]) * inv_dx;
      if (left) row[0] -= cm[0] * 2.0 * w[0] * inv_dx;
      if (right) row[nx] += cm[nx] * 2.0 * w[nx - 1] * inv_dx;
    }
  });
}

// the centre fluxes of row k: x-flux of u and z-flux of w (the lines' inner values by carried_inner in
// loops of their own, the ends by carried: the same values)
void centre_fluxes_row(const Grid2D& g, const MomentumFields& f, MomentumScratch& s, int k) {
  const int nx = g.nx(), nz = g.nz(), sx = nx + 1;
  const double* u = f.face_u + sx * k;
  const double* p = s.pore_u.data() + sx * k;
  double* flux = s.cell_flux_u.data() + nx * k;
  for (int i = 0; i < nx; i += std::max(nx - 1, 1)) {
    const double a = 0.5 * (u[i] + u[i + 1]);
    flux[i] = a * carried(p, 1, i, nx + 1, a);
  }
  for (int i = 1; i < nx - 1; ++i) {
    const double a = 0.5 * (u[i] + u[i + 1]);
    flux[i] = a * carried_inner(p, 1, i, a);
  }
  const double* pw = s.pore_w.data();
  const double* w = f.face_w + nx * k;
  flux = s.cell_flux_w.data() + nx * k;
  if (k >= 1 && k <= nz - 2) {
    for (int i = 0; i < nx; ++i) {
      const double b = 0.5 * (w[i] + w[i + nx]);
      flux[i] = b * carried_inner(pw + i, nx, k, b);
    }
  } else {
    for (int i = 0; i < nx; ++i) {
      const double b = 0.5 * (w[i] + w[i + nx]);
      flux[i] = b * carried(pw + i, nx, k, nz + 1, b);
    }
  }
}

// the fluxes at the inner corners of z-face row kk (1 <= kk < nz): z-flux of u, and x-flux of w with u
// interpolated to the corner height
void corner_fluxes_row(const Grid2D& g, const MomentumFields& f, MomentumScratch& s, int kk) {
  const int nx = g.nx(), nz = g.nz(), sx = nx + 1;
  const double* pu = s.pore_u.data();
  const double* w = f.face_w + nx * kk;
  double* flux = s.corner_flux_u.data() + sx * kk;
  if (kk >= 2 && kk <= nz - 2) {
    for (int ii = 1; ii < nx; ++ii) {
      const double a = 0.5 * (w[ii - 1] + w[ii]);
      flux[ii] = a * carried_inner(pu + ii, sx, kk - 1, a);
    }
  } else {
    for (int ii = 1; ii < nx; ++ii) {
      const double a = 0.5 * (w[ii - 1] + w[ii]);
      flux[ii] = a * carried(pu + ii, sx, kk - 1, nz, a);
    }
  }
  const double wl = g.dz(kk) / (g.dz(kk - 1) + g.dz(kk)), wu = 1.0 - wl;
  const double* u0 = f.face_u + sx * (kk - 1);
  const double* u1 = f.face_u + sx * kk;
  const double* prow = s.pore_w.data() + nx * kk;
  flux = s.corner_flux_w.data() + sx * kk;
  for (int ii = 0; ii <= nx; ++ii) {
    if (ii == 2) ii = std::max(2, nx - 1);  // the inner corners below
    const double a = wl * u0[ii] + wu * u1[ii];
    double v;
    if (ii == 0) v = a > 0.0 ? 0.0 : prow[0];  // the inlet brings no vertical momentum
    else if (ii == nx) v = prow[nx - 1];       // open end: zero gradient (a = 0 at a wall)
    else v = carried(prow, 1, ii - 1, nx, a);
    flux[ii] = a * v;
  }
  for (int ii = 2; ii < nx - 1; ++ii) {
    const double a = wl * u0[ii] + wu * u1[ii];
    flux[ii] = a * carried_inner(prow, 1, ii - 1, a);
  }
}

// convective fluxes of both momentum components: cell centres and corners, row by row on the threads,
// then the corners of the open boundaries
void convective_fluxes(const Grid2D& g, const MomentumFields& f, const MomentumBoundary& bc, MomentumScratch& s) {
  const int nx = g.nx(), nz = g.nz(), sx = nx + 1;
  s.cell_flux_u.resize(g.ncell());
  s.cell_flux_w.resize(g.ncell());
  s.corner_flux_u.assign(static_cast<size_t>(sx) * (nz + 1), 0.0);
  s.corner_flux_w.assign(static_cast<size_t>(sx) * (nz + 1), 0.0);
  detail::parallel_for(nz, 4 * sx, [&](int k0, int k1) {
    for (int k = k0; k < k1; ++k) {
      centre_fluxes_row(g, f, s, k);
      if (k >= 1) corner_fluxes_row(g, f, s, k);
    }
  });
  const double* pu = s.pore_u.data();
  const double* pw = s.pore_w.data();
  // the open top is zero-gradient
  if (bc.top_open)
    for (int ii = 1; ii < nx; ++ii) {
      const double a = 0.5 * (f.face_w[ii - 1 + nx * nz] + f.face_w[ii + nx * nz]);
      s.corner_flux_u[ii + sx * nz] = a * pu[ii + sx * (nz - 1)];
    }
  // z-flux of u at the corners of the open end (ghost w = w of the last column)
  if (bc.right_open) {
    for (int kk = 1; kk < nz; ++kk) {
      const double a = f.face_w[nx - 1 + nx * kk];
      s.corner_flux_u[nx + sx * kk] = a * carried(pu + nx, sx, kk - 1, nz, a);
    }
    if (bc.top_open) s.corner_flux_u[nx + sx * nz] = f.face_w[nx - 1 + nx * nz] * pu[nx + sx * (nz - 1)];
  }
  // x-flux of w at the corners of the open top (ghost u = u of the top row)
  if (bc.top_open) {
    const double* prow = pw + nx * nz;
    for (int ii = 0; ii <= nx; ++ii) {
      const double a = f.face_u[ii + sx * (nz - 1)];
      double v;
      if (ii == 0) v = a > 0.0 ? 0.0 : prow[0];
      else if (ii == nx) v = prow[nx - 1];
      else v = carried(prow, 1, ii - 1, nx, a);
      s.corner_flux_w[ii + sx * nz] = a * v;
    }
  }
}

// An open face's own momentum flux a u / n (a: its carrying velocity, u / n its pore velocity). Drawn in
// (a < 0) it is explicit; carried out (a > 0) it is implicit in u, u* = (u + dt rest) / (1 + a dt / (n h)):
// explicit, the outflow is stable only for a dt / (n h) below 1 (forward Euler) or 1/2 (AB2: the
// term's eigenvalue is -2 a / (n h)), where the water leaving needs only 2 cfl (vof_advection.h).
inline double open_inflow(double a, double pore) { return a < 0.0 ? a * pore : 0.0; }
inline double open_outflow_keep(double a, double n, double dt_over_h) {
  return a > 0.0 ? 1.0 / (1.0 + a * dt_over_h / n) : 1.0;
}

// every term in one step of dt (the viscous stresses explicit, or split with the column solves)
void momentum_once(const Grid2D& g, const MomentumFields& f, const MomentumTerms& t, const MomentumBoundary& bc,
                   double dt, std::vector<double>& u_star, std::vector<double>& w_star, MomentumScratch& s) {
  const int nx = g.nx(), nz = g.nz(), sx = nx + 1;
  const double dx = g.dx(), inv_dx = 1.0 / dx;
  u_star.assign(g.nface_x(), 0.0);
  w_star.assign(g.nface_z(), 0.0);
  // the convective term's velocities (the extrapolated ones of AB2, else the step's start)
  MomentumFields fc = f;
  if (f.conv_face_u) fc.face_u = f.conv_face_u;
  if (f.conv_face_w) fc.face_w = f.conv_face_w;
  if (t.convection) {
    pore_velocities(g, fc, s);
    convective_fluxes(g, fc, bc, s);
  }
  const bool implicit = t.viscosity && t.implicit_vertical;
  if (t.viscosity) corner_shear(g, f, bc, s);
  // the columns start from the velocities after the explicit stresses (the former scheme: from u^n)
  const bool stressed = implicit && !t.vertical_from_start;
  // the rows too: only the cross terms explicit (implicit_row_diffusion)
  const bool rows = stressed && t.implicit_horizontal;
  if (implicit) explicit_part_for_u(g, f, bc, s);
  if (rows) explicit_part_for_w(g, f, bc, s);
  if (stressed) {
    // every face the column solves read is written below (a closed face: u^n)
    s.stressed_u.resize(g.nface_x());
    s.stressed_w.resize(g.nface_z());
  }
  const double* tau_u = implicit ? s.corner_tau_u.data() : s.corner_tau.data();
  const double* tau_w = rows ? s.corner_tau_w.data() : s.corner_tau.data();
  const double* mu = f.cell_mu;
  const double xx = rows ? 0.0 : 1.0;  // the normal stress 2 mu du/dx explicit (else in the row solve)
  // x-faces
  detail::parallel_for(nz, sx, [&, inv_dx, dt, xx](int k0, int k1) {
    for (int k = k0; k < k1; ++k) {
      const double dz = g.dz(k), inv_dz = 1.0 / dz;
      for (int i = 1; i < nx; ++i) {
        const int j = i + sx * k, c = i + nx * k;
        if (f.face_x_porosity[j] <= 0.0) {
          if (stressed) s.stressed_u[j] = f.face_u[j];
          continue;
        }
        double rhs = f.face_x_porosity[j] * t.gravity_x;
        if (t.convection)
          rhs -= (s.cell_flux_u[c] - s.cell_flux_u[c - 1]) * inv_dx +
                 (s.corner_flux_u[i + sx * (k + 1)] - s.corner_flux_u[i + sx * k]) * inv_dz;
        if (t.viscosity) {
          const double txx_e = xx * 2.0 * mu[c] * (f.face_u[j + 1] - f.face_u[j]) * inv_dx;
          const double txx_w = xx * 2.0 * mu[c - 1] * (f.face_u[j] - f.face_u[j - 1]) * inv_dx;
          const double visc =
              ((txx_e - txx_w) * inv_dx + (tau_u[i + sx * (k + 1)] - tau_u[i + sx * k]) * inv_dz) / f.face_x_rho[j];
          rhs += visc;
          if (stressed) s.stressed_u[j] = f.face_u[j] + dt * visc;
        }
        u_star[j] = f.face_u[j] + dt * rhs;
      }
      // ends: the inlet keeps its value for the boundary stage; an open end's control volume reaches a
      // ghost cell of zero gradient, so the momentum leaving carries u_b u_b / n_b out
      if (bc.left_inlet) u_star[sx * k] = f.face_u[sx * k];
      const int je = nx + sx * k;
      if (bc.right_open && f.face_x_porosity[je] > 0.0) {
        double rhs = f.face_x_porosity[je] * t.gravity_x, keep = 1.0;
        if (t.convection) {
          rhs -= (open_inflow(fc.face_u[je], s.pore_u[je]) - s.cell_flux_u[nx - 1 + nx * k]) * inv_dx +
                 (s.corner_flux_u[nx + sx * (k + 1)] - s.corner_flux_u[nx + sx * k]) * inv_dz;
          keep = open_outflow_keep(fc.face_u[je], f.face_x_porosity[je], dt * inv_dx);
        }
        u_star[je] = (f.face_u[je] + dt * rhs) * keep;
      }
    }
  });
  // interior z-faces
  detail::parallel_for(nz - 1, nx, [&, inv_dx, dt](int k0, int k1) {
    for (int k = k0 + 1; k <= k1; ++k) {
      const double inv_dzc = 1.0 / (g.z_center(k) - g.z_center(k - 1));
      const double inv_dz0 = 1.0 / g.dz(k - 1), inv_dz1 = 1.0 / g.dz(k);
      for (int i = 0; i < nx; ++i) {
        const int j = i + nx * k;
        if (f.face_z_porosity[j] <= 0.0) {
          if (stressed) s.stressed_w[j] = f.face_w[j];
          continue;
        }
        double rhs = f.face_z_porosity[j] * t.gravity_z;
        if (t.convection)
          rhs -= (s.corner_flux_w[i + 1 + sx * k] - s.corner_flux_w[i + sx * k]) * inv_dx +
                 (s.cell_flux_w[j] - s.cell_flux_w[j - nx]) * inv_dzc;
        if (t.viscosity) {
          const double tzz_n = implicit ? 0.0 : 2.0 * mu[j] * (f.face_w[j + nx] - f.face_w[j]) * inv_dz1;
          const double tzz_s = implicit ? 0.0 : 2.0 * mu[j - nx] * (f.face_w[j] - f.face_w[j - nx]) * inv_dz0;
          const double visc =
              ((tau_w[i + 1 + sx * k] - tau_w[i + sx * k]) * inv_dx + (tzz_n - tzz_s) * inv_dzc) /
              f.face_z_rho[j];
          rhs += visc;
          if (stressed) s.stressed_w[j] = f.face_w[j] + dt * visc;
        }
        w_star[j] = f.face_w[j] + dt * rhs;
      }
    }
  });
  // the open top: a ghost cell of zero gradient above, as the open end
  if (bc.top_open) {
    const double inv_dz = 1.0 / g.dz(nz - 1);
    for (int i = 0; i < nx; ++i) {
      const int j = i + nx * nz;
      if (f.face_z_porosity[j] <= 0.0) continue;
      double rhs = f.face_z_porosity[j] * t.gravity_z;
      if (t.convection)
        rhs -= (s.corner_flux_w[i + 1 + sx * nz] - s.corner_flux_w[i + sx * nz]) * inv_dx +
               (fc.face_w[j] * s.pore_w[j] - s.cell_flux_w[j - nx]) * inv_dz;
      w_star[j] = f.face_w[j] + dt * rhs;
    }
  }
  if (rows) {
    implicit_rows_and_columns(g, f, bc, dt, u_star, w_star, s);
  } else if (implicit) {
    implicit_vertical_diffusion(g, f, bc, dt, stressed ? s.stressed_u.data() : f.face_u,
                                stressed ? s.stressed_w.data() : f.face_w, u_star, w_star, s);
  }
}

// the viscous increment of m substeps of dt / m added to u*, w* (open faces only: the boundary and
// closed faces carry no viscous increment in the one-step scheme either)
void add_viscous_substeps(const Grid2D& g, const MomentumFields& f, const MomentumTerms& t, const MomentumBoundary& bc,
                          double dt, std::vector<double>& u_star, std::vector<double>& w_star, MomentumScratch& s) {
  MomentumTerms vt = t;
  vt.convection = false;
  vt.gravity_x = vt.gravity_z = 0.0;
  vt.viscous_substeps = 1;
  const int m = t.viscous_substeps;
  const double h = dt / m;
  s.sub_u.assign(f.face_u, f.face_u + g.nface_x());
  s.sub_w.assign(f.face_w, f.face_w + g.nface_z());
  MomentumFields vf = f;
  vf.conv_face_u = vf.conv_face_w = nullptr;
  for (int i = 0; i < m; ++i) {
    vf.face_u = s.sub_u.data(), vf.face_w = s.sub_w.data();
    momentum_once(g, vf, vt, bc, h, s.sub_u_next, s.sub_w_next, s);
    s.sub_u.swap(s.sub_u_next), s.sub_w.swap(s.sub_w_next);
  }
  detail::parallel_range(g.nface_x(), [&](long long j0, long long j1) {
    for (long long j = j0; j < j1; ++j)
      if (f.face_x_porosity[j] > 0.0) u_star[j] += s.sub_u[j] - f.face_u[j];
  });
  detail::parallel_range(g.nface_z(), [&](long long j0, long long j1) {
    for (long long j = j0; j < j1; ++j)
      if (f.face_z_porosity[j] > 0.0) w_star[j] += s.sub_w[j] - f.face_w[j];
  });
}

}  // namespace

void momentum_explicit(const Grid2D& g, const MomentumFields& f, const MomentumTerms& t, const MomentumBoundary& bc,
                       double dt, std::vector<double>& u_star, std::vector<double>& w_star, MomentumScratch& s) {
  if (!t.viscosity || t.viscous_substeps <= 1) {
    momentum_once(g, f, t, bc, dt, u_star, w_star, s);
    return;
  }
  MomentumTerms cg = t;
  cg.viscosity = false;
  momentum_once(g, f, cg, bc, dt, u_star, w_star, s);
  add_viscous_substeps(g, f, t, bc, dt, u_star, w_star, s);
}

double viscous_stable_dt(const Grid2D& g, const MomentumFields& f, std::vector<double>& cm, bool implicit_vertical,
                         ViscousBound bound, int* cell) {
  const bool energy = bound == ViscousBound::kEnergy;
  if (energy && !implicit_vertical)
    throw std::invalid_argument("viscous_stable_dt: the energy bound holds for the split scheme only (implicit_vertical)");
  // forward Euler is stable while dt <= 2 / lambda_max; Gershgorin: lambda_max <= max row sum of |A|,
  // whose row of a face is twice its diagonal plus (kRowSum) the u-w cross terms. kEnergy (momentum.h):
  // no cross terms, and the x-diffusion of w doubled
  const double zf = implicit_vertical ? 0.0 : 1.0;
  const double xf = energy ? 0.0 : 1.0, wf = energy ? 2.0 : 1.0;
  const int nx = g.nx(), nz = g.nz(), sx = nx + 1;
  const double dx = g.dx();
  // corners first, then the per-cell work values of the corner viscosity, then the rows' largest rates
  const std::size_t ncorner = static_cast<std::size_t>(sx) * (nz + 1);
  const std::size_t rows_x = detail::row_maxima_size(nz, sx), rows_z = detail::row_maxima_size(nz - 1, sx);
  cm.resize(ncorner + g.ncell() + std::max(rows_x, rows_z));
  corner_viscosity(g, f.cell_mu, f.cell_mu_eddy, cm.data(), cm.data() + ncorner);
  double* work = cm.data() + ncorner + g.ncell();
  double worst = 0.0;
  int where = -1;
  // each row's rates first (divisions without a branch, closed faces 0: vectorised), then its largest
  // (the rows on the threads), then the rows in order: row k's first face at i0 + (its position) + nx k
  auto take = [&](int rows, int k0, int i0) {
    for (int r = 0; r < rows; ++r)
      if (work[r] > worst) worst = work[r], where = i0 + static_cast<int>(work[rows + r]) + nx * (k0 + r);
  };
  detail::row_maxima(nz, sx, work, [&, dx, zf, xf](int k, double* rate) {
    const double dz = g.dz(k);
    const double* mu = f.cell_mu + nx * k;  // mu[i - 1], mu[i]: the cells left and right of x-face i
    const double* mn = cm.data() + sx * (k + 1);
    const double* ms = cm.data() + sx * k;
    const double* rho = f.face_x_rho + sx * k;
    const double* n = f.face_x_porosity + sx * k;
    for (int i = 1; i < nx; ++i) {
      const double diag = 2.0 * (mu[i - 1] + mu[i]) / (dx * dx) + zf * (mn[i] + ms[i]) / (dz * dz);
      const double cross = xf * 2.0 * (mn[i] + ms[i]) / (dx * dz);
      const double r = (2.0 * diag + cross) / rho[i];
      rate[i - 1] = n[i] > 0.0 ? r : 0.0;
    }
    return nx - 1;
  });
  take(nz, 0, 1);
  detail::row_maxima(nz - 1, sx, work, [&, dx, zf, xf, wf](int r, double* rate) {
    const int k = r + 1;
    const double dzc = g.z_center(k) - g.z_center(k - 1);
    const double hz = std::min(g.dz(k), g.dz(k - 1));
    const double* mb = f.cell_mu + nx * (k - 1);
    const double* mt = f.cell_mu + nx * k;
    const double* mw = cm.data() + sx * k;  // mw[i]: the corner left of z-face i; mw[i + 1] right of it
    const double* rho = f.face_z_rho + nx * k;
    const double* n = f.face_z_porosity + nx * k;
    for (int i = 0; i < nx; ++i) {
      const double diag = zf * 2.0 * (mb[i] + mt[i]) / (dzc * hz) + wf * (mw[i + 1] + mw[i]) / (dx * dx);
      const double cross = xf * 2.0 * (mw[i + 1] + mw[i]) / (dx * hz);
      const double r = (2.0 * diag + cross) / rho[i];
      rate[i] = n[i] > 0.0 ? r : 0.0;
    }
    return nx;
  });
  take(nz - 1, 1, 0);
  if (cell) *cell = where;
  return worst > 0.0 ? 2.0 / worst : std::numeric_limits<double>::infinity();
}

}  // namespace vofdem
