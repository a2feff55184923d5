// The disc path pinned: hashes of a disc heap, a packed disc weir and a coupled disc scene, taken
// before the polygon stones were added. A change of any bit of the disc results fails these tests.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <random>

#include "common/coupler_scenes.h"
#include "common/pin_hash.h"
#include "vofdem/stones/weir_packing.h"
#include "common/pinned_params.h"

using namespace vofdem;

namespace {

DEMSystem disc_heap() {
  std::mt19937_64 g(11);
  auto u = [&g] { return static_cast<double>(g() >> 11) * 0x1.0p-53; };
  std::vector<double> pos, radius;
  for (int k = 0; k < 48; ++k) {
    pos.push_back(0.03 + 0.055 * (k % 7) + 0.004 * u());
    pos.push_back(0.03 + 0.055 * (k / 7));
    radius.push_back(0.024 * (0.9 + 0.2 * u()));
  }
  DEMParams p;
  p.add_flume(0.0, 0.4, 0.0, 0.3);
  p.restitution = 0.3;
  p.flags |= kDEMSleeping;
  return DEMSystem(p, pos, radius, {2650.0});
}
}  // namespace

TEST(DiscPins, HeapOfDiscs) {
  DEMSystem s = disc_heap();
  s.advance(0.4);
  const auto state = s.export_state();
  EXPECT_TRUE(test::rolling_springs_zero(state));
  // taken again when the energy account booked the springs of contacts that open and the slip from the
  // work done (dem_contact.h): only the account's `dissipated` changed (zeroed, the hash was the same)
  EXPECT_EQ(test::pin_hash(state), 11446235763509087469ull);
}

TEST(DiscPins, PackedDiscWeir) {
  WeirSpec spec;
  spec.height = 0.12;
  spec.crest = 0.08;
  spec.seed = 3;
  spec.settle_time_max = 1.0;
  spec.d_mean = 0.048;  // the Maeno weir's stones
  spec.density = 2650.0;
  WeirPackingReport r;
  DEMSystem s = pack_weir(spec, DEMParams{}, r);
  const auto state = s.export_state();
  EXPECT_TRUE(test::rolling_springs_zero(state));
  // taken again when the stones laid by hand stayed above the fixed layer (no stone on the bed at a toe's
  // tip) and the toe rollers were removed in up to three rounds (weir_packing.cpp, steps 6 and 7); and
  // when the energy account booked the springs of contacts that open and the slip from the work done
  // (dem_contact.h): only the account's `dissipated` changed (zeroed, the hash was the same)
  EXPECT_EQ(test::pin_hash(state), 4821646297219714695ull);
  EXPECT_EQ(r.porosity, 0.21451204055766793);
  EXPECT_EQ(r.outline_error, 0.03489373339692101);
}

TEST(DiscPins, CoupledDiscsInATank) {
  // taken again when the disc physics changed: the wet fraction following each stone over the DEM's
  // substeps (wet_fraction.h), then the implicit drag exchange and Adams-Bashforth 2 (drag_exchange.h,
  // momentum.h), each time the same hash as the disc-only code with that change; then the still air's
  // total pressure where the open top draws air in (projection.h: the flow alone changed); then the
  // wet fraction's tolerance (wet_fraction.h), with which off the former hash is kept; then the
  // column solves of the viscous stresses after their explicit part (momentum.h), with the former
  // splitting (ViscousScheme::kImplicitVerticalFromStart) the former hashes
  struct Pin {
    ViscousScheme scheme;
    double tol;
    std::uint64_t hash;
  };
  const double tol = CouplerParams().wet_fraction_tolerance;
  for (const Pin& pin : {Pin{ViscousScheme::kImplicitVerticalFromStart, 0.0, 5615575716851011222ull},
                         Pin{ViscousScheme::kImplicitVerticalFromStart, tol, 5962126411014851550ull},
                         Pin{ViscousScheme::kImplicitVertical, 0.0, 10472922950744682249ull},
                         Pin{ViscousScheme::kImplicitVertical, tol, 5539174150878618620ull}}) {
    FlowParams fp = test::pinned_flow_params();
    fp.viscous_scheme = pin.scheme;
    auto sc = test::tank(0.3, 0.3, 0.01, 0.2, {0.1, 0.15, 0.16, 0.12, 0.2, 0.05}, 0.02, kCoupleDefault, fp);
    CouplerParams cp = sc.sim->params();
    cp.wet_fraction_tolerance = pin.tol;
    sc.sim->set_params(cp);
    for (int k = 0; k < 20; ++k) sc.sim->step();
    const auto state = sc.sim->export_state();
    EXPECT_TRUE(test::rolling_springs_zero(state));
    EXPECT_EQ(test::pin_hash(state), pin.hash) << "scheme " << static_cast<int>(pin.scheme) << ", tol " << pin.tol;
  }
}
