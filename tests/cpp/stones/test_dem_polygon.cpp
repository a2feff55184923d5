// DEMSystem with polygon stones: a stack at rest, a flat impact's restitution, a block on an incline,
// energy without losses, determinism and bit-for-bit restart, refused input.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <random>
#include <stdexcept>

#include "vofdem/stones/dem_contact.h"
#include "vofdem/stones/dem_system.h"
#include "vofdem/stones/polygon.h"
#include "common/pin_hash.h"
#include "vofdem/common/numbers.h"

using namespace vofdem;

namespace {
using vofdem::kPi;
constexpr double kRho = 2650.0;

std::uint64_t state_hash(const DEMSystem& s) { return test::state_hash(s.export_state()); }

// n boxes of half-sides (a, b) at pos
DEMSystem boxes(const DEMParams& p, const std::vector<double>& pos, double a, double b,
                const std::vector<std::uint8_t>& fixed = {}) {
  const std::size_t n = pos.size() / 2;
  DEMSystem s(p, pos, std::vector<double>(n, std::hypot(a, b)), {kRho}, fixed);
  std::vector<double> v;
  std::vector<int> off = {0};
  for (std::size_t i = 0; i < n; ++i) {
    for (double q : {-a, -b, a, -b, a, b, -a, b}) v.push_back(q);
    off.push_back(off.back() + 4);
  }
  s.set_polygons(v, off);
  return s;
}

// mass of the matching stone of a 2a x 2b section
double box_mass(double a, double b) {
  const double area = 4.0 * a * b;
  return kRho * 4.0 / 3.0 * area * std::sqrt(area / kPi);
}

// a heap of random polygon stones dropped into a box
DEMSystem random_polygons(int n, std::uint64_t seed) {
  std::mt19937_64 g(seed);
  DEMParams p;
  p.add_flume(0.0, 0.46, 0.0, 0.3);
  p.restitution = 0.3;
  p.dt = 5e-5;
  p.contact_steps = 40;
  std::vector<double> pos, radius, v;
  std::vector<int> off = {0};
  PolygonSpec spec;
  for (int k = 0; k < n; ++k) {
    pos.push_back(0.045 + 0.075 * (k % 6) + 0.004 * rng_uniform01(g));
    pos.push_back(0.045 + 0.075 * (k / 6));
    const auto poly = random_convex_polygon(g, spec, 0.048 * (0.9 + 0.2 * rng_uniform01(g)));
    v.insert(v.end(), poly.begin(), poly.end());
    off.push_back(off.back() + static_cast<int>(poly.size() / 2));
    radius.push_back(0.03);
  }
  DEMSystem s(p, pos, radius, {kRho});
  for (int i = 0; i < n; ++i) s.stone_angle[i] = 2.0 * kPi * rng_uniform01(g);
  s.set_polygons(v, off);
  return s;
}
}  // namespace

TEST(DEMPolygon, MassAndInertiaOfTheMatchingStone) {
  DEMParams p;
  DEMSystem s = boxes(p, {0.0, 0.0}, 0.03, 0.01);
  EXPECT_STREQ(s.model().name(), "polygon");
  const double m = box_mass(0.03, 0.01);
  EXPECT_NEAR(s.mass(0), m, 1e-15);
  EXPECT_NEAR(s.volume(0), m / kRho, 1e-18);
  // I = 2 f M J/A, J/A = (w^2 + h^2)/12 for a rectangle
  EXPECT_NEAR(s.inertia(0), 0.8 * m * (0.06 * 0.06 + 0.02 * 0.02) / 12.0, 1e-18);
  EXPECT_NEAR(s.stone_radius[0], std::hypot(0.03, 0.01), 1e-16);  // the bounding radius
  EXPECT_NEAR(s.nominal_diameter(0), 2.0 * std::sqrt(0.0012 / kPi), 1e-16);
  // projected area: (pi/2) r_A W; flow along x sees the height 0.02, along z the length 0.06
  const double rA = std::sqrt(0.0012 / kPi);
  EXPECT_NEAR(s.projected_area(0, 1.0, 0.0), 0.5 * kPi * rA * 0.02, 1e-16);
  EXPECT_NEAR(s.projected_area(0, 0.0, 1.0), 0.5 * kPi * rA * 0.06, 1e-16);
  EXPECT_NEAR(s.projected_area(0), 0.5 * rA * 0.16, 1e-16);  // mean: r_A P / 2
}

