#include "vofdem/flow/pressure_solver.h"

#include <stdexcept>
#include <string>

#include "flow/pressure_direct.h"
#include "flow/pressure_mgcg.h"
#include "flow/pressure_system.h"

namespace vofdem {

void PressureProblem::resize(const Grid2D& grid) {
  face_x_coef.assign(grid.nface_x(), 0.0);
  face_z_coef.assign(grid.nface_z(), 0.0);
  face_x_bc.assign(grid.nface_x(), 0.0);
  face_z_bc.assign(grid.nface_z(), 0.0);
  cell_active.assign(grid.ncell(), 1);
}

std::unique_ptr<PressureSolver> make_pressure_solver(PressureSolverKind kind, const PressureSolverParams& params) {
  switch (kind) {
    case PressureSolverKind::kEigenDirect:
      return std::make_unique<detail::EigenDirectPressureSolver>();
    case PressureSolverKind::kMultigridCG:
      return std::make_unique<detail::MultigridCGPressureSolver>(params);
  }
  throw std::invalid_argument("kind = " + std::to_string(static_cast<int>(kind)) +
                              " is outside the allowed range {0 (kEigenDirect), 1 (kMultigridCG)}");
}

void pressure_residual(const Grid2D& grid, const PressureProblem& problem, const std::vector<double>& rhs,
                       const std::vector<double>& p, std::vector<double>& residual) {
  detail::PressureSystem sys;
  sys.build(grid, problem);
  if (p.size() != static_cast<std::size_t>(grid.ncell()))
    throw std::invalid_argument("p has size " + std::to_string(p.size()) + ", expected " +
                                std::to_string(grid.ncell()));
  // b - A p = -(f - M p) with the unprojected f = g - b
  std::vector<double> f;
  sys.source(rhs, f, false);
  sys.residual(f, p, residual);
  for (double& r : residual) r = -r;
}

}  // namespace vofdem
