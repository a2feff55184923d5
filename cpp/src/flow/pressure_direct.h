// Internal: the reference pressure solver, Eigen's sparse LDL^T (SimplicialLDLT) of M = -A0.
//
// Singular groups are made definite by pinning one cell (its row and column become identity, its
// value 0): the projected source is compatible, so the pinned system solves the full one, and the
// group's mean is removed afterwards.
#pragma once

#include <Eigen/SparseCholesky>
#include <Eigen/SparseCore>
#include <vector>

#include "flow/pressure_system.h"
#include "vofdem/flow/pressure_solver.h"

namespace vofdem::detail {

class EigenDirectPressureSolver final : public PressureSolver {
 public:
  void setup(const Grid2D& grid, const PressureProblem& problem) override;
  PressureSolveStats solve(const std::vector<double>& rhs, std::vector<double>& p, double tol) override;
  PressureSolverKind kind() const override { return PressureSolverKind::kEigenDirect; }

 private:
  PressureSystem sys_;
  std::vector<int> unknown_;        // cell -> unknown index (-1 inactive)
  std::vector<std::uint8_t> pinned_;  // cell pinned to 0 (one per singular group)
  std::vector<Eigen::Triplet<double>> triplets_;
  Eigen::SparseMatrix<double> matrix_;
  Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> ldlt_;
  std::vector<int> pattern_key_;    // active cells and pinned cells of the analysed pattern
  Eigen::VectorXd b_, x_;
  std::vector<double> f_, work_, r_;
  double setup_seconds_ = 0.0;
  bool ready_ = false;
};

}  // namespace vofdem::detail
