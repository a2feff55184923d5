// Overflow load: drag and lift of the water passing over a stone that sticks out of the stone surface.
//
//   F_D = 1/2 rho_w C_D A_exp |u_r| u_r f                  drag along the relative approach velocity
//   F_L = 1/2 rho_w C_L A_exp |u_r|^2 f                    lift, vertical (upwards)
//   A_exp = phi A_p,   phi = 1 - w_disc(1 - 2 p / h)       exposed share of the projected area
//   p = z_top - z_ref,   z_ref = 1/2 (S(x_lo) + S(x_hi))   protrusion above the others' surface
//
// S(x) is the stone surface of the other stones: the highest upper outline of any other stone at x, each
// outline the half-ellipse of the stone's horizontal and vertical extents (a disc's or a sphere's circle
// exactly; a polygon's extents through StoneModel::outline_max, an ellipse approximation of its top);
// x_lo, x_hi the stone's own horizontal extent, h its height, z_top its top. A stone whose centre is
// covered by the others' surface above its top (S(x_c) > z_top), or whose flanks both lie above its top,
// is buried: p = 0. A flank that no other stone covers takes the stone's own bottom (the bed). w_disc(s) is
// the share of a circle below the level s radii above its centre (wet_fraction.h), so phi is the share of
// the projected area (a circle, or an ellipse of the stone's height) above the surface; A_p the stone
// model's projected area across u_r (StoneModel::projected_area): no branch on the shape.
//
// Approach velocity u_r = U_a - u_p: U_a the pore velocity of the water in the band from the stone's top
// up to band_height stone diameters above it, in the flow column of the stone's centre, averaged with
// weights l_c F_c (l_c the band's length in cell c, F_c its water fraction); f = sum l_c F_c / sum l_c
// the band's water share (a dry band: no load). Why the band and not the depth-averaged overflow
// velocity: the measurements below refer the force to the velocity met by the grain's exposed part
// (Schmeeckle et al.: in front of it at its height; Einstein & El-Samni: 0.35 d above the bed's
// theoretical level), and the band needs no free surface detection in a plunging, aerated overflow.
//
// Not counting twice: the coupler's drag of eqs. (16)-(18) (or the bed drag) loads the whole stone with the
// pore velocity averaged over its cells. With this load on, the exposed share phi of the stone is loaded by
// the approach velocity instead: the coupler scales that drag (and its slope) by 1 - phi and adds F_D, F_L.
// The pressure-gradient force F_S is kept whole (the overflow's pressure field is the flow's).
//
// Newton's third law: F_D + F_L is taken out of the band's cells with the weights l_c F_c / sum l_c F_c.
// The flow is per metre of flume width B and each stone is one stone in the flume, so a cell loses
// (F_D + F_L) w_c / B per metre of width; the coupler splits each cell's share evenly over the cell's open
// x-faces (x) and z-faces (z) as an impulse on the superficial velocity, du = -F w_c dt / (B rho_w V_f)
// (V_f = dx dz, the face's control volume), so that B rho_w sum_f V_f du_f = -(F_D + F_L) dt exactly.
// (The coupler's scaled-down share phi of the cell drag is not given back: eqs. 16-18 have no reaction
// in the flow, and with the bed drag the flow's resistance stays whole.)
//
// Coefficients, each from a measurement on stones or spheres on a rough bed, never fitted to the weir:
//   C_D = 0.91: the mean drag coefficient of 7 natural particles measured by Schmeeckle, Nelson & Shreve
//     (2007) (spheres 0.76, cubes 1.36), at particle Reynolds numbers like the weir's (u d / nu ~ 1e4),
//     with the velocity in front of the particle; well above 0.4 of a sphere in still water.
//   C_L = 0.178: Einstein & El-Samni (1949), the lift of hemispheres in a bed of hemispheres with the
//     velocity at 0.35 d above the bed's theoretical level. Schmeeckle et al. found the vertical force
//     poorly correlated with any velocity, so no better measured value exists; Chepil (1958) measured a
//     lift of about 0.85 times the drag on hemispheres in air (kept as an upper bound, not used).
//
// References: M. W. Schmeeckle, J. M. Nelson and R. L. Shreve (2007), Forces on stationary particles in
// near-bed turbulent flows, J. Geophys. Res. 112, F02003; H. A. Einstein and E. A. El-Samni (1949),
// Hydrodynamic forces on a rough wall, Rev. Mod. Phys. 21, 520-524; W. S. Chepil (1958), The use of evenly
// spaced hemispheres to evaluate aerodynamic forces on a soil surface, Trans. AGU 39, 397-404; J. W.
// Kirchner, W. E. Dietrich, F. Iseya and H. Ikeda (1990), The variability of critical shear stress,
// friction angle, and grain protrusion in water-worked sediments, Sedimentology 37, 647-672 (protrusion
// above the neighbours' surface).
#pragma once

#include <cstdint>

#include "vofdem/common/grid.h"
#include "vofdem/coupling/drag.h"

namespace vofdem {

// coefficients of the overflow load (CouplerParams::overflow; the switch is kCoupleOverflowLoad)
struct OverflowLoadParams {
  double drag_coefficient = 0.91;   // C_D [-], (0, 5]; 0.91 (Schmeeckle et al. 2007, natural particles)
  double lift_coefficient = 0.178;  // C_L [-], [0, 5]; 0.178 (Einstein & El-Samni 1949)
  double band_height = 1.0;         // the approach band above the stone's top, in stone diameters [-], (0, 5]; 1

  // throws std::invalid_argument naming the first bad parameter
  void validate() const;
};

// a stone's outline extents [m] (from StoneModel::outline_max)
struct StoneExtent {
  double x_lo, x_hi, z_lo, z_hi;
};

// the others' surface S(x) [m] at x for stone j: the highest upper outline (half-ellipse of the extents) of
// the active stones k != j at x; -infinity where none covers x. extents and active have count entries
double surface_of_others(int j, double x, int count, const StoneExtent* extents, const std::uint8_t* active);

// protrusion p [m] of stone j above the others' surface (0 when buried, at most its height)
double stone_protrusion(int j, int count, const StoneExtent* extents, const std::uint8_t* active);

// the share phi [-] of the projected area above the surface for protrusion p [m] of a stone of height h [m]
double exposed_share(double protrusion, double height);

// the band's sample: pore velocity (u, w) [m/s], water share f [-]
struct OverflowSample {
  double u = 0.0, w = 0.0, wet = 0.0;
};

// F_D + F_L [N] on exposed area a_exp [m^2] for the relative approach velocity (ur, wr) [m/s], band water
// share wet [-], water density rho [kg/m^3]
DragForce overflow_force(double a_exp, double ur, double wr, double wet, double rho, const OverflowLoadParams& p);

// whether cell c has an open interior face in x and in z (face porosity > 0; the boundary faces' velocities are
// the boundary conditions', so an impulse there would be lost): the cells a band may sample
bool overflow_band_cell(const Grid2D& g, int i, int k, const double* face_x_n, const double* face_z_n);

// the reaction on the flow: each cell's share (reaction[2c], reaction[2c + 1]) [N per metre of width] over dt [s]
// given to its open interior x-faces (u) and z-faces (w), evenly, as du = r dt / (rho V_c m) (V_c = dx dz_k
// the cell's volume per metre of width, m its open faces in that direction), so that rho sum V_c du = r dt
void apply_overflow_reaction(const Grid2D& g, const double* face_x_n, const double* face_z_n, const double* reaction,
                             double dt, double rho, double* face_u, double* face_w);

}  // namespace vofdem
