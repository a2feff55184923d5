#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
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

namespace {

constexpr double kNu = vofdem::test::kNuWater;
using Flow = vofdem::test::KEpsilonFlow;

KEpsilonBoundaries closed_to_flux() {
  KEpsilonBoundaries b;
  b.left = b.right = b.bottom = b.top = KEpsilonBoundary::kZeroGradient;
  return b;
}

KEpsilonBoundaries walled_box() {
  KEpsilonBoundaries b;
  b.left = b.right = b.bottom = b.top = KEpsilonBoundary::kWall;
  return b;
}

// decay of homogeneous turbulence without production: dk/dt = -eps, deps/dt = -C2 eps^2/k
double decay_k(double k0, double eps0, double c2, double t) {
  return k0 * std::pow(1.0 + (c2 - 1.0) * eps0 * t / k0, -1.0 / (c2 - 1.0));
}

}  // namespace

TEST(KEpsilon, WallShearVelocitySolvesTheLogLaw) {
  const double kappa = 0.41, e = 9.8;
  // smooth wall, y+ = 125: U = u_tau/kappa ln(E y+)
  const double u_tau = 0.05, y = 0.0025;
  const double u = u_tau / kappa * std::log(e * y * u_tau / kNu);
  EXPECT_NEAR(vofdem::wall_shear_velocity(u, y, kNu, 0.0, kappa, e), u_tau, 1e-12);
  // viscous sublayer, y+ = 3: U = u_tau y+
  const double y_lin = 3.0 * kNu / u_tau;
  EXPECT_NEAR(vofdem::wall_shear_velocity(u_tau * 3.0, y_lin, kNu, 0.0, kappa, e), u_tau, 1e-12);
  // rough wall: z0 = nu/(E u_tau) + ks/30; fully rough limit ln(30 y / ks) within 0.5 %
  const double ks = 0.01, yr = 0.02;
  const double ur = u_tau / kappa * std::log(yr / (kNu / (e * u_tau) + ks / 30.0));
  EXPECT_NEAR(vofdem::wall_shear_velocity(ur, yr, kNu, ks, kappa, e), u_tau, 1e-12);
  const double u_fully_rough = kappa * ur / std::log(30.0 * yr / ks);
  EXPECT_NEAR(vofdem::wall_shear_velocity(ur, yr, kNu, ks, kappa, e), u_fully_rough, 5e-3 * u_fully_rough);
  EXPECT_EQ(vofdem::wall_shear_velocity(0.0, y, kNu, 0.0, kappa, e), 0.0);
  // a cell inside the roughness still gets a finite, positive u_tau
  const double inside = vofdem::wall_shear_velocity(0.1, 0.001, kNu, 0.1, kappa, e);
  EXPECT_TRUE(std::isfinite(inside) && inside > 0.0);
}

TEST(KEpsilon, InflowValuesFromIntensityAndLengthScale) {
  KEpsilonParams p = pinned_k_epsilon_params();
  p.inflow_intensity = 0.1;
  p.inflow_length_scale = 0.02;
  const KEpsilonModel m(Grid2D::uniform(2, 2, 1.0, 1.0), p);
  const double k = 1.5 * 0.1 * 0.1 * 0.5 * 0.5;  // U = 0.5 m/s
  EXPECT_NEAR(m.inflow_k(0.5), k, 1e-15);
  EXPECT_NEAR(m.inflow_eps(0.5), std::pow(0.09, 0.75) * std::pow(k, 1.5) / 0.02, 1e-14);
  EXPECT_EQ(m.inflow_k(0.0), p.k_min);
}

