#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include "vofdem/porous_resistance.h"
#include "vofdem/vof_grid.h"

using namespace vofdem;

namespace {

double max_abs(const std::vector<double>& a) {
  double m = 0.0;
  for (double v : a) m = std::max(m, std::abs(v));
  return m;
}

}  // namespace

class VOFGridBySolver : public ::testing::TestWithParam<PressureSolverKind> {};
INSTANTIATE_TEST_SUITE_P(Solvers, VOFGridBySolver,
                         ::testing::Values(PressureSolverKind::kEigenDirect, PressureSolverKind::kMultigridCG));

TEST_P(VOFGridBySolver, StillWaterWithPorousBlockStaysStill) {
  // 0.4 m x 0.3 m tank, water 0.2 m deep, a porous block (n = 0.4, D = 4.8 cm) on the bed
  const Grid2D g = Grid2D::uniform(20, 15, 0.4, 0.3);
  FlowParams p;
  p.pressure_solver = GetParam();
  VOFGrid flow(g, p);
  flow.fill_water_below(0.2);
  flow.set_porosity_box(0.1, 0.25, 0.0, 0.12, 0.4, 0.048);
  flow.set_hydrostatic_pressure();
  const double v0 = flow.water_volume();
  flow.advance(2.0);
  // tolerance of the issue: spurious velocities below 1e-6 m/s after 2 s
  EXPECT_LT(max_abs(flow.face_u), 1e-6);
  EXPECT_LT(max_abs(flow.face_w), 1e-6);
  EXPECT_NEAR(flow.water_volume(), v0, 1e-12 * v0);
  EXPECT_NEAR(flow.time(), 2.0, 1e-12);
}

TEST_P(VOFGridBySolver, SteadyFlowThroughPorousBlockFollowsClosureLaw) {
  // single-phase channel 1 m x 0.1 m under a slip lid; a porous block fills x in [0.3, 0.7]
  const Grid2D g = Grid2D::uniform(40, 5, 1.0, 0.1);
  FlowParams p;
  p.pressure_solver = GetParam();
  p.flags = kFlowPorousResistance | kFlowViscosity | kFlowConvection;  // no free surface, no gravity
  p.inlet = InletBoundary::kDischarge;
  p.outlet = OutletBoundary::kFreeOverfall;
  p.top = TopBoundary::kWall;
  p.flume_width = 0.3;
  VOFGrid flow(g, p);
  const double n = 0.4, d = 0.02, Q = 0.003;
  flow.set_porosity_box(0.3, 0.7, 0.0, 0.1, n, d);
  flow.set_discharge(DischargeTable::constant(Q));
  flow.advance(0.5);
  const double u = Q / p.flume_width / 0.1;  // superficial velocity [m/s]
  const PorousCoefficients c = porous_coefficients(n, d, p.nu_water, p.k1, p.k2);
  const double expected = -p.rho_water * u * (c.linear + c.quadratic * u);
  // interior of the block, away from its ends (i = 14..25 hold centres 0.3625..0.6375 m)
  for (int k = 0; k < g.nz(); ++k) {
    const double dpdx = (flow.cell_p[g.cell(25, k)] - flow.cell_p[g.cell(14, k)]) / (11 * g.dx());
    EXPECT_NEAR(dpdx, expected, 0.01 * std::abs(expected)) << "row " << k;
    EXPECT_NEAR(flow.face_u[g.face_x(20, k)], u, 1e-9);
  }
}

TEST_P(VOFGridBySolver, SloshingInAClosedBoxConservesWater) {
  // a tilted free surface sloshes in a 0.3 m x 0.2 m box; water volume conserved to round-off
  const Grid2D g = Grid2D::uniform(24, 16, 0.3, 0.2);
  FlowParams p;
  p.pressure_solver = GetParam();
  VOFGrid flow(g, p);
  for (int i = 0; i < g.nx(); ++i) {
    const double level = 0.08 + 0.04 * (g.x_center(i) / 0.3 - 0.5);
    for (int k = 0; k < g.nz(); ++k)
      flow.cell_F[g.cell(i, k)] = std::clamp((level - g.z_face(k)) / g.dz(k), 0.0, 1.0);
  }
  flow.set_porosity_box(0.1, 0.2, 0.0, 0.05, 0.45, 0.03);
  const double v0 = flow.water_volume();
  flow.advance(0.5);
  EXPECT_GT(max_abs(flow.face_u), 1e-3);  // it does move
  EXPECT_NEAR(flow.water_volume(), v0, 1e-10 * v0);
  for (double f : flow.cell_F) {
    EXPECT_GE(f, -1e-9);
    EXPECT_LE(f, 1.0 + 1e-9);
  }
}

