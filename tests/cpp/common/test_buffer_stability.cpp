// The arrays behind the Python views keep their buffers (bindings/views.h): set_params, building and
// freeing a Coupler, stepping, a guard's restore and a checkpoint's import write in place. Each held
// pointer is also read after the operations, so a buffer freed behind it is a heap-use-after-free under
// the sanitizer build (scripts/test_cpp.sh).
#include <gtest/gtest.h>

#include <algorithm>
#include <map>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include "common/coupler_scenes.h"
#include "common/pinned_params.h"

namespace vofdem {
namespace {

using Buffers = std::map<std::string, const void*>;

Buffers fluid_buffers(VOFGrid& f) {
  return {{"face_u", f.face_u.data()},
          {"face_w", f.face_w.data()},
          {"cell_p", f.cell_p.data()},
          {"cell_F", f.cell_F.data()},
          {"cell_porosity", f.cell_porosity.data()},
          {"face_x_porosity", f.face_x_porosity.data()},
          {"face_z_porosity", f.face_z_porosity.data()},
          {"cell_stone_diameter", f.cell_stone_diameter.data()},
          {"cell_nut", f.cell_nut.data()},
          {"cell_k", f.turbulence().cell_k.data()},
          {"cell_eps", f.turbulence().cell_eps.data()},
          {"face_x_solid_u", f.face_x_solid_u.data()},
          {"face_z_solid_w", f.face_z_solid_w.data()}};
}

Buffers stone_buffers(DEMSystem& s) {
  return {{"stone_pos", s.stone_pos.data()},         {"stone_vel", s.stone_vel.data()},
          {"stone_angle", s.stone_angle.data()},     {"stone_omega", s.stone_omega.data()},
          {"stone_radius", s.stone_radius.data()},   {"stone_density", s.stone_density.data()},
          {"stone_fixed", s.stone_fixed.data()},     {"stone_active", s.stone_active.data()},
          {"stone_force_ext", s.stone_force_ext.data()}, {"stone_drag_coef", s.stone_drag_coef.data()},
          {"stone_drag_vel", s.stone_drag_vel.data()},   {"stone_wet", s.stone_wet.data()},
          {"stone_water_level", s.stone_water_level.data()}, {"stone_force", s.stone_force.data()},
          {"stone_torque", s.stone_torque.data()},   {"stone_acc", s.stone_acc.data()},
          {"stone_alpha", s.stone_alpha.data()},     {"stone_asleep", s.stone_asleep.data()}};
}

// the names of the held pointers that are no longer the owner's ("" when none)
std::string moved(const Buffers& held, const Buffers& now) {
  std::string out;
  for (const auto& [name, p] : held)
    if (now.at(name) != p) out += name + " ";
  return out;
}

TEST(BufferStability, ViewsOfFlowAndStonesSurviveEveryOperation) {
  const Grid2D g = Grid2D::uniform(20, 40, 0.2, 0.4);
  auto fluid = std::make_unique<VOFGrid>(g, test::pinned_flow_params());
  fluid->fill_water_below(0.2);
  fluid->set_hydrostatic_pressure();
  const std::vector<double> pos = {0.1, 0.2, 0.102, 0.25, 0.104, 0.3};
  DEMSystem stones(test::wet_dem(0.0, 0.2), pos, std::vector<double>(3, 0.024), std::vector<double>(3, 2650.0));
  const Buffers flow0 = fluid_buffers(*fluid), stones0 = stone_buffers(stones);
  const double* k = fluid->turbulence().cell_k.data();
  const double* n = fluid->cell_porosity.data();
  auto expect_held = [&](const char* after) {
    EXPECT_EQ(moved(flow0, fluid_buffers(*fluid)), "") << after;
    EXPECT_EQ(moved(stones0, stone_buffers(stones)), "") << after;
    EXPECT_EQ(k[0], fluid->turbulence().cell_k[0]) << after;
    EXPECT_EQ(n[0], fluid->cell_porosity[0]) << after;
  };

  FlowParams fp = fluid->params();
  fp.flags |= kFlowTurbulence;
  fp.pressure_solver = PressureSolverKind::kEigenDirect;
  fluid->set_params(fp);
  expect_held("VOFGrid::set_params");
  {
    test::resist_relative_to_stones(*fluid);
    Coupler sim(fluid.get(), &stones, CouplerParams());
    expect_held("Coupler()");
    sim.advance(0.03);
    expect_held("Coupler::advance");
    double n_min = 1.0;
    for (std::size_t c = 0; c < fluid->cell_porosity.size(); ++c) n_min = std::min(n_min, n[c]);
    EXPECT_LT(n_min, 0.9);  // the held pointer shows the stones' porosity
    const auto state = sim.export_state();
    sim.advance(0.06);
    sim.import_state(state);
    expect_held("Coupler::import_state");
    CouplerParams cp = sim.params();
    cp.flags |= kCoupleLookupPorosity;  // a new porosity mapper
    sim.set_params(cp);
    expect_held("Coupler::set_params");
    FlowParams rel = fluid->params();
    rel.flags &= ~kFlowRelativeVelocity;
    fluid->set_params(rel);
    expect_held("VOFGrid::set_params of the relative velocity");
  }
  expect_held("~Coupler");
  EXPECT_THROW(fluid->step(10.0), std::runtime_error);  // the guard restores the step's start
  expect_held("VOFGrid guard");
  stones.import_state(stones.export_state());
  DEMParams dp = stones.params();
  dp.friction_stone = 0.5;
  stones.set_params(dp);
  fluid->advance(fluid->time() + 0.01);
  stones.advance(0.01);
  expect_held("stepping alone");
}

}  // namespace
}  // namespace vofdem
