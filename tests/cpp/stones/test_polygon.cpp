// Polygon stones' geometry (polygon.h) and contact manifolds (polygon_contact.h), by hand.
#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <stdexcept>
#include <vector>

#include "vofdem/stones/polygon.h"
#include "vofdem/stones/polygon_contact.h"
#include "vofdem/common/numbers.h"

using namespace vofdem;

namespace {
using vofdem::kPi;

// the rectangle [-a, a] x [-b, b] (CCW), moved by (x, z) and turned by angle
std::vector<double> box(double a, double b, double x = 0.0, double z = 0.0, double angle = 0.0) {
  const std::vector<double> body = {-a, -b, a, -b, a, b, -a, b};
  std::vector<double> out(8);
  polygon_to_world(body.data(), 4, x, z, angle, out.data());
  return out;
}

std::vector<double> normals(const std::vector<double>& v) {
  std::vector<double> u(v.size());
  polygon_edge_normals(v.data(), static_cast<int>(v.size() / 2), u.data());
  return u;
}

ContactManifold collide(const std::vector<double>& a, const std::vector<double>& b) {
  const auto ua = normals(a), ub = normals(b);
  return collide_polygons(a.data(), ua.data(), static_cast<int>(a.size() / 2), b.data(), ub.data(),
                          static_cast<int>(b.size() / 2));
}
}  // namespace

TEST(Polygon, PropertiesOfARectangleByHand) {
  const auto v = box(0.03, 0.01, 0.5, -0.2);
  const PolygonProperties p = polygon_properties(v.data(), 4);
  EXPECT_NEAR(p.area, 0.06 * 0.02, 1e-17);
  EXPECT_NEAR(p.centroid[0], 0.5, 1e-15);
  EXPECT_NEAR(p.centroid[1], -0.2, 1e-15);
  // J = A (w^2 + h^2) / 12 about the centroid
  EXPECT_NEAR(p.polar_moment, 0.0012 * (0.06 * 0.06 + 0.02 * 0.02) / 12.0, 1e-20);
  EXPECT_NEAR(p.bounding_radius, std::hypot(0.03, 0.01), 1e-15);
  EXPECT_NEAR(p.perimeter, 0.16, 1e-15);
  EXPECT_TRUE(polygon_is_convex_ccw(v.data(), 4));
  const std::vector<double> cw = {-1, -1, -1, 1, 1, 1, 1, -1};
  EXPECT_FALSE(polygon_is_convex_ccw(cw.data(), 4));
  const std::vector<double> dart = {0, 0, 2, -1, 1, 0, 2, 1};  // a reflex vertex
  EXPECT_FALSE(polygon_is_convex_ccw(dart.data(), 4));
}

TEST(Polygon, MatchingStoneOfARoundSectionIsTheSphere) {
  const double r = 0.024;
  const double area = kPi * r * r;
  EXPECT_NEAR(polygon_stone_volume(area), 4.0 / 3.0 * kPi * r * r * r, 1e-18);
  EXPECT_NEAR(polygon_nominal_diameter(area), 2.0 * r, 1e-16);
  // a 16-gon approaches the disc: J/A -> r^2/2, so I = 0.8 M J/A -> 0.4 M r^2 (to the polygon's error)
  std::vector<double> v;
  for (int k = 0; k < 16; ++k) v.push_back(r * std::cos(2 * kPi * k / 16)), v.push_back(r * std::sin(2 * kPi * k / 16));
  const PolygonProperties p = polygon_properties(v.data(), 16);
  EXPECT_NEAR(0.8 * p.polar_moment / p.area, 0.4 * r * r, 0.03 * 0.4 * r * r);
}

