// 3D spheres under the 2D vertical flow: each cell's slab across the width holds the sphere's exact
// volume (PorosityMapper::map_spheres), the porosity is the true void fraction, and the coupled step runs
// with them: a sphere falling in still water at the force balance's velocity, the water kept when a
// sphere moves through the cells, and the refusals.
#include <gtest/gtest.h>

#include <cmath>
#include <memory>
#include <numeric>
#include <stdexcept>
#include <string>

#include "common/coupler_scenes.h"
#include "vofdem/coupling/porosity_map.h"
#include "vofdem/coupling/slab_volume.h"
#include "vofdem/stones/dem_system.h"
#include "common/pinned_params.h"
#include "vofdem/common/numbers.h"

using namespace vofdem;
using namespace vofdem::test;

namespace {
using vofdem::kPi;
constexpr double kR = 0.024;

// a still tank width x height [m] of square cells h [m], water below level [m], 3D spheres of radius kR at
// (x, z) pairs in a flume of width b [m], coupled with n_exp = 0
Scene sphere_tank(double width, double height, double h, double level, const std::vector<double>& pos, double b,
                  unsigned flags) {
  Scene s;
  const Grid2D g = Grid2D::uniform(static_cast<int>(std::lround(width / h)), static_cast<int>(std::lround(height / h)),
                                   width, height);
  s.fluid = std::make_unique<VOFGrid>(g, test::pinned_flow_params());
  s.fluid->fill_water_below(level);
  s.fluid->set_hydrostatic_pressure();
  DEMParams p = wet_dem(0.0, width);
  p.width = b;
  const std::size_t n = pos.size() / 2;
  s.stones = std::make_unique<DEMSystem>(p, pos, std::vector<double>(n, kR), std::vector<double>(n, 2650.0));
  s.stones->set_model("sphere");
  if (flags & kCouplePorosity) resist_relative_to_stones(*s.fluid);
  CouplerParams cp;
  cp.flags = flags;
  cp.n_exp = 0.0;
  s.sim = std::make_unique<Coupler>(s.fluid.get(), s.stones.get(), cp);
  return s;
}
}  // namespace

TEST(SphereFootprint, PartsSumToTheVolumeOverTheWidthAndEachIsTheSlabVolume) {
  const Grid2D g = Grid2D::uniform(20, 30, 0.5, 0.3);  // 2.5 x 1 cm: the paper's mesh
  PorosityParams pp;
  pp.n_exp = 0.0;
  pp.r_min = pp.r_max = kR;
  PorosityMapper m(g, pp);
  const double b = 0.3, x[2] = {0.2037, 0.49}, z[2] = {0.1412, 0.1};  // the second: cut by the grid's end
  const double r[2] = {kR, kR};
  m.map_spheres(2, x, z, r, b);
  const double v = 4.0 / 3.0 * kPi * kR * kR * kR;
  const auto& off = m.stone_cell_offsets();
  const auto& area = m.stone_cell_area();
  const auto& idx = m.stone_cell_index();
  double first = 0.0, second = 0.0;
  for (int p = off[0]; p < off[1]; ++p) first += area[p];
  for (int p = off[1]; p < off[2]; ++p) second += area[p];
  EXPECT_NEAR(first * b, v, 1e-12 * v);
  // inside the grid: the volume less the part beyond x = 0.5
  const double beyond = sphere_slab_volume(0.49, 0.1, kR, 0.5, 0.6, 0.0, 0.3);
  EXPECT_NEAR(second * b, v - beyond, 1e-12 * v);
  for (int p = off[0]; p < off[1]; ++p) {
    const int i = idx[p] % g.nx(), k = idx[p] / g.nx();
    const double slab = sphere_slab_volume(x[0], z[0], kR, g.x_face(i), g.x_face(i + 1), g.z_face(k), g.z_face(k + 1));
    EXPECT_NEAR(area[p] * b, slab, 1e-15) << "cell " << idx[p];
  }
  // the true solid fraction: n = 1 - V_cell / (dx dz B)
  const int c = g.cell(g.locate_x(x[0]), g.locate_z(z[0]));
  double vc = 0.0;
  for (int p = off[0]; p < off[1]; ++p)
    if (idx[p] == c) vc = area[p] * b;
  EXPECT_NEAR(m.cell_porosity()[c], 1.0 - vc / (g.cell_area(g.locate_z(z[0])) * b), 1e-14);
  PorosityParams lookup = pp;
  lookup.method = PorosityMethod::kLookup;
  PorosityMapper ml(g, lookup);
  // the slab mapping's two preconditions (require_slab_mapping), the shape and the key named
  auto refused = [](auto&& call, const char* what) {
    try {
      call();
      ADD_FAILURE() << what << ": no throw";
    } catch (const std::invalid_argument& e) {
      EXPECT_NE(std::string(e.what()).find(what), std::string::npos) << e.what();
    }
  };
  refused([&] { ml.map_spheres(2, x, z, r, b); }, "3D spheres need method = 0 (exact)");
  refused([&] { m.map_spheres(2, x, z, r, 0.0); }, "width = 0 m is outside the allowed range (0, inf)");
  refused([&] { m.map_spheres(2, x, z, r, std::nan("")); }, "width = nan m");
}

