#include "vofdem/momentum.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace vofdem {

namespace {

// pore velocity of a face: u / n, 0 on a closed face
inline double pore(double v, double n) { return n > 0.0 ? v / n : 0.0; }

// one momentum component's view: value and porosity of face j along a line of faces
struct Line {
  const double* v;
  const double* n;
  int stride;
  double at(int j) const { return pore(v[j * stride], n[j * stride]); }
};

// carried value across a side between faces j and j + 1 of a line of m faces (0..m-1), advected
// with velocity a: the upwind face's pore velocity with a limited slope where a second upwind exists
inline double carried(const Line& line, int j, int m, double a) {
  if (a >= 0.0) {
    const double up = line.at(j);
    if (j - 1 < 0) return up;
    return muscl_value(line.at(j - 1), up, line.at(j + 1));
  }
  const double up = line.at(j + 1);
  if (j + 2 > m - 1) return up;
  return muscl_value(line.at(j + 2), up, line.at(j));
}

double corner_mu(const Grid2D& g, const double* mu, int ii, int kk) {
  const int nx = g.nx(), nz = g.nz();
  double s = 0.0;
  int c = 0;
  for (int k = kk - 1; k <= kk; ++k) {
    if (k < 0 || k >= nz) continue;
    for (int i = ii - 1; i <= ii; ++i) {
      if (i < 0 || i >= nx) continue;
      s += mu[i + nx * k];
      ++c;
    }
  }
  return c ? s / c : 0.0;
}

// shear stress mu (du/dz + dw/dx) at every corner (x-face ii, z-face kk), ghost values at boundaries
void corner_shear(const Grid2D& g, const MomentumFields& f, const MomentumBoundary& bc, std::vector<double>& tau) {
  const int nx = g.nx(), nz = g.nz(), sx = nx + 1;
  const double dx = g.dx();
  tau.assign(static_cast<size_t>(sx) * (nz + 1), 0.0);
  for (int kk = 0; kk <= nz; ++kk) {
    for (int ii = 0; ii <= nx; ++ii) {
      double dudz = 0.0, dwdx = 0.0;
      if (kk == 0) {
        // bed: no-slip ghost -u, slip ghost +u
        if (bc.no_slip) dudz = 2.0 * f.face_u[ii] / g.dz(0);
      } else if (kk == nz) {
        continue;  // open top or slip lid: stress-free
      } else {
        dudz = (f.face_u[ii + sx * kk] - f.face_u[ii + sx * (kk - 1)]) / (g.z_center(kk) - g.z_center(kk - 1));
      }
      if (kk > 0) {
        if (ii == 0) {
          if (bc.left_inlet || bc.no_slip) dwdx = 2.0 * f.face_w[nx * kk] / dx;
        } else if (ii == nx) {
          if (!bc.right_open && bc.no_slip) dwdx = -2.0 * f.face_w[nx - 1 + nx * kk] / dx;
        } else {
          dwdx = (f.face_w[ii + nx * kk] - f.face_w[ii - 1 + nx * kk]) / dx;
        }
      }
      // a slip wall carries no shear at all
      if (kk == 0 && !bc.no_slip) continue;
      if ((ii == 0 && !bc.left_inlet && !bc.no_slip) || (ii == nx && (bc.right_open || !bc.no_slip))) continue;
      tau[ii + sx * kk] = corner_mu(g, f.cell_mu, ii, kk) * (dudz + dwdx);
    }
  }
}

double x_face_rhs(const Grid2D& g, const MomentumFields& f, const MomentumTerms& t, const MomentumBoundary& bc,
                  const std::vector<double>& tau, int i, int k) {
  const int nx = g.nx(), nz = g.nz(), sx = nx + 1;
  const double dx = g.dx(), dz = g.dz(k);
  const int j = i + sx * k;
  double rhs = f.face_x_porosity[j] * t.gravity_x;
  if (t.convection) {
    const Line row{f.face_u + sx * k, f.face_x_porosity + sx * k, 1};
    // x-fluxes at the cell centres right (i) and left (i - 1) of the face
    const double ae = 0.5 * (f.face_u[j] + f.face_u[j + 1]);
    const double aw = 0.5 * (f.face_u[j - 1] + f.face_u[j]);
    const double fe = ae * carried(row, i, nx + 1, ae);
    const double fw = aw * carried(row, i - 1, nx + 1, aw);
    // z-fluxes at the corners above (k + 1) and below (k)
    const Line col{f.face_u + i, f.face_x_porosity + i, sx};
    double fn = 0.0, fs = 0.0;
    if (k + 1 < nz) {
      const double an = 0.5 * (f.face_w[i - 1 + nx * (k + 1)] + f.face_w[i + nx * (k + 1)]);
      fn = an * carried(col, k, nz, an);
    } else if (bc.top_open) {
      const double an = 0.5 * (f.face_w[i - 1 + nx * nz] + f.face_w[i + nx * nz]);
      fn = an * col.at(k);
    }
    if (k > 0) {
      const double as = 0.5 * (f.face_w[i - 1 + nx * k] + f.face_w[i + nx * k]);
      fs = as * carried(col, k - 1, nz, as);
    }
    rhs -= (fe - fw) / dx + (fn - fs) / dz;
  }
  if (t.viscosity) {
    const int c = i + nx * k;
    const double txx_e = 2.0 * f.cell_mu[c] * (f.face_u[j + 1] - f.face_u[j]) / dx;
    const double txx_w = 2.0 * f.cell_mu[c - 1] * (f.face_u[j] - f.face_u[j - 1]) / dx;
    rhs += ((txx_e - txx_w) / dx + (tau[i + sx * (k + 1)] - tau[i + sx * k]) / dz) / f.face_x_rho[j];
  }
  return rhs;
}

double z_face_rhs(const Grid2D& g, const MomentumFields& f, const MomentumTerms& t, const MomentumBoundary& bc,
                  const std::vector<double>& tau, int i, int k) {
  const int nx = g.nx(), nz = g.nz(), sx = nx + 1;
  const double dx = g.dx();
  const double dzc = g.z_center(k) - g.z_center(k - 1);
  const int j = i + nx * k;
  double rhs = f.face_z_porosity[j] * t.gravity_z;
  if (t.convection) {
    const Line col{f.face_w + i, f.face_z_porosity + i, nx};
    const double an = 0.5 * (f.face_w[j] + f.face_w[j + nx]);
    const double as = 0.5 * (f.face_w[j - nx] + f.face_w[j]);
    const double fn = an * carried(col, k, nz + 1, an);
    const double fs = as * carried(col, k - 1, nz + 1, as);
    // x-velocity at the corner height z_face(k), interpolated between the rows k - 1 and k
    const double wl = g.dz(k) / (g.dz(k - 1) + g.dz(k)), wu = 1.0 - wl;
    auto corner_u = [&](int ii) { return wl * f.face_u[ii + sx * (k - 1)] + wu * f.face_u[ii + sx * k]; };
    const Line row{f.face_w + nx * k, f.face_z_porosity + nx * k, 1};
    auto side_flux = [&](int ii) {
      const double a = corner_u(ii);
      if (ii == 0) return a > 0.0 ? 0.0 : a * row.at(0);  // the inlet brings no vertical momentum
      if (ii == nx) return a * row.at(nx - 1);             // open end: zero gradient
      return a * carried(row, ii - 1, nx, a);
    };
    rhs -= (side_flux(i + 1) - side_flux(i)) / dx + (fn - fs) / dzc;
  }
  if (t.viscosity) {
    const double tzz_n = 2.0 * f.cell_mu[i + nx * k] * (f.face_w[j + nx] - f.face_w[j]) / g.dz(k);
    const double tzz_s = 2.0 * f.cell_mu[i + nx * (k - 1)] * (f.face_w[j] - f.face_w[j - nx]) / g.dz(k - 1);
    rhs += ((tau[i + 1 + sx * k] - tau[i + sx * k]) / dx + (tzz_n - tzz_s) / dzc) / f.face_z_rho[j];
  }
  (void)bc;
  return rhs;
}

}  // namespace

