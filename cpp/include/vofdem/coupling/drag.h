// Fluid drag on a stone: seed paper eqs. (16)-(18).
//
//   F_D = 1/2 rho C_D A_p |U - u_p| (U - u_p)                           (16), (17)
//   C_D = 0.4 + 24 / Re,   Re = |U - u_p| d / nu                        (18)
//
// U is the pore (interstitial) velocity of the water, u/n [m/s], u_p the stone velocity [m/s], d the
// stone diameter [m], A_p = pi d^2 / 4 the projected area of a sphere of diameter d [m^2], rho the
// water density [kg/m^3], nu its kinematic viscosity [m^2/s]. The force [N] is on the stone.
//
// Written as F = 1/2 rho A_p (0.4 |v| + 24 nu / d) v, eq. (18) has no division by the relative speed,
// so zero relative velocity gives zero force, never 0/0. Its slope along v, the stone's drag per unit
// of relative speed gained, is
//   d|F| / d|v| = 1/2 rho A_p (0.8 |v| + 24 nu / d)                     (18')
// the coefficient of the implicit drag exchange (drag_exchange.h) and, with the stone's mass, the
// drag's relaxation time that bounds a step with the drag held (coupler.h). Schiller & Naumann (1933),
// C_D = 24/Re (1 + 0.15 Re^0.687) for Re < 1000 and 0.44 above, is offered as a second law.
//
// Reference: S. Maeno and A. Tomita (2008), ICHE 2008, Nagoya; L. Schiller and A. Naumann (1933),
// Z. Ver. Deut. Ing. 77, 318-320.
#pragma once

namespace vofdem {

enum class DragLaw {
  kPaper = 0,            // C_D = 0.4 + 24 / Re, eq. (18)
  kSchillerNaumann = 1,  // C_D = 24/Re (1 + 0.15 Re^0.687), 0.44 above Re = 1000
};

// drag coefficient [-] at Reynolds number re > 0
double drag_coefficient(double re, DragLaw law = DragLaw::kPaper);

struct DragForce {
  double fx, fz;  // [N]
};

// drag on a sphere of diameter d [m] moving at (up, wp) [m/s] in water of pore velocity (u, w) [m/s]
DragForce drag_force(double u, double w, double up, double wp, double d, double rho, double nu,
                     DragLaw law = DragLaw::kPaper);
// the same without argument checks, for inner loops whose inputs were checked once
DragForce drag_force_unchecked(double u, double w, double up, double wp, double d, double rho, double nu,
                               DragLaw law);
// the same with the projected area A_p [m^2] given apart from the diameter d of Re (non-spherical stones)
DragForce drag_force_area_unchecked(double u, double w, double up, double wp, double d, double area, double rho,
                                    double nu, DragLaw law);

// slope d|F|/d|v| [N s/m] of the drag along the relative velocity, eq. (18') (Schiller & Naumann:
// the derivative of its c(|v|) |v|), at relative speed `speed` [m/s] for the diameter d [m] of Re;
// half_rho_area [kg/m] is 1/2 rho A_p, multiplied first by any prefactor (a wet fraction). Unchecked
double drag_slope(double speed, double d, double half_rho_area, double nu, DragLaw law);

}  // namespace vofdem
