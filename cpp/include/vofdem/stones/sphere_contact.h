// Linear spring-dashpot contact of 3D spheres (sphere-sphere and sphere-plane), the 3D form of the law
// in dem_contact.h (Maeno & Tomita 2008 sec. 2.2, after Cundall & Strack 1979), with the tangential
// spring kept as a 3-vector as in LAMMPS pair gran/hooke/history and pair granular, and the type-C
// rolling resistance of rolling_resistance.h (Ai, Chen, Rotter & Ooi 2011) in 3D.
//
//   n        unit normal from sphere i to sphere j (to a plane: minus the plane's normal)
//   delta    = r_i + r_j - |x_j - x_i|  (plane: r_i - (x_i - p) . n_p),  > 0 in contact      [m]
//   c        contact point, the middle of the overlap: x_i + (r_i - delta/2) n                [m]
//   v_rel    = (v_i + w_i x (c - X_i)) - (v_j + w_j x (c - X_j))  (X: the body's centre of mass)
//   normal   f_n = k_n delta + c_n v_n,  v_n = v_rel . n = d(delta)/dt                        [N]
//   tangent  xi <- |xi| (xi - (xi . n) n) / |xi - (xi . n) n|   (onto the new tangent plane, length kept)
//            xi <- xi + v_t dt,  v_t = v_rel - v_n n;   f_t = -k_t xi - c_t v_t
//            |f_t| <= mu max(f_n, 0): at the cap f_t is scaled to it and xi = -(f_t + c_t v_t) / k_t
//   damping  c_n = 2 zeta sqrt(m* k_n), c_t = tangential_damping_factor c_n, m* = m_i m_j / (m_i + m_j)
//            (a plane: m* = m_i), zeta from the restitution e (dem_contact.h)
//   loads    F_i = -f_n n + f_t,  F_j = -F_i;  T_i = (c - X_i) x F_i + M_r,  T_j = (c - X_j) x F_j - M_r
//   rolling  w_r = (w_i - w_j) minus its part along n (twisting is not resisted);
//            M_r^k <- (M_r^k onto the tangent plane, length kept) - k_r w_r dt,
//            |M_r^k| <= mu_r R* max(f_n, 0) (full mobilisation: scaled to the cap, damper off),
//            M_r = M_r^k - C_r w_r below the cap;  k_r = k_t R*^2,  C_r = eta_r 2 sqrt(I_r k_r),
//            R* = r_i r_j / (r_i + r_j) (plane: r_i),  I_r = [1/(I_i + m_i r_i^2) + 1/(I_j + m_j r_j^2)]^-1
//
// The normal force is not clipped at zero (the dashpot may pull at the end of a contact), as in 2D: that
// is the model whose restitution the formula of dem_contact.h gives exactly. Newton's third law holds for
// the forces and for the moments about the contact point, to round-off.
//
// References: Cundall, P. A. & Strack, O. D. L. (1979), Geotechnique 29(1), 47-65. Ai, J., Chen, J.-F.,
// Rotter, J. M. & Ooi, J. Y. (2011), Powder Technology 206, 269-282. LAMMPS pair gran/hooke/history and
// pair granular (tangential history rotated onto the tangent plane and rescaled to its length).
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>

namespace vofdem {

// the contact law's constants (the 2D law's parametrisation, DEMParams)
struct SphereContactLaw {
  double stiffness_normal = 1.0e5;          // k_n [N/m], > 0
  double stiffness_ratio = 2.0 / 7.0;       // k_t / k_n [-], >= 0
  double restitution = 0.0;                 // normal restitution e [-] in [0, 1]; 0 = critical damping
  double tangential_damping_factor = 0.5;   // c_t / c_n [-], >= 0
  double friction = 0.577;                  // Coulomb coefficient mu [-], >= 0
  double rolling_friction = 0.0;            // mu_r [-], >= 0; 0 = no rolling resistance
  double rolling_damping = 0.0;             // eta_r [-] in [0, 1]: C_r over its critical value