// homogeneous decay against k(t) = k0 (1 + (C2-1) eps0 t/k0)^(-1/(C2-1)), on a grid graded in z
// with air on top: the free surface must not disturb the water below
TEST(KEpsilon, HomogeneousDecayMatchesTheAnalyticSolution) {
  const Grid2D g = Grid2D::graded(3, 0.3, 0.05, 0.01, 0.005, 0.02);  // dz 0.005 then 0.01
  const double k0 = 1e-2, eps0 = 1e-3, tau = k0 / eps0;            // tau = 10 s
  auto run = [&](double dt, double t_end) {
    KEpsilonModel m(g, pinned_k_epsilon_params(), closed_to_flux());
    m.initialize(k0, eps0, kNu);
    Flow f(g);
    for (int i = 0; i < g.nx(); ++i) f.F[g.cell(i, g.nz() - 1)] = 0.0;  // an air row
    const int nsteps = static_cast<int>(std::lround(t_end / dt));
    for (int s = 0; s < nsteps; ++s) m.step(dt, f.face_u, f.face_w, f.porosity, f.F, f.nu);
    // water cells stay uniform; air cells hold the floors and no eddy viscosity
    for (int c = 0; c < g.cell(0, g.nz() - 1); ++c) EXPECT_NEAR(m.cell_k[c], m.cell_k[0], 1e-13 * m.cell_k[0]);
    EXPECT_EQ(m.cell_nut[g.cell(1, g.nz() - 1)], 0.0);
    EXPECT_EQ(m.cell_k[g.cell(1, g.nz() - 1)], m.params().k_min);
    return m.cell_k[0];
  };
  const double t_end = 3.0 * tau;
  const double exact = decay_k(k0, eps0, 1.92, t_end);
  const double k_fine = run(tau / 200.0, t_end), k_coarse = run(tau / 100.0, t_end);
  const double err_fine = std::abs(k_fine / exact - 1.0), err_coarse = std::abs(k_coarse / exact - 1.0);
  EXPECT_LT(err_fine, 0.01) << "k = " << k_fine << ", exact " << exact;
  std::printf("[ info     ] decay to t = 3 k0/eps0: error %.3g %% at dt = tau/200, %.3g %% at tau/100\n",
              100 * err_fine, 100 * err_coarse);
  // backward Euler with linearised sinks: first order in dt
  EXPECT_NEAR(err_coarse / err_fine, 2.0, 0.15);
}

TEST(KEpsilon, StaysPositiveUnderHugeStepsAndExtremeStrain) {
  const Grid2D g = Grid2D::graded(10, 0.5, 0.12, 0.02, 0.005, 0.02);
  std::mt19937 rng(7);
  for (int sweeps : {1, 3}) {
    for (double dt : {1e-6, 1e2, 1e6}) {
      KEpsilonParams p = pinned_k_epsilon_params();
      p.sweeps = sweeps;
      // nu_t also within its cap, nut_max_ratio times the molecular viscosity
      run_random_strain(g, p, dt, rng, [](const KEpsilonModel& m) {
        expect_all_positive_finite(m);
        for (double nut : m.cell_nut) ASSERT_LE(nut, m.params().nut_max_ratio * kNu * (1 + 1e-15));
      });
      if (HasFatalFailure()) return;
    }
  }
}

// no mean flow in a walled box: k and eps only decay (their maxima never grow), stay positive
TEST(KEpsilon, ZeroVelocityDecaysAndStaysBounded) {
  const Grid2D g = Grid2D::graded(8, 0.2, 0.1, 0.01, 0.005, 0.02);
  KEpsilonModel m(g, pinned_k_epsilon_params(), walled_box());
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  for (int c = 0; c < g.ncell(); ++c) {
    m.cell_k[c] = 1e-3 * (0.1 + unit(rng));
    m.cell_eps[c] = 1e-4 * (0.1 + unit(rng));
  }
  Flow f(g);
  double kmax = *std::max_element(m.cell_k.begin(), m.cell_k.end());
  double emax = *std::max_element(m.cell_eps.begin(), m.cell_eps.end());
  const double dt = 0.01;
  for (int s = 0; s < 300; ++s) {
    m.step(dt, f.face_u, f.face_w, f.porosity, f.F, f.nu);
    expect_all_positive_finite(m);
    const double kn = *std::max_element(m.cell_k.begin(), m.cell_k.end());
    const double en = *std::max_element(m.cell_eps.begin(), m.cell_eps.end());
    ASSERT_LE(kn, kmax);
    ASSERT_LE(en, emax);
    kmax = kn;
    emax = en;
  }
  EXPECT_LT(kmax, 1e-3 * 1.1 * 0.5);  // decayed well below the initial maximum
  // no flow, no wall shear
  for (double t : m.face_z_wall_shear) EXPECT_EQ(t, 0.0);
}

