// Internal: geometric multigrid for the MAC-grid pressure operator M = -A0 of pressure_solver.h,
// used as the preconditioner of a conjugate gradient.
//
// Each level stores M as face coefficients on a grid padded by one ghost layer (ghost values are 0, so
// boundary faces act only through the diagonal, as homogeneous Dirichlet faces of the correction):
//   (M x)_c = d_c x_c - w_c x_{c-1} - w_{c+1} x_{c+1} - s_c x_{c-W} - s_{c+W} x_{c+W},
//   d_c = w_c + w_{c+1} + s_c + s_{c+W}.
// Coarsening agglomerates 2 x 2 cells (2 x 3, 3 x 3 at the end of odd rows and columns; 1 in a direction
// already one cell thick). With piecewise-constant prolongation P and restriction P^T the Galerkin
// operator P^T M P has the same five-point form: a coarse face coefficient is the sum of the fine face
// coefficients it covers. The coarse operators thus follow coefficient jumps (density 1000:1, porosity
// 1e-3) and solid cells exactly, whatever their alignment with the coarse grid.
// Smoother: zebra line Gauss-Seidel (tridiagonal solves along each line, even lines then odd ones
// before the coarse correction, the reverse after). Lines run along z (columns), robust to the strong
// vertical coupling of grids finer in z than in x and to horizontal free surfaces; a level whose x
// coupling dominates (total x coefficient above the total z one) uses lines along x instead. The V-cycle is symmetric and positive
// definite, so it can precondition CG. The coarsest level is solved by a dense Cholesky factorisation
// (one cell of each group without a Dirichlet face pinned).
// References: Braess, Towards algebraic multigrid for elliptic problems of second order, Computing 55
// (1995); Notay & Vassilevski, Recursive Krylov-based multigrid cycles, NLAA 15 (2008); Trottenberg,
// Oosterlee & Schuller, Multigrid (2001), ch. 5 (line relaxation).
#pragma once

#include <Eigen/Dense>
#include <vector>

#include "vofdem/flow/pressure_solver.h"

namespace vofdem::detail {

struct MultigridLevel {
  int nx = 0, nz = 0, w = 0;  // cells in x and z; padded row width nx + 2
  // padded arrays of size (nx + 2) (nz + 2); cell (i, k) at (i + 1) + w (k + 1)
  std::vector<double> west, south, diag;  // face coefficient left of / below the cell, diagonal
  std::vector<double> inv, up;            // line Thomas factors: 1 / pivot, next face coefficient / pivot
  bool x_lines = false;                   // smoother lines along x (else along z)
  std::vector<double> mask;               // 1 on cells with d > 0, else 0
  std::vector<double> x, b;               // correction and right-hand side of this level (coarse levels)
  // coarsening to the next level: parent column / row of each fine column / row
  std::vector<int> parent_i, parent_k;
  int index(int i, int k) const { return (i + 1) + w * (k + 1); }
  int size() const { return (nx + 2) * (nz + 2); }
};

class Multigrid {
 public:
  // builds the level structure for an nx x nz fine grid (allocation happens here only)
  void allocate(int nx, int nz, const PressureSolverParams& params);
  // fills the fine level from the face coefficients of pressure_solver.h (unpadded layout) and
  // computes the coarse operators, the smoother factors and the coarsest factorisation
  void setup(const std::vector<double>& face_x_coef, const std::vector<double>& face_z_coef,
             const std::vector<std::uint8_t>& cell_active);
  // z = B r (one V-cycle from a zero guess) on padded fine-level vectors (ghosts of z: 0)
  void apply(const double* r, double* z);
  // q = M x on padded fine-level vectors (ghosts of q untouched); returns x . q
  double multiply(const double* x, double* q) const;

  // over-correction factor of the coarse-grid correction (1 = plain Galerkin correction)
  void set_correction_scale(double scale) { scale_ = scale; }
  int levels() const { return static_cast<int>(levels_.size()); }
  const MultigridLevel& level(int l) const { return levels_[l]; }
  bool allocated_for(int nx, int nz) const {
    return !levels_.empty() && levels_[0].nx == nx && levels_[0].nz == nz;
  }

 private:
  void galerkin(const MultigridLevel& fine, MultigridLevel& coarse);
  void factor_lines(MultigridLevel& lv);
  void factor_coarsest();
  void smooth(const MultigridLevel& lv, const double* b, double* x, int parity, bool zero_guess);
  void smooth_rows(const MultigridLevel& lv, const double* b, double* x, int parity, bool zero_guess);
  void restrict_residual(const MultigridLevel& fine, const double* b, const double* x, MultigridLevel& coarse);
  void prolong(const MultigridLevel& fine, double* x, const MultigridLevel& coarse);
  // x = one V-cycle from a zero guess on level l for the right-hand side b (padded arrays; the ghost
  // layer of x must hold 0, its interior may hold anything)
  void cycle(int l, const double* b, double* x);

  std::vector<MultigridLevel> levels_;
  int sweeps_ = 1;
  double scale_ = 1.0;
  Eigen::MatrixXd coarse_matrix_;
  Eigen::LLT<Eigen::MatrixXd> coarse_llt_;
  Eigen::VectorXd coarse_rhs_;
  std::vector<int> coarse_group_, coarse_stack_;
  std::vector<double> row_;  // one row of residuals
};

}  // namespace vofdem::detail
