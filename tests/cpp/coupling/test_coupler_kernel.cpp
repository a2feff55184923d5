// The kernel mapping of the coupler (CouplerParams::mapping = kKernel): the solid volume the flow sees,
// what the stones see, Newton's third law of the bed drag, the default untouched, argument checks.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <random>
#include <stdexcept>
#include <string>
#include <vector>

#include "common/coupler_scenes.h"
#include "vofdem/coupling/kernel_smoothing.h"
#include "vofdem/flow/porous_resistance.h"

using namespace vofdem;
using vofdem::test::Scene;

namespace {
constexpr double kR = 0.024;  // the paper's stones, 4.8 cm

// two touching rows of stones on the bed of a 0.6 m x 0.3 m tank of 1 cm cells, one against the inflow
// wall, water to 0.25 m; the kernel of width b (0: the stones' diameter)
Scene kernel_tank(double b, unsigned flags, StoneDragModel drag = StoneDragModel::kSphere) {
  std::vector<double> pos{kR, 0.15};  // against the wall x = 0, in the water column
  for (int row = 0; row < 2; ++row)
    for (int i = 0; i < 8; ++i) pos.push_back(0.15 + 2.0 * kR * i + kR * row), pos.push_back(kR + 2.0 * kR * row);
  Scene s = vofdem::test::tank(0.6, 0.3, 0.01, 0.25, pos, kR, flags);
  CouplerParams cp = s.sim->params();
  cp.mapping = CouplingMapping::kKernel;
  cp.bandwidth = b;
  cp.stone_drag = drag;
  s.sim->set_params(cp);
  return s;
}

// sum_c (1 - n_c) A_c: the solid area per unit width the flow sees [m^2]
double seen_solid_area(const VOFGrid& f) {
  const Grid2D& g = f.grid();
  double s = 0.0;
  for (int k = 0; k < g.nz(); ++k)
    for (int i = 0; i < g.nx(); ++i) s += (1.0 - f.cell_porosity[g.cell(i, k)]) * g.cell_area(k);
  return s;
}
}  // namespace

// eq. (11) on the smoothed solid fraction: the flow sees (1 - n_exp) x the stones' areas, to round-off
TEST(CouplerKernel, TheFlowSeesTheStonesWholeSolidVolume) {
  for (const double b : {0.036, 0.048, 0.072}) {
    Scene s = kernel_tank(b, kCoupleTwoWay);
    s.sim->update_porosity(false);
    ASSERT_NE(s.sim->kernel(), nullptr);
    EXPECT_EQ(s.sim->kernel_bandwidth(), b);
    EXPECT_EQ(s.sim->floored_solid_area(), 0.0) << "b " << b;
    const double n_exp = s.sim->params().n_exp;
    const double stones = (1.0 - n_exp) * s.stones->n() * M_PI * kR * kR;
    EXPECT_NEAR(seen_solid_area(*s.fluid), stones, 1e-12 * stones) << "b " << b;
    // smoothed: no cell reaches the packing's porosity (two rows of touching discs: phi <= pi/4 locally)
    double n_min = 1.0;
    for (double n : s.fluid->cell_porosity) n_min = std::min(n_min, n);
    EXPECT_GT(n_min, n_exp) << "b " << b;
  }
}

// overlapping stones (a pile of discs in one place) exceed the packing's solid fraction: the floor
// n >= n_exp takes the excess out, and says how much
TEST(CouplerKernel, TheFloorRemovesOnlyTheExcessAndCountsIt) {
  std::vector<double> pos;
  for (int m = 0; m < 6; ++m) pos.push_back(0.3 + 0.002 * m), pos.push_back(0.1);
  Scene s = vofdem::test::tank(0.6, 0.3, 0.01, 0.25, pos, kR, kCoupleTwoWay);
  CouplerParams cp = s.sim->params();
  cp.mapping = CouplingMapping::kKernel;
  s.sim->set_params(cp);
  s.sim->update_porosity(false);
  const double n_exp = cp.n_exp;
  EXPECT_GT(s.sim->floored_solid_area(), 0.0);
  for (double n : s.fluid->cell_porosity) EXPECT_GE(n, n_exp);
  const double stones = (1.0 - n_exp) * 6 * M_PI * kR * kR;
  EXPECT_NEAR(seen_solid_area(*s.fluid) + s.sim->floored_solid_area(), stones, 1e-12 * stones);
}