// the log-layer solution k = u_tau^2/sqrt(C_mu), eps = u_tau^3/(kappa z) under the log-law profile
// U = u_tau/kappa ln(E z u_tau/nu) solves (K), (E) exactly when the constants satisfy
// kappa^2 = (C2 - C1) sigma_eps sqrt(C_mu). Its discrete residual, the rates d ln k/dt and
// d ln eps/dt of one short step relative to eps/k, must vanish at second order in dz: checks the
// assembled production, dissipation and diffusion. The analytic solution ignores the molecular
// diffusion nu d2eps/dz2, whose relative size 2 nu kappa/(u_tau z sqrt(C_mu)) would leave a
// grid-independent residual: nu is made tiny here (it only shifts U by a constant).
double log_layer_residual(int nz) {
  const double h = 0.1, u_tau = 0.02, nu = 1e-12;
  const Grid2D g = Grid2D::uniform(3, nz, 0.1, h);
  KEpsilonParams p = pinned_k_epsilon_params();
  p.kappa = std::sqrt((p.c2 - p.c1) * p.sigma_eps * std::sqrt(p.c_mu));  // 0.4327
  KEpsilonBoundaries b;
  b.left = b.right = KEpsilonBoundary::kZeroGradient;
  KEpsilonModel m(g, p, b);
  Flow f(g);
  std::fill(f.nu.begin(), f.nu.end(), nu);
  for (int k = 0; k < g.nz(); ++k) {
    const double z = g.z_center(k);
    for (int i = 0; i <= g.nx(); ++i)
      f.face_u[g.face_x(i, k)] = u_tau / p.kappa * std::log(p.log_law_e * z * u_tau / nu);
    for (int i = 0; i < g.nx(); ++i) {
      m.cell_k[g.cell(i, k)] = u_tau * u_tau / std::sqrt(p.c_mu);
      m.cell_eps[g.cell(i, k)] = std::pow(u_tau, 3) / (p.kappa * z);
      m.cell_nut[g.cell(i, k)] = p.kappa * u_tau * z;
    }
  }
  const double dt = 1e-4;
  const std::vector<double> k0 = m.cell_k, e0 = m.cell_eps;
  m.step(dt, f.face_u, f.face_w, f.porosity, f.F, f.nu);
  EXPECT_NEAR(m.cell_k[g.cell(1, 0)], k0[g.cell(1, 0)], 1e-12 * k0[g.cell(1, 0)]);  // wall function
  double worst = 0.0;
  for (int k = 0; k < g.nz(); ++k) {
    const double z = g.z_center(k);
    if (z < 0.3 * h || z > 0.7 * h) continue;  // away from the wall cell and the zero-gradient top
    const int c = g.cell(1, k);
    const double scale = e0[c] / k0[c];
    worst = std::max(worst, std::abs(m.cell_k[c] / k0[c] - 1.0) / dt / scale);
    worst = std::max(worst, std::abs(m.cell_eps[c] / e0[c] - 1.0) / dt / scale);
  }
  return worst;
}

TEST(KEpsilon, LogLayerSolutionIsSteadyToSecondOrder) {
  const double r20 = log_layer_residual(20), r40 = log_layer_residual(40);
  EXPECT_LT(r40, 0.01) << "residual " << r40;
  std::printf("[ info     ] log-layer residual (relative to eps/k), 20 rows: %.3g, 40 rows: %.3g\n", r20, r40);
  EXPECT_NEAR(r20 / r40, 4.0, 0.6) << r20 << " " << r40;
}

