// k-epsilon transport by alternating lines (KEpsilonTimeScheme::kAlternatingLines, k_epsilon_lines.cpp):
// its step limit is the horizontal advection's alone, it stays at or above the floors under huge steps,
// keeps the analytic decay in a column (and lags it, never leads it, across columns), differs from the
// fully implicit backward Euler (a dense solve) by a splitting error of second order in dt, reaches the
// steady state of the present schemes (a developing open channel, the horizontal diffusion in play) at
// steps far above their limits, and keeps thin rows within the start's range (the stop of the grid four
// times as fine, reduced to four cells).
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

KEpsilonParams scheme(KEpsilonTimeScheme s) {
  KEpsilonParams p = pinned_k_epsilon_params();
  p.time_scheme = s;
  return p;
}

KEpsilonParams alternating() { return scheme(KEpsilonTimeScheme::kAlternatingLines); }

// a random field with porous and solid cells, an inflow side and a graded grid (no production)
struct RandomCase {
  Grid2D g = Grid2D::graded(6, 0.6, 0.06, 0.02, 0.01, 0.02);
  KEpsilonBoundaries b;
  Flow f{g};
  std::vector<double> k0, e0, nut0;
  RandomCase() {
    b.left = KEpsilonBoundary::kInflow;
    b.right = b.bottom = b.top = KEpsilonBoundary::kZeroGradient;
    std::mt19937 rng(11);
    std::uniform_real_distribution<double> unit(0.0, 1.0);
    const int n = g.ncell();
    k0.resize(n), e0.resize(n), nut0.resize(n);
    for (int c = 0; c < n; ++c) {
      k0[c] = 1e-4 * (0.5 + unit(rng));
      e0[c] = 1e-5 * (0.5 + unit(rng));
      nut0[c] = 0.09 * k0[c] * k0[c] / e0[c];
      f.porosity[c] = unit(rng) < 0.3 ? 0.4 : 1.0;
    }
    f.porosity[g.cell(2, 1)] = 0.0;
    for (int k = 0; k < g.nz(); ++k)
      for (int i = 0; i <= g.nx(); ++i) f.face_u[g.face_x(i, k)] = 0.05 + 0.05 * unit(rng);
    for (int k = 1; k < g.nz(); ++k)
      for (int i = 0; i < g.nx(); ++i) f.face_w[g.face_z(i, k)] = 0.05 * (unit(rng) - 0.5);
  }
  KEpsilonModel model(KEpsilonParams p) const {
    p.flags = vofdem::kKEpsAdvection | vofdem::kKEpsDiffusion;
    KEpsilonModel m(g, p, b);
    m.cell_k = k0, m.cell_eps = e0, m.cell_nut = nut0;
    return m;
  }
};

// backward Euler of the whole system (every face implicit), assembled densely and solved by LU: the
// solution the alternating lines approximate
std::vector<double> dense_backward_euler(const RandomCase& rc, const KEpsilonParams& p, double dt, int eq) {
  const Grid2D& g = rc.g;
  const Flow& f = rc.f;
  const int nx = g.nx(), nz = g.nz(), n = g.ncell();
  const double sigma = eq == 0 ? p.sigma_k : p.sigma_eps, sink_c = eq == 0 ? 1.0 : p.c2;
  const std::vector<double>& x0 = eq == 0 ? rc.k0 : rc.e0;
  Eigen::MatrixXd a = Eigen::MatrixXd::Zero(n, n);
  Eigen::VectorXd rhs = Eigen::VectorXd::Zero(n);
  auto cond = [&](int c) { return f.porosity[c] * (kNu + rc.nut0[c] / sigma); };
  for (int k = 0; k < nz; ++k)
    for (int i = 0; i < nx; ++i) {
      const int c = g.cell(i, k);
      const double np = f.porosity[c], dx = g.dx(), dz = g.dz(k);
      if (np == 0.0) {
        a(c, c) = 1.0;
        rhs(c) = eq == 0 ? p.k_min : p.eps_min;
        continue;
      }
      a(c, c) += np / dt + np * sink_c * rc.e0[c] / rc.k0[c];
      rhs(c) += np * x0[c] / dt;
      struct Side { int i, k; double vin, len; };
      const Side sides[4] = {{i - 1, k, f.face_u[g.face_x(i, k)], dx},
                             {i + 1, k, -f.face_u[g.face_x(i + 1, k)], dx},
                             {i, k - 1, f.face_w[g.face_z(i, k)], dz},
                             {i, k + 1, -f.face_w[g.face_z(i, k + 1)], dz}};
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
        const double coef =
            std::max(sd.vin, 0.0) / sd.len + 1.0 / (sd.len * (half_p / cond(c) + half_n / cond(cn)));
        a(c, c) += coef, a(c, cn) -= coef;
      }
    }
  const Eigen::VectorXd x = a.partialPivLu().solve(rhs);
  return std::vector<double>(x.data(), x.data() + n);
}

