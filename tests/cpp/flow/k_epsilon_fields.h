// What the tests of the k-epsilon schemes share (test_k_epsilon.cpp, test_k_epsilon_lines.cpp,
// test_k_epsilon_alternating.cpp): the fields a flow solver hands the model, the check that k, eps and
// nu_t stay finite and at or above their floors, and the stress run of huge steps under random strain.
#pragma once

#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <vector>

#include "vofdem/common/grid.h"
#include "vofdem/flow/k_epsilon.h"

namespace vofdem::test {

inline constexpr double kNuWater = 1e-6;  // water [m^2/s]

// the fields a flow solver hands to the model: at rest, open cells full of water
struct KEpsilonFlow {
  std::vector<double> face_u, face_w, porosity, F, nu;
  explicit KEpsilonFlow(const Grid2D& g)
      : face_u(g.nface_x(), 0.0), face_w(g.nface_z(), 0.0), porosity(g.ncell(), 1.0), F(g.ncell(), 1.0),
        nu(g.ncell(), kNuWater) {}
};

inline void expect_all_positive_finite(const KEpsilonModel& m) {
  const KEpsilonParams& p = m.params();
  for (std::size_t c = 0; c < m.cell_k.size(); ++c) {
    ASSERT_TRUE(std::isfinite(m.cell_k[c]) && m.cell_k[c] >= p.k_min) << "k[" << c << "] = " << m.cell_k[c];
    ASSERT_TRUE(std::isfinite(m.cell_eps[c]) && m.cell_eps[c] >= p.eps_min) << "eps[" << c << "] = " << m.cell_eps[c];
    ASSERT_TRUE(std::isfinite(m.cell_nut[c]) && m.cell_nut[c] >= 0.0) << "nut[" << c << "] = " << m.cell_nut[c];
  }
}

// ten steps of dt [s] of a model of p on g from k and eps drawn over 15 decades, each under a new random
// field: velocities of +-100 m/s far from divergence-free, solid, porous and air cells; check(m) after
// every step (its fatal failure ends the run)
template <class Check>
void run_random_strain(const Grid2D& g, const KEpsilonParams& p, double dt, std::mt19937& rng, Check&& check) {
  std::uniform_real_distribution<double> vel(-100.0, 100.0), unit(0.0, 1.0), expo(-12.0, 3.0);
  KEpsilonModel m(g, p, KEpsilonBoundaries{});
  for (int c = 0; c < g.ncell(); ++c) {
    m.cell_k[c] = std::pow(10.0, expo(rng));
    m.cell_eps[c] = std::pow(10.0, expo(rng));
  }
  KEpsilonFlow f(g);
  for (int st = 0; st < 10; ++st) {
    for (double& u : f.face_u) u = vel(rng);
    for (double& w : f.face_w) w = vel(rng);
    for (int c = 0; c < g.ncell(); ++c) {
      const double r = unit(rng);
      f.porosity[c] = r < 0.1 ? 0.0 : (r < 0.4 ? 0.3 + 0.7 * unit(rng) : 1.0);
      f.F[c] = unit(rng) < 0.2 ? 0.0 : unit(rng);
    }
    ASSERT_NO_THROW(m.step(dt, f.face_u, f.face_w, f.porosity, f.F, f.nu));
    check(m);
    if (::testing::Test::HasFatalFailure()) return;
  }
}

}  // namespace vofdem::test