TEST(Polygon, RandomStonesAreConvexOfTheRequestedSizeAndReproducible) {
  PolygonSpec spec;
  std::mt19937_64 g1(7), g2(7);
  int counts[kPolygonMaxVertices + 1] = {0};
  double elong = 0.0;
  for (int s = 0; s < 400; ++s) {
    const double d = 0.048;
    const std::vector<double> v = random_convex_polygon(g1, spec, d);
    EXPECT_EQ(v, random_convex_polygon(g2, spec, d));
    const int n = static_cast<int>(v.size() / 2);
    ASSERT_GE(n, spec.vertices_min);
    ASSERT_LE(n, spec.vertices_max);
    ++counts[n];
    ASSERT_TRUE(polygon_is_convex_ccw(v.data(), n));
    const PolygonProperties p = polygon_properties(v.data(), n);
    EXPECT_NEAR(p.area, kPi * d * d / 4.0, 1e-14 * p.area);
    EXPECT_LT(std::hypot(p.centroid[0], p.centroid[1]), 1e-15);
    elong += polygon_width_across(v.data(), n, 0.0, 0.0, 1.0) / polygon_width_across(v.data(), n, 0.0, 1.0, 0.0);
  }
  for (int n = spec.vertices_min; n <= spec.vertices_max; ++n) EXPECT_GT(counts[n], 40) << n;
  // stretched along x: the mean extent ratio is near the aspect ratio 1.5 (the jitter spreads it)
  EXPECT_NEAR(elong / 400, spec.aspect_ratio, 0.15);
  PolygonSpec bad;
  bad.vertices_max = 4;
  EXPECT_THROW(bad.validate(), std::invalid_argument);
  bad = PolygonSpec{};
  bad.aspect_ratio = 0.5;
  EXPECT_THROW(random_convex_polygon(g1, bad, 0.048), std::invalid_argument);
}

TEST(Polygon, WidthAcrossADirection) {
  const std::vector<double> v = box(0.03, 0.01);
  EXPECT_NEAR(polygon_width_across(v.data(), 4, 0.0, 1.0, 0.0), 0.02, 1e-16);  // flow along x: height
  EXPECT_NEAR(polygon_width_across(v.data(), 4, 0.0, 0.0, -2.0), 0.06, 1e-16);
  EXPECT_NEAR(polygon_width_across(v.data(), 4, 0.5 * kPi, 1.0, 0.0), 0.06, 1e-16);  // turned upright
  EXPECT_NEAR(polygon_width_across(v.data(), 4, 0.0, 1.0, 1.0), 0.08 / std::sqrt(2.0), 1e-16);
}

TEST(Polygon, RectangleClipAreasByHand) {
  const std::vector<double> v = box(0.5, 0.5, 0.5, 0.5);  // the unit square
  std::vector<double> scratch(64);
  EXPECT_DOUBLE_EQ(polygon_rect_area(v.data(), 4, 0, 1, 0, 1, scratch.data()), 1.0);
  EXPECT_DOUBLE_EQ(polygon_rect_area(v.data(), 4, 0.25, 2, -1, 0.5, scratch.data()), 0.375);
  EXPECT_EQ(polygon_rect_area(v.data(), 4, 1.5, 2, 0, 1, scratch.data()), 0.0);
  // the unit square turned 45 degrees about its centre, cut by the vertical through its centre: half
  const std::vector<double> d = box(0.5, 0.5, 0.0, 0.0, 0.25 * kPi);
  EXPECT_NEAR(polygon_rect_area(d.data(), 4, 0, 5, -5, 5, scratch.data()), 0.5, 1e-15);
  // its top corner above z = 0.5: a triangle of height h = sqrt(2)/2 - 0.5 and area h^2
  const double h = std::sqrt(0.5) - 0.5;
  EXPECT_NEAR(polygon_rect_area(d.data(), 4, -5, 5, 0.5, 5, scratch.data()), h * h, 1e-15);
}