// a pressure field linear in x and z: its gradient is uniform, the kernel keeps it uniform, so every
// stone (the one at the wall too) feels -V grad p in excess of the hydrostatic one exactly
TEST(CouplerKernel, AUniformPressureGradientReachesEveryStoneUnchanged) {
  Scene s = kernel_tank(0.0, kCoupleTwoWay);
  s.sim->update_porosity(false);
  const Grid2D& g = s.fluid->grid();
  const double rho = s.fluid->params().medium.rho_water, grav = s.fluid->params().medium.gravity[1];
  for (int k = 0; k < g.nz(); ++k)
    for (int i = 0; i < g.nx(); ++i) {
      s.fluid->cell_F[g.cell(i, k)] = 1.0;
      s.fluid->cell_p[g.cell(i, k)] = -1500.0 * g.x_center(i) + (rho * grav + 400.0) * g.z_center(k);
    }
  s.sim->update_fluid_forces();
  for (int j = 0; j < s.stones->n(); ++j) {
    const double V = s.stones->volume(j);
    EXPECT_NEAR(s.sim->stone_force_pressure[2 * j], 1500.0 * V, 1e-9 * 1500.0 * V) << "stone " << j;
    EXPECT_NEAR(s.sim->stone_force_pressure[2 * j + 1], -400.0 * V, 1e-9 * 400.0 * V) << "stone " << j;
    EXPECT_NEAR(s.stones->stone_wet[j], 1.0, 1e-12) << "stone " << j;
  }
}

// what a stone sees = the smoothed field over its footprint = its smoothed footprint over the raw
// field: checked against an operator of the same width built here, on a random pressure field
TEST(CouplerKernel, AStoneSeesItsSmoothedFootprintOverTheRawField) {
  Scene s = kernel_tank(0.05, kCoupleTwoWay);
  s.sim->update_porosity(false);
  const Grid2D& g = s.fluid->grid();
  std::mt19937_64 rng(3);
  std::uniform_real_distribution<double> u(-200.0, 200.0);
  for (double& p : s.fluid->cell_p) p = u(rng);
  s.sim->update_fluid_forces();
  std::vector<double> dpdx, dpdz;
  s.fluid->pressure_gradient_at_cells(dpdx, dpdz);
  KernelParams kp;
  kp.bandwidth = 0.05;
  KernelSmoother k(g, kp);
  const double rho = s.fluid->params().medium.rho_water, gx = s.fluid->params().medium.gravity[0];
  for (int j = 0; j < s.stones->n(); ++j) {
    // stone j's exact footprint as a fraction per cell, smoothed
    std::vector<double> foot(static_cast<std::size_t>(g.ncell()), 0.0);
    double area = 0.0;
    for (int kk = 0; kk < g.nz(); ++kk)
      for (int i = 0; i < g.nx(); ++i) {
        const double a = disc_rect_area(s.stones->stone_pos[2 * j], s.stones->stone_pos[2 * j + 1], kR, g.x_face(i),
                                        g.x_face(i + 1), g.z_face(kk), g.z_face(kk + 1));
        foot[g.cell(i, kk)] = a / g.cell_area(kk);
        area += a;
      }
    k.smooth(foot);
    double sx = 0.0;
    for (int kk = 0; kk < g.nz(); ++kk)
      for (int i = 0; i < g.nx(); ++i) {
        const int c = g.cell(i, kk);
        sx += g.cell_area(kk) * foot[c] * (dpdx[c] - rho * s.fluid->cell_F[c] * gx);
      }
    const double expect = -s.stones->volume(j) * sx / area;
    EXPECT_NEAR(s.sim->stone_force_pressure[2 * j], expect, 1e-10 * std::abs(expect) + 1e-15) << "stone " << j;
  }
}

