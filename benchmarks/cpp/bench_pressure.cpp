// Cost of the pressure solvers on a dam-break-like two-phase field: a water column (rho 1000 kg/m^3)
// and a shallow layer under air (rho 1.2 kg/m^3), a porous mound (n = 0.4) on a solid bed step, open
// top (p = 0), grid graded in z (dz_bed = dz / 2 near the bed) as in the flume of the seed paper.
// Sizes about 2.7e3, 1.1e4 and 4.3e4 cells. Counters: CG iterations, setup and solve times [ms] and the
// cost per cell [us], in thread CPU time (the machine may be shared: CPU time is what the solver
// costs; the wall times are reported next to it).
#include <benchmark/benchmark.h>

#include <chrono>
#include <cmath>
#include <ctime>
#include <vector>

#include "vofdem/common/grid.h"
#include "vofdem/flow/pressure_solver.h"

using namespace vofdem;

namespace {

struct Case {
  Grid2D grid;
  PressureProblem problem;
  std::vector<double> rhs;
};

Case dam_break_case(int scale) {
  // scale 1: 84 x 30 cells over 2.1 m x 0.3 m (2.5 cm x 1 cm, 0.5 cm below 2 cm)
  const int nx = 84 * scale;
  const double dz = 0.01 / scale, dz_bed = 0.5 * dz;
  Grid2D g = Grid2D::graded(nx, 2.1, 0.3, dz, dz_bed, 0.02);
  const int nz = g.nz();
  const double dt = 1e-3;
  std::vector<double> rho(g.ncell()), n(g.ncell(), 1.0);
  std::vector<std::uint8_t> active(g.ncell(), 1);
  for (int k = 0; k < nz; ++k)
    for (int i = 0; i < nx; ++i) {
      const double x = g.x_center(i), z = g.z_center(k);
      const bool water = x < 0.6 ? z < 0.25 : z < 0.05;
      rho[g.cell(i, k)] = water ? 1000.0 : 1.2;
      if (z < 0.01 && x > 1.6) active[g.cell(i, k)] = 0;               // solid bed step
      if (z < 0.15 - std::abs(x - 1.2) * 0.5 && z > 0.0) n[g.cell(i, k)] = 0.4;  // porous mound
    }
  Case c{g, PressureProblem(), std::vector<double>(g.ncell())};
  c.problem.resize(g);
  c.problem.cell_active = active;
  auto beta = [&](int a, int b) {
    const double r = 0.5 * (rho[a] + rho[b]), nf = 0.5 * (n[a] + n[b]);
    return dt * nf / r;
  };
  for (int k = 0; k < nz; ++k)
    for (int i = 1; i < nx; ++i) {
      const int a = g.cell(i - 1, k), b = g.cell(i, k);
      if (active[a] && active[b]) c.problem.face_x_coef[g.face_x(i, k)] = beta(a, b) * g.dz(k) / g.dx();
    }
  for (int k = 1; k < nz; ++k)
    for (int i = 0; i < nx; ++i) {
      const int a = g.cell(i, k - 1), b = g.cell(i, k);
      if (active[a] && active[b])
        c.problem.face_z_coef[g.face_z(i, k)] = beta(a, b) * g.dx() / (g.z_center(k) - g.z_center(k - 1));
    }
  for (int i = 0; i < nx; ++i) {
    const int a = g.cell(i, nz - 1);
    c.problem.face_z_coef[g.face_z(i, nz)] = beta(a, a) * g.dx() / (0.5 * g.dz(nz - 1));
  }
  // a divergence field of the size a projection meets (about 1e-3 m^2/s per cell)
  for (int cidx = 0; cidx < g.ncell(); ++cidx)
    c.rhs[cidx] = active[cidx] ? 1e-3 * g.dx() * std::sin(0.7 * cidx) * std::cos(0.013 * cidx) : 0.0;
  return c;
}

double thread_cpu_seconds() {
  timespec t;
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
  return t.tv_sec + 1e-9 * t.tv_nsec;
}

// setup + solve, the per-step cost of a projection: from a zero guess (warm = 0) or from the solution
// of the previous step, whose source differed by a few percent (warm = 1)
void BM_PressureSetupSolve(benchmark::State& state) {
  const auto kind = static_cast<PressureSolverKind>(state.range(0));
  const Case c = dam_break_case(static_cast<int>(state.range(1)));
  const bool warm = state.range(2) != 0;
  auto solver = make_pressure_solver(kind);
  std::vector<double> p(c.grid.ncell(), 0.0), previous(c.grid.ncell(), 0.0), rhs_previous(c.rhs);
  for (std::size_t j = 0; j < rhs_previous.size(); ++j) rhs_previous[j] *= 1.0 + 0.05 * std::sin(0.01 * j);
  if (warm) {
    solver->setup(c.grid, c.problem);
    solver->solve(rhs_previous, previous, 1e-8);
  }
  double setup_cpu = 0, solve_cpu = 0, setup_wall = 0, solve_wall = 0;
  int iterations = 0;
  for (auto _ : state) {
    std::copy(previous.begin(), previous.end(), p.begin());
    const double t0 = thread_cpu_seconds();
    solver->setup(c.grid, c.problem);
    const double t1 = thread_cpu_seconds();
    const auto st = solver->solve(c.rhs, p, 1e-8);
    const double t2 = thread_cpu_seconds();
    benchmark::DoNotOptimize(p.data());
    setup_cpu += t1 - t0;
    solve_cpu += t2 - t1;
    setup_wall += st.setup_seconds;
    solve_wall += st.solve_seconds;
    iterations = st.iterations;
  }
  const double runs = static_cast<double>(state.iterations()), cells = c.grid.ncell();
  state.counters["cells"] = cells;
  state.counters["iterations"] = iterations;
  state.counters["setup_ms"] = 1e3 * setup_cpu / runs;
  state.counters["solve_ms"] = 1e3 * solve_cpu / runs;
  state.counters["us_per_cell"] = 1e6 * (setup_cpu + solve_cpu) / runs / cells;
  state.counters["wall_ms"] = 1e3 * (setup_wall + solve_wall) / runs;
}

}  // namespace

// the direct solver does not use the guess: zero guess only
BENCHMARK(BM_PressureSetupSolve)
    ->ArgsProduct({{static_cast<int>(PressureSolverKind::kEigenDirect)}, {1, 2, 4}, {0}})
    ->ArgsProduct({{static_cast<int>(PressureSolverKind::kMultigridCG)}, {1, 2, 4}, {0, 1}})
    ->ArgNames({"kind", "scale", "warm"})
    ->Unit(benchmark::kMillisecond);
