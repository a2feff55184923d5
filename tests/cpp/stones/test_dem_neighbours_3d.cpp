// The 3D neighbour list of 3D stones (dem_neighbours.cpp): cells in x, y and z list exactly the pairs a
// brute-force O(n^2) search finds within reach (their gap below the skin), in (i, j) order; builds are
// deterministic; and a settling run with it gives the same bits as with the plane's list, which holds
// every pair whose x-z projections are within reach whatever their y.
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <random>
#include <vector>

#include "vofdem/stones/dem_system.h"

using namespace vofdem;

namespace {
constexpr double kR = 0.024;
constexpr double kSkin = 0.005;

// the pairs i < j (not both fixed, both active) whose centres are closer than r_i + r_j + skin, in 3D or,
// with plane, by their x-z projections
std::vector<std::array<int, 2>> brute_force(const DEMSystem& s, bool plane) {
  std::vector<std::array<int, 2>> out;
  for (int i = 0; i < s.n(); ++i) {
    if (!s.stone_active[i]) continue;
    for (int j = i + 1; j < s.n(); ++j) {
      if (!s.stone_active[j] || (s.stone_fixed[i] && s.stone_fixed[j])) continue;
      const double dx = s.stone_pos[2 * j] - s.stone_pos[2 * i], dz = s.stone_pos[2 * j + 1] - s.stone_pos[2 * i + 1];
      const double dy = plane ? 0.0 : s.stone_y[j] - s.stone_y[i];
      const double cut = s.stone_radius[i] + s.stone_radius[j] + kSkin;
      if (dx * dx + dy * dy + dz * dz < cut * cut) out.push_back({i, j});
    }
  }
  return out;
}

// n spheres of radii kR U(0.9, 1.1) placed at random in a box 0.6 m long, `width` wide, 0.4 m high (they
// may overlap: only the list is looked at), a tenth of them fixed and one inactive
DEMSystem random_spheres(int n, double width, bool plane_list, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  std::vector<double> xz, radius;
  for (int i = 0; i < n; ++i) {
    xz.push_back(0.6 * u(rng));
    xz.push_back(0.4 * u(rng));
    radius.push_back(kR * (0.9 + 0.2 * u(rng)));
  }
  DEMParams p;
  p.width = width;
  p.neighbour_skin = kSkin;
  p.plane_neighbour_list = plane_list;
  DEMSystem s(p, xz, radius, {2650.0});
  s.set_model("sphere");
  for (int i = 0; i < n; ++i) s.stone_y[i] = 1.1 * kR + (width - 2.2 * kR) * u(rng);
  for (int i = 0; i < n; i += 10) s.stone_fixed[i] = 1;
  s.stone_active[n / 2] = 0;
  return s;
}

// spheres on a cubic lattice of pitch 0.055 m (6 along x, `across` in y, 5 high), jittered by +-1 mm, dropping
// into a box with a bed and end walls
DEMSystem settling(int across, bool plane_list) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  const double pitch = 0.055, width = across * pitch;
  std::vector<double> xz, radius, y;
  for (int k = 0; k < 5; ++k)
    for (int j = 0; j < across; ++j)
      for (int i = 0; i < 6; ++i) {
        xz.push_back(pitch * (i + 0.5) + 0.001 * u(rng));
        xz.push_back(pitch * (k + 0.5) + 0.001 * u(rng));
        y.push_back(pitch * (j + 0.5) + 0.001 * u(rng));
        radius.push_back(kR * (1.0 + 0.1 * u(rng)));
      }
  DEMParams p;
  p.add_flume(0.0, 6 * pitch, 0.0);
  p.width = width;
  p.stiffness_normal = 2e5;
  p.restitution = 0.5;
  p.neighbour_skin = kSkin;
  p.plane_neighbour_list = plane_list;
  DEMSystem s(p, xz, radius, {2650.0});
  s.set_model("sphere");
  s.stone_y = y;
  return s;
}
}  // namespace

TEST(DEMNeighbours3D, ListEqualsTheBruteForcePairsWithinReach) {
  for (unsigned seed : {1u, 2u, 3u}) {
    DEMSystem s = random_spheres(400, 0.3, false, seed);
    s.overlapping_pairs();  // builds the list
    const auto list = s.neighbour_pairs();
    EXPECT_EQ(list, brute_force(s, false)) << "seed " << seed;
    EXPECT_GT(list.size(), 100u);
    // the plane's list holds every pair within reach in x-z, a superset several times longer
    DEMSystem t = random_spheres(400, 0.3, true, seed);
    t.overlapping_pairs();
    EXPECT_EQ(t.neighbour_pairs(), brute_force(t, true)) << "seed " << seed;
    EXPECT_GT(t.neighbour_pairs().size(), 2 * list.size());
  }
}

TEST(DEMNeighbours3D, ANarrowFlumeOfOneCellAcrossListsThePairsToo) {
  // width below one cell (h = 2 r_max + skin): a single cell across
  DEMSystem s = random_spheres(200, 0.055, false, 4);
  s.overlapping_pairs();
  EXPECT_EQ(s.neighbour_pairs(), brute_force(s, false));
}

TEST(DEMNeighbours3D, BuildsAreDeterministic) {
  DEMSystem a = settling(8, false), b = settling(8, false);
  a.advance(0.2);
  b.advance(0.2);
  EXPECT_EQ(a.neighbour_pairs(), b.neighbour_pairs());
  EXPECT_EQ(a.stone_pos, b.stone_pos);
  EXPECT_EQ(a.stone_y, b.stone_y);
  EXPECT_EQ(a.neighbour_builds(), b.neighbour_builds());
}

TEST(DEMNeighbours3D, ASettlingRunGivesTheSameBitsAsWithThePlanesList) {
  DEMSystem a = settling(8, false), b = settling(8, true);
  for (int k = 0; k < 4; ++k) {
    a.advance(0.1);
    b.advance(0.1);
    // the list holds the same pairs that touch, in the same order: every force sum adds the same terms
    EXPECT_EQ(a.stone_pos, b.stone_pos) << "after " << 0.1 * (k + 1) << " s";
    EXPECT_EQ(a.stone_y, b.stone_y);
    EXPECT_EQ(a.stone_vel, b.stone_vel);
    EXPECT_EQ(a.stone_vel_y, b.stone_vel_y);
    EXPECT_EQ(a.stone_quat, b.stone_quat);
    EXPECT_EQ(a.stone_omega_3d, b.stone_omega_3d);
    EXPECT_EQ(a.contact_count(), b.contact_count());
  }
  EXPECT_GT(a.contact_count(), 100);
  // the 3D list is the shorter (8 spheres across), rebuilt at least as often (it also follows y)
  EXPECT_LT(2 * a.neighbour_pairs().size(), b.neighbour_pairs().size());
  EXPECT_GE(a.neighbour_builds(), b.neighbour_builds());
}