// largest difference of the alternating lines' step from the dense backward Euler's, over the largest
// change backward Euler makes in the step (per equation, the larger of the two)
double splitting_error(const RandomCase& rc, double dt, const KEpsilonParams& p = alternating()) {
  KEpsilonModel m = rc.model(p);
  m.step(dt, rc.f.face_u, rc.f.face_w, rc.f.porosity, rc.f.F, rc.f.nu);
  double worst = 0.0;
  for (int eq = 0; eq < 2; ++eq) {
    const std::vector<double> ref = dense_backward_euler(rc, m.params(), dt, eq);
    const std::vector<double>& got = eq == 0 ? m.cell_k : m.cell_eps;
    const std::vector<double>& x0 = eq == 0 ? rc.k0 : rc.e0;
    double diff = 0.0, change = 0.0;
    for (int c = 0; c < rc.g.ncell(); ++c) {
      if (rc.f.porosity[c] == 0.0) continue;
      diff = std::max(diff, std::abs(got[c] - ref[c]));
      change = std::max(change, std::abs(ref[c] - x0[c]));
    }
    worst = std::max(worst, diff / change);
  }
  return worst;
}

}  // namespace

TEST(KEpsilonAlternating, StableDtIsTheHorizontalAdvectionsLimitAlone) {
  // one inflow face per cell (u > 0 everywhere): the same bits as the vertical lines' limit with the
  // diffusion switched off; none without flow
  RandomCase rc;
  KEpsilonParams lines = scheme(KEpsilonTimeScheme::kVerticalLines);
  lines.flags = vofdem::kKEpsAdvection;
  KEpsilonModel alt = rc.model(alternating()), adv_only(rc.g, lines, rc.b);
  adv_only.cell_k = rc.k0, adv_only.cell_eps = rc.e0, adv_only.cell_nut = rc.nut0;
  int c_alt = -2, c_ref = -2;
  const double dt_alt = alt.stable_dt(rc.f.face_u, rc.f.face_w, rc.f.porosity, rc.f.F, rc.f.nu, &c_alt);
  const double dt_ref = adv_only.stable_dt(rc.f.face_u, rc.f.face_w, rc.f.porosity, rc.f.F, rc.f.nu, &c_ref);
  EXPECT_EQ(dt_alt, dt_ref);
  EXPECT_EQ(c_alt, c_ref);
  EXPECT_TRUE(std::isfinite(dt_alt));
  // a huge eddy viscosity bounds the vertical lines' step, not this one
  KEpsilonModel big = rc.model(alternating()), big_lines = rc.model(scheme(KEpsilonTimeScheme::kVerticalLines));
  for (double& v : big.cell_nut) v = 100.0;
  big_lines.cell_nut = big.cell_nut;
  const double dt_big = big.stable_dt(rc.f.face_u, rc.f.face_w, rc.f.porosity, rc.f.F, rc.f.nu);
  EXPECT_EQ(dt_big, dt_alt);
  EXPECT_LT(big_lines.stable_dt(rc.f.face_u, rc.f.face_w, rc.f.porosity, rc.f.F, rc.f.nu), 0.01 * dt_alt);
  // still water: no limit
  Flow still(rc.g);
  EXPECT_EQ(big.stable_dt(still.face_u, still.face_w, still.porosity, still.F, still.nu),
            std::numeric_limits<double>::infinity());
}

