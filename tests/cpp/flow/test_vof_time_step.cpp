// The flow's time step from rest: FlowParams::initial_dt, then at most max_dt_growth times the last step;
// a step that breaches the CFL taken again, shorter (step_retry.h).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "common/coupler_scenes.h"
#include "vofdem/coupling/coupler.h"
#include "vofdem/common/step_retry.h"
#include "vofdem/flow/vof_grid.h"
#include "common/pinned_params.h"

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
  FlowParams p = test::pinned_flow_params();
  p.initial_dt = p.max_dt;
  p.max_dt_growth = 10.0;
  VOFGrid flow(wall_grid(), p);
  column_against_wall(flow);
  EXPECT_DOUBLE_EQ(flow.stable_dt(), 0.01);
  try {
    flow.step(flow.stable_dt());
    FAIL() << "no exception";
  } catch (const CflBreach& e) {
    EXPECT_GT(e.courant(), 1.0);
    EXPECT_NE(std::string(e.what()).find("CFL"), std::string::npos) << e.what();
  }
  EXPECT_EQ(flow.time(), 0.0);
}

TEST(VOFTimeStep, CflBreachesNameTheTooLongStepOrTheNewVelocity) {
  auto breach = [](VOFGrid& flow) -> std::string {
    try {
      flow.step(0.01);
    } catch (const CflBreach& e) {
      EXPECT_GT(e.courant(), 1.0);
      return e.what();
    }
    return "no exception";
  };
  // at the step's start: 0.2 m/s through pores of 0.05 cross 8 cells of 5 mm in 0.01 s
  VOFGrid a(wall_grid(), test::pinned_flow_params());
  column_against_wall(a);
  a.face_u[wall_grid().face_x(40, 0)] = 0.2;
  EXPECT_EQ(breach(a).rfind("VOFGrid stage 'step': CFL breach: dt = 0.01 s gives a Courant number 8 (pore velocity) "
                            "at x-face (i=40, k=0",
                            0),
            0u);
  // at its end (no free surface, so no advection to meet it first): the inflow made in the step
  FlowParams p = test::pinned_flow_params();
  p.flags &= ~kFlowFreeSurface;
  p.inlet = InletBoundary::kDischarge;
  p.outlet = OutletBoundary::kFreeOverfall;
  VOFGrid b(wall_grid(), p);
  column_against_wall(b);
  b.set_discharge(DischargeTable::constant(0.2));
  EXPECT_EQ(breach(b).rfind("VOFGrid stage 'checks': CFL breach: the new velocity crosses ", 0), 0u);
}

TEST(VOFTimeStep, RetriesShortenTheStepByTheCourantNumberReached) {
  // dt 1, target 0.5: Courant 1.25 -> dt 0.4 (0.5 / 1.25); 3 -> 0.4 / 6; then it passes
  std::vector<double> courants = {1.25, 3.0}, tried, retried;
  auto step = [&](double dt) {
    tried.push_back(dt);
    if (tried.size() <= courants.size()) throw CflBreach("breach", courants[tried.size() - 1]);
  };
  const double taken = step_with_retries(1.0, 0.5, 1e-9, step, [&](double dt) { retried.push_back(dt); });
  EXPECT_DOUBLE_EQ(taken, 0.4 / 6.0);
  EXPECT_EQ(tried, (std::vector<double>{1.0, 0.4, 0.4 / 6.0}));
  EXPECT_EQ(retried, (std::vector<double>{0.4, 0.4 / 6.0}));
  // a breach just above 1 still halves the step at least
  tried.clear();
  courants = {1.01};
  EXPECT_DOUBLE_EQ(step_with_retries(1.0, 0.9, 1e-9, step, [](double) {}), 0.5);
}

