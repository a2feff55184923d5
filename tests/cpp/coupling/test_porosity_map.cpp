// Porosity from stone discs (seed section 2.4, eq. 11): disc-rectangle areas, the mapper, the lookup.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <stdexcept>
#include <vector>

#include "vofdem/coupling/porosity_map.h"
#include "vofdem/common/numbers.h"

using namespace vofdem;

namespace {
using vofdem::kPi;

// slow obvious reference: midpoint rule on the length of each vertical chord inside [z0, z1]
double reference_area(double cx, double cz, double r, double x0, double x1, double z0, double z1) {
  const double a = std::max(x0, cx - r), b = std::min(x1, cx + r);
  if (b <= a) return 0.0;
  const int n = 200000;
  const double h = (b - a) / n;
  double sum = 0.0;
  for (int i = 0; i < n; ++i) {
    const double x = a + h * (i + 0.5);
    const double s = std::sqrt(std::max(0.0, r * r - (x - cx) * (x - cx)));
    sum += std::max(0.0, std::min(z1, cz + s) - std::max(z0, cz - s));
  }
  return sum * h;
}

Grid2D paper_grid() { return Grid2D::graded(40, 1.0, 0.30, 0.01, 0.005, 0.02); }

PorosityParams params(PorosityMethod method, double r_min, double r_max, int m = 8, int max_discs = 64) {
  PorosityParams p;
  p.method = method;
  p.r_min = r_min;
  p.r_max = r_max;
  p.m = m;
  p.max_discs = max_discs;
  return p;
}
}  // namespace

TEST(DiscRectArea, HandComputedValues) {
  const double r = 0.024, full = kPi * r * r;
  EXPECT_NEAR(disc_rect_area(0.5, 0.5, r, 0, 1, 0, 1), full, 1e-15 * full);
  EXPECT_NEAR(disc_rect_area(0, 0, r, 0, 1, 0, 1), full / 4, 1e-15 * full);
  EXPECT_NEAR(disc_rect_area(0, 0.5, r, 0, 1, 0, 1), full / 2, 1e-15 * full);
  EXPECT_DOUBLE_EQ(disc_rect_area(0, 0, r, -0.01, 0.005, -0.002, 0.003), 0.015 * 0.005);
  EXPECT_EQ(disc_rect_area(0, 0, r, 0.03, 0.04, 0, 1), 0.0);
  const double theta = 2 * kPi / 3;  // segment cut at r/2 from the centre
  EXPECT_NEAR(disc_rect_area(0, 0, r, r / 2, 1, -1, 1), r * r * (theta - std::sin(theta)) / 2, 1e-13 * full);
}

TEST(DiscRectArea, MatchesTheSlowReferenceForEveryRelativePosition) {
  // a 4.8 cm stone against a 2.5 cm x 1.0 cm cell, centres on a lattice around and inside the cell
  const double r = 0.024;
  for (double cx = -0.03; cx <= 0.056; cx += 0.0071) {
    for (double cz = -0.03; cz <= 0.041; cz += 0.0053) {
      const double got = disc_rect_area(cx, cz, r, 0.0, 0.025, 0.0, 0.01);
      EXPECT_NEAR(got, reference_area(cx, cz, r, 0.0, 0.025, 0.0, 0.01), 1e-6 * r * r) << cx << " " << cz;
    }
  }
}

TEST(DiscRectArea, RefusesBadInput) {
  EXPECT_THROW(disc_rect_area(0, 0, -1e-3, 0, 1, 0, 1), std::invalid_argument);
  EXPECT_THROW(disc_rect_area(0, 0, 0.01, 1, 0, 0, 1), std::invalid_argument);
  EXPECT_THROW(disc_rect_area(std::nan(""), 0, 0.01, 0, 1, 0, 1), std::invalid_argument);
}

TEST(PorosityMapper, DiscOverManyCellsSumsToPiRSquared) {
  const Grid2D g = Grid2D::uniform(60, 50, 0.3, 0.25);
  const double r = 0.024;
  PorosityMapper mp(g, params(PorosityMethod::kExact, r, r));
  mp.map({0.1234567}, {0.1111111}, {r});
  double sum = 0.0;
  for (int p = mp.stone_cell_offsets()[0]; p < mp.stone_cell_offsets()[1]; ++p) sum += mp.stone_cell_area()[p];
  EXPECT_GT(mp.stone_cell_offsets()[1], 80);
  EXPECT_NEAR(sum, kPi * r * r, 1e-12 * kPi * r * r);
}

