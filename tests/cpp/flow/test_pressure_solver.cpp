#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <random>
#include <stdexcept>
#include <string>
#include <vector>

#include "vofdem/common/grid.h"
#include "vofdem/flow/pressure_solver.h"

using vofdem::Grid2D;
using vofdem::make_pressure_solver;
using vofdem::PressureProblem;
using vofdem::PressureSolverKind;

namespace {

constexpr PressureSolverKind kDirect = PressureSolverKind::kEigenDirect;
constexpr PressureSolverKind kMgcg = PressureSolverKind::kMultigridCG;
constexpr PressureSolverKind kAllKinds[] = {kDirect, kMgcg};

// finite-volume coefficients beta_f * face length / centre distance from a cell field beta [m^3 s/kg];
// faces next to inactive cells closed, boundary faces closed unless `open_top` (Dirichlet p = top_bc)
PressureProblem fv_problem(const Grid2D& g, const std::vector<double>& beta, const std::vector<std::uint8_t>& active,
                           const std::vector<std::uint8_t>& open_top, const std::vector<double>& top_bc) {
  PressureProblem pb;
  pb.resize(g);
  pb.cell_active = active;
  const int nx = g.nx(), nz = g.nz();
  auto face_beta = [&](int c0, int c1) { return 2.0 * beta[c0] * beta[c1] / (beta[c0] + beta[c1]); };
  for (int k = 0; k < nz; ++k)
    for (int i = 1; i < nx; ++i) {
      const int c0 = g.cell(i - 1, k), c1 = g.cell(i, k);
      if (active[c0] && active[c1]) pb.face_x_coef[g.face_x(i, k)] = face_beta(c0, c1) * g.dz(k) / g.dx();
    }
  for (int k = 1; k < nz; ++k)
    for (int i = 0; i < nx; ++i) {
      const int c0 = g.cell(i, k - 1), c1 = g.cell(i, k);
      if (active[c0] && active[c1])
        pb.face_z_coef[g.face_z(i, k)] = face_beta(c0, c1) * g.dx() / (g.z_center(k) - g.z_center(k - 1));
    }
  for (int i = 0; i < nx; ++i) {
    const int c = g.cell(i, nz - 1);
    if (open_top[i] && active[c]) {
      pb.face_z_coef[g.face_z(i, nz)] = beta[c] * g.dx() / (0.5 * g.dz(nz - 1));
      pb.face_z_bc[g.face_z(i, nz)] = top_bc[i];
    }
  }
  return pb;
}

struct RandomCase {
  Grid2D grid;
  PressureProblem problem;
  std::vector<double> rhs;
};

// a random two-phase problem: water (rho 1000) under a wavy free surface, air (rho 1) above, porous
// cells (n down to 1e-3), solid cells, a non-uniform z grid, some open top faces (or none: singular)
RandomCase random_case(std::mt19937& rng, int nx, int nz, double solid_fraction, double open_fraction) {
  std::uniform_real_distribution<double> u(0.0, 1.0);
  std::vector<double> zf(nz + 1, 0.0);
  for (int k = 1; k <= nz; ++k) zf[k] = zf[k - 1] + 0.01 * (0.5 + u(rng));
  Grid2D g(nx, 0.02, zf);
  const double h = g.height_z() * (0.3 + 0.4 * u(rng)), amp = 0.2 * h, wn = 2 + 6 * u(rng);
  std::vector<double> beta(g.ncell());
  std::vector<std::uint8_t> active(g.ncell(), 1);
  for (int k = 0; k < nz; ++k)
    for (int i = 0; i < nx; ++i) {
      const int c = g.cell(i, k);
      const double eta = h + amp * std::sin(wn * g.x_center(i) / g.length_x());
      const double rho = g.z_center(k) < eta ? 1000.0 : 1.0;
      const double n = u(rng) < 0.15 ? std::pow(10.0, -3.0 * u(rng)) : 1.0;
      beta[c] = 1e-3 * n / rho;
      if (u(rng) < solid_fraction) active[c] = 0;
    }
  std::vector<std::uint8_t> open(nx, 0);
  std::vector<double> bc(nx, 0.0);
  for (int i = 0; i < nx; ++i) {
    open[i] = u(rng) < open_fraction;
    bc[i] = 100.0 * (u(rng) - 0.5);
  }
  RandomCase rc{g, fv_problem(g, beta, active, open, bc), std::vector<double>(g.ncell())};
  for (int c = 0; c < g.ncell(); ++c) rc.rhs[c] = active[c] ? 1e-6 * (u(rng) - 0.5) : 0.0;
  return rc;
}

[[maybe_unused]] double max_abs_diff(const std::vector<double>& a, const std::vector<double>& b) {
  double m = 0.0;
  for (std::size_t j = 0; j < a.size(); ++j) m = std::max(m, std::abs(a[j] - b[j]));
  return m;
}

double max_abs(const std::vector<double>& a) {
  double m = 0.0;
  for (double v : a) m = std::max(m, std::abs(v));
  return m;
}

}  // namespace