// fully developed open channel: depth h, slope S, so u_tau = sqrt(g h S) by the momentum balance.
// A 1D momentum solve in the test, d/dz((nu + nu_t) dU/dz) + g S = 0 with the model's wall shear at
// the bed and no stress at the surface, alternates with k-epsilon steps until both are steady.
TEST(KEpsilon, OpenChannelWallFunctionAndNearWallEddyViscosity) {
  const double h = 0.1, slope = 4e-4, grav = 9.81, u_tau = std::sqrt(grav * h * slope);
  const Grid2D g = Grid2D::graded(1, 0.1, h, 0.01, 0.005, 0.02);  // the paper's rows: y1 = 2.5 mm
  const int nz = g.nz();
  KEpsilonBoundaries b;
  b.left = b.right = KEpsilonBoundary::kZeroGradient;
  KEpsilonModel m(g, pinned_k_epsilon_params(), b);
  m.initialize(1e-4, 1e-5, kNu);
  Flow f(g);
  std::vector<double> u(nz), lo(nz), di(nz), up(nz), rhs(nz);
  for (int k = 0; k < nz; ++k) u[k] = u_tau / 0.41 * std::log(9.8 * g.z_center(k) * u_tau / kNu);
  double change = 1.0;
  int it = 0;
  for (; it < 20000 && change > 1e-11; ++it) {
    for (int k = 0; k < nz; ++k) f.face_u[g.face_x(0, k)] = f.face_u[g.face_x(1, k)] = u[k];
    const std::vector<double> k_prev = m.cell_k;
    m.step(m.stable_dt(f.face_u, f.face_w, f.porosity, f.F, f.nu), f.face_u, f.face_w, f.porosity, f.F, f.nu);
    // steady momentum with the bed shear u_tau^2 linearised in U_0 (Thomas algorithm)
    const double cw = -m.face_z_wall_shear[g.face_z(0, 0)] / u[0];
    for (int k = 0; k < nz; ++k) {
      const double dn = k > 0 ? (kNu + 0.5 * (m.cell_nut[k] + m.cell_nut[k - 1])) / (g.z_center(k) - g.z_center(k - 1))
                              : cw;
      const double dp = k + 1 < nz
                            ? (kNu + 0.5 * (m.cell_nut[k] + m.cell_nut[k + 1])) / (g.z_center(k + 1) - g.z_center(k))
                            : 0.0;
      lo[k] = k > 0 ? -dn : 0.0;
      up[k] = -dp;
      di[k] = dn + dp;
      rhs[k] = grav * slope * g.dz(k);
    }
    for (int k = 1; k < nz; ++k) {
      const double w = lo[k] / di[k - 1];
      di[k] -= w * up[k - 1];
      rhs[k] -= w * rhs[k - 1];
    }
    u[nz - 1] = rhs[nz - 1] / di[nz - 1];
    for (int k = nz - 2; k >= 0; --k) u[k] = (rhs[k] - up[k] * u[k + 1]) / di[k];
    change = 0.0;
    for (int k = 0; k < nz; ++k) change = std::max(change, std::abs(m.cell_k[k] / k_prev[k] - 1.0));
  }
  ASSERT_LE(change, 1e-11) << "not steady after " << it << " iterations";
  // the bed shear balances gravity: the wall function's u_tau is sqrt(g h S)
  EXPECT_NEAR(m.cell_u_tau[0], u_tau, 1e-6 * u_tau);
  // first cell: the wall-function values (to round-off for the u_tau it found)
  const double ut = m.cell_u_tau[0], y1 = 0.5 * g.dz(0);
  EXPECT_NEAR(m.cell_k[0], ut * ut / std::sqrt(0.09), 1e-12);
  EXPECT_NEAR(m.cell_eps[0], std::pow(ut, 3) / (0.41 * y1), 1e-10);
  EXPECT_NEAR(m.cell_nut[0], 0.41 * ut * y1, 1e-15);
  // the first cell's velocity obeys the log law: U_0 = u_tau/kappa ln(E y1 u_tau/nu)
  EXPECT_NEAR(u[0], ut / 0.41 * std::log(9.8 * y1 * ut / kNu), 1e-9);
  // near the bed (z < 0.2 h): the velocity follows the log law within 2 %, and nu_t is within 20 %
  // of the local-equilibrium value kappa u_tau z (1 - z/h) of a log layer under the linear stress
  // of an open channel. Measured: 0.93, 0.86, 0.83 of it at z/h = 0.075, 0.125, 0.175 (and 0.83 up
  // to z/h = 0.4, on 2.5 mm rows as well): the model is not in local equilibrium there (turbulent
  // transport of k and eps), and the wall cell's fixed eps bounds the first rows. An a-priori 15 %
  // was exceeded at z/h = 0.175.
  for (int k = 1; g.z_center(k) < 0.2 * h; ++k) {
    const double z = g.z_center(k), expect = 0.41 * u_tau * z * (1.0 - z / h);
    EXPECT_NEAR(m.cell_nut[k], expect, 0.20 * expect) << "row " << k << " z = " << z;
    const double u_log = u_tau / 0.41 * std::log(9.8 * z * u_tau / kNu);
    EXPECT_NEAR(u[k], u_log, 0.02 * u_log) << "row " << k;
    std::printf("[ info     ] z/h = %.3f  nu_t / (kappa u_tau z (1 - z/h)) = %.3f  U / U_log = %.4f\n", z / h,
                m.cell_nut[k] / expect, u[k] / u_log);
  }
}