TEST(DEMPolygon, StackAtRestBalancesTheWeights) {
  // two boxes 6 x 3 cm on the bed, one on the other: each flat face carries the weight above it on
  // two points, so the overlaps are delta_bed = 2 m g / (2 k) and delta_top = m g / (2 k)
  const double a = 0.03, b = 0.015, k = 1e5, g = 9.81;
  DEMParams p;
  p.stiffness_normal = k;
  p.dt = 5e-5;
  p.walls.push_back({{0.0, 0.0}, {0.0, 1.0}, 0.5});
  DEMSystem s = boxes(p, {0.0, b, 0.0, 3.0 * b + 1e-4}, a, b);
  s.advance(1.0);
  const double m = box_mass(a, b);
  const double d_bed = m * g / k, d_top = 0.5 * m * g / k;
  EXPECT_NEAR(s.stone_pos[1], b - d_bed, 1e-4 * d_bed);
  EXPECT_NEAR(s.stone_pos[3], 3.0 * b - d_bed - d_top, 1e-4 * d_bed);
  for (int i = 0; i < 2; ++i) {
    // contact forces = the weight: the net force vanishes to 1e-6 of the weight, no spin
    EXPECT_LT(std::hypot(s.stone_force[2 * i], s.stone_force[2 * i + 1]), 1e-6 * m * g) << i;
    EXPECT_LT(std::fabs(s.stone_torque[i]), 1e-6 * m * g * a) << i;
    EXPECT_LT(std::hypot(s.stone_vel[2 * i], s.stone_vel[2 * i + 1]), 1e-8) << i;
  }
  EXPECT_EQ(s.contact_count(), 1);
  EXPECT_EQ(s.wall_contact_count(), 1);
  // the upper box pushed off-centre by 1.5 cm still rests: its weight now on unequal points
  DEMSystem t = boxes(p, {0.0, b, 0.015, 3.0 * b + 1e-4}, a, b);
  t.advance(1.0);
  EXPECT_LT(std::hypot(t.stone_force[2], t.stone_force[3]), 1e-6 * m * g);
  EXPECT_LT(std::fabs(t.stone_torque[1]), 1e-6 * m * g * a);
  EXPECT_LT(std::fabs(t.stone_angle[1]), 1e-3);
  EXPECT_NEAR(t.stone_pos[2], 0.015, 1e-5);  // the tangential springs' creep only
}

TEST(DEMPolygon, FlatImpactOnTheBedHasTheRestitution) {
  // a box falls flat onto the bed (no gravity): its two points are one spring-dashpot of 2 k_n with
  // each point's dashpot taking half the mass, so the rebound is e v, resolved by 400 steps per contact
  for (double e : {0.3, 0.5, 0.9}) {
    DEMParams p;
    p.medium.gravity = {0.0, 0.0};
    p.restitution = e;
    p.stiffness_normal = 1e5;
    p.walls.push_back({{0.0, 0.0}, {0.0, 1.0}, 0.5});
    DEMSystem s = boxes(p, {0.0, 0.0155}, 0.03, 0.015);
    const double m = s.mass(0);
    const double tc = contact_duration(2e5, m, damping_ratio_from_restitution(e));
    p.dt = tc / 400.0;
    s.set_params(p);
    s.stone_vel[1] = -0.5;
    s.advance(0.0005 / 0.5 + 2.0 * tc);
    EXPECT_NEAR(s.stone_vel[1], 0.5 * e, 0.005 * 0.5 * e) << e;
    EXPECT_NEAR(s.stone_vel[0], 0.0, 1e-12);
    EXPECT_NEAR(s.stone_omega[0], 0.0, 1e-9);
  }
}

TEST(DEMPolygon, BlockOnInclineHoldsBelowTheFrictionAngleAndSlidesAbove) {
  // a box (rotation on: it does not tip below 45 degrees) on a bed tilted by theta
  const double mu = 0.5, g = 9.81, a = 0.03, b = 0.015;
  auto incline = [&](double theta) {
    DEMParams p;
    p.medium.gravity = {g * std::sin(theta), -g * std::cos(theta)};
    p.stiffness_normal = 1e5;
    p.dt = 5e-5;
    p.walls.push_back({{0.0, 0.0}, {0.0, 1.0}, mu});
    const double delta = box_mass(a, b) * g * std::cos(theta) / 2e5;
    return boxes(p, {0.0, b - delta}, a, b);
  };
  {
    DEMSystem s = incline(std::atan(0.9 * mu));
    s.advance(1.0);
    EXPECT_LT(std::fabs(s.stone_vel[0]), 1e-4);
    EXPECT_LT(std::fabs(s.stone_pos[0]), 1e-4);  // the tangential springs' creep only
  }
  {
    const double th = std::atan(1.1 * mu);
    DEMSystem s = incline(th);
    s.advance(0.5);
    const double v0 = s.stone_vel[0];
    s.advance(0.5);
    const double acc = (s.stone_vel[0] - v0) / 0.5, exact = g * (std::sin(th) - mu * std::cos(th));
    EXPECT_NEAR(acc, exact, 0.01 * exact);
    EXPECT_LT(std::fabs(s.stone_angle[0]), 1e-3);  // slides flat
  }
}

