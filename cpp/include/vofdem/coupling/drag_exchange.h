// Implicit drag exchange: the stones' drag linearised in their own velocity at each exchange and
// integrated implicitly by the DEM over the exchange step, so that no drag relaxation time bounds it.
//
//   F(v) = F(v0) + dF/dv (v - v0) + O(|v - v0|^2)  ~  F0 - beta (v - v0) = beta (U* - v)
//   beta = |dF/du_p| along the relative velocity [N s/m],   U* = v0 + F0 / beta
//
// F0 is the drag at the exchange (sphere drag eqs. 16-18, fluid_forces.h, or the bed drag, bed_drag.h)
// on a stone of velocity v0; the DEM applies beta (U* - v) at every substep with the current velocity
// and integrates it exactly over each half kick (dem_system.h), so the stone relaxes towards U* at the
// drag's own rate whatever the exchange step, never past it. U* lies between v0 and the flow's velocity:
// for a drag c(|r|) r of the relative velocity r = U - v with c growing with |r| (both laws here),
// beta = c + c'|r| >= c, so F0 / beta = r c / (c + c'|r|) is a fraction in (1/2, 1] of r (quadratic
// drag 1/2, Stokes drag 1). The force at v0 is exact; its slope is exact along r (Newton linearisation:
// the relaxation over a step is second-order accurate in the step; over many relaxation times the
// stone closes at least half of the remaining relative velocity per exchange). Across r the slope of
// the quadratic part is smaller than beta (the stone is damped more there, by at most a factor 2).
// This is the implicit momentum-exchange coefficient of unresolved CFD-DEM (e.g. Kloss et al. 2012,
// the implicit part K_sl u_p of the particle's drag) applied to the stone's side; the flow's side, the
// porous resistance of eqs. (5)-(7), is already semi-implicit in the flow's velocity (vof_grid.h).
//
// Held instead (explicit exchange, CouplerParams::implicit_drag = false), F0 acts unchanged over the
// step and the step must stay below the relaxation time (M + M') / beta (CouplerParams::drag_relaxation).
//
// References: C. Kloss, C. Goniva, A. Hager, S. Amberger and S. Pirker (2012), Prog. Comput. Fluid
// Dyn. 12, 140-152; H. P. Zhu, Z. Y. Zhou, R. Y. Yang and A. B. Yu (2007), Chem. Eng. Sci. 62, 3378.
#pragma once

#include "vofdem/coupling/drag.h"
#include "vofdem/coupling/fluid_forces.h"

namespace vofdem {

// the linear drag beta (U* - v) handed to the DEM
struct LinearDrag {
  double coef = 0.0;            // beta [N s/m]
  double vel_x = 0.0, vel_z = 0.0;  // U* [m/s]
};

// |dF/du_p| [N s/m] of the sphere drag (16)-(18) along the relative velocity, scaled by the wet fraction
double sphere_drag_slope(const StoneFlowSample& s, double up, double wp, double d, double rho_w, double nu_w,
                         DragLaw law);
// the same for a stone of projected area `area` [m^2] across the relative velocity and nominal diameter d
// [m] (polygon stones, stone_drag_area); its area is held along the relative velocity
double stone_drag_slope_area(const StoneFlowSample& s, double up, double wp, double d, double area, double rho_w,
                             double nu_w, DragLaw law);

// the drag force f [N] at the stone velocity (up, wp) [m/s] with slope [N s/m] as beta (U* - v); no
// drag (slope <= 0) gives coef 0
LinearDrag linearise_drag(const DragForce& f, double slope, double up, double wp);

}  // namespace vofdem
