// Implicit vertical diffusion of momentum (MomentumTerms::implicit_vertical,
// FlowParams::viscous_scheme): decay of a sinusoidal shear profile against its analytic answer, the
// backward-Euler amplification of one step, and stability far above the explicit limit.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include <Eigen/Dense>

#include "vofdem/flow/momentum.h"
#include "vofdem/flow/vof_grid.h"
#include "common/pinned_params.h"
#include "vofdem/common/numbers.h"

using namespace vofdem;

namespace {

using vofdem::kPi;

// single-phase kernel fields: water density, uniform viscosity mu [Pa s]
struct Column {
  Grid2D g;
  std::vector<double> u, w, nx_, nz_, mu, rx, rz;
  Column(const Grid2D& grid, double mu0)
      : g(grid),
        u(grid.nface_x(), 0.0),
        w(grid.nface_z(), 0.0),
        nx_(grid.nface_x(), 1.0),
        nz_(grid.nface_z(), 1.0),
        mu(grid.ncell(), mu0),
        rx(grid.nface_x(), 1000.0),
        rz(grid.nface_z(), 1000.0) {}
  MomentumFields fields() const { return {u.data(), w.data(), nx_.data(), nz_.data(), mu.data(), rx.data(), rz.data()}; }
};

// u = cos(pi z / H) on every x-face (uniform in x: no x-diffusion, no cross term), slip bed, slip lid
void set_shear_mode(Column& c, double amp) {
  const double h = c.g.height_z();
  for (int k = 0; k < c.g.nz(); ++k)
    for (int i = 0; i <= c.g.nx(); ++i) c.u[c.g.face_x(i, k)] = amp * std::cos(kPi * (c.g.z_center(k) - c.g.z_faces().front()) / h);
}

// advance the kernel (viscosity only) n steps of dt, the end faces kept on the mode
double decay(Column& c, bool implicit, double dt, int n) {
  MomentumTerms t;
  t.convection = false;
  t.implicit_vertical = implicit;
  MomentumBoundary bc;
  bc.top_open = false;
  std::vector<double> us, ws;
  MomentumScratch s;
  const int j_probe = c.g.face_x(c.g.nx() / 2, 0);
  const double a0 = c.u[j_probe];
  for (int step = 0; step < n; ++step) {
    momentum_explicit(c.g, c.fields(), t, bc, dt, us, ws, s);
    for (int k = 0; k < c.g.nz(); ++k)
      for (int i = 1; i < c.g.nx(); ++i) c.u[c.g.face_x(i, k)] = us[c.g.face_x(i, k)];
    for (int k = 0; k < c.g.nz(); ++k) {  // end faces: same value as their neighbour (uniform in x)
      c.u[c.g.face_x(0, k)] = c.u[c.g.face_x(1, k)];
      c.u[c.g.face_x(c.g.nx(), k)] = c.u[c.g.face_x(1, k)];
    }
  }
  return c.u[j_probe] / a0;
}

double explicit_limit(const Column& c) {
  std::vector<double> cm;
  return viscous_stable_dt(c.g, c.fields(), cm, false);
}

}  // namespace

TEST(ImplicitViscosity, ShearModeDecaysAtTheAnalyticRateWithBothSchemes) {
  // H = 0.2 m, 40 rows, nu = 1e-3 m^2/s: u = cos(pi z/H) exp(-nu (pi/H)^2 t); to t = 4 s the amplitude
  // is exp(-0.987) = 0.373. Spatial error of the decay rate (pi dz / H)^2 / 12 = 5e-4, time error
  // O(dt lambda) at dt = explicit limit / 4: both within 1 % of the exact amplitude, and of each other
  const Grid2D g = Grid2D::uniform(4, 40, 0.2, 0.2);
  const double nu = 1e-3, t_end = 4.0;
  const double exact = std::exp(-nu * (kPi / 0.2) * (kPi / 0.2) * t_end);
  Column ce(g, nu * 1000.0), ci(g, nu * 1000.0);
  set_shear_mode(ce, 1.0);
  set_shear_mode(ci, 1.0);
  const double dt_lim = explicit_limit(ce);
  const int n = static_cast<int>(std::ceil(t_end / (0.25 * dt_lim)));
  const double ae = decay(ce, false, t_end / n, n), ai = decay(ci, true, t_end / n, n);
  EXPECT_NEAR(ae, exact, 0.01 * exact);
  EXPECT_NEAR(ai, exact, 0.01 * exact);
  EXPECT_NEAR(ae, ai, 0.01 * exact);
}

TEST(ImplicitViscosity, OneStepIsBackwardEulerOfTheDiscreteMode) {
  // the cell-centred cosine is an eigenvector of the discrete Neumann operator with
  // lambda = nu (4 / dz^2) sin^2(pi dz / (2 H)): one step multiplies it by 1 / (1 + dt lambda) exactly
  const Grid2D g = Grid2D::uniform(4, 20, 0.2, 0.1);
  const double nu = 2e-3, dz = 0.1 / 20, h = 0.1;
  const double lambda = nu * 4.0 / (dz * dz) * std::pow(std::sin(kPi * dz / (2.0 * h)), 2);
  Column c(g, nu * 1000.0);
  set_shear_mode(c, 1.0);
  const std::vector<double> u0 = c.u;
  const double dt = 100.0 * explicit_limit(c);
  decay(c, true, dt, 1);
  for (int k = 0; k < g.nz(); ++k) {
    const int j = g.face_x(2, k);
    EXPECT_NEAR(c.u[j], u0[j] / (1.0 + dt * lambda), 1e-12) << k;
  }
}

