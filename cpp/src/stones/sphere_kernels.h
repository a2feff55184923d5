// The kernels of sphere_contact.h's law (its equations and sources are there), inline so that the contact
// and wall loops of sphere_model.cpp compile them in (no call, no ~25-double result written through memory
// for what the loop does not read); sphere_contact.cpp's public functions call the same code, so the bits
// agree.
#pragma once

#include <algorithm>
#include <cmath>

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "vofdem/stones/sphere_contact.h"

// forced: the compilers' size limits would otherwise keep the law out of line in the loops
#if defined(__GNUC__)
#define VOFDEM_SPHERE_INLINE inline __attribute__((always_inline))
#else
#define VOFDEM_SPHERE_INLINE inline
#endif

namespace vofdem::sphere_kernels {

using Vec3 = Eigen::Vector3d;

// turns a history vector onto the tangent plane of n, keeping its length (LAMMPS pair granular)
VOFDEM_SPHERE_INLINE void onto_tangent_plane(Vec3& v, const Vec3& n) {
  const double length = v.norm();
  if (length == 0.0) return;
  const Vec3 p = v - v.dot(n) * n;
  const double pl = p.norm();
  v = pl > 0.0 ? Vec3(p * (length / pl)) : Vec3(Vec3::Zero());
}

// what the law needs beyond the law's constants and the histories
struct Geometry {
  Vec3 n;              // from i to j
  double delta;        // overlap [m]
  Vec3 point;          // contact point [m]
  Vec3 v_rel;          // velocity of i relative to j at the point [m/s]
  Vec3 w_rel;          // omega_i - omega_j [rad/s]
  double m_reduced;    // m* [kg]
  double r_eff = 0.0;  // R* [m] (sphere pairs: set only with the rolling resistance on)
  double roll_inertia = 0.0;  // I_r [kg m^2] (likewise)
  double mu, mu_r;     // Coulomb and rolling friction [-]
};

// the tangential spring's update and the Coulomb cap; returns f_t on i
VOFDEM_SPHERE_INLINE Vec3 tangential(const Geometry& g, const Vec3& vt, double fn, double kt, double ct, double dt,
                                     SphereContactHistory& h, SphereContactLoads& out) {
  onto_tangent_plane(h.spring, g.n);
  h.spring += vt * dt;
  Vec3 ft = -kt * h.spring - ct * vt;
  const double cap = g.mu * std::max(fn, 0.0);
  const double f = ft.norm();
  if (f > cap) {
    // sliding: the spring is shortened so that it carries exactly the Coulomb force
    const double old2 = h.spring.squaredNorm();
    ft *= cap / f;
    h.spring = kt > 0.0 ? Vec3(-(ft + ct * vt) / kt) : Vec3(Vec3::Zero());
    out.energy_slip += 0.5 * kt * (old2 - h.spring.squaredNorm());
    out.sliding = true;
  }
  return ft;
}

// the type-C rolling spring-dashpot (rolling_resistance.h in 3D); returns M_r on i
VOFDEM_SPHERE_INLINE Vec3 rolling(const Geometry& g, double fn, double kt, double eta, double dt,
                                  SphereContactHistory& h, SphereContactLoads& out) {
  const Vec3 wr = g.w_rel - g.w_rel.dot(g.n) * g.n;  // twisting is not resisted
  const double kr = kt * g.r_eff * g.r_eff;
  const double cr = 2.0 * eta * std::sqrt(g.roll_inertia * kr);
  onto_tangent_plane(h.rolling, g.n);
  h.rolling -= kr * dt * wr;
  const double cap = g.mu_r * g.r_eff * std::max(fn, 0.0);
  const double m = h.rolling.norm();
  Vec3 moment;
  if (m > cap) {
    // full mobilisation: the spring slips to the cap, the damper is off
    h.rolling *= cap / m;
    out.energy_slip += kr > 0.0 ? 0.5 * (m * m - cap * cap) / kr : 0.0;
    moment = h.rolling;
  } else {
    moment = h.rolling - cr * wr;
    out.power_damp += cr * wr.squaredNorm();
  }
  out.energy_spring += kr > 0.0 ? 0.5 * h.rolling.squaredNorm() / kr : 0.0;
  return moment;
}

// the law at one contact: forces on i, torques on i and j about their centres of mass
VOFDEM_SPHERE_INLINE SphereContactLoads apply_law(const Geometry& g, const Vec3& arm_i, const Vec3& arm_j,
                                                  SphereContactHistory& h, const SphereContactLaw& law,
                                                  double zeta, double dt) {
  SphereContactLoads out;
  out.touching = true;
  out.normal = g.n;
  out.point = g.point;
  out.overlap = g.delta;
  const double kn = law.stiffness_normal, kt = law.stiffness_ratio * kn;
  const double cn = 2.0 * zeta * std::sqrt(g.m_reduced * kn);
  const double ct = law.tangential_damping_factor * cn;
  const double vn = g.v_rel.dot(g.n);
  const Vec3 vt = g.v_rel - vn * g.n;
  out.fn = kn * g.delta + cn * vn;
  const Vec3 ft = tangential(g, vt, out.fn, kt, ct, dt, h, out);
  out.force_i = -out.fn * g.n + ft;
  out.torque_i = arm_i.cross(out.force_i);
  out.torque_j = arm_j.cross(-out.force_i);
  out.power_damp += cn * vn * vn + ct * vt.squaredNorm();
  out.energy_spring += 0.5 * kn * g.delta * g.delta + 0.5 * kt * h.spring.squaredNorm();
  if (g.mu_r > 0.0) {
    const Vec3 m = rolling(g, out.fn, kt, law.rolling_damping, dt, h, out);
    out.torque_i += m;
    out.torque_j -= m;
  }
  return out;
}

// sphere_sphere_contact_unchecked's body (sphere_contact.h)
VOFDEM_SPHERE_INLINE SphereContactLoads sphere_pair(const SphereOfBody& i, const SphereOfBody& j,
                                                    SphereContactHistory& h, const SphereContactLaw& law, double zeta,
                                                    double dt) {
  const Vec3 d = j.centre - i.centre;
  const double dist = d.norm();
  const double delta = i.radius + j.radius - dist;
  if (!(delta > 0.0)) {
    h = SphereContactHistory();  // the contact opened: its histories start again from zero
    return SphereContactLoads();
  }
  Geometry g;
  g.n = dist > 0.0 ? Vec3(d / dist) : Vec3(Vec3::UnitZ());  // coincident centres: an arbitrary fixed normal
  g.delta = delta;
  g.point = i.centre + (i.radius - 0.5 * delta) * g.n;
  const Vec3 arm_i = g.point - i.com, arm_j = g.point - j.com;
  g.v_rel = (i.vel + i.omega.cross(arm_i)) - (j.vel + j.omega.cross(arm_j));
  g.w_rel = i.omega - j.omega;
  g.m_reduced = 1.0 / (1.0 / i.mass + 1.0 / j.mass);  // a fixed body's mass is +inf
  g.mu = law.friction;
  g.mu_r = law.rolling_friction;
  if (g.mu_r > 0.0) {
    // only the rolling resistance reads them: four divisions saved per contact without it
    g.r_eff = i.radius * j.radius / (i.radius + j.radius);
    const double inv_i = 1.0 / (i.inertia + i.mass * i.radius * i.radius);
    const double inv_j = 1.0 / (j.inertia + j.mass * j.radius * j.radius);
    g.roll_inertia = 1.0 / (inv_i + inv_j);
  }
  return apply_law(g, arm_i, arm_j, h, law, zeta, dt);
}

// sphere_plane_contact_unchecked's body (sphere_contact.h)
VOFDEM_SPHERE_INLINE SphereContactLoads sphere_plane(const SphereOfBody& i, const ContactPlane& plane,
                                                     SphereContactHistory& h, const SphereContactLaw& law,
                                                     double zeta, double dt) {
  const double delta = i.radius - (i.centre - plane.point).dot(plane.normal);
  if (!(delta > 0.0)) {
    h = SphereContactHistory();
    return SphereContactLoads();
  }
  Geometry g;
  g.n = -plane.normal;
  g.delta = delta;
  g.point = i.centre + (i.radius - 0.5 * delta) * g.n;
  const Vec3 arm_i = g.point - i.com;
  g.v_rel = i.vel + i.omega.cross(arm_i);
  g.w_rel = i.omega;
  g.m_reduced = i.mass;
  g.r_eff = i.radius;
  g.roll_inertia = i.inertia + i.mass * i.radius * i.radius;
  g.mu = plane.friction;
  g.mu_r = plane.rolling_friction;
  return apply_law(g, arm_i, Vec3::Zero(), h, law, zeta, dt);
}

}  // namespace vofdem::sphere_kernels