TEST(PressureSolver, OneCellWithADirichletFace) {
  // a (p_bc - p) = b  ->  p = p_bc - b / a = 5 - 4 / 2 = 3
  const Grid2D g = Grid2D::uniform(1, 1, 1.0, 1.0);
  PressureProblem pb;
  pb.resize(g);
  pb.face_z_coef[g.face_z(0, 1)] = 2.0;
  pb.face_z_bc[g.face_z(0, 1)] = 5.0;
  for (auto kind : kAllKinds) {
    auto s = make_pressure_solver(kind);
    s->setup(g, pb);
    std::vector<double> p(1, 0.0);
    s->solve({4.0}, p, 1e-12);
    EXPECT_NEAR(p[0], 3.0, 1e-12);
  }
}

TEST(PressureSolver, TwoCellsByHand) {
  // cell 0: 1 (p1 - p0) + 2 (0 - p0) = 0; cell 1: 1 (p0 - p1) = 1  ->  p0 = -0.5, p1 = -1.5
  const Grid2D g = Grid2D::uniform(2, 1, 2.0, 1.0);
  PressureProblem pb;
  pb.resize(g);
  pb.face_x_coef[g.face_x(0, 0)] = 2.0;
  pb.face_x_coef[g.face_x(1, 0)] = 1.0;
  for (auto kind : kAllKinds) {
    auto s = make_pressure_solver(kind);
    s->setup(g, pb);
    std::vector<double> p(2, 0.0);
    s->solve({0.0, 1.0}, p, 1e-12);
    EXPECT_NEAR(p[0], -0.5, 1e-12);
    EXPECT_NEAR(p[1], -1.5, 1e-12);
  }
}

TEST(PressureSolver, SingularPairTakesTheCompatiblePartAndZeroMean) {
  // closed pair, a = 1: p1 - p0 = 1 from b = (1, -1); b = (2, 0) has the same compatible part
  const Grid2D g = Grid2D::uniform(1, 2, 1.0, 2.0);
  PressureProblem pb;
  pb.resize(g);
  pb.face_z_coef[g.face_z(0, 1)] = 1.0;
  for (auto kind : kAllKinds)
    for (const std::vector<double>& b : {std::vector<double>{1.0, -1.0}, std::vector<double>{2.0, 0.0}}) {
      auto s = make_pressure_solver(kind);
      s->setup(g, pb);
      std::vector<double> p(2, 7.0);
      s->solve(b, p, 1e-12);
      EXPECT_NEAR(p[0], -0.5, 1e-12);
      EXPECT_NEAR(p[1], 0.5, 1e-12);
    }
}

TEST(PressureSolver, InactiveCellsAreUntouchedAndIsolatedGroupsAreZero) {
  // 3 x 1: cell 0 open to p = 2 on the left, cell 1 solid, cell 2 closed on all sides (singular, p = 0)
  const Grid2D g = Grid2D::uniform(3, 1, 3.0, 1.0);
  PressureProblem pb;
  pb.resize(g);
  pb.cell_active[1] = 0;
  pb.face_x_coef[g.face_x(0, 0)] = 4.0;
  pb.face_x_bc[g.face_x(0, 0)] = 2.0;
  for (auto kind : kAllKinds) {
    auto s = make_pressure_solver(kind);
    s->setup(g, pb);
    std::vector<double> p = {0.0, 42.0, 9.0};
    s->solve({1.0, 5.0, 3.0}, p, 1e-12);
    EXPECT_NEAR(p[0], 2.0 - 1.0 / 4.0, 1e-12);
    EXPECT_EQ(p[1], 42.0);
    EXPECT_NEAR(p[2], 0.0, 1e-12);
  }
}

