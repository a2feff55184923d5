// The kernels of sphere_contact.h's law (its equations and sources are there), inline so that the contact
// and wall loops of sphere_model.cpp compile them in (no call, no ~25-double result written through memory
// for what the loop does not read); sphere_contact.cpp's public functions call the same code, so the bits
// agree.
#pragma once

#include <algorithm>
#include <cmath>

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "vofdem/stones/rolling_resistance.h"
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

// whether sqrt(x) > c, as the rounded root compares, without the root when x lies clearly below c^2 (a
// contact below its cap, the common case): there sqrt(x) < c (1 - 4e-13), which no rounding lifts to c
// (c > 1e-150: c^2 keeps its relative precision, no subnormal)
VOFDEM_SPHERE_INLINE bool root_exceeds(double x, double c) {
  if (c > 1e-150 && x < c * c * (1.0 - 1e-12)) return false;
  return std::sqrt(x) > c;
}

// what the law needs beyond the law's constants, the pair's constants and the histories (sphere_contact.h)
using Geometry = SphereContactGeometry;

// a model's loop keeps these per listed pair while the masses, radii and inertia stay the same (the same
// expressions as computed at each contact: the same bits): nine divisions and two square roots a contact
using PairConstants = SpherePairConstants;

// from m* [kg], R* [m] and I_r [kg m^2] (sphere_contact.h)
VOFDEM_SPHERE_INLINE PairConstants constants(double m_reduced, double r_eff, double roll_inertia, double mu_r,
                                             const SphereContactLaw& law, double zeta) {
  PairConstants c;
  c.r_eff = r_eff;
  const double kn = law.stiffness_normal, kt = law.stiffness_ratio * kn;
  c.cn = 2.0 * zeta * std::sqrt(m_reduced * kn);
  c.ct = law.tangential_damping_factor * c.cn;
  if (mu_r > 0.0) {
    c.kr = kt * r_eff * r_eff;
    c.cr = 2.0 * law.rolling_damping * std::sqrt(roll_inertia * c.kr);
  }
  return c;
}

// a sphere pair's constants (the bodies' mass and inertia: +inf for a fixed body)
VOFDEM_SPHERE_INLINE PairConstants pair_constants(const SphereOfBody& i, const SphereOfBody& j,
                                                  const SphereContactLaw& law, double zeta) {
  const double m_reduced = 1.0 / (1.0 / i.mass + 1.0 / j.mass);  // a fixed body's mass is +inf
  double r_eff = 0.0, roll_inertia = 0.0;
  if (law.rolling_friction > 0.0) {
    // only the rolling resistance reads them: four divisions saved per contact without it
    r_eff = i.radius * j.radius / (i.radius + j.radius);
    const double inv_i = 1.0 / (i.inertia + i.mass * i.radius * i.radius);
    const double inv_j = 1.0 / (j.inertia + j.mass * j.radius * j.radius);
    roll_inertia = 1.0 / (inv_i + inv_j);
  }
  return constants(m_reduced, r_eff, roll_inertia, law.rolling_friction, law, zeta);
}

// a contact that opens drops its springs' histories; the energy they held (k_t = stiffness_ratio k_n, the
// rolling k_r = k_t R*^2 as constants() sets it; R* [m] of the pair, the sphere's radius on a plane) is
// dissipated, returned [J]. (At a cap the tangential spring is set so that spring and dashpot carry the cap
// together, LAMMPS's rule: under strong damping it can hold more than the slip took from it, which the
// account would lose as the contact opens.)
VOFDEM_SPHERE_INLINE double release(SphereContactHistory& h, const SphereContactLaw& law, double r_eff) {
  const double kt = law.stiffness_ratio * law.stiffness_normal, kr = rolling_stiffness(kt, r_eff);
  const double e = 0.5 * kt * h.spring.squaredNorm() + (kr > 0.0 ? 0.5 * h.rolling.squaredNorm() / kr : 0.0);
  h = SphereContactHistory();
  return e;
}

// the energy a sliding step dissipates beyond the dashpot's c_t |v_t|^2 dt [J]: of the work -f_t . v_t dt
// the force does, what the spring (from xi_0 to xi, |xi_0|^2 = before2) does not store,
// 1/2 k_t (|xi_0|^2 - |xi - v_t dt|^2) up to the second order in dt (f_t = -k_t xi - c_t v_t; zero as the
// cut vanishes). Not the spring's cut 1/2 k_t (|xi_0 + v_t dt|^2 - |xi|^2): under strong damping the cap
// sets the spring against the slip, and that booked the dashpot's excess as dissipated twice
VOFDEM_SPHERE_INLINE double slip_energy(double kt, double before2, const Vec3& spring, const Vec3& step) {
  return 0.5 * kt * (before2 - (spring - step).squaredNorm());
}

// the tangential spring's update and the Coulomb cap; returns f_t on i
VOFDEM_SPHERE_INLINE Vec3 tangential(const Geometry& g, const Vec3& vt, double fn, double kt, double ct, double dt,
                                     SphereContactHistory& h, SphereContactLoads& out) {
  onto_tangent_plane(h.spring, g.n);
  h.spring += vt * dt;
  Vec3 ft = -kt * h.spring - ct * vt;
  const double cap = g.mu * std::max(fn, 0.0);
  if (root_exceeds(ft.squaredNorm(), cap)) {
    // sliding: the spring is shortened so that spring and dashpot carry exactly the Coulomb force
    const double f = ft.norm();
    const double before2 = (h.spring - vt * dt).squaredNorm();
    ft *= cap / f;
    h.spring = kt > 0.0 ? Vec3(-(ft + ct * vt) / kt) : Vec3(Vec3::Zero());
    out.energy_slip += slip_energy(kt, before2, h.spring, vt * dt);
    out.sliding = true;
  }
  return ft;
}

