// Cost of the width-averaged solid fraction of 3D stones (PorosityMapper, sphere_porosity.cpp): clumps
// (map_clumps: each sub-sphere's exact slab volumes, scaled to the union's volume and merged into one cell
// list per stone) against spheres of the same volume (map_spheres). A deterministic cloud of 300 stones of
// d_eq = 4.8 cm, turned at random, in the lower 0.5 m of the paper's grid (2.5 cm x 1.0 cm cells, 0.5 cm
// rows up to 2 cm), across a flume of 0.3 m. benchmarks/clump_map_table.py writes the results file.
#include <benchmark/benchmark.h>

#include <random>
#include <string>
#include <vector>

#include <Eigen/Geometry>

#include "vofdem/common/grid.h"
#include "vofdem/coupling/porosity_map.h"
#include "vofdem/stones/clump.h"

namespace {

constexpr int kStones = 300;
constexpr double kDeq = 0.048, kWidth = 0.3;

struct Cloud {
  std::vector<double> x, z, quat, sphere, volume, r;
  std::vector<int> offset{0};
  double reach = 0.0;  // the largest bounding radius [m]
};

// the shape `name` (or spheres of d_eq when empty) at random places and orientations (seed 1)
Cloud make_cloud(const std::string& name) {
  std::mt19937 rng(1);
  std::uniform_real_distribution<double> ux(0.05, 2.95), uz(0.03, 0.47), u(0.0, 1.0);
  Cloud c;
  const vofdem::Clump shape = name.empty() ? vofdem::Clump({{Eigen::Vector3d::Zero(), 0.5 * kDeq}})
                                           : vofdem::quarried_stone(name, kDeq);
  c.reach = shape.bounding_radius();
  for (int j = 0; j < kStones; ++j) {
    c.x.push_back(ux(rng));
    c.z.push_back(uz(rng));
    const Eigen::Quaterniond q = Eigen::Quaterniond::UnitRandom();
    c.quat.insert(c.quat.end(), {q.w(), q.x(), q.y(), q.z()});
    for (const vofdem::ClumpSphere& s : shape.spheres())
      c.sphere.insert(c.sphere.end(), {s.centre[0], s.centre[1], s.centre[2], s.radius});
    c.offset.push_back(c.offset.back() + static_cast<int>(shape.spheres().size()));
    c.volume.push_back(shape.volume());
    c.r.push_back(0.5 * kDeq);
  }
  return c;
}

vofdem::PorosityMapper make_mapper(double reach) {
  vofdem::PorosityParams p;
  p.n_exp = 0.0;  // the true void fraction, as the 3D models require
  p.r_min = 0.5 * kDeq;
  p.r_max = reach;
  p.max_discs = kStones;
  return vofdem::PorosityMapper(vofdem::Grid2D::graded(120, 3.0, 0.6, 0.01, 0.005, 0.02), p);
}

// items = stones: the report shows the time per stone (the per-call work on all cells included)
void BM_MapSpheres(benchmark::State& state) {
  const Cloud c = make_cloud("");
  vofdem::PorosityMapper m = make_mapper(0.5 * kDeq);
  for (auto _ : state) {
    m.map_spheres(kStones, c.x.data(), c.z.data(), c.r.data(), kWidth);
    benchmark::DoNotOptimize(m.cell_porosity().data());
  }
  state.SetItemsProcessed(state.iterations() * kStones);
}

void map_clumps(benchmark::State& state, const std::string& name) {
  const Cloud c = make_cloud(name);
  vofdem::PorosityMapper m = make_mapper(c.reach);
  for (auto _ : state) {
    m.map_clumps(kStones, c.x.data(), c.z.data(), c.quat.data(), c.sphere.data(), c.offset.data(), c.volume.data(),
                 kWidth);
    benchmark::DoNotOptimize(m.cell_porosity().data());
  }
  state.SetItemsProcessed(state.iterations() * kStones);
  state.counters["spheres"] = static_cast<double>(c.offset[1]);
}

void BM_MapClumps_pair_2(benchmark::State& state) { map_clumps(state, "pair_2"); }
void BM_MapClumps_triangle_3(benchmark::State& state) { map_clumps(state, "triangle_3"); }
void BM_MapClumps_tetra_4(benchmark::State& state) { map_clumps(state, "tetra_4"); }
void BM_MapClumps_box_8(benchmark::State& state) { map_clumps(state, "box_8"); }

}  // namespace

BENCHMARK(BM_MapSpheres);
BENCHMARK(BM_MapClumps_pair_2);
BENCHMARK(BM_MapClumps_triangle_3);
BENCHMARK(BM_MapClumps_tetra_4);
BENCHMARK(BM_MapClumps_box_8);
