// Internal: the default pressure solver, conjugate gradient on M p = f preconditioned by one multigrid
// V-cycle (multigrid.h).
//
// Singular groups: f is projected on zero group means, each preconditioned residual is projected the
// same way (so the iterates stay in the range of M), and p is fixed to zero group means at the end.
// The hierarchy's structure depends on the grid size only and is reused by every setup; a setup
// recomputes the coefficients of all levels, a solve allocates nothing.
#pragma once

#include <vector>

#include "flow/multigrid.h"
#include "flow/pressure_system.h"
#include "vofdem/flow/pressure_solver.h"

namespace vofdem::detail {

class MultigridCGPressureSolver final : public PressureSolver {
 public:
  explicit MultigridCGPressureSolver(const PressureSolverParams& params);
  void setup(const Grid2D& grid, const PressureProblem& problem) override;
  PressureSolveStats solve(const std::vector<double>& rhs, std::vector<double>& p, double tol) override;
  PressureSolverKind kind() const override { return PressureSolverKind::kMultigridCG; }
  const Multigrid& multigrid() const { return mg_; }

 private:
  // removes the group means of a padded vector
  void project(double* v) const;
  [[noreturn]] void fail(int iterations, double residual, double tol, double fnorm) const;

  PressureSolverParams params_;
  PressureSystem sys_;
  Multigrid mg_;
  std::vector<double> f_;                  // unpadded source
  std::vector<double> b_, x_, r_, z_, d_, q_;  // padded CG vectors
  std::vector<int> group_cells_, group_start_;  // padded cells of the singular groups
  double setup_seconds_ = 0.0;
  bool ready_ = false;
};

}  // namespace vofdem::detail
