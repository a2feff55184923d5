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

#include "common/parallel.h"
#include "vofdem/flow/k_epsilon.h"
#include "vofdem/flow/momentum.h"

namespace vofdem {

namespace {

// stable_dt()'s rates [1/s] of one row (u: its x-faces, the other arrays its cells; g_k, g_eps: nx - 1
// work values): the sums of face_coefficients() in the same operations and order (the same bits),
// inactive neighbours' faces and inactive cells 0. A face's diffusion conductance first (the same from
// both sides, as a sum commutes), then the sums by selects without a branch (both loops vectorised);
// the end cells have no neighbour beyond the flume's ends. kLargest (the alternating lines, advection
// alone): the larger of the two faces' rates instead of their sum, each face's Courant number as the
// flow's advective limit takes it (no sum is needed for stability: every face is implicit)
template <bool kAdv, bool kDif, bool kLargest = false>
void lines_row_rates(int nx, double dx, const double* u, const double* n, const double* act, const double* res_k,
                     const double* res_eps, double* g_k, double* g_eps, double* rate) {
  if (kDif)
    for (int i = 0; i + 1 < nx; ++i) {
      g_k[i] = 1.0 / (dx * (res_k[i] + res_k[i + 1]));
      g_eps[i] = 1.0 / (dx * (res_eps[i] + res_eps[i + 1]));
    }
  // the coefficient of a face with inflow vin and conductance g, open or not
  auto coef = [&](double vin, double g, bool open) {
    const double a_adv = kAdv ? std::max(vin, 0.0) / dx : 0.0;
    const double a = kDif ? a_adv + g : a_adv;
    return open ? a : 0.0;
  };
  auto at = [&](int i, double gw_k, double gw_eps, double ge_k, double ge_eps, bool w_open, bool e_open) {
    double sk = 0.0, se = 0.0;
    if (kLargest) {
      static_assert(!kLargest || !kDif, "the largest face's rate is the advection's alone");
      sk = std::max(coef(u[i], 0.0, w_open), coef(-u[i + 1], 0.0, e_open)), se = sk;
    } else {
      sk += coef(u[i], gw_k, w_open), se += coef(u[i], gw_eps, w_open);
      sk += coef(-u[i + 1], ge_k, e_open), se += coef(-u[i + 1], ge_eps, e_open);
    }
    const double r = std::max(sk, se) / n[i];
    return act[i] != 0.0 ? r : 0.0;
  };
  if (nx == 1) {
    rate[0] = at(0, 0.0, 0.0, 0.0, 0.0, false, false);
    return;
  }
  const int e = nx - 1;
  rate[0] = at(0, 0.0, 0.0, g_k[0], g_eps[0], false, act[1] != 0.0);
  for (int i = 1; i < e; ++i)
    rate[i] = at(i, g_k[i - 1], g_eps[i - 1], g_k[i], g_eps[i], act[i - 1] != 0.0, act[i + 1] != 0.0);
  rate[e] = at(e, g_k[e - 1], g_eps[e - 1], 0.0, 0.0, act[e - 1] != 0.0, false);
}

// a cell's row of a tridiagonal system (sub, diagonal, super, rhs) before its assembly: the identity,
// x_c = rhs (a known value, or no change)
void reset_row(std::vector<double>* row, int c, double rhs) {
  row[0][c] = row[2][c] = 0.0;
  row[1][c] = 1.0;
  row[3][c] = rhs;
}

}  // namespace

// row by row (vectorised), the rows' largest taken in order: the first cell at the largest rate
double KEpsilonModel::lines_stable_rate(const std::vector<double>& face_u, const std::vector<double>& cell_porosity,
                                        const std::vector<double>& cell_F, int& cell, bool diffusion) const {
  const int nx = grid_.nx(), nz = grid_.nz(), sx = nx + 1;
  const bool adv = (params_.flags & kKEpsAdvection) != 0u;
  const bool dif = diffusion && (params_.flags & kKEpsDiffusion) != 0u;
  // the alternating lines (diffusion false) bound each face's advection alone, as the flow's CFL does
  auto row_rates = adv ? (dif ? lines_row_rates<true, true> : diffusion ? lines_row_rates<true, false>
                                                                        : lines_row_rates<true, false, true>)
                       : (dif ? lines_row_rates<false, true> : lines_row_rates<false, false>);
  const double dx = grid_.dx(), fmin = params_.water_fraction_min;
  // a row's rates at the start of its buffer, then its cells' activity and its faces' conductances
  row_rate_.resize(std::max(row_rate_.size(), detail::row_maxima_size(nz, 4 * nx)));
  detail::row_maxima(nz, 4 * nx, row_rate_.data(), [&, dx, fmin](int k, double* rate) {
    const int row = nx * k;
    const double* n = cell_porosity.data() + row;
    double* act = rate + nx;
    if (cell_F.empty())
      for (int i = 0; i < nx; ++i) act[i] = n[i] > 0.0 ? 1.0 : 0.0;
    else
      for (int i = 0; i < nx; ++i) act[i] = (n[i] > 0.0) & (cell_F[row + i] >= fmin) ? 1.0 : 0.0;
    // a row of air or solid cells has rates 0 (no water above the surface): nothing to take
    double active = 0.0;
    for (int i = 0; i < nx; ++i) active += act[i];
    if (active == 0.0) return 0;
    row_rates(nx, dx, face_u.data() + sx * k, n, act, half_res_x_[0].data() + row, half_res_x_[1].data() + row,
              rate + 2 * nx, rate + 3 * nx, rate);
    return nx;
  });
  double worst = 0.0;
  cell = -1;
  for (int k = 0; k < nz; ++k)
    if (row_rate_[k] > worst) worst = row_rate_[k], cell = nx * k + static_cast<int>(row_rate_[nz + k]);
  return worst;
}

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
  start_values();
  const std::vector<double>* start[2] = {&scratch_, &scratch_eps_};
  half_cell_resistances(cell_porosity, cell_F, cell_nu);
  // rows on the threads: a cell writes its own rows of the systems and reads the start values only
  detail::parallel_for(nz, nx, [&, dt](int k0, int k1) {
    FaceCoef fc[4];
    for (int k = k0; k < k1; ++k) {
      for (int i = 0; i < nx; ++i) {
        const int c = grid_.cell(i, k);
        for (int e = 0; e < 2; ++e) reset_row(tri_[e], c, (*start[e])[c]);  // a known value unless solved
        if (cell_role_[c] != kSolved) continue;
        face_coefficients(i, k, face_u, face_w, cell_porosity, cell_F, cell_nu, fc);
        const double n = cell_porosity[c];
        const SourceSink ss = source_sink(c, prod_on);
        const double* source = ss.source;
        const double* sink = ss.sink;
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
  });
  for (int e = 0; e < 2; ++e) {
    std::vector<double>* row = tri_[e];
    solve_tridiagonal_rows(nz, 0, nx, nx, row[0].data(), row[1].data(), row[2].data(), row[3].data());
    std::vector<double>& dst = *target[e];
    const double floor_e = floor[e];
    detail::parallel_range(ncell, [&, floor_e](long long c0, long long c1) {
      for (long long c = c0; c < c1; ++c) dst[c] = std::max(row[3][c], floor_e);
    });
  }
}

}  // namespace vofdem

namespace vofdem {

// kAlternatingLines: backward Euler of (K) and (E) with every face implicit, (M + A_x + A_z) x = b,
// approximately factored in delta form (Douglas & Gunn 1964) with the whole diagonal between the passes
// (a diagonally dominant form of the factorisation): with x = x0 + d, the residual of
// the step's start r = b - (M + A_x + A_z) x0 and D = M + D_x + D_z the system's diagonal,
//   (M + D_z + A_x) y = r      one tridiagonal system per row (horizontal faces; the vertical on the diagonal)
//   (M + D_x + A_z) d = D y    one per column (vertical faces; the horizontal on the diagonal)
// M = n/dt + n D (the diagonal: storage and the linearised sink), A_x, A_z: the horizontal and vertical
// faces' coefficients of face_coefficients() (upwind inflow + diffusion; a boundary inflow face or a
// face to a wall cell on the diagonal alone, its value known), D_x, D_z: their sums per cell, A = D - O.
// The product is the backward-Euler matrix plus O_x D^-1 O_z, a weight of at most min(O_x, O_z) between
// diagonal neighbours: bounded by the faces' own coefficients for any dt. With M alone between the
// passes (the classic form, used before) the extra term was A_x M^-1 A_z, which grows as D_z / M ~ dt
// nu_t / dz^2 on thin rows: a cell's row value y, its whole vertical residual over M, ran along its row
// into a neighbour whose column did not take it back (no vertical faces, at the water's front), and k
// doubled there in one step; on the grid four times as fine it grew to 1e216 and eps overflowed
// (docs/k_epsilon.md, "Alternating lines"). A steady state is kept exactly (r = 0, d = 0); a uniform
// decaying field is exact in a single column and lags the point-implicit decay elsewhere, by
// D_x D_z / ((M + D_x)(M + D_z)) of each step's change in an inner cell. Where A_x is small (the paper's
// grid, below the horizontal limit) the scheme is close to the column solves of kVerticalLines with
// their horizontal faces explicit. Both systems are M-matrices, stable for any dt; d is not sign-bound,
// so k and eps are kept at their floors (k_min, eps_min) as every scheme's are.
void KEpsilonModel::solve_transport_alternating(double dt, const std::vector<double>& face_u,
                                                const std::vector<double>& face_w,
                                                const std::vector<double>& cell_porosity,
                                                const std::vector<double>& cell_F, const std::vector<double>& cell_nu) {
  const KEpsilonParams& p = params_;
  const bool prod_on = (p.flags & kKEpsProduction) != 0u;
  const int nx = grid_.nx(), nz = grid_.nz(), ncell = grid_.ncell();
  std::vector<double>* target[2] = {&cell_k, &cell_eps};
  const double floor[2] = {p.k_min, p.eps_min};
  for (int e = 0; e < 2; ++e) {
    for (std::vector<double>& t : tri_[e]) t.resize(static_cast<std::size_t>(ncell));
    row_pass_[e].resize(static_cast<std::size_t>(ncell));
  }
  start_values();
  const std::vector<double>* start[2] = {&scratch_, &scratch_eps_};
  half_cell_resistances(cell_porosity, cell_F, cell_nu);
  // pass 0: the rows' systems for y (sub/super-diagonal: west/east); pass 1: the columns' for d
  for (int pass = 0; pass < 2; ++pass) {
    const bool rows = pass == 0;
    detail::parallel_for(nz, nx, [&, dt, rows](int k0, int k1) {
      FaceCoef fc[4];
      for (int k = k0; k < k1; ++k) {
        for (int i = 0; i < nx; ++i) {
          const int c = grid_.cell(i, k);
          for (int e = 0; e < 2; ++e) reset_row(tri_[e], c, 0.0);  // no change unless solved
          if (cell_role_[c] != kSolved) continue;
          face_coefficients(i, k, face_u, face_w, cell_porosity, cell_F, cell_nu, fc);
          const double n = cell_porosity[c];
          const SourceSink ss = source_sink(c, prod_on);
          const double* source = ss.source;
          const double* sink = ss.sink;
          for (int e = 0; e < 2; ++e) {
            const std::vector<double>& x0 = *start[e];
            std::vector<double>* row = tri_[e];
            const double m = n / dt + n * sink[e];
            // the whole diagonal M + D_x + D_z: each pass holds the other direction's faces on its own
            const double d_x = fc[0].a[e] + fc[1].a[e], d_z = fc[2].a[e] + fc[3].a[e];
            double diag = m + (rows ? d_z : d_x);
            double rhs = rows ? n * (source[e] - sink[e] * x0[c]) : (m + d_x + d_z) * row_pass_[e][c];
            for (int f = 0; f < 4; ++f) {
              const double a = fc[f].a[e];
              if (a == 0.0) continue;
              const int nb = fc[f].nb;
              // the residual: every face at the step's start (rows pass only)
              if (rows) {
                const double x_nb = nb < 0 ? (e == 0 ? inflow_k(fc[f].inflow_u) : inflow_eps(fc[f].inflow_u))
                                           : x0[nb];
                rhs += a * (x_nb - x0[c]);
              }
              if ((f < 2) != rows) continue;  // the other direction's faces: not in this pass's operator
              diag += a;
              if (nb >= 0 && cell_role_[nb] == kSolved) row[(f == 0 || f == 2) ? 0 : 2][c] = -a;
            }
            row[1][c] = diag;
            row[3][c] = rhs;
          }
        }
      }
    });
    for (int e = 0; e < 2; ++e) {
      std::vector<double>* row = tri_[e];
      if (rows) {
        // each row a contiguous system of nx cells
        detail::parallel_for(nz, nx, [&](int k0, int k1) {
          for (int k = k0; k < k1; ++k) {
            const std::size_t o = static_cast<std::size_t>(nx) * k;
            solve_tridiagonal(nx, row[0].data() + o, row[1].data() + o, row[2].data() + o, row[3].data() + o);
          }
        });
        std::vector<double>& y = row_pass_[e];
        detail::parallel_range(ncell, [&](long long c0, long long c1) {
          for (long long c = c0; c < c1; ++c) y[c] = row[3][c];
        });
      } else {
        solve_tridiagonal_rows(nz, 0, nx, nx, row[0].data(), row[1].data(), row[2].data(), row[3].data());
        std::vector<double>& dst = *target[e];
        const std::vector<double>& x0 = *start[e];
        const double floor_e = floor[e];
        detail::parallel_range(ncell, [&, floor_e](long long c0, long long c1) {
          for (long long c = c0; c < c1; ++c) dst[c] = std::max(x0[c] + row[3][c], floor_e);
        });
      }
    }
  }
}

}  // namespace vofdem
