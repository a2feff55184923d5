// Open end faces hold the still air outside in hydrostatic balance (open_end_pressure, projection.h);
// the water leaving carries its own momentum out implicitly and sets the step at half its Courant number.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <tuple>
#include <vector>

#include "vofdem/flow/momentum.h"
#include "vofdem/flow/projection.h"
#include "vofdem/flow/vof_grid.h"
#include "common/pinned_params.h"

using namespace vofdem;

namespace {

double max_abs_open(const std::vector<double>& a) {
  double m = 0.0;
  for (double v : a) m = std::max(m, std::abs(v));
  return m;
}

// a 0.4 m x 0.2 m box of air with an open right end and an open top
VOFGrid air_box(OutletBoundary outlet, double tailwater_level) {
  FlowParams p = test::pinned_flow_params();
  p.outlet = outlet;
  p.tailwater_level = tailwater_level;
  return VOFGrid(Grid2D::uniform(20, 10, 0.4, 0.2), p);
}

}  // namespace

TEST(VOFOpenEnd, StillAirStaysStillAtAFreeOverfall) {
  // with p = 0 over the whole end face the air in the last column would fall at about g
  VOFGrid flow = air_box(OutletBoundary::kFreeOverfall, 0.0);
  flow.set_hydrostatic_pressure();
  flow.advance(0.5);
  EXPECT_LT(max_abs_open(flow.face_u), 1e-6);
  EXPECT_LT(max_abs_open(flow.face_w), 1e-6);
}

TEST(VOFOpenEnd, StillWaterAtTheTailwaterLevelStaysStill) {
  // water 0.1 m deep, tailwater level 0.1 m: the end face is hydrostatic for both phases
  VOFGrid flow = air_box(OutletBoundary::kTailwater, 0.1);
  flow.fill_water_below(0.1);
  flow.set_hydrostatic_pressure();
  const double v0 = flow.water_volume();
  flow.advance(0.5);
  EXPECT_LT(max_abs_open(flow.face_u), 1e-6);
  EXPECT_LT(max_abs_open(flow.face_w), 1e-6);
  EXPECT_NEAR(flow.water_volume(), v0, 1e-9 * v0);
}

TEST(VOFOpenEnd, BoundaryBudgetAccountsForTheWaterLeavingAFreeOverfall) {
  // a pool draining over the free overfall while the inlet feeds it: the stored water changes by
  // exactly what the advection carried through the boundary faces
  FlowParams p = test::pinned_flow_params();
  p.inlet = InletBoundary::kDischarge;
  p.outlet = OutletBoundary::kFreeOverfall;
  p.flume_width = 0.5;
  VOFGrid flow(Grid2D::uniform(20, 10, 0.4, 0.2), p);
  flow.set_discharge(DischargeTable::constant(0.005));
  flow.fill_water_below(0.08);
  flow.set_hydrostatic_pressure();
  const double v0 = flow.water_volume();
  EXPECT_EQ(flow.net_inflow_volume(), 0.0);
  flow.advance(1.0);
  const double out = flow.inlet_volume() - flow.net_inflow_volume();
  EXPECT_GT(out, 0.05 * v0);  // the overfall carried a good share of the pool away
  // round-off of the per-step sums: measured 6.5e-11 of v0 after 1 s
  EXPECT_NEAR(flow.water_volume(), v0 + flow.net_inflow_volume(), 1e-9 * v0);
}

