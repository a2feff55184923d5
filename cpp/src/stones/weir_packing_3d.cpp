// Packing generator of a trapezoidal rubble mound weir of 3D stones: see weir_packing_3d.h.
#include "vofdem/stones/weir_packing_3d.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <memory>
#include <random>
#include <stdexcept>
#include <string>
#include <vector>

#include "stones/packing_random.h"
#include "stones/packing_steps.h"
#include "vofdem/common/check.h"
#include "vofdem/common/numbers.h"
#include "vofdem/common/grid.h"
#include "vofdem/coupling/porosity_map.h"
#include "vofdem/stones/stone_model.h"
#include "vofdem/stones/stone_packing.h"

namespace vofdem {

namespace {
using packing_random::uniform01;

// largest speed of a free stone [m/s], spin included (|omega| r)
double max_speed_3d(const DEMSystem& sys) {
  double v2 = 0.0;
  for (int i = 0; i < sys.n(); ++i) {
    if (!sys.stone_active[i] || sys.stone_fixed[i]) continue;
    const double vx = sys.stone_vel[2 * i], vz = sys.stone_vel[2 * i + 1], vy = sys.stone_vel_y[i];
    const double* w = &sys.stone_omega_3d[3 * i];
    const double r2 = sys.stone_radius[i] * sys.stone_radius[i];
    v2 = std::max(v2, std::max(vx * vx + vy * vy + vz * vz, (w[0] * w[0] + w[1] * w[1] + w[2] * w[2]) * r2));
  }
  return std::sqrt(v2);
}

double settle(DEMSystem& sys, const WeirSpec& s, double hold) {
  return packing_steps::settle(sys, s, hold, max_speed_3d);
}

// the fixed bottom layer: rows of touching stones along the base, spaced evenly across the width by at
// least the largest bounding diameter d_max
void bottom_layer(const WeirSpec& spec, double width, double d_max, std::mt19937_64& rng, StonePacking& packing,
                  PackedStones& pile) {
  const int rows = std::max(1, static_cast<int>(std::floor(width / d_max)));
  const double x_end = spec.x_end();
  for (int j = 0; j < rows; ++j) {
    const double y = (j + 0.5) * width / rows;
    PackedStone s = packing.draw(packing_random::diameter(rng, spec));
    double x = spec.x_toe + s.radius;
    while (x + s.radius <= x_end + 1e-12) {
      pile.add(x, y, spec.z_bed + s.radius, s, 1);
      const PackedStone next = packing.draw(packing_random::diameter(rng, spec));
      x += s.radius + next.radius;
      s = next;
    }
  }
}

// the pour's fill above the crest, relative to the height [-]: the loose lattice (solid fraction ~0.5)
// compacts by about a fifth as it settles
constexpr double kOverfill = 0.3;

// adds stones at the free sites of a loose face-centred lattice filling the trapezoid's prism extended
// upwards (the slopes continued to (1 + kOverfill) H; centres within `off` [m] outside the slopes);
// returns how many
int pour_round(const WeirSpec& spec, double width, double off, double d_max, std::mt19937_64& rng,
               StonePacking& packing, PackedStones& pile) {
  const double au = spec.slope_up_deg * kPi / 180.0, ad = spec.slope_down_deg * kPi / 180.0;
  const double pitch = 1.04 * (spec.d_mean * (1.0 + spec.d_spread) * packing.lattice_factor());
  const double layer = pitch / std::sqrt(2.0);  // nearest sites of adjacent layers one pitch apart
  const double z_fill = spec.z_bed + (1.0 + kOverfill) * spec.height;
  int added = 0, k = 0;
  for (double z = spec.z_bed + 1.6 * d_max; z <= z_fill; z += layer, ++k) {
    const double hz = z - spec.z_bed, shift = (k % 2) * 0.5 * pitch;
    const double xa = spec.x_toe + hz / std::tan(au) + (0.5 * pitch - off) / std::sin(au);
    const double xb = spec.x_end() - hz / std::tan(ad) - (0.5 * pitch - off) / std::sin(ad);
    for (double xc = xa + shift; xc <= xb; xc += pitch) {
      for (double yc = 0.5 * pitch + shift; yc <= width - 0.5 * pitch; yc += pitch) {
        const double dc = packing_random::diameter(rng, spec);
        const double xj = xc + 0.02 * (2.0 * uniform01(rng) - 1.0) * spec.d_mean;
        const double yj = yc + 0.02 * (2.0 * uniform01(rng) - 1.0) * spec.d_mean;
        const PackedStone stone = packing.draw(dc);
        if (!packing.fits_3d(pile, xj, yj, z, stone, 0.02 * spec.d_mean)) continue;
        pile.add(xj, yj, z, stone, 0);
        ++added;
      }
    }
  }
  return added;
}

// whether (x, z) lies inside the trapezoid
bool inside(const WeirSpec& spec, double x, double z) {
  return x > spec.x_toe && x < spec.x_end() && z > spec.z_bed && z - spec.z_bed < spec.top(x);
}

double segment_distance(double x, double z, double ax, double az, double bx, double bz) {
  const double ex = bx - ax, ez = bz - az;
  const double t = std::clamp(((x - ax) * ex + (z - az) * ez) / (ex * ex + ez * ez), 0.0, 1.0);
  return std::hypot(x - ax - t * ex, z - az - t * ez);
}

// distance [m] from (x, z) outside the trapezoid to it (0 inside)
double outside_distance(const WeirSpec& s, double x, double z) {
  if (inside(s, x, z)) return 0.0;
  const double x1 = s.x_toe + s.height / std::tan(s.slope_up_deg * kPi / 180.0), x2 = x1 + s.crest;
  const double zt = s.z_bed + s.height;
  const double px[4] = {s.x_toe, x1, x2, s.x_end()}, pz[4] = {s.z_bed, zt, zt, s.z_bed};
  double d = INFINITY;
  for (int k = 0; k < 4; ++k) d = std::min(d, segment_distance(x, z, px[k], pz[k], px[(k + 1) % 4], pz[(k + 1) % 4]));
  return d;
}

// the model's packing of the spec's stones; std::invalid_argument naming `shape` without one
std::unique_ptr<StonePacking> model_packing(const WeirSpec& spec) {
  std::unique_ptr<StonePacking> packing = make_stone_model(spec.shape)->packing(spec);
  if (!packing)
    throw std::invalid_argument("shape = '" + spec.shape + "': the packing generator cannot pack this stone model");
  return packing;
}
}  // namespace

// the bounding spheres keep more than margin apart
bool StonePacking::fits_3d(const PackedStones& pile, double x, double y, double z, const PackedStone& s,
                           double margin) const {
  for (std::size_t i = 0; i < pile.size(); ++i) {
    const double dx = x - pile.pos[2 * i], dz = z - pile.pos[2 * i + 1], dy = y - pile.y[i];
    const double reach = pile.radius[i] + s.radius + margin;
    if (dx * dx + dy * dy + dz * dz <= reach * reach) return false;
  }
  return true;
}

double StonePacking::porosity_3d(const DEMSystem& sys, const WeirSpec& spec) const {
  return weir_porosity_3d(sys, spec);
}

DEMSystem pack_weir_3d(const WeirSpec& spec, const DEMParams& params, WeirPackingReport& report) {
  check_weir_spec(spec);
  const auto wall_start = std::chrono::steady_clock::now();
  std::unique_ptr<StonePacking> packing = model_packing(spec);
  const double width = params.width;
  const double d_max = spec.d_mean * (1.0 + spec.d_spread) * packing->bounding_factor();
  if (!(width >= 1.5 * 1.04 * d_max))
    require_in_closed("width", width, 1.5 * 1.04 * d_max, INFINITY);  // two lattice columns across
  std::mt19937_64 rng(spec.seed);
  PackedStones pile;
  const auto make = [&packing, &spec](const DEMParams& p, const PackedStones& stones) {
    return packing->make(p, stones, spec.density);
  };

  // (1) the fixed bottom layer
  bottom_layer(spec, width, d_max, rng, *packing, pile);
  const int n_fixed = static_cast<int>(pile.size());

  // (2) free stones poured in rounds inside temporary slope walls half a mean diameter outside the slopes
  std::vector<DEMWall> final_walls;
  const DEMParams p = packing_steps::pour_params(params, spec, final_walls);
  const double off = 0.5 * spec.d_mean;  // the slope walls' offset outside the slopes
  double t_total = 0.0;
  // a light compaction where the model asks for one: the rounds settle at a lower friction, then the weir's
  DEMParams pour = p;
  const double compaction = spec.compaction_friction >= 0.0 ? spec.compaction_friction : packing->pour_friction();
  const bool compacted = compaction >= 0.0;
  if (compacted) pour.friction_stone = compaction;
  DEMSystem box = make(pour, pile);
  for (int round = 0; round < packing->pour_rounds(); ++round) {
    const int added = pour_round(spec, width, off, d_max, rng, *packing, pile);
    if (added == 0 && round > 0) break;
    box = make(pour, pile);
    t_total += settle(box, spec, 0.2);
    pile.take(box);
  }
  if (compacted) {
    box = make(p, pile);
    t_total += settle(box, spec, 0.2);
    pile.take(box);
  }

  // (3) keep the stones whose centres lie below the crest (the plane's criterion)
  pile = packing_steps::below_crest(box, pile, spec);

  // (4) slope walls removed: the mound settles on its own; stones that rolled off a toe are not the weir's
  DEMParams q = params;
  q.walls = final_walls;
  DEMSystem weir = make(q, pile);
  t_total += settle(weir, spec, 0.5);
  if (packing->drop_toe_rollers()) {
    pile.take(weir);
    PackedStones on;
    for (int i = 0; i < weir.n(); ++i)
      if (weir.stone_fixed[i] ||
          outside_distance(spec, weir.stone_pos[2 * i], weir.stone_pos[2 * i + 1]) < 0.5 * spec.d_mean)
        on.copy_stone(weir, pile, i);
    if (on.size() < static_cast<std::size_t>(weir.n())) {
      pile = on;
      weir = make(q, pile);
      t_total += settle(weir, spec, 0.3);
    }
  }

  report.n_stones = weir.n();
  report.n_fixed = n_fixed;
  report.max_speed = max_speed_3d(weir);
  report.settle_time = t_total;
  report.porosity = packing->porosity_3d(weir, spec);
  report.stones_across = weir_stones_across(weir, spec);
  report.outline_error = weir_outline_error(weir, spec);
  report.wall_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - wall_start).count();
  return weir;
}

