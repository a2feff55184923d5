// Internal: the checked, analysed form of a PressureProblem shared by the pressure solvers.
//
// From (P) it keeps M = -A0 (symmetric, positive semi-definite), the boundary source g_c (sum of
// a_f p_bc over the Dirichlet faces of c) and the connected groups of active cells (coupled through
// faces with a_f > 0). A group without a Dirichlet face is singular: its right-hand side is projected
// on zero mean and its solution is fixed to zero mean. An interior face whose a_f is below
// kNegligibleFace times the largest face of either of its cells counts as closed: its flux is below
// round-off anyway, and a pocket of cells joined to the rest only through such faces (porosity 1e-6:
// ~1e-15 of an open face) would otherwise be a numerically singular group that breaks the LDLT
// factorisation and stalls the CG.
#pragma once

#include <cstdint>
#include <vector>

#include "vofdem/common/grid.h"
#include "vofdem/flow/pressure_solver.h"

namespace vofdem::detail {

class PressureSystem {
 public:
  // checks sizes and values (std::invalid_argument), copies coefficients, finds the groups;
  // allocates only when the grid size changes
  void build(const Grid2D& grid, const PressureProblem& problem);

  int nx() const { return nx_; }
  int nz() const { return nz_; }
  int ncell() const { return nx_ * nz_; }
  const std::vector<double>& face_x_coef() const { return ax_; }
  const std::vector<double>& face_z_coef() const { return az_; }
  const std::vector<std::uint8_t>& cell_active() const { return active_; }
  // number of active cells
  int nactive() const { return nactive_; }

  // f = g - rhs on active cells (0 elsewhere), projected to zero mean on each singular group
  // (without the projection when project = false)
  void source(const std::vector<double>& rhs, std::vector<double>& f, bool project = true) const;
  // subtracts from x its mean over each singular group (x has size ncell)
  void remove_singular_means(double* x) const;
  bool has_singular_groups() const { return singular_start_.size() > 1; }
  // cells of the singular groups: group s holds singular_cells()[singular_start()[s] .. singular_start()[s + 1])
  const std::vector<int>& singular_cells() const { return singular_cells_; }
  const std::vector<int>& singular_start() const { return singular_start_; }
  // one cell of each singular group (the one the direct solver pins)
  std::vector<int> singular_anchor_cells() const;

  // r = f - M x on active cells, 0 on inactive ones
  void residual(const std::vector<double>& f, const std::vector<double>& x, std::vector<double>& r) const;

 private:
  void find_groups();
  void close_negligible_faces(const Grid2D& grid);
  // writes the pattern (pattern_changed_: whether it changed); false if a value fails a check
  bool pattern_checked(const Grid2D& grid, const PressureProblem& problem, bool had_pattern);
  // throws std::invalid_argument naming the first value that fails a check
  void check_pattern(const Grid2D& grid, const PressureProblem& problem) const;

  int nx_ = 0, nz_ = 0, nactive_ = 0;
  // open faces (x then z) and active cells of the last build, and whether its groups are known
  std::vector<std::uint8_t> pattern_;
  bool groups_valid_ = false, pattern_changed_ = false;
  std::vector<double> ax_, az_, g_;
  std::vector<std::uint8_t> active_;
  // cells of the singular groups, group s holds singular_cells_[singular_start_[s] .. singular_start_[s+1])
  std::vector<int> singular_cells_, singular_start_;
  // work space of the group search
  std::vector<int> stack_, group_;
  std::vector<double> cell_amax_;  // largest face coefficient of each cell (close_negligible_faces)
};

// a face below this fraction of its cells' largest face is closed [-]
constexpr double kNegligibleFace = 1e-13;

}  // namespace vofdem::detail