TEST(DEMPolygon, HexagonTipsOverAtThirtyDegrees) {
  // a regular hexagon lying on an edge, friction 0.8 (no sliding below 38.7 degrees): it tips over its
  // lower vertex when the weight's line passes it, tan(theta) = (s/2) / (sqrt(3) s/2), theta = 30 degrees
  const double r = 0.025;
  std::vector<double> v;
  for (int k = 0; k < 6; ++k) v.push_back(r * std::cos(kPi / 3.0 * (k - 1))), v.push_back(r * std::sin(kPi / 3.0 * (k - 1)));
  auto run = [&](double deg) {
    const double th = deg * kPi / 180.0;
    DEMParams p;
    p.medium.gravity = {9.81 * std::sin(th), -9.81 * std::cos(th)};
    p.dt = 4e-5;
    p.contact_steps = 50;
    p.walls.push_back({{0.0, 0.0}, {0.0, 1.0}, 0.8});
    DEMSystem s(p, {0.0, r * std::sqrt(3.0) / 2.0}, {r}, {kRho});
    s.set_polygons(v, {0, 6});
    s.advance(1.0);
    return s;
  };
  const DEMSystem held = run(29.0);
  EXPECT_LT(std::fabs(held.stone_angle[0]), 1e-3);
  EXPECT_LT(std::fabs(held.stone_pos[0]), 1e-4);
  const DEMSystem rolling = run(31.0);
  EXPECT_LT(rolling.stone_angle[0], -kPi);  // rolled over more than three edges down the slope
  EXPECT_GT(rolling.stone_pos[0], 0.05);
}

TEST(DEMPolygon, EnergyIsConservedWithoutDampingOrFriction) {
  DEMSystem s = random_polygons(24, 3);
  DEMParams p = s.params();
  p.flags &= ~(kDEMDamping | kDEMFriction);
  s.set_params(p);
  const double e0 = s.energy().total();
  double worst = 0.0, scale = 0.0;
  // the stones fall ~0.2 m and collide: the total drifts by the time-step error of the contacts only
  for (int k = 0; k < 40; ++k) {
    s.advance(0.01);
    const DEMEnergy e = s.energy();
    worst = std::max(worst, std::fabs(e.total() - e0));
    scale = std::max(scale, e.kinetic);
  }
  EXPECT_GT(s.contact_count() + s.wall_contact_count(), 0);
  EXPECT_LT(worst, 0.03 * scale);
}

TEST(DEMPolygon, RunsAreBitForBitReproducibleAndRestartable) {
  DEMSystem a = random_polygons(36, 5), b = random_polygons(36, 5);
  a.advance(0.3);
  b.advance(0.3);
  EXPECT_EQ(state_hash(a), state_hash(b));
  EXPECT_GT(a.contact_count(), 5);
  const auto checkpoint = a.export_state();
  a.advance(0.1);
  DEMSystem c = random_polygons(36, 99);  // other stones: everything comes from the checkpoint
  c.import_state(checkpoint);
  c.advance(0.1);
  EXPECT_EQ(state_hash(a), state_hash(c));
  EXPECT_EQ(std::memcmp(a.stone_pos.data(), c.stone_pos.data(), a.stone_pos.size() * sizeof(double)), 0);
  EXPECT_NE(state_hash(a), state_hash(b));
  // a disc state makes the system discs again
  DEMSystem d(c.params(), {0.1, 0.1}, {0.024}, {kRho});
  c.import_state(d.export_state());
  EXPECT_STREQ(c.model().name(), "disc");
  EXPECT_EQ(c.n(), 1);
}

TEST(DEMPolygon, StableStepBoundsTheRockingModes) {
  DEMSystem s = random_polygons(24, 1);
  const double dt = s.stable_dt();
  // the trace bound: 4 k (1/m + R^2/I) over the stones
  double lam = 0.0;
  for (int i = 0; i < s.n(); ++i)
    lam = std::max(lam, 1.0 / s.mass(i) + s.stone_radius[i] * s.stone_radius[i] / s.inertia(i));
  EXPECT_NEAR(dt, kPi / (10.0 * std::sqrt(4.0 * s.stiffness_normal() * lam)), 1e-15);
  EXPECT_GE(dt, s.params().dt);  // 40 steps per contact at 5e-5 s: the same k_n as discs at 20 and 1e-4 s
  EXPECT_THROW(s.step(2.0 * dt), std::invalid_argument);
}

