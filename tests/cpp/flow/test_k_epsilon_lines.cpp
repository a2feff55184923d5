// k-epsilon transport by vertical lines (KEpsilonTimeScheme::kVerticalLines, k_epsilon_lines.cpp):
// against a slow, obvious dense solve of the same semi-implicit system, positivity under huge steps,
// the analytic decay, the steady open channel of the point-implicit scheme, and its step limit.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <random>
#include <stdexcept>
#include <string>
#include <vector>

#include <Eigen/Dense>

#include "vofdem/common/grid.h"
#include "vofdem/flow/k_epsilon.h"
#include "common/pinned_params.h"
#include "flow/k_epsilon_fields.h"

using vofdem::Grid2D;
using vofdem::KEpsilonBoundaries;
using vofdem::KEpsilonBoundary;
using vofdem::KEpsilonModel;
using vofdem::KEpsilonParams;
using vofdem::test::expect_all_positive_finite;
using vofdem::test::pinned_k_epsilon_params;
using vofdem::test::run_random_strain;
using vofdem::KEpsilonTimeScheme;

namespace {

constexpr double kNu = vofdem::test::kNuWater;
using Flow = vofdem::test::KEpsilonFlow;

KEpsilonParams lines() {
  KEpsilonParams p = pinned_k_epsilon_params();
  p.time_scheme = KEpsilonTimeScheme::kVerticalLines;
  return p;
}

// the system of k_epsilon_lines.cpp without production, assembled into a dense matrix row by row
// (porous and solid cells, an inflow side, a graded grid) and solved by LU; dt_factor times the
// horizontal limit decides whether the horizontal faces are explicit (<= 1) or lagged-implicit
void check_against_dense(double dt_factor) {
  const Grid2D g = Grid2D::graded(5, 0.5, 0.06, 0.02, 0.01, 0.02);
  const int nx = g.nx(), nz = g.nz(), n = g.ncell();
  KEpsilonParams p = lines();
  p.flags = vofdem::kKEpsAdvection | vofdem::kKEpsDiffusion;
  KEpsilonBoundaries b;
  b.left = KEpsilonBoundary::kInflow;
  b.right = b.bottom = b.top = KEpsilonBoundary::kZeroGradient;
  KEpsilonModel m(g, p, b);
  Flow f(g);
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  for (int c = 0; c < n; ++c) {
    m.cell_k[c] = 1e-4 * (0.5 + unit(rng));
    m.cell_eps[c] = 1e-5 * (0.5 + unit(rng));
    m.cell_nut[c] = 0.09 * m.cell_k[c] * m.cell_k[c] / m.cell_eps[c];
    f.porosity[c] = unit(rng) < 0.3 ? 0.4 : 1.0;
  }
  f.porosity[g.cell(2, 1)] = 0.0;
  for (int k = 0; k < nz; ++k)
    for (int i = 0; i <= nx; ++i) f.face_u[g.face_x(i, k)] = 0.2 + 0.1 * unit(rng);
  for (int k = 1; k < nz; ++k)
    for (int i = 0; i < nx; ++i) f.face_w[g.face_z(i, k)] = 0.3 * (unit(rng) - 0.5);
  const double dt = dt_factor * m.stable_dt(f.face_u, f.face_w, f.porosity, f.F, f.nu) / p.cfl;
  const std::vector<double> k0 = m.cell_k, e0 = m.cell_eps, nut0 = m.cell_nut;
  m.step(dt, f.face_u, f.face_w, f.porosity, f.F, f.nu);
  int explicit_cells = 0;
  for (int eq = 0; eq < 2; ++eq) {
    const double sigma = eq == 0 ? p.sigma_k : p.sigma_eps, sink_c = eq == 0 ? 1.0 : p.c2;
    const std::vector<double>& x0 = eq == 0 ? k0 : e0;
    Eigen::MatrixXd a = Eigen::MatrixXd::Zero(n, n);
    Eigen::VectorXd rhs = Eigen::VectorXd::Zero(n);
    auto cond = [&](int c) { return f.porosity[c] * (kNu + nut0[c] / sigma); };
    for (int k = 0; k < nz; ++k)
      for (int i = 0; i < nx; ++i) {
        const int c = g.cell(i, k);
        const double np = f.porosity[c], dx = g.dx(), dz = g.dz(k);
        if (np == 0.0) {
          a(c, c) = 1.0;
          rhs(c) = eq == 0 ? p.k_min : p.eps_min;
          continue;
        }
        a(c, c) += np / dt + np * sink_c * e0[c] / k0[c];
        rhs(c) += np * x0[c] / dt;
        struct Side { int i, k; double vin, len; };
        const Side sides[4] = {{i - 1, k, f.face_u[g.face_x(i, k)], dx},
                               {i + 1, k, -f.face_u[g.face_x(i + 1, k)], dx},
                               {i, k - 1, f.face_w[g.face_z(i, k)], dz},
                               {i, k + 1, -f.face_w[g.face_z(i, k + 1)], dz}};
        double coef[4] = {0, 0, 0, 0};
        int nb[4] = {-1, -1, -1, -1};
        for (int s = 0; s < 4; ++s) {
          const Side& sd = sides[s];
          if (sd.i < 0) {  // the inflow side: implicit with the inflow value
            if (sd.vin <= 0.0) continue;
            const double kin = 1.5 * std::pow(p.inflow_intensity * sd.vin / np, 2);
            const double vin = eq == 0 ? kin : std::pow(0.09, 0.75) * std::pow(kin, 1.5) / p.inflow_length_scale;
            const double cf = sd.vin / dx + cond(c) / (dx * 0.5 * dx);
            a(c, c) += cf;
            rhs(c) += cf * vin;
            continue;
          }
          if (sd.i >= nx || sd.k < 0 || sd.k >= nz) continue;
          const int cn = g.cell(sd.i, sd.k);
          if (f.porosity[cn] == 0.0) continue;
          const double half_p = 0.5 * sd.len, half_n = 0.5 * (s < 2 ? dx : g.dz(sd.k));
          coef[s] = std::max(sd.vin, 0.0) / sd.len + 1.0 / (sd.len * (half_p / cond(c) + half_n / cond(cn)));
          nb[s] = cn;
        }
        const bool expl = dt * (coef[0] + coef[1]) <= np;
        explicit_cells += expl;
        for (int s = 0; s < 4; ++s) {
          if (nb[s] < 0) continue;
          if (s >= 2) {
            a(c, c) += coef[s], a(c, nb[s]) -= coef[s];
          } else if (expl) {
            rhs(c) += coef[s] * (x0[nb[s]] - x0[c]);
          } else {
            a(c, c) += coef[s], rhs(c) += coef[s] * x0[nb[s]];
          }
        }
      }
    const Eigen::VectorXd x = a.partialPivLu().solve(rhs);
    const std::vector<double>& got = eq == 0 ? m.cell_k : m.cell_eps;
    for (int c = 0; c < n; ++c) EXPECT_NEAR(got[c], x(c), 1e-12 * x(c)) << "eq " << eq << " cell " << c;
  }
  // the case is what it says: every cell explicit in x at factor <= 1, none far above
  if (dt_factor <= 1.0) EXPECT_EQ(explicit_cells, 2 * (n - 1));
  else EXPECT_LT(explicit_cells, n);
}

}  // namespace

