// What the 3D models built on sphere contacts share (sphere_model.cpp, clump_model.cpp): the contact law's
// constants from the system's parameters and effect flags, the loads of one contact added into the
// system's arrays with the energy tally, and the 3-vectors and plane histories of their checkpoint arrays.
#pragma once

#include <vector>

#include <Eigen/Core>

#include "vofdem/stones/dem_system.h"
#include "vofdem/stones/sphere_contact.h"
#include "vofdem/stones/stone_model.h"

namespace vofdem::sphere_loads {

// the law's constants with the effect flags of the system (damping off: e = 1; friction off: mu = k_t = 0)
inline SphereContactLaw law(const DEMSystem& s) {
  const DEMParams& p = s.params();
  SphereContactLaw law;
  law.stiffness_normal = s.stiffness_normal();
  const bool friction = p.flags & kDEMFriction;
  law.stiffness_ratio = friction ? p.stiffness_ratio : 0.0;
  law.friction = friction ? p.friction_stone : 0.0;
  law.restitution = (p.flags & kDEMDamping) ? p.restitution : 1.0;
  law.tangential_damping_factor = p.tangential_damping_factor;
  law.rolling_friction = (p.flags & kDEMRollingResistance) ? p.rolling_friction_stone : 0.0;
  law.rolling_damping = p.rolling_damping;
  return law;
}

// the loads of a contact into the system's arrays: i gets them, j (if >= 0) their opposite
// (Loads: SphereContactLoads or a type with its force_i, torque_i, torque_j, energy_spring, power_damp and
// energy_slip)
template <class Loads>
inline void apply(DEMSystem& s, int i, int j, const Loads& f, ContactTally& t, double dt) {
  s.stone_force[2 * i] += f.force_i[0];
  s.stone_force_y[i] += f.force_i[1];
  s.stone_force[2 * i + 1] += f.force_i[2];
  for (int k = 0; k < 3; ++k) s.stone_torque_3d[3 * i + k] += f.torque_i[k];
  if (j >= 0) {
    s.stone_force[2 * j] -= f.force_i[0];
    s.stone_force_y[j] -= f.force_i[1];
    s.stone_force[2 * j + 1] -= f.force_i[2];
    for (int k = 0; k < 3; ++k) s.stone_torque_3d[3 * j + k] += f.torque_j[k];
  }
  ++t.count;
  t.elastic += f.energy_spring;
  t.dissipated += f.power_damp * dt + f.energy_slip;
}

inline void push3(std::vector<double>& out, const Eigen::Vector3d& v) { out.insert(out.end(), {v[0], v[1], v[2]}); }
inline Eigen::Vector3d at3(const std::vector<double>& v, std::size_t k) {
  return {v[3 * k], v[3 * k + 1], v[3 * k + 2]};
}

// a history with nothing stored (a pair's is then left out of the checkpoint)
inline bool zero(const SphereContactHistory& h) { return h.spring.isZero(0.0) && h.rolling.isZero(0.0); }

// the first `size` plane histories into a checkpoint's arrays, 3 values each (those not made yet: zero)
inline void push_histories(const std::vector<SphereContactHistory>& h, std::size_t size, std::vector<double>& spring,
                           std::vector<double>& rolling) {
  for (std::size_t k = 0; k < size; ++k) {
    const SphereContactHistory e = k < h.size() ? h[k] : SphereContactHistory();
    push3(spring, e.spring);
    push3(rolling, e.rolling);
  }
}

// the plane histories of a checkpoint's arrays (push_histories' inverse)
inline std::vector<SphereContactHistory> histories(const std::vector<double>& spring, const std::vector<double>& rolling) {
  std::vector<SphereContactHistory> h(spring.size() / 3);
  for (std::size_t k = 0; k < h.size(); ++k) h[k] = {at3(spring, k), at3(rolling, k)};
  return h;
}

}  // namespace vofdem::sphere_loads
