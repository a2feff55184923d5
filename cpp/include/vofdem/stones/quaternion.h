// Orientation of a 3D rigid stone: a unit quaternion q (Eigen::Quaterniond) that takes body-frame vectors
// to the world, and one rotation step of a body whose inertia is diagonal in its body frame (principal
// axes) under a world torque.
//
//   world <- body   v_w = q v_b q*          (R(q) v_b)
//   body  <- world  v_b = q* v_w q          (R(q)^T v_w)
//   Euler           dL_w/dt = tau_w,   L_b = R^T L_w = I omega_b,   dq/dt = q (0, omega_b) / 2
//                   so that  I domega_b/dt + omega_b x (I omega_b) = R^T tau_w  (Euler's equations)
//
// The step is the symplectic splitting of Dullweber, Leimkuhler & McLachlan (1997) for the free rotor,
// T = sum_k L_bk^2 / (2 I_k): each term's flow is an exact rotation of the body about its principal axis k
// by phi_k = (L_bk / I_k) h, which turns L_b by -phi_k about the same axis and keeps L_w. The symmetric
// sequence
//   kick  L_w += tau_w dt/2;   R_1(dt/2) R_2(dt/2) R_3(dt) R_2(dt/2) R_1(dt/2);   kick  L_w += tau_w dt/2
// is second order and time-reversible; it keeps L_w of a torque-free body to round-off (every sub-step is
// a rotation that leaves L_w alone) and its kinetic energy within a bounded O(dt^2) oscillation, without
// drift. It is the NO_SQUISH scheme of Miller et al. (2002) written with the body angular momentum instead
// of the quaternion's conjugate momentum (LAMMPS fix rigid/nve, MathExtra::no_squish_rotate). A constant
// torque along a principal axis keeps L_b on that axis, so omega = tau t / I is kept to round-off.
//
// A body whose three principal moments are equal (a sphere) is the exception: its free rotation keeps
// omega_w = L_w / I constant, so the orientation turns exactly by the angle |omega| dt about omega in one
// rotation, q(t + dt) = (cos(|omega| dt / 2), sin(|omega| dt / 2) omega / |omega|) q(t), one sin/cos
// pair (spherical_rotation below) instead of the splitting's five.
//
// References: Dullweber, A., Leimkuhler, B. & McLachlan, R. (1997), Symplectic splitting methods for
// rigid body molecular dynamics, J. Chem. Phys. 107, 5840-5851. Miller, T. F., Eleftheriou, M.,
// Pattnaik, P., Ndirango, A., Newns, D. & Martyna, G. J. (2002), Symplectic quaternion scheme for
// biophysical molecular dynamics, J. Chem. Phys. 116, 8649-8659.
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>

namespace vofdem {

using Quat = Eigen::Quaterniond;
using Vec3 = Eigen::Vector3d;
using Mat3 = Eigen::Matrix3d;

// R(q) v: a body-frame vector in the world frame (q a unit quaternion)
inline Vec3 body_to_world(const Quat& q, const Vec3& v) { return q * v; }

// R(q)^T v: a world vector in the body frame
inline Vec3 world_to_body(const Quat& q, const Vec3& v) { return q.conjugate() * v; }

// world angular momentum L_w [kg m^2/s] of a body: principal moments inertia [kg m^2], world omega [rad/s]
Vec3 angular_momentum(const Quat& q, const Vec3& inertia, const Vec3& omega_world);

// world angular velocity [rad/s] from the world angular momentum L_w [kg m^2/s]
Vec3 angular_velocity(const Quat& q, const Vec3& inertia, const Vec3& l_world);

// rotational kinetic energy [J]: sum_k I_k omega_bk^2 / 2
double rotational_energy(const Quat& q, const Vec3& inertia, const Vec3& omega_world);

// torque-free rotation over dt [s]: turns q and keeps L_w [kg m^2/s] (the splitting above, no kicks).
// inertia: principal moments [kg m^2], each > 0; dt >= 0.
void free_rotation(Quat& q, const Vec3& l_world, const Vec3& inertia, double dt);

// the same in the body frame, for a caller that holds the body angular momentum l_body [kg m^2/s] (turned
// with the body) and has checked inertia and dt; q is not renormalised
void free_rotation_body(Quat& q, Vec3& l_body, const Vec3& inertia, double dt);

// torque-free rotation over dt [s] of a body with equal principal moments: turns q exactly by |omega| dt
// about the world angular velocity omega [rad/s] (kept; q unchanged when omega is 0) and renormalises it.
// Throws std::invalid_argument if dt is not finite and >= 0.
void spherical_rotation(Quat& q, const Vec3& omega_world, double dt);

// one rotation step over dt [s] under a world torque [N m] held constant over the step (kick, free
// rotation, kick): updates the orientation q (renormalised) and the world angular velocity omega [rad/s].
// Throws std::invalid_argument if an inertia is not finite and > 0 or dt is not finite and >= 0.
void rotation_step(Quat& q, Vec3& omega_world, const Vec3& inertia, const Vec3& torque_world, double dt);

}  // namespace vofdem