TEST(ImplicitViscosity, WModeDecaysWithTwiceTheRateOfItsNormalStress) {
  // w = sin(pi z / H) on z-faces, zero on the bed and the lid: d/dz(2 mu dw/dz) gives
  // lambda = 2 nu (4 / dz^2) sin^2(pi dz / (2 H)) on the uniform grid; backward Euler divides by 1 + dt lambda
  const Grid2D g = Grid2D::uniform(4, 20, 0.2, 0.1);
  const double nu = 2e-3, dz = 0.1 / 20, h = 0.1;
  const double lambda = 2.0 * nu * 4.0 / (dz * dz) * std::pow(std::sin(kPi * dz / (2.0 * h)), 2);
  Column c(g, nu * 1000.0);
  for (int k = 0; k <= g.nz(); ++k)
    for (int i = 0; i < g.nx(); ++i) c.w[g.face_z(i, k)] = std::sin(kPi * k * dz / h);
  MomentumTerms t;
  t.convection = false;
  MomentumBoundary bc;
  bc.top_open = false;
  std::vector<double> us, ws;
  MomentumScratch s;
  const double dt_small = 1e-3 * explicit_limit(c), dt_big = 50.0 * explicit_limit(c);
  // explicit, one small step: (w* - w) / dt = -lambda w
  momentum_explicit(g, c.fields(), t, bc, dt_small, us, ws, s);
  for (int k = 1; k < g.nz(); ++k) {
    const int j = g.face_z(1, k);
    EXPECT_NEAR((ws[j] - c.w[j]) / dt_small, -lambda * c.w[j], 1e-9 * lambda) << k;
  }
  t.implicit_vertical = true;
  momentum_explicit(g, c.fields(), t, bc, dt_big, us, ws, s);
  for (int k = 1; k < g.nz(); ++k) {
    const int j = g.face_z(1, k);
    EXPECT_NEAR(ws[j], c.w[j] / (1.0 + dt_big * lambda), 1e-12) << k;
  }
}

TEST(ImplicitViscosity, StableFarAboveTheExplicitLimitWhereForwardEulerBlowsUp) {
  // a rough profile (cos mode plus the grid-scale zigzag) with an eddy-viscosity-like nu = 8e-3 m^2/s
  // over dz = 5 mm: 200 steps of 200 explicit limits stay bounded and decay. The Gershgorin bound is set
  // by the w-rows (normal stress 2 mu: ~ dz^2 / (4 nu)); the zigzag of u is unstable above
  // dz^2 / (2 nu): forward Euler at 8 bounds (dt lambda ~ 7 for the zigzag) grows ~6 x per step
  const Grid2D g = Grid2D::uniform(4, 30, 0.1, 0.15);
  Column ci(g, 8.0), ce(g, 8.0);
  for (Column* c : {&ci, &ce}) {
    set_shear_mode(*c, 1.0);
    for (int k = 0; k < g.nz(); ++k)
      for (int i = 0; i <= g.nx(); ++i) c->u[g.face_x(i, k)] += (k % 2 ? 0.5 : -0.5);
  }
  const double lim = explicit_limit(ci);
  decay(ci, true, 200.0 * lim, 200);
  double mi = 0.0, me = 0.0;
  for (double v : ci.u) mi = std::max(mi, std::abs(v));
  EXPECT_LT(mi, 1.5);
  decay(ce, false, 8.0 * lim, 200);
  for (double v : ce.u) me = std::max(me, std::abs(v));
  EXPECT_GT(me, 10.0);
}

TEST(ImplicitViscosity, StepLimitOfTheImplicitSchemeLeavesOutTheVerticalDiffusion) {
  // uniform nu on dx = 2.5 cm, dz = 5 mm: the explicit bound is set by dz, the implicit one by dx and
  // the cross terms; forward Euler's ~ 1 / (nu (8/dx^2 + 4/dz^2 + ...)), here at least 3x smaller
  const Grid2D g = Grid2D::uniform(8, 20, 0.2, 0.1);
  Column c(g, 8.0);
  std::vector<double> cm;
  const double de = viscous_stable_dt(g, c.fields(), cm, false), di = viscous_stable_dt(g, c.fields(), cm, true);
  EXPECT_GT(di, 3.0 * de);
  // the implicit scheme's bound: 2 / (nu (8 / dx^2 + 4 / (dx dz))) on the x-faces (interior row)
  const double nu = 8e-3, dx = 0.025, dz = 0.005;
  EXPECT_NEAR(di, 2.0 / (nu * (8.0 / (dx * dx) + 4.0 / (dx * dz))), 1e-12);
  // the energy bound: 2 / (nu 8 / dx^2) on both kinds of face, the constant-coefficient dx^2 / (4 nu)
  EXPECT_NEAR(viscous_stable_dt(g, c.fields(), cm, true, ViscousBound::kEnergy), dx * dx / (4.0 * nu), 1e-12);
}

