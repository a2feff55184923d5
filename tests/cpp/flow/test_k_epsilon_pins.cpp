// The k-epsilon schemes pinned: hashes of k, eps, nu_t and the wall shear after a few steps of each
// transport scheme (point-implicit with and without sweeps, vertical lines, alternating lines) on a
// random field with every effect on (advection, diffusion, production, wall functions), porous, solid
// and air cells, an inflow side and a wall bed. Taken before the schemes' shared per-cell code was
// factored out (start values, sources and sinks, row resets): a change of any bit fails these tests.
#include <gtest/gtest.h>

#include <cstdint>
#include <map>
#include <random>
#include <string>
#include <vector>

#include "common/pin_hash.h"
#include "vofdem/common/grid.h"
#include "vofdem/flow/k_epsilon.h"
#include "common/pinned_params.h"

using vofdem::Grid2D;
using vofdem::KEpsilonBoundaries;
using vofdem::KEpsilonBoundary;
using vofdem::KEpsilonModel;
using vofdem::KEpsilonParams;
using vofdem::test::pinned_k_epsilon_params;
using vofdem::KEpsilonTimeScheme;

namespace {

// the state after `steps` steps of dt [s] of one scheme on the random field, as named arrays
std::map<std::string, std::vector<double>> pinned_run(KEpsilonTimeScheme scheme, int sweeps, int steps, double dt) {
  const Grid2D g = Grid2D::graded(9, 0.9, 0.08, 0.02, 0.01, 0.02);
  KEpsilonBoundaries b;
  b.left = KEpsilonBoundary::kInflow;
  b.right = KEpsilonBoundary::kZeroGradient;
  b.bottom = KEpsilonBoundary::kWall;
  b.top = KEpsilonBoundary::kZeroGradient;
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  const int n = g.ncell();
  std::vector<double> u(g.nface_x(), 0.0), w(g.nface_z(), 0.0), porosity(n, 1.0), F(n, 1.0), nu(n, 1e-6);
  for (int c = 0; c < n; ++c) porosity[c] = unit(rng) < 0.3 ? 0.3 + 0.3 * unit(rng) : 1.0;
  porosity[g.cell(4, 1)] = 0.0;
  // the top row partly air, partly a free surface
  for (int i = 0; i < g.nx(); ++i) F[g.cell(i, g.nz() - 1)] = i % 3 == 0 ? 0.05 : 0.6;
  for (int k = 0; k < g.nz(); ++k)
    for (int i = 0; i <= g.nx(); ++i) u[g.face_x(i, k)] = 0.3 * (0.5 + unit(rng));
  for (int k = 1; k < g.nz(); ++k)
    for (int i = 0; i < g.nx(); ++i) w[g.face_z(i, k)] = 0.1 * (unit(rng) - 0.5);
  KEpsilonParams p = pinned_k_epsilon_params();
  p.time_scheme = scheme;
  p.sweeps = sweeps;
  p.bed_roughness = 0.01;
  KEpsilonModel m(g, p, b);
  m.initialize(1e-4, 1e-5, 1e-6);
  for (int s = 0; s < steps; ++s) m.step(dt, u, w, porosity, F, nu);
  return {{"cell_k", m.cell_k},
          {"cell_eps", m.cell_eps},
          {"cell_nut", m.cell_nut},
          {"face_x_wall_shear", m.face_x_wall_shear},
          {"face_z_wall_shear", m.face_z_wall_shear}};
}

}  // namespace

TEST(KEpsilonPins, PointImplicitPredictorAlone) {
  // every cell below its explicit limit (the inflow faces' dt a <= 0.01)
  const auto state = pinned_run(KEpsilonTimeScheme::kPointImplicit, 0, 6, 2e-3);
  EXPECT_EQ(vofdem::test::state_hash(state), 13486846820423108389ull);
}

TEST(KEpsilonPins, PointImplicitWithSweeps) {
  // dt a = 0.45-1.35 against n = 0.3-1: cells below and above their explicit limit
  const auto state = pinned_run(KEpsilonTimeScheme::kPointImplicit, 3, 6, 0.3);
  EXPECT_EQ(vofdem::test::state_hash(state), 2562272824920431704ull);
}

TEST(KEpsilonPins, VerticalLines) {
  // cells below and above the horizontal faces' limit: both branches of the row assembly
  const auto state = pinned_run(KEpsilonTimeScheme::kVerticalLines, 1, 6, 0.3);
  EXPECT_EQ(vofdem::test::state_hash(state), 15532480422466328765ull);
}

TEST(KEpsilonPins, AlternatingLines) {
  const auto state = pinned_run(KEpsilonTimeScheme::kAlternatingLines, 1, 6, 0.3);
  EXPECT_EQ(vofdem::test::state_hash(state), 2417601373062599029ull);
}