TEST(KEpsilonAlternating, StableDtTakesEachFaceAloneAsTheFlowsCfl) {
  // three cells of one row, 0.1 m wide, porosity 0.25 in the middle: water enters the middle cell from
  // both sides (0.2 m/s from the west, 0.1 m/s from the east). Its horizontal faces are implicit: the
  // limit is the larger face's Courant number, cfl n dx / u = 0.5 x 0.25 x 0.1 / 0.2 = 0.0625 s (the
  // flow's own CFL on that face, whose porosity is the tighter cell's), not the explicit column scheme's
  // sum, 0.5 x 0.25 x 0.1 / 0.3 = 0.04167 s
  const Grid2D g = Grid2D::uniform(3, 1, 0.3, 0.1);
  KEpsilonBoundaries b;
  Flow f(g);
  f.porosity[1] = 0.25;
  f.face_u = {0.0, 0.2, -0.1, 0.0};
  KEpsilonParams p = alternating();
  ASSERT_EQ(p.cfl, 0.5);
  p.flags = vofdem::kKEpsAdvection | vofdem::kKEpsDiffusion;
  KEpsilonModel alt(g, p, b);
  alt.initialize(1e-4, 1e-5, 1e-6);
  int cell = -2;
  EXPECT_NEAR(alt.stable_dt(f.face_u, f.face_w, f.porosity, f.F, f.nu, &cell), 0.0625, 1e-15);
  EXPECT_EQ(cell, 1);
  KEpsilonParams lines = scheme(KEpsilonTimeScheme::kVerticalLines);
  lines.flags = vofdem::kKEpsAdvection;
  KEpsilonModel col(g, lines, b);
  col.initialize(1e-4, 1e-5, 1e-6);
  EXPECT_NEAR(col.stable_dt(f.face_u, f.face_w, f.porosity, f.F, f.nu), 0.5 * 0.25 * 0.1 / 0.3, 1e-15);
  // the outer cells see 0.2 and 0.1 m/s leaving: no inflow, no limit of theirs; porosity 1 in the
  // middle: 0.5 x 0.1 / 0.2
  f.porosity[1] = 1.0;
  EXPECT_NEAR(alt.stable_dt(f.face_u, f.face_w, f.porosity, f.F, f.nu), 0.25, 1e-15);
}

TEST(KEpsilonAlternating, ValidationNamesTheSchemes) {
  const Grid2D g = Grid2D::uniform(3, 3, 0.3, 0.3);
  KEpsilonParams p = pinned_k_epsilon_params();
  p.time_scheme = static_cast<KEpsilonTimeScheme>(3);
  try {
    KEpsilonModel m(g, p);
    FAIL() << "no exception";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("2 (kAlternatingLines)"), std::string::npos) << e.what();
  }
  p = alternating();
  p.limit_step = false;
  EXPECT_NO_THROW(KEpsilonModel(g, p));
  p.time_scheme = KEpsilonTimeScheme::kPointImplicit;
  EXPECT_THROW(KEpsilonModel(g, p), std::invalid_argument);
}

TEST(KEpsilonAlternating, DiffersFromBackwardEulerBySecondOrderSplitting) {
  // one step from the same state: the factorisation's extra term A_x M^-1 A_z d is, over the step's
  // change d, of order dt^2 where dt is small against every face's explicit limit (the point-implicit
  // scheme's, dt0 below): halving dt there divides it by about 4 (3 to 5)
  RandomCase rc;
  KEpsilonModel point = rc.model(pinned_k_epsilon_params());
  const double dt0 = point.stable_dt(rc.f.face_u, rc.f.face_w, rc.f.porosity, rc.f.F, rc.f.nu) / 0.5;
  double prev = splitting_error(rc, dt0);
  std::printf("[ info     ] error over the change at 1 x the all-faces limit: %.3e\n", prev);
  for (double factor = 0.5; factor > 1e-3; factor *= 0.5) {
    const double err = splitting_error(rc, factor * dt0);
    std::printf("[ info     ] at 1/%.0f x: %.3e (ratio %.2f)\n", 1.0 / factor, err, prev / err);
    if (factor < 0.02) {
      EXPECT_GT(prev / err, 3.0);
      EXPECT_LT(prev / err, 5.0);
    }
    prev = err;
  }
}

