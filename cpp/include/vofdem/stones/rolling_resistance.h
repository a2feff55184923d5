// Rolling resistance of a contact: the elastic-plastic spring-dashpot model, type C of Ai, Chen,
// Rotter & Ooi (2011), Powder Technology 206, 269-282 (LIGGGHTS `rolling_friction epsd`, PFC `rrlinear`),
// for discs in the x-z plane (one rotation angle per stone, counter-clockwise).
//
//   M_r       = M_r^k + M_r^d                          rolling moment on stone i [N m]; -M_r on stone j
//   M_r^k     <- M_r^k - k_r dtheta_r,                 dtheta_r = (omega_i - omega_j) dt   (history per contact)
//   |M_r^k|  <= M_r^m = mu_r R* f_n                    full mobilisation: the spring slips at the cap
//   M_r^d     = -C_r (omega_i - omega_j)   below the cap,   0 at full mobilisation (type C, f = 0)
//   k_r       = k_t R*^2                               rolling stiffness [N m/rad] (Iwashita & Oda 1998)
//   C_r       = eta_r 2 sqrt(I_r k_r),   I_r = [1/(I_i + m_i r_i^2) + 1/(I_j + m_j r_j^2)]^-1
//   R*        = r_i r_j / (r_i + r_j)                  (a wall or fixed stone: 1/(I_j + m_j r_j^2) = 0;
//                                                       a wall: R* = r_i, omega_j = 0)
//
// f_n is the compressive part of the contact's normal force, max(f_n, 0), as for the Coulomb cap.
// mu_r [-] is the rolling friction coefficient: a disc on an incline of angle theta stays at rest while
// tan(theta) <= mu_r (and the Coulomb friction holds it), and rolls above it with, at full mobilisation,
//   a = g (sin(theta) - mu_r cos(theta)) / (1 + I / (M r^2)).
//
// Stiffness: k_r = k_t R*^2 (Iwashita & Oda 1998; LIGGGHTS `epsd2`) rather than Ai et al.'s
// 2.25 k_n mu_r^2 R*^2 (LIGGGHTS `epsd`), because (a) it does not depend on mu_r, so calibrating mu_r
// moves only the plateau and never the stable time step, and (b) the 2.25 is a fit for 3D spheres with
// no 2D counterpart. Its angular frequency sqrt(k_r / I_r) stays below that of the tangential spring
// with spin; DEMSystem::stable_dt() adds the spin stiffness of a wall contact, k_t r^2 / I = k_t / (f M)
// (f = I / (M r^2)), counted for two contacts, to the tangential-rotational mode all the same.
//
// References: Ai, J., Chen, J.-F., Rotter, J. M. & Ooi, J. Y. (2011), Assessment of rolling resistance
// models in discrete element simulations, Powder Technology 206, 269-282. Iwashita, K. & Oda, M. (1998),
// Rolling resistance at contacts in simulation of shear band development by DEM, J. Eng. Mech. 124(3),
// 285-292.
#pragma once

#include <cmath>

namespace vofdem {

// effective rolling radius R* [m] of two discs of radii r_i, r_j [m]
inline double rolling_radius(double ri, double rj) { return ri * rj / (ri + rj); }

// rolling stiffness k_r = k_t R*^2 [N m/rad]: tangential stiffness k_t [N/m], R* [m]
inline double rolling_stiffness(double kt, double r_eff) { return kt * r_eff * r_eff; }

// damping coefficient C_r = eta_r 2 sqrt(I_r k_r) [N m s/rad]: ratio eta_r [-], I_r [kg m^2], k_r [N m/rad]
inline double rolling_damping_coefficient(double eta, double inertia, double kr) {
  return 2.0 * eta * std::sqrt(inertia * kr);
}

// result of one rolling-resistance evaluation
struct RollingMoment {
  double moment = 0.0;         // M_r on stone i [N m] (counter-clockwise positive); -M_r on stone j
  double power_damp = 0.0;     // power dissipated by the damper [W] (>= 0)
  double energy_slip = 0.0;    // spring energy lost at full mobilisation in this step [J] (>= 0)
  double energy_spring = 0.0;  // energy stored in the rolling spring after the update [J]
  bool mobilised = false;      // the spring sits at the cap mu_r R* f_n
};

// updates the rolling spring m_spring [N m] over dt [s] and returns the contact's rolling moment.
// w_rel = omega_i - omega_j [rad/s]; kr [N m/rad]; cr [N m s/rad]; m_cap = mu_r R* max(f_n, 0) [N m].
inline RollingMoment rolling_resistance(double w_rel, double& m_spring, double dt, double kr, double cr,
                                        double m_cap) {
  RollingMoment r;
  m_spring -= kr * w_rel * dt;
  if (std::fabs(m_spring) > m_cap) {
    // full mobilisation: the spring slips to the cap, the damper is off (type C)
    const double old = m_spring;
    m_spring = std::copysign(m_cap, m_spring);
    r.energy_slip = kr > 0.0 ? 0.5 * (old * old - m_spring * m_spring) / kr : 0.0;
    r.moment = m_spring;
    r.mobilised = true;
  } else {
    r.moment = m_spring - cr * w_rel;
    r.power_damp = cr * w_rel * w_rel;
  }
  r.energy_spring = kr > 0.0 ? 0.5 * m_spring * m_spring / kr : 0.0;
  return r;
}

}  // namespace vofdem
