// Cost of the coupled guard's state copy per step: the named-array maps it used (Coupler::export_state()
// and the DEM's own export_state() in DEMSystem::advance) against the typed states (CouplerState,
// DEMState) copied into reused values, on a scene of the paper's size (3.7 m x 0.45 m at 2.5 cm x 1 cm,
// 100 stones in water), next to one coupled step. Interleave the runs:
//   build-bench/bench_state --benchmark_enable_random_interleaving=true --benchmark_repetitions=10
//       --benchmark_report_aggregates_only=true
#include <benchmark/benchmark.h>

#include <memory>
#include <vector>

#include "vofdem/coupling/coupler.h"

namespace {
struct Scene {
  std::unique_ptr<vofdem::VOFGrid> fluid;
  std::unique_ptr<vofdem::DEMSystem> stones;
  std::unique_ptr<vofdem::Coupler> sim;
};

// a heap of 100 stones (rows of 16 down to 7, 5 cm apart) in water 0.3 m deep, run for 0.05 s
Scene& scene() {
  static Scene s = [] {
    Scene s;
    const vofdem::Grid2D g = vofdem::Grid2D::uniform(148, 45, 3.7, 0.45);
    s.fluid = std::make_unique<vofdem::VOFGrid>(g, vofdem::FlowParams());
    s.fluid->fill_water_below(0.3);
    s.fluid->set_hydrostatic_pressure();
    std::vector<double> pos;
    for (int row = 0, count = 16; count >= 7; ++row, --count)
      for (int j = 0; j < count; ++j) pos.push_back(1.0 + 0.025 * row + 0.05 * j), pos.push_back(0.025 + 0.045 * row);
    const std::size_t n = pos.size() / 2;
    vofdem::DEMParams p;
    p.submerged = true;
    p.medium.rho_water = vofdem::FlowParams().medium.rho_water;
    p.add_flume(0.0, 3.7, 0.0);
    s.stones = std::make_unique<vofdem::DEMSystem>(p, pos, std::vector<double>(n, 0.024), std::vector<double>(n, 2650.0));
    vofdem::FlowParams fp = s.fluid->params();
    fp.flags |= vofdem::kFlowRelativeVelocity;  // the two-way scene's resistance relative to the stones
    s.fluid->set_params(fp);
    s.sim = std::make_unique<vofdem::Coupler>(s.fluid.get(), s.stones.get(), vofdem::CouplerParams());
    s.sim->advance(0.05);
    return s;
  }();
  return s;
}
}  // namespace

// what a coupled step copied before: the coupler's map (with the stones' map inside) and the DEM's own map
static void BM_SnapshotMaps(benchmark::State& state) {
  Scene& s = scene();
  for (auto _ : state) {
    auto coupled = s.sim->export_state();
    auto stones = s.stones->export_state();
    benchmark::DoNotOptimize(coupled.size() + stones.size());
  }
}

// the same two copies as typed states into reused values
static void BM_SnapshotTyped(benchmark::State& state) {
  Scene& s = scene();
  vofdem::CouplerState coupled;
  vofdem::DEMState stones;
  for (auto _ : state) {
    s.sim->export_state(coupled);
    s.stones->export_state(stones);
    benchmark::DoNotOptimize(coupled.fluid.cell_F.data());
    benchmark::DoNotOptimize(stones.stone_pos.data());
  }
}

// one coupled step for scale (the state moves on: a run of the scene)
static void BM_CoupledStep(benchmark::State& state) {
  Scene& s = scene();
  for (auto _ : state) s.sim->step();
}

BENCHMARK(BM_SnapshotMaps)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_SnapshotTyped)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_CoupledStep)->Unit(benchmark::kMicrosecond);