// the whole viscous step (x-diffusion and cross terms explicit, vertical diffusion backward Euler) as
// a matrix, column by column from unit velocities, in a closed box (no-slip walls, slip lid): its
// spectral radius at dt_factor times the step limit (written to *limit)
// (kImplicit: the rows implicit too, dt_factor times kImplicitVertical's limit; slip walls unless
// no_slip; energy_norm receives the step's norm in the kinetic energy, ||R^1/2 M R^-1/2||_2)
double whole_step_radius(const Column& c, const std::vector<double>& eddy, double dt_factor, double* limit,
                         int substeps, ViscousScheme scheme, ViscousBound bound, bool no_slip = true,
                         double* energy_norm = nullptr) {
  const Grid2D& g = c.g;
  MomentumFields f = c.fields();
  f.cell_mu_eddy = eddy.data();  // the flow's default: the eddy part of a corner by harmonic mean
  std::vector<double> cm;
  *limit = viscous_stable_dt(g, f, cm, true, bound);
  const double dt = dt_factor * *limit;
  // unknowns: interior x-faces, then interior z-faces
  std::vector<int> xs, zs;
  for (int k = 0; k < g.nz(); ++k)
    for (int i = 1; i < g.nx(); ++i) xs.push_back(g.face_x(i, k));
  for (int k = 1; k < g.nz(); ++k)
    for (int i = 0; i < g.nx(); ++i) zs.push_back(g.face_z(i, k));
  const int n = static_cast<int>(xs.size() + zs.size());
  Eigen::MatrixXd m(n, n);
  MomentumTerms t;
  t.convection = false;
  t.implicit_vertical = true;
  t.vertical_from_start = scheme == ViscousScheme::kImplicitVerticalFromStart;
  t.implicit_horizontal = scheme == ViscousScheme::kImplicit;
  t.viscous_substeps = substeps;
  MomentumBoundary bc;
  bc.top_open = false;
  bc.no_slip = no_slip;
  Column unit = c;
  std::vector<double> us, ws;
  MomentumScratch s;
  for (int col = 0; col < n; ++col) {
    std::fill(unit.u.begin(), unit.u.end(), 0.0);
    std::fill(unit.w.begin(), unit.w.end(), 0.0);
    if (col < static_cast<int>(xs.size())) unit.u[xs[col]] = 1.0;
    else unit.w[zs[col - xs.size()]] = 1.0;
    MomentumFields fu = unit.fields();
    fu.cell_mu_eddy = eddy.data();
    momentum_explicit(g, fu, t, bc, dt, us, ws, s);
    for (std::size_t r = 0; r < xs.size(); ++r) m(r, col) = us[xs[r]];
    for (std::size_t r = 0; r < zs.size(); ++r) m(xs.size() + r, col) = ws[zs[r]];
  }
  if (energy_norm) {
    // sqrt of each face's mass rho dV (dV per unit width: dx times the face's vertical extent)
    Eigen::VectorXd root(n);
    for (std::size_t r = 0; r < xs.size(); ++r) root(r) = std::sqrt(c.rx[xs[r]] * g.dx() * g.dz(xs[r] / (g.nx() + 1)));
    for (std::size_t r = 0; r < zs.size(); ++r) {
      const int k = zs[r] / g.nx();
      root(xs.size() + r) = std::sqrt(c.rz[zs[r]] * g.dx() * (g.z_center(k) - g.z_center(k - 1)));
    }
    const Eigen::MatrixXd e = root.asDiagonal() * m * root.cwiseInverse().asDiagonal();
    *energy_norm = Eigen::JacobiSVD<Eigen::MatrixXd>(e).singularValues()(0);
  }
  return m.eigenvalues().cwiseAbs().maxCoeff();
}

// water (1e-3 Pa s) plus an eddy viscosity 1e-3 (contrast^r - 1), r uniform in [0, 1) per cell; with
// `air`, the top row air (1.8e-5 Pa s, 1.2 kg/m3) without eddy viscosity. Returns the eddy part
std::vector<double> set_viscosity(Column& c, double contrast, bool air, unsigned seed) {
  const Grid2D& g = c.g;
  auto unit = [&seed] { return (seed = seed * 1103515245u + 12345u) / 4294967296.0; };
  std::vector<double> eddy(g.ncell(), 0.0);
  for (int k = 0; k < g.nz(); ++k)
    for (int i = 0; i < g.nx(); ++i) {
      const int cc = g.cell(i, k);
      const bool in_air = air && k == g.nz() - 1;
      eddy[cc] = in_air ? 0.0 : 1e-3 * (std::pow(contrast, unit()) - 1.0);
      c.mu[cc] = (in_air ? 1.8e-5 : 1e-3) + eddy[cc];
    }
  if (air) {
    for (int i = 0; i <= g.nx(); ++i) c.rx[g.face_x(i, g.nz() - 1)] = 1.2;
    for (int i = 0; i < g.nx(); ++i) c.rz[g.face_z(i, g.nz() - 1)] = 0.5 * (1000.0 + 1.2);
  }
  return eddy;
}

// the viscous fields of the whole-step tests on a graded box (dx 2.5 cm; dz 5 mm then 1 cm): a random
// eddy viscosity (contrast 100) under an air layer, or water of one viscosity throughout (the air's
// larger nu binds the first's limit, the water's the second's)
enum class StepField { kRandomUnderAir, kUniformWater };

double step_spectral_radius(double dt_factor, double* limit, int substeps = 1, StepField field = StepField::kRandomUnderAir,
                            ViscousScheme scheme = ViscousScheme::kImplicitVertical,
                            ViscousBound bound = ViscousBound::kEnergy) {
  Column c(Grid2D::graded(6, 0.15, 0.06, 0.01, 0.005, 0.02), 1e-3);
  std::vector<double> eddy;
  if (field == StepField::kRandomUnderAir) {
    eddy = set_viscosity(c, 100.0, true, 7);
  } else {
    eddy.assign(c.g.ncell(), 1e-2);
    for (double& mu : c.mu) mu = 1e-3 + 1e-2;
  }
  return whole_step_radius(c, eddy, dt_factor, limit, substeps, scheme, bound);
}

TEST(ImplicitViscosity, StepLimitIsStableOnTheWholeStepMatrix) {
  // measured, the energy bound: under the air layer 0.976 at it, uniform water 0.835 at it but 1.149
  // at 1.2 x and 1.601 at 1.5 x (nearly sharp); the row-sum bound: 0.995 and 0.935 at it, the water
  // 0.817 at 3 x, 1.495 at 5 x; the energy limit is 4.7 and 3.5 times the row sum's. The former splitting
  // (the columns from u^n, the explicit increment beside them) grew the uniform water's step at the
  // row-sum limit (1.591): a mode the columns damp keeps dt X u^n whole, stable only to dt |X| = 1
  for (ViscousBound bound : {ViscousBound::kEnergy, ViscousBound::kRowSum})
    for (StepField field : {StepField::kRandomUnderAir, StepField::kUniformWater}) {
      double limit = 0.0;
      const double at = step_spectral_radius(1.0, &limit, 1, field, ViscousScheme::kImplicitVertical, bound);
      std::printf("[ info     ] %s bound, %s: step limit %.3e s, spectral radius %.6f at it\n",
                  bound == ViscousBound::kEnergy ? "energy" : "row-sum",
                  field == StepField::kUniformWater ? "uniform water" : "under air", limit, at);
      EXPECT_LE(at, 1.0 + 1e-9) << static_cast<int>(field) << static_cast<int>(bound);
    }
  double energy = 0.0, row_sum = 0.0;
  // the bounds are not vacuous: above them the step grows
  EXPECT_GT(step_spectral_radius(1.5, &energy, 1, StepField::kUniformWater), 1.0);
  EXPECT_GT(step_spectral_radius(5.0, &row_sum, 1, StepField::kUniformWater, ViscousScheme::kImplicitVertical,
                                 ViscousBound::kRowSum),
            1.0);
  std::printf("[ info     ] uniform water: the energy limit %.4f times the row sum's\n", energy / row_sum);
  EXPECT_GT(energy, 1.5 * row_sum);
  EXPECT_GT(step_spectral_radius(1.0, &row_sum, 1, StepField::kUniformWater, ViscousScheme::kImplicitVerticalFromStart,
                                 ViscousBound::kRowSum),
            1.5);
}

