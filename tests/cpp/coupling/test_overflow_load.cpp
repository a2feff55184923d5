#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <stdexcept>
#include <string>
#include <vector>

#include "common/coupler_scenes.h"
#include "vofdem/coupling/overflow_load.h"
#include "common/pinned_params.h"

using namespace vofdem;
using namespace vofdem::test;

namespace {

// share of a circle above a chord at s radii above its centre, by the segment's area formula
double segment_share(double s) { return (std::acos(s) - s * std::sqrt(1.0 - s * s)) / M_PI; }

StoneExtent disc(double x, double z, double r) { return {x - r, x + r, z - r, z + r}; }

// three discs of radius 2 cm, 3 cm apart, the middle one raised by 1 cm (centres 2, 3, 2 cm above the bed)
constexpr double kR = 0.02;
const std::vector<double> kRow = {0.07, 0.02, 0.10, 0.03, 0.13, 0.02};

// the others' surface at the middle disc's flanks x = 0.10 -+ r: the outer discs' circles 1 cm from
// their centres, 0.02 + sqrt(r^2 - 0.01^2)
double middle_protrusion_by_hand() { return 0.05 - (0.02 + std::sqrt(kR * kR - 0.01 * 0.01)); }

// the row in a tank of still water up to `level` [m], the flow frozen at a uniform superficial velocity u
// [m/s] (porosity 1: no porosity mapping), the overflow load on, the stones' forces exchanged once
Scene row_in_uniform_flow(double level, double u, unsigned extra = 0) {
  Scene s = tank(0.2, 0.2, 0.01, level, kRow, kR, kCoupleDEM | kCoupleDrag | kCoupleOverflowLoad | extra);
  std::fill(s.fluid->face_u.begin(), s.fluid->face_u.end(), u);
  std::fill(s.fluid->face_w.begin(), s.fluid->face_w.end(), 0.0);
  s.sim->update_fluid_forces();
  return s;
}

}  // namespace

TEST(OverflowLoad, ProtrusionAndExposedShareByHand) {
  const std::vector<StoneExtent> e = {disc(0.07, 0.02, kR), disc(0.10, 0.03, kR), disc(0.13, 0.02, kR)};
  const std::vector<std::uint8_t> on = {1, 1, 1};
  const double p = middle_protrusion_by_hand();  // 0.0126795 m
  EXPECT_NEAR(stone_protrusion(1, 3, e.data(), on.data()), p, 1e-15);
  // the share of the disc's projection above the level p below its top: the segment's area over pi r^2
  EXPECT_NEAR(exposed_share(p, 2.0 * kR), segment_share(1.0 - p / kR), 1e-14);
  EXPECT_NEAR(exposed_share(kR, 2.0 * kR), 0.5, 1e-15);  // protruding by its radius: half exposed
  EXPECT_EQ(exposed_share(0.0, 2.0 * kR), 0.0);
  EXPECT_EQ(exposed_share(2.0 * kR, 2.0 * kR), 1.0);
  // an outer disc: its open flank is the bed (its own bottom), the other the middle disc's circle
  const double flank = 0.03 + std::sqrt(kR * kR - 0.01 * 0.01);
  EXPECT_NEAR(stone_protrusion(0, 3, e.data(), on.data()), 0.04 - 0.5 * (0.0 + flank), 1e-15);
  // an inactive neighbour is no surface: the middle disc then stands on the bed alone
  const std::vector<std::uint8_t> alone = {0, 1, 0};
  EXPECT_NEAR(stone_protrusion(1, 3, e.data(), alone.data()), 2.0 * kR, 1e-15);
}

TEST(OverflowLoad, BuriedStoneHasNoProtrusion) {
  // a disc resting on the middle one's top covers its centre above its top
  const std::vector<StoneExtent> e = {disc(0.07, 0.02, kR), disc(0.10, 0.03, kR), disc(0.13, 0.02, kR),
                                      disc(0.105, 0.068, kR)};
  const std::vector<std::uint8_t> on = {1, 1, 1, 1};
  EXPECT_EQ(stone_protrusion(1, 4, e.data(), on.data()), 0.0);
  // flanks both above its top (a stone in a hollow): nothing either
  const std::vector<StoneExtent> hollow = {disc(0.07, 0.05, kR), disc(0.10, 0.02, kR), disc(0.13, 0.05, kR)};
  EXPECT_EQ(stone_protrusion(1, 3, hollow.data(), on.data()), 0.0);
}