TEST(VOFGrid, NearlyClosedCellNextToFastFlowStaysBounded) {
  // water released from a column rushes past a cell of porosity 1e-6 on the bed
  const Grid2D g = Grid2D::uniform(30, 20, 0.6, 0.4);
  VOFGrid flow(g, FlowParams{});
  flow.fill_water_box(0.0, 0.2, 0.0, 0.2);
  flow.set_porosity_box(0.29, 0.31, 0.0, 0.02, 1e-6, 0.02);
  const double v0 = flow.water_volume();
  flow.advance(0.3);  // the front passes the cell at 0.1 s and has not reached the top by 0.3 s
  std::vector<double> U, W;
  flow.pore_velocity_at_cells(U, W);
  EXPECT_LT(max_abs(U), 5.0);  // bounded by the free-fall speed sqrt(2 g h) = 2.2 m/s with margin
  EXPECT_LT(max_abs(W), 5.0);
  EXPECT_NEAR(flow.water_volume(), v0, 1e-10 * v0);
  const int c = g.cell(g.locate_x(0.3), 0);
  EXPECT_EQ(flow.cell_porosity[c], 1e-6);
  EXPECT_LT(std::abs(U[c]), 5.0);
}

TEST(VOFGrid, PlungingJetIntoAPoolStaysBounded) {
  // an inflow at 0.3 m/s superficial over 2 cm falls over a step into a pool: bounded, water balance
  const Grid2D g = Grid2D::uniform(32, 20, 0.64, 0.4);
  FlowParams p;
  p.inlet = InletBoundary::kDischarge;
  p.flume_width = 0.3;
  VOFGrid flow(g, p);
  flow.set_porosity_box(0.0, 0.2, 0.0, 0.2, 0.0, 0.05);  // a solid step 0.2 m high
  flow.fill_water_below(0.1);                            // the pool
  flow.fill_water_box(0.0, 0.2, 0.2, 0.22);              // water on the step
  const double Q = 0.3 * 0.02 * p.flume_width;
  flow.set_discharge(DischargeTable::constant(Q));
  const double v0 = flow.water_volume();
  flow.advance(0.8);
  std::vector<double> U, W;
  flow.pore_velocity_at_cells(U, W);
  EXPECT_LT(max_abs(U), 5.0);
  EXPECT_LT(max_abs(W), 5.0);
  // closed except the inlet and the open top (which the water never reaches): V = V0 + q t
  const double q = Q / p.flume_width;
  EXPECT_NEAR(flow.water_volume(), v0 + q * 0.8, 1e-6 * v0);
  EXPECT_NEAR(flow.water_volume(), v0 + flow.inlet_volume(), 1e-10 * v0);
}

TEST(VOFGrid, NaNIsCaughtWithStageCellAndTime) {
  const Grid2D g = Grid2D::uniform(10, 10, 0.1, 0.1);
  VOFGrid flow(g, FlowParams{});
  flow.fill_water_below(0.05);
  flow.advance(0.01);
  const double t = flow.time();
  const auto F = flow.cell_F;
  flow.face_u[g.face_x(3, 4)] = std::nan("");
  try {
    flow.step(1e-3);
    FAIL() << "no error";
  } catch (const std::runtime_error& e) {
    const std::string m = e.what();
    EXPECT_NE(m.find("stage"), std::string::npos) << m;
    EXPECT_NE(m.find("i="), std::string::npos) << m;
    EXPECT_NE(m.find("t = "), std::string::npos) << m;
  }
  // the state at the start of the failed step is kept
  EXPECT_EQ(flow.time(), t);
  EXPECT_TRUE(std::isnan(flow.face_u[g.face_x(3, 4)]));
  EXPECT_EQ(flow.cell_F, F);
}

TEST(VOFGrid, CflBreachIsRefused) {
  const Grid2D g = Grid2D::uniform(10, 10, 0.1, 0.1);
  VOFGrid flow(g, FlowParams{});
  flow.fill_water_below(0.05);
  flow.face_u[g.face_x(5, 2)] = 1.0;
  EXPECT_THROW(flow.step(0.05), std::runtime_error);
  EXPECT_EQ(flow.time(), 0.0);
  EXPECT_EQ(flow.face_u[g.face_x(5, 2)], 1.0);
}