TEST(ImplicitViscosity, EnergyBoundHoldsForTheSplitSchemeOnly) {
  const Grid2D g = Grid2D::uniform(4, 4, 0.1, 0.1);
  Column c(g, 1e-3);
  std::vector<double> cm;
  EXPECT_THROW(viscous_stable_dt(g, c.fields(), cm, false, ViscousBound::kEnergy), std::invalid_argument);
  FlowParams p = test::pinned_flow_params();
  EXPECT_EQ(p.step_bound(), ViscousBound::kEnergy);
  for (ViscousScheme scheme : {ViscousScheme::kExplicit, ViscousScheme::kImplicitVerticalFromStart}) {
    p.viscous_scheme = scheme;
    EXPECT_EQ(p.step_bound(), ViscousBound::kRowSum);
  }
}

TEST(ViscousSubsteps, StableAtFiveTimesTheLimitWhereOneStepGrows) {
  // the same step matrix at 5 x the explicit limit: one step grows (5.489 measured), five substeps
  // of dt / 5 are each at the limit, so the whole step is a product of stable steps
  double limit = 0.0;
  const double one = step_spectral_radius(5.0, &limit, 1, StepField::kUniformWater);
  const double five = step_spectral_radius(5.0, &limit, 5, StepField::kUniformWater);
  std::printf("[ info     ] spectral radius at 5 x the limit: %.3f in one step, %.6f in 5 substeps\n", one, five);
  EXPECT_GT(one, 1.0);
  EXPECT_LE(five, 1.0 + 1e-9);
}

TEST(ImplicitViscosity, StepLimitIsStableOverGridsAndViscosityContrasts) {
  // 96 fields: four grids (dx / dz from 1 to 2.5, one graded), eddy-viscosity contrasts 1-1000, with
  // and without an air layer, three seeds each; at either bound's limit every whole-step matrix stays
  // stable. Measured: largest 0.999302 (energy), 0.999596 (row sums); the former splitting at the
  // row-sum limit: 29 of the 64 kinds of a wider sweep grew, up to 1.68
  const Grid2D grids[] = {Grid2D::graded(6, 0.15, 0.06, 0.01, 0.005, 0.02), Grid2D::uniform(8, 10, 0.2, 0.1),
                          Grid2D::uniform(8, 8, 0.08, 0.08), Grid2D::uniform(6, 12, 0.15, 0.06)};
  for (ViscousBound bound : {ViscousBound::kEnergy, ViscousBound::kRowSum}) {
    double worst = 0.0;
    for (const Grid2D& g : grids)
      for (double contrast : {1.0001, 10.0, 100.0, 1000.0})
        for (bool air : {false, true})
          for (unsigned seed = 1; seed <= 3; ++seed) {
            Column c(g, 1e-3);
            const std::vector<double> eddy = set_viscosity(c, contrast, air, 7919u * seed);
            double limit = 0.0;
            const double r = whole_step_radius(c, eddy, 1.0, &limit, 1, ViscousScheme::kImplicitVertical, bound);
            worst = std::max(worst, r);
            EXPECT_LE(r, 1.0 + 1e-9) << g.nx() << "x" << g.nz() << " contrast " << contrast << " air " << air;
          }
    std::printf("[ info     ] %s bound: largest spectral radius at the limit over 96 fields: %.6f\n",
                bound == ViscousBound::kEnergy ? "energy" : "row-sum", worst);
  }
}

TEST(ViscousSubsteps, OneSubstepIsTheOneStepSchemeBitForBit) {
  // viscous_substeps = 1 takes the one-step path: the same u*, w* to the bit as the default terms
  const Grid2D g = Grid2D::uniform(6, 10, 0.15, 0.1);
  Column c(g, 5.0);
  set_shear_mode(c, 1.0);
  for (int k = 1; k < g.nz(); ++k)
    for (int i = 0; i < g.nx(); ++i) c.w[g.face_z(i, k)] = 0.1 * std::sin(0.7 * i + 1.3 * k);
  MomentumTerms a, b;
  a.implicit_vertical = b.implicit_vertical = true;
  a.gravity_z = b.gravity_z = -9.81;
  b.viscous_substeps = 1;
  std::vector<double> ua, wa, ub, wb;
  MomentumScratch s;
  momentum_explicit(g, c.fields(), a, MomentumBoundary{}, 1e-3, ua, wa, s);
  momentum_explicit(g, c.fields(), b, MomentumBoundary{}, 1e-3, ub, wb, s);
  EXPECT_EQ(ua, ub);
  EXPECT_EQ(wa, wb);
}

