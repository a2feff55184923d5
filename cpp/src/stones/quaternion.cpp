// Rotation step of a rigid body with principal moments of inertia (quaternion.h): the free rotor split
// into exact rotations about the principal axes (Dullweber, Leimkuhler & McLachlan 1997), and the exact
// rotation of a body with equal moments (a sphere).
#include "vofdem/stones/quaternion.h"

#include <cmath>
#include <stdexcept>
#include <string>

namespace vofdem {

namespace {

void check_inertia(const Vec3& inertia) {
  for (int k = 0; k < 3; ++k) {
    if (!(std::isfinite(inertia[k]) && inertia[k] > 0.0)) {
      throw std::invalid_argument("inertia: each principal moment must be finite and > 0 [kg m^2], got " +
                                  std::to_string(inertia[k]));
    }
  }
}

// the flow of T_k = L_bk^2 / (2 I_k) over h: the body turns by phi about its axis k, L_b by -phi
void rotate_about_axis(int k, Quat& q, Vec3& l_body, const Vec3& inertia, double h) {
  const double phi = l_body[k] / inertia[k] * h;
  const double ch = std::cos(0.5 * phi), sh = std::sin(0.5 * phi);  // one angle's sine and cosine, the
  const double c = ch * ch - sh * sh, s = 2.0 * sh * ch;              // double angle's from them
  const int a = (k + 1) % 3, b = (k + 2) % 3;
  const double la = l_body[a], lb = l_body[b];
  l_body[a] = c * la + s * lb;
  l_body[b] = -s * la + c * lb;
  Vec3 axis = Vec3::Zero();
  axis[k] = sh;
  q = q * Quat(ch, axis.x(), axis.y(), axis.z());
}

}  // namespace

Vec3 angular_momentum(const Quat& q, const Vec3& inertia, const Vec3& omega_world) {
  return body_to_world(q, inertia.cwiseProduct(world_to_body(q, omega_world)));
}

Vec3 angular_velocity(const Quat& q, const Vec3& inertia, const Vec3& l_world) {
  return body_to_world(q, world_to_body(q, l_world).cwiseQuotient(inertia));
}

double rotational_energy(const Quat& q, const Vec3& inertia, const Vec3& omega_world) {
  const Vec3 w = world_to_body(q, omega_world);
  return 0.5 * w.dot(inertia.cwiseProduct(w));
}

void free_rotation(Quat& q, const Vec3& l_world, const Vec3& inertia, double dt) {
  check_inertia(inertia);
  if (!(std::isfinite(dt) && dt >= 0.0)) {
    throw std::invalid_argument("dt: the time step must be finite and >= 0 [s], got " + std::to_string(dt));
  }
  Vec3 l_body = world_to_body(q, l_world);
  free_rotation_body(q, l_body, inertia, dt);
  q.normalize();
}

void free_rotation_body(Quat& q, Vec3& l_body, const Vec3& inertia, double dt) {
  // symmetric sequence 1 2 3 2 1 (second order, time-reversible)
  rotate_about_axis(0, q, l_body, inertia, 0.5 * dt);
  rotate_about_axis(1, q, l_body, inertia, 0.5 * dt);
  rotate_about_axis(2, q, l_body, inertia, dt);
  rotate_about_axis(1, q, l_body, inertia, 0.5 * dt);
  rotate_about_axis(0, q, l_body, inertia, 0.5 * dt);
}

void spherical_rotation(Quat& q, const Vec3& omega_world, double dt) {
  if (!(std::isfinite(dt) && dt >= 0.0)) {
    throw std::invalid_argument("dt: the time step must be finite and >= 0 [s], got " + std::to_string(dt));
  }
  const double rate = omega_world.norm();
  if (rate == 0.0) return;  // no axis to turn about: q stays as it is
  // the world-frame increment dq q (dq/dt = (0, omega_w) q / 2 with omega_w constant)
  const double half = 0.5 * rate * dt;
  const Vec3 v = (std::sin(half) / rate) * omega_world;
  q = Quat(std::cos(half), v.x(), v.y(), v.z()) * q;
  q.normalize();
}

void rotation_step(Quat& q, Vec3& omega_world, const Vec3& inertia, const Vec3& torque_world, double dt) {
  check_inertia(inertia);
  Vec3 l_world = angular_momentum(q, inertia, omega_world);
  l_world += 0.5 * dt * torque_world;
  free_rotation(q, l_world, inertia, dt);
  l_world += 0.5 * dt * torque_world;
  omega_world = angular_velocity(q, inertia, l_world);
}

}  // namespace vofdem