// Newton's third law of the bed drag: summed over the stones it is the flow's cell-wise removal
// rho F n (a + b |u_r|) u_r = rho F (1 - n)(A + B |u_r|) u_r per bulk volume, summed over the cells,
// times the width the stones stand for, (V / area) / (1 - n_exp) = (4 r / 3) / (1 - n_exp)
TEST(CouplerKernel, BedDragOnTheStonesIsWhatTheFlowLoses) {
  Scene s = kernel_tank(0.048, kCoupleTwoWay, StoneDragModel::kBed);
  const Grid2D& g = s.fluid->grid();
  for (std::size_t f = 0; f < s.fluid->face_u.size(); ++f) s.fluid->face_u[f] = 0.08 + 0.01 * std::sin(0.37 * f);
  for (std::size_t f = 0; f < s.fluid->face_w.size(); ++f) s.fluid->face_w[f] = 0.02 * std::cos(0.11 * f);
  s.sim->update_porosity(false);
  s.sim->update_fluid_forces();
  std::vector<double> U, W;
  s.fluid->pore_velocity_at_cells(U, W);
  const FlowParams& fp = s.fluid->params();
  const double rho = fp.medium.rho_water, nu = fp.medium.nu_water;
  double lost_x = 0.0, lost_z = 0.0;
  for (int k = 0; k < g.nz(); ++k)
    for (int i = 0; i < g.nx(); ++i) {
      const int c = g.cell(i, k);
      const double n = s.fluid->cell_porosity[c], F = s.fluid->cell_F[c];
      if (n >= 1.0 || F <= 0.0) continue;
      const PorousCoefficients pc = bed_coefficients_unchecked(n, s.fluid->cell_stone_diameter[c], nu, fp.k1, fp.k2);
      const double ur = n * U[c], wr = n * W[c], r = pc.linear + pc.quadratic * std::hypot(ur, wr);
      lost_x += g.cell_area(k) * rho * F * (1.0 - n) * r * ur;
      lost_z += g.cell_area(k) * rho * F * (1.0 - n) * r * wr;
    }
  const double width = (4.0 * kR / 3.0) / (1.0 - s.sim->params().n_exp);
  double got_x = 0.0, got_z = 0.0;
  for (int j = 0; j < s.stones->n(); ++j) got_x += s.sim->stone_force_drag[2 * j], got_z += s.sim->stone_force_drag[2 * j + 1];
  ASSERT_GT(std::abs(lost_x), 0.0);
  EXPECT_EQ(s.sim->floored_solid_area(), 0.0);
  EXPECT_NEAR(got_x, width * lost_x, 1e-12 * std::abs(width * lost_x));
  EXPECT_NEAR(got_z, width * lost_z, 1e-12 * (std::abs(width * lost_z) + std::abs(width * lost_x)));
}

// a few coupled steps: deterministic, the kernel timed as its own stage; the default has no kernel
TEST(CouplerKernel, CoupledStepsAreDeterministicAndTheDefaultHasNoKernel) {
  std::map<std::string, std::vector<double>> first;
  for (int run = 0; run < 2; ++run) {
    Scene s = kernel_tank(0.0, kCoupleTwoWay, StoneDragModel::kBed);
    s.stones->stone_vel[0] = 0.2;  // the loose stone moves through the water
    s.sim->update_porosity(false);
    for (int m = 0; m < 5; ++m) s.sim->step(2e-3);
    const StageProfile& p = s.sim->profile();
    ASSERT_GE(p.find("kernel"), 0);
    // the first mapping, then the porosity and the forces of each of the 5 steps
    EXPECT_EQ(p.calls()[static_cast<std::size_t>(p.find("kernel"))], 11);
    if (run == 0) first = s.sim->export_state();
    std::string diff;
    EXPECT_TRUE(vofdem::test::same_bits(first, s.sim->export_state(), &diff)) << diff;
  }
  Scene d = vofdem::test::tank(0.6, 0.3, 0.01, 0.25, {0.3, 0.1}, kR, kCoupleTwoWay);
  d.sim->step(2e-3);
  EXPECT_EQ(d.sim->kernel(), nullptr);
  EXPECT_LT(d.sim->profile().find("kernel"), 0);
}

TEST(CouplerKernel, BadMappingOrBandwidthIsRefused) {
  Scene s = kernel_tank(0.0, kCoupleTwoWay);
  for (const double b : {-0.01, 1.5, std::nan("")}) {
    CouplerParams cp = s.sim->params();
    cp.bandwidth = b;
    try {
      s.sim->set_params(cp);
      ADD_FAILURE() << "bandwidth " << b << " accepted";
    } catch (const std::invalid_argument& e) {
      EXPECT_NE(std::string(e.what()).find("bandwidth"), std::string::npos) << e.what();
      EXPECT_NE(std::string(e.what()).find("(0, 1] m"), std::string::npos) << e.what();
    }
  }
  CouplerParams cp = s.sim->params();
  cp.mapping = static_cast<CouplingMapping>(2);
  EXPECT_THROW(s.sim->set_params(cp), std::invalid_argument);
  // the refused sets changed nothing: the stones' diameter still sets the width
  EXPECT_NEAR(s.sim->kernel_bandwidth(), 2.0 * kR, 1e-15);
}