TEST(PressureSolver, AFaceOfNegligibleCoefficientCountsAsClosed) {
  // 3 x 1: cell 0 open to p = 2 on the left, joined to cells 1-2 through a face 1e-20 of the others
  // (porosity 1e-6 with its resistance): cells 1-2 solve as the closed pair they practically are
  const Grid2D g = Grid2D::uniform(3, 1, 3.0, 1.0);
  PressureProblem pb;
  pb.resize(g);
  pb.face_x_coef[g.face_x(0, 0)] = 4.0;
  pb.face_x_bc[g.face_x(0, 0)] = 2.0;
  pb.face_x_coef[g.face_x(1, 0)] = 1e-20;
  pb.face_x_coef[g.face_x(2, 0)] = 1.0;
  for (auto kind : kAllKinds) {
    auto s = make_pressure_solver(kind);
    s->setup(g, pb);
    std::vector<double> p(3, 0.0);
    s->solve({1.0, 1.0, -1.0}, p, 1e-12);
    EXPECT_NEAR(p[0], 2.0 - 1.0 / 4.0, 1e-12);
    EXPECT_NEAR(p[1], -0.5, 1e-12);  // the closed pair of SingularPairTakesTheCompatiblePartAndZeroMean
    EXPECT_NEAR(p[2], 0.5, 1e-12);
  }
  // a face at 1e-12 of its neighbours is kept: it still carries flux above round-off
  pb.face_x_coef[g.face_x(1, 0)] = 1e-12;
  auto s = make_pressure_solver(kDirect);
  s->setup(g, pb);
  std::vector<double> p(3, 0.0);
  s->solve({1.0, 1.0, -1.0}, p, 1e-12);
  EXPECT_GT(std::abs(p[1] + 0.5), 1.0);  // joined to cell 0: no longer the zero-mean pair
}

TEST(PressureSolver, RefusesBadInput) {
  const Grid2D g = Grid2D::uniform(3, 2, 3.0, 2.0);
  PressureProblem pb;
  pb.resize(g);
  pb.face_x_coef[g.face_x(1, 0)] = 1.0;
  auto s = make_pressure_solver(kDirect);
  PressureProblem bad = pb;
  bad.face_x_coef[g.face_x(2, 1)] = -1.0;
  EXPECT_THROW(s->setup(g, bad), std::invalid_argument);
  bad = pb;
  bad.cell_active[0] = 0;  // face (1, 0) now touches a solid cell
  EXPECT_THROW(s->setup(g, bad), std::invalid_argument);
  bad = pb;
  bad.face_z_coef.pop_back();
  EXPECT_THROW(s->setup(g, bad), std::invalid_argument);
  s->setup(g, pb);
  std::vector<double> p(g.ncell(), 0.0), rhs(g.ncell(), 0.0);
  EXPECT_THROW(s->solve(rhs, p, 0.0), std::invalid_argument);
  std::vector<double> short_p(2, 0.0);
  EXPECT_THROW(s->solve(rhs, short_p, 1e-8), std::invalid_argument);
}