  // throws std::invalid_argument naming the first parameter out of its range
  void check() const;
};

// a sphere of a rigid body (a lone sphere: centre = com); world frame, SI
struct SphereOfBody {
  Eigen::Vector3d centre = Eigen::Vector3d::Zero();  // sphere centre [m]
  double radius = 0.0;                               // [m], > 0
  Eigen::Vector3d com = Eigen::Vector3d::Zero();     // the body's centre of mass [m]
  Eigen::Vector3d vel = Eigen::Vector3d::Zero();     // velocity of the centre of mass [m/s]
  Eigen::Vector3d omega = Eigen::Vector3d::Zero();   // angular velocity [rad/s]
  double mass = 0.0;                                 // the body's mass [kg], > 0 (damping's m*); +inf: fixed
  double inertia = 0.0;                              // moment of inertia about the centre of mass for the
                                                     // rolling damper's I_r [kg m^2] (sphere: 2/5 m r^2);
                                                     // +inf: a body that does not turn
};

// a fixed plane: the bed or a side wall, with its own friction coefficients
struct ContactPlane {
  Eigen::Vector3d point = Eigen::Vector3d::Zero();   // a point of the plane [m]
  Eigen::Vector3d normal = Eigen::Vector3d::UnitZ(); // unit normal towards the stones [-]
  double friction = 0.176;                           // Coulomb coefficient [-] (glass side wall: 0.176)
  double rolling_friction = 0.0;                     // mu_r [-]
};

// the histories one contact carries from step to step (zero when the contact opens)
struct SphereContactHistory {
  Eigen::Vector3d spring = Eigen::Vector3d::Zero();   // tangential spring xi [m]
  Eigen::Vector3d rolling = Eigen::Vector3d::Zero();  // rolling spring moment M_r^k on i [N m]
};

// the parts of the law fixed by the two bodies' masses, radii and inertia and the law's constants
// (c_n, c_t, R*, k_r, C_r above), which a model's loop keeps per pair between changes of those
struct SpherePairConstants {
  double cn = 0.0, ct = 0.0;  // normal and tangential dashpots [kg/s]
  double r_eff = 0.0;         // R* [m] (with the rolling resistance on)
  double kr = 0.0, cr = 0.0;  // rolling spring k_r [N m] and dashpot C_r [N m s] (likewise)
};

// what the law needs beyond its constants, the pair's constants and the histories: the geometry and
// kinematics of one touching contact, which a model's loop may keep between its passes
struct SphereContactGeometry {
  Eigen::Vector3d n = Eigen::Vector3d::UnitZ();       // normal from i to j [-]
  double delta = 0.0;                                 // overlap [m]
  Eigen::Vector3d point = Eigen::Vector3d::Zero();    // contact point [m]
  Eigen::Vector3d v_rel = Eigen::Vector3d::Zero();    // velocity of i relative to j at the point [m/s]
  Eigen::Vector3d w_rel = Eigen::Vector3d::Zero();    // omega_i - omega_j [rad/s]
  double mu = 0.0, mu_r = 0.0;                        // Coulomb and rolling friction [-]
};

// the loads of one contact (all zero when the spheres do not touch)
struct SphereContactLoads {
  bool touching = false;
  Eigen::Vector3d normal = Eigen::Vector3d::Zero();    // n, from i to j [-]
  Eigen::Vector3d point = Eigen::Vector3d::Zero();     // contact point c [m]
  double overlap = 0.0;                                // delta [m]
  double fn = 0.0;                                     // normal force, > 0 repulsive [N]
  Eigen::Vector3d force_i = Eigen::Vector3d::Zero();   // on i [N] (on j: -force_i)
  Eigen::Vector3d torque_i = Eigen::Vector3d::Zero();  // on i about its centre of mass [N m]
  Eigen::Vector3d torque_j = Eigen::Vector3d::Zero();  // on j about its centre of mass [N m]
  double energy_slip = 0.0;     // spring energy lost at the Coulomb and rolling caps in this step, or held by
                                // the springs of a contact that opened (dropped with them) [J]
  double power_damp = 0.0;      // power of the dashpots [W] (>= 0)
  double energy_spring = 0.0;   // energy in the normal, tangential and rolling springs [J]
  bool sliding = false;         // the tangential spring sits at the Coulomb cap
};

// contact of sphere i with sphere j over dt [s]; updates the history. Throws std::invalid_argument for a
// law out of range, a radius or mass <= 0, or dt < 0.
SphereContactLoads sphere_sphere_contact(const SphereOfBody& i, const SphereOfBody& j, SphereContactHistory& h,
                                         const SphereContactLaw& law, double dt);

// the same without the checks, for the stone models' loops (DEMSystem has checked their inputs); zeta [-]
// is the law's damping ratio, damping_ratio_from_restitution(law.restitution) (dem_contact.h), which a loop
// computes once for all its contacts (a log and a square root saved per contact)
SphereContactLoads sphere_sphere_contact_unchecked(const SphereOfBody& i, const SphereOfBody& j,
                                                   SphereContactHistory& h, const SphereContactLaw& law, double zeta,
                                                   double dt);

// contact of sphere i with a fixed plane over dt [s] (the plane's friction replaces law.friction and
// law.rolling_friction); torque_j is zero. Throws as above, and for a normal that is not of unit length.
SphereContactLoads sphere_plane_contact(const SphereOfBody& i, const ContactPlane& plane, SphereContactHistory& h,
                                        const SphereContactLaw& law, double dt);

// the same without the checks (the models' loops; zeta as above)
SphereContactLoads sphere_plane_contact_unchecked(const SphereOfBody& i, const ContactPlane& plane,
                                                  SphereContactHistory& h, const SphereContactLaw& law, double zeta,
                                                  double dt);

}  // namespace vofdem
