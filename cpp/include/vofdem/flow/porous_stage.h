// The porous resistance of eqs. (5)-(7) on the faces of the MAC grid, semi-implicit in the velocity:
// the flow's porous_resistance stage (vof_grid.h), after the explicit momentum terms, before the
// projection.
//
//   (1 + dt n_f R'_f) u_f = u*_f + dt n_f R'_f n_f u_s,f                          (5)-(7) on face f
//   R'_f = a_f + b_f |u^n_f - n_f u_s,f|,     beta_f <- beta_f / (1 + dt n_f R'_f)
//
// a_f and b_f are the linear and quadratic coefficients of porous_resistance.h at the face's porosity
// n_f and stone diameter D_f, with the molecular viscosity of its two cells (the mean of their rho nu,
// divided by the face's rho): eq. (5) takes nu, not nu + nu_t, whose eddy part (up to 1e4 nu in a weir)
// would make the Darcy term 1e4 times too large where the flow is turbulent. |u^n - n u_s| is the speed
// of the step's start (Picard), its component across the face the mean of the four faces around; u_s
// is the stones' velocity at the face (the relative-velocity option; else 0). The projection
// coefficient beta_f = dt n_f / rho_f is divided by the same factor, so the pressure correction moves
// the velocity the resistance left. Faces with n_f = 0 (closed) or n_f = 1 (clear water) keep u* and
// beta_f.
//
// References: S. Maeno and A. Tomita (2008), ICHE 2008, Nagoya, eqs. (5)-(7); P. Higuera, J. L. Lara
// and I. J. Losada (2014), Coastal Eng. 83 (VARANS with semi-implicit porous resistance).
#pragma once

#include <vector>

#include "vofdem/common/grid.h"
#include "vofdem/flow/porous_resistance.h"

namespace vofdem {

// read-only fields of the stage (pointers to flat arrays of the grid's sizes)
struct PorousStageFields {
  const double* face_u;           // u^n, nface_x [m/s]
  const double* face_w;           // w^n, nface_z [m/s]
  const double* face_x_porosity;  // n_f, nface_x [-]
  const double* face_z_porosity;  // n_f, nface_z [-]
  const double* face_x_diameter;  // D_f, nface_x [m]
  const double* face_z_diameter;  // D_f, nface_z [m]
  const double* face_x_rho;       // nface_x [kg/m^3]
  const double* face_z_rho;       // nface_z [kg/m^3]
  const double* cell_rho;         // ncell [kg/m^3]
  const double* cell_nu;          // molecular kinematic viscosity of the cell mixture, ncell [m^2/s]
  const double* face_x_solid_u;   // u_s on x-faces [m/s] (read with relative only)
  const double* face_z_solid_w;   // w_s on z-faces [m/s] (read with relative only)
};

struct PorousStageTerms {
  bool linear = true;      // the Darcy term a (kFlowPorousDarcy)
  bool quadratic = true;   // the Forchheimer term b |u| (kFlowPorousForchheimer)
  bool relative = false;   // on u - n u_s (kFlowRelativeVelocity)
  double k1 = kPaperK1;  // eq. (7) [-]
  double k2 = kPaperK2;  // eq. (7) [-]
};

// applies the resistance to u*, w* (sizes nface_x, nface_z) and divides the projection coefficients
// face_x_beta, face_z_beta by 1 + dt n_f R'_f on every porous face; dt [s]
void porous_resistance_stage(const Grid2D& grid, const PorousStageFields& fields, const PorousStageTerms& terms,
                             double dt, std::vector<double>& u_star, std::vector<double>& w_star,
                             std::vector<double>& face_x_beta, std::vector<double>& face_z_beta);

}  // namespace vofdem
