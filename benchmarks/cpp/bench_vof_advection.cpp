// Cost of one geometric VOF advection step (both sweeps), per cell, at about 1e4 and 1e5 cells.
//
//   vortex: unit square, steady single vortex, a circle of water (r = 0.15): few interface cells
//   flume:  graded rows as the seed paper's mesh (dz 0.5 cm at the bed, 1 cm above; dx from the
//           size), water below a wavy surface, a porous mound (n = 0.41), steady recirculation
//   all-interface: every cell holds an interface (the cost of the reconstruction itself)
// The *MYC variants use the mixed Youngs-centred normal instead of Youngs'.
// Counters: ns_per_cell (CPU time / cells / steps) and the share of interface cells at the end.
#include <benchmark/benchmark.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include "vofdem/common/grid.h"
#include "vofdem/flow/vof_advection.h"
#include "vofdem/common/numbers.h"

namespace {

using vofdem::Grid2D;

using vofdem::kPi;

struct Case {
  Grid2D grid;
  std::vector<double> n, u, w, f;
};

// divergence-free face velocities from a stream function at the corners
void from_psi(Case& c, double (*psi)(double, double, double, double), double lx, double lz) {
  const Grid2D& g = c.grid;
  const int nx = g.nx(), nz = g.nz();
  std::vector<double> node((nx + 1) * (nz + 1));
  for (int k = 0; k <= nz; ++k)
    for (int i = 0; i <= nx; ++i) node[i + (nx + 1) * k] = psi(g.x_face(i), g.z_face(k), lx, lz);
  c.u.assign(g.nface_x(), 0.0);
  c.w.assign(g.nface_z(), 0.0);
  for (int k = 0; k < nz; ++k)
    for (int i = 0; i <= nx; ++i)
      c.u[g.face_x(i, k)] = (node[i + (nx + 1) * (k + 1)] - node[i + (nx + 1) * k]) / g.dz(k);
  for (int k = 0; k <= nz; ++k)
    for (int i = 0; i < nx; ++i) c.w[g.face_z(i, k)] = -(node[i + 1 + (nx + 1) * k] - node[i + (nx + 1) * k]) / g.dx();
}

double vortex_psi(double x, double z, double lx, double lz) {
  return std::pow(std::sin(kPi * x / lx) * std::sin(kPi * z / lz), 2) * lx / kPi;
}

// fraction of a cell below the surface z = h(x), by sampling (setup only)
template <class Inside>
double fraction(const Grid2D& g, int i, int k, Inside inside) {
  const int ns = 8;
  int count = 0;
  for (int b = 0; b < ns; ++b)
    for (int a = 0; a < ns; ++a)
      count += inside(g.x_face(i) + (a + 0.5) * g.dx() / ns, g.z_face(k) + (b + 0.5) * g.dz(k) / ns);
  return static_cast<double>(count) / (ns * ns);
}

Case vortex_case(int N) {
  Case c{Grid2D::uniform(N, N, 1.0, 1.0), {}, {}, {}, {}};
  c.n.assign(c.grid.ncell(), 1.0);
  c.f.resize(c.grid.ncell());
  for (int k = 0; k < N; ++k)
    for (int i = 0; i < N; ++i)
      c.f[c.grid.cell(i, k)] =
          fraction(c.grid, i, k, [](double x, double z) { return std::hypot(x - 0.5, z - 0.75) < 0.15; });
  from_psi(c, vortex_psi, 1.0, 1.0);
  return c;
}

// nz rows: 4 bed rows of 0.5 cm then 1 cm; nx columns over 4 m
Case flume_case(int nx, int nz) {
  std::vector<double> zf{0.0};
  for (int k = 0; k < nz; ++k) zf.push_back(zf.back() + (k < 4 ? 0.005 : 0.01));
  Case c{Grid2D(nx, 4.0 / nx, zf), {}, {}, {}, {}};
  const Grid2D& g = c.grid;
  const double h = g.height_z();
  c.n.assign(g.ncell(), 1.0);
  c.f.resize(g.ncell());
  for (int k = 0; k < g.nz(); ++k)
    for (int i = 0; i < nx; ++i) {
      const double x = g.x_center(i), z = g.z_center(k);
      // trapezoidal mound 0.2 m high between x = 1.5 and 2.5 m
      if (z < 0.2 * std::clamp(std::min(x - 1.5, 2.5 - x) / 0.3, 0.0, 1.0)) c.n[g.cell(i, k)] = 0.41;
      c.f[g.cell(i, k)] = fraction(g, i, k, [h](double xs, double zs) {
        return zs < h * (0.5 + 0.1 * std::sin(2.0 * kPi * xs / 1.3));
      });
    }
  from_psi(c, vortex_psi, 4.0, h);
  return c;
}

// reset_f: restore the initial F before every step (untimed), so that the field keeps its interfaces
void run(benchmark::State& state, Case c, bool reset_f = false,
         vofdem::VofNormal normal = vofdem::VofNormal::kYoungs) {
  const Grid2D& g = c.grid;
  vofdem::VofBoundaryInflow inflow;
  vofdem::VofScratch scratch;
  const double dt = vofdem::vof_stable_dt(g, c.n, c.u, c.w, 0.4);
  bool x_first = true;
  long long step = 0;
  const std::vector<double> f0 = c.f;
  for (auto _ : state) {
    if (reset_f) {
      state.PauseTiming();
      c.f = f0;
      state.ResumeTiming();
    }
    vofdem::advect_vof(g, c.n, c.u, c.w, inflow, dt, x_first, c.f, scratch, normal);
    x_first = !x_first;
    // the flow reverses every 100 steps so that the interface stays as long as at the start
    if (++step % 100 == 0) {
      for (double& v : c.u) v = -v;
      for (double& v : c.w) v = -v;
    }
    benchmark::DoNotOptimize(c.f.data());
  }
  const double cells = g.ncell();
  int mixed = 0;
  for (double v : c.f) mixed += v > 1e-12 && v < 1.0 - 1e-12;
  state.counters["cells"] = cells;
  state.counters["mixed_share"] = mixed / cells;
  state.counters["ns_per_cell"] =
      benchmark::Counter(cells * 1e-9, benchmark::Counter::kIsIterationInvariantRate | benchmark::Counter::kInvert);
  state.counters["clips"] = static_cast<double>(scratch.clip_count);
}

// every cell an interface cell: F = 0.5 + 0.45 sin(2 pi x / 0.2) sin(2 pi z / 0.2) in the vortex
Case all_mixed_case(int N) {
  Case c = vortex_case(N);
  for (int k = 0; k < N; ++k)
    for (int i = 0; i < N; ++i)
      c.f[c.grid.cell(i, k)] =
          0.5 + 0.45 * std::sin(2.0 * kPi * c.grid.x_center(i) / 0.2) * std::sin(2.0 * kPi * c.grid.z_center(k) / 0.2);
  return c;
}

void BM_VortexCircle(benchmark::State& state) { run(state, vortex_case(static_cast<int>(state.range(0)))); }
void BM_FlumeGraded(benchmark::State& state) {
  run(state, flume_case(static_cast<int>(state.range(0)), static_cast<int>(state.range(1))));
}

}  // namespace

void BM_AllInterface(benchmark::State& state) { run(state, all_mixed_case(static_cast<int>(state.range(0))), true); }
void BM_AllInterfaceMYC(benchmark::State& state) {
  run(state, all_mixed_case(static_cast<int>(state.range(0))), true, vofdem::VofNormal::kMixedYoungsCentered);
}
void BM_FlumeGradedMYC(benchmark::State& state) {
  run(state, flume_case(static_cast<int>(state.range(0)), static_cast<int>(state.range(1))), false,
      vofdem::VofNormal::kMixedYoungsCentered);
}

BENCHMARK(BM_VortexCircle)->Arg(100)->Arg(316)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_FlumeGraded)->Args({160, 62})->Args({800, 125})->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_FlumeGradedMYC)->Args({160, 62})->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_AllInterface)->Arg(100)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_AllInterfaceMYC)->Arg(100)->Unit(benchmark::kMicrosecond);
