// Porosity from polygon stones: exact polygon-cell areas against a slow reference, their sum, a
// polygon equal to a cell, the refused lookup table.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <stdexcept>
#include <vector>

#include "vofdem/stones/polygon.h"
#include "vofdem/coupling/porosity_map.h"

using namespace vofdem;

namespace {
// slow obvious reference: midpoint rule on the length of each vertical chord of the convex polygon
// (world vertices w) inside [z0, z1]
double reference_area(const std::vector<double>& w, double x0, double x1, double z0, double z1) {
  const int n = static_cast<int>(w.size() / 2), cols = 20000;
  const double h = (x1 - x0) / cols;
  double sum = 0.0;
  for (int c = 0; c < cols; ++c) {
    const double x = x0 + h * (c + 0.5);
    double lo = INFINITY, hi = -INFINITY;
    for (int k = 0; k < n; ++k) {
      const int l = (k + 1) % n;
      const double ax = w[2 * k], az = w[2 * k + 1], bx = w[2 * l], bz = w[2 * l + 1];
      if ((x - ax) * (x - bx) > 0.0 || ax == bx) continue;
      const double z = az + (x - ax) / (bx - ax) * (bz - az);
      lo = std::min(lo, z);
      hi = std::max(hi, z);
    }
    if (hi > lo) sum += std::max(0.0, std::min(z1, hi) - std::max(z0, lo));
  }
  return sum * h;
}

PorosityParams params(double r_max, PorosityMethod method = PorosityMethod::kExact) {
  PorosityParams p;
  p.method = method;
  p.r_min = r_max;
  p.r_max = r_max;
  p.max_discs = 8;
  return p;
}
}  // namespace

TEST(PolygonPorosity, AreasSumToThePolygonAndMatchASlowReference) {
  const Grid2D g = Grid2D::graded(40, 1.0, 0.30, 0.01, 0.005, 0.02);
  std::mt19937_64 rng(4);
  PolygonSpec spec;
  for (int trial = 0; trial < 3; ++trial) {
    const std::vector<double> v = random_convex_polygon(rng, spec, 0.048);
    const int n = static_cast<int>(v.size() / 2);
    const PolygonProperties q = polygon_properties(v.data(), n);
    const double x = 0.3 + 0.1 * rng_uniform01(rng), z = 0.04 + 0.05 * rng_uniform01(rng);
    const double angle = 6.0 * rng_uniform01(rng);
    PorosityMapper m(g, params(q.bounding_radius));
    const int off[2] = {0, n};
    m.map_polygons(1, &x, &z, &angle, v.data(), off, nullptr);
    double sum = 0.0;
    for (int p = m.stone_cell_offsets()[0]; p < m.stone_cell_offsets()[1]; ++p) sum += m.stone_cell_area()[p];
    EXPECT_NEAR(sum, q.area, 1e-14 * q.area) << trial;
    EXPECT_GT(m.stone_cell_offsets()[1], 10);  // across many cells
    std::vector<double> w(v.size());
    polygon_to_world(v.data(), n, x, z, angle, w.data());
    for (int p = m.stone_cell_offsets()[0]; p < m.stone_cell_offsets()[1]; ++p) {
      const int c = m.stone_cell_index()[p], i = c % g.nx(), k = c / g.nx();
      const double ref = reference_area(w, g.x_face(i), g.x_face(i + 1), g.z_face(k), g.z_face(k + 1));
      EXPECT_NEAR(m.stone_cell_area()[p], ref, 1e-7 * q.area) << trial << " cell " << c;
    }
    // eq. (11) on the mapped areas
    for (int p = m.stone_cell_offsets()[0]; p < m.stone_cell_offsets()[1]; ++p) {
      const int c = m.stone_cell_index()[p];
      const double ac = g.cell_area(c / g.nx());
      EXPECT_NEAR(m.cell_porosity()[c], 1.0 - (1.0 - 0.41) * m.cell_solid_area()[c] / ac, 1e-14);
    }
  }
}

TEST(PolygonPorosity, APolygonEqualToACellFillsItAlone) {
  const Grid2D g = Grid2D::uniform(10, 10, 1.0, 0.5);  // cells 0.1 x 0.05
  const std::vector<double> v = {-0.05, -0.025, 0.05, -0.025, 0.05, 0.025, -0.05, 0.025};
  PorosityMapper m(g, params(std::hypot(0.05, 0.025)));
  const double x = 0.35, z = 0.175, angle = 0.0;  // the cell (3, 3)
  const int off[2] = {0, 4};
  m.map_polygons(1, &x, &z, &angle, v.data(), off, nullptr);
  const int c = g.cell(3, 3);
  EXPECT_NEAR(m.cell_solid_area()[c], 0.005, 1e-16);
  EXPECT_NEAR(m.cell_porosity()[c], 0.41, 1e-14);
  int touched = 0;
  // round-off of the vertex coordinates (0.35 - 0.05) may leave slivers of ~1e-18 m^2 next door
  for (int q = 0; q < g.ncell(); ++q) touched += m.cell_solid_area()[q] > 1e-14 * 0.005;
  EXPECT_EQ(touched, 1);
  // half a cell to the right: two halves
  const double x2 = 0.4;
  m.map_polygons(1, &x2, &z, &angle, v.data(), off, nullptr);
  EXPECT_NEAR(m.cell_solid_area()[g.cell(3, 3)], 0.0025, 1e-16);
  EXPECT_NEAR(m.cell_solid_area()[g.cell(4, 3)], 0.0025, 1e-16);
}

TEST(PolygonPorosity, TheLookupTableIsForDiscs) {
  const Grid2D g = Grid2D::uniform(10, 10, 1.0, 0.5);
  const std::vector<double> v = {-0.05, -0.025, 0.05, -0.025, 0.05, 0.025, -0.05, 0.025};
  PorosityMapper m(g, params(0.06, PorosityMethod::kLookup));
  const double x = 0.35, z = 0.175, angle = 0.0;
  const int off[2] = {0, 4};
  try {
    m.map_polygons(1, &x, &z, &angle, v.data(), off, nullptr);
    FAIL() << "lookup accepted for polygons";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("exact"), std::string::npos) << e.what();
  }
  // a polygon reaching beyond r_max is refused too
  PorosityMapper small(g, params(0.03));
  EXPECT_THROW(small.map_polygons(1, &x, &z, &angle, v.data(), off, nullptr), std::invalid_argument);
}
