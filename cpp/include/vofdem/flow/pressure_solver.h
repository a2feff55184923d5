// Pressure projection solve: the variable-coefficient Poisson problem of a MAC grid.
//
//   sum over the faces f of cell c:  a_f (p_nb(f) - p_c) = b_c                                (P)
//
// a_f >= 0 [m^3 s/kg] is the face coefficient assembled by the flow solver,
// beta_f * (face length) / (distance between the two cell centres), with
// beta_f = dt n_f / (rho_f (1 + dt n_f R'_f)) (porosity n, density rho and the semi-implicit porous
// resistance R' of the face); usual values 1e-6 (water, dt = 1e-3 s, square cells) to 1e-3 (air).
// b_c [m^2/s] is the cell's volume flux balance per metre of width (the divergence of the provisional
// velocity integrated over the cell), p [Pa]. a_f = 0 closes a face (wall, solid cell). On a boundary face with
// a_f > 0, p_nb is the boundary value given in face_*_bc (Dirichlet, e.g. p = 0 on the open top).
// Inactive cells (solid, n = 0) are not unknowns: their pressure is left untouched and every face
// touching them must have a_f = 0. The matrix is symmetric negative semi-definite; a connected group
// of active cells with no Dirichlet face is singular, and the solver then returns the solution whose
// mean over that group is zero after removing the mean of b from it (the compatible part).
//
// Written with A0 the operator with homogeneous boundary values and g_c = sum over the Dirichlet faces
// of c of a_f p_bc, (P) reads A0 p = b - g. The solvers work on the symmetric positive (semi-)definite
// M = -A0 and f = g - b (projected on the compatible part in singular groups). The relative residual
// reported and tested against tol is ||f - M p||_2 / ||f||_2 = ||b - A p||_2 / ||b - g||_2 (compatible
// parts), which stays meaningful when b = 0 but the boundary values are not.
//
// Two solvers share this interface: Eigen's sparse direct solver (the reference) and a geometric
// multigrid preconditioned conjugate gradient (the fast default); method, validation and costs in
// docs/pressure_solver.md.
#pragma once

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "vofdem/common/grid.h"

namespace vofdem {

struct PressureProblem {
  std::vector<double> face_x_coef;   // a_f on x-faces, size grid.nface_x()
  std::vector<double> face_z_coef;   // a_f on z-faces, size grid.nface_z()
  std::vector<double> face_x_bc;     // Dirichlet pressure [Pa] on boundary x-faces (i = 0, nx), size nface_x
  std::vector<double> face_z_bc;     // Dirichlet pressure [Pa] on boundary z-faces (k = 0, nz), size nface_z
  std::vector<std::uint8_t> cell_active;  // 1 = unknown, 0 = solid; size grid.ncell()

  // sizes every array for `grid`: all faces closed, all cells active, bc = 0
  void resize(const Grid2D& grid);
};

enum class PressureSolverKind {
  kEigenDirect = 0,  // Eigen SimplicialLDLT: exact to round-off, the reference
  kMultigridCG = 1,  // conjugate gradient preconditioned by a geometric multigrid V-cycle: the default
};

// solver parameters, constant between setups
struct PressureSolverParams {
  int max_iterations = 200;  // CG iteration limit [-], usual 200 (a solve needs ~10-20)
  int smoothing_sweeps = 1;  // pre- and post-smoothing sweeps per multigrid level [-], usual 1
  int coarsest_cells = 64;   // the hierarchy stops coarsening at or below this many cells [-], usual 64
  // over-correction factor of the piecewise-constant coarse-grid correction [-], in [1, 2), usual 1.8:
  // it compensates the too-small energy of piecewise-constant corrections (Braess 1995) and keeps the
  // CG iteration count nearly independent of the grid size; a solve that meets an indefinite
  // preconditioner falls back to 1
  double coarse_correction_scale = 1.8;
};

struct PressureSolveStats {
  int iterations = 0;        // CG iterations (0 for the direct solver)
  double residual = 0.0;     // final ||f - M p||_2 / ||f||_2 (see above; 0 when f = 0)
  double setup_seconds = 0;  // factorisation or multigrid hierarchy build
  double solve_seconds = 0;
};

class PressureSolver {
 public:
  virtual ~PressureSolver() = default;
  // takes new coefficients; call whenever a_f or cell_active changed (the flow solver: every step)
  virtual void setup(const Grid2D& grid, const PressureProblem& problem) = 0;
  // solves (P) for p [Pa] (size ncell; used as the initial guess by iterative solvers);
  // relative tolerance tol > 0 on ||f - M p|| / ||f|| (above). Iterative solvers throw std::runtime_error
  // if they do not converge within their iteration limit (p is then left as it was); the direct solver
  // refines its solution up to 3 times while above tol and reports the residual reached (round-off)
  virtual PressureSolveStats solve(const std::vector<double>& rhs, std::vector<double>& p, double tol) = 0;
  virtual PressureSolverKind kind() const = 0;
};

std::unique_ptr<PressureSolver> make_pressure_solver(PressureSolverKind kind,
                                                    const PressureSolverParams& params = PressureSolverParams());

// residual r = b - A p on active cells (0 on inactive ones); for tests and diagnostics
void pressure_residual(const Grid2D& grid, const PressureProblem& problem, const std::vector<double>& rhs,
                       const std::vector<double>& p, std::vector<double>& residual);

}  // namespace vofdem
