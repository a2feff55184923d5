// The sphere law two contacts at a time (sphere_kernels_x2.h) against the scalar law it restates
// (sphere_kernels.h), its slow reference: the same bits in every load, energy and history, on random
// contacts and on each branch of the law (an empty spring, a spring along the normal, the Coulomb cap, a
// pull apart, the rolling cap, a rolling spring of zero stiffness), in either lane; and the pair geometry
// from the stones' arrays against the scalar geometry, coincident centres and open pairs included.
#include <gtest/gtest.h>

#include <array>
#include <cstdint>
#include <cstring>
#include <random>
#include <tuple>
#include <vector>

#include "stones/sphere_kernels.h"
#include "stones/sphere_kernels_x2.h"

#if defined(VOFDEM_SPHERE_X2)
namespace {

using namespace vofdem;
namespace sk = vofdem::sphere_kernels;
using Vec3 = Eigen::Vector3d;

constexpr double kRadius = 0.024, kMass = 0.153, kDt = 6.25e-5;

std::uint64_t bits(double x) {
  std::uint64_t b;
  std::memcpy(&b, &x, sizeof b);
  return b;
}

void expect_same_bits(const Vec3& a, const Vec3& b, const char* what, int k) {
  for (int d = 0; d < 3; ++d) EXPECT_EQ(bits(a[d]), bits(b[d])) << what << "[" << d << "] of case " << k;
}

SphereContactLaw law_with(double mu_r) {
  SphereContactLaw law;
  law.stiffness_normal = 1.865e5;
  law.friction = 0.6;
  law.rolling_friction = mu_r;
  law.rolling_damping = 0.3;
  return law;
}

struct Case {
  SphereContactGeometry g;
  SpherePairConstants c;
  Vec3 arm_i, arm_j;
  SphereContactHistory h;
};

// a contact of the law's branch `kind` (0: any; 1..6 the branches of the header)
Case make_case(std::mt19937_64& rng, const SphereContactLaw& law, int kind) {
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  const auto vec = [&](double s) { return Vec3(s * u(rng), s * u(rng), s * u(rng)); };
  Case c;
  c.g.n = vec(1.0).normalized();
  c.g.delta = 1e-4 * (1.5 + u(rng));
  c.g.point = vec(0.5);
  c.g.v_rel = vec(0.05);
  c.g.w_rel = vec(2.0);
  c.g.mu = law.friction;
  c.g.mu_r = law.rolling_friction;
  c.arm_i = kRadius * c.g.n, c.arm_j = -kRadius * c.g.n + vec(1e-3);
  c.h.spring = vec(1e-5);
  c.h.rolling = vec(1e-3);
  const double r_eff = 0.5 * kRadius, roll_inertia = 0.7 * kMass * kRadius * kRadius;
  c.c = sk::constants(0.5 * kMass, r_eff, roll_inertia, law.rolling_friction, law, 0.3);
  switch (kind) {
    case 1: c.h = SphereContactHistory(); break;                                         // empty springs
    case 2: c.h.spring = 3e-6 * c.g.n, c.h.rolling = 2e-4 * c.g.n; break;                // along the normal
    case 3: c.g.v_rel += 5.0 * c.g.n.cross(Vec3::UnitX()), c.h.spring = vec(1e-3); break; // Coulomb cap
    case 4: c.g.delta = 1e-7, c.g.v_rel = -0.3 * c.g.n; break;                           // pulled apart: fn < 0
    case 5: c.g.w_rel = 50.0 * c.g.n.cross(Vec3::UnitY()), c.h.rolling = vec(0.5); break; // rolling cap
    case 6: c.c.kr = 0.0, c.c.cr = 0.0; break;                                           // no rolling spring
    default: break;
  }
  return c;
}

// the scalar law and the two-lane law at cases a and b (a in lane 0), each on its own copy of the histories
void expect_lanes_equal_scalar(const Case& a, const Case& b, const SphereContactLaw& law, int k) {
  SphereContactHistory ha = a.h, hb = b.h, xa = a.h, xb = b.h;
  const SphereContactLoads sa = sk::apply_law(a.g, a.c, a.arm_i, a.arm_j, ha, law, kDt);
  const SphereContactLoads sb = sk::apply_law(b.g, b.c, b.arm_i, b.arm_j, hb, law, kDt);
  SphereContactLoads oa, ob;
  sk::x2::apply_law({&a.g, &a.c, &a.arm_i, &a.arm_j, &xa, &oa}, {&b.g, &b.c, &b.arm_i, &b.arm_j, &xb, &ob}, law,
                    kDt);
  for (const auto& [s, o, h, x] : {std::tie(sa, oa, ha, xa), std::tie(sb, ob, hb, xb)}) {
    expect_same_bits(s.force_i, o.force_i, "force_i", k);
    expect_same_bits(s.torque_i, o.torque_i, "torque_i", k);
    expect_same_bits(s.torque_j, o.torque_j, "torque_j", k);
    EXPECT_EQ(bits(s.energy_spring), bits(o.energy_spring)) << "energy_spring of case " << k;
    EXPECT_EQ(bits(s.power_damp), bits(o.power_damp)) << "power_damp of case " << k;
    EXPECT_EQ(bits(s.energy_slip), bits(o.energy_slip)) << "energy_slip of case " << k;
    expect_same_bits(h.spring, x.spring, "spring", k);
    expect_same_bits(h.rolling, x.rolling, "rolling", k);
  }
}

TEST(SphereKernelsX2, TheLawInEitherLaneIsTheScalarLawBitForBit) {
  std::mt19937_64 rng(7);
  for (const double mu_r : {0.0, 0.2}) {
    const SphereContactLaw law = law_with(mu_r);
    std::vector<Case> cases;
    for (int k = 0; k < 700; ++k) cases.push_back(make_case(rng, law, k % 7));
    for (std::size_t k = 0; k + 1 < cases.size(); ++k) {
      expect_lanes_equal_scalar(cases[k], cases[k + 1], law, static_cast<int>(k));
      expect_lanes_equal_scalar(cases[k + 1], cases[k], law, static_cast<int>(k));
    }
  }
}

TEST(SphereKernelsX2, TheBranchesAreTaken) {
  // the cases above reach the caps and the tension they are made for (else the comparison proves less)
  std::mt19937_64 rng(7);
  const SphereContactLaw law = law_with(0.2);
  Case slide = make_case(rng, law, 3), pull = make_case(rng, law, 4), roll = make_case(rng, law, 5);
  EXPECT_TRUE(sk::apply_law(slide.g, slide.c, slide.arm_i, slide.arm_j, slide.h, law, kDt).sliding);
  EXPECT_LT(sk::apply_law(pull.g, pull.c, pull.arm_i, pull.arm_j, pull.h, law, kDt).fn, 0.0);
  const double fn = sk::apply_law(roll.g, roll.c, roll.arm_i, roll.arm_j, roll.h, law, kDt).fn;
  const double cap = law.rolling_friction * roll.c.r_eff * fn;  // the rolling spring ends at its cap
  EXPECT_GT(cap, 0.0);
  EXPECT_NEAR(roll.h.rolling.norm(), cap, 1e-12 * cap);
}

TEST(SphereKernelsX2, ThePairGeometryFromTheArraysIsTheScalarGeometry) {
  // stones: 0 and 1 touch, 2 and 3 apart, 4 and 5 on one centre (the normal +z), 6 and 7 touch
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  const int n = 8;
  std::vector<double> pos(2 * n), y(n), radius(n), vel(2 * n), vel_y(n), omega(3 * n);
  for (int s = 0; s < n; ++s) {
    radius[s] = kRadius * (1.0 + 0.1 * u(rng));
    vel[2 * s] = 0.1 * u(rng), vel[2 * s + 1] = 0.1 * u(rng), vel_y[s] = 0.1 * u(rng);
    for (int d = 0; d < 3; ++d) omega[3 * s + d] = 3.0 * u(rng);
  }
  const auto place = [&](int s, double x, double yy, double z) { pos[2 * s] = x, y[s] = yy, pos[2 * s + 1] = z; };
  place(0, 0.1, 0.02, 0.05), place(1, 0.1 + 0.03, 0.02 + 0.02, 0.05 + 0.01);
  place(2, 0.3, 0.1, 0.1), place(3, 0.4, 0.1, 0.1);
  place(4, 0.5, 0.2, 0.2), place(5, 0.5, 0.2, 0.2);
  place(6, 0.7, 0.3, 0.1), place(7, 0.7 - 0.02, 0.3 + 0.01, 0.1 - 0.035);
  const SphereContactLaw law = law_with(0.2);
  const auto scalar = [&](int s) {
    SphereOfBody b;
    b.centre = b.com = Vec3(pos[2 * s], y[s], pos[2 * s + 1]);
    b.radius = radius[s];
    b.vel = Vec3(vel[2 * s], vel_y[s], vel[2 * s + 1]);
    b.omega = Vec3(omega[3 * s], omega[3 * s + 1], omega[3 * s + 2]);
    return b;
  };
  const sk::x2::Stones stones{pos.data(), y.data(), radius.data(), vel.data(), vel_y.data(), omega.data()};
  for (const auto& [ia, ja, ib, jb] : {std::array<int, 4>{0, 1, 2, 3}, {2, 3, 0, 1}, {4, 5, 6, 7}, {7, 6, 5, 4}}) {
    SphereContactGeometry g2[2];
    Vec3 arm2_i[2], arm2_j[2];
    const int touching = sk::x2::pair_geometry(stones, ia, ja, ib, jb, law, g2[0], arm2_i[0], arm2_j[0], g2[1],
                                               arm2_i[1], arm2_j[1]);
    const int pairs[2][2] = {{ia, ja}, {ib, jb}};
    for (int lane = 0; lane < 2; ++lane) {
      SphereContactGeometry g;
      Vec3 arm_i, arm_j;
      const bool t = sk::pair_geometry(scalar(pairs[lane][0]), scalar(pairs[lane][1]), law, g, arm_i, arm_j);
      ASSERT_EQ(t, (touching >> lane & 1) != 0) << "pair " << pairs[lane][0] << "-" << pairs[lane][1];
      if (!t) continue;
      const int k = pairs[lane][0];
      expect_same_bits(g.n, g2[lane].n, "n", k);
      EXPECT_EQ(bits(g.delta), bits(g2[lane].delta)) << "delta of stone " << k;
      expect_same_bits(g.point, g2[lane].point, "point", k);
      expect_same_bits(g.v_rel, g2[lane].v_rel, "v_rel", k);
      expect_same_bits(g.w_rel, g2[lane].w_rel, "w_rel", k);
      expect_same_bits(arm_i, arm2_i[lane], "arm_i", k);
      expect_same_bits(arm_j, arm2_j[lane], "arm_j", k);
    }
  }
}

}  // namespace
#endif