// w = sin(pi z / H) (+ a grid-scale zigzag of size `zig`), uniform in x between slip end walls: a mode
// of the discrete stress operator, lambda = 2 nu (4 / dz^2) sin^2(pi dz / (2 H)); n steps of dt with
// the explicit stresses in `substeps` substeps; returns the largest |w| over the amplitude at the start
double w_mode_decay(int substeps, double dt_over_limit, int n, double zig, double* expected) {
  const Grid2D g = Grid2D::uniform(4, 40, 0.2, 0.2);
  const double nu = 1e-3, dz = 0.2 / 40, h = 0.2;
  Column c(g, nu * 1000.0);
  for (int k = 1; k < g.nz(); ++k)
    for (int i = 0; i < g.nx(); ++i) c.w[g.face_z(i, k)] = std::sin(kPi * k * dz / h) + (k % 2 ? zig : -zig);
  MomentumTerms t;
  t.convection = false;
  t.viscous_substeps = substeps;
  MomentumBoundary bc;
  bc.top_open = false;
  std::vector<double> cm, us, ws;
  MomentumScratch s;
  const double dt = dt_over_limit * viscous_stable_dt(g, c.fields(), cm, false);
  for (int step = 0; step < n; ++step) {
    momentum_explicit(g, c.fields(), t, bc, dt, us, ws, s);
    c.w = ws;
  }
  const double lambda = 2.0 * nu * 4.0 / (dz * dz) * std::pow(std::sin(kPi * dz / (2.0 * h)), 2);
  *expected = std::exp(-lambda * dt * n);
  double m = 0.0;
  for (double v : c.w) m = std::max(m, std::abs(v));
  return m;
}

TEST(ViscousSubsteps, ModeDecaysAtTheAnalyticRateAtEightTimesTheLimit) {
  // the explicit stresses at 8 x their limit in 8 substeps: after 40 steps the mode's amplitude is
  // within 1 % of exp(-lambda t) (0.32 here); the same steps without substeps blow a zigzag of 1e-6 up
  double expected = 0.0;
  const double sub = w_mode_decay(8, 8.0, 40, 0.0, &expected);
  std::printf("[ info     ] amplitude %.6f after 40 steps of 8 limits in 8 substeps, exact %.6f\n", sub, expected);
  EXPECT_NEAR(sub, expected, 0.01 * expected);
  EXPECT_LT(expected, 0.9);  // the mode did decay
  EXPECT_GT(w_mode_decay(1, 8.0, 40, 1e-6, &expected), 10.0);
}

TEST(ViscousSubsteps, FlowStepLimitIsTheSubstepsTimesTheExplicitLimit) {
  // a turbulent-like water column (nu = 1e-3 m^2/s): the reported viscous limit is viscous_substeps
  // times the explicit bound; 1 gives the bound itself; out of [1, 64] is refused naming the field
  const Grid2D g = Grid2D::uniform(10, 20, 0.25, 0.1);
  FlowParams p = test::pinned_flow_params();
  EXPECT_EQ(p.viscous_substeps, 8);
  p.flags = kFlowViscosity | kFlowGravity;
  p.medium.nu_water = 1e-3;
  VOFGrid f8(g, p);
  p.viscous_substeps = 1;
  VOFGrid f1(g, p);
  EXPECT_DOUBLE_EQ(f8.stable_dt_terms().viscous, 8.0 * f1.stable_dt_terms().viscous);
  for (int bad : {0, 65, -3}) {
    p.viscous_substeps = bad;
    try {
      p.validate();
      ADD_FAILURE() << bad;
    } catch (const std::invalid_argument& e) {
      EXPECT_NE(std::string(e.what()).find("viscous_substeps = " + std::to_string(bad)), std::string::npos);
      EXPECT_NE(std::string(e.what()).find("[1, 64]"), std::string::npos);
    }
  }
}

TEST(ImplicitViscosity, FlowParamsSelectTheSchemeAndTheStepLimit) {
  // the same laminar no-slip water column under both schemes: explicit limit ~ dz^2 / (4 nu) is the
  // smaller; default is the implicit vertical scheme
  const Grid2D g = Grid2D::uniform(10, 20, 0.25, 0.1);
  FlowParams p = test::pinned_flow_params();
  EXPECT_EQ(p.viscous_scheme, ViscousScheme::kImplicitVertical);
  p.flags = kFlowViscosity | kFlowGravity;
  p.walls = WallCondition::kNoSlip;
  p.medium.nu_water = 1e-3;
  VOFGrid fi(g, p);
  p.viscous_scheme = ViscousScheme::kExplicit;
  VOFGrid fe(g, p);
  EXPECT_GT(fi.stable_dt_terms().viscous, 3.0 * fe.stable_dt_terms().viscous);
}

TEST(CornerViscosity, EddyPartByHarmonicMeanKeepsWaterTurbulenceOffTheAirFaces) {
  // water (rho 1000, nu_t 1e-2 m^2/s) in the lower half, air (rho 1.2, no eddy viscosity) above: with
  // arithmetic corners an air face next to the water carries half the water's eddy viscosity over air
  // density; with the eddy part by harmonic mean those corners take molecular viscosity only
  const Grid2D g = Grid2D::uniform(8, 10, 0.2, 0.1);
  Column c(g, 0.0);
  std::vector<double> eddy(g.ncell(), 0.0);
  for (int k = 0; k < g.nz(); ++k)
    for (int i = 0; i < g.nx(); ++i) {
      const int cc = g.cell(i, k);
      const bool water = k < g.nz() / 2;
      c.mu[cc] = water ? 1e-3 + 1000.0 * 1e-2 : 1.8e-5;
      eddy[cc] = water ? 1000.0 * 1e-2 : 0.0;
    }
  for (int k = 0; k < g.nz(); ++k)
    for (int i = 0; i <= g.nx(); ++i) c.rx[g.face_x(i, k)] = k < g.nz() / 2 ? 1000.0 : 1.2;
  for (int k = 0; k <= g.nz(); ++k)
    for (int i = 0; i < g.nx(); ++i) c.rz[g.face_z(i, k)] = k < g.nz() / 2 ? 1000.0 : (k == g.nz() / 2 ? 500.6 : 1.2);
  MomentumFields fa = c.fields(), fh = c.fields();
  fh.cell_mu_eddy = eddy.data();
  std::vector<double> cm;
  const double da = viscous_stable_dt(g, fa, cm, true), dh = viscous_stable_dt(g, fh, cm, true);
  EXPECT_GT(dh, 100.0 * da);
  // inside the water the corner takes the full eddy viscosity (harmonic mean of equal values)
  MomentumScratch s;
  MomentumTerms t;
  t.convection = false;
  std::vector<double> us, ws;
  momentum_explicit(g, fh, t, MomentumBoundary{}, 1e-6, us, ws, s);
  EXPECT_NEAR(s.corner_mu[2 + (g.nx() + 1) * 2], 1e-3 + 10.0, 1e-12);
  // a corner touching an air cell: the molecular mean only ((2 x 1e-3 + 2 x 1.8e-5) / 4)
  EXPECT_NEAR(s.corner_mu[2 + (g.nx() + 1) * (g.nz() / 2)], 0.5 * (1e-3 + 1.8e-5), 1e-15);
  // laminar (no eddy part anywhere): the same bound as the arithmetic mean, to the bit
  std::vector<double> zero(g.ncell(), 0.0);
  fh.cell_mu_eddy = zero.data();
  EXPECT_EQ(viscous_stable_dt(g, fh, cm, true), viscous_stable_dt(g, fa, cm, true));
}

