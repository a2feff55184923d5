// State of DEMSystem: every piece of it as one typed value (DEMState), so that a run restarted from
// export_state() continues bit-for-bit (stone arrays, accelerations of the velocity Verlet scheme,
// contact histories, sleep timers, counters, time, energy accumulators). The guard of advance() and
// the coupler's snapshot copy it into a reused DEMState (array copies, no allocation once sized); the
// checkpoint maps it to named flat arrays of doubles. On import from such a map the rolling springs
// (contact_mr, wall_mr), the linear drag and the water levels are optional: a checkpoint written before
// they existed restarts with what it had.
#include <limits>
#include <stdexcept>
#include <utility>

#include "vofdem/check.h"
#include "vofdem/dem_system.h"

namespace vofdem {

namespace {
using StateMap = std::map<std::string, std::vector<double>>;
constexpr std::size_t kAny = static_cast<std::size_t>(-1);

template <class T>
std::vector<double> to_double(const std::vector<T>& v) {
  return std::vector<double>(v.begin(), v.end());
}

const std::vector<double>& get(const StateMap& s, const std::string& key, std::size_t size) {
  const auto it = s.find(key);
  if (it == s.end()) throw std::invalid_argument("import_state: missing array '" + key + "'");
  if (size != kAny && it->second.size() != size)
    throw std::invalid_argument("import_state: array '" + key + "' has size " + std::to_string(it->second.size()) +
                                ", expected " + std::to_string(size));
  return it->second;
}

template <class T>
void set(std::vector<T>& dst, const std::vector<double>& src) {
  dst.assign(src.size(), T{});
  for (std::size_t k = 0; k < src.size(); ++k) dst[k] = static_cast<T>(src[k]);
}

template <class T>
void need(const char* name, const std::vector<T>& v, std::size_t size) {
  if (v.size() != size)
    throw std::invalid_argument(std::string("import_state: array '") + name + "' has size " +
                                std::to_string(v.size()) + ", expected " + std::to_string(size));
}

// same size: written in place, so the numpy views of dst stay valid; another size reallocates
template <class T>
void copy_into(std::vector<T>& dst, const std::vector<T>& src) {
  if (dst.size() == src.size()) std::copy(src.begin(), src.end(), dst.begin());
  else dst = src;
}
}  // namespace

void DEMSystem::export_state(DEMState& s) const {
  s.disc_pos = disc_pos;
  s.disc_vel = disc_vel;
  s.disc_angle = disc_angle;
  s.disc_omega = disc_omega;
  s.disc_radius = disc_radius;
  s.disc_density = disc_density;
  s.disc_fixed = disc_fixed;
  s.disc_active = disc_active;
  s.disc_force_ext = disc_force_ext;
  s.disc_drag_coef = disc_drag_coef;
  s.disc_drag_vel = disc_drag_vel;
  s.disc_wet = disc_wet;
  s.disc_water_level = disc_water_level;
  s.disc_force = disc_force;
  s.disc_torque = disc_torque;
  s.disc_acc = disc_acc;
  s.disc_alpha = disc_alpha;
  s.disc_asleep = disc_asleep;
  s.disc_sleep_timer = disc_sleep_timer;
  // only the histories that are not zero: the rest is rebuilt by the neighbour search
  s.contact_i.clear(), s.contact_j.clear(), s.contact_xi.clear(), s.contact_mr.clear();
  for (const Pair& p : pairs_) {
    if (p.xi == 0.0 && p.mr == 0.0) continue;
    s.contact_i.push_back(p.i);
    s.contact_j.push_back(p.j);
    s.contact_xi.push_back(p.xi);
    s.contact_mr.push_back(p.mr);
  }
  s.wall_xi = wall_xi_;
  s.wall_mr = wall_mr_;
  s.time = time_;
  s.steps = steps_;
  s.removed = removed_;
  s.dissipated = dissipated_;
  s.work_external = work_external_;
  s.elastic = elastic_;
  s.ncontact = ncontact_;
  s.nwall_contact = nwall_contact_;
  s.forces_valid = forces_valid_;
  export_polygons(s);
}

void DEMSystem::check_state(const DEMState& s) const {
  const std::size_t n = s.disc_radius.size(), nw = n * params_.walls.size();
  for (const auto& [name, v] : {std::pair<const char*, const std::vector<double>*>{"disc_pos", &s.disc_pos},
                                {"disc_vel", &s.disc_vel},
                                {"disc_force_ext", &s.disc_force_ext},
                                {"disc_drag_vel", &s.disc_drag_vel},
                                {"disc_force", &s.disc_force},
                                {"disc_acc", &s.disc_acc}})
    need(name, *v, 2 * n);
  for (const auto& [name, v] : {std::pair<const char*, const std::vector<double>*>{"disc_angle", &s.disc_angle},
                                {"disc_omega", &s.disc_omega},
                                {"disc_density", &s.disc_density},
                                {"disc_drag_coef", &s.disc_drag_coef},
                                {"disc_wet", &s.disc_wet},
                                {"disc_water_level", &s.disc_water_level},
                                {"disc_torque", &s.disc_torque},
                                {"disc_alpha", &s.disc_alpha},
                                {"disc_sleep_timer", &s.disc_sleep_timer}})
    need(name, *v, n);
  need("disc_fixed", s.disc_fixed, n);
  need("disc_active", s.disc_active, n);
  need("disc_asleep", s.disc_asleep, n);
  const std::size_t nc = s.contact_i.size();
  need("contact_j", s.contact_j, nc);
  need("contact_xi", s.contact_xi, nc);
  need("contact_mr", s.contact_mr, nc);
  for (std::size_t k = 0; k < nc; ++k) {
    const int i = s.contact_i[k], j = s.contact_j[k];
    if (!(i >= 0 && i < j && j < static_cast<int>(n)))
      throw std::invalid_argument("import_state: contact pair (" + std::to_string(i) + ", " + std::to_string(j) +
                                  ") is outside 0 <= i < j < n");
    if (k > 0 && !(s.contact_i[k - 1] < i || (s.contact_i[k - 1] == i && s.contact_j[k - 1] < j)))
      throw std::invalid_argument("import_state: contact pairs are not sorted by (i, j)");
  }
  need("wall_xi", s.wall_xi, nw);
  need("wall_mr", s.wall_mr, nw);
  if (!s.poly_offset.empty()) check_polygon_state(s);
}

void DEMSystem::import_state(const DEMState& s) {
  check_state(s);
  const std::size_t n = s.disc_radius.size();
  if (n != static_cast<std::size_t>(n_)) resize(static_cast<int>(n));
  copy_into(disc_pos, s.disc_pos);
  copy_into(disc_vel, s.disc_vel);
  copy_into(disc_angle, s.disc_angle);
  copy_into(disc_omega, s.disc_omega);
  copy_into(disc_radius, s.disc_radius);
  copy_into(disc_density, s.disc_density);
  copy_into(disc_fixed, s.disc_fixed);
  copy_into(disc_active, s.disc_active);
  copy_into(disc_force_ext, s.disc_force_ext);
  copy_into(disc_drag_coef, s.disc_drag_coef);
  copy_into(disc_drag_vel, s.disc_drag_vel);
  copy_into(disc_wet, s.disc_wet);
  copy_into(disc_water_level, s.disc_water_level);
  copy_into(disc_force, s.disc_force);
  copy_into(disc_torque, s.disc_torque);
  copy_into(disc_acc, s.disc_acc);
  copy_into(disc_alpha, s.disc_alpha);
  copy_into(disc_asleep, s.disc_asleep);
  copy_into(disc_sleep_timer, s.disc_sleep_timer);
  pairs_.clear();
  for (std::size_t k = 0; k < s.contact_i.size(); ++k)
    pairs_.push_back({s.contact_i[k], s.contact_j[k], s.contact_xi[k], 0.0, s.contact_mr[k]});  // masses: next build
  copy_into(wall_xi_, s.wall_xi);
  copy_into(wall_mr_, s.wall_mr);
  import_polygons(s);  // the shape: polygons if the state has them, else discs
  time_ = s.time;
  steps_ = s.steps;
  removed_ = s.removed;
  dissipated_ = s.dissipated;
  work_external_ = s.work_external;
  elastic_ = s.elastic;
  ncontact_ = s.ncontact;
  nwall_contact_ = s.nwall_contact;
  forces_valid_ = s.forces_valid;
  rebuild_ = true;
  prepared_ = false;
}

// ---- the checkpoint: named flat arrays of doubles

std::map<std::string, std::vector<double>> dem_state_to_map(DEMState t) {
  StateMap s;
  s["disc_pos"] = std::move(t.disc_pos);
  s["disc_vel"] = std::move(t.disc_vel);
  s["disc_angle"] = std::move(t.disc_angle);
  s["disc_omega"] = std::move(t.disc_omega);
  s["disc_radius"] = std::move(t.disc_radius);
  s["disc_density"] = std::move(t.disc_density);
  s["disc_fixed"] = to_double(t.disc_fixed);
  s["disc_active"] = to_double(t.disc_active);
  s["disc_force_ext"] = std::move(t.disc_force_ext);
  s["disc_drag_coef"] = std::move(t.disc_drag_coef);
  s["disc_drag_vel"] = std::move(t.disc_drag_vel);
  s["disc_wet"] = std::move(t.disc_wet);
  s["disc_water_level"] = std::move(t.disc_water_level);
  s["disc_force"] = std::move(t.disc_force);
  s["disc_torque"] = std::move(t.disc_torque);
  s["disc_acc"] = std::move(t.disc_acc);
  s["disc_alpha"] = std::move(t.disc_alpha);
  s["disc_asleep"] = to_double(t.disc_asleep);
  s["disc_sleep_timer"] = std::move(t.disc_sleep_timer);
  s["contact_i"] = to_double(t.contact_i);
  s["contact_j"] = to_double(t.contact_j);
  s["contact_xi"] = std::move(t.contact_xi);
  s["contact_mr"] = std::move(t.contact_mr);
  s["wall_xi"] = std::move(t.wall_xi);
  s["wall_mr"] = std::move(t.wall_mr);
  s["scalars"] = {t.time,
                  static_cast<double>(t.steps),
                  static_cast<double>(t.removed),
                  t.dissipated,
                  t.work_external,
                  t.elastic,
                  static_cast<double>(t.ncontact),
                  static_cast<double>(t.nwall_contact),
                  t.forces_valid ? 1.0 : 0.0};
  if (!t.poly_offset.empty()) {
    s["poly_vertex"] = std::move(t.poly_vertex);
    s["poly_offset"] = to_double(t.poly_offset);
    s["poly_contact_i"] = to_double(t.poly_contact_i);
    s["poly_contact_j"] = to_double(t.poly_contact_j);
    s["poly_contact_id"] = to_double(t.poly_contact_id);
    s["poly_contact_xi"] = std::move(t.poly_contact_xi);
    s["poly_wall_id"] = to_double(t.poly_wall_id);
    s["poly_wall_xi"] = std::move(t.poly_wall_xi);
  }
  return s;
}

DEMState dem_state_from_map(const std::map<std::string, std::vector<double>>& s, std::size_t nwalls) {
  DEMState t;
  const std::size_t n = get(s, "disc_radius", kAny).size();
  t.disc_pos = get(s, "disc_pos", 2 * n);
  t.disc_vel = get(s, "disc_vel", 2 * n);
  t.disc_angle = get(s, "disc_angle", n);
  t.disc_omega = get(s, "disc_omega", n);
  t.disc_radius = get(s, "disc_radius", n);
  t.disc_density = get(s, "disc_density", n);
  set(t.disc_fixed, get(s, "disc_fixed", n));
  set(t.disc_active, get(s, "disc_active", n));
  t.disc_force_ext = get(s, "disc_force_ext", 2 * n);
  // older states hold no linear drag
  const bool drag = s.count("disc_drag_coef") > 0;
  t.disc_drag_coef = drag ? get(s, "disc_drag_coef", n) : std::vector<double>(n, 0.0);
  t.disc_drag_vel = drag ? get(s, "disc_drag_vel", 2 * n) : std::vector<double>(2 * n, 0.0);
  t.disc_wet = get(s, "disc_wet", n);
  // older states hold no water levels: the wet fractions are then held as set
  t.disc_water_level = s.count("disc_water_level") ? get(s, "disc_water_level", n)
                                                   : std::vector<double>(n, std::numeric_limits<double>::quiet_NaN());
  t.disc_force = get(s, "disc_force", 2 * n);
  t.disc_torque = get(s, "disc_torque", n);
  t.disc_acc = get(s, "disc_acc", 2 * n);
  t.disc_alpha = get(s, "disc_alpha", n);
  set(t.disc_asleep, get(s, "disc_asleep", n));
  t.disc_sleep_timer = get(s, "disc_sleep_timer", n);
  const auto& ci = get(s, "contact_i", kAny);
  set(t.contact_i, ci);
  set(t.contact_j, get(s, "contact_j", ci.size()));
  t.contact_xi = get(s, "contact_xi", ci.size());
  t.contact_mr = s.count("contact_mr") ? get(s, "contact_mr", ci.size()) : std::vector<double>(ci.size(), 0.0);
  const std::size_t nw = n * nwalls;
  t.wall_xi = get(s, "wall_xi", nw);
  t.wall_mr = s.count("wall_mr") ? get(s, "wall_mr", nw) : std::vector<double>(nw, 0.0);
  if (s.count("poly_vertex")) {
    t.poly_vertex = s.at("poly_vertex");
    set(t.poly_offset, get(s, "poly_offset", n + 1));
    const auto& pi = get(s, "poly_contact_i", kAny);
    set(t.poly_contact_i, pi);
    set(t.poly_contact_j, get(s, "poly_contact_j", pi.size()));
    set(t.poly_contact_id, get(s, "poly_contact_id", 2 * pi.size()));
    t.poly_contact_xi = get(s, "poly_contact_xi", 2 * pi.size());
    set(t.poly_wall_id, get(s, "poly_wall_id", 2 * nw));
    t.poly_wall_xi = get(s, "poly_wall_xi", 2 * nw);
  }
  const auto& sc = get(s, "scalars", 9);
  t.time = sc[0];
  t.steps = static_cast<long long>(sc[1]);
  t.removed = static_cast<int>(sc[2]);
  t.dissipated = sc[3];
  t.work_external = sc[4];
  t.elastic = sc[5];
  t.ncontact = static_cast<int>(sc[6]);
  t.nwall_contact = static_cast<int>(sc[7]);
  t.forces_valid = sc[8] != 0.0;
  return t;
}

std::map<std::string, std::vector<double>> DEMSystem::export_state() const {
  DEMState t;
  export_state(t);
  return dem_state_to_map(std::move(t));
}

void DEMSystem::import_state(const std::map<std::string, std::vector<double>>& s) {
  import_state(dem_state_from_map(s, params_.walls.size()));
}

}  // namespace vofdem
