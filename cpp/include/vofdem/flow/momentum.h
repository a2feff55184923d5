// Explicit momentum terms of the volume-averaged Navier-Stokes equations: seed paper eqs. (2)-(3).
//
//   u* = u^n + dt [ -div(u u / n) + n g + (1/rho) div(mu_e (grad u + grad u^T)) ]
//
// on the staggered grid: u = (u, w) superficial velocities on x- and z-faces, n the face porosity,
// rho the face density, mu_e the cell dynamic viscosity (molecular + eddy). The pressure gradient and
// the porous resistance are added later (semi-implicit resistance, projection).
//
// Convection (conservative form, div u = 0): the momentum of a face is carried with its pore velocity
// u_f / n_f; the value carried across a control-volume side is the upwind one corrected by a van Leer
// limited slope (MUSCL), so the scheme is second order in smooth flow and bounded at the interface.
// Diffusion: the full stress tensor, 2 mu du/dx at cell centres and mu (du/dz + dw/dx) at corners,
// corner viscosity the arithmetic mean of its cells (optionally the eddy part by harmonic mean). Forward Euler, or (implicit_vertical) the vertical parts
// d/dz(mu du/dz) and d/dz(2 mu dw/dz) by backward Euler, one tridiagonal solve per column: the
// eddy viscosity over dz = 5-10 mm would otherwise bind the step (explicit limit ~ dz^2 / (4 nu_t)).
// The two parts are applied one after the other, v = (I - dt Z)^-1 (I + dt X) u^n (X explicit, Z
// implicit): each factor is stable on its own. Added side by side, v = (I - dt Z)^-1 u^n + dt X u^n,
// a mode that Z damps keeps dt X u^n whole, which grows past dt |X| = 1, half the forward-Euler limit
// the step is bounded by (test_viscous_implicit.cpp). With implicit_horizontal the horizontal parts
// d/dx(2 mu du/dx) and d/dx(mu dw/dx) go by row solves too, and only the cross terms stay explicit
// (MomentumTerms; cpp/src/flow/momentum_implicit.cpp).
//
// Boundaries (ghost values): walls slip (zero shear) or no-slip (u = 0 at the wall), or the log-law
// shear of the wall functions when the turbulence model supplies it; the inlet carries no vertical
// velocity; open ends and the open top are zero-gradient and stress-free, and an open face's own
// outflow flux is implicit (backward Euler in that one term), so that it bounds no step.
//
// References: F. H. Harlow and J. E. Welch (1965), Phys. Fluids 8, 2182; B. van Leer (1979),
// J. Comput. Phys. 32, 101.
#pragma once

#include <vector>

#include "vofdem/common/grid.h"

