// The volume of a sphere in a flow cell's slab (slab_volume.h): the corner primitive by hand values
// (quarter and half spheres, a cap, a small cell at the centre), a sphere's parts over uniform and
// non-uniform grids summing to its volume (crossing cell corners, touching and cut by the domain edge),
// single cells against a slow column-by-column integration, symmetry; a clump's parts summing to its
// union volume, and the local error of the scaled sub-sphere approximation against a brute-force union.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <random>
#include <stdexcept>
#include <string>
#include <vector>

#include "vofdem/coupling/slab_volume.h"
#include "vofdem/stones/clump.h"

using namespace vofdem;
using Vec3 = Eigen::Vector3d;

namespace {

double sphere_volume(double r) { return 4.0 / 3.0 * M_PI * r * r * r; }

double sum_parts(const std::vector<CellVolume>& cells) {
  double s = 0.0;
  for (const CellVolume& c : cells) s += c.volume;
  return s;
}

std::vector<double> uniform_edges(double a, double b, int n) {
  std::vector<double> e;
  for (int k = 0; k <= n; ++k) e.push_back(a + (b - a) * k / n);
  return e;
}

std::vector<double> random_edges(double a, double b, int n, std::mt19937_64& g) {
  std::uniform_real_distribution<double> u(0.2, 1.0);
  std::vector<double> w(static_cast<std::size_t>(n));
  double total = 0.0;
  for (double& x : w) total += (x = u(g));
  std::vector<double> e{a};
  for (double x : w) e.push_back(e.back() + (b - a) * x / total);
  e.back() = b;
  return e;
}

// slow reference: the midpoint rule over x (n columns) of each column's exact area of the disk slice
// of radius rho = sqrt(R^2 - (x - x_c)^2) between z0 and z1, int 2 sqrt(rho^2 - z^2) dz = z s + rho^2 asin(z/rho)
double slab_volume_by_columns(double xc, double zc, double r, double x0, double x1, double z0, double z1, int n) {
  const double a = std::max(x0, xc - r), b = std::min(x1, xc + r);
  if (b <= a) return 0.0;
  const double h = (b - a) / n;
  double v = 0.0;
  for (int k = 0; k < n; ++k) {
    const double x = a + (k + 0.5) * h - xc, rho2 = r * r - x * x;
    if (rho2 <= 0.0) continue;
    const double rho = std::sqrt(rho2);
    const double lo = std::max(z0 - zc, -rho), hi = std::min(z1 - zc, rho);
    if (hi <= lo) continue;
    auto prim = [&](double z) { return z * std::sqrt(std::max(rho2 - z * z, 0.0)) + rho2 * std::asin(z / rho); };
    v += (prim(hi) - prim(lo)) * h;
  }
  return v;
}

}  // namespace

// hand values: P(R, R) is a quarter of the sphere; P(u, R) = pi u (3R^2 - u^2) / 6 (a column of half
// disks); the cap x > x_c + a has pi (R - a)^2 (2R + a) / 3; a small cell 2h x 2h at the centre holds
// 2R (2h)^2 to O(h^2 / R^2)
TEST(SlabVolume, CornerPrimitiveHandValues) {
  const double r = 0.024, v = sphere_volume(r);
  EXPECT_NEAR(sphere_corner_volume(r, r, r), v / 4.0, 1e-15 * v);
  EXPECT_NEAR(sphere_corner_volume(5.0 * r, -3.0 * r, r), -v / 4.0, 1e-15 * v);
  EXPECT_EQ(sphere_corner_volume(0.0, 0.01, r), 0.0);
  for (const double u : {0.003, 0.012, 0.02}) {
    EXPECT_NEAR(sphere_corner_volume(u, r, r), M_PI * u * (3.0 * r * r - u * u) / 6.0, 1e-15 * v) << u;
    const double a = u;
    EXPECT_NEAR(sphere_slab_volume(0.1, 0.2, r, 0.1 + a, 1.0, -1.0, 1.0), M_PI * (r - a) * (r - a) * (2.0 * r + a) / 3.0,
                1e-14 * v)
        << a;
  }
  EXPECT_NEAR(sphere_slab_volume(0.1, 0.2, r, 0.1, 0.5, -1.0, 1.0), v / 2.0, 1e-15 * v);
  const double h = 1e-4 * r;
  EXPECT_NEAR(sphere_slab_volume(0.0, 0.0, r, -h, h, -h, h), 2.0 * r * 4.0 * h * h, 1e-8 * 2.0 * r * 4.0 * h * h);
  // F(a, b) of the brief: the sphere with x < a and z < b; F(R, R) the whole, F(0, R) half
  auto f = [&](double a, double b) {
    return sphere_corner_volume(a, b, r) + sphere_corner_volume(a, r, r) + sphere_corner_volume(r, b, r) +
           sphere_corner_volume(r, r, r);
  };
  EXPECT_NEAR(f(r, r), v, 1e-15 * v);
  EXPECT_NEAR(f(0.0, r), v / 2.0, 1e-15 * v);
  EXPECT_NEAR(f(0.0, 0.0), v / 4.0, 1e-15 * v);
}