// the type-C rolling spring-dashpot (rolling_resistance.h in 3D); returns M_r on i
VOFDEM_SPHERE_INLINE Vec3 rolling(const Geometry& g, const PairConstants& c, double fn, double dt,
                                  SphereContactHistory& h, SphereContactLoads& out) {
  const Vec3 wr = g.w_rel - g.w_rel.dot(g.n) * g.n;  // twisting is not resisted
  const double kr = c.kr, cr = c.cr;
  onto_tangent_plane(h.rolling, g.n);
  h.rolling -= kr * dt * wr;
  const double cap = g.mu_r * c.r_eff * std::max(fn, 0.0);
  Vec3 moment;
  if (root_exceeds(h.rolling.squaredNorm(), cap)) {
    // full mobilisation: the spring slips to the cap, the damper is off
    const double m = h.rolling.norm();
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
VOFDEM_SPHERE_INLINE SphereContactLoads apply_law(const Geometry& g, const PairConstants& c, const Vec3& arm_i,
                                                  const Vec3& arm_j, SphereContactHistory& h,
                                                  const SphereContactLaw& law, double dt) {
  SphereContactLoads out;
  out.touching = true;
  out.normal = g.n;
  out.point = g.point;
  out.overlap = g.delta;
  const double kn = law.stiffness_normal, kt = law.stiffness_ratio * kn;
  const double cn = c.cn, ct = c.ct;
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
    const Vec3 m = rolling(g, c, out.fn, dt, h, out);
    out.torque_i += m;
    out.torque_j -= m;
  }
  return out;
}

// sphere_sphere_contact_unchecked's body (sphere_contact.h); the pair's constants from `constants()`,
// called only for spheres that touch (a loop hands its kept ones)
// a sphere pair's geometry and the arms from the bodies' centres of mass to the contact point; false when
// the spheres do not touch
VOFDEM_SPHERE_INLINE bool pair_geometry(const SphereOfBody& i, const SphereOfBody& j, const SphereContactLaw& law,
                                        Geometry& g, Vec3& arm_i, Vec3& arm_j) {
  const Vec3 d = j.centre - i.centre;
  const double dist = d.norm();
  const double delta = i.radius + j.radius - dist;
  if (!(delta > 0.0)) return false;
  g.n = dist > 0.0 ? Vec3(d / dist) : Vec3(Vec3::UnitZ());  // coincident centres: an arbitrary fixed normal
  g.delta = delta;
  g.point = i.centre + (i.radius - 0.5 * delta) * g.n;
  arm_i = g.point - i.com, arm_j = g.point - j.com;
  g.v_rel = (i.vel + i.omega.cross(arm_i)) - (j.vel + j.omega.cross(arm_j));
  g.w_rel = i.omega - j.omega;
  g.mu = law.friction;
  g.mu_r = law.rolling_friction;
  return true;
}

template <class Constants>
VOFDEM_SPHERE_INLINE SphereContactLoads sphere_pair_with(const SphereOfBody& i, const SphereOfBody& j,
                                                         SphereContactHistory& h, const SphereContactLaw& law,
                                                         double dt, Constants&& constants) {
  Geometry g;
  Vec3 arm_i, arm_j;
  if (!pair_geometry(i, j, law, g, arm_i, arm_j)) {
    SphereContactLoads out;  // the contact opened: its histories start again from zero
    out.energy_slip = release(h, law, i.radius * j.radius / (i.radius + j.radius));
    return out;
  }
  return apply_law(g, constants(), arm_i, arm_j, h, law, dt);
}

VOFDEM_SPHERE_INLINE SphereContactLoads sphere_pair(const SphereOfBody& i, const SphereOfBody& j,
                                                    SphereContactHistory& h, const SphereContactLaw& law, double zeta,
                                                    double dt) {
  return sphere_pair_with(i, j, h, law, dt, [&] { return pair_constants(i, j, law, zeta); });
}

// sphere_plane_contact_unchecked's body (sphere_contact.h)
VOFDEM_SPHERE_INLINE SphereContactLoads sphere_plane(const SphereOfBody& i, const ContactPlane& plane,
                                                     SphereContactHistory& h, const SphereContactLaw& law,
                                                     double zeta, double dt) {
  const double delta = i.radius - (i.centre - plane.point).dot(plane.normal);
  if (!(delta > 0.0)) {
    SphereContactLoads out;
    out.energy_slip = release(h, law, i.radius);
    return out;
  }
  Geometry g;
  g.n = -plane.normal;
  g.delta = delta;
  g.point = i.centre + (i.radius - 0.5 * delta) * g.n;
  const Vec3 arm_i = g.point - i.com;
  g.v_rel = i.vel + i.omega.cross(arm_i);
  g.w_rel = i.omega;
  g.mu = plane.friction;
  g.mu_r = plane.rolling_friction;
  const PairConstants c =
      constants(i.mass, i.radius, i.inertia + i.mass * i.radius * i.radius, g.mu_r, law, zeta);
  return apply_law(g, c, arm_i, Vec3::Zero(), h, law, dt);
}

}  // namespace vofdem::sphere_kernels
