// Time integration of the explicit momentum terms (FlowParams::time_scheme) and the step-limit record
// of the Coupler: the order of forward Euler and Adams-Bashforth 2 measured on a smooth vortex, the
// history in the checkpoint, and the limits counted per term.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <vector>

#include "common/coupler_scenes.h"
#include "common/pinned_params.h"

using namespace vofdem;
using namespace vofdem::test;

namespace {

// a closed unit box, one phase, convection only, started from the discretely divergence-free vortex of
// the stream function psi = sin^2(pi x) sin^2(pi z) / pi; returns the x-velocities after T [s]
std::vector<double> vortex(MomentumTimeScheme scheme, int nsteps, double T = 0.5, int n = 16) {
  const Grid2D g = Grid2D::uniform(n, n, 1.0, 1.0);
  FlowParams p = test::pinned_flow_params();
  p.flags = kFlowConvection;
  p.top = TopBoundary::kWall;
  p.time_scheme = scheme;
  p.pressure_tol = 1e-12;
  VOFGrid f(g, p);
  const double h = 1.0 / n;
  auto psi = [](double x, double z) { return std::pow(std::sin(M_PI * x) * std::sin(M_PI * z), 2) / M_PI; };
  for (int k = 0; k < n; ++k)
    for (int i = 0; i <= n; ++i) f.face_u[g.face_x(i, k)] = (psi(i * h, (k + 1) * h) - psi(i * h, k * h)) / h;
  for (int k = 0; k <= n; ++k)
    for (int i = 0; i < n; ++i) f.face_w[g.face_z(i, k)] = -(psi((i + 1) * h, k * h) - psi(i * h, k * h)) / h;
  for (int s = 0; s < nsteps; ++s) f.step(T / nsteps);
  return f.face_u;
}

double max_gap(const std::vector<double>& a, const std::vector<double>& b) {
  double m = 0.0;
  for (std::size_t j = 0; j < a.size(); ++j) m = std::max(m, std::abs(a[j] - b[j]));
  return m;
}

}  // namespace

TEST(VOFTimeScheme, AdamsBashforthIsSecondOrderAndEulerFirst) {
  for (MomentumTimeScheme s : {MomentumTimeScheme::kEuler, MomentumTimeScheme::kAdamsBashforth2}) {
    const std::vector<double> ref = vortex(s, 400);
    const double e1 = max_gap(vortex(s, 25), ref), e2 = max_gap(vortex(s, 50), ref), e3 = max_gap(vortex(s, 100), ref);
    const double order = std::log2(std::sqrt(e1 / e2 * e2 / e3));
    std::printf("[ info     ] %s: errors %.3g %.3g %.3g at 25, 50, 100 steps: order %.2f\n",
                s == MomentumTimeScheme::kEuler ? "Euler" : "AB2", e1, e2, e3, order);
    if (s == MomentumTimeScheme::kEuler) {
      EXPECT_NEAR(order, 1.0, 0.25);
    } else {
      EXPECT_NEAR(order, 2.0, 0.25);
    }
  }
}

TEST(VOFTimeScheme, FirstStepAndClearedHistoryAreEuler) {
  // without history the AB2 step is the Euler step, bit for bit
  const std::vector<double> a = vortex(MomentumTimeScheme::kEuler, 1, 0.02),
                            b = vortex(MomentumTimeScheme::kAdamsBashforth2, 1, 0.02);
  EXPECT_EQ(a, b);
  const Grid2D g = Grid2D::uniform(4, 4, 1.0, 1.0);
  VOFGrid f(g, test::pinned_flow_params());
  EXPECT_EQ(f.prev_dt(), 0.0);
  f.fill_water_below(0.5);
  f.step(1e-3);
  EXPECT_EQ(f.prev_dt(), 1e-3);
  EXPECT_EQ(f.face_u_prev.size(), f.face_u.size());
  f.clear_step_history();
  EXPECT_EQ(f.prev_dt(), 0.0);
  EXPECT_THROW(f.set_prev_dt(-1.0), std::invalid_argument);
}

TEST(Coupler, StepLimitsCountEveryStepAndNameTheStone) {
  // a stone falling through a still tank: at first the fluid's terms bind, then the stone's own limit
  Scene s = tank(0.2, 0.5, 0.01, 0.45, {0.1, 0.35}, 0.024, kCoupleOneWay);
  const long long n = s.sim->advance(0.3);
  long long sum = 0;
  for (const auto& kv : s.sim->step_limits()) sum += kv.second;
  EXPECT_EQ(sum, n);
  ASSERT_TRUE(s.sim->step_limits().count("stone_cfl"));
  // the stone's cell is where that limit bound
  const std::vector<long long>& cells = s.sim->step_limit_cells().at("stone_cfl");
  long long in_column = 0;
  const int i = s.fluid->grid().locate_x(0.1);
  for (int k = 0; k < s.fluid->grid().nz(); ++k) in_column += cells[s.fluid->grid().cell(i, k)];
  EXPECT_EQ(in_column, s.sim->step_limits().at("stone_cfl"));
  s.sim->clear_step_limits();
  EXPECT_TRUE(s.sim->step_limits().empty());
}