TEST(VOFTimeStep, RetriesGiveUpWithTheLastBreachAndTheirCount) {
  int calls = 0;
  auto always = [&](double) {
    ++calls;
    throw CflBreach("vof advection: CFL number 2 > 1", 2.0);
  };
  try {
    step_with_retries(1.0, 0.5, 1e-9, always, [](double) {});
    FAIL() << "no exception";
  } catch (const CflBreach& e) {
    EXPECT_NE(std::string(e.what()).find("after 4 retries"), std::string::npos) << e.what();
  }
  EXPECT_EQ(calls, kMaxStepRetries + 1);
  calls = 0;
  EXPECT_THROW(step_with_retries(1.0, 0.5, 0.3, always, [](double) {}), CflBreach);  // 0.25 < min_dt
  EXPECT_EQ(calls, 1);
  // other failures are not retried
  calls = 0;
  auto broken = [&](double) {
    ++calls;
    throw std::runtime_error("not finite");
  };
  EXPECT_THROW(step_with_retries(1.0, 0.5, 1e-9, broken, [](double) {}), std::runtime_error);
  EXPECT_EQ(calls, 1);
}

TEST(VOFTimeStep, AdvanceRetriesABreachingStepShorterAndStaysBounded) {
  // the first step of max_dt that breaches the CFL above: advance takes it again, shorter
  FlowParams p = test::pinned_flow_params();
  p.initial_dt = p.max_dt;
  p.max_dt_growth = 10.0;
  VOFGrid flow(wall_grid(), p);
  column_against_wall(flow);
  const double v0 = flow.water_volume();
  flow.advance(0.05);
  EXPECT_GE(flow.retried_steps(), 1);
  EXPECT_DOUBLE_EQ(flow.time(), 0.05);
  EXPECT_NEAR(flow.water_volume(), v0, 1e-10 * v0);
  for (double F : flow.cell_F) {
    EXPECT_GE(F, -1e-9);
    EXPECT_LE(F, 1.0 + 1e-9);
  }
  // the default start needs none: the retry costs nothing where the step holds
  VOFGrid calm(wall_grid(), test::pinned_flow_params());
  column_against_wall(calm);
  calm.advance(0.05);
  EXPECT_EQ(calm.retried_steps(), 0);
}

TEST(VOFTimeStep, CouplerRetriesABreachingStepAndCountsIt) {
  FlowParams p = test::pinned_flow_params();
  p.initial_dt = p.max_dt;
  p.max_dt_growth = 10.0;
  VOFGrid flow(wall_grid(), p);
  column_against_wall(flow);
  DEMParams dp;
  dp.submerged = true;
  dp.medium.rho_water = p.medium.rho_water;
  dp.add_flume(0.0, 0.5, 0.0);
  DEMSystem stones(dp, {0.4, 0.02}, {0.02}, {2650.0});  // a stone on the dry bed behind the wall
  CouplerParams cp;
  cp.flags = kCoupleTwoWay;
  test::resist_relative_to_stones(flow);
  Coupler sim(&flow, &stones, cp);
  const double v0 = sim.water_volume();
  sim.advance(0.05);
  const auto& limits = sim.step_limits();
  ASSERT_EQ(limits.count("cfl_retry"), 1u);
  EXPECT_GE(limits.at("cfl_retry"), 1);
  EXPECT_DOUBLE_EQ(sim.time(), 0.05);
  EXPECT_NEAR(sim.water_volume(), v0, 1e-10 * v0);
}

