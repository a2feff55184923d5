// Coupler::settle, the stones settling in still water before the first step: a stone on the bed carries
// its submerged weight (under water), its weight less the share under the surface (cut by it), its full
// weight (in the air), discs and spheres alike; the flow stays frozen; the same bits twice; a cap; the
// refusals.
#include <gtest/gtest.h>

#include <cmath>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include "common/coupler_scenes.h"
#include "vofdem/stones/wet_fraction.h"

using namespace vofdem;
using namespace vofdem::test;

namespace {
constexpr double kR = 0.024;

// a still tank 0.2 m x 0.3 m of 1 cm cells, water below `level` [m], one stone of radius kR just above the
// bed (centre 1 mm over its resting height), as the given model (a sphere in the middle of a 0.2 m flume)
Scene stone_on_bed(double level, const std::string& model) {
  Scene s = tank(0.2, 0.3, 0.01, level, {0.1, kR + 1e-3}, kR, kCoupleTwoWay);
  if (model != "disc") {
    DEMParams p = s.stones->params();
    p.width = 0.2;
    s.stones->set_params(p);
    s.stones->set_model(model);
    s.stones->stone_y[0] = 0.1;
    CouplerParams cp = s.sim->params();
    cp.n_exp = 0.0;  // 3D stones map their volume exactly
    s.sim = std::make_unique<Coupler>(s.fluid.get(), s.stones.get(), cp);
  }
  return s;
}

// the bed's normal force on the resting stone, k_n delta (dem_contact.h; at rest the dashpot is idle) [N]
double bed_force(const Scene& s) { return s.stones->stiffness_normal() * (kR - s.stones->stone_pos[1]); }

// (rho_s - w rho_w) V g with w the stone's share below `level` at its settled height (its model's law) [N]
double weight_in_water(const Scene& s, double level, const WetLaw& law) {
  const double rho_w = s.fluid->params().medium.rho_water, g = -s.fluid->params().medium.gravity[1];
  const double w = law.fraction((level - s.stones->stone_pos[1]) / kR);
  return (2650.0 - w * rho_w) * s.stones->volume(0) * g;
}

void check_rests_on_its_weight_in_water(double level, const std::string& model, const WetLaw& law) {
  Scene s = stone_on_bed(level, model);
  const std::vector<double> F0 = s.fluid->cell_F;
  const SettleReport r = s.sim->settle();
  EXPECT_TRUE(r.rested);
  EXPECT_LT(r.max_speed, 1e-3);
  EXPECT_GT(r.time, 0.0);
  // hand value: the contact carries the stone's weight in the water it sits in, to 1e-4
  const double want = weight_in_water(s, level, law);
  EXPECT_NEAR(bed_force(s), want, 1e-4 * want) << model << " with the water at " << level << " m";
  // the flow is frozen and the coupler's clock kept
  EXPECT_EQ(s.fluid->cell_F, F0);
  EXPECT_EQ(s.sim->time(), 0.0);
  EXPECT_EQ(s.sim->step_count(), 0);
  EXPECT_GE(s.sim->profile().find("settle"), 0);
}
}  // namespace

TEST(CouplerSettle, DiscUnderWaterCarriesItsSubmergedWeight) {
  check_rests_on_its_weight_in_water(0.25, "disc", kDiscWetLaw);
  // the hand value itself: (2650 - 1000) 4/3 pi r^3 g for a stone wholly under water
  Scene s = stone_on_bed(0.25, "disc");
  s.sim->settle();
  const double V = 4.0 / 3.0 * M_PI * kR * kR * kR;
  EXPECT_NEAR(bed_force(s), (2650.0 - s.fluid->params().medium.rho_water) * V * 9.81, 1e-4 * 1650.0 * V * 9.81);
}

TEST(CouplerSettle, DiscInTheAirCarriesItsFullWeight) {
  Scene s = stone_on_bed(0.0, "disc");
  EXPECT_TRUE(s.sim->settle().rested);
  EXPECT_EQ(s.stones->stone_wet[0], 0.0);
  const double full = s.stones->mass(0) * 9.81;
  EXPECT_NEAR(bed_force(s), full, 1e-4 * full);
}

TEST(CouplerSettle, DiscCutByTheSurfaceCarriesItsWeightLessItsWetShare) {
  // the surface on a cell face 6 mm above the centre: the disc's exact share below it (wet_fraction.h)
  check_rests_on_its_weight_in_water(0.03, "disc", kDiscWetLaw);
}

