// Cost per particle-step of DEMSystem on the 2D settling of ../shared/peers/dem_settle (lattice start,
// linear spring-dashpot, friction 0.577). The comparison with LAMMPS is benchmarks/dem_settle.py.
#include <benchmark/benchmark.h>

#include <cmath>
#include <random>

#include "vofdem/stones/dem_system.h"

namespace {
vofdem::DEMSystem settling(int n) {
  const double pitch = 0.055, d_mean = 0.048, kPi = 3.14159265358979323846;
  std::mt19937_64 g(12345);
  auto u = [&g] { return static_cast<double>(g() >> 11) * 0x1.0p-53; };
  const int nx = static_cast<int>(std::ceil(std::sqrt(n)));
  std::vector<double> pos, radius;
  for (int k = 0; k < n; ++k) {
    radius.push_back(0.5 * d_mean * (0.9 + 0.2 * u()));
    pos.push_back((k % nx + 0.5) * pitch + 0.002 * (u() - 0.5));
    pos.push_back((k / nx + 0.5) * pitch);
  }
  vofdem::DEMParams p;
  // LAMMPS's kn = 5e6 N/m for discs of unit thickness, scaled to sphere masses (same contact time)
  p.stiffness_normal = 5e6 * (d_mean / 1.5);
  p.restitution = 0.5;
  p.inertia_factor = 0.5;
  p.add_flume(0.0, nx * pitch, 0.0, 0.577);
  (void)kPi;
  return vofdem::DEMSystem(p, pos, radius, {2650.0});
}
}  // namespace

static void BM_DEMSettle(benchmark::State& state) {
  const int n = static_cast<int>(state.range(0));
  const int steps = 2000;
  for (auto _ : state) {
    state.PauseTiming();
    vofdem::DEMSystem s = settling(n);
    state.ResumeTiming();
    s.advance(steps * 1e-4);
    benchmark::DoNotOptimize(s.stone_pos.data());
  }
  state.counters["ns_per_particle_step"] = benchmark::Counter(
      static_cast<double>(n) * steps * state.iterations() * 1e-9,
      benchmark::Counter::kIsRate | benchmark::Counter::kInvert);
}
BENCHMARK(BM_DEMSettle)->Arg(1000)->Arg(10000)->Unit(benchmark::kMillisecond);
