// Polygon stones in the weir's packing generator (stone_packing.h, weir_packing.h): convex polygons of
// nominal diameter d (the equal-area disc's, polygon.h), their shapes and orientations from a second
// generator seeded from the weir's seed (the diameters follow the same draws as for discs). The bottom
// row lies on its longest edges, touching; the free stones take random orientations; the lattice pitch
// and the free-site tests use the bounding radii and separating axes, so no two polygons overlap.
#include <cmath>
#include <memory>
#include <random>

#include "vofdem/common/numbers.h"
#include "vofdem/stones/dem_system.h"
#include "vofdem/stones/polygon.h"
#include "vofdem/stones/polygon_contact.h"
#include "vofdem/stones/polygon_model.h"
#include "vofdem/stones/stone_packing.h"
#include "vofdem/stones/weir_packing.h"

namespace vofdem {

namespace {
class PolygonPacking final : public StonePacking {
 public:
  explicit PolygonPacking(const WeirSpec& s) : rng_(s.seed ^ 0x9e3779b97f4a7c15ull), spec_(s.polygon) {
    spec_.validate();
  }

  PackedStone draw(double d) override {
    PackedStone out;
    out.shape = random_convex_polygon(rng_, spec_, d);
    out.angle = 2.0 * kPi * rng_uniform01(rng_);
    out.radius = polygon_properties(out.shape.data(), static_cast<int>(out.shape.size() / 2)).bounding_radius;
    return out;
  }

  double bounding_factor() const override {
    return std::sqrt(spec_.aspect_ratio) * (1.0 + 0.5 * spec_.radial_jitter);
  }

  // each lying on its longest edge, touching its neighbour
  void bottom_row(const WeirSpec& spec, const std::function<double()>& next_diameter, PackedStones& pile) override {
    double x_left = spec.x_toe;
    const double x_end = spec.x_end();
    for (;;) {
      PackedStone s = draw(next_diameter());
      const int n = static_cast<int>(s.shape.size() / 2);
      s.angle = polygon_rest_angle(s.shape.data(), n);
      std::vector<double> w(s.shape.size());
      polygon_to_world(s.shape.data(), n, 0.0, 0.0, s.angle, w.data());
      double xmin = INFINITY, xmax = -INFINITY, zmin = INFINITY;
      for (int k = 0; k < n; ++k)
        xmin = std::min(xmin, w[2 * k]), xmax = std::max(xmax, w[2 * k]), zmin = std::min(zmin, w[2 * k + 1]);
      const double xc = x_left - xmin;
      if (xc + xmax > x_end + 1e-12) break;
      pile.add(xc, spec.z_bed - zmin, s, 1);
      x_left = xc + xmax;
    }
  }

  // separating axes against every placed stone whose bounding circle comes near
  bool fits(const PackedStones& pile, double x, double z, const PackedStone& s, double margin) const override {
    const int n = static_cast<int>(s.shape.size() / 2);
    double wc[2 * kPolygonMaxVertices], uc[2 * kPolygonMaxVertices], wi[2 * kPolygonMaxVertices],
        ui[2 * kPolygonMaxVertices];
    polygon_to_world(s.shape.data(), n, x, z, s.angle, wc);
    polygon_edge_normals(wc, n, uc);
    for (std::size_t i = 0; i < pile.size(); ++i) {
      if (std::hypot(x - pile.pos[2 * i], z - pile.pos[2 * i + 1]) > pile.radius[i] + s.radius + margin) continue;
      const int m = static_cast<int>(pile.shape[i].size() / 2);
      polygon_to_world(pile.shape[i].data(), m, pile.pos[2 * i], pile.pos[2 * i + 1], pile.angle[i], wi);
      polygon_edge_normals(wi, m, ui);
      if (polygon_separation(wc, uc, n, wi, ui, m) <= margin) return false;
    }
    return true;
  }

  int turns() const override { return 6; }
  bool drop_toe_rollers() const override { return true; }

  DEMSystem make(const DEMParams& p, const PackedStones& pile, double density) const override {
    DEMSystem sys(p, pile.pos, pile.radius, {density}, pile.fixed);
    std::vector<double> v;
    std::vector<int> off = {0};
    for (const auto& w : pile.shape) {
      v.insert(v.end(), w.begin(), w.end());
      off.push_back(off.back() + static_cast<int>(w.size() / 2));
    }
    sys.stone_angle = pile.angle;
    sys.set_polygons(v, off);
    return sys;
  }

 private:
  std::mt19937_64 rng_;
  PolygonSpec spec_;
};
}  // namespace

std::unique_ptr<StonePacking> PolygonModel::packing(const WeirSpec& spec) const {
  return std::make_unique<PolygonPacking>(spec);
}

}  // namespace vofdem