// slow, obvious reference: the backward-Euler system of (K) and (E) without production, assembled
// row by row into a dense matrix and solved by LU; the model's Jacobi sweeps must converge to it
// (porous and solid cells, an inflow side, a graded grid, dt 5x above the explicit limit)
TEST(KEpsilon, JacobiSweepsConvergeToTheDenseBackwardEulerSolution) {
  const Grid2D g = Grid2D::graded(5, 0.5, 0.06, 0.02, 0.01, 0.02);  // rows 0.01, 0.01, 0.02, 0.02
  const int nx = g.nx(), nz = g.nz(), n = g.ncell();
  KEpsilonParams p = pinned_k_epsilon_params();
  p.flags = vofdem::kKEpsAdvection | vofdem::kKEpsDiffusion;
  p.sweeps = 400;
  KEpsilonBoundaries b = closed_to_flux();
  b.left = KEpsilonBoundary::kInflow;
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
  f.porosity[g.cell(2, 1)] = 0.0;  // a solid cell
  for (int k = 0; k < nz; ++k)
    for (int i = 0; i <= nx; ++i) f.face_u[g.face_x(i, k)] = 0.2 + 0.1 * unit(rng);
  for (int k = 1; k < nz; ++k)
    for (int i = 0; i < nx; ++i) f.face_w[g.face_z(i, k)] = 0.1 * (unit(rng) - 0.5);
  const double dt = 5.0 * m.stable_dt(f.face_u, f.face_w, f.porosity, f.F, f.nu);
  const std::vector<double> k0 = m.cell_k, e0 = m.cell_eps, nut0 = m.cell_nut;
  m.step(dt, f.face_u, f.face_w, f.porosity, f.F, f.nu);

  for (int eq = 0; eq < 2; ++eq) {
    const double sigma = eq == 0 ? p.sigma_k : p.sigma_eps;
    const double sink_c = eq == 0 ? 1.0 : p.c2;
    Eigen::MatrixXd a = Eigen::MatrixXd::Zero(n, n);
    Eigen::VectorXd rhs = Eigen::VectorXd::Zero(n);
    auto cond = [&](int c) { return f.porosity[c] * (kNu + nut0[c] / sigma); };
    for (int k = 0; k < nz; ++k) {
      for (int i = 0; i < nx; ++i) {
        const int c = g.cell(i, k);
        const double np = f.porosity[c];
        if (np == 0.0) {  // not an unknown: keep its value
          a(c, c) = 1.0;
          rhs(c) = eq == 0 ? p.k_min : p.eps_min;
          continue;
        }
        const double old = eq == 0 ? k0[c] : e0[c];
        a(c, c) += np / dt + np * sink_c * e0[c] / k0[c];
        rhs(c) += np * old / dt;
        // west, east, south, north: neighbour, inflow velocity, face length, half widths
        const double dz = g.dz(k), dx = g.dx();
        struct Side { int i, k; double vin, len; };
        const Side sides[4] = {{i - 1, k, f.face_u[g.face_x(i, k)], dx},
                               {i + 1, k, -f.face_u[g.face_x(i + 1, k)], dx},
                               {i, k - 1, f.face_w[g.face_z(i, k)], dz},
                               {i, k + 1, -f.face_w[g.face_z(i, k + 1)], dz}};
        for (int s = 0; s < 4; ++s) {
          const Side& sd = sides[s];
          if (sd.i < 0) {  // inflow side
            if (sd.vin <= 0.0) continue;
            const double kin = 1.5 * std::pow(p.inflow_intensity * sd.vin / np, 2);
            const double vin = eq == 0 ? kin : std::pow(0.09, 0.75) * std::pow(kin, 1.5) / p.inflow_length_scale;
            const double coef = sd.vin / dx + cond(c) / (dx * 0.5 * dx);
            a(c, c) += coef;
            rhs(c) += coef * vin;
            continue;
          }
          if (sd.i >= nx || sd.k < 0 || sd.k >= nz) continue;  // zero gradient
          const int cn = g.cell(sd.i, sd.k);
          if (f.porosity[cn] == 0.0) continue;  // solid: no flux
          const double half_p = 0.5 * sd.len, half_n = 0.5 * (s < 2 ? dx : g.dz(sd.k));
          const double coef = std::max(sd.vin, 0.0) / sd.len + 1.0 / (sd.len * (half_p / cond(c) + half_n / cond(cn)));
          a(c, c) += coef;
          a(c, cn) -= coef;
        }
      }
    }
    const Eigen::VectorXd x = a.partialPivLu().solve(rhs);
    const std::vector<double>& got = eq == 0 ? m.cell_k : m.cell_eps;
    for (int c = 0; c < n; ++c) EXPECT_NEAR(got[c], x(c), 1e-10 * x(c)) << "eq " << eq << " cell " << c;
  }
}

