// Small coupled scenes shared by the coupler's tests (tank, falling stones, bed pocket).
#pragma once

#include <cmath>
#include <cstring>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "vofdem/coupling/coupler.h"
#include "common/pinned_params.h"

namespace vofdem::test {

// two exported states hold the same keys and the same bits; else the first key that differs
inline bool same_bits(const std::map<std::string, std::vector<double>>& a,
                      const std::map<std::string, std::vector<double>>& b, std::string* first_diff) {
  if (a.size() != b.size()) return *first_diff = "entry count", false;
  for (const auto& kv : a) {
    auto it = b.find(kv.first);
    if (it == b.end() || it->second.size() != kv.second.size() ||
        (!kv.second.empty() &&
        std::memcmp(kv.second.data(), it->second.data(), kv.second.size() * sizeof(double)) != 0))
      return *first_diff = kv.first, false;
  }
  return true;
}

struct Scene {
  std::unique_ptr<VOFGrid> fluid;
  std::unique_ptr<DEMSystem> stones;
  std::unique_ptr<Coupler> sim;
};

inline DEMParams wet_dem(double x0, double x1) {
  DEMParams p;
  p.submerged = true;
  p.medium.rho_water = test::pinned_flow_params().medium.rho_water;
  p.add_flume(x0, x1, 0.0);
  return p;
}

// the porous resistance on the velocity relative to the stones: the flow's own flag, set on the built
// flow (set_params) right before the Coupler, as the scenes' pinned runs had it
inline void resist_relative_to_stones(VOFGrid& f) {
  FlowParams p = f.params();
  if (p.flags & kFlowRelativeVelocity) return;
  p.flags |= kFlowRelativeVelocity;
  f.set_params(p);
}

// a tank width x height [m] of square cells h [m], water below `level` [m], stones at pos (x, z pairs)
// of radius r [m] (density 2650); a two-way coupling (kCouplePorosity) resists relative to the stones
inline Scene tank(double width, double height, double h, double level, const std::vector<double>& pos, double r,
                  unsigned flags, const FlowParams& fp = test::pinned_flow_params()) {
  Scene s;
  const Grid2D g = Grid2D::uniform(static_cast<int>(std::lround(width / h)), static_cast<int>(std::lround(height / h)),
                                   width, height);
  s.fluid = std::make_unique<VOFGrid>(g, fp);
  // the stone diameter of the cells without stones the pins were taken with (the core's former
  // default, now given): it enters no porous cell here, only the exported state
  s.fluid->cell_stone_diameter.assign(s.fluid->cell_stone_diameter.size(), 0.048);
  s.fluid->fill_water_below(level);
  s.fluid->set_hydrostatic_pressure();
  const std::size_t n = pos.size() / 2;
  s.stones = std::make_unique<DEMSystem>(wet_dem(0.0, width), pos, std::vector<double>(n, r),
                                         std::vector<double>(n, 2650.0));
  if ((flags & kCouplePorosity) && n > 0) resist_relative_to_stones(*s.fluid);
  CouplerParams cp;
  cp.flags = flags;
  s.sim = std::make_unique<Coupler>(s.fluid.get(), s.stones.get(), cp);
  return s;
}

// the drag held over the step (explicit exchange, drag_relaxation 1e-3) and stone 0 moving at 0.3 m/s
// through the still water, its forces exchanged; returns its mass with the added mass [kg], M + M' of
// the drag's relaxation time (M + M') / slope
inline double hold_the_drag_of_a_moving_stone(Scene& s) {
  CouplerParams cp = s.sim->params();
  cp.implicit_drag = false;
  cp.drag_relaxation = 1e-3;
  s.sim->set_params(cp);
  s.stones->stone_vel[0] = 0.3;
  s.sim->update_fluid_forces();
  const DEMParams& dp = s.stones->params();
  const double rho = s.fluid->params().medium.rho_water, w = s.stones->stone_wet[0];
  const bool added = (dp.flags & kDEMAddedMass) && dp.water_density() > 0.0;
  return s.stones->mass(0) + (added ? rho * dp.added_mass_coefficient * s.stones->volume(0) * w : 0.0);
}

// terminal velocity [m/s] of the force balance 1/2 rho A (0.4 v^2 + 24 nu v / d) = (rho_s - rho) V g
inline double terminal_velocity(double d, double rho_s, double rho, double nu, double g) {
  const double a = 0.5 * rho * M_PI * d * d / 4.0, w = (rho_s - rho) * M_PI * d * d * d / 6.0 * g;
  const double A = 0.4 * a, B = a * 24.0 * nu / d;
  return (-B + std::sqrt(B * B + 4.0 * A * w)) / (2.0 * A);
}

}  // namespace vofdem::test
