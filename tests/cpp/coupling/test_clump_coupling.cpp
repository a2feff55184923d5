// Clump stones under the 2D vertical flow: each stone's sub-spheres put their slab volumes, scaled by
// V_union / sum V_k (slab_volume.h), into one cell list per stone (PorosityMapper::map_clumps), the
// porosity is the true void fraction, and the coupled step runs with them: the footprint against the
// sphere's and the reference slab volumes, the solid the flow sees, a clump resting in still water,
// the wet law with the volume-equivalent radius, the kernel mapping's totals, determinism and restart.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <memory>
#include <random>
#include <set>
#include <stdexcept>
#include <string>
#include <vector>

#include "common/coupler_scenes.h"
#include "common/pinned_params.h"
#include "vofdem/coupling/porosity_map.h"
#include "vofdem/coupling/slab_volume.h"
#include "vofdem/flow/porous_resistance.h"
#include "vofdem/stones/clump.h"
#include "vofdem/stones/clump_model.h"
#include "vofdem/stones/dem_system.h"
#include "vofdem/stones/wet_fraction.h"
#include "vofdem/common/numbers.h"

using namespace vofdem;
using namespace vofdem::test;

namespace {
using vofdem::kPi;
constexpr double kR = 0.024;   // the sphere of the sphere model's tests [m]
constexpr double kD = 0.048;   // the library clumps' equivalent diameter [m]
constexpr double kRd = 0.015;  // a dumbbell's sphere radius [m]
constexpr double kCd = 0.010;  // its centres' distance from the middle [m]

// a dumbbell along the x axis in its principal frame, and its union
Clump dumbbell() { return Clump({{Eigen::Vector3d(-kCd, 0, 0), kRd}, {Eigen::Vector3d(kCd, 0, 0), kRd}}); }

// the (x, y, z, r) rows of a clump's spheres (principal frame)
std::vector<double> rows(const Clump& c) {
  std::vector<double> out;
  for (const ClumpSphere& s : c.spheres()) out.insert(out.end(), {s.centre[0], s.centre[1], s.centre[2], s.radius});
  return out;
}

// the areas of stone j's cells [m^2]
double sum_parts(PorosityMapper& m, int j) {
  double a = 0.0;
  for (int p = m.stone_cell_offsets()[j]; p < m.stone_cell_offsets()[j + 1]; ++p) a += m.stone_cell_area()[p];
  return a;
}

Eigen::Quaterniond random_turn(std::mt19937_64& rng) {
  std::normal_distribution<double> n(0.0, 1.0);
  return Eigen::Quaterniond(n(rng), n(rng), n(rng), n(rng)).normalized();
}

// library clumps of d_eq = kD (names cycled, each turned at random) at (x, z) pairs in a still tank
// width x height [m] of square cells h [m], water below level [m], a flume of width b [m], n_exp = 0
Scene clump_tank(double width, double height, double h, double level, const std::vector<double>& pos, double b,
                 unsigned flags, unsigned seed = 1) {
  Scene s;
  const Grid2D g = Grid2D::uniform(static_cast<int>(std::lround(width / h)), static_cast<int>(std::lround(height / h)),
                                   width, height);
  s.fluid = std::make_unique<VOFGrid>(g, test::pinned_flow_params());
  s.fluid->fill_water_below(level);
  s.fluid->set_hydrostatic_pressure();
  DEMParams p = wet_dem(0.0, width);
  p.width = b;
  p.dt = 1e-5;  // the clumps' stricter stable step (stones_3d.md)
  p.stiffness_normal = 1e5;
  const std::size_t n = pos.size() / 2;
  s.stones = std::make_unique<DEMSystem>(p, pos, std::vector<double>(n, 0.5 * kD), std::vector<double>(n, 2650.0));
  const std::vector<std::string> names = quarried_stone_names();
  std::vector<double> sphere;
  std::vector<int> offset{0};
  for (std::size_t j = 0; j < n; ++j) {
    const std::vector<double> r = rows(quarried_stone(names[j % names.size()], kD));
    sphere.insert(sphere.end(), r.begin(), r.end());
    offset.push_back(static_cast<int>(sphere.size() / 4));
  }
  set_clumps(*s.stones, sphere, offset);
  std::mt19937_64 rng(seed);
  for (std::size_t j = 0; j < n; ++j) {
    const Eigen::Quaterniond q = random_turn(rng);
    s.stones->stone_quat[4 * j] = q.w(), s.stones->stone_quat[4 * j + 1] = q.x();
    s.stones->stone_quat[4 * j + 2] = q.y(), s.stones->stone_quat[4 * j + 3] = q.z();
    s.stones->stone_y[j] = 0.5 * b;
  }
  if (flags & kCouplePorosity) resist_relative_to_stones(*s.fluid);
  CouplerParams cp;
  cp.flags = flags;
  cp.n_exp = 0.0;
  s.sim = std::make_unique<Coupler>(s.fluid.get(), s.stones.get(), cp);
  return s;
}

// sum_c (1 - n_c) A_c B: the solid volume the flow sees [m^3]
double seen_solid_volume(const VOFGrid& f, double b) {
  const Grid2D& g = f.grid();
  double s = 0.0;
  for (int k = 0; k < g.nz(); ++k)
    for (int i = 0; i < g.nx(); ++i) s += (1.0 - f.cell_porosity[g.cell(i, k)]) * g.cell_area(k);
  return s * b;
}

double stones_volume(const DEMSystem& s) {
  double v = 0.0;
  for (int j = 0; j < s.n(); ++j) v += s.volume(j);
  return v;
}
}  // namespace

