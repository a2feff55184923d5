// The weir packing generator (weir_packing.h): geometry by hand, a small weir packed and at rest.
#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>
#include <string>

#include "vofdem/stones/weir_packing.h"

using namespace vofdem;

namespace {
// the Maeno weir's stones (the core has no stone default: the scene gives them)
WeirSpec maeno_stones() {
  WeirSpec s;
  s.d_mean = 0.048;
  s.density = 2650.0;
  return s;
}
}  // namespace

TEST(WeirPacking, TrapezoidGeometryByHand) {
  WeirSpec s = maeno_stones();
  s.height = 0.25;
  s.crest = 0.2;
  s.slope_up_deg = s.slope_down_deg = 45.0;
  s.x_toe = 1.0;
  EXPECT_NEAR(s.x_end(), 1.0 + 0.25 + 0.2 + 0.25, 1e-12);
  EXPECT_NEAR(s.top(1.1), 0.1, 1e-12);
  EXPECT_NEAR(s.top(1.3), 0.25, 1e-12);
  EXPECT_NEAR(s.top(1.65), 0.05, 1e-12);
  EXPECT_EQ(s.top(0.9), 0.0);
  EXPECT_NEAR(s.area(), 0.5 * 0.25 * (0.2 + 0.7), 1e-12);
}

TEST(WeirPacking, SmallWeirIsPackedAtRestAndReproducible) {
  WeirSpec s = maeno_stones();
  s.height = 0.15;
  s.crest = 0.1;
  s.seed = 2;
  WeirPackingReport r1, r2;
  DEMSystem a = pack_weir(s, DEMParams{}, r1);
  DEMSystem b = pack_weir(s, DEMParams{}, r2);
  EXPECT_EQ(a.stone_pos, b.stone_pos);
  EXPECT_GT(r1.n_fixed, 5);
  EXPECT_LT(r1.max_speed, 1e-3);
  EXPECT_LT(r1.outline_error, s.d_mean);
  EXPECT_GT(r1.porosity, 0.05);
  EXPECT_LT(r1.porosity, 0.5);
  for (int i = 0; i < a.n(); ++i) {
    const double d = 2.0 * a.stone_radius[i];
    EXPECT_GE(d, 0.9 * s.d_mean - 1e-12);
    EXPECT_LE(d, 1.1 * s.d_mean + 1e-12);
  }
}

TEST(WeirPacking, RefusesBadSpecs) {
  WeirSpec s = maeno_stones();
  s.slope_up_deg = 0.0;
  WeirPackingReport r;
  EXPECT_THROW(pack_weir(s, DEMParams{}, r), std::invalid_argument);
  WeirSpec t = maeno_stones();
  t.d_spread = 0.9;
  EXPECT_THROW(pack_weir(t, DEMParams{}, r), std::invalid_argument);
}

// the stones' size and density have no default in the core: unset, they are refused with the key named
TEST(WeirPacking, RefusesUnsetStoneDiameterAndDensityNamingTheKey) {
  WeirSpec s;
  WeirPackingReport r;
  try {
    pack_weir(s, DEMParams{}, r);
    FAIL() << "packed stones of no diameter";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("d_mean"), std::string::npos) << e.what();
  }
  s.d_mean = 0.048;
  try {
    check_weir_spec(s);
    FAIL() << "accepted stones of no density";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("density"), std::string::npos) << e.what();
  }
  s.density = 2650.0;
  EXPECT_NO_THROW(check_weir_spec(s));
}

// the plane's rounds settle at the weir's friction: a compaction friction is refused with the key named
TEST(WeirPacking, ThePlanesGeneratorRefusesACompactionFrictionNamingTheKey) {
  WeirSpec s = maeno_stones();
  s.compaction_friction = 0.2;
  WeirPackingReport r;
  try {
    pack_weir(s, DEMParams{}, r);
    FAIL() << "the plane's generator took a compaction friction";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("compaction_friction"), std::string::npos) << e.what();
  }
}

TEST(WeirPacking, SmallPolygonWeirIsPackedAtRestInsideTheOutlineAndReproducible) {
  WeirSpec s = maeno_stones();
  s.height = 0.12;
  s.crest = 0.08;
  s.seed = 5;
  s.shape = "polygon";
  s.settle_time_max = 2.0;
  DEMParams p;
  p.dt = 4e-5;
  p.contact_steps = 50;  // the disc's k_n at 20 steps of 1e-4 s, within the polygons' stable step
  WeirPackingReport r1, r2;
  DEMSystem a = pack_weir(s, p, r1);
  DEMSystem b = pack_weir(s, p, r2);
  EXPECT_STREQ(a.model().name(), "polygon");
  EXPECT_EQ(a.stone_pos, b.stone_pos);
  EXPECT_EQ(a.poly_vertex, b.poly_vertex);
  EXPECT_GT(r1.n_fixed, 3);
  EXPECT_GT(r1.n_stones, r1.n_fixed + 5);
  EXPECT_LT(r1.max_speed, 1e-3);  // at rest
  // inside the outline: no stone reaches out, no point of the slopes and crest lies farther from a
  // stone, than one mean diameter
  EXPECT_LT(r1.outline_error, s.d_mean);
  EXPECT_GT(r1.porosity, 0.05);
  EXPECT_LT(r1.porosity, 0.5);
  for (int i = 0; i < a.n(); ++i) {
    EXPECT_GE(a.nominal_diameter(i), 0.9 * s.d_mean - 1e-12);
    EXPECT_LE(a.nominal_diameter(i), 1.1 * s.d_mean + 1e-12);
  }
  // no two stones overlap by more than the contact's own overlap (~1e-5 m)
  a.advance(1e-4);
  EXPECT_LT(a.energy().elastic, 1e-3);
}