// each kind of bad value, on interior and boundary faces of both directions, refused naming its field
// (the checks run row by row and, when one fails, again face by face for the message); a good problem
// after a refused one is set up as if none had been
TEST(PressureSolver, RefusesEachBadValueNamingItsField) {
  const Grid2D g = Grid2D::uniform(4, 3, 4.0, 3.0);
  PressureProblem pb;
  pb.resize(g);
  for (double& a : pb.face_x_coef) a = 1.0;
  for (double& a : pb.face_z_coef) a = 1.0;
  const double nan = std::numeric_limits<double>::quiet_NaN(), inf = std::numeric_limits<double>::infinity();
  struct Bad {
    const char* field;
    std::function<void(PressureProblem&)> make;
  };
  const std::vector<Bad> cases = {
      {"face_x_coef", [&](PressureProblem& q) { q.face_x_coef[g.face_x(2, 1)] = -1.0; }},
      {"face_x_coef", [&](PressureProblem& q) { q.face_x_coef[g.face_x(0, 2)] = nan; }},
      {"face_x_coef", [&](PressureProblem& q) { q.face_x_coef[g.face_x(4, 0)] = inf; }},
      {"face_z_coef", [&](PressureProblem& q) { q.face_z_coef[g.face_z(1, 3)] = -2.0; }},
      {"face_z_coef", [&](PressureProblem& q) { q.face_z_coef[g.face_z(3, 1)] = nan; }},
      {"face_x_coef", [&](PressureProblem& q) { q.cell_active[g.cell(1, 1)] = 0; }},  // open faces beside it
      {"face_z_coef", [&](PressureProblem& q) {
         for (int i = 0; i <= g.nx(); ++i) q.face_x_coef[g.face_x(i, 0)] = 0.0;
         q.cell_active[g.cell(2, 0)] = 0;
       }},
      {"face_x_bc", [&](PressureProblem& q) { q.face_x_bc[g.face_x(4, 1)] = nan; }},
      {"face_z_bc", [&](PressureProblem& q) { q.face_z_bc[g.face_z(2, 0)] = inf; }},
      {"cell_active", [&](PressureProblem& q) { q.cell_active[g.cell(3, 2)] = 2; }},
  };
  for (auto kind : kAllKinds) {
    auto s = make_pressure_solver(kind);
    std::vector<double> rhs(g.ncell(), 0.0), p_ref(g.ncell(), 0.0), p(g.ncell(), 0.0);
    rhs[0] = 1.0, rhs[g.ncell() - 1] = -1.0;
    s->setup(g, pb);
    s->solve(rhs, p_ref, 1e-12);
    for (const Bad& c : cases) {
      PressureProblem q = pb;
      c.make(q);
      try {
        s->setup(g, q);
        ADD_FAILURE() << c.field << ": no throw";
      } catch (const std::invalid_argument& e) {
        EXPECT_EQ(std::string(e.what()).rfind(c.field, 0), 0u) << c.field << ": " << e.what();
      }
      s->setup(g, pb);
      std::fill(p.begin(), p.end(), 0.0);
      s->solve(rhs, p, 1e-12);
      EXPECT_EQ(p, p_ref) << "after " << c.field;
    }
  }
}

TEST(PressureSolver, DirectSolutionSatisfiesTheEquationsOnRandomProblems) {
  std::mt19937 rng(7);
  for (int trial = 0; trial < 6; ++trial) {
    RandomCase rc = random_case(rng, 9 + 4 * trial, 5 + 3 * trial, 0.05, trial == 0 ? 0.0 : 0.3);
    auto s = make_pressure_solver(kDirect);
    s->setup(rc.grid, rc.problem);
    std::vector<double> p(rc.grid.ncell(), 0.0), r;
    const auto st = s->solve(rc.rhs, p, 1e-9);
    EXPECT_LT(st.residual, 1e-9);
    if (trial > 0) {
      // b - A p = 0 up to round-off relative to the size of the terms
      vofdem::pressure_residual(rc.grid, rc.problem, rc.rhs, p, r);
      EXPECT_LT(max_abs(r), 1e-9 * max_abs(rc.rhs) + 1e-12);
    }
  }
}

TEST(PressureSolver, MultigridCGAgreesWithTheDirectSolverOnRandomProblems) {
  // two-phase (1000:1), porous (n >= 1e-3), solid cells, graded z, odd sizes, singular boxes
  struct Size {
    int nx, nz;
    double solid, open;
  };
  const Size sizes[] = {{23, 17, 0.05, 0.3}, {40, 13, 0.1, 0.0}, {61, 29, 0.02, 1.0},
                        {100, 35, 0.05, 0.3}, {7, 50, 0.0, 0.5}, {3, 2, 0.0, 0.0}};
  std::mt19937 rng(11);
  for (const Size& sz : sizes) {
    RandomCase rc = random_case(rng, sz.nx, sz.nz, sz.solid, sz.open);
    auto d = make_pressure_solver(kDirect);
    auto m = make_pressure_solver(kMgcg);
    d->setup(rc.grid, rc.problem);
    m->setup(rc.grid, rc.problem);
    std::vector<double> pd(rc.grid.ncell(), 0.0), pm(rc.grid.ncell(), 0.0);
    d->solve(rc.rhs, pd, 1e-9);
    const auto st = m->solve(rc.rhs, pm, 1e-12);
    EXPECT_LE(st.residual, 1e-12);
    EXPECT_LT(max_abs_diff(pd, pm), 1e-8 * max_abs(pd)) << sz.nx << " x " << sz.nz;
  }
}