TEST(PolygonContact, FaceOnFaceGivesTwoPointsOfTheOverlap) {
  // B's left face 0.1 inside A's right face, both 2 x 2 squares, B shifted up by 0.5
  const auto a = box(1, 1), b = box(1, 1, 1.9, 0.5);
  const ContactManifold m = collide(a, b);
  ASSERT_EQ(m.count, 2);
  EXPECT_NEAR(m.normal[0], 1.0, 1e-15);
  EXPECT_NEAR(m.normal[1], 0.0, 1e-15);
  double zs[2];
  for (int k = 0; k < 2; ++k) {
    EXPECT_NEAR(m.point[k].depth, 0.1, 1e-14);
    EXPECT_NEAR(m.point[k].x, 0.95, 1e-14);  // half-way through the overlap
    zs[k] = m.point[k].z;
  }
  // the incident face clipped to the reference face's extent: z from -0.5 to 1
  EXPECT_NEAR(std::min(zs[0], zs[1]), -0.5, 1e-14);
  EXPECT_NEAR(std::max(zs[0], zs[1]), 1.0, 1e-14);
  // the same with the bodies swapped: the normal turns, the points stay
  const ContactManifold s = collide(b, a);
  ASSERT_EQ(s.count, 2);
  EXPECT_NEAR(s.normal[0], -1.0, 1e-15);
  EXPECT_NEAR(s.point[0].depth, 0.1, 1e-14);
}

TEST(PolygonContact, CornerIntoFaceGivesOnePointAndSeparatedGiveNone) {
  // B turned 45 degrees, its left corner 0.05 into A's right face
  const double h = std::sqrt(2.0);
  const auto a = box(1, 1), b = box(1, 1, 1.0 + h - 0.05, 0.2, 0.25 * kPi);
  const ContactManifold m = collide(a, b);
  ASSERT_EQ(m.count, 1);
  EXPECT_NEAR(m.point[0].depth, 0.05, 1e-14);
  EXPECT_NEAR(m.point[0].x, 0.975, 1e-14);
  EXPECT_NEAR(m.point[0].z, 0.2, 1e-14);
  EXPECT_NEAR(m.normal[0], 1.0, 1e-15);
  // apart, and touching without overlap: no points
  EXPECT_EQ(collide(a, box(1, 1, 2.01, 0.0)).count, 0);
  EXPECT_EQ(collide(a, box(1, 1, 2.0, 0.0)).count, 0);
}

TEST(PolygonContact, FeatureIdsStayWhileTheSameFeaturesTouch) {
  const auto a = box(1, 1);
  const ContactManifold m1 = collide(a, box(1, 1, 1.9, 0.5));
  const ContactManifold m2 = collide(a, box(1, 1, 1.92, 0.45, 0.01));
  ASSERT_EQ(m1.count, 2);
  ASSERT_EQ(m2.count, 2);
  for (int k = 0; k < 2; ++k) EXPECT_TRUE(m2.point[k].id == m1.point[0].id || m2.point[k].id == m1.point[1].id);
  EXPECT_NE(m1.point[0].id, m1.point[1].id);
}

TEST(PolygonContact, PolygonOnAWall) {
  // a box lying 0.01 into the bed z = 0: its two lower corners; tilted: its lowest corner only
  const auto v = box(0.5, 0.2, 3.0, 0.19);
  const auto u = normals(v);
  const ContactManifold m = collide_polygon_wall(v.data(), u.data(), 4, 0.0, 0.0, 0.0, 1.0);
  ASSERT_EQ(m.count, 2);
  EXPECT_NEAR(m.normal[1], -1.0, 1e-15);
  for (int k = 0; k < 2; ++k) {
    EXPECT_NEAR(m.point[k].depth, 0.01, 1e-14);
    EXPECT_NEAR(m.point[k].z, -0.005, 1e-14);
  }
  const auto t = box(0.5, 0.2, 3.0, 0.3, 0.3);
  const auto ut = normals(t);
  const ContactManifold c = collide_polygon_wall(t.data(), ut.data(), 4, 0.0, 0.0, 0.0, 1.0);
  double lowest = INFINITY;
  for (int k = 0; k < 4; ++k) lowest = std::min(lowest, t[2 * k + 1]);
  ASSERT_EQ(c.count, 1);
  EXPECT_NEAR(c.point[0].depth, -lowest, 1e-14);
}

