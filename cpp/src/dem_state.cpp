// Checkpoint of DEMSystem: every piece of its state as named flat arrays of doubles, so that a run
// restarted from export_state() continues bit-for-bit (stone arrays, accelerations of the velocity
// Verlet scheme, contact histories, sleep timers, counters, time, energy accumulators). The rolling
// springs (contact_mr, wall_mr) are optional on import: a checkpoint written before the rolling
// resistance existed restarts with them at zero, which is what it had.
#include <limits>
#include <stdexcept>

#include "vofdem/check.h"
#include "vofdem/dem_system.h"

namespace vofdem {

namespace {
template <class T>
std::vector<double> to_double(const std::vector<T>& v) {
  return std::vector<double>(v.begin(), v.end());
}

const std::vector<double>& get(const std::map<std::string, std::vector<double>>& s, const std::string& key,
                               std::size_t size) {
  const auto it = s.find(key);
  if (it == s.end()) throw std::invalid_argument("import_state: missing array '" + key + "'");
  if (size != static_cast<std::size_t>(-1) && it->second.size() != size)
    throw std::invalid_argument("import_state: array '" + key + "' has size " + std::to_string(it->second.size()) +
                                ", expected " + std::to_string(size));
  return it->second;
}

template <class T>
void set(std::vector<T>& dst, const std::vector<double>& src) {
  dst.assign(src.size(), T{});
  for (std::size_t k = 0; k < src.size(); ++k) dst[k] = static_cast<T>(src[k]);
}
}  // namespace

std::map<std::string, std::vector<double>> DEMSystem::export_state() const {
  std::map<std::string, std::vector<double>> s;
  s["disc_pos"] = disc_pos;
  s["disc_vel"] = disc_vel;
  s["disc_angle"] = disc_angle;
  s["disc_omega"] = disc_omega;
  s["disc_radius"] = disc_radius;
  s["disc_density"] = disc_density;
  s["disc_fixed"] = to_double(disc_fixed);
  s["disc_active"] = to_double(disc_active);
  s["disc_force_ext"] = disc_force_ext;
  s["disc_drag_coef"] = disc_drag_coef;
  s["disc_drag_vel"] = disc_drag_vel;
  s["disc_wet"] = disc_wet;
  s["disc_water_level"] = disc_water_level;
  s["disc_force"] = disc_force;
  s["disc_torque"] = disc_torque;
  s["disc_acc"] = disc_acc;
  s["disc_alpha"] = disc_alpha;
  s["disc_asleep"] = to_double(disc_asleep);
  s["disc_sleep_timer"] = disc_sleep_timer;
  // only the histories that are not zero: the rest is rebuilt by the neighbour search
  std::vector<double> ci, cj, cxi, cmr;
  for (const Pair& p : pairs_) {
    if (p.xi == 0.0 && p.mr == 0.0) continue;
    ci.push_back(p.i);
    cj.push_back(p.j);
    cxi.push_back(p.xi);
    cmr.push_back(p.mr);
  }
  s["contact_i"] = ci;
  s["contact_j"] = cj;
  s["contact_xi"] = cxi;
  s["contact_mr"] = cmr;
  s["wall_xi"] = wall_xi_;
  s["wall_mr"] = wall_mr_;
  s["scalars"] = {time_,
                  static_cast<double>(steps_),
                  static_cast<double>(removed_),
                  dissipated_,
                  work_external_,
                  elastic_,
                  static_cast<double>(ncontact_),
                  static_cast<double>(nwall_contact_),
                  forces_valid_ ? 1.0 : 0.0};
  if (shape_ == StoneShape::kPolygon) export_polygons(s);
  return s;
}

void DEMSystem::import_state(const std::map<std::string, std::vector<double>>& s) {
  const std::size_t n = get(s, "disc_radius", static_cast<std::size_t>(-1)).size();
  if (n != static_cast<std::size_t>(n_)) resize(static_cast<int>(n));
  set(disc_pos, get(s, "disc_pos", 2 * n));
  set(disc_vel, get(s, "disc_vel", 2 * n));
  set(disc_angle, get(s, "disc_angle", n));
  set(disc_omega, get(s, "disc_omega", n));
  set(disc_radius, get(s, "disc_radius", n));
  set(disc_density, get(s, "disc_density", n));
  set(disc_fixed, get(s, "disc_fixed", n));
  set(disc_active, get(s, "disc_active", n));
  set(disc_force_ext, get(s, "disc_force_ext", 2 * n));
  // older states hold no linear drag
  if (s.count("disc_drag_coef")) {
    set(disc_drag_coef, get(s, "disc_drag_coef", n));
    set(disc_drag_vel, get(s, "disc_drag_vel", 2 * n));
  } else {
    disc_drag_coef.assign(n, 0.0);
    disc_drag_vel.assign(2 * n, 0.0);
  }
  set(disc_wet, get(s, "disc_wet", n));
  // older states hold no water levels: the wet fractions are then held as set
  if (s.count("disc_water_level")) set(disc_water_level, get(s, "disc_water_level", n));
  else disc_water_level.assign(n, std::numeric_limits<double>::quiet_NaN());
  set(disc_force, get(s, "disc_force", 2 * n));
  set(disc_torque, get(s, "disc_torque", n));
  set(disc_acc, get(s, "disc_acc", 2 * n));
  set(disc_alpha, get(s, "disc_alpha", n));
  set(disc_asleep, get(s, "disc_asleep", n));
  set(disc_sleep_timer, get(s, "disc_sleep_timer", n));
  const auto& ci = get(s, "contact_i", static_cast<std::size_t>(-1));
  const auto& cj = get(s, "contact_j", ci.size());
  const auto& cxi = get(s, "contact_xi", ci.size());
  const bool has_mr = s.count("contact_mr") > 0;
  const std::vector<double> cmr = has_mr ? get(s, "contact_mr", ci.size()) : std::vector<double>(ci.size(), 0.0);
  pairs_.clear();
  for (std::size_t k = 0; k < ci.size(); ++k) {
    const int i = static_cast<int>(ci[k]), j = static_cast<int>(cj[k]);
    if (!(i >= 0 && i < j && j < static_cast<int>(n)))
      throw std::invalid_argument("import_state: contact pair (" + std::to_string(i) + ", " + std::to_string(j) +
                                  ") is outside 0 <= i < j < n");
    if (k > 0 && !(pairs_.back().i < i || (pairs_.back().i == i && pairs_.back().j < j)))
      throw std::invalid_argument("import_state: contact pairs are not sorted by (i, j)");
    pairs_.push_back({i, j, cxi[k], 0.0, cmr[k]});  // masses set by the next build
  }
  set(wall_xi_, get(s, "wall_xi", n * params_.walls.size()));
  if (s.count("wall_mr"))
    set(wall_mr_, get(s, "wall_mr", n * params_.walls.size()));
  else
    wall_mr_.assign(wall_xi_.size(), 0.0);
  import_polygons(s);  // the shape: polygons if the state has them, else discs
  const auto& sc = get(s, "scalars", 9);
  time_ = sc[0];
  steps_ = static_cast<long long>(sc[1]);
  removed_ = static_cast<int>(sc[2]);
  dissipated_ = sc[3];
  work_external_ = sc[4];
  elastic_ = sc[5];
  ncontact_ = static_cast<int>(sc[6]);
  nwall_contact_ = static_cast<int>(sc[7]);
  forces_valid_ = sc[8] != 0.0;
  rebuild_ = true;
  prepared_ = false;
}

}  // namespace vofdem
