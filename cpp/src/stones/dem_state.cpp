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

#include "common/state_fields.h"
#include "vofdem/common/check.h"
#include "vofdem/stones/dem_system.h"

namespace vofdem {

namespace {
using state::entry;
using state::from_double;
using state::StateMap;
using state::to_double;
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

// the per-stone arrays (values per stone; optional: what a checkpoint written before it existed holds)
template <class T>
using DiscField = state::Field<DEMState, DEMSystem, T>;
const DiscField<double> kDiscReals[] = {
    {"stone_pos", &DEMState::stone_pos, &DEMSystem::stone_pos, 0, 2, false, 0.0},
    {"stone_vel", &DEMState::stone_vel, &DEMSystem::stone_vel, 0, 2, false, 0.0},
    {"stone_angle", &DEMState::stone_angle, &DEMSystem::stone_angle, 0, 1, false, 0.0},
    {"stone_omega", &DEMState::stone_omega, &DEMSystem::stone_omega, 0, 1, false, 0.0},
    {"stone_radius", &DEMState::stone_radius, &DEMSystem::stone_radius, 0, 1, false, 0.0},
    {"stone_density", &DEMState::stone_density, &DEMSystem::stone_density, 0, 1, false, 0.0},
    {"stone_force_ext", &DEMState::stone_force_ext, &DEMSystem::stone_force_ext, 0, 2, false, 0.0},
    // older states hold no linear drag
    {"stone_drag_coef", &DEMState::stone_drag_coef, &DEMSystem::stone_drag_coef, 0, 1, true, 0.0},
    {"stone_drag_vel", &DEMState::stone_drag_vel, &DEMSystem::stone_drag_vel, 0, 2, true, 0.0},
    {"stone_wet", &DEMState::stone_wet, &DEMSystem::stone_wet, 0, 1, false, 0.0},
    // older states hold no water levels: the wet fractions are then held as set
    {"stone_water_level", &DEMState::stone_water_level, &DEMSystem::stone_water_level, 0, 1, true, kNaN},
    {"stone_force", &DEMState::stone_force, &DEMSystem::stone_force, 0, 2, false, 0.0},
    {"stone_torque", &DEMState::stone_torque, &DEMSystem::stone_torque, 0, 1, false, 0.0},
    {"stone_acc", &DEMState::stone_acc, &DEMSystem::stone_acc, 0, 2, false, 0.0},
    {"stone_alpha", &DEMState::stone_alpha, &DEMSystem::stone_alpha, 0, 1, false, 0.0},
    {"stone_sleep_timer", &DEMState::stone_sleep_timer, &DEMSystem::stone_sleep_timer, 0, 1, false, 0.0},
};
const DiscField<std::uint8_t> kDiscFlags[] = {
    {"stone_fixed", &DEMState::stone_fixed, &DEMSystem::stone_fixed, 0, 1, false, 0.0},
    {"stone_active", &DEMState::stone_active, &DEMSystem::stone_active, 0, 1, false, 0.0},
    {"stone_asleep", &DEMState::stone_asleep, &DEMSystem::stone_asleep, 0, 1, false, 0.0},
};

// the out-of-plane state of 3D stones: its arrays and their values per stone (empty for the plane's models)
struct OutOfPlane {
  const char* key;
  std::vector<double> DEMState::*state;
  std::vector<double> DEMSystem::*live;
  std::size_t per;
};
const OutOfPlane kOutOfPlane[] = {
    {"stone_y", &DEMState::stone_y, &DEMSystem::stone_y, 1},
    {"stone_vel_y", &DEMState::stone_vel_y, &DEMSystem::stone_vel_y, 1},
    {"stone_force_y", &DEMState::stone_force_y, &DEMSystem::stone_force_y, 1},
    {"stone_acc_y", &DEMState::stone_acc_y, &DEMSystem::stone_acc_y, 1},
    {"stone_quat", &DEMState::stone_quat, &DEMSystem::stone_quat, 4},
    {"stone_omega_3d", &DEMState::stone_omega_3d, &DEMSystem::stone_omega_3d, 3},
    {"stone_torque_3d", &DEMState::stone_torque_3d, &DEMSystem::stone_torque_3d, 3},
};

// op(field) for every per-stone array, of either element type
template <class Op>
void each_disc_field(Op&& op) {
  for (const auto& f : kDiscReals) op(f);
  for (const auto& f : kDiscFlags) op(f);
}
}  // namespace

void DEMSystem::export_state(DEMState& s) const {
  each_disc_field([&](const auto& f) { s.*f.state = this->*f.live; });
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
  s.model = model_->name();
  for (const auto& f : kOutOfPlane) s.*f.state = this->*f.live;
  s.clear_model_part();
  model_->export_state(*this, s);
}

void DEMState::clear_model_part() {
  poly_vertex.clear(), poly_offset.clear();
  poly_contact_i.clear(), poly_contact_j.clear(), poly_contact_id.clear(), poly_contact_xi.clear();
  poly_wall_id.clear(), poly_wall_xi.clear();
  sphere_contact_i.clear(), sphere_contact_j.clear(), sphere_contact_spring.clear(), sphere_contact_rolling.clear();
  sphere_wall_spring.clear(), sphere_wall_rolling.clear();
  clump_sphere.clear(), clump_property.clear(), clump_offset.clear(), clump_contact.clear();
  clump_contact_spring.clear(), clump_contact_rolling.clear(), clump_wall_spring.clear(), clump_wall_rolling.clear();
}

void DEMSystem::check_state(const DEMState& s) const {
  const std::size_t n = s.stone_radius.size(), nw = n * params_.walls.size();
  each_disc_field([&](const auto& f) { require_size(f.key, s.*f.state, f.per * n); });
  const std::size_t nc = s.contact_i.size();
  require_size("contact_j", s.contact_j, nc);
  require_size("contact_xi", s.contact_xi, nc);
  require_size("contact_mr", s.contact_mr, nc);
  state::check_sorted_pairs("contact", s.contact_i, s.contact_j, n);
  require_size("wall_xi", s.wall_xi, nw);
  require_size("wall_mr", s.wall_mr, nw);
  const bool three_d = (s.model == model_->name() ? model_->dimensions() : make_stone_model(s.model)->dimensions()) == 3;
  for (const auto& f : kOutOfPlane) require_size(f.key, s.*f.state, three_d ? f.per * n : 0);
  if (s.model == model_->name()) model_->check_state(*this, s);
  else make_stone_model(s.model)->check_state(*this, s);
}

void DEMSystem::import_state(const DEMState& s) {
  check_state(s);
  const std::size_t n = s.stone_radius.size();
  if (n != static_cast<std::size_t>(n_)) resize(static_cast<int>(n));
  each_disc_field([&](const auto& f) { state::copy_into(this->*f.live, s.*f.state); });
  pairs_.clear();
  for (std::size_t k = 0; k < s.contact_i.size(); ++k)
    pairs_.push_back({s.contact_i[k], s.contact_j[k], s.contact_xi[k], 0.0, s.contact_mr[k]});  // masses: next build
  state::copy_into(wall_xi_, s.wall_xi);
  state::copy_into(wall_mr_, s.wall_mr);
  if (s.model != model_->name()) {  // the state's own model, its shape arrays made anew
    model_ = make_stone_model(s.model);
    poly_vertex.clear();
    poly_offset.clear();
  }
  three_d_ = model_->dimensions() == 3;
  wet_law_ = model_->wet_law();
  for (const auto& f : kOutOfPlane) state::copy_into(this->*f.live, s.*f.state);
  inertia_3d_.assign(three_d_ ? 3 * n : 0, std::numeric_limits<double>::infinity());
  model_->import_state(*this, s);
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
  for (const auto& f : kDiscReals) s[f.key] = std::move(t.*f.state);
  for (const auto& f : kDiscFlags) s[f.key] = to_double(t.*f.state);
  s["contact_i"] = to_double(t.contact_i);
  s["contact_j"] = to_double(t.contact_j);
  s["contact_xi"] = std::move(t.contact_xi);
  s["contact_mr"] = std::move(t.contact_mr);
  s["wall_xi"] = std::move(t.wall_xi);
  s["wall_mr"] = std::move(t.wall_mr);
  for (const auto& f : kOutOfPlane)
    if (!(t.*f.state).empty()) s[f.key] = std::move(t.*f.state);
  s["scalars"] = {t.time,
                  static_cast<double>(t.steps),
                  static_cast<double>(t.removed),
                  t.dissipated,
                  t.work_external,
                  t.elastic,
                  static_cast<double>(t.ncontact),
                  static_cast<double>(t.nwall_contact),
                  t.forces_valid ? 1.0 : 0.0};
  make_stone_model(t.model)->state_to_map(t, s);
  return s;
}

DEMState dem_state_from_map(const std::map<std::string, std::vector<double>>& checkpoint, std::size_t nwalls) {
  StateMap renamed;
  const StateMap& s = state::with_stone_keys(checkpoint, "", renamed);
  DEMState t;
  const std::size_t n = entry(s, "stone_radius", state::kAnySize).size();
  for (const auto& f : kDiscReals)
    t.*f.state = f.optional && !s.count(f.key) ? std::vector<double>(f.per * n, f.missing) : entry(s, f.key, f.per * n);
  for (const auto& f : kDiscFlags) from_double(t.*f.state, entry(s, f.key, f.per * n));
  const auto& ci = entry(s, "contact_i", state::kAnySize);
  from_double(t.contact_i, ci);
  from_double(t.contact_j, entry(s, "contact_j", ci.size()));
  t.contact_xi = entry(s, "contact_xi", ci.size());
  // (assigned apart: the conditional's temporary trips GCC 12's -Wfree-nonheap-object, a false positive)
  if (s.count("contact_mr")) t.contact_mr = entry(s, "contact_mr", ci.size());
  else t.contact_mr.assign(ci.size(), 0.0);
  const std::size_t nw = n * nwalls;
  t.wall_xi = entry(s, "wall_xi", nw);
  if (s.count("wall_mr")) t.wall_mr = entry(s, "wall_mr", nw);
  else t.wall_mr.assign(nw, 0.0);
  // the model whose own key the checkpoint holds, and its part
  t.model = stone_model_of_checkpoint([&](const std::string& key) { return s.count(key) > 0; });
  const auto model = make_stone_model(t.model);
  for (const auto& f : kOutOfPlane)
    if (model->dimensions() == 3) t.*f.state = entry(s, f.key, f.per * n);
  model->state_from_map(s, n, nwalls, t);
  const auto& sc = entry(s, "scalars", 9);
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