TEST(ImplicitViscosity, RowWiseTridiagonalSolveMatchesTheSingleColumnSolveBitForBit) {
  // columns [1, 6) of a row-major block with stride 7 (columns 0 and 6 untouched), diagonally dominant
  // random-like rows, some decoupled (a = c = 0) as closed faces make them
  const int m = 9, stride = 7, i0 = 1, i1 = 6;
  std::vector<double> a(m * stride), b(m * stride), c(m * stride), d(m * stride);
  for (int k = 0; k < m; ++k)
    for (int i = 0; i < stride; ++i) {
      const int j = i + stride * k;
      const double s = std::sin(1.3 * j + 0.7), t = std::cos(2.1 * j);
      a[j] = k > 0 && (i + k) % 4 ? -0.4 - 0.3 * s * s : 0.0;
      c[j] = k + 1 < m && (i + 2 * k) % 5 ? -0.5 - 0.2 * t * t : 0.0;
      b[j] = 1.0 - a[j] - c[j] + 0.1 * std::abs(s);
      d[j] = 3.0 * s - t;
    }
  const std::vector<double> b0 = b, d0 = d;
  solve_tridiagonal_rows(m, i0, i1, stride, a.data(), b.data(), c.data(), d.data());
  for (int i = 0; i < stride; ++i) {
    std::vector<double> ac(m), bc(m), cc(m), dc(m);
    for (int k = 0; k < m; ++k) {
      const int j = i + stride * k;
      ac[k] = a[j], bc[k] = b0[j], cc[k] = c[j], dc[k] = d0[j];
    }
    if (i >= i0 && i < i1) solve_tridiagonal(m, ac.data(), bc.data(), cc.data(), dc.data());
    for (int k = 0; k < m; ++k) EXPECT_EQ(d[i + stride * k], dc[k]) << "column " << i << " row " << k;
  }
}

namespace {

// the corner viscosity and the viscous step limit written face by face, as plainly as they read: the
// reference of the row-wise kernels (momentum.cpp), which must give the same bits
double reference_corner(const Grid2D& g, const double* mu, const double* eddy, int ii, int kk) {
  const int nx = g.nx(), nz = g.nz();
  const int i0 = std::max(ii - 1, 0), i1 = std::min(ii, nx - 1), k0 = std::max(kk - 1, 0), k1 = std::min(kk, nz - 1);
  const int c[4] = {i0 + nx * k0, i1 + nx * k0, i0 + nx * k1, i1 + nx * k1};
  const double mean = 0.25 * (mu[c[0]] + mu[c[1]] + mu[c[2]] + mu[c[3]]);
  if (!eddy) return mean;
  const double emean = 0.25 * (eddy[c[0]] + eddy[c[1]] + eddy[c[2]] + eddy[c[3]]);
  bool all = true;
  double inv = 0.0;
  for (int q : c) {
    all = all && eddy[q] > 0.0;
    inv += eddy[q] > 0.0 ? 1.0 / eddy[q] : 0.0;
  }
  return mean - emean + (all ? 4.0 / inv : 0.0);
}

double reference_viscous_limit(const Grid2D& g, const MomentumFields& f, bool implicit, ViscousBound bound, int* cell) {
  const int nx = g.nx(), nz = g.nz(), sx = nx + 1;
  const double dx = g.dx(), zf = implicit ? 0.0 : 1.0;
  const bool energy = bound == ViscousBound::kEnergy;
  auto cm = [&](int ii, int kk) { return reference_corner(g, f.cell_mu, f.cell_mu_eddy, ii, kk); };
  double worst = 0.0;
  *cell = -1;
  for (int k = 0; k < nz; ++k)
    for (int i = 1; i < nx; ++i) {
      if (f.face_x_porosity[i + sx * k] <= 0.0) continue;
      const double dz = g.dz(k), ml = f.cell_mu[i - 1 + nx * k], mr = f.cell_mu[i + nx * k];
      const double mn = cm(i, k + 1), ms = cm(i, k);
      const double diag = 2.0 * (ml + mr) / (dx * dx) + zf * (mn + ms) / (dz * dz);
      const double cross = energy ? 0.0 : 2.0 * (mn + ms) / (dx * dz);  // the energy bound: none
      const double rate = (2.0 * diag + cross) / f.face_x_rho[i + sx * k];
      if (rate > worst) worst = rate, *cell = i + nx * k;
    }
  for (int k = 1; k < nz; ++k)
    for (int i = 0; i < nx; ++i) {
      if (f.face_z_porosity[i + nx * k] <= 0.0) continue;
      const double dzc = g.z_center(k) - g.z_center(k - 1), hz = std::min(g.dz(k), g.dz(k - 1));
      const double mb = f.cell_mu[i + nx * (k - 1)], mt = f.cell_mu[i + nx * k], me = cm(i + 1, k), mw = cm(i, k);
      // the energy bound: w's x-diffusion doubled, no cross terms
      const double diag = zf * 2.0 * (mb + mt) / (dzc * hz) + (energy ? 2.0 : 1.0) * (me + mw) / (dx * dx);
      const double cross = energy ? 0.0 : 2.0 * (me + mw) / (dx * hz);
      const double rate = (2.0 * diag + cross) / f.face_z_rho[i + nx * k];
      if (rate > worst) worst = rate, *cell = i + nx * k;
    }
  return worst > 0.0 ? 2.0 / worst : std::numeric_limits<double>::infinity();
}

}  // namespace

