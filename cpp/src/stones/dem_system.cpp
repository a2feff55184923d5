// DEM of the stones, eqs. (8)-(10) of Maeno & Tomita (2008): see dem_system.h.
#include "vofdem/stones/dem_system.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include "vofdem/common/check.h"
#include "vofdem/common/numbers.h"
#include "vofdem/stones/dem_contact.h"
#include "vofdem/stones/stone_model.h"
#include "vofdem/stones/wet_fraction.h"

namespace vofdem {

namespace {
const char* kStageNames[kDEMStageCount] = {"integrate", "removal", "neighbours", "body_forces",
                                            "contacts",  "walls",   "sleep",      "checks"};

// the model of a system made without one: discs
constexpr const char* kDefaultStoneModel = "disc";

[[noreturn]] void fail(const std::string& stage, int stone, double t, const std::string& what) {
  throw std::runtime_error("DEM stage '" + stage + "': " + what + " of stone " + std::to_string(stone) +
                           " at t = " + format_value(t) + " s (state restored to the start of the call)");
}
}  // namespace

void DEMParams::add_flume(double x_min, double x_max, double z_bed, double mu) {
  require_finite("x_min", x_min);
  require_finite("z_bed", z_bed);
  if (!(x_max > x_min)) require_in_open_closed("x_max", x_max, x_min, INFINITY);
  require_non_negative("mu", mu);
  walls.push_back({{x_min, z_bed}, {0.0, 1.0}, mu});
  walls.push_back({{x_min, z_bed}, {1.0, 0.0}, mu});
  walls.push_back({{x_max, z_bed}, {-1.0, 0.0}, mu});
}

DEMSystem::DEMSystem(const DEMParams& params, int n)
    : params_(params), model_(make_stone_model(kDefaultStoneModel)) {
  for (int s = 0; s < kDEMStageCount; ++s) profile_.add_stage(kStageNames[s]);
  check_params();
  resize(n);
}

DEMSystem::DEMSystem(const DEMParams& params, const std::vector<double>& pos, const std::vector<double>& radius,
                     const std::vector<double>& density, const std::vector<std::uint8_t>& fixed)
    : DEMSystem(params, static_cast<int>(radius.size())) {
  if (pos.size() != 2 * radius.size())
    require_in_closed("pos size", static_cast<double>(pos.size()), 2.0 * radius.size(), 2.0 * radius.size());
  if (density.size() != radius.size() && density.size() != 1)
    require_in_closed("density size", static_cast<double>(density.size()), 1.0, 1.0 * radius.size());
  if (!fixed.empty() && fixed.size() != radius.size())
    require_in_closed("fixed size", static_cast<double>(fixed.size()), 0.0, 1.0 * radius.size());
  stone_pos = pos;
  stone_radius = radius;
  for (int i = 0; i < n_; ++i) stone_density[i] = density.size() == 1 ? density[0] : density[i];
  if (!fixed.empty()) stone_fixed = fixed;
  check_stones();
}

void DEMSystem::resize(int n) {
  if (n < 0) require_non_negative("n", n);
  n_ = n;
  const std::size_t un = static_cast<std::size_t>(n);
  const double wet = params_.submerged ? 1.0 : 0.0;
  stone_pos.assign(2 * un, 0.0);
  stone_vel.assign(2 * un, 0.0);
  stone_angle.assign(un, 0.0);
  stone_omega.assign(un, 0.0);
  stone_radius.assign(un, 0.0);
  stone_density.assign(un, 0.0);  // none: the stones give it (an active stone without one is refused)
  stone_fixed.assign(un, 0);
  stone_active.assign(un, 1);
  stone_force_ext.assign(2 * un, 0.0);
  stone_drag_coef.assign(un, 0.0);
  stone_drag_vel.assign(2 * un, 0.0);
  stone_wet.assign(un, wet);
  stone_water_level.assign(un, std::numeric_limits<double>::quiet_NaN());
  stone_force.assign(2 * un, 0.0);
  stone_torque.assign(un, 0.0);
  stone_acc.assign(2 * un, 0.0);
  stone_alpha.assign(un, 0.0);
  stone_asleep.assign(un, 0);
  stone_sleep_timer.assign(un, 0.0);
  // back to the default model: a model with shapes is made again (set_polygons(), set_model())
  model_ = make_stone_model(kDefaultStoneModel);
  three_d_ = false;
  wet_law_ = model_->wet_law();
  size_out_of_plane();
  poly_vertex.clear();
  poly_offset.clear();
  pairs_.clear();
  wall_xi_.assign(un * params_.walls.size(), 0.0);
  wall_mr_.assign(un * params_.walls.size(), 0.0);
  wall_points_.assign(un * params_.walls.size(), PointSprings{});
  rebuild_ = true;
  prepared_ = false;
  forces_valid_ = false;
}

void DEMSystem::set_params(const DEMParams& p) {
  // checked before anything changes: a refused set leaves the system as it was
  p.validate();
  model_->check_params(p);
  const std::size_t old_walls = params_.walls.size();
  params_ = p;
  forces_valid_ = false;
  if (params_.walls.size() != old_walls) {
    wall_xi_.assign(static_cast<std::size_t>(n_) * params_.walls.size(), 0.0);
    wall_mr_.assign(wall_xi_.size(), 0.0);
    wall_points_.assign(wall_xi_.size(), PointSprings{});
  }
  rebuild_ = true;
  prepared_ = false;
}

void DEMParams::validate() const {
  medium.validate();
  require_non_negative("added_mass_coefficient", added_mass_coefficient);
  require_positive("dt", dt);
  require_non_negative("stiffness_normal", stiffness_normal);
  require_in_closed("contact_steps", contact_steps, 5.0, 1e6);
  require_non_negative("stiffness_ratio", stiffness_ratio);
  require_in_closed("restitution", restitution, 0.0, 1.0);
  require_non_negative("tangential_damping_factor", tangential_damping_factor);
  require_non_negative("friction_stone", friction_stone);
  require_in_open_closed("inertia_factor", inertia_factor, 0.0, 1.0);
  require_non_negative("rolling_friction_stone", rolling_friction_stone);
  require_non_negative("rolling_friction_wall", rolling_friction_wall);
  require_in_closed("rolling_damping", rolling_damping, 0.0, 1.0);
  require_non_negative("neighbour_skin", neighbour_skin);
  require_non_negative("sleep_velocity", sleep_velocity);
  require_non_negative("sleep_time", sleep_time);
  require_non_negative("wake_acceleration", wake_acceleration);
  for (int c = 0; c < 2; ++c) {
    // -inf is a side without removal; NaN and +inf bound nothing
    if (!(domain_min[c] < INFINITY)) require_finite(c == 0 ? "domain_min[0]" : "domain_min[1]", domain_min[c]);
    if (!(domain_max[c] > domain_min[c]))
      require_in_open_closed(c == 0 ? "domain_max[0]" : "domain_max[1]", domain_max[c], domain_min[c], INFINITY);
  }
  require_finite("width", width);
  require_non_negative("width", width);
  require_non_negative("side_wall_friction", side_wall_friction);
  require_finite("side_wall_friction", side_wall_friction);
  for (const DEMWall& w : walls) {
    require_finite("wall point", w.point[0]);
    require_finite("wall point", w.point[1]);
    require_positive("wall normal length", std::hypot(w.normal[0], w.normal[1]));
    require_non_negative("wall friction", w.friction);
  }
  if (flags >= (1u << 10))
    throw std::invalid_argument("flags = " + std::to_string(flags) + " is outside the allowed range [0, 1023]");
}

void DEMSystem::check_params() const {
  params_.validate();
  model_->check_params(params_);
}

void DEMSystem::set_model(const std::string& name) { set_model(make_stone_model(name)); }

void DEMSystem::set_model(std::unique_ptr<StoneModel> model) {
  if (!model) throw std::invalid_argument("set_model: no model");
  model->check_params(params_);
  model_ = std::move(model);
  three_d_ = model_->dimensions() == 3;
  wet_law_ = model_->wet_law();
  size_out_of_plane();
  poly_vertex.clear();
  poly_offset.clear();
  std::fill(wall_xi_.begin(), wall_xi_.end(), 0.0);
  std::fill(wall_mr_.begin(), wall_mr_.end(), 0.0);
  std::fill(wall_points_.begin(), wall_points_.end(), PointSprings{});
  shapes_changed();
}

void DEMSystem::shapes_changed() {
  pairs_.clear();
  rebuild_ = true;
  prepared_ = false;
  forces_valid_ = false;
}

void DEMSystem::check_stones() const {
  for (int i = 0; i < n_; ++i) {
    if (!stone_active[i]) continue;
    require_positive("stone_radius", stone_radius[i]);
    if (!(stone_density[i] > 0.0 && std::isfinite(stone_density[i])))
      throw std::invalid_argument("stone_density[" + std::to_string(i) + "] = " + std::to_string(stone_density[i]) +
                                  " kg/m^3 must be a finite value > 0: the stones' density is given by the scene "
                                  "(stones.density) or DEMSystem's density argument");
    require_in_closed("stone_wet", stone_wet[i], 0.0, 1.0);
    require_finite("stone_pos", stone_pos[2 * i]);
    require_finite("stone_pos", stone_pos[2 * i + 1]);
    require_finite("stone_force_ext", stone_force_ext[2 * i]);
    require_finite("stone_force_ext", stone_force_ext[2 * i + 1]);
    require_non_negative("stone_drag_coef", stone_drag_coef[i]);
    require_finite("stone_drag_coef", stone_drag_coef[i]);
    require_finite("stone_drag_vel", stone_drag_vel[2 * i]);
    require_finite("stone_drag_vel", stone_drag_vel[2 * i + 1]);
  }
  if (three_d_) check_out_of_plane();
}

// derived masses (eqs. 8-9): M + M', buoyant weight, inertia; fixed or inactive stones get 1/M = 0
void DEMSystem::update_properties() {
  const std::size_t un = static_cast<std::size_t>(n_);
  mass_eff_.resize(un);
  inv_mass_.resize(un);
  inv_inertia_.resize(un);
  weight_.resize(un);
  for (int i = 0; i < n_; ++i) update_stone_properties(i);
}

// effective mass, weight and inverse inertia of stone i from its size, density and wet fraction
void DEMSystem::update_stone_properties(int i) {
  const double m = update_stone_masses(i);
  const DEMParams& p = params_;
  const bool mobile = stone_active[i] && !stone_fixed[i];
  const double inertia = model_->inertia(*this, i, m);
  // 3D stones turn by their principal moments (inertia_3d_), not by the plane's angle
  inv_inertia_[i] = mobile && (p.flags & kDEMRotation) && !three_d_ ? 1.0 / inertia : 0.0;
}

// the parts that follow the wet fraction (eqs. 8-9): M + M', buoyant weight, 1/(M + M'); returns the
// dry mass M [kg] (of the matching 3D stone for a polygon)
double DEMSystem::update_stone_masses(int i) {
  const DEMParams& p = params_;
  const bool added = (p.flags & kDEMAddedMass) && p.water_density() > 0.0;
  const bool buoy = (p.flags & kDEMBuoyancy) && p.water_density() > 0.0;
  const double v = volume(i);
  const double m = stone_density[i] * v;
  const double wv = v * stone_wet[i];
  mass_eff_[i] = m + (added ? p.water_density() * p.added_mass_coefficient * wv : 0.0);
  weight_[i] = m - (buoy ? p.water_density() * wv : 0.0);
  const bool mobile = stone_active[i] && !stone_fixed[i];
  inv_mass_[i] = mobile ? 1.0 / mass_eff_[i] : 0.0;
  return m;
}

void DEMSystem::set_wet_fraction(int i, double w) {
  if (i < 0 || i >= n_) require_in_closed("i", i, 0, n_ - 1);
  require_in_closed("stone_wet", w, 0.0, 1.0);
  change_wet_fraction(i, w);
}

// set_wet_fraction without its checks (w in [0, 1] from the model's wet law)
void DEMSystem::change_wet_fraction(int i, double w) {
  const double w_old = stone_wet[i];
  if (w == w_old) return;
  const DEMParams& p = params_;
  const bool added = (p.flags & kDEMAddedMass) && p.water_density() > 0.0;
  if (added && w > w_old && stone_active[i] && !stone_fixed[i]) {
    // the water taken on starts at rest: (M + M') v kept, the kinetic energy that costs dissipated
    const double v_i = volume(i), m = stone_density[i] * v_i;
    const double c = p.water_density() * p.added_mass_coefficient * v_i;
    const double m_old = m + c * w_old, r = m_old / (m + c * w);
    double* v = &stone_vel[2 * i];
    double v2 = v[0] * v[0] + v[1] * v[1];
    if (three_d_) v2 += stone_vel_y[i] * stone_vel_y[i], stone_vel_y[i] *= r;
    dissipated_ += 0.5 * m_old * (1.0 - r) * v2;
    v[0] *= r;
    v[1] *= r;
  }
  stone_wet[i] = w;
  // masses derived already (within a step): refreshed now; else the next step derives them
  if (mass_eff_.size() == static_cast<std::size_t>(n_)) update_stone_masses(i);
}

// the wet fraction of a stone given a water level follows its height (wet_fraction.h); within a step
// the drag's kick scale follows its new mass, so that the next half kicks integrate the linear drag
// exactly with the added mass the stone now has (set_wet_fraction has kept its momentum)
void DEMSystem::follow_water_level(int i) {
  const double w = wet_law_.fraction((stone_water_level[i] - stone_pos[2 * i + 1]) / wet_radius(i));
  if (w == stone_wet[i]) return;
  change_wet_fraction(i, w);
  if (kick_scale_.size() == static_cast<std::size_t>(n_)) kick_scale_[i] = drag_kick_scale(i, kick_dt_);
}

// reduced mass of two mean mobile stones [kg], for the automatic stiffness
double DEMSystem::reduced_stiffness_mass() const {
  double sum = 0.0;
  int count = 0;
  for (int i = 0; i < n_; ++i) {
    if (!stone_active[i] || stone_fixed[i]) continue;
    sum += mass(i);
    ++count;
  }
  if (count == 0) {
    for (int i = 0; i < n_; ++i) sum += mass(i), ++count;
  }
  return count > 0 ? 0.5 * sum / count : 0.0;
}

void DEMSystem::prepare() {
  check_params();  // C++ callers may have built the system from unchecked parameters
  model_->prepare(*this);  // shapes edited through the views
  check_stones();
  const DEMParams& p = params_;
  if (p.stiffness_normal > 0.0) {
    kn_ = p.stiffness_normal;
  } else {
    const double w = kPi / (p.contact_steps * p.dt);
    kn_ = reduced_stiffness_mass() * w * w;
  }
  kt_ = p.stiffness_ratio * kn_;
  zeta_ = damping_ratio_from_restitution(p.restitution);
  double rmax = 0.0;
  for (int i = 0; i < n_; ++i)
    if (stone_active[i]) rmax = std::max(rmax, stone_radius[i]);
  const double skin = p.neighbour_skin > 0.0 ? p.neighbour_skin : 0.2 * rmax;
  if (skin != skin_) rebuild_ = true;
  skin_ = skin;
  if (neighbours_3d() == build_y_.empty()) rebuild_ = true;  // the list's kind changed (3D cells keep y)
  if (wall_xi_.size() != static_cast<std::size_t>(n_) * p.walls.size())
    wall_xi_.assign(static_cast<std::size_t>(n_) * p.walls.size(), 0.0);
  if (wall_mr_.size() != wall_xi_.size()) wall_mr_.assign(wall_xi_.size(), 0.0);
  if (wall_points_.size() != wall_xi_.size()) wall_points_.assign(wall_xi_.size(), PointSprings{});
  if (!(p.flags & kDEMSleeping)) std::fill(stone_asleep.begin(), stone_asleep.end(), 0);
  update_properties();
  update_rolling_inertia();
  if (three_d_) update_inertia_3d();
  // radii, activity or fixing may have been changed through the views: the list is rebuilt; else only
  // the pairs' reduced masses are refreshed (wet fractions may have changed)
  if (cached_radius_ != stone_radius || cached_active_ != stone_active || cached_fixed_ != stone_fixed) {
    cached_radius_ = stone_radius;
    cached_active_ = stone_active;
    cached_fixed_ = stone_fixed;
    rebuild_ = true;
  }
  // the contacts' dashpots use the masses of the step's start: a wet fraction that follows a water
  // level changes them within the step, and a neighbour build then must not depend on when it happens
  contact_inv_mass_ = inv_mass_;
  if (!rebuild_) {
    for (Pair& c : pairs_) c.sqrt_m = std::sqrt(1.0 / (contact_inv_mass_[c.i] + contact_inv_mass_[c.j]));
    update_pair_rolling();
  }
  prepared_ = true;
}

double DEMSystem::stable_dt() {
  prepare();
  return model_->stable_dt(*this);
}

void DEMSystem::set_held(bool held) {
  if (held && !held_) {
    for (auto* v : {&stone_vel, &stone_omega, &stone_vel_y, &stone_omega_3d}) std::fill(v->begin(), v->end(), 0.0);
  }
  if (!held) forces_valid_ = false;
  held_ = held;
}

void DEMSystem::step(double dt) { advance_checked(dt, 1); }

void DEMSystem::advance(double duration) {
  require_positive("duration", duration);
  const long long nsub = std::max(1LL, static_cast<long long>(std::ceil(duration / params_.dt - 1e-9)));
  advance_checked(duration / static_cast<double>(nsub), nsub);
}

void DEMSystem::advance_checked(double dt, long long nsub) {
  require_positive("dt", dt);
  const double limit = stable_dt();  // also prepares
  if (dt > limit)
    throw std::invalid_argument("dt = " + format_value(dt) +
                                " s exceeds the DEM contact's stable step: allowed range (0, " +
                                format_value(limit) + "] (stable_dt(); lower dt or stiffness_normal)");
  export_state(backup_);
  update_kick_scale(dt);
  try {
    StageLaps laps(profile_);
    for (long long s = 0; s < nsub; ++s) substep(dt, laps);
  } catch (const std::runtime_error&) {
    import_state(backup_);
    throw;
  }
}

// phi(x) = (1 - e^-x) / x of each stone's linear drag over a half kick of the substep dt (1 without drag)
void DEMSystem::update_kick_scale(double dt) {
  kick_dt_ = dt;
  kick_scale_.resize(static_cast<std::size_t>(n_));
  for (int i = 0; i < n_; ++i) kick_scale_[i] = drag_kick_scale(i, dt);
}

// phi(h c / (M + M')) of stone i for a half kick h = dt / 2, with its present mass
double DEMSystem::drag_kick_scale(int i, double dt) const {
  if (!(params_.flags & kDEMExternalForce)) return 1.0;
  const double x = 0.5 * dt * stone_drag_coef[i] * inv_mass_[i];
  if (x > 1e-8) return -std::expm1(-x) / x;
  return x > 0.0 ? 1.0 - 0.5 * x : 1.0;
}

// body, contact and wall forces at the current positions (dt: step of the history springs); each
// stage's time is the lap that ends it
void DEMSystem::evaluate_forces(double dt, bool body, StageLaps& laps) {
  if (body) {
    body_forces(dt);
    laps.lap(kStageBodyForces);
  }
  const ContactTally c = model_->contact_forces(*this, dt);
  elastic_ = c.elastic;
  dissipated_ += c.dissipated;
  ncontact_ = c.count;
  laps.lap(kStageContacts);
  if (!params_.walls.empty() || three_d_) {  // 3D stones have their side walls
    const ContactTally w = model_->wall_forces(*this, dt);
    elastic_ += w.elastic;
    dissipated_ += w.dissipated;
    nwall_contact_ = w.count;
    laps.lap(kStageWalls);
  }
}

// one velocity-Verlet step: kick-drift, forces at the new positions, kick (the time since the last
// lap of the previous substep counts to this one's integration)
void DEMSystem::substep(double dt, StageLaps& laps) {
  if (held_) {  // nothing moves, nothing changes: the time alone
    time_ += dt;
    ++steps_;
    return;
  }
  const unsigned f = params_.flags;
  if (!forces_valid_) {
    // a fresh start: the first kick needs the accelerations of the initial state
    if (rebuild_ || neighbours_stale()) {
      build_neighbours();
      laps.lap(kStageNeighbours);
    }
    evaluate_forces(0.0, true, laps);
    for (int i = 0; i < n_; ++i) {
      stone_acc[2 * i] = stone_force[2 * i] * inv_mass_[i];
      stone_acc[2 * i + 1] = stone_force[2 * i + 1] * inv_mass_[i];
      stone_alpha[i] = stone_torque[i] * inv_inertia_[i];
    }
    if (three_d_) out_of_plane_accelerations();
    forces_valid_ = true;
  }
  // one pass: kick, drift, body forces, escape and neighbour-list checks
  const FirstHalf pass = integrate_first_half(dt);
  laps.lap(kStageIntegrate);
  if (pass.escaped) {
    remove_escaped();
    laps.lap(kStageRemoval);
  }
  if (rebuild_ || pass.stale) {  // 3D: the move across too (integrate_first_half)
    build_neighbours();
    laps.lap(kStageNeighbours);
  }
  evaluate_forces(dt, false, laps);
  time_ += dt;
  ++steps_;
  integrate_second_half(dt);
  laps.lap(kStageChecks);
  if (f & kDEMSleeping) {
    sleep_update(dt);
    laps.lap(kStageSleep);
  }
}

// kick-drift of the awake stones; body forces (gravity minus buoyancy, eq. 9, and the external force)
// of every mobile stone, with the escape and neighbour-list checks folded into the same pass
DEMSystem::FirstHalf DEMSystem::integrate_first_half(double dt) {
  const DEMParams& p = params_;
  const double h = 0.5 * dt;
  const bool grav = p.flags & kDEMGravity;
  const bool ext = p.flags & kDEMExternalForce;
  const bool removal = p.flags & kDEMRemoval;
  const double gx = p.medium.gravity[0], gz = p.medium.gravity[1];
  FirstHalf out;
  out.stale = build_pos_.size() != stone_pos.size();
  double work = 0.0;
  for (int i = 0; i < n_; ++i) {
    double* f = &stone_force[2 * i];
    f[0] = f[1] = 0.0;
    stone_torque[i] = 0.0;
    if (inv_mass_[i] == 0.0) continue;
    double* v = &stone_vel[2 * i];
    double* x = &stone_pos[2 * i];
    if (!stone_asleep[i]) {
      const double* a = &stone_acc[2 * i];
      const double s = kick_scale_[i];
      v[0] += h * a[0] * s;
      v[1] += h * a[1] * s;
      x[0] += dt * v[0];
      x[1] += dt * v[1];
      stone_omega[i] += h * stone_alpha[i];
      stone_angle[i] += dt * stone_omega[i];
      if (!std::isnan(stone_water_level[i])) follow_water_level(i);
    }
    if (removal) {
      out.escaped |= x[0] < p.domain_min[0] || x[0] > p.domain_max[0] || x[1] < p.domain_min[1] ||
                     x[1] > p.domain_max[1];
    }
    if (!out.stale && !neighbours_3d()) out.stale = moved_half_skin(i);  // 3D list: after the move across
    if (grav) {
      f[0] += weight_[i] * gx;
      f[1] += weight_[i] * gz;
    }
    if (ext) {
      const double* fe = &stone_force_ext[2 * i];
      double fx = fe[0], fz = fe[1];
      const double c = stone_drag_coef[i];
      if (c > 0.0) fx += c * (stone_drag_vel[2 * i] - v[0]), fz += c * (stone_drag_vel[2 * i + 1] - v[1]);
      f[0] += fx;
      f[1] += fz;
      work += fx * v[0] + fz * v[1];
    }
  }
  work_external_ += work * dt;
  // 3D: the move across the flume, and with the 3D list the skin rule on the whole move
  if (three_d_ && out_of_plane_first_half(dt, !out.stale && neighbours_3d())) out.stale = true;
  return out;
}

// second kick from the new accelerations; a non-finite value aborts the call
void DEMSystem::integrate_second_half(double dt) {
  const double h = 0.5 * dt;
  const bool ext = params_.flags & kDEMExternalForce;
  for (int i = 0; i < n_; ++i) {
    if (inv_mass_[i] == 0.0) continue;
    double* a = &stone_acc[2 * i];
    a[0] = stone_force[2 * i] * inv_mass_[i];
    a[1] = stone_force[2 * i + 1] * inv_mass_[i];
    stone_alpha[i] = stone_torque[i] * inv_inertia_[i];
    if (stone_asleep[i]) continue;
    double* v = &stone_vel[2 * i];
    const double s = kick_scale_[i];
    const double vx = v[0], vz = v[1];
    v[0] += h * a[0] * s;
    v[1] += h * a[1] * s;
    stone_omega[i] += h * stone_alpha[i];
    // the linear drag of the force evaluation is that of the half-step velocity: brought to the new one
    const double c = stone_drag_coef[i];
    if (c > 0.0 && ext) {
      const double dvx = v[0] - vx, dvz = v[1] - vz;
      stone_force[2 * i] -= c * dvx, stone_force[2 * i + 1] -= c * dvz;
      a[0] -= c * inv_mass_[i] * dvx, a[1] -= c * inv_mass_[i] * dvz;
    }
    if (!std::isfinite(v[0] + v[1] + stone_omega[i] + stone_pos[2 * i] + stone_pos[2 * i + 1]))
      fail("integrate", i, time_, "non-finite position or velocity");
  }
  if (three_d_) out_of_plane_second_half(dt);
}

void DEMSystem::remove_escaped() {
  const DEMParams& p = params_;
  for (int i = 0; i < n_; ++i) {
    if (inv_mass_[i] == 0.0) continue;
    const double x = stone_pos[2 * i], z = stone_pos[2 * i + 1];
    if (x >= p.domain_min[0] && x <= p.domain_max[0] && z >= p.domain_min[1] && z <= p.domain_max[1]) continue;
    // kept in the arrays (indices stay stable), no longer simulated
    stone_active[i] = 0;
    inv_mass_[i] = 0.0;
    inv_inertia_[i] = 0.0;
    stone_vel[2 * i] = stone_vel[2 * i + 1] = 0.0;
    stone_omega[i] = 0.0;
    stone_acc[2 * i] = stone_acc[2 * i + 1] = 0.0;
    stone_alpha[i] = 0.0;
    stone_force[2 * i] = stone_force[2 * i + 1] = 0.0;
    if (three_d_) out_of_plane_removed(i);
    for (std::size_t w = 0; w < p.walls.size(); ++w) {
      wall_xi_[i * p.walls.size() + w] = 0.0;
      wall_mr_[i * p.walls.size() + w] = 0.0;
      wall_points_[i * p.walls.size() + w] = PointSprings{};
    }
    ++removed_;
    rebuild_ = true;
  }
}

void DEMSystem::body_forces(double dt) {
  const DEMParams& p = params_;
  const bool grav = p.flags & kDEMGravity;
  const bool ext = p.flags & kDEMExternalForce;
  for (int i = 0; i < n_; ++i) {
    double* f = &stone_force[2 * i];
    f[0] = f[1] = 0.0;
    stone_torque[i] = 0.0;
    if (inv_mass_[i] == 0.0) continue;
    if (grav) {
      f[0] += weight_[i] * p.medium.gravity[0];
      f[1] += weight_[i] * p.medium.gravity[1];
    }
    if (ext) {
      const double* fe = &stone_force_ext[2 * i];
      const double* v = &stone_vel[2 * i];
      const double c = stone_drag_coef[i];
      const double fx = fe[0] + c * (stone_drag_vel[2 * i] - v[0]), fz = fe[1] + c * (stone_drag_vel[2 * i + 1] - v[1]);
      f[0] += fx;
      f[1] += fz;
      work_external_ += (fx * v[0] + fz * v[1]) * dt;
    }
  }
  if (three_d_) out_of_plane_body_forces(dt);
}

// Box2D-like sleeping: slow for sleep_time -> frozen; woken when its net force would accelerate it
void DEMSystem::sleep_update(double dt) {
  const DEMParams& p = params_;
  const double v2 = p.sleep_velocity * p.sleep_velocity;
  const double a2 = p.wake_acceleration * p.wake_acceleration;
  for (int i = 0; i < n_; ++i) {
    if (inv_mass_[i] == 0.0) continue;
    const double* a = &stone_acc[2 * i];
    const double r = stone_radius[i];
    if (stone_asleep[i]) {
      const double ar = stone_alpha[i] * r;
      double acc2 = a[0] * a[0] + a[1] * a[1] + ar * ar;
      if (three_d_) acc2 += stone_acc_y[i] * stone_acc_y[i];
      if (acc2 > a2) {
        stone_asleep[i] = 0;
        stone_sleep_timer[i] = 0.0;
      }
      continue;
    }
    double* v = &stone_vel[2 * i];
    const double wr = stone_omega[i] * r;
    double speed2 = v[0] * v[0] + v[1] * v[1], spin2 = wr * wr;
    if (three_d_) speed2 += stone_vel_y[i] * stone_vel_y[i], spin2 += out_of_plane_speed2(i);
    if (speed2 < v2 && spin2 < v2) {
      stone_sleep_timer[i] += dt;
      if (stone_sleep_timer[i] >= p.sleep_time) {
        dissipated_ += 0.5 * mass_eff_[i] * (v[0] * v[0] + v[1] * v[1]) +
                       (inv_inertia_[i] > 0.0 ? 0.5 * stone_omega[i] * stone_omega[i] / inv_inertia_[i] : 0.0);
        if (three_d_) out_of_plane_sleep(i);
        stone_asleep[i] = 1;
        v[0] = v[1] = 0.0;
        stone_omega[i] = 0.0;
      }
    } else {
      stone_sleep_timer[i] = 0.0;
    }
  }
}

double DEMSystem::max_speed() const {
  double v2 = 0.0;
  for (int i = 0; i < n_; ++i) {
    if (!stone_active[i] || stone_fixed[i]) continue;
    const double vx = stone_vel[2 * i], vz = stone_vel[2 * i + 1];
    const double vy = three_d_ ? stone_vel_y[i] : 0.0;
    double w2 = stone_omega[i] * stone_omega[i];
    if (three_d_) {
      const double* w = &stone_omega_3d[3 * i];
      w2 = w[0] * w[0] + w[1] * w[1] + w[2] * w[2];
    }
    v2 = std::max(v2, std::max(vx * vx + vy * vy + vz * vz, w2 * stone_radius[i] * stone_radius[i]));
  }
  return std::sqrt(v2);
}

DEMEnergy DEMSystem::energy() const {
  const DEMParams& p = params_;
  DEMEnergy e;
  const bool added = (p.flags & kDEMAddedMass) && p.water_density() > 0.0;
  const bool buoy = (p.flags & kDEMBuoyancy) && p.water_density() > 0.0;
  const bool grav = p.flags & kDEMGravity;
  for (int i = 0; i < n_; ++i) {
    if (!stone_active[i] || stone_fixed[i]) continue;
    const double v = volume(i);
    const double m = stone_density[i] * v;
    const double wv = v * stone_wet[i];
    const double me = m + (added ? p.water_density() * p.added_mass_coefficient * wv : 0.0);
    const double mw = m - (buoy ? p.water_density() * wv : 0.0);
    const double inertia = model_->inertia(*this, i, m);
    const double* u = &stone_vel[2 * i];
    e.kinetic += 0.5 * me * (u[0] * u[0] + u[1] * u[1]) + 0.5 * inertia * stone_omega[i] * stone_omega[i];
    if (three_d_) e.kinetic += out_of_plane_kinetic(i, me);
    if (grav) e.potential -= mw * (p.medium.gravity[0] * stone_pos[2 * i] + p.medium.gravity[1] * stone_pos[2 * i + 1]);
  }
  e.elastic = elastic_;
  e.dissipated = dissipated_;
  e.work_external = work_external_;
  return e;
}

}  // namespace vofdem
