// Packing generator of a trapezoidal rubble mound weir: see weir_packing.h.
#include "vofdem/stones/weir_packing.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <random>
#include <cstdio>
#include <cstdlib>
#include <memory>
#include <stdexcept>

#include "vofdem/common/check.h"
#include "vofdem/common/numbers.h"
#include "vofdem/stones/stone_model.h"
#include "vofdem/stones/stone_packing.h"
#include "vofdem/stones/weir_packing_3d.h"
#include "stones/packing_random.h"
#include "stones/packing_steps.h"

namespace vofdem {

namespace {
using packing_random::uniform01;
double draw_diameter(std::mt19937_64& g, const WeirSpec& s) { return packing_random::diameter(g, s); }

}  // namespace

void check_weir_spec(const WeirSpec& s) {
  require_positive("height", s.height);
  require_non_negative("crest", s.crest);
  require_in_open_closed("slope_up_deg", s.slope_up_deg, 0.0, 90.0);
  require_in_open_closed("slope_down_deg", s.slope_down_deg, 0.0, 90.0);
  require_finite("x_toe", s.x_toe);
  require_finite("z_bed", s.z_bed);
  require_positive("d_mean", s.d_mean);
  require_in_closed("d_spread", s.d_spread, 0.0, 0.5);
  require_positive("density", s.density);
  require_positive("settle_time_max", s.settle_time_max);
  require_positive("rest_speed", s.rest_speed);
  // -1 (the model's own) or a friction
  if (s.compaction_friction != -1.0 && !(s.compaction_friction >= 0.0 && s.compaction_friction <= 2.0))
    throw std::invalid_argument("compaction_friction = " + std::to_string(s.compaction_friction) +
                                " must be -1 (the stone model's own) or in [0, 2]");
  if (s.height < 2.0 * s.d_mean) require_in_closed("height", s.height, 2.0 * s.d_mean, INFINITY);
  check_clump_mix(s.clump);
}

namespace {
double max_speed(const DEMSystem& sys) {
  double v2 = 0.0;
  for (int i = 0; i < sys.n(); ++i) {
    if (!sys.stone_active[i] || sys.stone_fixed[i]) continue;
    const double vx = sys.stone_vel[2 * i], vz = sys.stone_vel[2 * i + 1];
    const double wr = sys.stone_omega[i] * sys.stone_radius[i];
    v2 = std::max(v2, std::max(vx * vx + vz * vz, wr * wr));
  }
  return std::sqrt(v2);
}

double settle(DEMSystem& sys, const WeirSpec& s, double hold) { return packing_steps::settle(sys, s, hold, max_speed); }

}  // namespace

void PackedStones::add(double x, double z, const PackedStone& s, std::uint8_t fixed_flag) {
  pos.push_back(x);
  pos.push_back(z);
  radius.push_back(s.radius);
  angle.push_back(s.angle);
  fixed.push_back(fixed_flag);
  shape.push_back(s.shape);
}

void PackedStones::add(double x, double y_across, double z, const PackedStone& s, std::uint8_t fixed_flag) {
  add(x, z, s, fixed_flag);
  y.push_back(y_across);
  quat.insert(quat.end(), s.quat.begin(), s.quat.end());
}

void PackedStones::copy_stone(const DEMSystem& sys, const PackedStones& from, int i) {
  pos.push_back(sys.stone_pos[2 * i]);
  pos.push_back(sys.stone_pos[2 * i + 1]);
  radius.push_back(sys.stone_radius[i]);
  angle.push_back(sys.stone_angle[i]);
  fixed.push_back(sys.stone_fixed[i]);
  shape.push_back(from.shape[static_cast<std::size_t>(i)]);
  // 3D stones keep their place across the flume and their orientation
  if (!from.y.empty()) {
    y.push_back(sys.stone_y[i]);
    quat.insert(quat.end(), sys.stone_quat.begin() + 4 * i, sys.stone_quat.begin() + 4 * i + 4);
  }
}

void PackedStones::take(const DEMSystem& sys) {
  pos = sys.stone_pos;
  angle = sys.stone_angle;
  if (!y.empty()) {
    y = sys.stone_y;
    quat = sys.stone_quat;
  }
}

void StonePacking::bottom_row(const WeirSpec&, const std::function<double()>&, PackedStones&) {
  throw std::logic_error("StonePacking::bottom_row: a 2D step asked of a model that does not lay a row");
}

bool StonePacking::fits(const PackedStones&, double, double, const PackedStone&, double) const {
  throw std::logic_error("StonePacking::fits: a 2D step asked of a model that does not test its fit");
}

namespace {
// adds stones at the free sites of a loose triangular lattice filling the trapezoid (centres up to the
// crest, within `off` [m] outside the slopes); returns how many. The pitch is that of the largest
// bounding diameter, the free-site test the model's
int pour_round(const WeirSpec& spec, double off, std::mt19937_64& rng, StonePacking& packing, PackedStones& pile) {
  const double au = spec.slope_up_deg * kPi / 180.0, ad = spec.slope_down_deg * kPi / 180.0;
  const double d_max = spec.d_mean * (1.0 + spec.d_spread) * packing.bounding_factor();
  const double pitch = 1.04 * d_max;
  const double row = pitch * std::sqrt(3.0) / 2.0;
  const double z_fill = spec.z_bed + spec.height;
  int added = 0, k = 0;
  for (double z = spec.z_bed + 1.6 * d_max; z <= z_fill; z += row, ++k) {
    const double hz = z - spec.z_bed;
    const double xa = spec.x_toe + hz / std::tan(au) + (0.5 * pitch - off) / std::sin(au);
    const double xb = spec.x_end() - hz / std::tan(ad) - (0.5 * pitch - off) / std::sin(ad);
    for (double xc = xa + (k % 2) * 0.5 * pitch; xc <= xb; xc += pitch) {
      const double dc = draw_diameter(rng, spec);
      const double xj = xc + 0.02 * (2.0 * uniform01(rng) - 1.0) * spec.d_mean;
      const PackedStone stone = packing.draw(dc);
      if (!packing.fits(pile, xj, z, stone, 0.02 * spec.d_mean)) continue;
      pile.add(xj, z, stone, 0);
      ++added;
    }
  }
  return added;
}

// distance from (x, z) to the segment a-b [m]
double segment_distance(double x, double z, double ax, double az, double bx, double bz) {
  const double ex = bx - ax, ez = bz - az;
  const double len2 = ex * ex + ez * ez;
  double t = len2 > 0.0 ? ((x - ax) * ex + (z - az) * ez) / len2 : 0.0;
  t = std::clamp(t, 0.0, 1.0);
  return std::hypot(x - ax - t * ex, z - az - t * ez);
}

double largest_gap(const DEMSystem& sys, const WeirSpec& spec, double& gx, double& gz, double z_min = -INFINITY);

struct Trapezoid {
  double px[4], pz[4];  // corners counter-clockwise: toe, upstream crest, downstream crest, downstream toe
  explicit Trapezoid(const WeirSpec& s) {
    const double x1 = s.x_toe + s.height / std::tan(s.slope_up_deg * kPi / 180.0);
    const double x2 = x1 + s.crest;
    const double zt = s.z_bed + s.height;
    const double xs[4] = {s.x_toe, s.x_end(), x2, x1};
    const double zs[4] = {s.z_bed, s.z_bed, zt, zt};
    for (int k = 0; k < 4; ++k) px[k] = xs[k], pz[k] = zs[k];
  }
  bool inside(double x, double z) const {
    for (int k = 0; k < 4; ++k) {
      const int l = (k + 1) % 4;
      const double cross = (px[l] - px[k]) * (z - pz[k]) - (pz[l] - pz[k]) * (x - px[k]);
      if (cross < 0.0) return false;
    }
    return true;
  }
  // signed distance (< 0 inside)
  double distance(double x, double z) const {
    double d = INFINITY;
    for (int k = 0; k < 4; ++k) {
      const int l = (k + 1) % 4;
      d = std::min(d, segment_distance(x, z, px[k], pz[k], px[l], pz[l]));
    }
    return inside(x, z) ? -d : d;
  }
};
}  // namespace

double WeirSpec::x_end() const {
  return x_toe + height / std::tan(slope_up_deg * kPi / 180.0) + crest +
         height / std::tan(slope_down_deg * kPi / 180.0);
}

double WeirSpec::top(double x) const {
  const double up = (x - x_toe) * std::tan(slope_up_deg * kPi / 180.0);
  const double down = (x_end() - x) * std::tan(slope_down_deg * kPi / 180.0);
  return std::max(0.0, std::min(height, std::min(up, down)));
}

double WeirSpec::area() const { return 0.5 * height * (crest + (x_end() - x_toe)); }

namespace {
// the model's packing of the spec's stones; std::invalid_argument naming `shape` for an unknown model or
// one without a packing
std::unique_ptr<StonePacking> model_packing(const WeirSpec& spec) {
  std::unique_ptr<StonePacking> packing = make_stone_model(spec.shape)->packing(spec);
  if (!packing)
    throw std::invalid_argument("shape = '" + spec.shape + "': the packing generator cannot pack this stone model");
  return packing;
}
}  // namespace

DEMSystem pack_weir(const WeirSpec& spec, const DEMParams& params, WeirPackingReport& report) {
  check_weir_spec(spec);
  // stones that also move across the flume: the 3D generator (weir_packing_3d.h)
  if (make_stone_model(spec.shape)->dimensions() == 3) return pack_weir_3d(spec, params, report);
  // the plane's rounds settle at the weir's friction
  if (spec.compaction_friction != -1.0)
    throw std::invalid_argument("compaction_friction = " + std::to_string(spec.compaction_friction) +
                                ": the plane's packing generator has no compaction (3D stone models only; -1: none)");
  const auto wall_start = std::chrono::steady_clock::now();
  std::unique_ptr<StonePacking> packing = model_packing(spec);
  std::mt19937_64 rng(spec.seed);
  PackedStones pile;
  const auto make = [&packing, &spec](const DEMParams& p, const PackedStones& stones) {
    return packing->make(p, stones, spec.density);
  };

  // (1) the fixed bottom row: touching stones on the bed along the base
  packing->bottom_row(spec, [&rng, &spec] { return draw_diameter(rng, spec); }, pile);
  const int n_fixed = static_cast<int>(pile.size());

  // (2) free stones poured in rounds: the free sites of a loose triangular lattice filling the
  // trapezoid are occupied, the stones settle inside temporary slope walls, and the gaps left at the
  // top by the compaction are filled again in the next round
  std::vector<DEMWall> final_walls;
  const DEMParams p = packing_steps::pour_params(params, spec, final_walls);
  const double off = 0.5 * spec.d_mean;  // the slope walls' offset outside the slopes
  double t_total = 0.0;
  DEMSystem box(p, 0);
  for (int round = 0; round < 6; ++round) {
    if (pour_round(spec, off, rng, *packing, pile) == 0 && round > 0) break;
    box = make(p, pile);
    t_total += settle(box, spec, 0.2);
    pile.take(box);
  }

  // (3) keep the stones whose centres lie below the crest
  pile = packing_steps::below_crest(box, pile, spec);

  // (4) slope walls removed: the mound settles on its own
  DEMParams q = params;
  q.walls = final_walls;
  DEMSystem weir = make(q, pile);
  t_total += settle(weir, spec, 0.5);
  // (5) hollows left where stones rolled off the crest corners are topped up, without the walls
  for (int round = 0; round < 3; ++round) {
    pile.take(weir);
    if (pour_round(spec, off, rng, *packing, pile) == 0) break;
    weir = make(q, pile);
    t_total += settle(weir, spec, 0.5);
  }
  // (6) stones laid by hand into the largest remaining hollows of the slopes and crest, above the fixed
  // layer: a stone laid on the bed at a toe's tip would rest against one fixed stone, loose in the first flow
  const double z_laid = spec.z_bed + spec.d_mean;
  for (int k = 0; k < 12; ++k) {
    double px = 0.0, pz = 0.0;
    if (largest_gap(weir, spec, px, pz, z_laid) < 0.5 * spec.d_mean) break;
    PackedStone stone = packing->draw(draw_diameter(rng, spec));
    const double rc = stone.radius;
    pile.take(weir);
    // lowest free spot above the hollow's point, in each of the model's orientations at each height
    bool placed = false;
    for (double lift = 0.0; lift <= 2.0 * rc && !placed; lift += 0.05 * rc) {
      bool free_site = false;
      for (int turn = 0; turn < packing->turns() && !free_site; ++turn, stone.angle += kPi / 3.0)
        free_site = packing->fits(pile, px, pz + lift, stone, 1e-4);
      if (!free_site) continue;
      pile.add(px, pz + lift, stone, 0);
      placed = true;
    }
    if (!placed) break;
    weir = make(q, pile);
    t_total += settle(weir, spec, 0.3);
  }

  // (7) stones that rolled off a toe onto the bed beyond it (centre more than half a diameter outside
  // the trapezoid) are not part of the weir, for the models whose stones roll that far
  // (the mound settles again after each removal, and another stone may roll off: up to three rounds)
  for (int round = 0; round < 3 && packing->drop_toe_rollers(); ++round) {
    const Trapezoid trap(spec);
    PackedStones kept_on;
    for (int i = 0; i < weir.n(); ++i)
      if (weir.stone_fixed[i] || trap.distance(weir.stone_pos[2 * i], weir.stone_pos[2 * i + 1]) < 0.5 * spec.d_mean)
        kept_on.copy_stone(weir, pile, i);
    if (kept_on.size() == static_cast<std::size_t>(weir.n())) break;
    pile = kept_on;
    weir = make(q, pile);
    t_total += settle(weir, spec, 0.3);
  }

  report.n_stones = weir.n();
  report.n_fixed = n_fixed;
  report.max_speed = max_speed(weir);
  report.settle_time = t_total;
  report.porosity = weir_porosity(weir, spec);
  report.outline_error = weir_outline_error(weir, spec);
  report.wall_seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - wall_start).count();
  return weir;
}