void momentum_explicit(const Grid2D& g, const MomentumFields& f, const MomentumTerms& t, const MomentumBoundary& bc,
                       double dt, std::vector<double>& u_star, std::vector<double>& w_star, MomentumScratch& s) {
  const int nx = g.nx(), nz = g.nz(), sx = nx + 1;
  u_star.assign(g.nface_x(), 0.0);
  w_star.assign(g.nface_z(), 0.0);
  if (t.viscosity) corner_shear(g, f, bc, s.corner_tau);
  for (int k = 0; k < nz; ++k) {
    for (int i = 1; i < nx; ++i) {
      const int j = i + sx * k;
      if (f.face_x_porosity[j] <= 0.0) continue;
      u_star[j] = f.face_u[j] + dt * x_face_rhs(g, f, t, bc, s.corner_tau, i, k);
    }
    // ends: the inlet keeps its value for the boundary stage; an open end is zero-gradient
    if (bc.left_inlet) u_star[sx * k] = f.face_u[sx * k];
    const int je = nx + sx * k;
    if (bc.right_open && f.face_x_porosity[je] > 0.0)
      u_star[je] = f.face_u[je] + dt * f.face_x_porosity[je] * t.gravity_x;
  }
  for (int k = 1; k < nz; ++k) {
    for (int i = 0; i < nx; ++i) {
      const int j = i + nx * k;
      if (f.face_z_porosity[j] <= 0.0) continue;
      w_star[j] = f.face_w[j] + dt * z_face_rhs(g, f, t, bc, s.corner_tau, i, k);
    }
  }
  if (bc.top_open) {
    for (int i = 0; i < nx; ++i) {
      const int j = i + nx * nz;
      if (f.face_z_porosity[j] > 0.0) w_star[j] = f.face_w[j] + dt * f.face_z_porosity[j] * t.gravity_z;
    }
  }
}