TEST(KEpsilonLines, ColumnSolveIsTheDenseSemiImplicitSolution) {
  check_against_dense(1.0);   // horizontal faces explicit
  check_against_dense(20.0);  // most cells above their horizontal limit: lagged-implicit
}

TEST(KEpsilonLines, StableDtIgnoresTheVerticalFaces) {
  const Grid2D g = Grid2D::uniform(5, 4, 0.5, 0.2);  // dx 0.1, dz 0.05
  KEpsilonParams p = lines();
  p.flags = vofdem::kKEpsAdvection;
  KEpsilonBoundaries b;
  b.left = b.right = b.bottom = b.top = KEpsilonBoundary::kZeroGradient;
  KEpsilonModel m(g, p, b);
  Flow f(g);
  for (double& u : f.face_u) u = 2.0;
  int cell = -2;
  EXPECT_NEAR(m.stable_dt(f.face_u, f.face_w, f.porosity, f.F, f.nu, &cell), 0.5 / 20.0, 1e-15);
  EXPECT_GE(cell, 0);
  // a vertical flow alone: no limit for the column solves (the point-implicit scheme: 0.5 dz / w)
  std::fill(f.face_u.begin(), f.face_u.end(), 0.0);
  for (int k = 1; k < g.nz(); ++k)
    for (int i = 0; i < g.nx(); ++i) f.face_w[g.face_z(i, k)] = 2.0;
  EXPECT_TRUE(std::isinf(m.stable_dt(f.face_u, f.face_w, f.porosity, f.F, f.nu, &cell)));
  EXPECT_EQ(cell, -1);
  KEpsilonParams q = p;
  q.time_scheme = KEpsilonTimeScheme::kPointImplicit;
  KEpsilonModel point(g, q, b);
  EXPECT_NEAR(point.stable_dt(f.face_u, f.face_w, f.porosity, f.F, f.nu), 0.5 * 0.05 / 2.0, 1e-15);
}

