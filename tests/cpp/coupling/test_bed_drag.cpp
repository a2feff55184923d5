// Bed drag (bed_drag.h): the reaction of the flow's porous resistance on the stones.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <stdexcept>

#include "common/coupler_scenes.h"
#include "vofdem/coupling/bed_drag.h"
#include "vofdem/flow/porous_resistance.h"
#include "common/pinned_params.h"

using namespace vofdem;
using namespace vofdem::test;

TEST(BedDrag, CoefficientsAreTheResistancePerSolidVolume) {
  // n / (1 - n) (a, b) of eq. (7), expanded so that n -> 1 stays finite
  for (double n : {0.2, 0.41, 0.6, 0.95}) {
    const PorousCoefficients a = porous_coefficients(n, 0.048, 1e-6, 200.0, 2.8);
    const PorousCoefficients b = bed_coefficients_unchecked(n, 0.048, 1e-6, 200.0, 2.8);
    EXPECT_NEAR(b.linear, n / (1.0 - n) * a.linear, 1e-12 * b.linear) << "n = " << n;
    EXPECT_NEAR(b.quadratic, n / (1.0 - n) * a.quadratic, 1e-12 * b.quadratic) << "n = " << n;
  }
  const PorousCoefficients e = bed_coefficients_unchecked(1.0 - 1e-15, 0.048, 1e-6, 200.0, 2.8);
  EXPECT_TRUE(std::isfinite(e.linear) && std::isfinite(e.quadratic));
  EXPECT_NEAR(e.quadratic, 2.8 / 0.048, 1e-9);
}

TEST(BedDrag, HandComputedCellsAndGuards) {
  // one stone over four cells of equal disc area: a porous cell (n = 0.4, D = 0.02 m, pore velocity
  // 0.15 m/s), a clear-water cell (n = 1), a wall cell (n = 0) and a dry cell (F = 0); V = 1e-5 m^3,
  // rho = 1000, nu = 1.004e-6, (k1, k2) = (200, 2.8). By hand, in the porous cell u_r = 0.4 x 0.15 =
  // 0.06 m/s, A = k1 nu (1 - n) / (n^2 D^2) = 1.2048e-4 / 6.4e-5 = 1.8825 1/s, B = k2 / (n^2 D) = 875 1/m,
  // and with omega = 1/4: F_x = V rho omega (A + B u_r) u_r = 1e-2 x 0.25 x 54.3825 x 0.06 = 8.157375e-3 N.
  const int cells[4] = {0, 1, 2, 3};
  const double areas[4] = {1e-4, 1e-4, 1e-4, 1e-4};
  const double F[4] = {1.0, 1.0, 1.0, 0.0}, n[4] = {0.4, 1.0, 0.0, 0.4}, D[4] = {0.02, 0.02, 0.02, 0.02};
  const double U[4] = {0.15, 0.5, 0.5, 0.5}, W[4] = {0.0, 0.3, 0.3, 0.3};
  FlowParams fp;
  fp.medium.rho_water = 1000.0, fp.medium.nu_water = 1.004e-6, fp.k1 = 200.0, fp.k2 = 2.8;
  fp.flags = kFlowPorousResistance | kFlowRelativeVelocity;
  BedDragParams p(fp);
  double slope = -1.0;
  DragForce f = bed_drag(4, cells, areas, F, n, D, U, W, 0.0, 0.0, 1e-5, p, &slope);
  EXPECT_NEAR(f.fx, 8.157375e-3, 1e-12);
  EXPECT_EQ(f.fz, 0.0);
  // slope V rho omega n (A + 2 B |u_r|) = 1e-2 x 0.25 x 0.4 x 106.8825 = 0.10688250 N s/m
  EXPECT_NEAR(slope, 0.1068825, 1e-10);
  // the stone moving with the water feels nothing (relative velocity) ...
  f = bed_drag(4, cells, areas, F, n, D, U, W, 0.15, 0.0, 1e-5, p, &slope);
  EXPECT_NEAR(f.fx, 0.0, 1e-15);
  // ... unless the flow's resistance ignores the stones' velocity
  p.relative = false;
  f = bed_drag(4, cells, areas, F, n, D, U, W, 0.15, 0.0, 1e-5, p, &slope);
  EXPECT_NEAR(f.fx, 8.157375e-3, 1e-12);
  EXPECT_EQ(slope, 0.0);
  // the Darcy or the Forchheimer term alone, as the flow's effect flags select
  p.relative = true, p.quadratic = false;
  f = bed_drag(4, cells, areas, F, n, D, U, W, 0.0, 0.0, 1e-5, p);
  EXPECT_NEAR(f.fx, 1e-2 * 0.25 * 1.8825 * 0.06, 1e-14);
  // outside the grid: nothing
  f = bed_drag(0, cells, areas, F, n, D, U, W, 0.0, 0.0, 1e-5, p, &slope);
  EXPECT_EQ(f.fx, 0.0);
  EXPECT_EQ(slope, 0.0);
}

