// The out-of-plane state of 3D stones in DEMSystem (dem_system.h): y across the flume, its velocity and
// force, and the rotation (a unit quaternion and the world angular velocity). The plane's arrays carry x
// and z as for every model; these passes run after the plane's, each over the same stones, so that a 3D
// stone is kicked, drifted, loaded, put to sleep and accounted as a whole:
//
//   translation   v_y += (h a_y) phi,  y += dt v_y   (the plane's half kicks with the linear drag's phi;
//                 the drag c (0 - v_y): the width-averaged flow has no velocity across the flume)
//   rotation      L_w += h tau_w;  free rotation over dt (rotation_step's splitting, quaternion.h);
//                 L_w += h tau_w' with the torque of the new positions. Spheres (equal moments I):
//                 omega += h tau_w / I;  one exact turn by omega dt (spherical_rotation);  omega += h tau_w' / I
//
// A stone that does not turn (fixed, inactive, or with kDEMRotation off) keeps its orientation and a zero
// spin; its principal moments are stored as +inf, which the contact models read as a body that cannot turn.
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

#include "vofdem/common/check.h"
#include "vofdem/stones/dem_system.h"
#include "vofdem/stones/quaternion.h"

namespace vofdem {

namespace {
constexpr double kInf = std::numeric_limits<double>::infinity();

Quat quat_at(const std::vector<double>& q, int i) { return Quat(q[4 * i], q[4 * i + 1], q[4 * i + 2], q[4 * i + 3]); }
void store_quat(std::vector<double>& q, int i, const Quat& v) {
  q[4 * i] = v.w(), q[4 * i + 1] = v.x(), q[4 * i + 2] = v.y(), q[4 * i + 3] = v.z();
}
Vec3 vec_at(const std::vector<double>& v, int i) { return Vec3(v[3 * i], v[3 * i + 1], v[3 * i + 2]); }
void store_vec(std::vector<double>& v, int i, const Vec3& x) {
  v[3 * i] = x[0], v[3 * i + 1] = x[1], v[3 * i + 2] = x[2];
}
}  // namespace

// the arrays for the model's dimensions: empty for the plane's models; else n stones at mid-width, at rest,
// unturned
void DEMSystem::size_out_of_plane() {
  std::vector<double>* arrays[] = {&stone_y,    &stone_vel_y,    &stone_force_y,  &stone_acc_y,
                                   &stone_quat, &stone_omega_3d, &stone_torque_3d};
  if (!three_d_) {
    for (auto* a : arrays) a->clear();
    inertia_3d_.clear();
    return;
  }
  const std::size_t n = static_cast<std::size_t>(n_);
  stone_y.assign(n, 0.5 * params_.width);
  for (auto* a : {&stone_vel_y, &stone_force_y, &stone_acc_y}) a->assign(n, 0.0);
  for (auto* a : {&stone_omega_3d, &stone_torque_3d}) a->assign(3 * n, 0.0);
  stone_quat.assign(4 * n, 0.0);
  for (std::size_t i = 0; i < n; ++i) stone_quat[4 * i] = 1.0;
  inertia_3d_.assign(3 * n, kInf);
}

void DEMSystem::check_out_of_plane() const {
  const std::size_t n = static_cast<std::size_t>(n_);
  require_size("stone_y", stone_y, n);
  require_size("stone_quat", stone_quat, 4 * n);
  require_size("stone_omega_3d", stone_omega_3d, 3 * n);
  const double width = params_.width;
  for (int i = 0; i < n_; ++i) {
    if (!stone_active[i]) continue;
    if (2.0 * stone_radius[i] > width)
      throw std::invalid_argument("width = " + format_value(width) + " m is narrower than stone " + std::to_string(i) +
                                  " (diameter " + format_value(2.0 * stone_radius[i]) +
                                  " m): 3D stones need width >= the largest diameter");
    require_in_closed("stone_y", stone_y[i], 0.0, width);
    require_finite("stone_vel_y", stone_vel_y[i]);
    const Quat q = quat_at(stone_quat, i);
    if (!(std::fabs(q.norm() - 1.0) <= 1e-6))
      throw std::invalid_argument("stone_quat of stone " + std::to_string(i) + " has length " + format_value(q.norm()) +
                                  ": allowed range [1 - 1e-6, 1 + 1e-6] (a unit quaternion w, x, y, z)");
    for (int k = 0; k < 3; ++k) require_finite("stone_omega_3d", stone_omega_3d[3 * i + k]);
  }
}

// principal moments of the stones that turn; +inf for the others
void DEMSystem::update_inertia_3d() {
  inertia_3d_.assign(3 * static_cast<std::size_t>(n_), kInf);
  if (!(params_.flags & kDEMRotation)) return;
  for (int i = 0; i < n_; ++i) {
    if (inv_mass_[i] == 0.0) continue;
    const auto inertia = model_->principal_inertia(*this, i, mass(i));
    for (int k = 0; k < 3; ++k) inertia_3d_[3 * i + k] = inertia[k];
  }
}

// forces and torques set to the body forces across the flume (only the linear drag's; gravity and the
// flow's forces lie in the plane) before the contacts add theirs
void DEMSystem::out_of_plane_body_forces(double dt) {
  const bool ext = params_.flags & kDEMExternalForce;
  double work = 0.0;
  for (int i = 0; i < n_; ++i) work += out_of_plane_body_force(i, ext);
  work_external_ += work * dt;
}

// stone i's force and torque across the flume set to its body force (ext: the drag is on); returns the
// drag's power [W] (0 for a fixed stone, whose force stays 0)
double DEMSystem::out_of_plane_body_force(int i, bool ext) {
  stone_force_y[i] = 0.0;
  stone_torque_3d[3 * i] = stone_torque_3d[3 * i + 1] = stone_torque_3d[3 * i + 2] = 0.0;
  if (inv_mass_[i] == 0.0 || !ext) return 0.0;
  const double fy = -stone_drag_coef[i] * stone_vel_y[i];
  stone_force_y[i] = fy;
  return fy * stone_vel_y[i];
}

// one pass over the stones: each is kicked, drifted and turned with the torque of the last evaluation,
// then its force and torque across the flume are set to its body force (out_of_plane_body_force)
bool DEMSystem::out_of_plane_first_half(double dt, bool stale_3d) {
  const double h = 0.5 * dt;
  const bool spherical = model_->spherical_inertia();
  const bool ext = params_.flags & kDEMExternalForce;
  bool stale = stale_3d && build_y_.size() != stone_y.size();
  double work = 0.0;
  for (int i = 0; i < n_; ++i) {
    if (inv_mass_[i] != 0.0 && !stone_asleep[i]) out_of_plane_turn(i, h, dt, spherical);
    work += out_of_plane_body_force(i, ext);
    if (stale_3d && !stale && inv_mass_[i] != 0.0) stale = moved_half_skin(i);
  }
  work_external_ += work * dt;
  return stale;
}

// stone i's kick and drift across the flume and its turn (h = dt / 2)
void DEMSystem::out_of_plane_turn(int i, double h, double dt, bool spherical) {
  stone_vel_y[i] += h * stone_acc_y[i] * kick_scale_[i];
  stone_y[i] += dt * stone_vel_y[i];
  if (std::isinf(inertia_3d_[3 * i])) return;
  Quat q = quat_at(stone_quat, i);
  if (spherical) {
    // equal moments: omega = L / I, constant over the free rotation, so one exact turn about it
    const Vec3 omega = vec_at(stone_omega_3d, i) + (h / inertia_3d_[3 * i]) * vec_at(stone_torque_3d, i);
    spherical_rotation(q, omega, dt);
    store_quat(stone_quat, i, q);
    store_vec(stone_omega_3d, i, omega);
    return;
  }
  // in the body frame, L_b = I omega_b + h tau_b through the free turn (three rotations of a vector, not five)
  const Vec3 inertia = vec_at(inertia_3d_, i);
  Vec3 l = inertia.cwiseProduct(world_to_body(q, vec_at(stone_omega_3d, i))) +
           h * world_to_body(q, vec_at(stone_torque_3d, i));
  free_rotation_body(q, l, inertia, dt);
  q.normalize();
  store_quat(stone_quat, i, q);
  store_vec(stone_omega_3d, i, body_to_world(q, l.cwiseQuotient(inertia)));
}

void DEMSystem::out_of_plane_second_half(double dt) {
  const double h = 0.5 * dt;
  const bool spherical = model_->spherical_inertia();
  const bool ext = params_.flags & kDEMExternalForce;
  for (int i = 0; i < n_; ++i) {
    if (inv_mass_[i] == 0.0) continue;
    stone_acc_y[i] = stone_force_y[i] * inv_mass_[i];
    if (stone_asleep[i]) continue;
    const double vy = stone_vel_y[i];
    stone_vel_y[i] += h * stone_acc_y[i] * kick_scale_[i];
    const double c = stone_drag_coef[i];
    if (c > 0.0 && ext) {
      // the drag of the half-step velocity brought to the new one, as in the plane
      const double dvy = stone_vel_y[i] - vy;
      stone_force_y[i] -= c * dvy;
      stone_acc_y[i] -= c * inv_mass_[i] * dvy;
    }
    if (spherical && !std::isinf(inertia_3d_[3 * i])) {
      const double h_inertia = h / inertia_3d_[3 * i];  // once, not per component
      for (int k = 0; k < 3; ++k) stone_omega_3d[3 * i + k] += h_inertia * stone_torque_3d[3 * i + k];
    } else if (!std::isinf(inertia_3d_[3 * i])) {
      // omega_w += R (h tau_b / I): the kick in the body frame (two rotations of a vector, not four)
      const Quat q = quat_at(stone_quat, i);
      const Vec3 dw = (h * world_to_body(q, vec_at(stone_torque_3d, i))).cwiseQuotient(vec_at(inertia_3d_, i));
      store_vec(stone_omega_3d, i, vec_at(stone_omega_3d, i) + body_to_world(q, dw));
    }
    if (!std::isfinite(stone_y[i] + stone_vel_y[i] + stone_omega_3d[3 * i] + stone_omega_3d[3 * i + 1] +
                       stone_omega_3d[3 * i + 2]))
      throw std::runtime_error("DEM stage 'integrate': non-finite position or velocity across the flume or 3D spin "
                               "of stone " + std::to_string(i) + " at t = " + format_value(time_) +
                               " s (state restored to the start of the call)");
  }
}

void DEMSystem::out_of_plane_accelerations() {
  for (int i = 0; i < n_; ++i) stone_acc_y[i] = stone_force_y[i] * inv_mass_[i];
}

void DEMSystem::out_of_plane_removed(int i) {
  stone_vel_y[i] = stone_acc_y[i] = stone_force_y[i] = 0.0;
  for (int k = 0; k < 3; ++k) inertia_3d_[3 * i + k] = kInf;
  for (int k = 0; k < 3; ++k) stone_omega_3d[3 * i + k] = stone_torque_3d[3 * i + k] = 0.0;
}

// (|omega| r)^2 [m^2/s^2]: the spin's part of the sleeping test
double DEMSystem::out_of_plane_speed2(int i) const {
  const double r = stone_radius[i];
  return vec_at(stone_omega_3d, i).squaredNorm() * r * r;
}

// falls asleep: its motion across the flume and its spin stop, their energy counted as dissipated
void DEMSystem::out_of_plane_sleep(int i) {
  dissipated_ += out_of_plane_kinetic(i, mass_eff_[i]);
  stone_vel_y[i] = 0.0;
  for (int k = 0; k < 3; ++k) stone_omega_3d[3 * i + k] = 0.0;
}

// 1/2 (M + M') v_y^2 + 1/2 omega . I omega [J]
double DEMSystem::out_of_plane_kinetic(int i, double mass_eff) const {
  double e = 0.5 * mass_eff * stone_vel_y[i] * stone_vel_y[i];
  if (i < static_cast<int>(inertia_3d_.size() / 3) && !std::isinf(inertia_3d_[3 * i]))
    e += rotational_energy(quat_at(stone_quat, i), vec_at(inertia_3d_, i), vec_at(stone_omega_3d, i));
  return e;
}

}  // namespace vofdem
