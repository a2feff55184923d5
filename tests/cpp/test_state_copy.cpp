// Typed state copies (FlowState, DEMState, CouplerState): a coupled run copied mid-run, run on, restored
// and run again follows the same trajectory bit for bit; the checkpoint's map is the same state.
#include <gtest/gtest.h>

#include "coupler_scenes.h"
#include "pin_hash.h"

namespace vofdem {
namespace {

TEST(StateCopy, CoupledRunBranchesBitForBit) {
  FlowParams fp;
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
  EXPECT_NE(first.at("dem/disc_pos"), at_branch.at("dem/disc_pos"));
}

TEST(StateCopy, RefusedStateChangesNothing) {
  auto s = test::tank(0.2, 0.4, 0.01, 0.2, {0.1, 0.2}, 0.024, kCoupleDefault);
  s.sim->advance(0.02);
  CouplerState bad;
  s.sim->export_state(bad);
  bad.stones.disc_vel.pop_back();
  const auto before = s.sim->export_state();
  EXPECT_THROW(s.sim->import_state(bad), std::invalid_argument);
  EXPECT_EQ(test::state_hash(s.sim->export_state()), test::state_hash(before));
}

}  // namespace
}  // namespace vofdem