// one sphere as a clump (the model's default shapes, and a shape set of one sphere): the sphere's cells,
// in its order, with its volumes
TEST(ClumpFootprint, AOneSphereClumpMapsToTheSpheresCells) {
  const Grid2D g = Grid2D::uniform(20, 30, 0.5, 0.3);  // 2.5 x 1 cm: the paper's mesh
  PorosityParams pp;
  pp.n_exp = 0.0;
  pp.r_min = pp.r_max = kR;
  PorosityMapper ms(g, pp), mc(g, pp), mset(g, pp);
  const double b = 0.3, x[2] = {0.2037, 0.49}, z[2] = {0.1412, 0.1};  // the second: cut by the grid's end
  const double r[2] = {kR, kR};
  ms.map_spheres(2, x, z, r, b);
  // the default shapes' volume, 4/3 pi r^3 as the mapper sums it: the scale is 1 and the bits the same
  const double quat[8] = {1, 0, 0, 0, 0.3, -0.5, 0.1, 0.8};
  const double two[8] = {0.0, 0.0, 0.0, kR, 0.0, 0.0, 0.0, kR};
  const int offset[3] = {0, 1, 2};
  const double v[2] = {4.0 / 3.0 * kPi * kR * kR * kR, 4.0 / 3.0 * kPi * kR * kR * kR};
  mc.map_clumps(2, x, z, quat, two, offset, v, b);
  ASSERT_EQ(mc.stone_cell_offsets()[2], ms.stone_cell_offsets()[2]);
  for (int p = 0; p < ms.stone_cell_offsets()[2]; ++p) {
    EXPECT_EQ(mc.stone_cell_index()[p], ms.stone_cell_index()[p]) << p;
    EXPECT_EQ(mc.stone_cell_area()[p], ms.stone_cell_area()[p]) << p;
  }
  EXPECT_EQ(mc.cell_porosity(), ms.cell_porosity());
  // a shape of one sphere set through clump.h: its union volume by quadrature, the parts within 1e-15
  const Clump one({{Eigen::Vector3d(0.003, -0.002, 0.001), kR}});
  const double vq[2] = {one.volume(), one.volume()};
  EXPECT_NEAR(one.volume(), v[0], 1e-15 * v[0] + 1e-18);
  mset.map_clumps(2, x, z, quat, two, offset, vq, b);
  ASSERT_EQ(mset.stone_cell_offsets()[2], ms.stone_cell_offsets()[2]);
  for (int p = 0; p < ms.stone_cell_offsets()[2]; ++p)
    EXPECT_NEAR(mset.stone_cell_area()[p] * b, ms.stone_cell_area()[p] * b, 1e-15 * v[0]) << p;
}