TEST(ViscousLimit, RowWiseKernelsMatchTheFaceByFaceReferenceBitForBit) {
  // a graded grid, random viscosities with an eddy part (some cells without), densities and closed faces
  const Grid2D g = Grid2D::graded(13, 0.325, 0.11, 0.01, 0.004, 0.02);
  Column c(g, 1e-3);
  unsigned seed = 11;
  auto unit = [&seed] { return (seed = seed * 1103515245u + 12345u) / 4294967296.0; };
  std::vector<double> eddy(g.ncell());
  for (int cc = 0; cc < g.ncell(); ++cc) {
    eddy[cc] = unit() < 0.2 ? 0.0 : 10.0 * unit();
    c.mu[cc] = 1e-3 * (0.01 + unit()) + eddy[cc];
  }
  for (double& r : c.rx) r = 1.2 + 1000.0 * unit();
  for (double& r : c.rz) r = 1.2 + 1000.0 * unit();
  for (double& n : c.nx_) n = unit() < 0.1 ? 0.0 : unit();
  for (double& n : c.nz_) n = unit() < 0.1 ? 0.0 : unit();
  const std::pair<bool, ViscousBound> bounds[] = {
      {false, ViscousBound::kRowSum}, {true, ViscousBound::kRowSum}, {true, ViscousBound::kEnergy}};
  for (auto [implicit, bound] : bounds)
    for (bool with_eddy : {false, true}) {
      MomentumFields f = c.fields();
      f.cell_mu_eddy = with_eddy ? eddy.data() : nullptr;
      std::vector<double> cm;
      int cell = -2, ref_cell = -3;
      const double dt = viscous_stable_dt(g, f, cm, implicit, bound, &cell);
      EXPECT_EQ(dt, reference_viscous_limit(g, f, implicit, bound, &ref_cell))
          << implicit << static_cast<int>(bound) << with_eddy;
      EXPECT_EQ(cell, ref_cell);
      for (int kk = 0; kk <= g.nz(); ++kk)
        for (int ii = 0; ii <= g.nx(); ++ii)
          ASSERT_EQ(cm[ii + (g.nx() + 1) * kk], reference_corner(g, f.cell_mu, f.cell_mu_eddy, ii, kk)) << ii << " " << kk;
    }
}

// the rows implicit too (ViscousScheme::kImplicit): only the cross terms explicit

TEST(ImplicitRows, OneStepIsBackwardEulerOfTheHorizontalModeOfU) {
  // u = sin(pi x / L) on the x-faces between two walls (u = 0 there), uniform in z, w = 0: an eigenvector
  // of d/dx(2 nu d/dx) with lambda = 2 nu (4 / dx^2) sin^2(pi dx / (2 L)), and no cross term, no vertical
  // diffusion; the whole step at 100 x the split scheme's limit divides it by 1 + dt lambda
  const Grid2D g = Grid2D::uniform(20, 4, 0.2, 0.1);
  const double nu = 2e-3, dx = 0.01, l = 0.2;
  const double lambda = 2.0 * nu * 4.0 / (dx * dx) * std::pow(std::sin(kPi * dx / (2.0 * l)), 2);
  Column c(g, nu * 1000.0);
  for (int k = 0; k < g.nz(); ++k)
    for (int i = 0; i <= g.nx(); ++i) c.u[g.face_x(i, k)] = std::sin(kPi * i * dx / l);
  MomentumTerms t;
  t.convection = false;
  t.implicit_vertical = true;
  t.implicit_horizontal = true;
  MomentumBoundary bc;
  bc.top_open = false;
  std::vector<double> us, ws, cm;
  MomentumScratch s;
  const double dt = 100.0 * viscous_stable_dt(g, c.fields(), cm, true, ViscousBound::kEnergy);
  momentum_explicit(g, c.fields(), t, bc, dt, us, ws, s);
  for (int k = 0; k < g.nz(); ++k)
    for (int i = 1; i < g.nx(); ++i) {
      const int j = g.face_x(i, k);
      EXPECT_NEAR(us[j], c.u[j] / (1.0 + dt * lambda), 1e-12) << i << " " << k;
    }
  for (double w : ws) EXPECT_NEAR(w, 0.0, 1e-15);  // the new u's round-off in the cross term
}

// one row solve of w (implicit_row_diffusion) with uniform corner viscosity mu [Pa s]: returns w*
std::vector<double> row_solve_w(const Column& c, const MomentumBoundary& bc, double mu, double dt) {
  MomentumScratch s;
  s.corner_mu.assign(static_cast<std::size_t>(c.g.nx() + 1) * (c.g.nz() + 1), mu);
  std::vector<double> us(c.u), ws(c.w);
  implicit_row_diffusion(c.g, c.fields(), bc, dt, c.u.data(), c.w.data(), us, ws, s);
  return ws;
}