// faces of solid cells are walls: the cells beside a solid block get wall-law values and a wall shear
TEST(KEpsilon, SolidCellsActAsWalls) {
  const Grid2D g = Grid2D::uniform(6, 5, 0.6, 0.5);
  KEpsilonModel m(g, pinned_k_epsilon_params(), closed_to_flux());
  m.initialize(1e-4, 1e-5, kNu);
  Flow f(g);
  const int solid = g.cell(3, 2);
  f.porosity[solid] = 0.0;
  for (double& u : f.face_u) u = 0.3;
  for (int k = 0; k <= g.nz(); ++k) f.face_w[g.face_z(1, k)] = -0.2;  // column i = 1 flows down
  f.face_w[g.face_z(3, 2)] = f.face_w[g.face_z(3, 3)] = 0.0;          // no flow into the block
  m.step(1e-3, f.face_u, f.face_w, f.porosity, f.F, f.nu);
  const int above = g.cell(3, 3), left = g.cell(2, 2);
  EXPECT_GT(m.cell_u_tau[above], 0.0);
  // the block's top face: x-shear against the flow (u > 0)
  EXPECT_LT(m.face_z_wall_shear[g.face_z(3, 3)], 0.0);
  EXPECT_NEAR(m.face_z_wall_shear[g.face_z(3, 3)], -std::pow(m.cell_u_tau[above], 2), 1e-15);
  // the block's left face: tangential velocity zero there, so no shear
  EXPECT_EQ(m.face_x_wall_shear[g.face_x(3, 2)], 0.0);
  EXPECT_EQ(m.cell_u_tau[left], 0.0);
  // solid cell: no eddy viscosity; a cell away from walls keeps being solved
  EXPECT_EQ(m.cell_nut[solid], 0.0);
  EXPECT_EQ(m.cell_u_tau[g.cell(1, 1)], 0.0);
  const double y = 0.05;
  const double ut = vofdem::wall_shear_velocity(0.3, y, kNu, 0.0, 0.41, 9.8);
  EXPECT_NEAR(m.cell_k[above], ut * ut / 0.3, 1e-15);
}

// without solid cells only the cells along the domain's sides are visited for wall faces: their wall
// values are the same to the bit as when a solid cell elsewhere has every cell visited
TEST(KEpsilon, SideWallValuesDoNotDependOnASolidCellElsewhere) {
  const Grid2D g = Grid2D::uniform(9, 7, 0.9, 0.35);
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> vel(-0.5, 0.5);
  Flow f(g);
  for (double& u : f.face_u) u = vel(rng);
  for (double& w : f.face_w) w = vel(rng);
  Flow with_solid = f;
  const int solid = g.cell(4, 3);
  with_solid.porosity[solid] = 0.0;
  KEpsilonModel a(g, pinned_k_epsilon_params(), walled_box()), b(g, pinned_k_epsilon_params(), walled_box());
  a.initialize(1e-4, 1e-5, kNu);
  b.initialize(1e-4, 1e-5, kNu);
  a.step(1e-3, f.face_u, f.face_w, f.porosity, f.F, f.nu);
  b.step(1e-3, with_solid.face_u, with_solid.face_w, with_solid.porosity, with_solid.F, with_solid.nu);
  int sides = 0;
  for (int k = 0; k < g.nz(); ++k)
    for (int i = 0; i < g.nx(); ++i) {
      if (!(i == 0 || k == 0 || i == g.nx() - 1 || k == g.nz() - 1)) continue;
      const int c = g.cell(i, k);
      EXPECT_GT(a.cell_u_tau[c], 0.0) << "cell (" << i << ", " << k << ")";
      EXPECT_EQ(a.cell_u_tau[c], b.cell_u_tau[c]) << "cell (" << i << ", " << k << ")";
      ++sides;
    }
  EXPECT_EQ(sides, 2 * (9 + 7) - 4);
  for (int k = 0; k < g.nz(); ++k) {
    EXPECT_EQ(a.face_x_wall_shear[g.face_x(0, k)], b.face_x_wall_shear[g.face_x(0, k)]);
    EXPECT_EQ(a.face_x_wall_shear[g.face_x(g.nx(), k)], b.face_x_wall_shear[g.face_x(g.nx(), k)]);
  }
  for (int i = 0; i < g.nx(); ++i) {
    EXPECT_EQ(a.face_z_wall_shear[g.face_z(i, 0)], b.face_z_wall_shear[g.face_z(i, 0)]);
    EXPECT_EQ(a.face_z_wall_shear[g.face_z(i, g.nz())], b.face_z_wall_shear[g.face_z(i, g.nz())]);
  }
  // the inner cells beside the solid one are walls there only
  EXPECT_EQ(a.cell_u_tau[g.cell(4, 4)], 0.0);
  EXPECT_GT(b.cell_u_tau[g.cell(4, 4)], 0.0);
}