TEST(PressureSolver, MultigridCGIterationsHardlyGrowWithTheGrid) {
  // the same two-phase flume at 64^2 and 256^2 cells: a grid-independent preconditioner keeps the
  // iteration count within a few
  auto iterations = [](int n) {
    const Grid2D g = Grid2D::uniform(n, n, 1.0, 1.0);
    std::vector<double> beta(g.ncell());
    std::vector<std::uint8_t> active(g.ncell(), 1), open(n, 1);
    for (int k = 0; k < n; ++k)
      for (int i = 0; i < n; ++i) {
        // dam-break-like: a water column on the left, a thin layer on the right
        const bool water = g.x_center(i) < 0.4 ? g.z_center(k) < 0.6 : g.z_center(k) < 0.1;
        beta[g.cell(i, k)] = water ? 1e-3 : 1.0;
      }
    PressureProblem pb = fv_problem(g, beta, active, open, std::vector<double>(n, 0.0));
    std::vector<double> rhs(g.ncell()), p(g.ncell(), 0.0);
    for (int c = 0; c < g.ncell(); ++c) rhs[c] = std::sin(0.37 * c) * g.dx() * g.dx();
    auto m = make_pressure_solver(kMgcg);
    m->setup(g, pb);
    return m->solve(rhs, p, 1e-8).iterations;
  };
  const int it64 = iterations(64), it256 = iterations(256);
  EXPECT_LE(it64, 20);
  EXPECT_LE(it256, it64 + 4) << "64^2: " << it64 << ", 256^2: " << it256;
}

TEST(PressureSolver, ManufacturedSolutionConvergesAtSecondOrder) {
  // p = cos(pi x / L) cosh(pi z / L) solves div grad p = 0 with dp/dn = 0 on the sides and the bed;
  // p is imposed on the open top; the z spacing is graded smoothly (z = H (e^{a s} - 1) / (e^a - 1)).
  // Max errors 3.0e-2, 9.3e-3, 2.6e-3, 6.7e-4 on 16x8 .. 128x64 (orders 1.70, 1.86, 1.93): the
  // asymptotic order, from 32x16 on, is checked
  const double pi = 3.14159265358979323846, L = 1.0, H = 0.5, a = 1.5;
  auto exact = [&](double x, double z) { return std::cos(pi * x / L) * std::cosh(pi * z / L); };
  std::vector<double> err;
  for (int n : {16, 32, 64}) {
    std::vector<double> zf(n + 1);
    for (int k = 0; k <= n; ++k) zf[k] = H * (std::exp(a * k / double(n)) - 1.0) / (std::exp(a) - 1.0);
    const Grid2D g(2 * n, L / (2 * n), zf);
    std::vector<double> beta(g.ncell(), 1.0), top(g.nx());
    for (int i = 0; i < g.nx(); ++i) top[i] = exact(g.x_center(i), H);
    PressureProblem pb = fv_problem(g, beta, std::vector<std::uint8_t>(g.ncell(), 1),
                                    std::vector<std::uint8_t>(g.nx(), 1), top);
    for (auto kind : kAllKinds) {
      auto s = make_pressure_solver(kind);
      s->setup(g, pb);
      std::vector<double> p(g.ncell(), 0.0);
      s->solve(std::vector<double>(g.ncell(), 0.0), p, 1e-12);
      double e = 0.0;
      for (int k = 0; k < g.nz(); ++k)
        for (int i = 0; i < g.nx(); ++i)
          e = std::max(e, std::abs(p[g.cell(i, k)] - exact(g.x_center(i), g.z_center(k))));
      if (kind == kDirect)
        err.push_back(e);
      else  // the iterative solver reaches the same discrete solution
        EXPECT_NEAR(e, err.back(), 1e-9);
    }
  }
  for (std::size_t j = 1; j < err.size(); ++j) {
    const double order = std::log2(err[j - 1] / err[j]);
    EXPECT_GT(order, 1.8) << "refinement " << j << ": errors " << err[j - 1] << " -> " << err[j];
  }
  EXPECT_LT(err.back(), 1e-3);
}

