// Porous resistance of a stone matrix to the flow through it: seed paper eqs. (5)-(7).
//
//   R = -u (nu / K + C / sqrt(K) |u|)                                   (5), (6)
//   K = n^3 D^2 / (k1 (1 - n)^2),   C = k2 / sqrt(k1 n^3)               (7)
//
// u is the superficial (mesh-averaged) velocity [m/s], n the porosity [-], D the stone diameter [m],
// nu the kinematic viscosity [m^2/s]. R is a force per unit mass [m/s^2] that points against the
// flow. The seed paper writes R along u inside -n^2 (dp/dx / rho - g - R), which would accelerate
// the flow; here R carries the minus sign itself, so the momentum equation reads
//   n du/dt + ... = -n^2 (dp/dx / rho - g_x - R_x) + ...
// with R_x = -u (a + b |u|) and the resistance always removes energy.
//
// Expanding, nu/K = k1 nu (1-n)^2 / (n^3 D^2) and C/sqrt(K) = k2 (1-n) / (n^3 D), so in steady uniform
// flow -dp/dx = rho u (nu/K + C/sqrt(K) |u|); (k1, k2) = (150, 1.75) is exactly the Ergun equation in
// the superficial velocity, and the paper's (200, 2.8) is 1.33x Ergun in the linear term and 1.60x
// in the quadratic term.
//
// Reference: S. Maeno and A. Tomita (2008), Destruction prediction of a rubble mound weir using
// VOF-DEM coupled model, ICHE 2008, Nagoya; S. Ergun (1952), Chem. Eng. Prog. 48, 89-94.
#pragma once

namespace vofdem {

// the paper's coefficients (Maeno et al. 2007)
inline constexpr double kPaperK1 = 200.0;
inline constexpr double kPaperK2 = 2.8;
// Ergun's coefficients
inline constexpr double kErgunK1 = 150.0;
inline constexpr double kErgunK2 = 1.75;

// intrinsic permeability K [m^2] of eq. (7); n in (0, 1), d > 0 [m], k1 > 0 [-]
double permeability(double n, double d, double k1);
// Forchheimer coefficient C [-] of eq. (7); n in (0, 1], k1 > 0, k2 >= 0
double forchheimer_coefficient(double n, double k1, double k2);

// linear and quadratic resistance coefficients: R = -u (linear + quadratic |u|)
struct PorousCoefficients {
  double linear;     // nu / K [1/s]
  double quadratic;  // C / sqrt(K) [1/m]
};

// coefficients of eqs. (5)-(7); n = 1 (clear water) gives zero resistance. Checks its arguments.
PorousCoefficients porous_coefficients(double n, double d, double nu, double k1 = kPaperK1,
                                       double k2 = kPaperK2);
// the same without argument checks, for inner loops whose inputs were checked once; n in (0, 1]
PorousCoefficients porous_coefficients_unchecked(double n, double d, double nu, double k1, double k2);

// the same per unit volume of solid: n / (1 - n) (a, b) in the expanded form
//   (k1 nu (1 - n) / (n^2 D^2), k2 / (n^2 D)),
// finite as n -> 1; the reaction of the resistance on the stones (bed_drag.h). n in (0, 1), unchecked
PorousCoefficients bed_coefficients_unchecked(double n, double d, double nu, double k1, double k2);

// resistance per unit mass [m/s^2] of eqs. (5)-(6) for superficial velocity (u, w) [m/s]
struct Resistance {
  double rx, rz;
};
Resistance porous_resistance(double u, double w, double n, double d, double nu, double k1 = kPaperK1,
                             double k2 = kPaperK2);

}  // namespace vofdem
