// The coupler with polygon stones: the fall of a flat stone against its force balance (projected area
// and volume of the matching 3D stone), the porosity of the exact polygon areas, the refused lookup
// table, a bit-for-bit restart.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <stdexcept>
#include <string>

#include "common/coupler_scenes.h"
#include "vofdem/coupling/fluid_forces.h"
#include "common/pinned_params.h"
#include "vofdem/common/numbers.h"

using namespace vofdem;
using namespace vofdem::test;

namespace {
using vofdem::kPi;

// a tank of square cells h with water below `level` and box stones (half-sides a, b) at pos
Scene box_tank(double width, double height, double h, double level, const std::vector<double>& pos, double a,
               double b, unsigned flags) {
  Scene s;
  const Grid2D g = Grid2D::uniform(static_cast<int>(std::lround(width / h)), static_cast<int>(std::lround(height / h)),
                                   width, height);
  s.fluid = std::make_unique<VOFGrid>(g, test::pinned_flow_params());
  s.fluid->fill_water_below(level);
  s.fluid->set_hydrostatic_pressure();
  const std::size_t n = pos.size() / 2;
  DEMParams p = wet_dem(0.0, width);
  p.dt = 5e-5;
  p.contact_steps = 40;
  s.stones = std::make_unique<DEMSystem>(p, pos, std::vector<double>(n, std::hypot(a, b)),
                                         std::vector<double>(n, 2650.0));
  std::vector<double> v;
  std::vector<int> off = {0};
  for (std::size_t i = 0; i < n; ++i) {
    for (double q : {-a, -b, a, -b, a, b, -a, b}) v.push_back(q);
    off.push_back(off.back() + 4);
  }
  s.stones->set_polygons(v, off);
  if (flags & kCouplePorosity) resist_relative_to_stones(*s.fluid);
  CouplerParams cp;
  cp.flags = flags;
  s.sim = std::make_unique<Coupler>(s.fluid.get(), s.stones.get(), cp);
  return s;
}

std::map<std::string, std::vector<double>> diff_free(const Scene& s) { return s.sim->export_state(); }
}  // namespace

TEST(CouplerPolygon, DragOfAGivenProjectedAreaByHand) {
  // F = w 1/2 rho A_p (0.4 |v| + 24 nu / d) v with v = U - u_p: A_p = 1.2e-3 m^2, d = 0.04 m, w = 0.5
  StoneFlowSample s;
  s.area = 1.0;
  s.wet = 0.5;
  s.u = 0.3;
  s.w_vel = -0.4;
  const double up = -0.1, wp = 0.1, rho = 1000.0, nu = 1e-6;
  const DragForce f = stone_drag_area(s, up, wp, 0.04, 1.2e-3, rho, nu, DragLaw::kPaper);
  const double vx = 0.4, vz = -0.5, speed = std::hypot(vx, vz);
  const double coef = 0.5 * 0.5 * rho * 1.2e-3 * (0.4 * speed + 24.0 * nu / 0.04);
  EXPECT_NEAR(f.fx, coef * vx, 1e-15);
  EXPECT_NEAR(f.fz, coef * vz, 1e-15);
  // the sphere's area pi d^2 / 4 gives the disc drag exactly
  const DragForce g = stone_drag_area(s, up, wp, 0.04, 0.25 * kPi * 0.04 * 0.04, rho, nu, DragLaw::kPaper);
  const DragForce h = stone_drag(s, up, wp, 0.04, rho, nu, DragLaw::kPaper);
  EXPECT_EQ(g.fx, h.fx);
  EXPECT_EQ(g.fz, h.fz);
}

TEST(CouplerPolygon, HeldDragBoundsTheStepByItsRelaxationTime) {
  // a held drag on a polygon: the slope of eq. (18) with its mean projected area and nominal diameter
  Scene s = box_tank(0.2, 0.2, 0.01, 0.15, {0.1, 0.08}, 0.01, 0.006, kCoupleOneWay);
  const double mass = hold_the_drag_of_a_moving_stone(s);  // |U - u_p| = 0.3 m/s
  const Medium& m = s.fluid->params().medium;
  const double w = s.stones->stone_wet[0], d = s.stones->nominal_diameter(0);
  ASSERT_GT(w, 0.99);
  const double slope = w * 0.5 * m.rho_water * s.stones->projected_area(0) * (0.8 * 0.3 + 24.0 * m.nu_water / d);
  EXPECT_EQ(s.sim->stable_dt(), s.sim->params().drag_relaxation * mass / slope);
  EXPECT_LT(s.sim->stable_dt(), s.fluid->stable_dt());
}