// a sphere's parts over a grid sum to its volume to 1e-12: uniform and non-uniform grids, random
// centres, a centre on a grid node (the sphere crossing cell corners), a sphere touching the domain edge
TEST(SlabVolume, PartsSumToSphereVolume) {
  std::mt19937_64 g(11);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  const double r = 0.024, v = sphere_volume(r);
  for (int trial = 0; trial < 40; ++trial) {
    const bool uniform = trial % 2 == 0;
    const auto xe = uniform ? uniform_edges(0.0, 0.3, 12) : random_edges(0.0, 0.3, 17, g);
    const auto ze = uniform ? uniform_edges(0.0, 0.2, 20) : random_edges(0.0, 0.2, 23, g);
    double xc = r + (0.3 - 2 * r) * u(g), zc = r + (0.2 - 2 * r) * u(g);
    if (trial == 2) xc = xe[5], zc = ze[7];      // centre on a node
    if (trial == 4) xc = r, zc = 0.2 - r;        // touching two domain edges
    if (trial == 6) xc = xe[3], zc = r;          // on a grid line and touching the bed
    std::vector<CellVolume> cells;
    sphere_cell_volumes(xc, zc, r, xe, ze, cells);
    EXPECT_NEAR(sum_parts(cells), v, 1e-12 * v) << trial;
    // cell by cell through sphere_slab_volume: the same parts
    double s = 0.0;
    for (const CellVolume& c : cells) {
      const double one = sphere_slab_volume(xc, zc, r, xe[c.i], xe[c.i + 1], ze[c.k], ze[c.k + 1]);
      EXPECT_NEAR(one, c.volume, 1e-14 * v);
      EXPECT_GE(c.volume, 0.0);
      s += one;
    }
    EXPECT_NEAR(s, v, 1e-12 * v) << trial;
  }
  // cut by the domain edge at distance a from the centre: the cap beyond it is left out
  const double a = 0.01;
  std::vector<CellVolume> cells;
  sphere_cell_volumes(a, 0.1, r, uniform_edges(0.0, 0.3, 12), uniform_edges(0.0, 0.2, 20), cells);
  EXPECT_NEAR(sum_parts(cells), v - M_PI * (r - a) * (r - a) * (2.0 * r + a) / 3.0, 1e-12 * v);
}

// single cells against the slow column integration (20000 columns, error ~1e-9 of the sphere's volume),
// the cells placed across the sphere's edge, centre and corners
TEST(SlabVolume, SingleCellsAgainstSlowReference) {
  std::mt19937_64 g(3);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  const double r = 0.024, v = sphere_volume(r), xc = 0.13, zc = 0.07;
  double worst = 0.0;
  for (int trial = 0; trial < 40; ++trial) {
    const double x0 = xc + 1.2 * r * u(g), z0 = zc + 1.2 * r * u(g);
    const double x1 = x0 + 0.025 * (0.1 + std::fabs(u(g))), z1 = z0 + 0.01 * (0.1 + std::fabs(u(g)));
    const double exact = sphere_slab_volume(xc, zc, r, x0, x1, z0, z1);
    const double slow = slab_volume_by_columns(xc, zc, r, x0, x1, z0, z1, 20000);
    EXPECT_NEAR(exact, slow, 1e-8 * v) << trial;
    worst = std::max(worst, std::fabs(exact - slow) / v);
  }
  std::printf("slab volume against 20000-column integration: worst difference %.1e of the sphere volume\n", worst);
}

// mirror images of the cell about the centre's lines, and x and z exchanged, hold the same volume
TEST(SlabVolume, Symmetry) {
  const double r = 0.02, xc = 0.1, zc = 0.05, x0 = 0.093, x1 = 0.118, z0 = 0.041, z1 = 0.052;
  const double v = sphere_slab_volume(xc, zc, r, x0, x1, z0, z1);
  EXPECT_NEAR(sphere_slab_volume(xc, zc, r, 2 * xc - x1, 2 * xc - x0, z0, z1), v, 1e-15 * sphere_volume(r));
  EXPECT_NEAR(sphere_slab_volume(xc, zc, r, x0, x1, 2 * zc - z1, 2 * zc - z0), v, 1e-15 * sphere_volume(r));
  EXPECT_NEAR(sphere_slab_volume(zc, xc, r, z0, z1, x0, x1), v, 1e-15 * sphere_volume(r));
}

