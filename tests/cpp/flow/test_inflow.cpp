#include <gtest/gtest.h>

#include <algorithm>
#include <vector>

#include "vofdem/flow/inflow.h"
#include "vofdem/flow/vof_grid.h"
#include "common/pinned_params.h"

using namespace vofdem;

namespace {

std::vector<double> inlet(InletProfile profile, double q, const std::vector<double>& dz, const std::vector<double>& F,
                          const std::vector<double>& porosity) {
  std::vector<double> u;
  inlet_velocities(q, dz, F.data(), porosity.data(), 1, profile, u);
  return u;
}

double discharge(const std::vector<double>& u, const std::vector<double>& dz) {
  double s = 0.0;
  for (size_t k = 0; k < u.size(); ++k) s += u[k] * dz[k];
  return s;
}

const std::vector<double> kDz(5, 0.01);
const std::vector<double> kOpen(5, 1.0);

}  // namespace

TEST(Inflow, ASharpColumnTakesTheSameProfileEitherWay) {
  // h = 0.025 m, q / h = 2 m/s: full rows at 2 m/s, the half row at 1, the dry rows none
  const std::vector<double> F = {1, 1, 0.5, 0, 0};
  for (InletProfile p : {InletProfile::kEquivalentDepth, InletProfile::kWaterFraction}) {
    const std::vector<double> u = inlet(p, 0.05, kDz, F, kOpen);
    const std::vector<double> expected = {2, 2, 1, 0, 0};
    for (int k = 0; k < 5; ++k) EXPECT_NEAR(u[k], expected[k], 1e-12) << k;
  }
}

TEST(Inflow, ATraceAboveTheLevelTakesInflowOnlyByWaterFraction) {
  // a trace F = 0.1 in the top row: h = 0.026 m, q / h = 1.923077 m/s
  const std::vector<double> F = {1, 1, 0.5, 0, 0.1};
  const double qh = 0.05 / 0.026;
  const std::vector<double> by_fraction = inlet(InletProfile::kWaterFraction, 0.05, kDz, F, kOpen);
  EXPECT_NEAR(by_fraction[4], 0.1 * qh, 1e-12);  // water of fraction 1 enters the trace's row
  EXPECT_NEAR(by_fraction[2], 0.5 * qh, 1e-12);
  const std::vector<double> by_depth = inlet(InletProfile::kEquivalentDepth, 0.05, kDz, F, kOpen);
  const std::vector<double> expected = {qh, qh, 0.6 * qh, 0, 0};  // the level is 0.6 into row 2
  for (int k = 0; k < 5; ++k) EXPECT_NEAR(by_depth[k], expected[k], 1e-12) << k;
  EXPECT_NEAR(discharge(by_fraction, kDz), 0.05, 1e-15);
  EXPECT_NEAR(discharge(by_depth, kDz), 0.05, 1e-15);
}

TEST(Inflow, SolidRowsAreSkippedAndADryInletFeedsItsLowestOpenRow) {
  // a solid bottom row: the level counts the open rows only, h = 0.015 m
  const std::vector<double> porosity = {0, 1, 1, 1, 1};
  const std::vector<double> u = inlet(InletProfile::kEquivalentDepth, 0.03, kDz, {1, 1, 0.5, 0, 0}, porosity);
  const std::vector<double> expected = {0, 2, 1, 0, 0};
  for (int k = 0; k < 5; ++k) EXPECT_NEAR(u[k], expected[k], 1e-12) << k;
  for (InletProfile p : {InletProfile::kEquivalentDepth, InletProfile::kWaterFraction}) {
    const std::vector<double> dry = inlet(p, 0.03, kDz, {0, 0, 0, 0, 0}, porosity);
    EXPECT_NEAR(dry[1], 3.0, 1e-12);  // q / dz
    EXPECT_NEAR(discharge(dry, kDz), 0.03, 1e-15);
  }
}

namespace {

// the most water in the inlet column above z = 0.2 m over 0.1 s of inflow into a flume 0.1 m deep whose
// inlet column holds a trace F = 0.01 from 0.2 to 0.3 m (0.1 cells of water at the start)
double most_water_above(InletProfile profile) {
  const Grid2D g = Grid2D::uniform(40, 30, 0.8, 0.3);
  FlowParams p = test::pinned_flow_params();
  p.inlet = InletBoundary::kDischarge;
  p.inlet_profile = profile;
  p.outlet = OutletBoundary::kFreeOverfall;
  VOFGrid flow(g, p);
  flow.fill_water_below(0.1);
  for (int k = 20; k < g.nz(); ++k) flow.cell_F[g.cell(0, k)] = 0.01;
  flow.set_discharge(DischargeTable::constant(0.03 * p.flume_width));  // q = 0.03 m^2/s
  double most = 0.0;
  for (int n = 1; n <= 10; ++n) {
    flow.advance(0.01 * n - flow.time());
    double v = 0.0;
    for (int k = 20; k < g.nz(); ++k) v += flow.cell_F[g.cell(0, k)];
    most = std::max(most, v);
  }
  return most;
}

}  // namespace

TEST(Inflow, ATraceAboveTheInletLevelDoesNotGrowByItself) {
  // fed by fraction the trace grows at up to q / (h dx) = 0.03 / (0.1 x 0.02) = 15 /s less what it loses
  // by falling (x 1.78 by 0.1 s, measured); fed below the level it only falls
  EXPECT_LE(most_water_above(InletProfile::kEquivalentDepth), 0.1);
  EXPECT_GT(most_water_above(InletProfile::kWaterFraction), 0.15);
}
