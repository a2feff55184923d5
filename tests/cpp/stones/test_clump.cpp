// Clumps of overlapping spheres (clump.h): one sphere exactly; two equal spheres against the lens
// formula and a slice-by-slice derivation; the power-cell quadrature against the exact pair and chain
// formulas, with its error bound and convergence; contained and disjoint spheres; invariance to a rigid
// motion of the input; the principal frame; the quarried-stone library's equivalent diameter and aspect
// ratios; determinism and bad input.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <random>
#include <stdexcept>
#include <string>
#include <vector>

#include "vofdem/stones/clump.h"

using namespace vofdem;
using Vec3 = Eigen::Vector3d;
using Mat3 = Eigen::Matrix3d;

namespace {

double rel(const Mat3& a, const Mat3& b) { return (a - b).norm() / b.norm(); }

// errors of quadrature moments q against a reference: volume (relative), centroid (over a length),
// inertia about the centroid (relative, Frobenius)
struct Errors {
  double volume, centroid, inertia;
};
Errors errors(const VolumeMoments& q, const VolumeMoments& ref, double length) {
  return {std::fabs(q.m0 / ref.m0 - 1.0), (q.centroid() - ref.centroid()).norm() / length,
          rel(q.inertia_about_centroid(), ref.inertia_about_centroid())};
}

// 3-point Gauss-Legendre on [a, b]: exact for polynomials of degree <= 5
template <class F>
double gauss3(F f, double a, double b) {
  const double m = 0.5 * (a + b), h = 0.5 * (b - a), x = std::sqrt(0.6);
  return h * (5.0 / 9.0 * f(m - h * x) + 8.0 / 9.0 * f(m) + 5.0 / 9.0 * f(m + h * x));
}

}  // namespace

TEST(Clump, SingleSphereExact) {
  const double r = 0.024;
  const Clump c({{Vec3(0.3, -0.1, 0.05), r}});
  const double v = 4.0 / 3.0 * M_PI * r * r * r;
  EXPECT_NEAR(c.volume(), v, 1e-14 * v);
  EXPECT_NEAR(c.equivalent_diameter(), 2.0 * r, 1e-15);
  for (int k = 0; k < 3; ++k) EXPECT_NEAR(c.principal_inertia()[k], 0.4 * v * r * r, 1e-13 * v * r * r);
  EXPECT_LT((c.input_centroid() - Vec3(0.3, -0.1, 0.05)).norm(), 1e-16);
  // the quadrature is exact for one sphere too (every ray ends at r; the rule integrates w w^T exactly)
  const VolumeMoments q = union_moments_quadrature({{Vec3(0.3, -0.1, 0.05), r}}, 8);
  const Errors e = errors(q, sphere_moments({Vec3(0.3, -0.1, 0.05), r}), r);
  EXPECT_LT(e.volume, 1e-14);
  EXPECT_LT(e.centroid, 1e-13);
  EXPECT_LT(e.inertia, 1e-12);
}