double weir_porosity_3d(const DEMSystem& sys, const WeirSpec& spec, double h) {
  require_positive("h", h);
  const int n = sys.n();
  double r_min = INFINITY, r_max = 0.0;
  for (int i = 0; i < n; ++i) r_min = std::min(r_min, sys.stone_radius[i]), r_max = std::max(r_max, sys.stone_radius[i]);
  if (n == 0) return 1.0;
  // a grid over the trapezoid with a margin of the largest stone (no stone reaches past its edges)
  const double margin = 2.0 * r_max;
  const double x0 = spec.x_toe - margin, lx = spec.x_end() - spec.x_toe + 2.0 * margin;
  const double lz = spec.height + margin;
  const int nx = static_cast<int>(std::ceil(lx / h)), nz = static_cast<int>(std::ceil(lz / h));
  const Grid2D grid = Grid2D::uniform(nx, nz, nx * h, nz * h, x0, spec.z_bed);
  PorosityParams pp;
  pp.n_exp = 0.0;
  pp.r_min = r_min;
  pp.r_max = r_max;
  pp.max_discs = n;
  PorosityMapper mapper(grid, pp);
  std::vector<double> x(n), z(n);
  for (int i = 0; i < n; ++i) x[i] = sys.stone_pos[2 * i], z[i] = sys.stone_pos[2 * i + 1];
  sys.model().map_footprint(sys, mapper, x.data(), z.data());
  // solid area per unit width in the cells whose centre is inside (each cell's slab holds V / B's share)
  double solid = 0.0;
  for (int k = 0; k < nz; ++k)
    for (int i = 0; i < nx; ++i)
      if (inside(spec, x0 + (i + 0.5) * h, spec.z_bed + (k + 0.5) * h)) solid += mapper.cell_solid_area()[grid.cell(i, k)];
  return 1.0 - solid / spec.area();
}