TEST(KEpsilonLines, StepLimitCanBeSwitchedOffForTheLinesOnly) {
  // limit_step = false: no bound (the horizontal flow of the test above binds 0.025 s with it); the
  // point-implicit scheme refuses it by name (its step is bounded by all four faces)
  const Grid2D g = Grid2D::uniform(5, 4, 0.5, 0.2);
  KEpsilonParams p = lines();
  p.limit_step = false;
  KEpsilonBoundaries b;
  KEpsilonModel m(g, p, b);
  Flow f(g);
  for (double& u : f.face_u) u = 2.0;
  int cell = -2;
  EXPECT_TRUE(std::isinf(m.stable_dt(f.face_u, f.face_w, f.porosity, f.F, f.nu, &cell)));
  EXPECT_EQ(cell, -1);
  p.time_scheme = KEpsilonTimeScheme::kPointImplicit;
  try {
    vofdem::check_k_epsilon_params(p);
    FAIL() << "limit_step = false accepted with the point-implicit scheme";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("limit_step"), std::string::npos) << e.what();
  }
}

// the horizontal limit (vectorised row by row) against the obvious cell-by-cell sum of the two
// horizontal faces' coefficients: random flow, porosity (solid cells), water fraction (air cells) and
// eddy viscosity, one to nine columns; the same step and binding cell to the bit
TEST(KEpsilonLines, StableDtMatchesTheCellByCellReferenceBitForBit) {
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  for (int nx : {1, 2, 3, 9}) {
    for (unsigned flags : {vofdem::kKEpsAdvection | vofdem::kKEpsDiffusion, unsigned(vofdem::kKEpsAdvection),
                           unsigned(vofdem::kKEpsDiffusion)}) {
      const Grid2D g = Grid2D::graded(nx, 0.05 * nx, 0.06, 0.02, 0.01, 0.02);
      KEpsilonParams p = lines();
      p.flags = flags;
      KEpsilonModel m(g, p, KEpsilonBoundaries{});
      Flow f(g);
      for (double& u : f.face_u) u = 2.0 * unit(rng) - 1.0;
      for (int c = 0; c < g.ncell(); ++c) {
        const double r = unit(rng);
        f.porosity[c] = r < 0.15 ? 0.0 : r < 0.5 ? 0.3 + 0.6 * unit(rng) : 1.0;
        f.F[c] = unit(rng) < 0.2 ? 0.05 : unit(rng) < 0.5 ? p.water_fraction_min : 1.0;
        m.cell_nut[c] = 1e-4 * unit(rng);
      }
      auto active = [&](int c) { return f.porosity[c] > 0.0 && f.F[c] >= p.water_fraction_min; };
      const bool adv = flags & vofdem::kKEpsAdvection, dif = flags & vofdem::kKEpsDiffusion;
      const double dx = g.dx(), inv_sigma[2] = {1.0 / p.sigma_k, 1.0 / p.sigma_eps};
      auto res = [&](int e, int c) { return 0.5 * dx / (f.porosity[c] * (f.nu[c] + m.cell_nut[c] * inv_sigma[e])); };
      double worst = 0.0;
      int where = -1;
      for (int k = 0; k < g.nz(); ++k)
        for (int i = 0; i < nx; ++i) {
          const int c = g.cell(i, k);
          if (!active(c)) continue;
          double sum[2] = {0.0, 0.0};
          for (int e = 0; e < 2; ++e) {
            if (i > 0 && active(c - 1))
              sum[e] += (adv ? std::max(f.face_u[g.face_x(i, k)], 0.0) / dx : 0.0) +
                        (dif ? 1.0 / (dx * (res(e, c) + res(e, c - 1))) : 0.0);
            if (i + 1 < nx && active(c + 1))
              sum[e] += (adv ? std::max(-f.face_u[g.face_x(i + 1, k)], 0.0) / dx : 0.0) +
                        (dif ? 1.0 / (dx * (res(e, c) + res(e, c + 1))) : 0.0);
          }
          const double rate = std::max(sum[0], sum[1]) / f.porosity[c];
          if (rate > worst) worst = rate, where = c;
        }
      int cell = -2;
      const double dt = m.stable_dt(f.face_u, f.face_w, f.porosity, f.F, f.nu, &cell);
      EXPECT_EQ(dt, worst > 0.0 ? p.cfl / worst : std::numeric_limits<double>::infinity()) << nx << " " << flags;
      EXPECT_EQ(cell, where) << nx << " " << flags;
    }
  }
}