// a dumbbell's one list per stone: each cell once, each part the reference clump_slab_volume, and the
// parts summing to the union volume over the width at a wall, on the bed, across faces, turned at random
TEST(ClumpFootprint, ADumbbellsPartsSumToItsUnionVolumeWherever) {
  const Grid2D g = Grid2D::uniform(20, 30, 0.5, 0.3);
  const Clump c = dumbbell();
  const std::vector<double> sph = rows(c);
  const double bound = kCd + kRd, b = 0.2, v = c.volume();
  PorosityParams pp;
  pp.n_exp = 0.0;
  pp.r_min = pp.r_max = bound;
  PorosityMapper m(g, pp);
  std::mt19937_64 rng(7);
  // at the end wall x = 0, on the bed z = 0, centred on a node (cells' faces through it), in a cell
  const std::vector<std::array<double, 2>> where{{bound, 0.15}, {0.2, bound}, {0.25, 0.1}, {0.2137, 0.1412},
                                                 {bound, bound}};
  int worst_cell = 0;
  for (const auto& w : where) {
    for (int turn = 0; turn < 6; ++turn) {
      const Eigen::Quaterniond q = turn == 0 ? Eigen::Quaterniond::Identity() : random_turn(rng);
      const double quat[4] = {q.w(), q.x(), q.y(), q.z()};
      const int offset[2] = {0, 2};
      m.map_clumps(1, &w[0], &w[1], quat, sph.data(), offset, &v, b);
      EXPECT_NEAR(sum_parts(m, 0) * b, v, 1e-12 * v) << "at " << w[0] << ", " << w[1] << " turn " << turn;
      std::set<int> seen;
      for (int p = m.stone_cell_offsets()[0]; p < m.stone_cell_offsets()[1]; ++p) {
        const int cell = m.stone_cell_index()[p];
        EXPECT_TRUE(seen.insert(cell).second) << "cell " << cell << " listed twice";
        const int i = cell % g.nx(), k = cell / g.nx();
        const double ref = clump_slab_volume(c, Eigen::Vector3d(w[0], 0.1, w[1]), q, g.x_face(i), g.x_face(i + 1),
                                             g.z_face(k), g.z_face(k + 1));
        EXPECT_NEAR(m.stone_cell_area()[p] * b, ref, 1e-15) << "cell " << cell;
      }
      worst_cell = std::max(worst_cell, static_cast<int>(seen.size()));
    }
  }
  EXPECT_GT(worst_cell, 6);  // the cases spread over several cells
}