TEST(CouplerPolygon, FlatStoneFallsAtTheTerminalVelocityOfItsProjectedArea) {
  // a 6 x 3 cm box falling flat: A_p = (pi/2) r_A W with W = 6 cm across the vertical fall,
  // V = (4/3) A r_A, Re on d = 2 r_A; force balance 1/2 rho A_p (0.4 v^2 + 24 nu v / d) = (rho_s - rho) V g
  const double a = 0.03, b = 0.015;
  Scene s = box_tank(0.3, 1.5, 0.01, 1.45, {0.15, 1.3}, a, b, kCoupleOneWay);
  const FlowParams fp = test::pinned_flow_params();
  const double area = 4 * a * b, rA = std::sqrt(area / kPi), d = 2 * rA;
  const double Ap = 0.5 * kPi * rA * 2 * a, V = 4.0 / 3.0 * area * rA;
  const double W = (2650.0 - fp.medium.rho_water) * V * 9.81;
  const double A = 0.5 * fp.medium.rho_water * Ap * 0.4, B = 0.5 * fp.medium.rho_water * Ap * 24.0 * fp.medium.nu_water / d;
  const double vt = (-B + std::sqrt(B * B + 4 * A * W)) / (2 * A);
  s.sim->advance(1.0);
  EXPECT_NEAR(-s.stones->stone_vel[1], vt, 0.03 * vt) << "v_t = " << vt;
  EXPECT_LT(std::fabs(s.stones->stone_angle[0]), 1e-6);  // the fluid forces act at the centre: no spin
  // the drag on it is the formula's at its own velocity
  const double v = -s.stones->stone_vel[1];
  EXPECT_NEAR(s.sim->stone_force_drag[1], A * v * v + B * v, 0.02 * W);
  EXPECT_LT(std::fabs(s.sim->stone_force_pressure[1]), 1e-9);  // still water: buoyancy only, counted in eq. (9)
}

TEST(CouplerPolygon, PorosityOfThePolygonAreas) {
  // a box inside the grid: the solid it maps is (1 - n_exp) times its area, and its cells are listed
  Scene s = box_tank(0.3, 0.3, 0.01, 0.25, {0.153, 0.117}, 0.03, 0.015, kCoupleTwoWay);
  s.stones->stone_angle[0] = 0.4;
  s.sim->update_porosity(false);
  const Grid2D& g = s.fluid->grid();
  double solid = 0.0;
  for (int c = 0; c < g.ncell(); ++c) solid += (1.0 - s.fluid->cell_porosity[c]) * g.cell_area(c / g.nx());
  EXPECT_NEAR(solid, (1.0 - 0.41) * 4 * 0.03 * 0.015, 1e-14);
  // the water volume is kept exactly while it falls through the tank (two-way)
  const double w0 = s.sim->water_volume();
  s.sim->advance(0.2);
  EXPECT_NEAR(s.sim->water_volume(), w0, 1e-9 * w0);  // round-off (the disc test: 1e-9)
}

TEST(CouplerPolygon, TheLookupTableIsRefusedForPolygons) {
  try {
    Scene s = box_tank(0.3, 0.3, 0.01, 0.25, {0.15, 0.1}, 0.03, 0.015, kCoupleTwoWay | kCoupleLookupPorosity);
    FAIL() << "lookup accepted";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("polygon"), std::string::npos) << e.what();
  }
}

TEST(CouplerPolygon, RestartIsBitForBit) {
  auto build = [] { return box_tank(0.2, 0.4, 0.01, 0.2, {0.1, 0.2, 0.102, 0.26, 0.098, 0.32}, 0.03, 0.015, kCoupleTwoWay); };
  Scene a = build();
  a.sim->advance(0.2);
  const auto checkpoint = a.sim->export_state();
  a.sim->advance(0.35);
  Scene b = build();
  b.sim->import_state(checkpoint);
  b.sim->advance(0.35);
  const auto sa = diff_free(a), sb = diff_free(b);
  ASSERT_EQ(sa.size(), sb.size());
  for (const auto& kv : sa) {
    const auto& other = sb.at(kv.first);
    ASSERT_EQ(kv.second.size(), other.size()) << kv.first;
    if (!kv.second.empty()) {
      EXPECT_EQ(std::memcmp(kv.second.data(), other.data(), kv.second.size() * sizeof(double)), 0) << kv.first;
    }
  }
  EXPECT_GT(a.stones->contact_count() + a.stones->wall_contact_count(), 0);
  EXPECT_EQ(sa.count("dem/poly_vertex"), 1u);
}