double viscous_stable_dt(const Grid2D& g, const MomentumFields& f) {
  // forward Euler is stable while dt <= 2 / lambda_max; Gershgorin: lambda_max <= max row sum of |A|,
  // whose row of a face is twice its diagonal plus the u-w cross terms
  const int nx = g.nx(), nz = g.nz(), sx = nx + 1;
  const double dx = g.dx();
  double worst = 0.0;
  for (int k = 0; k < nz; ++k) {
    const double dz = g.dz(k);
    for (int i = 1; i < nx; ++i) {
      const int j = i + sx * k;
      if (f.face_x_porosity[j] <= 0.0) continue;
      const double ml = f.cell_mu[i - 1 + nx * k], mr = f.cell_mu[i + nx * k];
      const double mn = corner_mu(g, f.cell_mu, i, k + 1), ms = corner_mu(g, f.cell_mu, i, k);
      const double diag = 2.0 * (ml + mr) / (dx * dx) + (mn + ms) / (dz * dz);
      const double cross = 2.0 * (mn + ms) / (dx * dz);
      worst = std::max(worst, (2.0 * diag + cross) / f.face_x_rho[j]);
    }
  }
  for (int k = 1; k < nz; ++k) {
    const double dzc = g.z_center(k) - g.z_center(k - 1);
    const double hz = std::min(g.dz(k), g.dz(k - 1));
    for (int i = 0; i < nx; ++i) {
      const int j = i + nx * k;
      if (f.face_z_porosity[j] <= 0.0) continue;
      const double mb = f.cell_mu[i + nx * (k - 1)], mt = f.cell_mu[i + nx * k];
      const double me = corner_mu(g, f.cell_mu, i + 1, k), mw = corner_mu(g, f.cell_mu, i, k);
      const double diag = 2.0 * (mb + mt) / (dzc * hz) + (me + mw) / (dx * dx);
      const double cross = 2.0 * (me + mw) / (dx * hz);
      worst = std::max(worst, (2.0 * diag + cross) / f.face_z_rho[j]);
    }
  }
  return worst > 0.0 ? 2.0 / worst : std::numeric_limits<double>::infinity();
}

}  // namespace vofdem
