// The momentum kernels' vectorised loops (momentum.cpp: pore velocities, the MUSCL convective fluxes
// with their inner values computed apart from the lines' ends, the implicit vertical diffusion's column
// systems assembled row by row, the horizontal diffusion's row systems solved together) against a
// reference written face by
// face, as plainly as the scheme reads: the same bits on random fields with closed faces and flows of
// both signs, on grids small enough that every end case and every inner range (empty too) occurs.
#include <gtest/gtest.h>

#include <vector>

#include "vofdem/flow/momentum.h"

using namespace vofdem;

namespace {

// the value carried across the side between entries j and j + 1 of a line, advected with velocity a
double reference_carried(const std::vector<double>& line, int j, double a) {
  const int m = static_cast<int>(line.size());
  const bool forward = a >= 0.0;
  const int up = forward ? j : j + 1, far = forward ? j - 1 : j + 2, down = forward ? j + 1 : j;
  if (far < 0 || far > m - 1) return line[up];
  return muscl_value(line[far], line[up], line[down]);
}

struct Random {
  unsigned seed;
  double operator()() { return (seed = seed * 1103515245u + 12345u) / 4294967296.0; }
};

void check_fluxes(int nx, int nz, unsigned seed) {
  const Grid2D g = Grid2D::uniform(nx, nz, 0.025 * nx, 0.01 * nz);
  const int sx = nx + 1;
  Random rnd{seed};
  std::vector<double> u(g.nface_x()), w(g.nface_z()), nxp(g.nface_x()), nzp(g.nface_z());
  std::vector<double> mu(g.ncell(), 1e-3), rx(g.nface_x(), 1000.0), rz(g.nface_z(), 1000.0);
  for (auto* v : {&u, &w})
    for (double& x : *v) x = rnd() - 0.5;  // both signs, and exact repeats are rare: both limiter branches
  for (auto* v : {&nxp, &nzp})
    for (double& x : *v) x = rnd() < 0.15 ? 0.0 : 0.2 + 0.8 * rnd();
  MomentumFields f{u.data(), w.data(), nxp.data(), nzp.data(), mu.data(), rx.data(), rz.data()};
  MomentumTerms t;
  t.viscosity = false;
  MomentumBoundary bc;  // the open top and end: their rows too
  bc.right_open = bc.top_open = true;
  std::vector<double> us, ws;
  MomentumScratch s;
  momentum_explicit(g, f, t, bc, 1e-3, us, ws, s);
  auto pore = [](double v, double n) { return n > 0.0 ? v / n : 0.0; };
  for (int j = 0; j < g.nface_x(); ++j) ASSERT_EQ(s.pore_u[j], pore(u[j], nxp[j])) << j;
  for (int j = 0; j < g.nface_z(); ++j) ASSERT_EQ(s.pore_w[j], pore(w[j], nzp[j])) << j;
  // lines of pore velocities: rows of x-faces, columns of z-faces, columns of x-faces (nz entries), rows of z-faces
  auto row_u = [&](int k) { return std::vector<double>(s.pore_u.begin() + sx * k, s.pore_u.begin() + sx * (k + 1)); };
  auto col_w = [&](int i) {
    std::vector<double> c;
    for (int k = 0; k <= nz; ++k) c.push_back(s.pore_w[i + nx * k]);
    return c;
  };
  auto col_u = [&](int ii) {
    std::vector<double> c;
    for (int k = 0; k < nz; ++k) c.push_back(s.pore_u[ii + sx * k]);
    return c;
  };
  auto row_w = [&](int kk) { return std::vector<double>(s.pore_w.begin() + nx * kk, s.pore_w.begin() + nx * (kk + 1)); };
  for (int k = 0; k < nz; ++k)
    for (int i = 0; i < nx; ++i) {
      const double a = 0.5 * (u[i + sx * k] + u[i + 1 + sx * k]);
      ASSERT_EQ(s.cell_flux_u[i + nx * k], a * reference_carried(row_u(k), i, a)) << nx << "x" << nz << " " << i << "," << k;
      const double b = 0.5 * (w[i + nx * k] + w[i + nx * (k + 1)]);
      ASSERT_EQ(s.cell_flux_w[i + nx * k], b * reference_carried(col_w(i), k, b)) << nx << "x" << nz << " " << i << "," << k;
    }
  for (int kk = 1; kk < nz; ++kk) {
    for (int ii = 1; ii < nx; ++ii) {
      const double a = 0.5 * (w[ii - 1 + nx * kk] + w[ii + nx * kk]);
      ASSERT_EQ(s.corner_flux_u[ii + sx * kk], a * reference_carried(col_u(ii), kk - 1, a)) << ii << "," << kk;
    }
    const double wl = g.dz(kk) / (g.dz(kk - 1) + g.dz(kk)), wu = 1.0 - wl;
    const std::vector<double> prow = row_w(kk);
    for (int ii = 0; ii <= nx; ++ii) {
      const double a = wl * u[ii + sx * (kk - 1)] + wu * u[ii + sx * kk];
      const double v = ii == 0 ? (a > 0.0 ? 0.0 : prow[0]) : ii == nx ? prow[nx - 1] : reference_carried(prow, ii - 1, a);
      ASSERT_EQ(s.corner_flux_w[ii + sx * kk], a * v) << nx << "x" << nz << " " << ii << "," << kk;
    }
  }
}

// the implicit vertical diffusion column by column, as the scheme reads: each open face's row of
// (I - dt/rho d/dz mu d/dz) v = u^n with a closed neighbour a known zero (its coefficient dropped), a
// closed face's row the identity; on a no-slip bed without wall shear the ghost -u below (2 mu / dz0),
// stress free on top; w's top face known. u* += v - u^n on open faces
void reference_vertical_diffusion(const Grid2D& g, const MomentumFields& f, const MomentumBoundary& bc, double dt,
                                  const std::vector<double>& corner_mu, const std::vector<double>& u0,
                                  const std::vector<double>& w0, std::vector<double>& us, std::vector<double>& ws) {
  const int nx = g.nx(), nz = g.nz(), sx = nx + 1;
  const bool bed_no_slip = bc.no_slip && !f.face_z_wall_shear;
  for (int i = 1; i < nx; ++i) {
    std::vector<double> a(nz), b(nz), c(nz), d(nz);
    for (int k = 0; k < nz; ++k) {
      const int j = i + sx * k;
      a[k] = c[k] = 0.0, b[k] = 1.0, d[k] = u0[j];
      if (!(f.face_x_porosity[j] > 0.0)) continue;
      const double r = dt / (f.face_x_rho[j] * g.dz(k));
      double lo = 0.0, up = 0.0;
      if (k > 0) lo = corner_mu[j] / (g.z_center(k) - g.z_center(k - 1));
      else if (bed_no_slip) lo = 2.0 * corner_mu[j] / g.dz(0);
      if (k < nz - 1) up = corner_mu[j + sx] / (g.z_center(k + 1) - g.z_center(k));
      b[k] = 1.0 + r * (lo + up);
      if (k > 0 && f.face_x_porosity[j - sx] > 0.0) a[k] = -r * lo;
      if (k < nz - 1 && f.face_x_porosity[j + sx] > 0.0) c[k] = -r * up;
    }
    solve_tridiagonal(nz, a.data(), b.data(), c.data(), d.data());
    for (int k = 0; k < nz; ++k) {
      const int j = i + sx * k;
      if (f.face_x_porosity[j] > 0.0) us[j] += d[k] - u0[j];
    }
  }
  if (nz < 2) return;
  for (int i = 0; i < nx; ++i) {
    const int m = nz - 1;
    std::vector<double> a(m), b(m), c(m), d(m);
    for (int k = 1; k < nz; ++k) {
      const int j = i + nx * k, row = k - 1;
      a[row] = c[row] = 0.0, b[row] = 1.0, d[row] = w0[j];
      if (!(f.face_z_porosity[j] > 0.0)) continue;
      const double r = dt / (f.face_z_rho[j] * (g.z_center(k) - g.z_center(k - 1)));
      const double lo = 2.0 * f.cell_mu[j - nx] / g.dz(k - 1), up = 2.0 * f.cell_mu[j] / g.dz(k);
      b[row] = 1.0 + r * (lo + up);
      if (k > 1 && f.face_z_porosity[j - nx] > 0.0) a[row] = -r * lo;
      if (k < nz - 1 && f.face_z_porosity[j + nx] > 0.0) c[row] = -r * up;
      if (k == nz - 1) d[row] = w0[j] + r * up * f.face_w[j + nx];
    }
    solve_tridiagonal(m, a.data(), b.data(), c.data(), d.data());
    for (int k = 1; k < nz; ++k) {
      const int j = i + nx * k;
      if (f.face_z_porosity[j] > 0.0) ws[j] += d[k - 1] - w0[j];
    }
  }
}

// random fields of the diffusion kernels' tests: velocities, porosities (a fifth closed), viscosities
// (molecular and eddy, contrasts of 1e4), densities (water and air), corner viscosities, u* and w*,
// and the solves' start u0, w0 (u^n plus an explicit increment); wall shears zero
struct DiffusionCase {
  std::vector<double> u, w, nxp, nzp, mu, rx, rz, shear_x, shear_z, us, ws, u0, w0;
  MomentumScratch s;
  DiffusionCase(const Grid2D& g, Random& rnd)
      : u(g.nface_x()), w(g.nface_z()), nxp(g.nface_x()), nzp(g.nface_z()), mu(g.ncell()), rx(g.nface_x()),
        rz(g.nface_z()), shear_x(g.nface_x(), 0.0), shear_z(g.nface_z(), 0.0), us(g.nface_x()), ws(g.nface_z()),
        u0(g.nface_x()), w0(g.nface_z()) {
    for (auto* v : {&u, &w}) for (double& x : *v) x = rnd() - 0.5;
    for (auto* v : {&nxp, &nzp}) for (double& x : *v) x = rnd() < 0.2 ? 0.0 : 0.2 + 0.8 * rnd();
    for (double& x : mu) x = rnd() < 0.3 ? 1e-3 : 10.0 * rnd();
    for (auto* v : {&rx, &rz}) for (double& x : *v) x = rnd() < 0.3 ? 1.2 : 1000.0;
    s.corner_mu.resize(static_cast<std::size_t>(g.nx() + 1) * (g.nz() + 1));
    for (double& x : s.corner_mu) x = 5.0 * rnd();
    for (auto* v : {&us, &ws}) for (double& x : *v) x = rnd() - 0.5;
    for (int j = 0; j < g.nface_x(); ++j) u0[j] = u[j] + 0.1 * (rnd() - 0.5);
    for (int j = 0; j < g.nface_z(); ++j) w0[j] = w[j] + 0.1 * (rnd() - 0.5);
  }
  MomentumFields fields() const {
    return {u.data(), w.data(), nxp.data(), nzp.data(), mu.data(), rx.data(), rz.data()};
  }
};

void check_vertical_diffusion(int nx, int nz, unsigned seed, bool no_slip, bool wall_shear) {
  // graded rows (a fine bed row), so that every spacing enters
  std::vector<double> zf{0.0, 0.005};
  for (int k = 1; k < nz; ++k) zf.push_back(zf.back() + 0.01 + 0.002 * k);
  const Grid2D g(nx, 0.025, zf);
  Random rnd{seed};
  DiffusionCase q(g, rnd);
  MomentumFields f = q.fields();
  if (wall_shear) f.face_z_wall_shear = q.shear_z.data();
  MomentumBoundary bc;
  bc.no_slip = no_slip;
  std::vector<double> us_ref = q.us, ws_ref = q.ws;
  const double dt = 0.01;
  implicit_vertical_diffusion(g, f, bc, dt, q.u0.data(), q.w0.data(), q.us, q.ws, q.s);
  reference_vertical_diffusion(g, f, bc, dt, q.s.corner_mu, q.u0, q.w0, us_ref, ws_ref);
  for (int j = 0; j < g.nface_x(); ++j) ASSERT_EQ(q.us[j], us_ref[j]) << nx << "x" << nz << " x-face " << j;
  for (int j = 0; j < g.nface_z(); ++j) ASSERT_EQ(q.ws[j], ws_ref[j]) << nx << "x" << nz << " z-face " << j;
}

// the implicit horizontal diffusion row by row, as the scheme reads: (I - dt/rho d/dx 2 mu d/dx) y = u0 on
// the interior x-faces of each row, the end faces' u^n known; (I - dt/rho d/dx mu d/dx) y = w0 on the
// z-faces of each interior row, an end corner's ghost -w (inlet or no-slip wall, no wall-function shear
// there) doubling its conductance and adding none to a neighbour, a stress-free end none. Closed faces
// as in the columns. u* += y - u0, w* += y - w0 on open faces
void reference_row_diffusion(const Grid2D& g, const MomentumFields& f, const MomentumBoundary& bc, double dt,
                             const std::vector<double>& corner_mu, const std::vector<double>& u0,
                             const std::vector<double>& w0, std::vector<double>& us, std::vector<double>& ws) {
  const int nx = g.nx(), nz = g.nz(), sx = nx + 1;
  const double inv_dx = 1.0 / g.dx();
  for (int k = 0; k < nz && nx > 1; ++k) {
    const int m = nx - 1;
    std::vector<double> a(m), b(m), c(m), d(m);
    for (int i = 1; i < nx; ++i) {
      const int j = i + sx * k, row = i - 1;
      a[row] = c[row] = 0.0, b[row] = 1.0, d[row] = u0[j];
      if (!(f.face_x_porosity[j] > 0.0)) continue;
      const double r = dt * inv_dx / f.face_x_rho[j];
      const double lo = r * 2.0 * f.cell_mu[i - 1 + nx * k] * inv_dx, up = r * 2.0 * f.cell_mu[i + nx * k] * inv_dx;
      b[row] = 1.0 + lo + up;
      if (f.face_x_porosity[j - 1] > 0.0) {
        if (i > 1) a[row] = -lo;
        else d[row] += lo * f.face_u[j - 1];
      }
      if (f.face_x_porosity[j + 1] > 0.0) {
        if (i < nx - 1) c[row] = -up;
        else d[row] += up * f.face_u[j + 1];
      }
    }
    solve_tridiagonal(m, a.data(), b.data(), c.data(), d.data());
    for (int i = 1; i < nx; ++i) {
      const int j = i + sx * k;
      if (f.face_x_porosity[j] > 0.0) us[j] += d[i - 1] - u0[j];
    }
  }
  const bool left = (bc.left_inlet || bc.no_slip) && !(f.face_x_wall_shear && !bc.left_inlet);
  const bool right = !bc.right_open && bc.no_slip && !f.face_x_wall_shear;
  for (int k = 1; k < nz; ++k) {
    std::vector<double> a(nx), b(nx), c(nx), d(nx);
    for (int i = 0; i < nx; ++i) {
      const int j = i + nx * k;
      a[i] = c[i] = 0.0, b[i] = 1.0, d[i] = w0[j];
      if (!(f.face_z_porosity[j] > 0.0)) continue;
      const double r = dt * inv_dx / f.face_z_rho[j];
      const double cl = i > 0 ? 1.0 : (left ? 2.0 : 0.0), cu = i < nx - 1 ? 1.0 : (right ? 2.0 : 0.0);
      const double lo = r * cl * corner_mu[i + sx * k] * inv_dx, up = r * cu * corner_mu[i + 1 + sx * k] * inv_dx;
      b[i] = 1.0 + lo + up;
      if (i > 0 && f.face_z_porosity[j - 1] > 0.0) a[i] = -lo;
      if (i < nx - 1 && f.face_z_porosity[j + 1] > 0.0) c[i] = -up;
    }
    solve_tridiagonal(nx, a.data(), b.data(), c.data(), d.data());
    for (int i = 0; i < nx; ++i) {
      const int j = i + nx * k;
      if (f.face_z_porosity[j] > 0.0) ws[j] += d[i] - w0[j];
    }
  }
}

enum RowEnds { kSlipWalls, kNoSlipWalls, kInletAndOpenEnd, kWallFunctions };

void check_row_diffusion(int nx, int nz, unsigned seed, RowEnds ends) {
  const Grid2D g = Grid2D::uniform(nx, nz, 0.025 * nx, 0.01 * nz);
  Random rnd{seed};
  DiffusionCase q(g, rnd);
  MomentumFields f = q.fields();
  MomentumBoundary bc;
  bc.no_slip = ends != kSlipWalls;
  bc.left_inlet = bc.right_open = ends == kInletAndOpenEnd;
  if (ends == kWallFunctions) f.face_x_wall_shear = q.shear_x.data(), f.face_z_wall_shear = q.shear_z.data();
  std::vector<double> us_ref = q.us, ws_ref = q.ws;
  const double dt = 0.01;
  implicit_row_diffusion(g, f, bc, dt, q.u0.data(), q.w0.data(), q.us, q.ws, q.s);
  reference_row_diffusion(g, f, bc, dt, q.s.corner_mu, q.u0, q.w0, us_ref, ws_ref);
  for (int j = 0; j < g.nface_x(); ++j) ASSERT_EQ(q.us[j], us_ref[j]) << nx << "x" << nz << " x-face " << j;
  for (int j = 0; j < g.nface_z(); ++j) ASSERT_EQ(q.ws[j], ws_ref[j]) << nx << "x" << nz << " z-face " << j;
}

}  // namespace

TEST(MomentumKernels, ConvectiveFluxesMatchTheFaceByFaceReferenceBitForBit) {
  unsigned seed = 1;
  for (int nx : {1, 2, 3, 4, 5, 9})
    for (int nz : {1, 2, 3, 4, 5, 8}) check_fluxes(nx, nz, seed++);
}

TEST(MomentumKernels, ImplicitVerticalDiffusionMatchesTheColumnByColumnReferenceBitForBit) {
  unsigned seed = 1;
  for (int nx : {1, 2, 3, 7})
    for (int nz : {1, 2, 3, 6})
      for (bool no_slip : {false, true})
        for (bool wall_shear : {false, true}) check_vertical_diffusion(nx, nz, seed++, no_slip, wall_shear);
}

TEST(MomentumKernels, ImplicitRowDiffusionMatchesTheRowByRowReferenceBitForBit) {
  unsigned seed = 1;
  for (int nx : {1, 2, 3, 7})
    for (int nz : {1, 2, 3, 6})
      for (RowEnds ends : {kSlipWalls, kNoSlipWalls, kInletAndOpenEnd, kWallFunctions})
        check_row_diffusion(nx, nz, seed++, ends);
}