TEST(VOFOpenEnd, DilatationCountsTheWaterOfAResidualDivergence) {
  // the same draining pool with a loose pressure solve: the residual divergence makes water through the
  // advection's divergence correction, dilatation_volume counts it and the budget closes again
  auto run = [](double tol) {
    FlowParams p = test::pinned_flow_params();
    p.inlet = InletBoundary::kDischarge;
    p.outlet = OutletBoundary::kFreeOverfall;
    p.flume_width = 0.5;
    p.pressure_tol = tol;
    VOFGrid flow(Grid2D::uniform(20, 10, 0.4, 0.2), p);
    flow.set_discharge(DischargeTable::constant(0.005));
    flow.fill_water_below(0.08);
    flow.set_hydrostatic_pressure();
    const double v0 = flow.water_volume();
    flow.advance(1.0);
    const double open = std::abs(flow.water_volume() - (v0 + flow.net_inflow_volume())) / v0;
    const double closed = std::abs(flow.water_volume() - (v0 + flow.net_inflow_volume() + flow.dilatation_volume())) / v0;
    return std::make_tuple(open, closed, std::abs(flow.dilatation_volume()) / v0);
  };
  const auto [open, closed, made] = run(1e-3);
  EXPECT_GT(made, 1e-8);  // a loose solve does make water
  EXPECT_NEAR(open, made, 1e-12);
  EXPECT_LT(closed, 1e-12);
  const auto [open8, closed8, made8] = run(1e-8);
  EXPECT_LT(made8, 1e-3 * made);  // it scales with the residual
  EXPECT_LT(closed8, 1e-12);
}

TEST(VOFOpenEnd, TailwaterInflowIsBoundedByItsHead) {
  // water 2 cm deep against a tailwater level of 10 cm: the tailwater pours in, no faster than a jet
  // from rest under the head difference (Torricelli: sqrt(2 g 0.08) = 1.25 m/s)
  VOFGrid flow = air_box(OutletBoundary::kTailwater, 0.1);
  flow.fill_water_below(0.02);
  flow.set_hydrostatic_pressure();
  double umax = 0.0;
  for (int s = 0; s < 40; ++s) {
    flow.advance(0.025 * (s + 1));
    for (int k = 0; k < flow.grid().nz(); ++k) umax = std::max(umax, -flow.face_u[flow.grid().nx() + (flow.grid().nx() + 1) * k]);
  }
  EXPECT_GT(umax, 0.3);  // it does flow in
  EXPECT_LT(umax, 1.25);
  EXPECT_GT(flow.net_inflow_volume(), 0.0);
}

TEST(VOFOpenEnd, OutflowMomentumIsImplicitInTheEndFace) {
  // one row of three 0.1 m cells, u = 0 (wall), 1, 1, 3 m/s (the end face), convection only: the last
  // cell carries a = (1 + 3) / 2 = 2 m/s times the upwind 1 m/s (the limited slope is 0 there) into the
  // end face's volume, which carries 3 u* out. At dt = 0.05 s (end-face Courant 1.5):
  //   implicit  u* = (3 + 0.05 * 2 / 0.1) / (1 + 0.05 * 3 / 0.1) = 4 / 2.5 = 1.6 m/s
  //   explicit  u* = 3 - 0.05 * (3 * 3 - 2) / 0.1 = -0.5 m/s (reversed: the step would be unstable)
  const Grid2D g = Grid2D::uniform(3, 1, 0.3, 0.1);
  const std::vector<double> u = {0.0, 1.0, 1.0, 3.0}, w(g.nface_z(), 0.0), nx(g.nface_x(), 1.0), nz(g.nface_z(), 1.0);
  const std::vector<double> mu(g.ncell(), 0.0), rx(g.nface_x(), 1000.0), rz(g.nface_z(), 1000.0);
  const MomentumFields f{u.data(), w.data(), nx.data(), nz.data(), mu.data(), rx.data(), rz.data()};
  MomentumTerms t;
  t.viscosity = false;
  MomentumBoundary bc;
  bc.right_open = true;
  std::vector<double> us, ws;
  MomentumScratch s;
  momentum_explicit(g, f, t, bc, 0.05, us, ws, s);
  EXPECT_NEAR(us[3], 1.6, 1e-12);
  // water drawn in (u < 0) keeps the explicit flux: u* = -1 - 0.05 (1 - (-1) (-1)) / 0.1 = -1 with the
  // interior at -1 (uniform inflow stays uniform)
  const std::vector<double> u_in = {0.0, -1.0, -1.0, -1.0};
  const MomentumFields fi{u_in.data(), w.data(), nx.data(), nz.data(), mu.data(), rx.data(), rz.data()};
  momentum_explicit(g, fi, t, bc, 0.05, us, ws, s);
  EXPECT_NEAR(us[3], -1.0, 1e-12);
}

