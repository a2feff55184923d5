// The flow parameters the C++ tests were written and pinned with. The core's defaults are the scenes'
// (python/vofdem/scene.py; tests/test_option_defaults.py checks them); these tests set the older values
// explicitly so that what each test computes, and every pin, stays what it was.
#pragma once

#include "vofdem/flow/k_epsilon.h"
#include "vofdem/flow/vof_grid.h"

namespace vofdem::test {

// k-epsilon point-implicit (every face explicit), the scheme the k-epsilon tests were written for
inline KEpsilonParams pinned_k_epsilon_params() {
  KEpsilonParams p;
  p.time_scheme = KEpsilonTimeScheme::kPointImplicit;
  return p;
}

// CFL 0.4, pressure tolerance 1e-8, laminar, closed outlet, k-epsilon point-implicit when switched on
inline FlowParams pinned_flow_params() {
  FlowParams p;
  p.cfl = 0.4;
  p.pressure_tol = 1e-8;
  p.flags = kFlowFreeSurface | kFlowPorousResistance | kFlowViscosity | kFlowGravity | kFlowConvection;
  p.outlet = OutletBoundary::kWall;
  p.turbulence = pinned_k_epsilon_params();
  return p;
}

}  // namespace vofdem::test