TEST(KEpsilonAlternating, IsNearerBackwardEulerThanTheVerticalLinesAtTheirLimit) {
  // both approximate backward Euler: the vertical lines with their horizontal faces explicit, the
  // alternating lines with the factorisation's term; at the vertical lines' limit and half of it
  RandomCase rc;
  const KEpsilonParams lines = scheme(KEpsilonTimeScheme::kVerticalLines);
  KEpsilonModel m = rc.model(lines);
  const double dt1 = m.stable_dt(rc.f.face_u, rc.f.face_w, rc.f.porosity, rc.f.F, rc.f.nu) / lines.cfl;
  for (double factor : {0.5, 1.0}) {
    const double alt = splitting_error(rc, factor * dt1), ref = splitting_error(rc, factor * dt1, lines);
    std::printf("[ info     ] at %.1f x the lines' limit: alternating %.3e, vertical lines %.3e\n", factor, alt, ref);
    EXPECT_LT(alt, ref);
  }
}

TEST(KEpsilonAlternating, StaysPositiveUnderHugeStepsAndExtremeStrain) {
  const Grid2D g = Grid2D::graded(10, 0.5, 0.12, 0.02, 0.005, 0.02);
  std::mt19937 rng(7);
  for (double dt : {1e-6, 1e2, 1e6}) {
    run_random_strain(g, alternating(), dt, rng, [](const KEpsilonModel& m) { expect_all_positive_finite(m); });
    if (HasFatalFailure()) return;
  }
}

// dk/dt = -eps, deps/dt = -C2 eps^2/k: a uniform field in a closed box of nx columns, 600 steps of
// tau / 200, beside the point-implicit scheme (exact for a uniform field) and the analytic decay
// k0 (1 + (C2 - 1) eps0 t / k0)^(-1/(C2 - 1)); returns {k of cell 0, largest |k - point's| / point's,
// smallest (k - point's) / point's, the analytic k}
struct Decay {
  double k, worst, lowest, exact;
};
Decay homogeneous_decay(int nx) {
  const Grid2D g = Grid2D::graded(nx, 0.1 * nx, 0.05, 0.01, 0.005, 0.02);
  const double k0 = 1e-2, eps0 = 1e-3, tau = k0 / eps0, t_end = 3.0 * tau, dt = tau / 200.0;
  KEpsilonBoundaries b;
  b.left = b.right = b.bottom = b.top = KEpsilonBoundary::kZeroGradient;
  KEpsilonModel m(g, alternating(), b), point(g, pinned_k_epsilon_params(), b);
  m.initialize(k0, eps0, kNu);
  point.initialize(k0, eps0, kNu);
  Flow f(g);
  for (int s = 0; s < 600; ++s) {
    m.step(dt, f.face_u, f.face_w, f.porosity, f.F, f.nu);
    point.step(dt, f.face_u, f.face_w, f.porosity, f.F, f.nu);
  }
  Decay d{m.cell_k[0], 0.0, 1.0, k0 * std::pow(1.0 + 0.92 * t_end / tau, -1.0 / 0.92)};
  for (int c = 0; c < g.ncell(); ++c) {
    const double rel = (m.cell_k[c] - point.cell_k[c]) / point.cell_k[c];
    d.worst = std::max(d.worst, std::abs(rel)), d.lowest = std::min(d.lowest, rel);
  }
  return d;
}

TEST(KEpsilonAlternating, HomogeneousDecayMatchesTheAnalyticSolutionInAColumn) {
  // one column: the rows' systems are single cells and the columns' are backward Euler itself, so a
  // uniform decaying field is the point-implicit scheme's to round-off (the vertical diffusion in play)
  const Decay d = homogeneous_decay(1);
  EXPECT_LT(d.worst, 1e-12);
  EXPECT_NEAR(d.k, d.exact, 0.01 * d.exact);
}

