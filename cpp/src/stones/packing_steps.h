// The steps the weir packing generators share (weir_packing.cpp in the plane, weir_packing_3d.cpp across
// the width): the temporary slope walls the pour settles in, the settling until rest, and the trim of
// the stones above the crest. Each generator measures its stones' speed its own way (spin about y in the
// plane, the 3D spin across the width).
#pragma once

#include <cmath>
#include <vector>

#include "vofdem/common/numbers.h"
#include "vofdem/stones/dem_system.h"
#include "vofdem/stones/stone_packing.h"
#include "vofdem/stones/weir_packing.h"

namespace vofdem::packing_steps {

// the pour's parameters: the bed (added if `params` has no wall), no sleeping and no external force, and
// two slope walls half a mean diameter outside the slopes (stone centres end near the slope lines);
// `final_walls` receives the walls the weir keeps once the slope walls are removed
inline DEMParams pour_params(const DEMParams& params, const WeirSpec& spec, std::vector<DEMWall>& final_walls) {
  const double au = spec.slope_up_deg * kPi / 180.0, ad = spec.slope_down_deg * kPi / 180.0;
  DEMParams p = params;
  if (p.walls.empty()) p.walls.push_back({{spec.x_toe, spec.z_bed}, {0.0, 1.0}, 0.176});
  final_walls = p.walls;
  p.flags &= ~static_cast<unsigned>(kDEMSleeping | kDEMExternalForce);
  const double off = 0.5 * spec.d_mean;
  p.walls.push_back({{spec.x_toe - off / std::sin(au), spec.z_bed}, {std::sin(au), -std::cos(au)},
                     p.walls.front().friction});
  p.walls.push_back({{spec.x_end() + off / std::sin(ad), spec.z_bed}, {-std::sin(ad), -std::cos(ad)},
                     p.walls.front().friction});
  return p;
}

// runs until every stone has been slower than rest_speed for `hold` seconds (max_speed(sys) [m/s]), or
// the settling time runs out; returns the simulated time [s]
template <class MaxSpeed>
double settle(DEMSystem& sys, const WeirSpec& s, double hold, MaxSpeed max_speed) {
  const double chunk = 0.01;
  double t = 0.0, quiet = 0.0;
  while (t < s.settle_time_max) {
    sys.advance(chunk);
    t += chunk;
    quiet = max_speed(sys) < s.rest_speed ? quiet + chunk : 0.0;
    if (quiet >= hold - 1e-12) break;
  }
  return t;
}

// the stones of `box` (whose shapes are `pile`'s) kept: the fixed ones and the free ones whose centres lie
// at most a quarter of a mean diameter above the crest
inline PackedStones below_crest(const DEMSystem& box, const PackedStones& pile, const WeirSpec& spec) {
  const double z_crest = spec.z_bed + spec.height;
  PackedStones kept;
  for (int i = 0; i < box.n(); ++i) {
    if (!box.stone_active[i]) continue;
    if (!box.stone_fixed[i] && box.stone_pos[2 * i + 1] > z_crest + 0.25 * spec.d_mean) continue;
    kept.copy_stone(box, pile, i);
  }
  return kept;
}

}  // namespace vofdem::packing_steps