// Two equal spheres of radius R at x = -d/2 and +d/2. The union's slice at x is the disk of the nearer
// centre, of radius^2 rho^2 = R^2 - (|x| - d/2)^2, for |x| <= R + d/2. With y = |x| - d/2 in [-d/2, R]
// and both halves:
//   V    = 2 pi int (R^2 - y^2) dy                            = 2 pi (2 R^3/3 + R^2 d/2 - d^3/24)
//   J_xx = 2 int pi rho^4 / 2 dy  (disk: int r^2 dA = pi rho^4 / 2)
//   J_yy = 2 int [pi rho^4 / 4 + pi rho^2 (y + d/2)^2] dy       (disk about its diameter, plus x^2 dA)
// and the textbook lens gives V = 8 pi R^3/3 - pi (4R + d)(2R - d)^2 / 12 as a check of the first.
TEST(Clump, TwoEqualSpheresAgainstLensDerivation) {
  const double r = 0.02;
  for (const double d : {0.004, 0.02, 0.035}) {
    const double v = 2.0 * M_PI * (2.0 * r * r * r / 3.0 + r * r * d / 2.0 - d * d * d / 24.0);
    const double v_lens = 8.0 * M_PI * r * r * r / 3.0 - M_PI * (4.0 * r + d) * (2.0 * r - d) * (2.0 * r - d) / 12.0;
    ASSERT_NEAR(v, v_lens, 1e-15 * v);
    auto rho2 = [&](double y) { return r * r - y * y; };
    const double jxx = 2.0 * gauss3([&](double y) { return M_PI * rho2(y) * rho2(y) / 2.0; }, -d / 2, r);
    const double jyy = 2.0 * gauss3(
                                 [&](double y) {
                                   return M_PI * rho2(y) * rho2(y) / 4.0 + M_PI * rho2(y) * (y + d / 2) * (y + d / 2);
                                 },
                                 -d / 2, r);
    // the input along a tilted axis, away from the origin
    const Vec3 axis = Vec3(1.0, 2.0, -0.5).normalized(), o(0.4, 0.1, -0.2);
    const Clump c({{o - 0.5 * d * axis, r}, {o + 0.5 * d * axis, r}});
    EXPECT_NEAR(c.volume(), v, 1e-13 * v) << d;
    EXPECT_LT((c.input_centroid() - o).norm(), 1e-15) << d;
    // principal moments ascending: the long axis first
    EXPECT_NEAR(c.principal_inertia()[0], jxx, 1e-12 * jxx) << d;
    EXPECT_NEAR(c.principal_inertia()[1], jyy, 1e-12 * jyy) << d;
    EXPECT_NEAR(c.principal_inertia()[2], jyy, 1e-12 * jyy) << d;
    EXPECT_LT((c.orientation() * Vec3::UnitX()).cross(axis).norm(), 1e-12) << d;
  }
}

// the quadrature against the exact union of two unequal spheres at several overlaps: within the stated
// bound at the default order, and converging (32 -> 256: the errors fall by more than 10; about n^-2
// but not monotone, as the kinks cross the nodes)
TEST(Clump, QuadratureErrorBoundAgainstExactPair) {
  const ClumpSphere a{Vec3(0.01, 0.02, 0.03), 0.024};
  for (const double d : {0.009, 0.016, 0.024, 0.036}) {
    const ClumpSphere b{a.centre + d * Vec3(0.6, 0.0, 0.8), 0.017};
    const VolumeMoments ex = sphere_pair_union_moments(a, b);
    const Errors e = errors(union_moments_quadrature({a, b}), ex, a.radius);
    EXPECT_LT(e.volume, 2e-5) << d;
    EXPECT_LT(e.centroid, 2e-5) << d;
    EXPECT_LT(e.inertia, 1e-4) << d;
    const Errors e32 = errors(union_moments_quadrature({a, b}, 32), ex, a.radius);
    const Errors e256 = errors(union_moments_quadrature({a, b}, 256), ex, a.radius);
    EXPECT_GT((e32.volume + e32.inertia) / (e256.volume + e256.inertia), 10.0) << d;
    std::printf("pair d = %.3f: quadrature errors V %.1e / %.1e / %.1e, J %.1e / %.1e / %.1e at n = 32 / 128 / 256\n",
                d, e32.volume, e.volume, e256.volume, e32.inertia, e.inertia, e256.inertia);
  }
}

// three spheres in a chain, the ends apart: inclusion-exclusion is exact,
// |A u B u C| = |A u B| + |B u C| - |B| (A n C empty), for every moment
TEST(Clump, QuadratureAgainstExactChain) {
  const ClumpSphere a{Vec3(0.0, 0.0, 0.0), 0.02}, b{Vec3(0.03, 0.01, 0.0), 0.018}, c{Vec3(0.05, 0.03, 0.01), 0.015};
  ASSERT_GT((c.centre - a.centre).norm(), a.radius + c.radius);
  const VolumeMoments ex = sphere_pair_union_moments(a, b) + sphere_pair_union_moments(b, c) - sphere_moments(b);
  const Errors e = errors(union_moments({a, b, c}), ex, 0.02);
  EXPECT_LT(e.volume, 2e-5);
  EXPECT_LT(e.centroid, 2e-5);
  EXPECT_LT(e.inertia, 1e-4);
}