TEST(PolygonContact, SeparationMatchesTheSlowReference) {
  // slow obvious reference: every edge normal of each polygon against every vertex of the other
  auto slow = [](const std::vector<double>& a, const std::vector<double>& b) {
    const auto ua = normals(a);
    double best = -INFINITY;
    for (std::size_t k = 0; k < a.size() / 2; ++k) {
      double s = INFINITY;
      for (std::size_t j = 0; j < b.size() / 2; ++j)
        s = std::min(s, ua[2 * k] * (b[2 * j] - a[2 * k]) + ua[2 * k + 1] * (b[2 * j + 1] - a[2 * k + 1]));
      best = std::max(best, s);
    }
    return best;
  };
  std::mt19937_64 rng(9);
  PolygonSpec spec;
  int overlapping = 0;
  for (int trial = 0; trial < 2000; ++trial) {
    const auto pa = random_convex_polygon(rng, spec, 0.05), pb = random_convex_polygon(rng, spec, 0.05);
    std::vector<double> a(pa.size()), b(pb.size());
    polygon_to_world(pa.data(), static_cast<int>(pa.size() / 2), 1.0, 0.2, 6.3 * rng_uniform01(rng), a.data());
    polygon_to_world(pb.data(), static_cast<int>(pb.size() / 2), 1.0 + 0.06 * rng_uniform01(rng),
                     0.2 + 0.06 * rng_uniform01(rng), 6.3 * rng_uniform01(rng), b.data());
    const auto ua = normals(a), ub = normals(b);
    const double fast = polygon_separation(a.data(), ua.data(), static_cast<int>(a.size() / 2), b.data(), ub.data(),
                                           static_cast<int>(b.size() / 2));
    const double ref = std::max(slow(a, b), slow(b, a));
    ASSERT_EQ(fast > 0.0, ref > 0.0) << trial;
    overlapping += ref < 0.0;
    EXPECT_EQ(fast, ref) << trial;
  }
  EXPECT_GT(overlapping, 200);
}

TEST(PolygonContact, IncidentEdgeAndItsMarginByHand) {
  // a unit square's normals: (0,-1), (1,0), (0,1), (-1,0); against n = (1, 0) the left edge (3) is the
  // most anti-parallel (n . u = -1), the bottom and top next (0): a lead of 1
  const auto u = normals(box(1, 1));
  double margin = -1.0;
  EXPECT_EQ(polygon_incident_edge(u.data(), 4, 1.0, 0.0, &margin), 3);
  EXPECT_DOUBLE_EQ(margin, 1.0);
  // n turned by 45 degrees towards z: bottom and left tie (-sqrt(1/2)); the first is kept, the lead is 0
  const double c = std::sqrt(0.5);
  EXPECT_EQ(polygon_incident_edge(u.data(), 4, c, c, &margin), 0);
  EXPECT_DOUBLE_EQ(margin, 0.0);
  // turned by 30 degrees: left (-cos 30) leads bottom (-sin 30) by cos 30 - sin 30
  const double cs = std::cos(kPi / 6), sn = std::sin(kPi / 6);
  EXPECT_EQ(polygon_incident_edge(u.data(), 4, cs, sn, &margin), 3);
  EXPECT_NEAR(margin, cs - sn, 1e-15);
  // the manifold with the incident edge given is the one that finds it
  const auto a = box(1, 1), b = box(1, 1, 1.9, 0.5, 0.05);
  const auto ua = normals(a), ub = normals(b);
  const int inc = polygon_incident_edge(ub.data(), 4, ua[2], ua[3]);
  const ContactManifold found = polygon_manifold(a.data(), ua.data(), 4, b.data(), ub.data(), 4, 0, 1);
  const ContactManifold given = polygon_manifold(a.data(), ua.data(), 4, b.data(), ub.data(), 4, 0, 1, inc);
  ASSERT_EQ(found.count, 2);
  ASSERT_EQ(given.count, found.count);
  for (int k = 0; k < 2; ++k) {
    EXPECT_EQ(given.point[k].x, found.point[k].x);
    EXPECT_EQ(given.point[k].depth, found.point[k].depth);
  }
}