TEST(VOFOpenEnd, WaterLeavingSetsTheStepAtHalfItsCourantNumber) {
  // the end face carrying 2 m/s out of a 0.02 m cell bounds the step at cfl 0.02 / (2 / 2); the same
  // speed drawn in, or on an interior face, at cfl 0.02 / 2
  FlowParams p = test::pinned_flow_params();
  p.outlet = OutletBoundary::kFreeOverfall;
  p.cfl = 0.4;
  VOFGrid flow(Grid2D::uniform(20, 10, 0.4, 0.2), p);
  const int end = flow.grid().face_x(20, 0);
  flow.face_u[end] = 2.0;
  EXPECT_NEAR(flow.stable_dt_terms().advective, 0.4 * 0.02 / 1.0, 1e-15);
  flow.face_u[end] = -2.0;
  EXPECT_NEAR(flow.stable_dt_terms().advective, 0.4 * 0.02 / 2.0, 1e-15);
  flow.face_u[end] = 0.0;
  flow.face_u[flow.grid().face_x(19, 0)] = 2.0;
  EXPECT_NEAR(flow.stable_dt_terms().advective, 0.4 * 0.02 / 2.0, 1e-15);
}

TEST(VOFOpenEnd, FluidDrawnInStartsFromRestAtEveryOpenFace) {
  // a 2 x 2 grid of 0.1 m cells, porosity 0.5 on the faces, air (1.2 kg/m3) everywhere: the open end's
  // lower face draws air in at u = -0.2 m/s (U = -0.4 m/s), the top's left face at w = -0.3 m/s (W =
  // -0.6 m/s); the faces carrying air out keep the still outside's static pressure
  const Grid2D g = Grid2D::uniform(2, 2, 0.2, 0.2);
  std::vector<double> nfx(g.nface_x(), 0.5), nfz(g.nface_z(), 0.5), beta_x(g.nface_x(), 1e-3),
      beta_z(g.nface_z(), 1e-3), u(g.nface_x(), 0.0), w(g.nface_z(), 0.0), rx(g.nface_x(), 1.2),
      rz(g.nface_z(), 1.2), us(g.nface_x(), 0.0), ws(g.nface_z(), 0.0), n(g.ncell(), 1.0);
  u[g.face_x(2, 0)] = -0.2, u[g.face_x(2, 1)] = 0.1;
  w[g.face_z(0, 2)] = -0.3, w[g.face_z(1, 2)] = 0.3;
  ProjectionFields f{nfx.data(), nfz.data(), beta_x.data(), beta_z.data(), u.data(), rx.data(),
                     us.data(),  ws.data(),  n.data(),      n.data(),      w.data(), rz.data()};
  ProjectionBoundary bc;
  bc.right_open = true;
  bc.rho_water = 998.2, bc.rho_air = 1.2, bc.gravity = 9.81;
  PressureProblem pb;
  pb.resize(g);
  std::vector<double> rhs(g.ncell(), 0.0);
  assemble_pressure_problem(g, f, bc, 0.0, pb, rhs);
  // outside: 1.2 * 9.81 * (0.2 - 0.05) = 1.7658 Pa at row 0, 0.5886 Pa at row 1; 1/2 1.2 0.4^2 = 0.096 Pa
  EXPECT_NEAR(pb.face_x_bc[g.face_x(2, 0)], 1.7658 - 0.096, 1e-12);
  EXPECT_NEAR(pb.face_x_bc[g.face_x(2, 1)], 0.5886, 1e-12);
  // top: p = 0 outside, 1/2 1.2 0.6^2 = 0.216 Pa
  EXPECT_NEAR(pb.face_z_bc[g.face_z(0, 2)], -0.216, 1e-12);
  EXPECT_EQ(pb.face_z_bc[g.face_z(1, 2)], 0.0);
}
