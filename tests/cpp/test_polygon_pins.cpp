// Polygon stones pinned: the hash of a settling heap of random polygons. Speed-ups of the contact search
// (the separating-axis cache) must leave every bit of the result unchanged.
#include <gtest/gtest.h>

#include <cstdint>
#include <random>

#include "vofdem/dem_system.h"

using namespace vofdem;

namespace {
std::uint64_t hash_state(const std::map<std::string, std::vector<double>>& state) {
  std::uint64_t h = 1469598103934665603ull;
  for (const auto& [key, v] : state) {
    for (char c : key) h = (h ^ static_cast<unsigned char>(c)) * 1099511628211ull;
    const auto* b = reinterpret_cast<const unsigned char*>(v.data());
    for (std::size_t k = 0; k < v.size() * sizeof(double); ++k) h = (h ^ b[k]) * 1099511628211ull;
  }
  return h;
}
}  // namespace

TEST(PolygonPins, SettlingHeapOfPolygons) {
  std::mt19937_64 g(21);
  DEMParams p;
  p.add_flume(0.0, 0.5, 0.0, 0.3);
  p.restitution = 0.3;
  p.dt = 4e-5;
  p.contact_steps = 50;
  std::vector<double> pos, radius, d;
  for (int k = 0; k < 42; ++k) {
    pos.push_back(0.045 + 0.08 * (k % 6) + 0.004 * rng_uniform01(g));
    pos.push_back(0.045 + 0.08 * (k / 6));
    radius.push_back(0.03);
    d.push_back(0.048 * (0.9 + 0.2 * rng_uniform01(g)));
  }
  DEMSystem s(p, pos, radius, {2650.0});
  for (int i = 0; i < s.n(); ++i) s.disc_angle[i] = 6.3 * rng_uniform01(g);
  std::vector<double> v;
  std::vector<int> off;
  random_polygon_set(3, PolygonSpec{}, d, v, off);
  s.set_polygons(v, off);
  s.advance(0.5);
  EXPECT_GT(s.contact_count(), 20);
  // the same bits with the separating-axis cache switched off (checked when the cache was added)
  EXPECT_EQ(hash_state(s.export_state()), 15784444030016356887ull);
}