TEST(DEMPolygon, SleepingAndRemovalWorkAsForDiscs) {
  DEMParams p;
  p.flags |= kDEMSleeping;
  p.stiffness_normal = 1e5;
  p.dt = 5e-5;
  p.walls.push_back({{0.0, 0.0}, {0.0, 1.0}, 0.5});
  p.domain_min = {-1.0, -0.5};
  p.domain_max = {1.0, 2.0};
  const double m = box_mass(0.03, 0.015);
  DEMSystem s = boxes(p, {0.0, 0.015 - m * 9.81 / 2e5, 0.5, 0.5}, 0.03, 0.015);
  s.stone_vel[2] = 2.0;  // the second box is thrown out of the domain
  s.advance(0.6);
  EXPECT_EQ(s.stone_asleep[0], 1);
  EXPECT_EQ(s.removed_count(), 1);
  EXPECT_EQ(s.stone_active[1], 0);
  const double x = s.stone_pos[0];
  s.advance(0.2);
  EXPECT_EQ(s.stone_pos[0], x);  // asleep: not integrated
  s.stone_force_ext[0] = 2.0;     // more than mu M g = 0.75 N
  s.advance(0.1);
  EXPECT_EQ(s.stone_asleep[0], 0);
  EXPECT_GT(s.stone_vel[0], 0.01);
}

TEST(DEMPolygon, RefusesBadPolygons) {
  DEMSystem s(DEMParams{}, {0.0, 0.0}, {0.03}, {kRho});
  EXPECT_THROW(s.set_polygons({-1, -1, -1, 1, 1, 1, 1, -1}, {0, 4}), std::invalid_argument);  // clockwise
  EXPECT_THROW(s.set_polygons({0, 0, 1, 0, 0, 1}, {0, 3}), std::invalid_argument);  // centroid off the origin
  EXPECT_THROW(s.set_polygons({-1, -1, 1, -1, 1, 1}, {0, 2}), std::invalid_argument);  // too few vertices
  EXPECT_THROW(s.set_polygons({-1, -1, 1, -1, 1, 1, -1, 1}, {0, 4, 8}), std::invalid_argument);  // n + 1 offsets
  try {
    s.set_polygons({-1, -1, -1, 1, 1, 1, 1, -1}, {0, 4});
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("stone 0"), std::string::npos) << e.what();
  }
  EXPECT_STREQ(s.model().name(), "disc");  // unchanged by the refused calls
}

TEST(DEMPolygon, RefusesTheDiscsRollingResistance) {
  // a polygon resists rolling by its shape: mu_r > 0 is refused whichever comes first, shape or parameter
  DEMParams p;
  p.rolling_friction_stone = 0.4;
  DEMSystem s(p, {0.0, 0.0}, {0.03}, {kRho});
  const std::vector<double> box = {-0.02, -0.01, 0.02, -0.01, 0.02, 0.01, -0.02, 0.01};
  try {
    s.set_polygons(box, {0, 4});
    ADD_FAILURE() << "set_polygons accepted rolling_friction_stone = 0.4";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("rolling_friction_stone"), std::string::npos) << e.what();
  }
  EXPECT_STREQ(s.model().name(), "disc");  // unchanged by the refused call
  p.rolling_friction_stone = 0.0;
  s.set_params(p);
  s.set_polygons(box, {0, 4});
  p.rolling_friction_wall = 0.2;
  try {
    s.set_params(p);
    ADD_FAILURE() << "set_params accepted rolling_friction_wall = 0.2 for polygon stones";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("rolling_friction_wall"), std::string::npos) << e.what();
  }
  p.rolling_friction_wall = 0.0;
  p.flags &= ~kDEMRollingResistance;
  p.contact_steps = 50;  // the polygons' stable step (docs/dem.md)
  s.set_params(p);  // mu_r = 0: accepted, the flag on or off
  EXPECT_NO_THROW(s.advance(1e-3));
}

// a heap of polygons under critical damping: the energy account's error halves with dt (the springs of
// manifold points that drop out and the slip from the work done are booked, dem_contact.h)
TEST(DEMPolygon, TheEnergyAccountConvergesUnderCriticalDamping) {
  double error[2];
  for (int k = 0; k < 2; ++k) {
    DEMSystem s = random_polygons(24, 3);
    DEMParams p = s.params();
    p.restitution = 0.0;
    p.stiffness_normal = 1e5;  // not the automatic one, which follows dt
    p.dt = k == 0 ? 2e-5 : 1e-5;
    s.set_params(p);
    const DEMEnergy a = s.energy();
    s.advance(0.4);
    const DEMEnergy b = s.energy();
    EXPECT_GT(b.dissipated, 0.0);
    error[k] = (b.total() - a.total()) / (a.potential - b.potential);
  }
  EXPECT_LT(std::fabs(error[0]), 0.02);
  EXPECT_LT(std::fabs(error[1]), 0.6 * std::fabs(error[0]));
  EXPECT_LT(std::fabs(2.0 * error[1] - error[0]), 2e-3);  // extrapolated to dt = 0
}
