// The momentum kernels' vectorised loops (momentum.cpp: pore velocities, the MUSCL convective fluxes
// with their inner values computed apart from the lines' ends) against a reference written face by
// face, as plainly as the scheme reads: the same bits on random fields with closed faces and flows of
// both signs, on grids small enough that every end case and every inner range (empty too) occurs.
#include <gtest/gtest.h>

#include <vector>

#include "vofdem/momentum.h"

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

}  // namespace

TEST(MomentumKernels, ConvectiveFluxesMatchTheFaceByFaceReferenceBitForBit) {
  unsigned seed = 1;
  for (int nx : {1, 2, 3, 4, 5, 9})
    for (int nz : {1, 2, 3, 4, 5, 8}) check_fluxes(nx, nz, seed++);
}