TEST(PressureSolver, NonConvergenceThrowsAndLeavesPUntouched) {
  std::mt19937 rng(5);
  RandomCase rc = random_case(rng, 64, 32, 0.02, 0.5);
  vofdem::PressureSolverParams prm;
  prm.max_iterations = 1;
  auto m = make_pressure_solver(kMgcg, prm);
  m->setup(rc.grid, rc.problem);
  std::vector<double> p(rc.grid.ncell(), 1.0);
  try {
    m->solve(rc.rhs, p, 1e-10);
    FAIL() << "expected std::runtime_error";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("no convergence after 1 iterations"), std::string::npos) << e.what();
  }
  EXPECT_EQ(p, std::vector<double>(rc.grid.ncell(), 1.0));
}

TEST(PressureSolver, MultigridCGIsDeterministicReusesItsHierarchyAndWarmStarts) {
  std::mt19937 rng(9);
  RandomCase a = random_case(rng, 50, 21, 0.03, 0.4);
  RandomCase b = random_case(rng, 50, 21, 0.03, 0.4);
  auto reused = make_pressure_solver(kMgcg);
  reused->setup(a.grid, a.problem);
  std::vector<double> pa(a.grid.ncell(), 0.0);
  reused->solve(a.rhs, pa, 1e-10);
  // new coefficients on the same grid: same answer as a fresh solver, bit for bit
  reused->setup(b.grid, b.problem);
  auto fresh = make_pressure_solver(kMgcg);
  fresh->setup(b.grid, b.problem);
  std::vector<double> p1(b.grid.ncell(), 0.0), p2(b.grid.ncell(), 0.0);
  const auto s1 = reused->solve(b.rhs, p1, 1e-10);
  fresh->solve(b.rhs, p2, 1e-10);
  EXPECT_EQ(p1, p2);
  // the converged answer as the initial guess needs (almost) no iteration
  const auto s3 = fresh->solve(b.rhs, p2, 1e-8);
  EXPECT_LE(s3.iterations, 1);
  EXPECT_GT(s1.iterations, 3);
  // closing the top makes the box singular: the reused solvers must notice the new groups
  PressureProblem closed = b.problem;
  for (int i = 0; i < b.grid.nx(); ++i) closed.face_z_coef[b.grid.face_z(i, b.grid.nz())] = 0.0;
  for (auto kind : kAllKinds) {
    auto s = make_pressure_solver(kind);
    s->setup(b.grid, b.problem);
    s->setup(b.grid, closed);
    auto f = make_pressure_solver(kind);
    f->setup(b.grid, closed);
    std::vector<double> q1(b.grid.ncell(), 0.0), q2(b.grid.ncell(), 0.0);
    s->solve(b.rhs, q1, 1e-10);
    f->solve(b.rhs, q2, 1e-10);
    EXPECT_EQ(q1, q2);
  }
}