TEST(BedDrag, ParamsAreTheFlowsWaterClosureLawAndTerms) {
  // the water is defined once, in the flow's Medium: the bed drag has no density or viscosity of its own
  FlowParams fp;
  fp.medium.rho_water = 1025.0, fp.medium.nu_water = 1.19e-6, fp.k1 = 150.0, fp.k2 = 1.75;
  fp.flags = kFlowPorousDarcy;
  const BedDragParams a(fp);
  EXPECT_EQ(a.rho_w, 1025.0);
  EXPECT_EQ(a.nu_w, 1.19e-6);
  EXPECT_EQ(a.k1, 150.0);
  EXPECT_EQ(a.k2, 1.75);
  EXPECT_TRUE(a.linear);
  EXPECT_FALSE(a.quadratic);
  EXPECT_FALSE(a.relative);
  // the default flow: its Medium's water, the paper's (k1, k2), both terms, the stones' velocity not seen
  const FlowParams d;
  const BedDragParams b(d);
  EXPECT_EQ(b.rho_w, Medium().rho_water);
  EXPECT_EQ(b.nu_w, Medium().nu_water);
  EXPECT_EQ(b.k1, kPaperK1);
  EXPECT_EQ(b.k2, kPaperK2);
  EXPECT_TRUE(b.linear && b.quadratic);
  EXPECT_EQ(b.relative, static_cast<bool>(d.flags & kFlowRelativeVelocity));
}

TEST(BedDrag, ParamsDefaultToTheSphereDragAndRejectUnknownModels) {
  CouplerParams p;
  EXPECT_EQ(p.stone_drag, StoneDragModel::kSphere);
  p.stone_drag = static_cast<StoneDragModel>(2);
  try {
    p.validate();
    FAIL() << "stone_drag = 2 accepted";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("stone_drag = 2"), std::string::npos) << e.what();
  }
}