namespace vofdem {

// what each end of the domain is, as the momentum stencils see it
struct MomentumBoundary {
  bool left_inlet = false;  // x = x0 carries a prescribed inflow (else a wall)
  bool right_open = false;  // x = end is open (free overfall or tailwater; else a wall)
  bool top_open = true;     // z = top is open to the atmosphere (else a slip lid)
  bool no_slip = false;     // bed and end walls no-slip (else slip)
};

// read-only fields the explicit terms need (pointers to flat arrays of the grid's sizes)
struct MomentumFields {
  const double* face_u;        // nface_x [m/s]
  const double* face_w;        // nface_z [m/s]
  const double* face_x_porosity;  // nface_x [-]
  const double* face_z_porosity;  // nface_z [-]
  const double* cell_mu;       // ncell, effective dynamic viscosity [Pa s]
  const double* face_x_rho;    // nface_x [kg/m^3]
  const double* face_z_rho;    // nface_z [kg/m^3]
  const double* cell_rho = nullptr;  // ncell [kg/m^3], needed with wall shear
  // kinematic wall shear [m^2/s^2] acting on the fluid from wall functions (k-epsilon), or null for
  // the slip / no-slip condition: x-component on the bed z-faces, z-component on the end-wall x-faces
  const double* face_z_wall_shear = nullptr;
  const double* face_x_wall_shear = nullptr;
  // eddy part rho nu_t of cell_mu [Pa s], ncell, or null: given, a corner takes the arithmetic mean of the
  // cells' molecular part plus the harmonic mean of their eddy part (0 if any cell has none); else the
  // arithmetic mean of cell_mu
  const double* cell_mu_eddy = nullptr;
  // velocities of the convective term (carrying and carried, [m/s]), or null for face_u, face_w: the
  // Adams-Bashforth 2 step evaluates convection at the extrapolated velocity, the rest at face_u, face_w
  const double* conv_face_u = nullptr;
  const double* conv_face_w = nullptr;
};

struct MomentumTerms {
  bool convection = true;
  bool viscosity = true;
  // vertical diffusion d/dz(mu du/dz) and d/dz(2 mu dw/dz) by backward Euler (one tridiagonal solve per
  // column for u and for w) after the explicit x-diffusion and cross terms
  bool implicit_vertical = false;
  // the former splitting (ViscousScheme::kImplicitVerticalFromStart): the columns solved from u^n, the
  // explicit increment added beside them
  bool vertical_from_start = false;
  // with implicit_vertical (not vertical_from_start): the horizontal diffusions d/dx(2 mu du/dx) and
  // d/dx(mu dw/dx) by backward Euler too, one tridiagonal solve per row before the column solves
  // (implicit_row_diffusion), so that only the cross terms stay explicit: d/dz(mu dw/dx) in u's
  // equation from w^n, then d/dx(mu du/dz) in w's from the new u (block Gauss-Seidel). With all four
  // diffusions implicit no stress bounds the step; the step's matrix stays stable to 1e4 times the
  // split scheme's limit (test_viscous_implicit.cpp)
  bool implicit_horizontal = false;
  // the viscous increment in this many substeps of dt / m, each the one-step scheme above (explicit
  // part, then the column solves), convection and gravity over the whole dt at the step's start: each
  // substep needs only dt / m below the explicit viscous limit (viscous_stable_dt); 1: one step
  int viscous_substeps = 1;
  double gravity_x = 0.0;  // [m/s^2], 0 when gravity is off
  double gravity_z = 0.0;  // [m/s^2]
};

// work array reused from step to step (corner shear stresses)
struct MomentumScratch {
  std::vector<double> pore_u, pore_w;          // u / n on faces (0 on closed faces)
  std::vector<double> corner_mu, corner_tau;   // (nx + 1) x (nz + 1) corners
  std::vector<double> corner_tau_u;            // corner stress the u-equation takes explicitly
  std::vector<double> cell_inv_eddy;           // 1 / eddy viscosity of each cell (harmonic corner mean)
  std::vector<double> tri_a, tri_b, tri_c, tri_d;  // tridiagonal systems of all columns, (nx + 1) x (nz + 1)
  std::vector<double> cell_flux_u, cell_flux_w;      // x-flux of u, z-flux of w at cell centres
  std::vector<double> corner_flux_u, corner_flux_w;  // z-flux of u, x-flux of w at corners
  std::vector<double> sub_u, sub_w, sub_u_next, sub_w_next;  // velocities of the viscous substeps
  std::vector<double> stressed_u, stressed_w;  // u^n + dt (explicit viscous term): the vertical solve's start
  std::vector<double> corner_tau_w;            // corner stress the w-equation takes explicitly (rows implicit)
  std::vector<double> rowed_u, rowed_w;        // the velocities after the row solves: the columns' start
};

// writes u* on every x-face and w* on every z-face. Closed faces (n_f = 0) and walls get 0; the
// inlet faces get u^n (the boundary stage overwrites them); open boundary faces get u^n + dt n g.
// terms.viscous_substeps > 1 with viscosity on: see MomentumTerms (1 takes the one-step path, bit for bit).
void momentum_explicit(const Grid2D& grid, const MomentumFields& fields, const MomentumTerms& terms,
                       const MomentumBoundary& bc, double dt, std::vector<double>& u_star,
                       std::vector<double>& w_star, MomentumScratch& scratch);

// van Leer limited face value from the upwind-upwind, upwind and downwind values
inline double muscl_value(double far, double up, double down) {
  const double d = down - up;
  const double b = up - far;
  // van Leer: slope = 2 d b / (d + b) when d, b share a sign, else 0; face value = up + slope / 2
  if (d * b <= 0.0) return up;
  return up + d * b / (d + b);
}

// the backward Euler of the vertical diffusion (terms.implicit_vertical) after the explicit stresses:
// (I - dt Z) v = v0 column by column, v0 the velocities after the explicit stresses alone (u0, w0:
// u^n + dt (explicit viscous term) on open faces); adds v - v0 to u* and w* on open faces. The corner
// viscosities in s.corner_mu are set by the caller; momentum_explicit's kernel, declared for its
// face-by-face reference test
void implicit_vertical_diffusion(const Grid2D& g, const MomentumFields& f, const MomentumBoundary& bc, double dt,
                                 const double* u0, const double* w0, std::vector<double>& u_star,
                                 std::vector<double>& w_star, MomentumScratch& s);

// the backward Euler of the horizontal diffusion (terms.implicit_horizontal) after the explicit cross
// terms: (I - dt H) y = v0 row by row, H u = (1/rho) d/dx(2 mu du/dx) on x-faces and H w = (1/rho)
// d/dx(mu dw/dx) on z-faces (corner viscosities in s.corner_mu, set by the caller). The end faces of a
// u-row keep their u^n (wall 0, inflow, open end) as known values; a w-row's ends carry the corner
// shear's ghost -w where corner_shear has it (inlet, no-slip wall) and no stress elsewhere. Writes y
// to s.rowed_u, s.rowed_w (closed faces: v0) and adds y - v0 to u* and w* on open faces. Declared for
// its face-by-face reference test
void implicit_row_diffusion(const Grid2D& g, const MomentumFields& f, const MomentumBoundary& bc, double dt,
                            const double* u0, const double* w0, std::vector<double>& u_star,
                            std::vector<double>& w_star, MomentumScratch& s);

// the bound of the viscous step (viscous_stable_dt). With mass R (rho times the face's volume) and the
// stress operator's energy K = sum 2 mu u_x^2 + 2 mu w_z^2 + mu (u_z + w_x)^2 (symmetric, K >= 0),
// split into Z (mu u_z^2 + 2 mu w_z^2, backward Euler) and X = K - Z (explicit):
// - kRowSum: forward Euler of the explicit operator is stable while dt <= 2 / lambda_max(R^-1 X), and
//   lambda_max <= the largest row sum of |R^-1 X| (Gershgorin), cross terms included;
// - kEnergy (the split scheme of momentum_explicit only): (R + dt Z) v = (R - dt X) u has both sides
//   symmetric, so its step is similar to a symmetric matrix and stable iff -(R + dt Z) <= R - dt X <=
//   R + dt Z. The right inequality is K >= 0. The left one needs dt (X - Z) <= 2 R, and corner by corner
//   2 u_z w_x - u_z^2 <= w_x^2 gives X - Z <= X' = sum 2 mu u_x^2 + 2 mu w_x^2: dt <= 2 / lambda_max(R^-1
//   X'), a pure x-diffusion (Gershgorin again) with no cross terms and w's coefficient doubled. A proof
//   (for the stresses; the wall functions' shear is an explicit source outside K), and a step 2.25
//   times kRowSum's in uniform water on cells of dx / dz = 2.5
enum class ViscousBound { kRowSum = 0, kEnergy = 1 };

// largest stable viscous step [s] (face by face); corner_mu: work array (resized on first use).
// implicit_vertical: the bound of the split scheme (the vertical diffusion by backward Euler), else
// of forward Euler of every stress (kRowSum only: kEnergy throws std::invalid_argument); cell
// (optional) receives the cell beside the binding face (-1: none)
double viscous_stable_dt(const Grid2D& grid, const MomentumFields& fields, std::vector<double>& corner_mu,
                         bool implicit_vertical = false, ViscousBound bound = ViscousBound::kRowSum,
                         int* cell = nullptr);

// solves a x = d in place (d becomes x) for a tridiagonal matrix: sub-diagonal a, diagonal b,
// super-diagonal c, rows [0, m); Thomas algorithm, stable for the diagonally dominant rows used here
void solve_tridiagonal(int m, const double* a, double* b, const double* c, double* d);

// the same for the independent systems of columns i in [i0, i1) stored row-major (row k of column i at
// i + stride k): every column gets exactly the operations of solve_tridiagonal, row by row across the
// columns so that the loops vectorise
void solve_tridiagonal_rows(int m, int i0, int i1, int stride, const double* a, double* b, const double* c,
                            double* d);

}  // namespace vofdem