TEST(SphereCoupling, FallsInStillWaterAtTheForceBalancesVelocity) {
  // one-way: the still tank stays still, and the sphere's drag (its pi r^2, eq. 18) and the DEM's
  // buoyancy and added mass give the terminal velocity of the force balance, as the discs do
  Scene s = sphere_tank(0.2, 1.5, 0.01, 1.45, {0.1, 1.35}, 0.2, kCoupleOneWay);
  s.stones->stone_y[0] = 0.1;
  const FlowParams fp = test::pinned_flow_params();
  const double vt = terminal_velocity(2.0 * kR, 2650.0, fp.medium.rho_water, fp.medium.nu_water, 9.81);
  s.sim->advance(1.0);
  EXPECT_NEAR(-s.stones->stone_vel[1], vt, 0.03 * vt) << "v_t = " << vt;
  EXPECT_EQ(s.stones->stone_vel_y[0], 0.0);  // nothing across the flume
  EXPECT_EQ(s.stones->stone_wet[0], 1.0);
}

TEST(SphereCoupling, TwoWayKeepsTheWaterWhileSpheresFallThroughTheCells) {
  std::vector<double> pos;
  for (int j = 0; j < 3; ++j) pos.push_back(0.08 + 0.04 * j), pos.push_back(0.25 + 0.05 * j);
  Scene s = sphere_tank(0.2, 0.4, 0.01, 0.35, pos, 0.1, kCoupleTwoWay);
  for (int j = 0; j < 3; ++j) s.stones->stone_y[j] = 0.03 + 0.02 * j;
  s.sim->update_porosity(true);
  const double v0 = s.sim->water_volume();
  // the porosity the spheres leave: their volume over the width, taken out of the tank's cells
  const auto& n = s.fluid->cell_porosity;
  const double solid = std::accumulate(n.begin(), n.end(), 0.0, [&](double acc, double nc) { return acc + (1.0 - nc); });
  EXPECT_NEAR(solid * 0.01 * 0.01 * 0.1, 3.0 * 4.0 / 3.0 * kPi * kR * kR * kR, 1e-9);
  s.sim->advance(0.3);
  EXPECT_NEAR(s.sim->water_volume(), v0, 1e-12 * v0);
  for (int j = 0; j < 3; ++j) EXPECT_LT(s.stones->stone_pos[2 * j + 1], pos[2 * j + 1]);  // they fell
}

TEST(SphereCoupling, AnExpectedPorosityInsideTheStonesIsRefusedWithTheKeyNamed) {
  Scene s = sphere_tank(0.2, 0.4, 0.01, 0.35, {0.1, 0.2}, 0.1, kCoupleTwoWay);
  CouplerParams cp = s.sim->params();
  cp.n_exp = 0.41;
  try {
    s.sim->set_params(cp);
    s.sim->advance(0.01);
    FAIL() << "no throw";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("n_exp"), std::string::npos) << e.what();
  }
}
