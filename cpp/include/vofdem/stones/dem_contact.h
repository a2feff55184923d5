// Linear spring-dashpot contact of two discs (or a disc and a wall), Maeno & Tomita (2008) sec. 2.2,
// after Gotoh & Sakai (1997) and Cundall & Strack (1979).
//
//   normal      f_n = k_n delta + c_n d(delta)/dt               (delta: overlap [m], > 0 in contact)
//   tangential  f_s = -k_t xi - c_t v_s,  |f_s| <= mu max(f_n, 0) (xi: tangential spring [m], history)
//   damping     c_n = 2 zeta sqrt(m* k_n),  c_t = tangential_damping_factor c_n,  m* = m_i m_j / (m_i + m_j)
//   restitution e = exp(-zeta pi / sqrt(1 - zeta^2)),  zeta = -ln e / sqrt(pi^2 + ln^2 e)  (e = 0: zeta = 1)
//   duration    t_c = pi / (omega_0 sqrt(1 - zeta^2)),  omega_0 = sqrt(k_n / m*)
//
// These enter eqs. (8)-(10) as {-f_n cos(alpha) + f_s sin(alpha)}, {-f_n sin(alpha) + f_s cos(alpha)} and
// (d/2) f_s. The normal force is not clipped at zero (the dashpot may pull briefly at the end of a
// contact): that is the model whose restitution the formulas above give exactly; friction is capped by
// the compressive part only.
//
// Automatic stiffness (Gotoh & Sakai 1997 choose the spring from the particle mass and the time step):
// k_n is set so that two mean stones stay in contact for `contact_steps` DEM steps when undamped,
//   k_n = m*_mean (pi / (contact_steps dt))^2,
// and the damping defaults to critical (e = 0, zeta = 1) as in their sheet-flow DEM.
#pragma once

#include <cmath>

#include "vofdem/common/numbers.h"

namespace vofdem {

// damping ratio zeta [-] that gives the restitution coefficient e [-] (e = 0: critical, zeta = 1)
inline double damping_ratio_from_restitution(double e) {
  if (e <= 0.0) return 1.0;
  if (e >= 1.0) return 0.0;
  const double l = std::log(e);
  return -l / std::sqrt(kPi * kPi + l * l);
}

// restitution coefficient e [-] of a linear spring-dashpot with damping ratio zeta [-] (0 for zeta >= 1)
inline double restitution_from_damping_ratio(double zeta) {
  if (zeta >= 1.0) return 0.0;
  return std::exp(-zeta * kPi / std::sqrt(1.0 - zeta * zeta));
}

// contact duration t_c [s] of a linear spring-dashpot: stiffness k [N/m], reduced mass m* [kg], zeta [-]
inline double contact_duration(double k, double m_reduced, double zeta) {
  if (zeta >= 1.0) return INFINITY;
  return kPi / (std::sqrt(k / m_reduced) * std::sqrt(1.0 - zeta * zeta));
}

// result of one contact evaluation, in the contact frame (n from i to j, t = n rotated +90 degrees)
struct ContactForce {
  double fn = 0.0;          // normal force [N], > 0 repulsive (pushes i along -n)
  double ft = 0.0;          // tangential force on i along t [N]
  double power_damp = 0.0;  // power dissipated by the dashpots [W] (>= 0)
  double energy_slip = 0.0; // elastic energy lost by Coulomb capping of the tangential spring [J]
  double energy_spring = 0.0;  // energy stored in the springs after the update [J]
};

// the energy a one-point contact's springs hold as it opens and they are dropped [J]: dissipated
// (tangential spring xi [m] of stiffness kt [N/m], rolling moment mr [N m] of stiffness kr [N m/rad])
inline double opened_energy(double xi, double kt, double mr, double kr) {
  return 0.5 * kt * xi * xi + (kr > 0.0 ? 0.5 * mr * mr / kr : 0.0);
}

// evaluates the contact and updates the tangential spring xi [m] over dt [s].
// delta: overlap [m]; vn: d(delta)/dt [m/s]; vt: sliding speed of i relative to j along t [m/s];
// kn, kt [N/m]; cn, ct [N s/m]; mu [-]; friction: Coulomb cap on (else the spring is unbounded).
inline ContactForce linear_contact(double delta, double vn, double vt, double& xi, double dt, double kn,
                                   double kt, double cn, double ct, double mu, bool friction) {
  ContactForce f;
  const double fn_spring = kn * delta;
  const double fn_damp = cn * vn;
  f.fn = fn_spring + fn_damp;
  xi += vt * dt;
  double ft = -kt * xi - ct * vt;
  if (friction) {
    const double cap = mu * (f.fn > 0.0 ? f.fn : 0.0);
    if (std::fabs(ft) > cap) {
      // sliding: the spring is shortened so that spring and dashpot carry exactly the Coulomb force
      const double before = xi - vt * dt;
      ft = std::copysign(cap, ft);
      xi = kt > 0.0 ? -(ft + ct * vt) / kt : 0.0;
      // of the work -f_t v_t dt, what neither the dashpot nor the spring (from `before` to xi) takes, to
      // the second order in dt (sphere_kernels.h slip_energy: the spring's cut 1/2 k_t (xi_trial^2 - xi^2)
      // booked the dashpot's excess twice under strong damping)
      const double back = xi - vt * dt;
      f.energy_slip = 0.5 * kt * (before * before - back * back);
    }
  }
  f.ft = ft;
  f.power_damp = fn_damp * vn + ct * vt * vt;
  f.energy_spring = 0.5 * kn * delta * delta + 0.5 * kt * xi * xi;
  return f;
}

}  // namespace vofdem