// a clump's parts sum to its union volume (the scaled sub-spheres), at random positions and
// orientations, over uniform and non-uniform grids; one cell at a time agrees
TEST(SlabVolume, ClumpPartsSumToUnionVolume) {
  std::mt19937_64 g(5);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  for (const std::string& name : quarried_stone_names()) {
    const Clump c = quarried_stone(name, 0.048);
    for (int trial = 0; trial < 6; ++trial) {
      const Eigen::Quaterniond q(Eigen::AngleAxisd(3.0 * u(g), Vec3(u(g), u(g), u(g)).normalized()));
      const Vec3 pos(0.15 + 0.1 * u(g), 0.1 + 0.2 * u(g), 0.1 + 0.05 * u(g));
      const auto xe = trial % 2 ? random_edges(0.0, 0.3, 13, g) : uniform_edges(0.0, 0.3, 12);
      const auto ze = trial % 2 ? random_edges(0.0, 0.2, 19, g) : uniform_edges(0.0, 0.2, 20);
      std::vector<CellVolume> cells;
      clump_cell_volumes(c, pos, q, xe, ze, cells);
      EXPECT_NEAR(sum_parts(cells), c.volume(), 1e-12 * c.volume()) << name;
      double s = 0.0;
      for (const CellVolume& cell : cells) {
        const double one = clump_slab_volume(c, pos, q, xe[cell.i], xe[cell.i + 1], ze[cell.k], ze[cell.k + 1]);
        EXPECT_NEAR(one, cell.volume, 1e-13 * c.volume()) << name;
        s += one;
      }
      EXPECT_NEAR(s, c.volume(), 1e-12 * c.volume()) << name;
    }
  }
}

// the scaled sub-spheres against the clump's true union per cell, by brute force (the union's chord
// across y at each of 600 x 600 points, the overlaps counted once) on the paper's mesh (2.5 x 1.0 cm):
// the approximation moves volume between neighbouring cells; the largest cell error, over the clump's
// volume, is measured and held below 5 % (the brute force itself sums to the union volume within 1e-3)
TEST(SlabVolume, ScaledPartsAgainstUnionByBruteForce) {
  const auto xe = uniform_edges(0.0, 0.2, 8), ze = uniform_edges(0.0, 0.1, 10);
  for (const std::string& name : {std::string("tetra_4"), std::string("box_8")}) {
    const Clump c = quarried_stone(name, 0.048);
    const Eigen::Quaterniond q(Eigen::AngleAxisd(0.6, Vec3(0.3, 1.0, 0.2).normalized()));
    const Vec3 pos(0.101, 0.0, 0.047);
    std::vector<double> truth(static_cast<std::size_t>(8 * 10), 0.0);
    const int n = 600;
    const double x_lo = pos.x() - 0.04, z_lo = pos.z() - 0.04, h = 0.08 / n;
    for (int a = 0; a < n; ++a) {
      for (int b = 0; b < n; ++b) {
        const double x = x_lo + (a + 0.5) * h, z = z_lo + (b + 0.5) * h;
        std::vector<std::pair<double, double>> chords;
        for (const ClumpSphere& s : c.spheres()) {
          const Vec3 w = pos + q * s.centre;
          const double d2 = s.radius * s.radius - (x - w.x()) * (x - w.x()) - (z - w.z()) * (z - w.z());
          if (d2 > 0.0) chords.push_back({w.y() - std::sqrt(d2), w.y() + std::sqrt(d2)});
        }
        std::sort(chords.begin(), chords.end());
        double length = 0.0, end = -INFINITY;
        for (const auto& [lo, hi] : chords) {
          if (hi <= end) continue;
          length += hi - std::max(lo, end);
          end = hi;
        }
        const int i = static_cast<int>(x / 0.025), k = static_cast<int>(z / 0.01);
        if (length > 0.0) truth[static_cast<std::size_t>(i * 10 + k)] += length * h * h;
      }
    }
    double total = 0.0;
    for (double t : truth) total += t;
    EXPECT_NEAR(total / c.volume(), 1.0, 1e-3) << name;
    std::vector<CellVolume> cells;
    clump_cell_volumes(c, pos, q, xe, ze, cells);
    std::vector<double> approx(truth.size(), 0.0);
    for (const CellVolume& cell : cells) approx[static_cast<std::size_t>(cell.i * 10 + cell.k)] = cell.volume;
    double worst = 0.0;
    for (std::size_t k = 0; k < truth.size(); ++k) worst = std::max(worst, std::fabs(approx[k] - truth[k]));
    EXPECT_LT(worst / c.volume(), 0.05) << name;
    std::printf("%s on a 2.5 x 1.0 cm mesh: largest cell error of the scaled sub-spheres %.2f %% of the clump volume\n",
                name.c_str(), 100.0 * worst / c.volume());
  }
}

TEST(SlabVolume, BadInputNamesParameter) {
  auto message = [](auto f) -> std::string {
    try {
      f();
    } catch (const std::invalid_argument& e) {
      return e.what();
    }
    return "";
  };
  std::vector<CellVolume> out;
  EXPECT_NE(message([] { sphere_slab_volume(0.0, 0.0, 0.0, 0.0, 1.0, 0.0, 1.0); }).find("r:"), std::string::npos);
  EXPECT_NE(message([] { sphere_slab_volume(0.0, 0.0, 1.0, 1.0, 0.0, 0.0, 1.0); }).find("x0, x1"), std::string::npos);
  EXPECT_NE(message([&] { sphere_cell_volumes(0.0, 0.0, 1.0, {0.0, 1.0, 0.5}, {0.0, 1.0}, out); }).find("x_edges"),
            std::string::npos);
  EXPECT_NE(message([&] { sphere_cell_volumes(0.0, 0.0, 1.0, {0.0, 1.0}, {0.0}, out); }).find("z_edges"),
            std::string::npos);
}
