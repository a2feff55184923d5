// Threads for one run (threads.h): the option's range, and runs on one and on two threads that end in
// the same bits. Every loop is split (thread_min_cells = 1), so that these small scenes reach each
// parallel loop of the flow and of the pressure solver's coarse levels.
#include <gtest/gtest.h>

#include <string>

#include "common/coupler_scenes.h"
#include "common/pin_hash.h"
#include "vofdem/common/threads.h"
#include "common/pinned_params.h"

#ifdef _OPENMP
#include <omp.h>
#endif

namespace vofdem {
namespace {

// the thread settings of a test, restored when it ends
struct ThreadSetting {
  int threads_before = threads(), min_cells_before = thread_min_cells();
  ThreadSetting(int n, int min_cells) {
    set_threads(n);
    set_thread_min_cells(min_cells);
  }
  ~ThreadSetting() {
    set_threads(threads_before);
    set_thread_min_cells(min_cells_before);
  }
};

// the exported state of `run` on n threads, every loop split
template <class Run>
std::map<std::string, std::vector<double>> state_on(int n, Run run) {
  const ThreadSetting setting(n, 1);
  return run();
}

// true if OpenMP gives a team of two threads here (else the two runs would be one thread each)
bool two_threads_run() {
  int team = 1;
#ifdef _OPENMP
#pragma omp parallel num_threads(2)
#pragma omp single
  team = omp_get_num_threads();
#endif
  return team == 2;
}

// a flume 0.6 m long fed by the inlet over a porous block, free overfall, k-epsilon with wall functions
// and the filtered pore strain, all four diffusions implicit, Adams-Bashforth 2; dx x dz [m]
std::map<std::string, std::vector<double>> flume_state(double dx, double dz) {
  FlowParams p = test::pinned_flow_params();
  p.inlet = InletBoundary::kDischarge;
  p.outlet = OutletBoundary::kFreeOverfall;
  p.flume_width = 0.5;
  p.flags |= kFlowTurbulence;
  p.viscous_scheme = ViscousScheme::kImplicit;
  p.time_scheme = MomentumTimeScheme::kAdamsBashforth2;
  p.turbulence.time_scheme = KEpsilonTimeScheme::kVerticalLines;
  p.turbulence.pore_strain = KEpsilonPoreStrain::kFiltered;
  p.turbulence.pore_filter_length = 0.05;
  VOFGrid flow(Grid2D::uniform(static_cast<int>(std::lround(0.6 / dx)), static_cast<int>(std::lround(0.3 / dz)), 0.6,
                               0.3),
               p);
  flow.set_porosity_box(0.25, 0.4, 0.0, 0.12, 0.4, 0.04);
  flow.set_discharge(DischargeTable::constant(0.01));
  flow.fill_water_below(0.1);
  flow.set_hydrostatic_pressure();
  flow.advance(0.3);
  std::map<std::string, std::vector<double>> out;
  out["face_u"] = flow.face_u, out["face_w"] = flow.face_w, out["cell_F"] = flow.cell_F, out["cell_p"] = flow.cell_p;
  out["cell_k"] = flow.turbulence().cell_k, out["cell_nut"] = flow.cell_nut;
  out["time"] = {flow.time()};
  return out;
}

TEST(Threads, TheOptionRefusesValuesOutsideItsRange) {
  const int before = threads();
  for (int bad : {0, -1, max_threads() + 1}) {
    try {
      set_threads(bad);
      FAIL() << "set_threads(" << bad << ") accepted";
    } catch (const std::invalid_argument& e) {
      const std::string m = e.what();
      EXPECT_EQ(m.rfind("threads = " + std::to_string(bad), 0), 0u) << m;
      EXPECT_NE(m.find("[1, " + std::to_string(max_threads()) + "]"), std::string::npos) << m;
    }
  }
  EXPECT_EQ(threads(), before);
  EXPECT_THROW(set_thread_min_cells(0), std::invalid_argument);
  EXPECT_THROW(set_thread_min_cells(1000000001), std::invalid_argument);
  EXPECT_GE(threads(), 1);
  EXPECT_LE(threads(), max_threads());
  EXPECT_EQ(max_threads() > 1, built_with_openmp());
}

TEST(Threads, ACoupledRunIsTheSameBitsOnOneAndTwoThreads) {
  if (!two_threads_run()) GTEST_SKIP() << "no team of two threads (built without OpenMP?)";
  // stones falling into a tank with turbulence: porosity, forces, DEM, every stage of the flow
  auto run_steps = [](int steps) {
    FlowParams fp = test::pinned_flow_params();
    fp.flags |= kFlowTurbulence;
    auto s = test::tank(0.3, 0.3, 0.01, 0.2, {0.1, 0.25, 0.16, 0.22, 0.2, 0.05}, 0.02, kCoupleDefault, fp);
    for (int k = 0; k < steps; ++k) s.sim->step();
    return s.sim->export_state();
  };
  const auto one = state_on(1, [&] { return run_steps(30); }), two = state_on(2, [&] { return run_steps(30); });
  std::string diff;
  EXPECT_TRUE(test::same_bits(one, two, &diff)) << "first difference: " << diff;
  EXPECT_EQ(test::state_hash(one), test::state_hash(two));
  EXPECT_NE(one.at("dem/stone_pos"), run_steps(0).at("dem/stone_pos"));  // the stones moved
}

TEST(Threads, AFlumeFlowIsTheSameBitsOnOneAndTwoThreads) {
  if (!two_threads_run()) GTEST_SKIP() << "no team of two threads (built without OpenMP?)";
  // cells flat (the pressure smoother's lines along z) and tall (along x)
  for (const auto& [dx, dz] : {std::pair{0.02, 0.01}, std::pair{0.01, 0.02}}) {
    const auto one = state_on(1, [&] { return flume_state(dx, dz); });
    const auto two = state_on(2, [&] { return flume_state(dx, dz); });
    std::string diff;
    EXPECT_TRUE(test::same_bits(one, two, &diff)) << "dx " << dx << ", dz " << dz << ": first difference " << diff;
    EXPECT_GT(one.at("time")[0], 0.29);
  }
}

}  // namespace
}  // namespace vofdem