TEST(KEpsilonAlternating, HomogeneousDecayIsNeverFasterThanThePointImplicitOne) {
  // three columns: the factorisation's extra term O_x (M + D_x + D_z)^-1 O_z couples a cell to its
  // diagonal neighbours with a positive weight, which takes from each step's change of a uniform field
  // (by D_x D_z / ((M + D_x)(M + D_z)) of it in an inner cell), so the decay lags the point-implicit one,
  // never leads it. (The former factorisation, M alone between the passes, kept this field exact, at
  // the price of an extra term A_x M^-1 A_z that grew without bound on thin rows: see
  // ThinRowsKeepTheStartsRangeAndTheHandValues.)
  const Decay d = homogeneous_decay(3);
  EXPECT_GE(d.lowest, -1e-12);
}

TEST(KEpsilonAlternating, DevelopingChannelReachesTheVerticalLinesSteadyStateAtLargerSteps) {
  // a developing open channel (k-epsilon alone under a fixed log-law velocity profile, turbulence of
  // the inflow's intensity entering on the left, walls below): k and eps change along the flume, so
  // the horizontal advection and diffusion are in play. The steady discrete equations do not depend on
  // dt: the alternating lines at 10 and 100 times the vertical lines' limit reach the steady state the
  // vertical lines reach at their limit, to 1e-8
  const double h = 0.1, u_tau = 0.02;
  const Grid2D g = Grid2D::graded(12, 0.3, h, 0.01, 0.005, 0.02);
  KEpsilonBoundaries b;
  b.left = KEpsilonBoundary::kInflow;
  b.right = KEpsilonBoundary::kZeroGradient;
  Flow f(g);
  for (int k = 0; k < g.nz(); ++k)
    for (int i = 0; i <= g.nx(); ++i)
      f.face_u[g.face_x(i, k)] = u_tau / 0.41 * std::log(9.8 * g.z_center(k) * u_tau / kNu);
  auto steady = [&](KEpsilonParams p, double factor) {
    KEpsilonModel m(g, p, b);
    m.initialize(1e-4, 1e-5, kNu);
    KEpsilonModel lines(g, scheme(KEpsilonTimeScheme::kVerticalLines), b);  // its limit sets the step
    double change = 1.0;
    int it = 0;
    for (; it < 200000 && change > 1e-13; ++it) {
      lines.cell_k = m.cell_k, lines.cell_eps = m.cell_eps, lines.cell_nut = m.cell_nut;
      const double dt = factor * lines.stable_dt(f.face_u, f.face_w, f.porosity, f.F, f.nu);
      const std::vector<double> prev = m.cell_k;
      m.step(dt, f.face_u, f.face_w, f.porosity, f.F, f.nu);
      change = 0.0;
      for (int c = 0; c < g.ncell(); ++c) change = std::max(change, std::abs(m.cell_k[c] / prev[c] - 1.0));
    }
    EXPECT_LE(change, 1e-13) << "not steady after " << it << " steps";
    std::printf("[ info     ] steady after %d steps at %.0f x the vertical lines' limit\n", it, factor);
    return m.cell_nut;
  };
  const std::vector<double> ref = steady(scheme(KEpsilonTimeScheme::kVerticalLines), 1.0);
  // the case is what it says: nu_t varies along the flume by more than 1 %
  double spread = 0.0;
  for (int i = 1; i < g.nx(); ++i) spread = std::max(spread, std::abs(ref[g.cell(i, 3)] / ref[g.cell(0, 3)] - 1.0));
  EXPECT_GT(spread, 0.01);
  for (double factor : {10.0, 100.0}) {
    const std::vector<double> got = steady(alternating(), factor);
    for (int c = 0; c < g.ncell(); ++c) EXPECT_NEAR(got[c], ref[c], 1e-8 * ref[c]) << "cell " << c;
  }
}