TEST(CouplerSettle, SphereUnderWaterAndCutByTheSurface) {
  check_rests_on_its_weight_in_water(0.25, "sphere", kSphereWetLaw);
  check_rests_on_its_weight_in_water(0.03, "sphere", kSphereWetLaw);
}

TEST(CouplerSettle, TwoSettlesGiveTheSameBitsAndARestartAfterOneContinuesThem) {
  // a pile of three stones dropped into the water: they move for a while before resting
  auto pile = [] {
    return tank(0.3, 0.4, 0.01, 0.3, {0.1, 0.03, 0.15, 0.03, 0.125, 0.08}, kR, kCoupleTwoWay);
  };
  Scene a = pile(), b = pile();
  const SettleReport ra = a.sim->settle(), rb = b.sim->settle();
  EXPECT_EQ(ra.time, rb.time);
  EXPECT_EQ(ra.max_speed, rb.max_speed);
  std::string diff;
  EXPECT_TRUE(same_bits(a.sim->export_state(), b.sim->export_state(), &diff)) << diff;
  // a run resumed from the settled state is the run that went on
  Scene c = pile();
  c.sim->import_state(a.sim->export_state());
  a.sim->advance(0.05);
  c.sim->advance(0.05);
  EXPECT_TRUE(same_bits(a.sim->export_state(), c.sim->export_state(), &diff)) << diff;
}

TEST(CouplerSettle, TheCapEndsASettlingThatHasNotRested) {
  Scene s = tank(0.2, 0.4, 0.01, 0.3, {0.1, 0.3}, kR, kCoupleTwoWay);  // a stone 28 cm above the bed
  SettleParams p;
  p.max_time = 0.05;
  const SettleReport r = s.sim->settle(p);
  EXPECT_FALSE(r.rested);
  EXPECT_NEAR(r.time, 0.05, 1e-12);
  EXPECT_GT(r.max_speed, 0.1);
  EXPECT_NEAR(s.stones->time(), r.time, 1e-12);  // the stones' own clock ran (in substeps), the coupler's did not
  EXPECT_EQ(s.sim->time(), 0.0);
}

TEST(CouplerSettle, NothingToSettleWithoutTheDEMEffect) {
  Scene s = tank(0.2, 0.3, 0.01, 0.25, {0.1, 0.1}, kR, kCoupleTwoWay & ~kCoupleDEM);
  const SettleReport r = s.sim->settle();
  EXPECT_EQ(r.time, 0.0);
  EXPECT_EQ(s.stones->stone_pos[1], 0.1);
}

TEST(CouplerSettle, BadParametersAreRefusedWithTheirNames) {
  Scene s = stone_on_bed(0.25, "disc");
  auto refused = [&](SettleParams p, const std::string& name) {
    try {
      s.sim->settle(p);
      ADD_FAILURE() << name << " accepted";
    } catch (const std::invalid_argument& e) {
      EXPECT_NE(std::string(e.what()).find(name), std::string::npos) << e.what();
    }
  };
  SettleParams p;
  p.max_time = 0.0;
  refused(p, "max_time");
  p = SettleParams(), p.max_time = 601.0;
  refused(p, "max_time");
  p = SettleParams(), p.rest_speed = 0.0;
  refused(p, "rest_speed");
  p = SettleParams(), p.hold = -1.0;
  refused(p, "hold");
  p = SettleParams(), p.chunk = NAN;
  refused(p, "chunk");
  EXPECT_EQ(s.stones->time(), 0.0);  // nothing stepped
}

TEST(DEMSystem, MaxSpeedCountsTheSpinAndSkipsFixedStones) {
  DEMParams dp;
  dp.add_flume(0.0, 1.0, 0.0);
  DEMSystem d(dp, {0.2, 0.5, 0.6, 0.5}, {0.02, 0.02}, {2650.0, 2650.0}, {0, 1});
  d.stone_vel[0] = 0.3, d.stone_vel[1] = 0.4;  // 0.5 m/s
  d.stone_vel[2] = 9.0;                        // fixed: not counted
  EXPECT_DOUBLE_EQ(d.max_speed(), 0.5);
  d.stone_omega[0] = 50.0;  // 50 x 0.02 = 1 m/s
  EXPECT_DOUBLE_EQ(d.max_speed(), 1.0);
}
