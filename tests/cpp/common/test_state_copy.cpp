// Typed state copies (FlowState, DEMState, CouplerState): a coupled run copied mid-run, run on, restored
// and run again follows the same trajectory bit for bit; the checkpoint's map is the same state.
#include <gtest/gtest.h>

#include "common/coupler_scenes.h"
#include "common/pin_hash.h"
#include "common/pinned_params.h"

namespace vofdem {
namespace {

TEST(StateCopy, CoupledRunBranchesBitForBit) {
  FlowParams fp = test::pinned_flow_params();
  fp.flags |= kFlowTurbulence;
  auto s = test::tank(0.2, 0.4, 0.01, 0.2, {0.1, 0.2, 0.102, 0.25, 0.104, 0.3}, 0.024, kCoupleDefault, fp);
  s.sim->advance(0.05);
  CouplerState branch;
  s.sim->export_state(branch);
  const auto at_branch = s.sim->export_state();
  s.sim->advance(0.1);
  const auto first = s.sim->export_state();
  s.sim->import_state(branch);
  EXPECT_EQ(test::state_hash(s.sim->export_state()), test::state_hash(at_branch));
  s.sim->advance(0.1);
  EXPECT_EQ(test::state_hash(s.sim->export_state()), test::state_hash(first));
  EXPECT_NE(first.at("dem/stone_pos"), at_branch.at("dem/stone_pos"));
}

TEST(StateCopy, AStepFailingLateInTheFlowRestoresTheCoupledStateAndGoesOnAsIfNeverTaken) {
  // a column of water dropped on the pool: a step of 0.02 s starts within the CFL condition and fails
  // in the VOF advection, the flow's last stage, after the others have written velocities, pressure,
  // k and epsilon (and the DEM its stones); the coupler's guard restores them all (the flow's own
  // snapshot then holds u^n and w^n only)
  FlowParams fp = test::pinned_flow_params();
  fp.flags |= kFlowTurbulence;
  auto s = test::tank(0.2, 0.4, 0.01, 0.15, {0.06, 0.024, 0.15, 0.024}, 0.024, kCoupleDefault, fp);
  s.sim->advance(0.05);
  s.fluid->fill_water_box(0.0, 0.05, 0.15, 0.35);
  CouplerState start;
  s.sim->export_state(start);
  const auto before = s.sim->export_state();
  try {
    s.sim->step(0.02);
    FAIL() << "no exception";
  } catch (const std::runtime_error& e) {
    const std::string m = e.what();
    EXPECT_EQ(m.rfind("Coupler stage 'fluid'", 0), 0u) << m;
    EXPECT_NE(m.find("VOFGrid stage 'advect_vof'"), std::string::npos) << m;
  }
  EXPECT_EQ(test::state_hash(s.sim->export_state()), test::state_hash(before));
  s.sim->advance(0.1);
  const auto after_failure = s.sim->export_state();
  s.sim->import_state(start);
  s.sim->advance(0.1);
  EXPECT_EQ(test::state_hash(s.sim->export_state()), test::state_hash(after_failure));
}

TEST(StateCopy, RefusedStateChangesNothing) {
  auto s = test::tank(0.2, 0.4, 0.01, 0.2, {0.1, 0.2}, 0.024, kCoupleDefault);
  s.sim->advance(0.02);
  CouplerState bad;
  s.sim->export_state(bad);
  bad.stones.stone_vel.pop_back();
  const auto before = s.sim->export_state();
  EXPECT_THROW(s.sim->import_state(bad), std::invalid_argument);
  EXPECT_EQ(test::state_hash(s.sim->export_state()), test::state_hash(before));
}

}  // namespace
}  // namespace vofdem
