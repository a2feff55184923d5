// Rolling resistance in DEMSystem: the type-C elastic-plastic spring-dashpot of rolling_resistance.h
// (Ai, Chen, Rotter & Ooi 2011) at every stone-stone and stone-wall contact, under the effect flag
// kDEMRollingResistance with the coefficients of DEMParams (rolling_friction_stone, rolling_friction_wall,
// rolling_damping). A contact kind whose mu_r is 0 is not entered, so mu_r = 0 or the flag off costs
// nothing and leaves every result bit for bit as without the model.
//
// The spring moment is a history per stone pair (Pair::mr) and per (stone, wall) (wall_mr_), carried
// over the neighbour-list rebuilds, zeroed when a contact opens and part of export_state().
#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>
#include <utility>

#include "vofdem/common/check.h"
#include "vofdem/stones/dem_system.h"
#include "vofdem/stones/rolling_resistance.h"

namespace vofdem {

bool DEMSystem::rolling_stones() const {
  return (params_.flags & kDEMRollingResistance) && params_.rolling_friction_stone > 0.0;
}

bool DEMSystem::rolling_walls() const {
  return (params_.flags & kDEMRollingResistance) && params_.rolling_friction_wall > 0.0;
}

// omega^2 [1/s^2] the rolling springs add to a stone's spin: k_r / I <= k_t r^2 / (f M r^2) per contact
// (the largest R* is a wall's, R* = r), counted for two contacts as the tangential mode is
double DEMSystem::rolling_spin_stiffness(double m_min) const {
  if (!(params_.flags & kDEMRotation) || !(rolling_stones() || rolling_walls())) return 0.0;
  return 2.0 * kt_ / (params_.inertia_factor * m_min);
}

// 1 / (I + (M + M') r^2): a stone's inertia about its contact point, for the damper's I_r; the damper's
// constant factors, so that the contact loops take no square root
void DEMSystem::update_rolling_inertia() {
  inv_roll_inertia_.assign(static_cast<std::size_t>(n_), 0.0);
  wall_roll_c_.assign(static_cast<std::size_t>(n_), 0.0);
  roll_eta_sqrt_kt_ = (params_.flags & kDEMDamping) ? params_.rolling_damping * std::sqrt(kt_) : 0.0;
  if (!(rolling_stones() || rolling_walls())) return;
  for (int i = 0; i < n_; ++i) {
    if (inv_inertia_[i] == 0.0) continue;  // fixed, inactive, or rotation off
    const double r = stone_radius[i];
    inv_roll_inertia_[i] = 1.0 / (1.0 / inv_inertia_[i] + mass_eff_[i] * r * r);
    wall_roll_c_[i] = 2.0 * r / std::sqrt(inv_roll_inertia_[i]);
  }
}

// C_r = 2 eta_r sqrt(I_r k_r) = eta_r sqrt(k_t) 2 R* sqrt(I_r): the pair's part, 2 R* sqrt(I_r)
void DEMSystem::update_pair_rolling() {
  if (!rolling_stones()) return;
  for (Pair& c : pairs_) {
    const double inv = inv_roll_inertia_[c.i] + inv_roll_inertia_[c.j];
    c.roll_r = rolling_radius(stone_radius[c.i], stone_radius[c.j]);
    c.roll_c = inv > 0.0 ? 2.0 * c.roll_r / std::sqrt(inv) : 0.0;
  }
}

DEMSystem::RollingEnergy DEMSystem::rolling_contact(Pair& c, double fn, double dt) {
  const int i = c.i, j = c.j;
  const double reff = c.roll_r;
  const double kr = rolling_stiffness(kt_, reff);
  const double cr = roll_eta_sqrt_kt_ * c.roll_c;
  const double cap = params_.rolling_friction_stone * reff * std::max(fn, 0.0);
  const RollingMoment m = rolling_resistance(stone_omega[i] - stone_omega[j], c.mr, dt, kr, cr, cap);
  stone_torque[i] += m.moment;
  stone_torque[j] -= m.moment;
  return {m.energy_spring, m.power_damp * dt + m.energy_slip};
}

DEMSystem::RollingEnergy DEMSystem::rolling_wall(int i, double& mr, double fn, double dt) {
  const double r = stone_radius[i];
  const double kr = rolling_stiffness(kt_, r);
  const double cr = roll_eta_sqrt_kt_ * wall_roll_c_[i];
  const double cap = params_.rolling_friction_wall * r * std::max(fn, 0.0);
  const RollingMoment m = rolling_resistance(stone_omega[i], mr, dt, kr, cr, cap);
  stone_torque[i] += m.moment;
  return {m.energy_spring, m.power_damp * dt + m.energy_slip};
}

}  // namespace vofdem