TEST(KEpsilonLines, StaysPositiveUnderHugeStepsAndExtremeStrain) {
  const Grid2D g = Grid2D::graded(10, 0.5, 0.12, 0.02, 0.005, 0.02);
  std::mt19937 rng(7);
  for (double dt : {1e-6, 1e2, 1e6}) {
    run_random_strain(g, lines(), dt, rng, [](const KEpsilonModel& m) { expect_all_positive_finite(m); });
    if (HasFatalFailure()) return;
  }
}

TEST(KEpsilonLines, HomogeneousDecayMatchesTheAnalyticSolution) {
  // dk/dt = -eps, deps/dt = -C2 eps^2/k: k = k0 (1 + (C2 - 1) eps0 t / k0)^(-1/(C2 - 1)); a uniform
  // field in a closed box stays uniform (no transport) and decays as the point-implicit scheme does
  const Grid2D g = Grid2D::graded(3, 0.3, 0.05, 0.01, 0.005, 0.02);
  const double k0 = 1e-2, eps0 = 1e-3, tau = k0 / eps0, t_end = 3.0 * tau, dt = tau / 200.0;
  KEpsilonBoundaries b;
  b.left = b.right = b.bottom = b.top = KEpsilonBoundary::kZeroGradient;
  KEpsilonModel m(g, lines(), b), point(g, pinned_k_epsilon_params(), b);
  m.initialize(k0, eps0, kNu);
  point.initialize(k0, eps0, kNu);
  Flow f(g);
  for (int s = 0; s < 600; ++s) {
    m.step(dt, f.face_u, f.face_w, f.porosity, f.F, f.nu);
    point.step(dt, f.face_u, f.face_w, f.porosity, f.F, f.nu);
  }
  const double exact = k0 * std::pow(1.0 + 0.92 * t_end / tau, -1.0 / 0.92);
  for (int c = 0; c < g.ncell(); ++c) EXPECT_NEAR(m.cell_k[c], point.cell_k[c], 1e-12 * point.cell_k[c]);
  EXPECT_NEAR(m.cell_k[0], exact, 0.01 * exact);
}

TEST(KEpsilonLines, OpenChannelReachesThePointImplicitSteadyStateAtLargerSteps) {
  // the log-law channel column (k-epsilon alone, a fixed log-law velocity profile): both schemes have
  // the same steady state (the discrete equations do not depend on dt there); the column solves reach
  // it at 20 times the point-implicit limit, where that scheme is not run
  const double h = 0.1, u_tau = 0.02;
  const Grid2D g = Grid2D::graded(1, 0.1, h, 0.01, 0.005, 0.02);
  KEpsilonBoundaries b;
  b.left = b.right = KEpsilonBoundary::kZeroGradient;
  Flow f(g);
  for (int k = 0; k < g.nz(); ++k)
    f.face_u[g.face_x(0, k)] = f.face_u[g.face_x(1, k)] = u_tau / 0.41 * std::log(9.8 * g.z_center(k) * u_tau / kNu);
  auto steady = [&](KEpsilonParams p, double factor) {
    KEpsilonModel m(g, p, b);
    m.initialize(1e-4, 1e-5, kNu);
    KEpsilonModel point(g, pinned_k_epsilon_params(), b);  // its limit sets the step of both runs
    double change = 1.0;
    int it = 0;
    for (; it < 40000 && change > 1e-12; ++it) {
      point.cell_k = m.cell_k, point.cell_eps = m.cell_eps, point.cell_nut = m.cell_nut;
      const double dt = factor * point.stable_dt(f.face_u, f.face_w, f.porosity, f.F, f.nu);
      const std::vector<double> prev = m.cell_k;
      m.step(dt, f.face_u, f.face_w, f.porosity, f.F, f.nu);
      change = 0.0;
      for (int k = 0; k < g.nz(); ++k) change = std::max(change, std::abs(m.cell_k[k] / prev[k] - 1.0));
    }
    EXPECT_LE(change, 1e-12) << "not steady after " << it << " steps";
    std::printf("[ info     ] steady after %d steps at %.0f x the point-implicit limit\n", it, factor);
    return m.cell_nut;
  };
  const std::vector<double> ref = steady(pinned_k_epsilon_params(), 1.0), got = steady(lines(), 20.0);
  for (int k = 0; k < g.nz(); ++k) EXPECT_NEAR(got[k], ref[k], 1e-8 * ref[k]) << "row " << k;
}
