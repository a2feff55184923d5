// Bed drag: the reaction on the stones of the porous resistance that the flow feels (eqs. 5-7), the
// drag of unresolved CFD-DEM, offered in place of the single-sphere drag of eqs. (16)-(18).
//
//   fluid (eqs. 2-3, 5-7):  rho du/dt + ... = -n grad p + rho n g + rho n R,   R = -u_r (a + b |u_r|)
//   so the resistance takes rho n (a + b |u_r|) u_r per unit bulk volume out of the water; by Newton's
//   third law the stones receive it. A stone of volume V stands for the bulk volume V / (1 - n) of
//   the packing, so
//
//   F_bed = V rho_w sum_c omega_c F_c n_c (a_c + b_c |u_r,c|) u_r,c / (1 - n_c)
//         = V rho_w sum_c omega_c F_c (A_c + B_c |u_r,c|) u_r,c                                  (*)
//   A_c = n a / (1 - n) = k1 nu (1 - n) / (n^2 D^2),   B_c = n b / (1 - n) = k2 / (n^2 D)
//
// u_r,c = n_c (U_c - u_p) is the superficial velocity relative to the stone (U_c the pore velocity,
// u_p the stone's velocity) when the flow's resistance uses the relative velocity, else n_c U_c;
// omega_c = a_c / sum a_c the share of the disc's area in cell c (as for F_S, fluid_forces.h), F_c the
// water fraction (no drag from air), a and b of eqs. (5)-(7) with the molecular viscosity nu and the
// cell's stone diameter D. This is the unresolved CFD-DEM drag F_i = V_i beta / (1 - eps) (U - v) of
// Zhu et al. (2007) and Kloss et al. (2012) with eps = n and the exchange coefficient fixed by the flow's
// own closure law, beta = rho n^2 (a + b |u_r|) (so beta (U - v) = rho n (a + b |u_r|) u_r): the
// stones receive exactly what the resistance takes from the water. With (k1, k2) = (150, 1.75) beta is
// the Ergun branch of the Gidaspow drag, 150 (1 - n)^2 mu / (n D^2) + 1.75 rho (1 - n) |U - v| / D.
//
// Check: in steady uniform flow through a fixed bed, -dp/dx = rho u (a + b |u|), so F_bed = V n/(1 - n)
// (-dp/dx) and F_bed + F_S = V (-dp/dx) / (1 - n): the stones carry the whole pressure drop of the
// bulk volume they stand for.
//
// Guards: the expanded form (*) has no 1/(1 - n): a cell without porous medium (n_c >= 1) gives
// nothing, and A_c, B_c stay finite as n_c -> 1 (omega_c bounds the share of a nearly empty cell);
// a solid cell (n_c <= 0, walls) or a cell without stone diameter (D_c <= 0) gives nothing; as
// n_c -> 0 the coefficients grow like 1/n_c^2, as the flow's resistance does: the stones take the
// drag implicitly through its slope (below, drag_exchange.h), never through a cut-off.
//
// References: S. Maeno and A. Tomita (2008), ICHE 2008, Nagoya (eqs. 5-7); H. P. Zhu, Z. Y. Zhou,
// R. Y. Yang and A. B. Yu (2007), Discrete particle simulation of particulate systems: theoretical
// developments, Chem. Eng. Sci. 62, 3378-3396 (the drag of unresolved coupling, Gidaspow's and
// Di Felice's correlations); C. Kloss, C. Goniva, A. Hager, S. Amberger and S. Pirker (2012), Models, algorithms
// and validation for opensource DEM and CFD-DEM, Prog. Comput. Fluid Dyn. 12, 140-152.
#pragma once

#include "vofdem/coupling/drag.h"
#include "vofdem/flow/porous_resistance.h"
#include "vofdem/flow/vof_grid.h"

namespace vofdem {

// what the bed drag needs of the flow's closure law (eqs. 5-7), made from the flow's parameters only:
// the water of its Medium, its (k1, k2) and its effect flags, so the stones take exactly what the flow's
// resistance removes and the water is defined in one place (FlowParams::medium)
struct BedDragParams {
  explicit BedDragParams(const FlowParams& flow);
  double rho_w;     // water density [kg/m^3]: flow.medium.rho_water
  double nu_w;      // molecular kinematic viscosity of the water [m^2/s]: flow.medium.nu_water (never nu + nu_t)
  double k1, k2;    // eq. (7) [-]: flow.k1, flow.k2
  bool linear;      // Darcy term a of the flow's resistance on (kFlowPorousDarcy)
  bool quadratic;   // Forchheimer term b |u| on (kFlowPorousForchheimer)
  bool relative;    // the flow's resistance acts on u - n u_p, the stones' velocity (kFlowRelativeVelocity)
};

// bed drag (*) on a stone of volume V [m^3] moving at (up, wp) [m/s] over count cells (indices cells,
// disc areas in them areas [m^2]); cell fields: water fraction F [-], porosity n [-], stone diameter
// D [m], pore velocity U, W [m/s]. slope (optional) receives |dF_bed / du_p| [N s/m], the stiffness of
// the force in the stone's velocity (0 without the relative velocity): the implicit drag exchange's
// coefficient (drag_exchange.h), or the relaxation limit of a held drag.
DragForce bed_drag(int count, const int* cells, const double* areas, const double* F, const double* n,
                   const double* D, const double* U, const double* W, double up, double wp, double volume,
                   const BedDragParams& p, double* slope = nullptr);

// the summand of (*) in one cell, per unit stone volume and water density: F_c (A_c + B_c |u_r,c|) u_r,c
// (fx, fz) [m/s^2], and |d / du_p| of it (slope) [1/s], the stones' velocity (up, wp) [m/s] there.
// The kernel mapping smooths these cell fields and averages them over each stone's footprint
// (coupler.h, CouplingMapping::kKernel); bed_drag above is the same sum over the raw cells.
struct BedDragDensity {
  double fx = 0.0, fz = 0.0, slope = 0.0;
};
BedDragDensity bed_drag_density(double F, double n, double D, double U, double W, double up, double wp,
                                const BedDragParams& p);

}  // namespace vofdem