TEST(VOFTimeStep, StartsAtInitialDtAndGrowsByAtMostTheFactor) {
  VOFGrid flow(wall_grid(), test::pinned_flow_params());
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

TEST(VOFTimeStep, TwoStepControlTakesTheSmallerOfThisAndTheLastStepsAdvectiveLimit) {
  // a fast face (0.2 m/s) sets the first limit; then a four times slower one: kTwoSteps keeps the
  // first step's limit for the second, kThisStep takes the new one
  const Grid2D g = Grid2D::uniform(20, 10, 0.2, 0.1);
  const int face = g.face_x(10, 2);
  auto limits = [&g, face](StepControl control) {
    FlowParams p = test::pinned_flow_params();
    p.step_control = control;
    VOFGrid flow(g, p);
    flow.fill_water_below(0.05);
    flow.face_u[face] = 0.2;
    const double first = flow.stable_dt_terms().advective;
    flow.step(1e-4);
    EXPECT_EQ(flow.last_advective(), first);
    std::fill(flow.face_u.begin(), flow.face_u.end(), 0.0);
    std::fill(flow.face_w.begin(), flow.face_w.end(), 0.0);
    flow.face_u[face] = 0.05;
    return std::make_pair(first, flow.stable_dt_terms().advective);
  };
  const auto [first, next] = limits(StepControl::kThisStep);
  EXPECT_DOUBLE_EQ(next, 4.0 * first);
  const auto [first2, next2] = limits(StepControl::kTwoSteps);
  EXPECT_EQ(first2, first);
  EXPECT_EQ(next2, first);
  // a step whose length the caller chose without asking measured no limit: nothing is kept
  FlowParams p = test::pinned_flow_params();
  p.step_control = StepControl::kTwoSteps;
  VOFGrid flow(g, p);
  flow.fill_water_below(0.05);
  flow.step(1e-4);
  EXPECT_EQ(flow.last_advective(), 0.0);
  // the kept limit is state: an exported and imported flow takes the same next step
  flow.face_u[face] = 0.2;
  const double limit = flow.stable_dt_terms().advective;
  flow.step(1e-4);
  FlowState s;
  flow.export_state(s);
  EXPECT_EQ(s.last_advective, limit);
  VOFGrid copy(g, p);
  copy.import_state(s);
  EXPECT_EQ(copy.last_advective(), limit);
  EXPECT_EQ(copy.stable_dt_terms().advective, flow.stable_dt_terms().advective);
  s.last_advective = -1.0;
  EXPECT_THROW(copy.import_state(s), std::invalid_argument);
  p.step_control = static_cast<StepControl>(2);
  EXPECT_THROW(VOFGrid(g, p), std::invalid_argument);
}

TEST(VOFTimeStep, AdvanceCutToItsEndKeepsTheStableStepForTheGrowth) {
  const Grid2D g = Grid2D::uniform(20, 10, 0.2, 0.1);
  VOFGrid flow(g, test::pinned_flow_params());
  flow.fill_water_below(0.05);
  flow.advance(1e-3 + 1e-4);  // 1e-3, then cut to 1e-4 (the stable step is 1.2e-3)
  EXPECT_DOUBLE_EQ(flow.last_dt(), 1.2e-3);
  EXPECT_DOUBLE_EQ(flow.stable_dt_terms().growth, 1.44e-3);
}

TEST(VOFTimeStep, AdvanceSplitsTheLastIntervalEvenly) {
  // stable steps 1e-3, 1.2e-3, 1.44e-3 from rest: 1e-3, then the 1.5e-3 left in two halves
  const Grid2D g = Grid2D::uniform(20, 10, 0.2, 0.1);
  VOFGrid flow(g, test::pinned_flow_params());
  flow.fill_water_below(0.05);
  EXPECT_EQ(flow.advance(2.5e-3), 3);
  EXPECT_DOUBLE_EQ(flow.time(), 2.5e-3);
  EXPECT_DOUBLE_EQ(flow.last_dt(), 1.44e-3);  // the stable step of the cut last one
  EXPECT_EQ(flow.advance(2.5e-3 + 1e-16), 0);  // a remainder of round-off size is no step
}

TEST(VOFTimeStep, ACollapsedStepIsAFailureThatNamesItsTerms) {
  const Grid2D g = Grid2D::uniform(20, 10, 0.2, 0.1);
  FlowParams p = test::pinned_flow_params();
  p.min_dt = 2e-3;  // above the first step, 1e-3
  VOFGrid flow(g, p);
  flow.fill_water_below(0.05);
  try {
    flow.advance(0.1);
    FAIL() << "no exception";
  } catch (const std::runtime_error& e) {
    const std::string m = e.what();
    EXPECT_EQ(m.rfind("VOFGrid stage 'checks': time step collapsed to 0.001 s (advective ", 0), 0u) << m;
    EXPECT_NE(m.find("state restored to t = 0 s"), std::string::npos) << m;
  }
  EXPECT_EQ(flow.time(), 0.0);
  EXPECT_THROW(flow.advance(NAN), std::invalid_argument);

  test::Scene s = test::tank(0.2, 0.2, 0.01, 0.15, {0.1, 0.08}, 0.01, kCoupleOneWay);
  CouplerParams cp = s.sim->params();
  cp.min_dt = 2e-3;
  s.sim->set_params(cp);
  try {
    s.sim->advance(0.1);
    FAIL() << "no exception";
  } catch (const std::runtime_error& e) {
    EXPECT_STREQ(e.what(), "Coupler stage 'step' at t = 0 s (step 0): time step collapsed to 0.001 s (below min_dt = "
                           "0.002 s); coupled state restored to t = 0 s");
  }
  EXPECT_THROW(s.sim->advance(INFINITY), std::invalid_argument);
}

TEST(VOFTimeStep, BadParametersAreRefused) {
  const Grid2D g = Grid2D::uniform(4, 4, 0.1, 0.1);
  for (double v : {0.0, -1e-3}) {
    FlowParams p = test::pinned_flow_params();
    p.initial_dt = v;
    EXPECT_THROW(VOFGrid(g, p), std::invalid_argument);
  }
  for (double v : {0.99, 10.5}) {
    FlowParams p = test::pinned_flow_params();
    p.max_dt_growth = v;
    try {
      VOFGrid flow(g, p);
      FAIL() << "no exception";
    } catch (const std::invalid_argument& e) {
      EXPECT_NE(std::string(e.what()).find("max_dt_growth"), std::string::npos) << e.what();
    }
  }
  VOFGrid flow(g, test::pinned_flow_params());
  EXPECT_THROW(flow.set_last_dt(-1.0), std::invalid_argument);
}

namespace {

// the advective limit written face by face: cfl / the largest |u| / (n h) of the open faces (an outflow
// face of the open end at half), and the cell beside its first face (x-faces row by row, then z-faces)
void reference_advective(const VOFGrid& flow, double& limit, int& cell) {
  const Grid2D& g = flow.grid();
  const int nx = g.nx(), nz = g.nz();
  double worst = 0.0;
  cell = -1;
  for (int k = 0; k < nz; ++k)
    for (int i = 0; i <= nx; ++i) {
      const int j = g.face_x(i, k);
      const double n = flow.face_x_porosity[j];
      if (!(n > 0.0)) continue;
      double c = std::abs(flow.face_u[j]) / n * (1.0 / g.dx());
      if (i == nx && flow.params().outlet != OutletBoundary::kWall && flow.face_u[j] > 0.0) c *= 0.5;
      if (c > worst) worst = c, cell = g.face_x_cells(i, k).b;
    }
  for (int k = 0; k <= nz; ++k)
    for (int i = 0; i < nx; ++i) {
      const int j = g.face_z(i, k);
      const double n = flow.face_z_porosity[j];
      if (!(n > 0.0)) continue;
      const double h = std::min(g.dz(std::max(k - 1, 0)), g.dz(std::min(k, nz - 1)));
      const double c = std::abs(flow.face_w[j]) / n * 1.0 / h;
      if (c > worst) worst = c, cell = g.face_z_cells(i, k).b;
    }
  limit = worst > 0.0 ? flow.params().cfl / worst : std::numeric_limits<double>::infinity();
}

}  // namespace

TEST(VOFTimeStep, AdvectiveLimitIsTheFaceByFaceReferenceBitForBit) {
  const Grid2D g = Grid2D::graded(13, 0.325, 0.11, 0.01, 0.004, 0.02);
  for (OutletBoundary outlet : {OutletBoundary::kWall, OutletBoundary::kFreeOverfall}) {
    FlowParams p = test::pinned_flow_params();
    p.outlet = outlet;
    VOFGrid flow(g, p);
    unsigned seed = 3;
    auto unit = [&seed] { return (seed = seed * 1103515245u + 12345u) / 4294967296.0; };
    for (int trial = 0; trial < 20; ++trial) {
      for (double& u : flow.face_u) u = unit() - 0.5;
      for (double& w : flow.face_w) w = unit() - 0.5;
      for (double& n : flow.face_x_porosity) n = unit() < 0.2 ? 0.0 : unit();
      for (double& n : flow.face_z_porosity) n = unit() < 0.2 ? 0.0 : unit();
      if (trial % 4 == 1) {  // the largest Courant number on two faces: the first of them binds
        flow.face_u[g.face_x(5, 7)] = flow.face_u[g.face_x(9, 2)] = 1e3;
        flow.face_x_porosity[g.face_x(5, 7)] = flow.face_x_porosity[g.face_x(9, 2)] = 1.0;
      }
      if (trial % 4 == 2) flow.face_w[g.face_z(4, g.nz())] = std::nan("");  // never taken
      if (trial == 3) std::fill(flow.face_x_porosity.begin(), flow.face_x_porosity.end(), 0.0);
      if (trial == 3) std::fill(flow.face_z_porosity.begin(), flow.face_z_porosity.end(), 0.0);
      double limit = 0.0;
      int cell = -2;
      reference_advective(flow, limit, cell);
      const FlowStableDt s = flow.stable_dt_terms();
      EXPECT_EQ(s.advective, limit) << trial;
      EXPECT_EQ(s.advective_cell, cell) << trial;
    }
  }
}

TEST(VOFTimeStep, AdvanceMeasuresItsFirstLimitAfreshAfterTheFieldsWereWritten) {
  // within advance() a step's end Courant rate is the next step's advective limit; a new advance() must
  // not take the last one's, as the fields may have been written through the views in between
  const Grid2D g = Grid2D::uniform(20, 10, 0.2, 0.1);
  VOFGrid flow(g, test::pinned_flow_params());
  flow.fill_water_box(0.0, 0.08, 0.0, 0.08);
  flow.advance(0.05);
  for (double& u : flow.face_u) u *= 10.0;  // as a user would through the view: the advective limit binds
  FlowState written;
  flow.export_state(written);
  VOFGrid fresh(g, test::pinned_flow_params());  // nothing measured before
  fresh.import_state(written);
  flow.advance(0.07);
  fresh.advance(0.07);
  FlowState a, b;
  flow.export_state(a);
  fresh.export_state(b);
  EXPECT_EQ(a.step_count, b.step_count);
  EXPECT_EQ(a.face_u, b.face_u);
  EXPECT_EQ(a.face_w, b.face_w);
  EXPECT_EQ(a.cell_F, b.cell_F);
  EXPECT_EQ(a.time, b.time);
}

TEST(VOFTimeStep, CouplerReplaysFromASparseSnapshotToTheSameBits) {
  // stones in a tank whose inflow jumps now and then within 0.1 ms: the step planned at the jump's
  // start breaches the CFL. With the guard's snapshot every few steps, a failing step is restored by
  // replaying the steps since the snapshot, and the run ends with the same bits as with a snapshot
  // every step
  auto run = [](int interval, std::map<std::string, std::vector<double>>& state, long long& retries,
                long long& replayed) {
    FlowParams fp = test::pinned_flow_params();
    fp.inlet = InletBoundary::kDischarge;
    fp.flume_width = 0.1;
    std::vector<double> pos;
    for (int j = 0; j < 3; ++j) pos.push_back(0.1 + 0.05 * j), pos.push_back(0.04 + 0.03 * j);
    test::Scene s = test::tank(0.3, 0.3, 0.01, 0.1, pos, 0.012, kCoupleTwoWay, fp);
    CouplerParams cp = s.sim->params();
    cp.max_snapshot_interval = interval;
    s.sim->set_params(cp);
    std::vector<double> t = {0.0}, q = {0.0};
    for (int k = 1; k <= 6; ++k) {
      t.push_back(0.05 * k), q.push_back(q.back());
      t.push_back(0.05 * k + 1e-4), q.push_back(k % 2 ? 2e-2 : 0.0);
    }
    s.sim->set_inflow_table(t, q);
    s.sim->advance(0.12);
    s.sim->advance(0.3);
    state = s.sim->export_state();
    const auto& limits = s.sim->step_limits();
    retries = limits.count("cfl_retry") ? limits.at("cfl_retry") : 0;
    replayed = s.sim->replayed_steps();
  };
  std::map<std::string, std::vector<double>> every, sparse;
  long long retries_every, retries_sparse, replayed_every, replayed_sparse;
  run(1, every, retries_every, replayed_every);
  run(32, sparse, retries_sparse, replayed_sparse);
  std::printf("retried steps %lld, steps replayed %lld\n", retries_every, replayed_sparse);
  EXPECT_GE(retries_every, 2);
  EXPECT_EQ(retries_sparse, retries_every);
  EXPECT_EQ(replayed_every, 0);
  EXPECT_GT(replayed_sparse, 0);  // the sparse run did restore by replaying
  std::string diff;
  EXPECT_TRUE(test::same_bits(every, sparse, &diff)) << "first difference: " << diff;
}