// a vertical wall: the shear on its x-faces is the z component, against the tangential flow; switching
// wall functions off clears the wall outputs
TEST(KEpsilon, EndWallShearOpposesTheFlowAndClearsWhenSwitchedOff) {
  const Grid2D g = Grid2D::uniform(4, 6, 0.4, 0.3);  // dx 0.1
  KEpsilonModel m(g, pinned_k_epsilon_params(), walled_box());
  m.initialize(1e-4, 1e-5, kNu);
  Flow f(g);
  for (int k = 1; k < g.nz(); ++k) f.face_w[g.face_z(0, k)] = -0.2;  // down along the left wall
  m.step(1e-3, f.face_u, f.face_w, f.porosity, f.F, f.nu);
  const int k = 3;
  const double ut = vofdem::wall_shear_velocity(0.2, 0.05, kNu, 0.0, 0.41, 9.8);
  EXPECT_NEAR(m.face_x_wall_shear[g.face_x(0, k)], ut * ut, 1e-15);  // upwards, against the flow
  EXPECT_NEAR(m.cell_u_tau[g.cell(0, k)], ut, 1e-15);
  EXPECT_EQ(m.face_x_wall_shear[g.face_x(4, k)], 0.0);  // the right wall sees no flow
  m.set_flags(vofdem::kKEpsAll & ~vofdem::kKEpsWallFunctions);
  EXPECT_EQ(m.face_x_wall_shear[g.face_x(0, k)], 0.0);
  EXPECT_EQ(m.cell_u_tau[g.cell(0, k)], 0.0);
}

// inflow side: k, eps from intensity and length scale are carried in; downstream they decay
TEST(KEpsilon, InflowFeedsTheDomain) {
  const Grid2D g = Grid2D::uniform(20, 1, 2.0, 0.1);
  KEpsilonParams p = pinned_k_epsilon_params();
  p.flags = vofdem::kKEpsAdvection | vofdem::kKEpsDiffusion;
  KEpsilonBoundaries b = closed_to_flux();
  b.left = KEpsilonBoundary::kInflow;
  KEpsilonModel m(g, p, b);
  Flow f(g);
  for (double& u : f.face_u) u = 0.5;
  for (int s = 0; s < 400; ++s) m.step(0.02, f.face_u, f.face_w, f.porosity, f.F, f.nu);
  const double k_in = m.inflow_k(0.5);
  EXPECT_GT(m.cell_k[0], 0.8 * k_in);
  EXPECT_LT(m.cell_k[0], k_in);
  for (int i = 1; i < g.nx(); ++i) EXPECT_LT(m.cell_k[i], m.cell_k[i - 1]);
}

TEST(KEpsilon, DisabledEffectsAreNotEntered) {
  const Grid2D g = Grid2D::uniform(4, 4, 0.4, 0.4);
  KEpsilonParams p = pinned_k_epsilon_params();
  p.flags = vofdem::kKEpsAdvection | vofdem::kKEpsDiffusion;
  KEpsilonModel m(g, p);
  Flow f(g);
  m.step(0.01, f.face_u, f.face_w, f.porosity, f.F, f.nu);
  const auto& prof = m.profile();
  EXPECT_EQ(prof.calls()[prof.find("k-eps wall functions")], 0);
  EXPECT_EQ(prof.calls()[prof.find("k-eps production")], 0);
  EXPECT_EQ(prof.calls()[prof.find("k-eps transport")], 1);
}