TEST(VOFGrid, SwitchedOffEffectsAreNotEntered) {
  const Grid2D g = Grid2D::uniform(8, 8, 0.1, 0.1);
  FlowParams p;
  p.flags = kFlowGravity | kFlowViscosity;  // single phase, no resistance
  VOFGrid flow(g, p);
  flow.set_porosity_box(0.0, 0.05, 0.0, 0.05, 0.4, 0.01);
  for (int s = 0; s < 3; ++s) flow.step(1e-3);
  const StageProfile& prof = flow.profile();
  EXPECT_EQ(prof.calls()[prof.find("advect_vof")], 0);
  EXPECT_EQ(prof.calls()[prof.find("porous_resistance")], 0);
  EXPECT_EQ(prof.calls()[prof.find("turbulence")], 0);
  EXPECT_EQ(prof.calls()[prof.find("momentum")], 3);
  EXPECT_EQ(prof.calls()[prof.find("pressure")], 3);
  // no free surface: water everywhere, the hydrostatic state stays at rest
  EXPECT_EQ(flow.cell_F[0], 1.0);
  EXPECT_LT(max_abs(flow.face_w), 1e-9);
}

TEST(VOFGrid, BadParametersAreRefused) {
  const Grid2D g = Grid2D::uniform(4, 4, 0.1, 0.1);
  FlowParams p;
  p.cfl = 1.5;
  EXPECT_THROW(VOFGrid(g, p), std::invalid_argument);
  VOFGrid flow(g, FlowParams{});
  std::vector<double> n(g.ncell(), 1.2);
  EXPECT_THROW(flow.set_porosity(n), std::invalid_argument);
  EXPECT_THROW(flow.set_discharge(DischargeTable{{1.0, 0.5}, {0.0, 0.01}}), std::invalid_argument);
}

TEST(VOFGrid, DischargeRampOfThePaper) {
  const DischargeTable t = DischargeTable::ramp(0.010, 0.025, 0.0, 120.0);
  EXPECT_DOUBLE_EQ(t.at(-1.0), 0.010);
  EXPECT_DOUBLE_EQ(t.at(60.0), 0.0175);
  EXPECT_DOUBLE_EQ(t.at(200.0), 0.025);
}

TEST(VOFGrid, SmallDamBreakRunsAndIsDeterministic) {
  const Grid2D g = Grid2D::uniform(40, 15, 0.4, 0.15);
  auto run = [&]() {
    VOFGrid flow(g, FlowParams{});
    flow.fill_water_box(0.0, 0.05715, 0.0, 0.1143);
    const double v0 = flow.water_volume();
    flow.advance(0.15);
    EXPECT_NEAR(flow.water_volume(), v0, 1e-10 * v0);
    // the front has left the column: water in the cell at x = 0.1 m on the bed
    EXPECT_GT(flow.cell_F[g.cell(g.locate_x(0.1), 0)], 0.1);
    return flow.face_u;
  };
  EXPECT_EQ(run(), run());
}

TEST(VOFGrid, TurbulentOpenChannelRunsWithEddyViscosityInTheWater) {
  // 10 l/s per 0.3 m (q = 0.033 m^2/s) over a rough bed into a free overfall, k-epsilon on
  const Grid2D g = Grid2D::graded(30, 1.5, 0.2, 0.01, 0.005, 0.02);
  FlowParams p;
  p.flags |= kFlowTurbulence;
  p.inlet = InletBoundary::kDischarge;
  p.outlet = OutletBoundary::kFreeOverfall;
  p.turbulence.bed_roughness = 0.005;
  VOFGrid flow(g, p);
  flow.fill_water_below(0.06);
  flow.set_discharge(DischargeTable::constant(0.010));
  flow.advance(1.0);
  const StageProfile& prof = flow.profile();
  EXPECT_EQ(prof.calls()[prof.find("turbulence")], flow.step_count());
  double nut_water = 0.0, nut_air = 0.0;
  for (int c = 0; c < g.ncell(); ++c) {
    if (flow.cell_F[c] > 0.99) nut_water = std::max(nut_water, flow.cell_nut[c]);
    if (flow.cell_F[c] < 0.01) nut_air = std::max(nut_air, flow.cell_nut[c]);
  }
  EXPECT_GT(nut_water, 1e-6);  // above the molecular viscosity somewhere in the water
  EXPECT_EQ(nut_air, 0.0);     // the model holds no eddy viscosity in air
  std::vector<double> U, W;
  flow.pore_velocity_at_cells(U, W);
  EXPECT_LT(max_abs(U), 3.0);
  EXPECT_LT(max_abs(W), 3.0);
}
