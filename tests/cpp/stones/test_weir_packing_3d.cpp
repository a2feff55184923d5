// The 3D weir packing generator (weir_packing_3d.h): a small weir of spheres across a narrow flume packed
// at rest, the same bits from a seed, inside the walls and the outline, its porosity that of a random
// pack; the porosity and the stones across measured on hand-placed spheres.
#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>

#include "vofdem/stones/weir_packing.h"
#include "vofdem/stones/weir_packing_3d.h"
#include "vofdem/common/numbers.h"

using namespace vofdem;

namespace {
using vofdem::kPi;

// a low weir of 3 cm spheres across a 10 cm flume (three fixed rows): ~50 stones, packed in a second
WeirSpec small_weir(std::uint64_t seed) {
  WeirSpec s;
  s.height = 0.08;
  s.crest = 0.06;
  s.d_mean = 0.03;
  s.density = 2650.0;
  s.shape = "sphere";
  s.seed = seed;
  return s;
}

DEMParams flume(double width) {
  DEMParams p;
  p.width = width;
  return p;
}

struct Packed {
  DEMSystem sys;
  WeirPackingReport report;
};

Packed pack(std::uint64_t seed) {
  WeirPackingReport r;
  DEMSystem s = pack_weir(small_weir(seed), flume(0.1), r);
  return {std::move(s), r};
}
}  // namespace

TEST(WeirPacking3D, SameSeedSameBitsOtherSeedDiffers) {
  const Packed a = pack(3), b = pack(3), c = pack(4);
  EXPECT_EQ(a.sys.stone_pos, b.sys.stone_pos);
  EXPECT_EQ(a.sys.stone_y, b.sys.stone_y);
  EXPECT_EQ(a.sys.stone_quat, b.sys.stone_quat);
  EXPECT_EQ(a.report.porosity, b.report.porosity);
  EXPECT_NE(a.sys.stone_radius, c.sys.stone_radius);
}

TEST(WeirPacking3D, SmallWeirAtRestInsideWallsAndOutlineWithARandomPacksPorosity) {
  const WeirSpec s = small_weir(3);
  const Packed a = pack(3);
  const DEMSystem& w = a.sys;
  ASSERT_EQ(std::string(w.model().name()), "sphere");
  EXPECT_LT(a.report.max_speed, s.rest_speed);
  // three rows of touching stones along the 0.37 m base, fixed on the bed
  EXPECT_GE(a.report.n_fixed, 3 * 11);
  int fixed = 0;
  for (int i = 0; i < w.n(); ++i) {
    const double r = w.stone_radius[i];
    EXPECT_GE(2.0 * r, 0.9 * s.d_mean - 1e-12);
    EXPECT_LE(2.0 * r, 1.1 * s.d_mean + 1e-12);
    // between the side walls (a contact's overlap of at most 1 % of the radius)
    EXPECT_GE(w.stone_y[i] - r, -0.01 * r) << i;
    EXPECT_LE(w.stone_y[i] + r, 0.1 + 0.01 * r) << i;
    if (w.stone_fixed[i]) {
      ++fixed;
      EXPECT_NEAR(w.stone_pos[2 * i + 1], s.z_bed + r, 1e-12) << i;
      EXPECT_GE(w.stone_pos[2 * i] - r, s.x_toe - 1e-12);
      EXPECT_LE(w.stone_pos[2 * i] + r, s.x_end() + 1e-12);
    }
  }
  EXPECT_EQ(fixed, a.report.n_fixed);
  EXPECT_GT(a.report.n_stones, a.report.n_fixed + 10);
  // the outline within a mean diameter, as the plane's generator
  EXPECT_LT(a.report.outline_error, s.d_mean);
  // random packs of uniform spheres hold 0.36-0.45 in the bulk, never below 0.36 (random close packing);
  // this weir is 2.7 stones high and 3.3 wide, so nearly every stone lies in a boundary layer (bed, side
  // walls, slopes), where a flat wall's first layer alone holds ~0.5 and the outline cuts the outer
  // stones: 0.62 measured at seed 3 (0.55 for the Maeno weir at B = 0.2 m), hence the bound 0.70
  EXPECT_GT(a.report.porosity, 0.36);
  EXPECT_LT(a.report.porosity, 0.70);
  // a line across the flume crosses about B (1 - n) / (2 d / 3) stones (mean chord of a sphere 2 d / 3):
  // 1.9 at n = 0.62, within 20 %
  const double across = 0.1 * (1.0 - a.report.porosity) / (2.0 * s.d_mean / 3.0);
  EXPECT_NEAR(a.report.stones_across, across, 0.2 * across);
}

TEST(WeirPacking3D, PorosityAndStonesAcrossOfHandPlacedSpheres) {
  // one sphere of radius 0.02 m wholly inside a trapezoid of area 0.5 * 0.1 * (0.3 + 0.1) = 0.02 m^2,
  // across a width of 0.05 m: n = 1 - (4/3 pi r^3) / (0.02 * 0.05)
  WeirSpec s;
  s.height = 0.1;
  s.crest = 0.1;
  s.slope_up_deg = s.slope_down_deg = 45.0;
  s.x_toe = 0.0;
  s.d_mean = 0.04;
  s.density = 2650.0;
  DEMParams p = flume(0.05);
  DEMSystem sys(p, {0.15, 0.05}, {0.02}, {2650.0});
  sys.set_model("sphere");
  sys.stone_y[0] = 0.025;
  const double v = 4.0 / 3.0 * kPi * 0.02 * 0.02 * 0.02;
  EXPECT_NEAR(weir_porosity_3d(sys, s, 0.001), 1.0 - v / (0.02 * 0.05), 1e-3);
  // a line across crosses it over its disc pi r^2 of the trapezoid's 0.02 m^2
  EXPECT_NEAR(weir_stones_across(sys, s, 0.001), kPi * 0.02 * 0.02 / 0.02, 2e-3);
}

TEST(WeirPacking3D, RefusesAFlumeTooNarrowForTwoColumnsNamingWidth) {
  WeirPackingReport r;
  try {
    pack_weir(small_weir(0), flume(0.04), r);
    FAIL() << "no exception";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("width"), std::string::npos) << e.what();
  }
}
