// k-epsilon transport by vertical lines (KEpsilonTimeScheme::kVerticalLines, k_epsilon.h): each
// column's backward-Euler system of (K) and (E) solved exactly, the horizontal faces explicit.
//
//   (n/dt + n D + sum_z a + sum_in a) x_c - a_s x_s - a_n x_n
//       = n x_old/dt + n S + sum_in a x_in + sum_x a (x_nb_old - x_c_old)      (dt sum_x a <= n)
//
// a: the face coefficients of face_coefficients() (upwind inflow + diffusion) [1/s]; z: the vertical
// faces to solved neighbours, whose values are the unknowns of the column; in: boundary inflow faces
// and faces to cells of fixed value (wall cells), taken implicitly with their known value; x: the
// horizontal faces to neighbours, explicit with the values of the step's start. In a cell above the
// horizontal limit (dt sum_x a > n) those faces are lagged-implicit instead: a x_nb_old on the right,
// a on the diagonal. The matrix is an M-matrix (diagonally dominant, positive diagonal, non-positive
// off-diagonals) and the right-hand side is non-negative in both cases, so k and eps stay positive
// for any dt; the vertical diffusion of the eddy viscosity over the thin rows, which bounds the
// point-implicit scheme's step, bounds nothing here. A uniform decaying field and a steady state are
// kept exactly (below the horizontal limit). Thomas algorithm on all columns together
// (solve_tridiagonal_rows, momentum.h), O(ncell).
#include <algorithm>

#include "vofdem/k_epsilon.h"
#include "vofdem/momentum.h"

namespace vofdem {

void KEpsilonModel::solve_transport_lines(double dt, const std::vector<double>& face_u,
                                          const std::vector<double>& face_w, const std::vector<double>& cell_porosity,
                                          const std::vector<double>& cell_F, const std::vector<double>& cell_nu) {
  const KEpsilonParams& p = params_;
  const bool prod_on = (p.flags & kKEpsProduction) != 0u;
  const int nx = grid_.nx(), nz = grid_.nz(), ncell = grid_.ncell();
  std::vector<double>* target[2] = {&cell_k, &cell_eps};
  const double floor[2] = {p.k_min, p.eps_min};
  for (int e = 0; e < 2; ++e)
    for (std::vector<double>& t : tri_[e]) t.resize(static_cast<std::size_t>(ncell));
  // values at the step's start: air/solid cells at the floor, wall cells at the wall-law values, solved
  // cells at their old value (or a freshly wetted cell's start)
  for (int c = 0; c < ncell; ++c) {
    const std::uint8_t role = cell_role_[c];
    scratch_[c] = role == kInactive ? p.k_min : role == kWallFixed ? wall_k_[c] : cell_k[c];
    scratch_eps_[c] = role == kInactive ? p.eps_min : role == kWallFixed ? wall_eps_[c] : cell_eps[c];
  }
  const std::vector<double>* start[2] = {&scratch_, &scratch_eps_};
  half_cell_resistances(cell_porosity, cell_F, cell_nu);
  FaceCoef fc[4];
  for (int k = 0; k < nz; ++k) {
    for (int i = 0; i < nx; ++i) {
      const int c = grid_.cell(i, k);
      for (int e = 0; e < 2; ++e) {
        std::vector<double>* row = tri_[e];
        row[0][c] = row[2][c] = 0.0;
        row[1][c] = 1.0;
        row[3][c] = (*start[e])[c];  // a known value unless solved
      }
      if (cell_role_[c] != kSolved) continue;
      face_coefficients(i, k, face_u, face_w, cell_porosity, cell_F, cell_nu, fc);
      const double n = cell_porosity[c];
      const double rate = eps_old_[c] / k_old_[c];  // 1/s, > 0 by the floors
      const double prod = prod_on ? cell_prod_[c] : 0.0;
      const double source[2] = {prod, p.c1 * rate * prod};
      const double sink[2] = {rate, p.c2 * rate};
      for (int e = 0; e < 2; ++e) {
        const std::vector<double>& x0 = *start[e];
        std::vector<double>* row = tri_[e];
        double diag = n / dt + n * sink[e];
        double rhs = n * x0[c] / dt + n * source[e];
        // horizontal faces: explicit below their own limit, lagged-implicit above
        double ax = 0.0;
        for (int f = 0; f < 2; ++f)
          if (fc[f].nb >= 0) ax += fc[f].a[e];
        const bool explicit_x = dt * ax <= n;
        for (int f = 0; f < 4; ++f) {
          const double a = fc[f].a[e];
          if (a == 0.0) continue;
          const int nb = fc[f].nb;
          if (nb < 0) {  // boundary inflow
            diag += a;
            rhs += a * (e == 0 ? inflow_k(fc[f].inflow_u) : inflow_eps(fc[f].inflow_u));
          } else if (f < 2) {
            if (explicit_x) rhs += a * (x0[nb] - x0[c]);
            else diag += a, rhs += a * x0[nb];
          } else if (cell_role_[nb] != kSolved) {  // a wall cell: known value
            diag += a, rhs += a * x0[nb];
          } else {
            diag += a;
            row[f == 2 ? 0 : 2][c] = -a;
          }
        }
        row[1][c] = diag;
        row[3][c] = rhs;
      }
    }
  }
  for (int e = 0; e < 2; ++e) {
    std::vector<double>* row = tri_[e];
    solve_tridiagonal_rows(nz, 0, nx, nx, row[0].data(), row[1].data(), row[2].data(), row[3].data());
    std::vector<double>& dst = *target[e];
    for (int c = 0; c < ncell; ++c) dst[c] = std::max(row[3][c], floor[e]);
  }
}

}  // namespace vofdem
