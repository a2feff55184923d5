// Cost of one porosity mapping per stone (seed section 2.4): exact areas against the lookup table,
// without the Python layer. Discs: a deterministic random cloud of 300 stones of 4.8 cm +-10 % in
// the lower 0.5 m of the paper's grid (2.5 cm x 1.0 cm cells, 0.5 cm rows up to 2 cm).
#include <benchmark/benchmark.h>

#include <random>
#include <vector>

#include "vofdem/coupling/porosity_map.h"

namespace {

struct Discs {
  std::vector<double> x, z, r;
};

Discs make_discs(int n) {
  std::mt19937 rng(1);
  std::uniform_real_distribution<double> ux(0.05, 2.95), uz(0.0, 0.5), ur(0.0216, 0.0264);
  Discs d;
  for (int j = 0; j < n; ++j) {
    d.x.push_back(ux(rng));
    d.z.push_back(uz(rng));
    d.r.push_back(ur(rng));
  }
  return d;
}

void run(benchmark::State& state, vofdem::PorosityMethod method, int m) {
  const vofdem::Grid2D grid = vofdem::Grid2D::graded(120, 3.0, 0.6, 0.01, 0.005, 0.02);
  const Discs d = make_discs(300);
  vofdem::PorosityParams p;
  p.method = method;
  p.m = m;
  p.r_min = 0.0216;
  p.r_max = 0.0264;
  p.max_discs = 300;
  vofdem::PorosityMapper mapper(grid, p);
  for (auto _ : state) {
    mapper.map(d.x, d.z, d.r);
    benchmark::DoNotOptimize(mapper.cell_porosity().data());
  }
  // items = stones: the report shows the time per stone (including the per-call work on all cells)
  state.SetItemsProcessed(state.iterations() * 300);
}

void BM_PorosityExact(benchmark::State& state) { run(state, vofdem::PorosityMethod::kExact, 1); }
void BM_PorosityLookup(benchmark::State& state) {
  run(state, vofdem::PorosityMethod::kLookup, static_cast<int>(state.range(0)));
}

}  // namespace

BENCHMARK(BM_PorosityExact);
BENCHMARK(BM_PorosityLookup)->Arg(2)->Arg(8)->Arg(32);
