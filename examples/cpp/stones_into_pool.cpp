// Six stones dropped into a pool, two-way coupled, with the C++ library alone.
//
// A 0.4 m x 0.5 m tank of 1 cm cells holds 0.25 m of water; six 4.8 cm stones (density 2650) fall from
// above it, sink and pile on the bed while the porosity follows them. Prints the time, the water
// volume (kept to round-off), the lowest stone and the fluid forces, then the per-stage costs.
#include <cmath>
#include <cstdio>
#include <vector>

#include "vofdem/coupling/coupler.h"

int main() {
  using namespace vofdem;
  const Grid2D grid = Grid2D::uniform(40, 50, 0.4, 0.5);
  FlowParams flow;                      // the scenes' flow model (k-epsilon, CFL 0.5), in a closed tank:
  flow.outlet = OutletBoundary::kWall;  // no outflow at x = 0.4 m (the default is a free overfall)
  flow.pressure_tol = 1e-8;             // the projection's tolerance that keeps the water volume to round-off
  flow.flags |= kFlowRelativeVelocity;  // the porous resistance on the water's velocity relative to the stones
  VOFGrid fluid(grid, flow);
  fluid.fill_water_below(0.25);
  fluid.set_hydrostatic_pressure();

  DEMParams dem;
  dem.submerged = true;  // wet from the start (the Coupler hands the stones the flow's medium)
  dem.add_flume(0.0, 0.4, 0.0);
  std::vector<double> pos, radius, density;
  for (int j = 0; j < 6; ++j) {
    pos.push_back(0.12 + 0.06 * (j % 3) + 0.003 * j);
    pos.push_back(0.32 + 0.06 * (j / 3));
    radius.push_back(0.024);
    density.push_back(2650.0);
  }
  DEMSystem stones(dem, pos, radius, density);

  CouplerParams params;  // two-way coupling: porosity, drag, pressure gradient, wet fraction
  Coupler sim(&fluid, &stones, params);
  const double v0 = sim.water_volume();
  std::printf("   t [s]   water volume error   lowest stone z [m]   drag z [N]   pressure z [N]\n");
  long long steps = 0;
  for (int q = 1; q <= 8; ++q) {
    sim.advance(0.1 * q, [&steps](double) { ++steps; });  // progress callback after every step
    int low = 0;
    for (int j = 1; j < stones.n(); ++j)
      if (stones.stone_pos[2 * j + 1] < stones.stone_pos[2 * low + 1]) low = j;
    std::printf("%8.3f   %18.2e   %18.4f   %10.4f   %14.4f\n", sim.time(), (sim.water_volume() - v0) / v0,
                stones.stone_pos[2 * low + 1], sim.stone_force_drag[2 * low + 1], sim.stone_force_pressure[2 * low + 1]);
  }
  std::printf("\n%lld coupling steps\nstage          seconds      calls\n", steps);
  const StageProfile& p = sim.profile();
  for (std::size_t s = 0; s < p.names().size(); ++s)
    std::printf("%-12s %9.4f %10lld\n", p.names()[s].c_str(), p.seconds()[s], p.calls()[s]);
  const double err = std::abs(sim.water_volume() - v0) / v0;
  return err < 1e-9 ? 0 : 1;
}
