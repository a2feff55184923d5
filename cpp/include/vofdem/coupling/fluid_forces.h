// Fluid forces on a stone from the flow around it: seed paper eqs. (16)-(18) and the pressure-gradient
// force F_S, averaged over the cells that the stone covers.
//
//   F_D = w 1/2 rho_w C_D A_p |U - u_p| (U - u_p)                        (16)-(18), drag.h
//   F_S = -V sum_c omega_c (grad p_c - rho_w F_c g)                      pressure gradient in excess of hydrostatic
//   w   = sum_c omega_c F_c,   omega_c = a_c / sum_c a_c                 wet fraction of the stone
//   U   = sum_c a_c F_c U_c / sum_c a_c F_c,   U_c = u_c / n_c           water pore velocity at the stone
//
// a_c [m^2] is the area of the disc inside cell c (PorosityMapper's per-disc lists), F_c the water
// fraction, n_c the porosity, u_c the superficial velocity at the cell centre, p the pressure [Pa],
// g the gravity vector [m/s^2], V the stone's (sphere) volume [m^3] and A_p = pi d^2 / 4.
// Polygon stones: V is the matching 3D stone's volume (polygon.h) and A_p the projected area of that
// stone across the relative velocity, (pi / 2) r_A W (W: the polygon's width across U - u_p, r_A its
// equal-area radius; exact for an ellipsoid, pi r^2 for a disc), d in Re its nominal diameter 2 r_A.
//
// Buoyancy is not counted twice: the DEM's eq. (9) already carries (M - rho_w V w) g, the buoyancy of
// the hydrostatic pressure, so F_S uses the pressure gradient in excess of the hydrostatic one,
// grad p - rho_w g. In still water F_S = 0 and the stone feels exactly its submerged weight; in air
// (F = 0, grad p ~ 0) it is 0 as well. The drag is scaled by the wet fraction (air drag neglected).
// The velocity average is weighted by F so that a stone at the free surface feels the water's velocity.
//
// References: S. Maeno and A. Tomita (2008), ICHE 2008, Nagoya, section 2.4; the split of the pressure
// force into buoyancy and a dynamic part follows e.g. Zhu et al. (2007), Chem. Eng. Sci. 62, 3378.
#pragma once

#include <array>

#include "vofdem/coupling/drag.h"

namespace vofdem {

// the flow averaged over the cells a stone covers
struct StoneFlowSample {
  double area = 0.0;              // sum a_c: the disc's area inside the grid [m^2]
  double wet = 0.0;               // w [-]
  double u = 0.0, w_vel = 0.0;    // water pore velocity (U, W) [m/s]
  double gx = 0.0, gz = 0.0;      // sum omega_c (grad p_c - rho_w F_c g) [Pa/m]
};

// samples the flow over count cells (indices cells, disc areas in them areas [m^2]) from the cell fields
// F [-], pore velocity U, W [m/s] and pressure gradient dpdx, dpdz [Pa/m]; water density rho_w
// [kg/m^3], gravity (grav_x, grav_z) [m/s^2]
StoneFlowSample sample_flow_at_stone(int count, const int* cells, const double* areas, const double* F,
                                     const double* U, const double* W, const double* dpdx, const double* dpdz,
                                     double rho_w, double grav_x, double grav_z);

// drag (16)-(18) on a stone of diameter d [m] moving at (up, wp) [m/s], scaled by the wet fraction [N]
DragForce stone_drag(const StoneFlowSample& s, double up, double wp, double d, double rho_w, double nu_w,
                     DragLaw law);

// the same for a stone of projected area `area` [m^2] across the relative velocity and nominal diameter
// d [m] in Re (polygon stones: DEMSystem::projected_area(i, U - u_p, W - w_p), nominal_diameter(i))
DragForce stone_drag_area(const StoneFlowSample& s, double up, double wp, double d, double area, double rho_w,
                          double nu_w, DragLaw law);

// F_S [N] on a stone of volume V [m^3]
std::array<double, 2> stone_pressure_force(const StoneFlowSample& s, double volume);

}  // namespace vofdem
