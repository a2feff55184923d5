// The flow's time step from rest: FlowParams::initial_dt, then at most max_dt_growth times the last step.
#include <gtest/gtest.h>

#include <stdexcept>
#include <vector>

#include "vofdem/vof_grid.h"

using namespace vofdem;

namespace {

// a 0.2 m x 0.5 m water column at rest against a nearly closed porous wall (n = 0.05) 5 cm thick,
// 5 mm cells: the jet into the wall's pores is fast
VOFGrid& column_against_wall(VOFGrid& flow) {
  flow.set_porosity_box(0.2, 0.25, 0.0, 0.6, 0.05, 0.02);
  flow.fill_water_box(0.0, 0.2, 0.0, 0.5);
  return flow;
}

const Grid2D& wall_grid() {
  static const Grid2D g = Grid2D::uniform(100, 120, 0.5, 0.6);
  return g;
}

}  // namespace

TEST(VOFTimeStep, FirstStepOfMaxDtFromRestBreachesTheCfl) {
  // the old rule (no growth limit, first step max_dt = 0.01 s): the velocities created in the first
  // step cross 3.7 cells of the wall's pores
  FlowParams p;
  p.initial_dt = p.max_dt;
  p.max_dt_growth = 10.0;
  VOFGrid flow(wall_grid(), p);
  column_against_wall(flow);
  EXPECT_DOUBLE_EQ(flow.stable_dt(), 0.01);
  EXPECT_THROW(flow.step(flow.stable_dt()), std::runtime_error);
  EXPECT_EQ(flow.time(), 0.0);
}

TEST(VOFTimeStep, StartsAtInitialDtAndGrowsByAtMostTheFactor) {
  VOFGrid flow(wall_grid(), FlowParams{});
  column_against_wall(flow);
  const double v0 = flow.water_volume();
  EXPECT_EQ(flow.last_dt(), 0.0);
  const FlowStableDt s0 = flow.stable_dt_terms();
  EXPECT_EQ(s0.growth, 1e-3);
  EXPECT_EQ(s0.min(), 1e-3);
  double last = 0.0;
  int grown = 0;
  while (flow.time() < 0.1) {
    const double dt = flow.stable_dt();
    if (last == 0.0) EXPECT_EQ(dt, 1e-3);
    else EXPECT_LE(dt, 1.2 * last * (1.0 + 1e-15));
    if (last > 0.0 && dt == 1.2 * last) ++grown;
    ASSERT_NO_THROW(flow.step(dt)) << "t = " << flow.time();
    EXPECT_EQ(flow.last_dt(), dt);
    last = dt;
  }
  EXPECT_GE(grown, 3);  // the growth limit was the binding term at the start
  EXPECT_NEAR(flow.water_volume(), v0, 1e-10 * v0);
}

TEST(VOFTimeStep, AdvanceCutToItsEndKeepsTheStableStepForTheGrowth) {
  const Grid2D g = Grid2D::uniform(20, 10, 0.2, 0.1);
  VOFGrid flow(g, FlowParams{});
  flow.fill_water_below(0.05);
  flow.advance(1e-3 + 1e-4);  // 1e-3, then cut to 1e-4 (the stable step is 1.2e-3)
  EXPECT_DOUBLE_EQ(flow.last_dt(), 1.2e-3);
  EXPECT_DOUBLE_EQ(flow.stable_dt_terms().growth, 1.44e-3);
}

TEST(VOFTimeStep, BadParametersAreRefused) {
  const Grid2D g = Grid2D::uniform(4, 4, 0.1, 0.1);
  for (double v : {0.0, -1e-3}) {
    FlowParams p;
    p.initial_dt = v;
    EXPECT_THROW(VOFGrid(g, p), std::invalid_argument);
  }
  for (double v : {0.99, 10.5}) {
    FlowParams p;
    p.max_dt_growth = v;
    try {
      VOFGrid flow(g, p);
      FAIL() << "no exception";
    } catch (const std::invalid_argument& e) {
      EXPECT_NE(std::string(e.what()).find("max_dt_growth"), std::string::npos) << e.what();
    }
  }
  VOFGrid flow(g, FlowParams{});
  EXPECT_THROW(flow.set_last_dt(-1.0), std::invalid_argument);
}