// The stop of the grid four times as fine (docs/k_epsilon.md, "Alternating lines"), reduced to four
// cells of pure k diffusion: a thin row (dz = 1 cm under dx = 10 cm, a_z = 100 a_x) in which cell A
// (0, 1) lies between two cells of k = 1 (L below, U above) and has a neighbour B (1, 1) whose vertical
// neighbours are solid, as at the water's front. With M alone between the factors (the former form)
// the row pass gave A the value y_A = r_A / (M + a_x) of its whole vertical residual (133 for a start
// of 1), B took half of it across the row (y_B = 66.7) and B's column, with no vertical faces, kept it:
// B ended at 66.7 and A, L and U below zero, clipped to the floor. Backward Euler keeps every value
// within [min, max] of the start. Each pass now holds the other direction's faces on its diagonal:
//   rows:    (M + D_z + A_x) y = r          columns: (M + D_x + A_z) d = (M + D_x + D_z) y
// solved here by hand (2x2 for row 1, 3x3 for column 0, B's column alone).
TEST(KEpsilonAlternating, ThinRowsKeepTheStartsRangeAndTheHandValues) {
  const Grid2D g = Grid2D::uniform(2, 3, 0.2, 0.03);  // dx = 0.1 m, dz = 0.01 m
  KEpsilonParams p = alternating();
  p.flags = vofdem::kKEpsDiffusion;  // diffusion alone: no wall values, no production, fluid at rest
  KEpsilonBoundaries b;
  b.left = b.right = b.bottom = b.top = KEpsilonBoundary::kZeroGradient;
  KEpsilonModel m(g, p, b);
  Flow f(g);
  f.porosity[g.cell(1, 0)] = f.porosity[g.cell(1, 2)] = 0.0;  // B's vertical neighbours: solid
  const int L = g.cell(0, 0), A = g.cell(0, 1), U = g.cell(0, 2), B = g.cell(1, 1);
  const double nut = 0.01, dt = 1.0;
  for (int c = 0; c < g.ncell(); ++c) m.cell_k[c] = p.k_min, m.cell_eps[c] = p.eps_min, m.cell_nut[c] = nut;
  m.cell_k[L] = m.cell_k[U] = 1.0;
  m.step(dt, f.face_u, f.face_w, f.porosity, f.F, f.nu);

  // by hand: n = 1, conductance nu + nu_t / sigma_k, faces a_x = cond / dx^2, a_z = cond / dz^2 (equal
  // halves), M = 1/dt + eps/k (the sink of each cell's start), D_x, D_z: a cell's open faces' sums
  const double cond = kNu + nut / p.sigma_k, ax = cond / (0.1 * 0.1), az = cond / (0.01 * 0.01);
  const double mL = 1.0 / dt + p.eps_min / 1.0, mA = 1.0 / dt + p.eps_min / p.k_min, mB = mA;
  const double k0L = 1.0, k0A = p.k_min, k0B = p.k_min;
  const double rL = -(mL - 1.0 / dt) * k0L + az * (k0A - k0L);
  const double rA = -(mA - 1.0 / dt) * k0A + 2.0 * az * (k0L - k0A) + ax * (k0B - k0A);
  const double rB = -(mB - 1.0 / dt) * k0B + ax * (k0A - k0B);
  // rows: L (and U) alone; A and B: [[mA + 2 az + ax, -ax], [-ax, mB + ax]] y = [rA, rB]
  const double yL = rL / (mL + az);
  const double a11 = mA + 2.0 * az + ax, a22 = mB + ax;
  const double yA = (rA * a22 + ax * rB) / (a11 * a22 - ax * ax), yB = (rB + ax * yA) / a22;
  // column 0: [[mL + az, -az, 0], [-az, mA + ax + 2 az, -az], [0, -az, mL + az]] d = rhs, L and U alike
  const double cL = mL + az, cA = mA + ax + 2.0 * az;
  const double sL = (mL + az) * yL, sA = (mA + ax + 2.0 * az) * yA;
  const double dA = (sA + 2.0 * az * sL / cL) / (cA - 2.0 * az * az / cL), dL = (sL + az * dA) / cL;
  const double dB = (mB + ax) * yB / (mB + ax);  // B's column: no vertical faces
  EXPECT_NEAR(m.cell_k[L], k0L + dL, 1e-12);
  EXPECT_NEAR(m.cell_k[U], k0L + dL, 1e-12);
  EXPECT_NEAR(m.cell_k[A], k0A + dA, 1e-12);
  EXPECT_NEAR(m.cell_k[B], k0B + dB, 1e-12);
  // the values those give (0.626, 0.622, 0.496): inside the start's range, as backward Euler's
  for (int c : {L, A, U, B}) {
    EXPECT_GE(m.cell_k[c], 0.3) << "cell " << c;
    EXPECT_LE(m.cell_k[c], 1.0) << "cell " << c;
  }
}