TEST(PressureSolver, ASingularGroupConvergesWhateverTheMeanOfItsSource) {
  // a closed box: the source's mean is removed (PressureSystem::source); a single removal leaves a mean
  // of its round-off, eps x the mean removed, that no iteration reduces (the multigrid CG stalled at
  // 6.4e-10 > tol 1e-10 for a mean 1e6 times the source's spread) and that the direct solver's pinned
  // cell turns into a point source. Every shift has the answer of the source without it, to the
  // rounding of the shifted input itself.
  std::mt19937 rng(9);
  RandomCase b = random_case(rng, 50, 21, 0.03, 0.4);
  PressureProblem closed = b.problem;
  for (int i = 0; i < b.grid.nx(); ++i) closed.face_z_coef[b.grid.face_z(i, b.grid.nz())] = 0.0;
  std::vector<double> ref(b.grid.ncell(), 0.0);
  auto direct = make_pressure_solver(kDirect);
  direct->setup(b.grid, closed);
  direct->solve(b.rhs, ref, 1e-12);
  for (auto kind : kAllKinds) {
    auto s = make_pressure_solver(kind);
    s->setup(b.grid, closed);
    for (double shift : {0.0, 1.0, 1e3}) {
      std::vector<double> rhs = b.rhs;
      for (double& v : rhs) v += shift;
      std::vector<double> p(b.grid.ncell(), 0.0);
      EXPECT_LE(s->solve(rhs, p, 1e-10).residual, 1e-10) << "shift " << shift;
      // the source's spread is 1e-6 (random_case): adding the shift rounds it by about eps x shift
      const double floor = 2.0 * std::numeric_limits<double>::epsilon() * shift / 1e-6;
      EXPECT_LE(max_abs_diff(p, ref), (1e-9 + floor) * max_abs(ref)) << "shift " << shift;
    }
  }
}

TEST(PressureSolver, MultigridCGHandlesAnisotropicCellsBothWays) {
  // cells 10x wider than tall (z lines) and 10x taller than wide (x lines), two-phase
  for (double ratio : {0.1, 10.0}) {
    const int nx = 96, nz = 48;
    const Grid2D g = Grid2D::uniform(nx, nz, ratio * nx, 1.0 * nz);
    std::vector<double> beta(g.ncell());
    for (int k = 0; k < nz; ++k)
      for (int i = 0; i < nx; ++i) beta[g.cell(i, k)] = g.z_center(k) < 0.3 * nz ? 1e-3 : 1.0;
    PressureProblem pb = fv_problem(g, beta, std::vector<std::uint8_t>(g.ncell(), 1),
                                    std::vector<std::uint8_t>(nx, 1), std::vector<double>(nx, 0.0));
    std::vector<double> rhs(g.ncell()), p(g.ncell(), 0.0);
    for (int c = 0; c < g.ncell(); ++c) rhs[c] = std::sin(0.37 * c);
    auto m = make_pressure_solver(kMgcg);
    m->setup(g, pb);
    EXPECT_LE(m->solve(rhs, p, 1e-8).iterations, 16) << "dx / dz = " << ratio;
  }
}

TEST(PressureSolver, MultigridCGWithLinesAlongXAgreesWithTheDirectSolver) {
  // cells 10x taller than wide: every level relaxes lines along x, four rows of a parity at a time and
  // the rest one by one (row counts of each remainder 0-3); the same solution as the direct solver and
  // the iteration count of a good preconditioner
  for (int nz : {2, 5, 9, 14, 23, 31}) {
    const int nx = 40;
    const Grid2D g = Grid2D::uniform(nx, nz, 0.1 * nx, 1.0 * nz);
    std::vector<double> beta(g.ncell());
    for (int k = 0; k < nz; ++k)
      for (int i = 0; i < nx; ++i) beta[g.cell(i, k)] = g.z_center(k) < 0.4 * nz ? 1e-3 : 1.0;
    PressureProblem pb = fv_problem(g, beta, std::vector<std::uint8_t>(g.ncell(), 1),
                                    std::vector<std::uint8_t>(nx, 1), std::vector<double>(nx, 0.0));
    std::vector<double> rhs(g.ncell());
    for (int c = 0; c < g.ncell(); ++c) rhs[c] = std::sin(0.37 * c);
    auto d = make_pressure_solver(kDirect);
    auto m = make_pressure_solver(kMgcg);
    d->setup(g, pb);
    m->setup(g, pb);
    std::vector<double> pd(g.ncell(), 0.0), pm(g.ncell(), 0.0);
    d->solve(rhs, pd, 1e-12);
    EXPECT_LE(m->solve(rhs, pm, 1e-12).iterations, 24) << "nz = " << nz;
    EXPECT_LT(max_abs_diff(pd, pm), 1e-9 * max_abs(pd)) << "nz = " << nz;
  }
}
