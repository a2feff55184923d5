// Cost of one k-epsilon step per cell: a flume on the paper's graded mesh (2.5 cm x 1 cm, 0.5 cm
// rows at the bed) with a sheared, divergence-free flow, a porous mound, a solid block and air in
// the upper third. Reported as ns per cell and step (counter ns_per_cell).
#include <benchmark/benchmark.h>

#include <cmath>
#include <vector>

#include "vofdem/common/grid.h"
#include "vofdem/flow/k_epsilon.h"

namespace {

struct Scene {
  vofdem::Grid2D grid;
  std::vector<double> face_u, face_w, porosity, F, nu;
  explicit Scene(int nx)
      : grid(vofdem::Grid2D::graded(nx, 0.025 * nx, 0.3, 0.01, 0.005, 0.02)),
        face_u(grid.nface_x()), face_w(grid.nface_z()), porosity(grid.ncell(), 1.0), F(grid.ncell(), 1.0),
        nu(grid.ncell(), 1e-6) {
    const double pi = std::acos(-1.0), lx = grid.length_x(), h = 0.3;
    // stream function psi = U z + A sin(2 pi x/lx) sin(pi z/h): u = dpsi/dz, w = -dpsi/dx
    auto psi = [&](double x, double z) { return 0.3 * z + 0.01 * std::sin(2 * pi * x / lx) * std::sin(pi * z / h); };
    for (int k = 0; k < grid.nz(); ++k)
      for (int i = 0; i <= grid.nx(); ++i)
        face_u[grid.face_x(i, k)] = (psi(grid.x_face(i), grid.z_face(k + 1)) - psi(grid.x_face(i), grid.z_face(k))) /
                                    grid.dz(k);
    for (int k = 0; k <= grid.nz(); ++k)
      for (int i = 0; i < grid.nx(); ++i)
        face_w[grid.face_z(i, k)] = -(psi(grid.x_face(i + 1), grid.z_face(k)) - psi(grid.x_face(i), grid.z_face(k))) /
                                    grid.dx();
    for (int k = 0; k < grid.nz(); ++k)
      for (int i = 0; i < grid.nx(); ++i) {
        const int c = grid.cell(i, k);
        const double x = grid.x_center(i) / lx, z = grid.z_center(k);
        if (std::abs(x - 0.5) < 0.1 && z < 0.1) porosity[c] = 0.41;  // porous mound
        if (std::abs(x - 0.25) < 0.02 && z < 0.03) porosity[c] = 0.0;  // solid block
        if (z > 0.2) F[c] = 0.0;                                       // air
      }
  }
};

void BM_KEpsilonStep(benchmark::State& state) {
  Scene s(static_cast<int>(state.range(0)));
  vofdem::KEpsilonParams p;
  p.sweeps = static_cast<int>(state.range(1));
  vofdem::KEpsilonModel m(s.grid, p);
  m.initialize(1e-4, 1e-5, 1e-6);
  const double dt = 1e-3;
  for (auto _ : state) {
    m.step(dt, s.face_u, s.face_w, s.porosity, s.F, s.nu);
    benchmark::DoNotOptimize(m.cell_k.data());
  }
  const double cells = static_cast<double>(s.grid.ncell());
  state.counters["ncell"] = cells;
  // share of each stage in the step time [%]
  const vofdem::StageProfile& prof = m.profile();
  for (std::size_t i = 0; i < prof.names().size(); ++i)
    state.counters[prof.names()[i].substr(6)] = 100.0 * prof.seconds()[i] / prof.total_seconds();
  state.counters["ns_per_cell"] =
      benchmark::Counter(cells * static_cast<double>(state.iterations()) * 1e-9,
                         benchmark::Counter::kIsRate | benchmark::Counter::kInvert);
}

void BM_KEpsilonStableDt(benchmark::State& state) {
  Scene s(static_cast<int>(state.range(0)));
  vofdem::KEpsilonModel m(s.grid);
  m.initialize(1e-4, 1e-5, 1e-6);
  for (auto _ : state) benchmark::DoNotOptimize(m.stable_dt(s.face_u, s.face_w, s.porosity, s.F, s.nu));
  const double cells = static_cast<double>(s.grid.ncell());
  state.counters["ns_per_cell"] =
      benchmark::Counter(cells * static_cast<double>(state.iterations()) * 1e-9,
                         benchmark::Counter::kIsRate | benchmark::Counter::kInvert);
}

}  // namespace

// nx (the paper's 2.5 cm columns; 30 rows), sweeps
BENCHMARK(BM_KEpsilonStep)->Args({80, 0})->Args({80, 1})->Args({80, 4})->Args({320, 1})->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_KEpsilonStableDt)->Arg(80)->Arg(320)->Unit(benchmark::kMicrosecond);