TEST(ImplicitRows, RowSolveOfWIsBackwardEulerWithStressFreeOrGhostEnds) {
  // slip ends (no stress): w = cos(pi x / L) at the cell centres is an eigenvector of d/dx(nu d/dx) with
  // lambda = nu (4 / dx^2) sin^2(pi dx / (2 L)); no-slip ends on a row of one cell: the two ghosts -w make
  // the rate 4 nu / dx^2, the explicit scheme's too (checked at a small step)
  const double nu = 2e-3, dx = 0.01, l = 0.2;
  const Grid2D g = Grid2D::uniform(20, 4, 0.2, 0.1);
  Column c(g, nu * 1000.0);
  for (int k = 1; k < g.nz(); ++k)
    for (int i = 0; i < g.nx(); ++i) c.w[g.face_z(i, k)] = std::cos(kPi * (i + 0.5) * dx / l);
  MomentumBoundary bc;
  bc.top_open = false;
  const double lambda = nu * 4.0 / (dx * dx) * std::pow(std::sin(kPi * dx / (2.0 * l)), 2), dt = 30.0 / lambda;
  const std::vector<double> ws = row_solve_w(c, bc, nu * 1000.0, dt);
  for (int k = 1; k < g.nz(); ++k)
    for (int i = 0; i < g.nx(); ++i) {
      const int j = g.face_z(i, k);
      EXPECT_NEAR(ws[j], c.w[j] / (1.0 + dt * lambda), 1e-12) << i << " " << k;
    }
  const Grid2D one = Grid2D::uniform(1, 4, 0.01, 0.04);
  Column d(one, nu * 1000.0);
  for (int k = 1; k < one.nz(); ++k) d.w[one.face_z(0, k)] = 1.0;  // bed and lid 0
  bc.no_slip = true;
  const double rate = 4.0 * nu / (dx * dx), big = 30.0 / rate, small = 1e-4 / rate;
  EXPECT_NEAR(row_solve_w(d, bc, nu * 1000.0, big)[one.face_z(0, 2)], 1.0 / (1.0 + big * rate), 1e-12);
  MomentumTerms t;
  t.convection = false;
  std::vector<double> us, we;
  MomentumScratch s;
  momentum_explicit(one, d.fields(), t, bc, small, us, we, s);
  EXPECT_NEAR((we[one.face_z(0, 2)] - 1.0) / small, -rate, 1e-9 * rate);
}

TEST(ImplicitRows, WholeStepStableFarAboveTheSplitSchemesLimit) {
  // the 96 fields of the split scheme's test (four grids, eddy-viscosity contrasts 1-1000, with and
  // without an air layer, three seeds), no-slip and slip walls, at 1, 3, 100 and 1e4 times the split
  // scheme's energy limit: the step's spectral radius stays <= 1 (measured: 0.999644, set by the slowest
  // mode; 0.2785 at 1e4). Its norm in the kinetic energy, ||R^1/2 M R^-1/2||_2, stays <= 1 up to 3 x
  // (0.9989), and then grows with the step (1.63 at 10 x, 5.90 at 100 x, 50.8 at 1e4 x): one step can
  // turn a w-mode into a larger u-mode, the cross term being explicit in u, which later steps damp.
  // The split scheme's own norm at its limit is 1.94. The split scheme at 100 x grows (first field)
  const Grid2D grids[] = {Grid2D::graded(6, 0.15, 0.06, 0.01, 0.005, 0.02), Grid2D::uniform(8, 10, 0.2, 0.1),
                          Grid2D::uniform(8, 8, 0.08, 0.08), Grid2D::uniform(6, 12, 0.15, 0.06)};
  for (double factor : {1.0, 3.0, 100.0, 1e4}) {
    double worst_radius = 0.0, worst_norm = 0.0;
    for (bool no_slip : {true, false})
      for (const Grid2D& g : grids)
        for (double contrast : {1.0001, 10.0, 100.0, 1000.0})
          for (bool air : {false, true})
            for (unsigned seed = 1; seed <= 3; ++seed) {
              Column c(g, 1e-3);
              const std::vector<double> eddy = set_viscosity(c, contrast, air, 7919u * seed);
              double limit = 0.0, norm = 0.0;
              const double r = whole_step_radius(c, eddy, factor, &limit, 1, ViscousScheme::kImplicit,
                                                 ViscousBound::kEnergy, no_slip, &norm);
              worst_radius = std::max(worst_radius, r), worst_norm = std::max(worst_norm, norm);
              EXPECT_LE(r, 1.0 + 1e-9) << factor << " " << g.nx() << "x" << g.nz() << " contrast " << contrast;
              if (factor <= 3.0) {
                EXPECT_LE(norm, 1.0 + 1e-9) << factor << " " << g.nx() << "x" << g.nz();
              }
            }
    std::printf("[ info     ] rows implicit at %g x the split limit, 192 fields: largest spectral radius %.6f, "
                "energy norm %.4f\n", factor, worst_radius, worst_norm);
  }
  Column c(grids[0], 1e-3);
  const std::vector<double> eddy = set_viscosity(c, 100.0, true, 7919u);
  double limit = 0.0;
  EXPECT_GT(whole_step_radius(c, eddy, 100.0, &limit, 1, ViscousScheme::kImplicitVertical, ViscousBound::kEnergy), 1.0);
}

TEST(ImplicitRows, FlowHasNoViscousStepLimitAndRefusesUnknownSchemes) {
  const Grid2D g = Grid2D::uniform(10, 20, 0.25, 0.1);
  FlowParams p = test::pinned_flow_params();
  p.flags = kFlowViscosity | kFlowGravity;
  p.walls = WallCondition::kNoSlip;
  p.medium.nu_water = 1e-3;
  p.viscous_scheme = ViscousScheme::kImplicit;
  VOFGrid f(g, p);
  EXPECT_TRUE(std::isinf(f.stable_dt_terms().viscous));
  p.viscous_scheme = static_cast<ViscousScheme>(4);
  try {
    p.validate();
    FAIL() << "viscous_scheme 4 accepted";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("viscous_scheme = 4"), std::string::npos) << e.what();
  }
}