TEST(ClumpFootprint, BadInputIsRefusedWithTheKeyNamed) {
  const Grid2D g = Grid2D::uniform(20, 30, 0.5, 0.3);
  PorosityParams pp;
  pp.n_exp = 0.0;
  pp.r_min = pp.r_max = kCd + kRd;
  PorosityMapper m(g, pp);
  const std::vector<double> sph = rows(dumbbell());
  const double x = 0.2, z = 0.1, quat[4] = {1, 0, 0, 0}, v = dumbbell().volume();
  const int offset[2] = {0, 2}, none[2] = {0, 0};
  auto refused = [&](auto&& call, const char* key) {
    try {
      call();
      ADD_FAILURE() << key << ": no throw";
    } catch (const std::invalid_argument& e) {
      EXPECT_NE(std::string(e.what()).find(key), std::string::npos) << e.what();
    }
  };
  refused([&] { m.map_clumps(1, &x, &z, quat, sph.data(), offset, &v, 0.0); }, "width");
  refused([&] { m.map_clumps(1, &x, &z, quat, sph.data(), none, &v, 0.1); }, "allowed range [1, 8]");
  const double nan = std::nan(""), big[8] = {-0.05, 0, 0, kRd, 0.05, 0, 0, kRd}, zero = 0.0;
  refused([&] { m.map_clumps(1, &nan, &z, quat, sph.data(), offset, &v, 0.1); }, "x");
  refused([&] { m.map_clumps(1, &x, &z, quat, big, offset, &v, 0.1); }, "clump bounding radius");
  refused([&] { m.map_clumps(1, &x, &z, quat, sph.data(), offset, &zero, 0.1); }, "clump volume");
  PorosityParams lookup = pp;
  lookup.method = PorosityMethod::kLookup;
  PorosityMapper ml(g, lookup);
  refused([&] { ml.map_clumps(1, &x, &z, quat, sph.data(), offset, &v, 0.1); }, "method");
}

// coupled: the porosity the clumps leave is their volume over the width; n_exp = 0.41 is refused
TEST(ClumpCoupling, TheFlowSeesTheStonesVolumeAndAPackingPorosityIsRefused) {
  std::vector<double> pos;
  for (int j = 0; j < 4; ++j) pos.push_back(0.05 + 0.05 * j), pos.push_back(0.06 + 0.06 * (j % 2));
  Scene s = clump_tank(0.25, 0.25, 0.01, 0.22, pos, 0.1, kCoupleTwoWay);
  s.sim->update_porosity(true);
  const double v = stones_volume(*s.stones);
  EXPECT_NEAR(seen_solid_volume(*s.fluid, 0.1), v, 1e-12 * v);
  CouplerParams cp = s.sim->params();
  cp.n_exp = 0.41;
  try {
    s.sim->set_params(cp);
    s.sim->advance(0.01);
    FAIL() << "no throw";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("n_exp"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("'clump'"), std::string::npos) << e.what();
  }
}

// a dumbbell lying on the bed of a still tank, two-way coupled: wet through, no excess pressure force,
// and its two contacts each pressed in by half its buoyant weight (M - rho_w V) g / 2 over k_n (dry:
// M g / 2 k_n, 1.6 times deeper)
TEST(ClumpCoupling, AClumpAtRestInStillWaterIsBuoyedByItsVolume) {
  Scene s;
  const Grid2D g = Grid2D::uniform(20, 15, 0.2, 0.15);
  s.fluid = std::make_unique<VOFGrid>(g, test::pinned_flow_params());
  s.fluid->fill_water_below(0.12);
  s.fluid->set_hydrostatic_pressure();
  DEMParams p = wet_dem(0.0, 0.2);
  p.width = 0.1;
  p.dt = 1e-5;
  p.stiffness_normal = 1e5;
  p.restitution = 0.0;  // critically damped contacts: it comes to rest
  s.stones = std::make_unique<DEMSystem>(p, std::vector<double>{0.1, kRd}, std::vector<double>{kRd},
                                         std::vector<double>{2650.0});
  set_clumps(*s.stones, rows(dumbbell()), {0, 2});
  s.stones->stone_y[0] = 0.05;
  resist_relative_to_stones(*s.fluid);
  CouplerParams cp;
  cp.flags = kCoupleTwoWay;
  cp.n_exp = 0.0;
  s.sim = std::make_unique<Coupler>(s.fluid.get(), s.stones.get(), cp);
  s.sim->advance(0.3);
  const double rho = s.fluid->params().medium.rho_water, grav = 9.81;
  const double M = s.stones->mass(0), V = s.stones->volume(0);
  const double sunk = (M - rho * V) * grav / (2.0 * s.stones->stiffness_normal());
  std::printf("dumbbell at rest: wet %.6f, sunk %.4e m against %.4e m, pressure force %.3e N, buoyancy %.5f N\n",
              s.stones->stone_wet[0], kRd - s.stones->stone_pos[1], sunk, s.sim->stone_force_pressure[1],
              rho * grav * V * s.stones->stone_wet[0]);
  EXPECT_EQ(s.stones->stone_wet[0], 1.0);
  // the flow's response to the stone's cells leaves a small excess (measured 0.09 % of the buoyancy)
  EXPECT_LT(std::abs(s.sim->stone_force_pressure[1]), 1e-2 * rho * grav * V);
  // the test_clump_model tolerance of the dry case (0.1 %), and no turn
  EXPECT_NEAR(kRd - s.stones->stone_pos[1], sunk, 1e-3 * sunk);
  EXPECT_NEAR(s.stones->stone_quat[0], 1.0, 1e-9);
}