namespace {
// the point of the slopes and crest farthest from every disc; returns that distance [m]
double largest_gap(const DEMSystem& sys, const WeirSpec& spec, double& gx, double& gz, double z_min) {
  const Trapezoid trap(spec);
  const StoneModel& model = sys.model();
  double worst = 0.0;
  for (int e = 1; e <= 3; ++e) {
    const int a = e % 4, b = (e + 1) % 4;
    const double len = std::hypot(trap.px[b] - trap.px[a], trap.pz[b] - trap.pz[a]);
    const int m = std::max(2, static_cast<int>(len / 0.002));
    for (int s = 0; s <= m; ++s) {
      const double t = static_cast<double>(s) / m;
      const double x = trap.px[a] + t * (trap.px[b] - trap.px[a]);
      const double z = trap.pz[a] + t * (trap.pz[b] - trap.pz[a]);
      if (z < z_min) continue;
      double gap = INFINITY;
      for (int i = 0; i < sys.n(); ++i) {
        if (!sys.stone_active[i]) continue;
        gap = std::min(gap, model.gap(sys, i, x, z));
      }
      if (gap > worst) {
        worst = gap;
        gx = x;
        gz = z;
      }
    }
  }
  return worst;
}
}  // namespace

double weir_outline_error(const DEMSystem& sys, const WeirSpec& spec) {
  const Trapezoid trap(spec);
  const auto distance = [&trap](double x, double z) { return trap.distance(x, z); };
  double err = 0.0;
  // (a) stones reaching outside
  for (int i = 0; i < sys.n(); ++i) {
    if (!sys.stone_active[i]) continue;
    err = std::max(err, sys.model().outline_max(sys, i, distance));
  }
  // (b) points of the slopes and crest far from every disc
  double gx = 0.0, gz = 0.0;
  err = std::max(err, largest_gap(sys, spec, gx, gz));
  return err;
}

double weir_porosity(const DEMSystem& sys, const WeirSpec& spec, double h) {
  require_positive("h", h);
  const Trapezoid trap(spec);
  const StoneModel& model = sys.model();
  long long inside = 0, covered = 0;
  for (double z = spec.z_bed + 0.5 * h; z < spec.z_bed + spec.height; z += h) {
    for (double x = spec.x_toe + 0.5 * h; x < spec.x_end(); x += h) {
      if (!trap.inside(x, z)) continue;
      ++inside;
      for (int i = 0; i < sys.n(); ++i) {
        if (!sys.stone_active[i]) continue;
        if (model.covers(sys, i, x, z)) {
          ++covered;
          break;
        }
      }
    }
  }
  return inside > 0 ? 1.0 - static_cast<double>(covered) / inside : 1.0;
}

}  // namespace vofdem