TEST(KEpsilon, StableDtIsTheExplicitLimit) {
  const Grid2D g = Grid2D::uniform(5, 4, 0.5, 0.2);  // dx 0.1, dz 0.05
  KEpsilonParams p = pinned_k_epsilon_params();
  p.flags = vofdem::kKEpsAdvection;
  KEpsilonModel m(g, p, closed_to_flux());
  Flow f(g);
  for (double& u : f.face_u) u = 2.0;
  // advection only: the inflow coefficient u/dx = 20 /s, times cfl 0.5
  EXPECT_NEAR(m.stable_dt(f.face_u, f.face_w, f.porosity, f.F, f.nu), 0.5 / 20.0, 1e-15);
  std::fill(f.face_u.begin(), f.face_u.end(), 0.0);
  EXPECT_TRUE(std::isinf(m.stable_dt(f.face_u, f.face_w, f.porosity, f.F, f.nu)));
}

TEST(KEpsilon, DeterministicToTheBit) {
  const Grid2D g = Grid2D::graded(12, 0.6, 0.1, 0.01, 0.005, 0.02);
  auto run = [&]() {
    KEpsilonModel m(g);
    m.initialize(1e-4, 1e-5, kNu);
    Flow f(g);
    std::mt19937 rng(11);
    std::uniform_real_distribution<double> vel(-0.5, 0.5);
    for (double& u : f.face_u) u = vel(rng);
    for (double& w : f.face_w) w = vel(rng);
    for (int s = 0; s < 50; ++s) m.step(1e-3, f.face_u, f.face_w, f.porosity, f.F, f.nu);
    std::vector<double> state = m.cell_k;
    state.insert(state.end(), m.cell_eps.begin(), m.cell_eps.end());
    state.insert(state.end(), m.cell_nut.begin(), m.cell_nut.end());
    return state;
  };
  const std::vector<double> a = run(), b = run();
  ASSERT_EQ(a.size(), b.size());
  EXPECT_EQ(std::memcmp(a.data(), b.data(), a.size() * sizeof(double)), 0);
}

TEST(KEpsilon, NonFiniteInputThrowsNamingTheCellAndRestores) {
  const Grid2D g = Grid2D::uniform(4, 3, 0.4, 0.3);
  KEpsilonModel m(g);
  m.initialize(1e-4, 1e-5, kNu);
  Flow f(g);
  m.step(1e-3, f.face_u, f.face_w, f.porosity, f.F, f.nu);
  const std::vector<double> k_before = m.cell_k;
  const double t_before = m.time;
  f.face_u[g.face_x(2, 1)] = std::nan("");
  try {
    m.step(1e-3, f.face_u, f.face_w, f.porosity, f.F, f.nu);
    FAIL() << "expected std::runtime_error";
  } catch (const std::runtime_error& e) {
    const std::string msg = e.what();
    EXPECT_NE(msg.find("cell (i="), std::string::npos) << msg;
    EXPECT_NE(msg.find("t = 0.002"), std::string::npos) << msg;
  }
  EXPECT_EQ(m.cell_k, k_before);
  EXPECT_EQ(m.time, t_before);
}

TEST(KEpsilon, RefusesBadInput) {
  const Grid2D g = Grid2D::uniform(3, 3, 0.3, 0.3);
  KEpsilonParams bad = pinned_k_epsilon_params();
  bad.c2 = 1.0;
  EXPECT_THROW(KEpsilonModel(g, bad), std::invalid_argument);
  bad = pinned_k_epsilon_params();
  bad.sweeps = -1;
  EXPECT_THROW(KEpsilonModel(g, bad), std::invalid_argument);
  bad = pinned_k_epsilon_params();
  bad.k_min = 0.0;
  EXPECT_THROW(KEpsilonModel(g, bad), std::invalid_argument);
  KEpsilonModel m(g);
  Flow f(g);
  EXPECT_THROW(m.step(0.0, f.face_u, f.face_w, f.porosity, f.F, f.nu), std::invalid_argument);
  std::vector<double> short_u(3, 0.0);
  EXPECT_THROW(m.step(0.1, short_u, f.face_w, f.porosity, f.F, f.nu), std::invalid_argument);
  // an empty cell_F means all water; k, eps set to zero by hand start from the floors
  std::fill(m.cell_k.begin(), m.cell_k.end(), 0.0);
  std::fill(m.cell_eps.begin(), m.cell_eps.end(), 0.0);
  for (double& u : f.face_u) u = 0.5;
  EXPECT_NO_THROW(m.step(0.1, f.face_u, f.face_w, f.porosity, {}, f.nu));
  expect_all_positive_finite(m);
  try {
    KEpsilonParams p = pinned_k_epsilon_params();
    p.cfl = 2.0;
    KEpsilonModel bad_model(g, p);
    FAIL();
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("cfl = 2"), std::string::npos);
  }
}
