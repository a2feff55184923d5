// Wet fraction of a stone at the free surface (wet_fraction.h) and the DEM following it: hand values
// of the disc's share below a level, its inverse, the momentum kept when a stone takes on water, and a
// floating stone whose bobbing does not feed itself.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <utility>

#include "vofdem/stones/dem_system.h"
#include "vofdem/stones/wet_fraction.h"
#include "vofdem/common/numbers.h"

using namespace vofdem;

namespace {
constexpr double kR = 0.024;
using vofdem::kPi;
constexpr double kV = 4.0 / 3.0 * kPi * kR * kR * kR;
}  // namespace

TEST(WetFraction, ShareOfADiscBelowALevel) {
  EXPECT_EQ(disc_wet_fraction(-1.5), 0.0);
  EXPECT_EQ(disc_wet_fraction(2.0), 1.0);
  EXPECT_NEAR(disc_wet_fraction(0.0), 0.5, 1e-15);
  // level at half the radius above the centre: (acos(-0.5) + 0.5 sqrt(0.75)) / pi = (2 pi/3 + 0.4330) / pi
  EXPECT_NEAR(disc_wet_fraction(0.5), (2.0 * kPi / 3.0 + 0.5 * std::sqrt(0.75)) / kPi, 1e-15);
  EXPECT_NEAR(disc_wet_fraction(0.5) + disc_wet_fraction(-0.5), 1.0, 1e-15);  // symmetric
  EXPECT_TRUE(std::isnan(disc_wet_fraction(std::nan(""))));
  for (double s : {-0.999, -0.7, -0.1, 0.0, 0.3, 0.9, 0.9999}) {
    const double h = water_level_of_wet_fraction(0.2, kR, disc_wet_fraction(s));
    EXPECT_NEAR(h, 0.2 + kR * s, 1e-11) << s;
  }
  EXPECT_EQ(water_level_of_wet_fraction(0.2, kR, 1.0), std::numeric_limits<double>::infinity());
  EXPECT_EQ(water_level_of_wet_fraction(0.2, kR, 0.0), -std::numeric_limits<double>::infinity());
}

TEST(WetFraction, AMeasuredValueWithinTheToleranceOfWetOrDryIsTakenAsWetOrDry) {
  EXPECT_EQ(snapped_wet_fraction(1.0 - 1e-7, 1e-6), 1.0);
  EXPECT_EQ(snapped_wet_fraction(1e-7, 1e-6), 0.0);
  EXPECT_EQ(snapped_wet_fraction(1.0 - 2e-6, 1e-6), 1.0 - 2e-6);
  EXPECT_EQ(snapped_wet_fraction(2e-6, 1e-6), 2e-6);
  EXPECT_EQ(snapped_wet_fraction(0.5, 0.5), 0.5);
  EXPECT_EQ(snapped_wet_fraction(1.0, 1e-6), 1.0);
  EXPECT_EQ(snapped_wet_fraction(0.0, 1e-6), 0.0);
  // no tolerance: every value as measured
  EXPECT_EQ(snapped_wet_fraction(1.0 - 1e-7, 0.0), 1.0 - 1e-7);
  EXPECT_EQ(snapped_wet_fraction(1e-300, 0.0), 1e-300);
}

TEST(WetFraction, WaterTakenOnStartsAtRest) {
  DEMParams p;
  p.submerged = true;
  p.medium.rho_water = 1000.0;
  p.flags &= ~kDEMGravity;
  DEMSystem s(p, {0.5, 0.5}, {kR}, {2650.0});
  s.set_wet_fraction(0, 0.0);
  s.stone_vel[1] = -1.0;
  s.advance(1e-4);
  const double M = 2650.0 * kV, e0 = s.energy().kinetic + s.energy().dissipated;
  // entering the water: (M + M') v kept, C_M = 1
  s.set_wet_fraction(0, 1.0);
  EXPECT_NEAR(s.stone_vel[1], -M / (M + 1000.0 * kV), 1e-15);
  // the kinetic energy lost is counted as dissipated
  EXPECT_NEAR(s.energy().kinetic + s.energy().dissipated, e0, 1e-15);
  // leaving it: the velocity is kept (the water left behind keeps its momentum)
  const double v = s.stone_vel[1];
  s.set_wet_fraction(0, 0.3);
  EXPECT_EQ(s.stone_vel[1], v);
  EXPECT_THROW(s.set_wet_fraction(0, 1.5), std::invalid_argument);
}

namespace {
// a 500 kg/m3 stone bobbing at a surface z = 0.3 m without drag or added mass (a conservative
// motion), for 4 s: its highest rise above the level in the first and in the last second. follow: the
// DEM moves w with the stone; else w is set from the height once every 0.01 s (an exchange step) and
// held in between
std::pair<double, double> bobbing(bool follow) {
  DEMParams p;
  p.submerged = true;
  p.medium.rho_water = 1000.0;
  p.added_mass_coefficient = 0.0;
  DEMSystem s(p, {0.5, 0.3}, {kR}, {500.0});
  s.stone_vel[1] = 0.2;
  double first = 0.0, last = 0.0;
  for (int k = 0; k < 400; ++k) {
    if (follow) s.stone_water_level[0] = 0.3;
    else s.set_wet_fraction(0, disc_wet_fraction((0.3 - s.stone_pos[1]) / kR));
    s.advance(0.01);
    const double rise = s.stone_pos[1] - 0.3;
    if (k < 100) first = std::max(first, rise);
    if (k >= 300) last = std::max(last, rise);
  }
  return {first, last};
}
}  // namespace

TEST(WetFraction, TheWetFractionFollowsTheStoneAcrossALevel) {
  DEMParams p;
  p.submerged = true;
  p.medium.rho_water = 1000.0;
  DEMSystem s(p, {0.5, 0.3}, {kR}, {500.0});
  s.stone_water_level[0] = 0.3;
  s.stone_vel[1] = 0.2;
  s.advance(0.01);
  EXPECT_NEAR(s.stone_wet[0], disc_wet_fraction((0.3 - s.stone_pos[1]) / kR), 1e-15);
  // held over each 0.01 s the buoyancy lags the motion and the bobbing grows; followed it keeps its
  // amplitude (to the DEM step's error)
  const auto held = bobbing(false), followed = bobbing(true);
  EXPECT_GT(held.second, 1.2 * held.first);
  EXPECT_NEAR(followed.second, followed.first, 1e-3 * followed.first);
}