// a sphere inside another adds nothing; spheres apart add up; in both the exact and quadrature paths
TEST(Clump, ContainedAndDisjointSpheres) {
  const ClumpSphere big{Vec3(0.0, 0.0, 0.0), 0.03}, small{Vec3(0.005, -0.004, 0.01), 0.012};
  const ClumpSphere far{Vec3(0.1, 0.0, 0.0), 0.01};
  const VolumeMoments inside = sphere_pair_union_moments(big, small);
  EXPECT_NEAR(inside.m0, sphere_moments(big).m0, 1e-15 * inside.m0);
  const VolumeMoments apart = sphere_pair_union_moments(big, far);
  EXPECT_NEAR(apart.m0, sphere_moments(big).m0 + sphere_moments(far).m0, 1e-15 * apart.m0);
  const Errors e = errors(union_moments_quadrature({big, small, far}), apart, 0.03);
  EXPECT_LT(e.volume, 1e-13);
  EXPECT_LT(e.centroid, 1e-13);
  EXPECT_LT(e.inertia, 1e-12);
}

// a rigid motion of the input moves the centroid with it and leaves the volume, the principal moments
// and the body-frame shape alone: to round-off for a pair (exact), within the quadrature's bound for four
// spheres (the direction grid does not turn with the input)
TEST(Clump, InvariantToRigidMotionOfInput) {
  const Eigen::Quaterniond rot(Eigen::AngleAxisd(0.9, Vec3(0.2, -0.7, 0.4).normalized()));
  const Vec3 shift(0.7, -0.3, 1.1);
  const std::vector<std::vector<ClumpSphere>> shapes = {
      {{Vec3(0.0, 0.0, 0.0), 0.02}, {Vec3(0.015, 0.01, -0.005), 0.016}},
      {{Vec3(0.0, 0.0, 0.0), 0.02}, {Vec3(0.015, 0.01, -0.005), 0.016}, {Vec3(-0.01, 0.012, 0.01), 0.014},
       {Vec3(0.004, -0.015, 0.006), 0.012}}};
  for (const auto& s : shapes) {
    std::vector<ClumpSphere> moved = s;
    for (ClumpSphere& c : moved) c.centre = rot * c.centre + shift;
    const Clump a(s), b(moved);
    const double tol = s.size() == 2 ? 1e-12 : 1e-4;
    EXPECT_NEAR(b.volume() / a.volume(), 1.0, tol) << s.size();
    EXPECT_LT((b.principal_inertia() - a.principal_inertia()).norm() / a.principal_inertia().norm(), tol) << s.size();
    EXPECT_LT((b.input_centroid() - (rot * a.input_centroid() + shift)).norm(), tol * 0.02) << s.size();
    // the body-frame sphere centres agree up to the sign of each principal axis
    for (std::size_t k = 0; k < s.size(); ++k) {
      const Vec3 ca = a.spheres()[k].centre.cwiseAbs(), cb = b.spheres()[k].centre.cwiseAbs();
      EXPECT_LT((ca - cb).norm(), s.size() == 2 ? 1e-14 : 1e-5) << s.size();
    }
  }
}

// in the principal frame the centroid is at the origin and the inertia tensor diagonal
TEST(Clump, StoredInPrincipalFrame) {
  for (const std::string& name : quarried_stone_names()) {
    const Clump c = quarried_stone(name, 0.048);
    const VolumeMoments m = union_moments(c.spheres());
    EXPECT_LT(m.centroid().norm(), 1e-15) << name;
    const Mat3 j = m.inertia_about_centroid();
    EXPECT_LT((j - Mat3(j.diagonal().asDiagonal())).norm(), 1e-12 * j.norm()) << name;
    EXPECT_LT((j.diagonal() - c.principal_inertia()).norm(), 1e-12 * j.norm()) << name;
    EXPECT_LE(c.principal_inertia()[0], c.principal_inertia()[1]) << name;
    EXPECT_LE(c.principal_inertia()[1], c.principal_inertia()[2]) << name;
  }
}