// the wet law of a clump scales the level by its volume-equivalent radius, not its bounding radius:
// a level half an r_eq above the centre wets 27/32 of it (the cap's volume), in the DEM's substeps and
// in the level the coupler writes
TEST(ClumpCoupling, TheWetLawReadsTheEquivalentRadius) {
  DEMParams p;
  p.submerged = true;
  p.width = 0.1;
  p.dt = 1e-5;
  p.stiffness_normal = 1e5;
  p.flags &= ~kDEMGravity;
  DEMSystem s(p, {0.1, 0.1}, {kRd}, {2650.0});
  set_clumps(s, rows(dumbbell()), {0, 2});
  s.stone_y[0] = 0.05;
  const double r_eq = 0.5 * s.nominal_diameter(0);
  ASSERT_LT(r_eq, s.stone_radius[0] - 1e-3);  // the bounding radius is another
  EXPECT_EQ(s.wet_radius(0), r_eq);
  s.stone_water_level[0] = 0.1 + 0.5 * r_eq;
  s.advance(1e-5);
  EXPECT_NEAR(s.stone_wet[0], 27.0 / 32.0, 1e-12);
  EXPECT_NEAR(water_level_of_wet_fraction(0.1, s.wet_radius(0), 27.0 / 32.0, kSphereWetLaw), 0.1 + 0.5 * r_eq, 1e-9);
}

