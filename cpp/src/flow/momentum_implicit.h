// The implicit viscous solves' internals shared by momentum.cpp and momentum_implicit.cpp.
#pragma once

#include <vector>

#include "vofdem/flow/momentum.h"

namespace vofdem {

// whether the end corners of a z-face row carry the ghost -w of corner_shear (inlet, no-slip wall),
// not overwritten by a wall function's shear: the part the row solves of w take implicitly
inline bool left_w_ghost(const MomentumFields& f, const MomentumBoundary& bc) {
  return (bc.left_inlet || bc.no_slip) && !(f.face_x_wall_shear && !bc.left_inlet);
}
inline bool right_w_ghost(const MomentumFields& f, const MomentumBoundary& bc) {
  return !bc.right_open && bc.no_slip && !f.face_x_wall_shear;
}

// terms.implicit_horizontal: the rows, then the columns of u from s.stressed_u (u^n plus its explicit
// cross term); the w-equation's cross term then taken from the new u rather than u^n (block
// Gauss-Seidel; with u^n, the product (I - dt Z)^-1 (I - dt H)^-1 (I + dt C) u^n, the step's norm in the
// kinetic energy is 1.84, 3.39, 5.78 at 1, 3, 10 times the split scheme's limit, against 1.00, 1.00,
// 1.63 so: test_viscous_implicit.cpp); then the rows and columns of w from s.stressed_w. Adds each
// solve's increment to u*, w*
void implicit_rows_and_columns(const Grid2D& g, const MomentumFields& f, const MomentumBoundary& bc, double dt,
                               std::vector<double>& u_star, std::vector<double>& w_star, MomentumScratch& s);

}  // namespace vofdem