// the library: the requested volume-equivalent diameter (and against a 4x finer quadrature, within
// the bound), the requested aspect ratios, overlapping spheres, their number
TEST(Clump, LibraryShapesHaveRequestedSizeAndAspect) {
  const double d = 0.048;
  const std::vector<int> count = {2, 3, 4, 8};
  const auto names = quarried_stone_names();
  ASSERT_EQ(names.size(), count.size());
  for (std::size_t k = 0; k < names.size(); ++k) {
    for (const auto& [p, q] : {std::make_pair(0.8, 0.6), std::make_pair(0.9, 0.7)}) {
      const Clump c = quarried_stone(names[k], d, p, q);
      EXPECT_EQ(static_cast<int>(c.spheres().size()), count[k]);
      EXPECT_NEAR(c.equivalent_diameter(), d, 1e-14) << names[k];
      if (p == 0.8) {
        const double v_fine = union_moments_quadrature(c.spheres(), 512).m0;
        EXPECT_NEAR(v_fine / c.volume(), 1.0, 2e-5) << names[k];
      }
      const Vec3 aspect = c.aspect_ratios();
      EXPECT_NEAR(aspect[1], names[k] == "pair_2" ? q : p, 1e-12) << names[k];
      EXPECT_NEAR(aspect[2], q, 1e-12) << names[k];
      EXPECT_GT(c.sphere_volume_sum(), 1.05 * c.volume()) << names[k];  // the spheres overlap
      // the long axis is the axis of least inertia
      const Vec3 e = c.principal_extents();
      EXPECT_NEAR(e[0], e.maxCoeff(), 1e-15) << names[k];
      if (k == 0) continue;
      std::printf("%s (1 : %.1f : %.1f), d_eq 48 mm: extents %.2f %.2f %.2f mm, sum of spheres / union %.3f\n",
                  names[k].c_str(), p, q, 1e3 * e[0], 1e3 * e[1], 1e3 * e[2], c.sphere_volume_sum() / c.volume());
    }
  }
}

// the bounding radius about the centroid: two equal spheres 2c apart reach c + r; a pair_2 of 1 : q : q
// along its long axis reaches half its length, its extent e_1 / 2
TEST(Clump, BoundingRadiusByHand) {
  const Clump two({{Vec3(0.01, 0.02, -0.03), 0.01}, {Vec3(0.022, 0.02, -0.03), 0.01}});
  EXPECT_NEAR(two.bounding_radius(), 0.006 + 0.01, 1e-15);
  const Clump pair = quarried_stone("pair_2", 0.048);
  EXPECT_NEAR(pair.bounding_radius(), 0.5 * pair.principal_extents()[0], 1e-15);
  EXPECT_EQ(pair.bounding_radius(), bounding_radius(pair.spheres()));
  // scaled: the same shape times the factor
  EXPECT_NEAR(pair.scaled(2.0).bounding_radius(), 2.0 * pair.bounding_radius(), 1e-15);
}

TEST(Clump, DeterministicBitForBit) {
  const Clump a = quarried_stone("box_8", 0.048), b = quarried_stone("box_8", 0.048);
  EXPECT_EQ(std::memcmp(a.principal_inertia().data(), b.principal_inertia().data(), 3 * sizeof(double)), 0);
  EXPECT_EQ(a.volume(), b.volume());
  for (std::size_t k = 0; k < a.spheres().size(); ++k) {
    EXPECT_EQ(std::memcmp(a.spheres()[k].centre.data(), b.spheres()[k].centre.data(), 3 * sizeof(double)), 0);
  }
}

TEST(Clump, BadInputNamesParameter) {
  auto message = [](auto f) -> std::string {
    try {
      f();
    } catch (const std::invalid_argument& e) {
      return e.what();
    }
    return "";
  };
  EXPECT_NE(message([] { Clump({{Vec3::Zero(), 0.0}}); }).find("radius"), std::string::npos);
  EXPECT_NE(message([] { Clump(std::vector<ClumpSphere>{}); }).find("spheres"), std::string::npos);
  EXPECT_NE(message([] { quarried_stone("cube", 0.048); }).find("name"), std::string::npos);
  EXPECT_NE(message([] { quarried_stone("box_8", -1.0); }).find("d_eq"), std::string::npos);
  EXPECT_NE(message([] { quarried_stone("box_8", 0.048, 0.8, 0.4); }).find("ratio_short"), std::string::npos);
  EXPECT_NE(message([] { quarried_stone("box_8", 0.048, 0.5, 0.6); }).find("ratio_intermediate"), std::string::npos);
  EXPECT_NE(message([] { union_moments_quadrature({{Vec3::Zero(), 1.0}}, 1); }).find("order"), std::string::npos);
}