TEST(OverflowLoad, ForceFollowsTheDragAndLiftFormulas) {
  const OverflowLoadParams p;  // C_D 0.91, C_L 0.178
  const double a = 3e-4, rho = 1000.0;
  const DragForce f = overflow_force(a, 0.5, 0.0, 1.0, rho, p);
  EXPECT_NEAR(f.fx, 0.5 * rho * 0.91 * a * 0.25, 1e-15);   // 0.0341250 N
  EXPECT_NEAR(f.fz, 0.5 * rho * 0.178 * a * 0.25, 1e-15);  // 0.0066750 N, upwards
  // along an oblique relative velocity: the drag along it, the lift vertical with its square; half wet
  const DragForce g = overflow_force(a, 0.3, -0.4, 0.5, rho, p);
  EXPECT_NEAR(g.fx, 0.5 * 0.5 * rho * a * 0.91 * 0.5 * 0.3, 1e-15);
  EXPECT_NEAR(g.fz, 0.5 * 0.5 * rho * a * (0.91 * 0.5 * -0.4 + 0.178 * 0.25), 1e-15);
  const DragForce none = overflow_force(a, 0.5, 0.0, 0.0, rho, p);  // a dry band
  EXPECT_EQ(none.fx, 0.0);
  EXPECT_EQ(none.fz, 0.0);
}

TEST(OverflowLoad, BadCoefficientsAreRefusedByName) {
  CouplerParams p;
  p.overflow.drag_coefficient = 0.0;
  EXPECT_THROW(p.validate(), std::invalid_argument);
  try {
    p.validate();
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("overflow_drag_coefficient"), std::string::npos) << e.what();
  }
  p = CouplerParams();
  p.overflow.lift_coefficient = -0.1;
  EXPECT_THROW(p.validate(), std::invalid_argument);
  p = CouplerParams();
  p.overflow.band_height = std::nan("");
  EXPECT_THROW(p.validate(), std::invalid_argument);
  p = CouplerParams();
  p.flags = 1u << 11;
  EXPECT_THROW(p.validate(), std::invalid_argument);
}

TEST(Coupler, ProtrudingDiscInUniformOverflowGetsTheHandForce) {
  const double u = 0.4, rho = test::pinned_flow_params().medium.rho_water;
  Scene s = row_in_uniform_flow(0.15, u);
  const double p = middle_protrusion_by_hand(), phi = segment_share(1.0 - p / kR);
  EXPECT_NEAR(s.sim->stone_exposed_share[1], phi, 1e-14);
  // the band over the middle disc is water moving at u: F_D = 1/2 rho C_D phi pi r^2 u^2, F_L with C_L
  const double a = phi * M_PI * kR * kR;
  EXPECT_NEAR(s.sim->stone_force_overflow[2], 0.5 * rho * 0.91 * a * u * u, 1e-12);
  EXPECT_NEAR(s.sim->stone_force_overflow[3], 0.5 * rho * 0.178 * a * u * u, 1e-12);
  std::printf("middle disc: p = %.6f m, phi = %.6f, F_D = %.6f N, F_L = %.6f N\n", p, phi,
              s.sim->stone_force_overflow[2], s.sim->stone_force_overflow[3]);
  // the stone's external force holds it (held over the step) with the drag's unexposed share
  EXPECT_GT(s.stones->stone_force_ext[2], s.sim->stone_force_overflow[2] - 1e-15);
}

TEST(Coupler, OverflowReactionSumsToMinusTheStonesLoad) {
  Scene s = row_in_uniform_flow(0.15, 0.4);
  const double b = s.fluid->params().flume_width;
  double sx = 0.0, sz = 0.0, cx = 0.0, cz = 0.0;
  for (int j = 0; j < s.stones->n(); ++j) sx += s.sim->stone_force_overflow[2 * j], sz += s.sim->stone_force_overflow[2 * j + 1];
  const std::vector<double>& r = s.sim->cell_overflow_reaction;
  for (std::size_t c = 0; c < r.size() / 2; ++c) cx += r[2 * c], cz += r[2 * c + 1];
  EXPECT_GT(sx, 0.0);
  EXPECT_NEAR(b * cx, -sx, 1e-15 * sx);
  EXPECT_NEAR(b * cz, -sz, 1e-15 * sz);
}