TEST(Coupler, BedDragAndPressureGradientCarryThePressureDropOfTheBulk) {
  // The closure-law channel (test_vof_grid.cpp): a porous box (n = 0.4, D = 0.02 m) in a 1 m x 0.1 m
  // closed channel, Q = 3 l/s over B = 0.3 m: u = 0.1 m/s superficial; three fixed
  // stones of the box's diameter inside it (their porosity not mapped: the box is the bed they stand
  // for). Steady uniform flow: -dp/dx = G = rho u (a + b u) with a = 200 x 1.004e-6 x 0.36 / (0.064 x
  // 4e-4) = 2.82375 1/s, b = 2.8 x 0.6 / (0.064 x 0.02) = 1312.5 1/m: G = 99.82 x 134.07375 = 13383.2 Pa/m.
  // By hand, per stone (V = pi 0.02^3 / 6 = 4.18879e-6 m^3): F_bed = V n / (1 - n) G = 0.037373 N and
  // F_bed + F_S = V G / (1 - n) = 0.093433 N: the stones carry the whole pressure drop of the bulk
  // volume V / (1 - n) they stand for. Tolerance 1 %: the flow after 0.5 s matches the law within 1 %
  // (PorousResistanceUsesTheMolecularViscosityNotTheEddyViscosity).
  const Grid2D g = Grid2D::uniform(40, 5, 1.0, 0.1);
  FlowParams p = test::pinned_flow_params();
  p.flags = kFlowPorousResistance | kFlowViscosity | kFlowConvection;
  p.flume_width = 0.3;
  p.inlet = InletBoundary::kDischarge;
  p.outlet = OutletBoundary::kFreeOverfall;
  p.top = TopBoundary::kWall;
  VOFGrid flow(g, p);
  flow.fill_water_below(0.1);
  const double n = 0.4, d = 0.02, Q = 0.003;
  flow.set_porosity_box(0.3, 0.7, 0.0, 0.1, n, d);
  flow.set_discharge(DischargeTable::constant(Q));
  flow.advance(0.5);
  const std::vector<double> pos = {0.45, 0.05, 0.5, 0.05, 0.55, 0.05};
  DEMSystem stones(wet_dem(0.0, 1.0), pos, std::vector<double>(3, 0.5 * d), std::vector<double>(3, 2650.0), {1, 1, 1});
  CouplerParams cp;
  cp.flags = kCoupleForces;
  cp.stone_drag = StoneDragModel::kBed;
  Coupler sim(&flow, &stones, cp);
  sim.update_fluid_forces();
  const double V = M_PI * d * d * d / 6.0;
  EXPECT_NEAR(V, 4.18879e-6, 1e-11);
  double sum = 0.0;
  for (int j = 0; j < 3; ++j) {
    EXPECT_NEAR(sim.stone_force_drag[2 * j], 0.037373, 0.01 * 0.037373) << "stone " << j;
    EXPECT_NEAR(sim.stone_force_drag[2 * j] + sim.stone_force_pressure[2 * j], 0.093433, 0.01 * 0.093433) << "stone " << j;
    sum += sim.stone_force_drag[2 * j] + sim.stone_force_pressure[2 * j];
  }
  // the sum over the stones against -dp/dx measured in the flow times their bulk volume
  const int k = 2;
  const double dpdx = (flow.cell_p[g.cell(25, k)] - flow.cell_p[g.cell(14, k)]) / (11 * g.dx());
  EXPECT_NEAR(sum, -dpdx * 3.0 * V / (1.0 - n), 0.01 * sum);
  std::printf("bed drag %.6f N per stone, F_bed + F_S %.6f N; sum %.6f N vs -dp/dx V_bulk %.6f N\n",
              sim.stone_force_drag[0], sim.stone_force_drag[0] + sim.stone_force_pressure[0], sum,
              -dpdx * 3.0 * V / (1.0 - n));
  // the sphere drag of eqs. (16)-(18) in the same flow, for scale: the pore velocity 0.25 m/s gives
  // 1/2 rho A (0.4 U + 24 nu / d) U = 0.15680 x 0.10120 x 0.25 = 3.967e-3 N, 9.4 times smaller
  cp.stone_drag = StoneDragModel::kSphere;
  sim.set_params(cp);
  sim.update_fluid_forces();
  EXPECT_NEAR(sim.stone_force_drag[0], 3.967e-3, 0.01 * 3.967e-3);
}

TEST(Coupler, SphereDragIsTheDefaultAndTheBedDragChangesTheRun) {
  // the default parameters and explicit kSphere give the same run bit for bit; kBed a different one
  auto run = [](bool set, StoneDragModel m) {
    Scene s = tank(0.2, 0.4, 0.01, 0.3, {0.1, 0.2, 0.13, 0.25}, 0.024, kCoupleTwoWay);
    if (set) {
      CouplerParams cp = s.sim->params();
      cp.stone_drag = m;
      s.sim->set_params(cp);
    }
    s.sim->advance(0.1);
    auto st = s.sim->export_state();
    st.erase("coupler/stone_drag_slope");
    return st;
  };
  const auto a = run(false, StoneDragModel::kSphere), b = run(true, StoneDragModel::kSphere);
  ASSERT_EQ(a.size(), b.size());
  for (const auto& kv : a) {
    const auto& v = b.at(kv.first);
    ASSERT_EQ(v.size(), kv.second.size()) << kv.first;
    EXPECT_TRUE(v.empty() || std::memcmp(v.data(), kv.second.data(), v.size() * sizeof(double)) == 0) << kv.first;
  }
  const auto c = run(true, StoneDragModel::kBed);
  EXPECT_NE(c.at("dem/stone_pos"), a.at("dem/stone_pos"));
}
