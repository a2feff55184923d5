// The pressure projection of the flow on the MAC grid (vof_grid.h): the problem (P) of
// pressure_solver.h assembled from the faces, and the velocity correction once it is solved.
//
//   u_f = u*_f - beta_f (p_R - p_L) / h_f                                     correction
//   sum_f a_f (p_nb(f) - p_c) = b_c,   a_f = beta_f l_f / h_f                 (P)
//   b_c = sum_f (+-) u*_f l_f + (n_c - n_c^prev) / dt dx dz                   dn/dt + div u = 0
//
// beta_f = dt n_f / (rho_f (1 + dt n_f R'_f)) (momentum and porous stages), l_f the face's length (dz
// on x-faces, dx on z-faces) and h_f the distance between the centres it separates: dx, z_c(k) -
// z_c(k-1), or half a cell at a Dirichlet face (an open end, the open top, p = 0 there). So b_c [m^2/s]
// is the net outflow of u* less the outflow the porosity change asks for, and the corrected velocities
// leave a cell at the rate -dn/dt dx dz: the water a stone displaces flows away. A cell that opens
// from solid takes no source. Walls, the inlet (its velocity given) and the faces of solid cells are
// closed, a_f = 0.
//
// Open end (free overfall or tailwater): the end face is Dirichlet with the still fluid outside,
// hydrostatic from p = 0 at the top: air above, water below the tailwater level (a single-phase flow:
// water up to that level, or to the top). Fluid drawn in through an open face (the end, or the open top)
// starts from rest outside: its static pressure there is the outside pressure less 1/2 rho U^2 (a
// total-pressure inlet, U the pore velocity at the step's start). A fixed static pressure lets the
// inflow run away: -25 m/s of tailwater below a weir's jet; a wind of air drawn in over a free overfall
// and out through the top over the inlet at 1 m/s, which set a quarter of a weir run's steps.
//
// References: A. J. Chorin (1968), Math. Comp. 22, 745-762 (projection); F. H. Harlow and J. E. Welch
// (1965), Phys. Fluids 8, 2182 (MAC grid).
#pragma once

#include <vector>

#include "vofdem/common/grid.h"
#include "vofdem/flow/pressure_solver.h"

namespace vofdem {

// the domain's ends as the projection sees them, and the still fluid outside an open end
struct ProjectionBoundary {
  bool right_open = false;       // the right end is open (free overfall or tailwater; else a wall)
  bool tailwater = false;        // water outside up to tailwater_level (else air)
  double tailwater_level = 0.0;  // [m]
  bool two_phase = true;         // air above the water outside (else water up to the level or the top)
  double rho_water = 0.0;        // [kg/m^3], the medium's
  double rho_air = 0.0;          // [kg/m^3], the medium's
  double gravity = 0.0;          // |g_z| [m/s^2], 0 without gravity
};

// read-only fields of the projection (pointers to flat arrays of the grid's sizes)
struct ProjectionFields {
  const double* face_x_porosity;     // n_f, nface_x [-]
  const double* face_z_porosity;     // n_f, nface_z [-]
  const double* face_x_beta;         // beta_f, nface_x [m^3 s/kg]
  const double* face_z_beta;         // beta_f, nface_z [m^3 s/kg]
  const double* face_u;              // u^n, nface_x [m/s]: the tailwater's inflow at the step's start
  const double* face_x_rho;          // nface_x [kg/m^3]
  const double* u_star;              // u*, nface_x [m/s]
  const double* w_star;              // w*, nface_z [m/s]
  const double* cell_porosity;       // n, ncell [-]
  const double* cell_porosity_prev;  // n of the last step, ncell [-]
  const double* face_w = nullptr;      // w^n, nface_z [m/s]: the open top's inflow (null: none)
  const double* face_z_rho = nullptr;  // nface_z [kg/m^3]
};

// the pressure [Pa] of the still fluid outside an open end at the centre of row k
double open_end_pressure(const Grid2D& grid, const ProjectionBoundary& bc, int k);

// writes the face coefficients, the boundary values and the active cells of (P) into problem, and b
// into rhs (size ncell), for a step of dt [s] (dt = 0: no porosity source)
void assemble_pressure_problem(const Grid2D& grid, const ProjectionFields& fields, const ProjectionBoundary& bc,
                               double dt, PressureProblem& problem, std::vector<double>& rhs);

// the corrected velocities face_u, face_w from u*, w* and the solved pressure cell_p [Pa] of the
// problem assemble_pressure_problem() wrote (a closed face keeps u*)
void correct_velocities(const Grid2D& grid, const ProjectionFields& fields, const PressureProblem& problem,
                        const std::vector<double>& cell_p, std::vector<double>& face_u, std::vector<double>& face_w);

}  // namespace vofdem