TEST(OverflowLoad, ReactionImpulseOnTheFacesEqualsTheReaction) {
  const Grid2D g = Grid2D::uniform(4, 3, 0.04, 0.03);
  std::vector<double> fxn(static_cast<std::size_t>(g.nface_x()), 1.0), fzn(static_cast<std::size_t>(g.nface_z()), 1.0);
  std::vector<double> u(fxn.size(), 0.0), w(fzn.size(), 0.0), r(2 * static_cast<std::size_t>(g.ncell()), 0.0);
  const int c = g.cell(1, 1), d = g.cell(2, 1);
  r[2 * c] = -2.0, r[2 * c + 1] = 3.0, r[2 * d] = 1.0;
  fxn[g.face_x(3, 1)] = 0.0;  // cell d's right face closed: its share all on its left face
  const double dt = 1e-3, rho = 1000.0, vol = g.cell_area(1);
  apply_overflow_reaction(g, fxn.data(), fzn.data(), r.data(), dt, rho, u.data(), w.data());
  EXPECT_DOUBLE_EQ(u[g.face_x(1, 1)], -2.0 * dt / (rho * vol * 2));
  EXPECT_DOUBLE_EQ(u[g.face_x(2, 1)], -2.0 * dt / (rho * vol * 2) + 1.0 * dt / (rho * vol));
  EXPECT_EQ(u[g.face_x(3, 1)], 0.0);
  EXPECT_DOUBLE_EQ(w[g.face_z(1, 1)], 3.0 * dt / (rho * vol * 2));
  EXPECT_DOUBLE_EQ(w[g.face_z(1, 2)], 3.0 * dt / (rho * vol * 2));
  double mx = 0.0, mz = 0.0;
  for (double v : u) mx += rho * vol * v;
  for (double v : w) mz += rho * vol * v;
  EXPECT_NEAR(mx, (-2.0 + 1.0) * dt, 1e-18);
  EXPECT_NEAR(mz, 3.0 * dt, 1e-18);
}

TEST(Coupler, DryOrBuriedStonesGetNoOverflowLoad) {
  // water below the stones' bottoms: every band is dry
  Scene dry = row_in_uniform_flow(0.005, 0.4);
  for (int j = 0; j < dry.stones->n(); ++j) {
    EXPECT_EQ(dry.sim->stone_force_overflow[2 * j], 0.0) << j;
    EXPECT_EQ(dry.sim->stone_force_overflow[2 * j + 1], 0.0) << j;
    EXPECT_EQ(dry.sim->stone_exposed_share[j], 0.0) << j;
  }
  // a fourth disc on the middle one's top: the middle one is buried
  std::vector<double> pos = kRow;
  pos.insert(pos.end(), {0.105, 0.068});
  Scene s = tank(0.2, 0.2, 0.01, 0.15, pos, kR, kCoupleDEM | kCoupleDrag | kCoupleOverflowLoad);
  std::fill(s.fluid->face_u.begin(), s.fluid->face_u.end(), 0.4);
  s.sim->update_fluid_forces();
  EXPECT_EQ(s.sim->stone_exposed_share[1], 0.0);
  EXPECT_EQ(s.sim->stone_force_overflow[2], 0.0);
  EXPECT_EQ(s.sim->stone_force_overflow[3], 0.0);
  EXPECT_GT(s.sim->stone_force_overflow[6], 0.0);  // the top disc takes the overflow
}

TEST(Coupler, OverflowLoadOffIsNotEnteredAndChangesNothing) {
  // the same coupled run with the effect off and with its coefficients changed: the same bits, no stage
  auto run = [](double cd) {
    Scene s = tank(0.2, 0.2, 0.01, 0.15, kRow, kR, kCoupleTwoWay);
    CouplerParams p = s.sim->params();
    p.overflow.drag_coefficient = cd;
    s.sim->set_params(p);
    s.sim->advance(0.05);
    EXPECT_EQ(s.sim->profile().find("overflow_load"), -1);
    return s.sim->export_state();
  };
  std::string diff;
  EXPECT_TRUE(same_bits(run(0.91), run(2.0), &diff)) << diff;
  // on: the stage runs every step and the run stays finite
  Scene on = tank(0.2, 0.2, 0.01, 0.15, kRow, kR, kCoupleTwoWay | kCoupleOverflowLoad);
  std::fill(on.fluid->face_u.begin(), on.fluid->face_u.end(), 0.2);
  on.sim->advance(0.05);
  const int st = on.sim->profile().find("overflow_load");
  ASSERT_GE(st, 0);
  EXPECT_GE(on.sim->profile().calls()[st], on.sim->step_count());
}