TEST(PorosityMapper, OverlapIsCappedAndPorosityStaysInRange) {
  const Grid2D g = paper_grid();
  PorosityMapper mp(g, params(PorosityMethod::kExact, 0.024, 0.024));
  mp.map({0.5, 0.5, 0.51}, {0.1, 0.1, 0.1}, {0.024, 0.024, 0.024});
  const int c = g.cell(g.locate_x(0.5), g.locate_z(0.1));
  EXPECT_EQ(mp.cell_solid_area()[c], g.cell_area(g.locate_z(0.1)));
  EXPECT_EQ(mp.cell_porosity()[c], 0.41);
  for (int k = 0; k < g.nz(); ++k)
    for (int i = 0; i < g.nx(); ++i) {
      EXPECT_LE(mp.cell_solid_area()[g.cell(i, k)], g.cell_area(k));
      EXPECT_GE(mp.cell_porosity()[g.cell(i, k)], 0.41);
      EXPECT_LE(mp.cell_porosity()[g.cell(i, k)], 1.0);
    }
}

TEST(PorosityMapper, LookupIsExactAtSubareaCentres) {
  // on the paper's graded rows, centres at sub-area centres and radii on the table nodes
  const Grid2D g = paper_grid();
  const int m = 5;
  PorosityParams pl = params(PorosityMethod::kLookup, 0.0216, 0.0264, m);
  pl.dr = 0.0012;
  PorosityMapper lk(g, pl);
  PorosityMapper ex(g, params(PorosityMethod::kExact, 0.0216, 0.0264, m));
  std::mt19937 rng(42);
  std::vector<double> x, z, r;
  for (int j = 0; j < 50; ++j) {
    const int i = rng() % g.nx(), k = rng() % g.nz(), a = rng() % m, b = rng() % m, q = rng() % 5;
    x.push_back(g.x_face(i) + g.dx() * (a + 0.5) / m);
    z.push_back(g.z_face(k) + g.dz(k) * (b + 0.5) / m);
    r.push_back(0.0216 + 0.0012 * q);
  }
  lk.map(x, z, r);
  ex.map(x, z, r);
  for (int c = 0; c < g.ncell(); ++c) EXPECT_NEAR(lk.cell_solid_area()[c], ex.cell_solid_area()[c], 1e-15);
}

TEST(PorosityMapper, LookupErrorShrinksAsMGrows) {
  const Grid2D g = paper_grid();
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> ux(0.0, 1.0), uz(0.0, 0.25), ur(0.0216, 0.0264);
  std::vector<double> x(100), z(100), r(100);
  for (int j = 0; j < 100; ++j) {
    x[j] = ux(rng);
    z[j] = uz(rng);
    r[j] = ur(rng);
  }
  PorosityMapper ex(g, params(PorosityMethod::kExact, 0.0216, 0.0264, 8, 100));
  ex.map(x, z, r);
  double last = 1.0;
  for (int m : {2, 4, 8, 16}) {
    PorosityMapper lk(g, params(PorosityMethod::kLookup, 0.0216, 0.0264, m, 100));
    lk.map(x, z, r);
    double err = 0.0;
    for (int c = 0; c < g.ncell(); ++c) err = std::max(err, std::fabs(lk.cell_porosity()[c] - ex.cell_porosity()[c]));
    EXPECT_LT(err, last) << "m = " << m;
    last = err;
  }
  EXPECT_LT(last, 0.05);
}

TEST(PorosityMapper, RefusesBadInput) {
  const Grid2D g = paper_grid();
  EXPECT_THROW(PorosityMapper(g, params(PorosityMethod::kExact, 0.03, 0.02)), std::invalid_argument);
  EXPECT_THROW(PorosityMapper(g, params(PorosityMethod::kLookup, 0.02, 0.03, 0)), std::invalid_argument);
  PorosityMapper mp(g, params(PorosityMethod::kExact, 0.02, 0.03, 8, 2));
  EXPECT_THROW(mp.map({0.1}, {0.1}, {0.04}), std::invalid_argument);
  EXPECT_THROW(mp.map({0.1, 0.2, 0.3}, {0.1, 0.1, 0.1}, {0.025, 0.025, 0.025}), std::invalid_argument);
  EXPECT_THROW(mp.map({std::nan("")}, {0.1}, {0.025}), std::invalid_argument);
}