// the kernel mapping: the flow sees the clumps' whole volume, and the bed drag on the stones is what the
// flow loses (Newton's third law), both to round-off
TEST(ClumpCoupling, TheKernelMappingKeepsTheSolidVolumeAndTheForce) {
  std::vector<double> pos;
  for (int j = 0; j < 6; ++j) pos.push_back(0.08 + 0.06 * j), pos.push_back(0.05 + 0.02 * (j % 2));
  for (const double bw : {0.036, 0.048, 0.072}) {
    Scene s = clump_tank(0.5, 0.25, 0.01, 0.2, pos, 0.1, kCoupleTwoWay);
    CouplerParams cp = s.sim->params();
    cp.mapping = CouplingMapping::kKernel;
    cp.bandwidth = bw;
    cp.stone_drag = StoneDragModel::kBed;
    s.sim->set_params(cp);
    for (std::size_t f = 0; f < s.fluid->face_u.size(); ++f) s.fluid->face_u[f] = 0.08 + 0.01 * std::sin(0.37 * f);
    for (std::size_t f = 0; f < s.fluid->face_w.size(); ++f) s.fluid->face_w[f] = 0.02 * std::cos(0.11 * f);
    s.sim->update_porosity(false);
    ASSERT_NE(s.sim->kernel(), nullptr);
    EXPECT_EQ(s.sim->floored_solid_area(), 0.0);
    const double v = stones_volume(*s.stones);
    EXPECT_NEAR(seen_solid_volume(*s.fluid, 0.1), v, 1e-12 * v) << "b " << bw;
    s.sim->update_fluid_forces();
    std::vector<double> U, W;
    s.fluid->pore_velocity_at_cells(U, W);
    const FlowParams& fp = s.fluid->params();
    const Grid2D& g = s.fluid->grid();
    double lost_x = 0.0, lost_z = 0.0;
    for (int k = 0; k < g.nz(); ++k)
      for (int i = 0; i < g.nx(); ++i) {
        const int c = g.cell(i, k);
        const double n = s.fluid->cell_porosity[c], F = s.fluid->cell_F[c];
        if (n >= 1.0 || F <= 0.0) continue;
        const PorousCoefficients pc =
            bed_coefficients_unchecked(n, s.fluid->cell_stone_diameter[c], fp.medium.nu_water, fp.k1, fp.k2);
        const double ur = n * U[c], wr = n * W[c], r = pc.linear + pc.quadratic * std::hypot(ur, wr);
        lost_x += g.cell_area(k) * fp.medium.rho_water * F * (1.0 - n) * r * ur;
        lost_z += g.cell_area(k) * fp.medium.rho_water * F * (1.0 - n) * r * wr;
      }
    // the width a stone's areas stand for: V / sum of its areas = B (n_exp = 0)
    double got_x = 0.0, got_z = 0.0;
    for (int j = 0; j < s.stones->n(); ++j)
      got_x += s.sim->stone_force_drag[2 * j], got_z += s.sim->stone_force_drag[2 * j + 1];
    ASSERT_GT(std::abs(lost_x), 0.0);
    EXPECT_NEAR(got_x, 0.1 * lost_x, 1e-12 * std::abs(0.1 * lost_x)) << "b " << bw;
    EXPECT_NEAR(got_z, 0.1 * lost_z, 1e-12 * (std::abs(0.1 * lost_z) + std::abs(0.1 * lost_x))) << "b " << bw;
  }
}

// clumps falling through the water two-way: the water kept, two runs the same bits, and a restart from a
// checkpoint the same bits
TEST(ClumpCoupling, TwoWayRunsKeepTheWaterAndRestartBitForBit) {
  std::vector<double> pos;
  for (int j = 0; j < 3; ++j) pos.push_back(0.05 + 0.05 * j), pos.push_back(0.05 + 0.04 * j);
  auto build = [&] { return clump_tank(0.2, 0.3, 0.01, 0.25, pos, 0.08, kCoupleTwoWay); };
  Scene a = build();
  a.sim->update_porosity(true);
  const double v0 = a.sim->water_volume();
  a.sim->advance(0.1);
  const auto checkpoint = a.sim->export_state();
  EXPECT_EQ(checkpoint.count("dem/clump_sphere"), 1u);
  a.sim->advance(0.2);
  std::printf("three clumps two-way over 0.3 s: water volume drift %.2e relative\n",
              std::abs(a.sim->water_volume() - v0) / v0);
  // the porosity map took the model's footprint (test_stone_model's bound for a model's coupled run)
  EXPECT_NEAR(a.sim->water_volume(), v0, 1e-9 * v0);
  for (int j = 0; j < 3; ++j) EXPECT_LT(a.stones->stone_pos[2 * j + 1], pos[2 * j + 1]) << "stone " << j;
  Scene b = build();
  b.sim->import_state(checkpoint);
  b.sim->advance(0.2);
  std::string diff;
  EXPECT_TRUE(same_bits(a.sim->export_state(), b.sim->export_state(), &diff)) << "first difference: " << diff;
  Scene c = build();
  c.sim->update_porosity(true);
  c.sim->advance(0.1);
  c.sim->advance(0.2);
  EXPECT_TRUE(same_bits(a.sim->export_state(), c.sim->export_state(), &diff)) << "first difference: " << diff;
  EXPECT_GT(a.stones->contact_count() + a.stones->wall_contact_count(), 0);  // histories exercised
}