double weir_porosity_3d_spheres(const std::vector<double>& sphere, double width, const WeirSpec& spec, double h) {
  require_positive("h", h);
  require_positive("width", width);
  const std::size_t ns = sphere.size() / 4;
  const double x0 = spec.x_toe, lx = spec.x_end() - spec.x_toe;
  const int nx = static_cast<int>(std::ceil(lx / h)), ny = static_cast<int>(std::ceil(width / h));
  const int nz = static_cast<int>(std::ceil(spec.height / h));
  // a point grid over the prism (cell centres), each point marked once however many spheres hold it
  std::vector<std::uint8_t> solid(static_cast<std::size_t>(nx) * ny * nz, 0);
  const auto index = [h](double lo, double v) { return static_cast<int>(std::floor((v - lo) / h - 0.5)); };
  for (std::size_t g = 0; g < ns; ++g) {
    const double cx = sphere[4 * g], cy = sphere[4 * g + 1], cz = sphere[4 * g + 2], r = sphere[4 * g + 3];
    const int i0 = std::max(0, index(x0, cx - r)), i1 = std::min(nx - 1, index(x0, cx + r) + 1);
    const int j0 = std::max(0, index(0.0, cy - r)), j1 = std::min(ny - 1, index(0.0, cy + r) + 1);
    const int k0 = std::max(0, index(spec.z_bed, cz - r)), k1 = std::min(nz - 1, index(spec.z_bed, cz + r) + 1);
    for (int k = k0; k <= k1; ++k)
      for (int j = j0; j <= j1; ++j)
        for (int i = i0; i <= i1; ++i) {
          const double dx = x0 + (i + 0.5) * h - cx, dy = (j + 0.5) * h - cy, dz = spec.z_bed + (k + 0.5) * h - cz;
          if (dx * dx + dy * dy + dz * dz <= r * r) solid[(static_cast<std::size_t>(k) * ny + j) * nx + i] = 1;
        }
  }
  long long in = 0, full = 0;
  for (int k = 0; k < nz; ++k)
    for (int i = 0; i < nx; ++i) {
      if (!inside(spec, x0 + (i + 0.5) * h, spec.z_bed + (k + 0.5) * h)) continue;
      for (int j = 0; j < ny; ++j) {
        ++in;
        full += solid[(static_cast<std::size_t>(k) * ny + j) * nx + i];
      }
    }
  return in > 0 ? 1.0 - static_cast<double>(full) / in : 1.0;
}

double weir_stones_across(const DEMSystem& sys, const WeirSpec& spec, double h) {
  require_positive("h", h);
  const StoneModel& model = sys.model();
  long long points = 0, crossings = 0;
  for (double z = spec.z_bed + 0.5 * h; z < spec.z_bed + spec.height; z += h) {
    for (double x = spec.x_toe + 0.5 * h; x < spec.x_end(); x += h) {
      if (!inside(spec, x, z)) continue;
      ++points;
      for (int i = 0; i < sys.n(); ++i) {
        if (!sys.stone_active[i]) continue;
        const double dx = x - sys.stone_pos[2 * i], dz = z - sys.stone_pos[2 * i + 1], r = sys.stone_radius[i];
        if (dx * dx + dz * dz <= r * r && model.covers(sys, i, x, z)) ++crossings;
      }
    }
  }
  return points > 0 ? static_cast<double>(crossings) / points : 0.0;
}

}  // namespace vofdem
