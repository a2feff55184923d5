#include "flow/multigrid.h"

#include <algorithm>
#include <stdexcept>

#include "common/parallel.h"

namespace vofdem::detail {

namespace {

void size_level(MultigridLevel& lv, int nx, int nz) {
  lv.nx = nx;
  lv.nz = nz;
  lv.w = nx + 2;
  const std::size_t n = static_cast<std::size_t>(lv.size());
  for (auto* v : {&lv.west, &lv.south, &lv.diag, &lv.inv, &lv.up, &lv.mask, &lv.x, &lv.b}) v->assign(n, 0.0);
}

// diagonal and mask of a level from its faces
void finish_level(MultigridLevel& lv) {
  const int w = lv.w;
  parallel_for(lv.nz, lv.nx, [&](int k0, int k1) {
    for (int k = k0; k < k1; ++k)
      for (int i = 0; i < lv.nx; ++i) {
        const int c = lv.index(i, k);
        lv.diag[c] = lv.west[c] + lv.west[c + 1] + lv.south[c] + lv.south[c + w];
        lv.mask[c] = lv.diag[c] > 0.0 ? 1.0 : 0.0;
      }
  });
}

// the first fine row whose parent row is at least kc (parent rows never decrease)
int first_child_row(const MultigridLevel& f, int kc) {
  int k = 0;
  while (k < f.nz && f.parent_k[k] < kc) ++k;
  return k;
}

}  // namespace

void Multigrid::allocate(int nx, int nz, const PressureSolverParams& params) {
  sweeps_ = params.smoothing_sweeps;
  scale_ = params.coarse_correction_scale;
  levels_.clear();
  levels_.emplace_back();
  size_level(levels_.back(), nx, nz);
  // the fine level works on the caller's vectors (apply)
  levels_.back().x = std::vector<double>();
  levels_.back().b = std::vector<double>();
  while (true) {
    MultigridLevel& f = levels_.back();
    if (f.nx * f.nz <= params.coarsest_cells || (f.nx == 1 && f.nz == 1)) break;
    const int nxc = std::max(1, f.nx / 2), nzc = std::max(1, f.nz / 2);
    f.parent_i.resize(f.nx);
    f.parent_k.resize(f.nz);
    for (int i = 0; i < f.nx; ++i) f.parent_i[i] = std::min(i / 2, nxc - 1);
    for (int k = 0; k < f.nz; ++k) f.parent_k[k] = std::min(k / 2, nzc - 1);
    MultigridLevel c;
    size_level(c, nxc, nzc);
    levels_.push_back(std::move(c));
  }
  const MultigridLevel& last = levels_.back();
  const int n = last.nx * last.nz;
  row_.assign(nx + 2, 0.0);
  coarse_matrix_.resize(n, n);
  coarse_rhs_.resize(n);
  coarse_group_.assign(n, -1);
  coarse_stack_.reserve(n);
}

void Multigrid::setup(const std::vector<double>& ax, const std::vector<double>& az,
                      const std::vector<std::uint8_t>& active) {
  MultigridLevel& f = levels_[0];
  const int nx = f.nx, nz = f.nz;
  parallel_for(nz + 1, nx, [&](int k0, int k1) {
    for (int k = k0; k < k1; ++k) {
      if (k < nz)
        for (int i = 0; i <= nx; ++i) f.west[f.index(i, k)] = ax[i + (nx + 1) * k];
      for (int i = 0; i < nx; ++i) f.south[f.index(i, k)] = az[i + nx * k];
    }
  });
  finish_level(f);
  parallel_for(nz, nx, [&](int k0, int k1) {
    for (int k = k0; k < k1; ++k)
      for (int i = 0; i < nx; ++i)
        if (!active[i + nx * k]) f.mask[f.index(i, k)] = 0.0;
  });
  for (std::size_t l = 0; l + 1 < levels_.size(); ++l) {
    factor_lines(levels_[l]);
    galerkin(levels_[l], levels_[l + 1]);
  }
  factor_coarsest();
}

void Multigrid::galerkin(const MultigridLevel& f, MultigridLevel& c) {
  std::fill(c.west.begin(), c.west.end(), 0.0);
  std::fill(c.south.begin(), c.south.end(), 0.0);
  // a fine face is a coarse face where it separates two parents (or lies on the boundary); each coarse
  // row sums its fine rows in their order (one thread per coarse row: the same sums for any count)
  parallel_for(c.nz, f.nx * 2, [&](int kc0, int kc1) {
    const int k1 = kc1 == c.nz ? f.nz : first_child_row(f, kc1);
    for (int k = first_child_row(f, kc0); k < k1; ++k) {
      const int kc = f.parent_k[k];
      for (int i = 0; i <= f.nx; ++i) {
        int ic;
        if (i == f.nx)
          ic = c.nx;
        else if (i == 0 || f.parent_i[i] != f.parent_i[i - 1])
          ic = f.parent_i[i];
        else
          continue;
        c.west[c.index(ic, kc)] += f.west[f.index(i, k)];
      }
    }
  });
  // one fine face row per coarse face row
  parallel_for(f.nz + 1, f.nx, [&](int k0, int k1) {
    for (int k = k0; k < k1; ++k) {
      int kc;
      if (k == f.nz)
        kc = c.nz;
      else if (k == 0 || f.parent_k[k] != f.parent_k[k - 1])
        kc = f.parent_k[k];
      else
        continue;
      for (int i = 0; i < f.nx; ++i) c.south[c.index(f.parent_i[i], kc)] += f.south[f.index(i, k)];
    }
  });
  finish_level(c);
}

void Multigrid::factor_lines(MultigridLevel& lv) {
  // lines along the stronger coupling: compare the total x and z coefficients of the interior faces
  double sum_x = 0.0, sum_z = 0.0;
  for (int k = 0; k < lv.nz; ++k)
    for (int i = 0; i < lv.nx; ++i) {
      const int c = lv.index(i, k);
      if (i > 0) sum_x += lv.west[c];
      if (k > 0) sum_z += lv.south[c];
    }
  lv.x_lines = sum_x > sum_z;
  // Thomas factors of each line's tridiagonal block: pivot_j = d_j - a_j up_{j-1}, up_j = a_{j+1} / pivot_j,
  // with a the coefficients of the faces along the line. Dead cells (mask 0) get inv = up = 0; a line
  // segment coupled to nothing else is singular, its last pivot vanishes: keeping d there is a
  // symmetric positive definite approximation of the block (the smoother stays convergent)
  const int w = lv.w, nx = lv.nx, nz = lv.nz;
  double *inv = lv.inv.data(), *up = lv.up.data();
  const double *d = lv.diag.data(), *m = lv.mask.data();
  if (!lv.x_lines) {
    // row by row, the columns of a thread's piece at once (up of the ghost row below is 0)
    const double* a = lv.south.data();
    parallel_for(nx, nz, [&](int i0, int i1) {
      for (int k = 0; k < nz; ++k) {
        const int row = w * (k + 1) + 1;
        const bool top = k + 1 == nz;
        for (int c = row + i0; c < row + i1; ++c) {
          double pivot = d[c] - a[c] * up[c - w];
          const double dc = d[c] > 0.0 ? d[c] : 1.0;
          if (!(pivot >= 1e-10 * dc)) pivot = dc;
          const double iv = m[c] != 0.0 ? 1.0 / pivot : 0.0;
          inv[c] = iv;
          up[c] = top ? 0.0 : a[c + w] * iv;
        }
      }
    });
    return;
  }
  const double* a = lv.west.data();
  parallel_for(nz, nx, [&](int k0, int k1) {
    for (int k = k0; k < k1; ++k) {
      const int row = w * (k + 1) + 1;
      double up_before = 0.0;
      for (int i = 0; i < nx; ++i) {
        const int c = row + i;
        double pivot = d[c] - a[c] * up_before;
        const double dc = d[c] > 0.0 ? d[c] : 1.0;
        if (!(pivot >= 1e-10 * dc)) pivot = dc;
        const double iv = m[c] != 0.0 ? 1.0 / pivot : 0.0;
        inv[c] = iv;
        up[c] = i + 1 < nx ? a[c + 1] * iv : 0.0;
        up_before = up[c];
      }
    }
  });
}

void Multigrid::factor_coarsest() {
  const MultigridLevel& lv = levels_.back();
  const int nx = lv.nx, nz = lv.nz, n = nx * nz, w = lv.w;
  coarse_matrix_.setZero();
  for (int k = 0; k < nz; ++k)
    for (int i = 0; i < nx; ++i) {
      const int j = i + nx * k, c = lv.index(i, k);
      if (lv.mask[c] == 0.0) {
        coarse_matrix_(j, j) = 1.0;
        continue;
      }
      coarse_matrix_(j, j) = lv.diag[c];
      if (i > 0 && lv.mask[c - 1] != 0.0) coarse_matrix_(j, j - 1) = -lv.west[c];
      if (i + 1 < nx && lv.mask[c + 1] != 0.0) coarse_matrix_(j, j + 1) = -lv.west[c + 1];
      if (k > 0 && lv.mask[c - w] != 0.0) coarse_matrix_(j, j - nx) = -lv.south[c];
      if (k + 1 < nz && lv.mask[c + w] != 0.0) coarse_matrix_(j, j + nx) = -lv.south[c + w];
    }
  // pin one cell of every group without a Dirichlet face (its block is singular)
  std::fill(coarse_group_.begin(), coarse_group_.end(), -1);
  for (int seed = 0; seed < n; ++seed) {
    if (coarse_group_[seed] >= 0 || lv.mask[lv.index(seed % nx, seed / nx)] == 0.0) continue;
    bool dirichlet = false;
    coarse_stack_.assign(1, seed);
    coarse_group_[seed] = seed;
    while (!coarse_stack_.empty()) {
      const int j = coarse_stack_.back();
      coarse_stack_.pop_back();
      const int i = j % nx, k = j / nx, c = lv.index(i, k);
      if ((i == 0 && lv.west[c] > 0) || (i == nx - 1 && lv.west[c + 1] > 0) || (k == 0 && lv.south[c] > 0) ||
          (k == nz - 1 && lv.south[c + w] > 0))
        dirichlet = true;
      auto visit = [&](bool open, int nb) {
        if (open && coarse_group_[nb] < 0) {
          coarse_group_[nb] = seed;
          coarse_stack_.push_back(nb);
        }
      };
      visit(i > 0 && lv.west[c] > 0, j - 1);
      visit(i + 1 < nx && lv.west[c + 1] > 0, j + 1);
      visit(k > 0 && lv.south[c] > 0, j - nx);
      visit(k + 1 < nz && lv.south[c + w] > 0, j + nx);
    }
    if (!dirichlet) coarse_matrix_(seed, seed) *= 2.0;
  }
  coarse_llt_.compute(coarse_matrix_);
  if (coarse_llt_.info() != Eigen::Success)
    throw std::runtime_error("pressure setup (multigrid): coarsest-level Cholesky factorisation failed");
}

void Multigrid::smooth(const MultigridLevel& lv, const double* b, double* x, int parity, bool zero_guess) {
  if (lv.x_lines) {
    smooth_rows(lv, b, x, parity, zero_guess);
    return;
  }
  // block Gauss-Seidel over the columns of one parity: forward elimination, then back substitution;
  // from a zero guess the neighbouring columns hold 0 and are not read. The columns of one parity are
  // independent (they read the other parity's only): a thread takes a piece of them
  const int w = lv.w, nx = lv.nx;
  const double *we = lv.west.data(), *so = lv.south.data(), *inv = lv.inv.data(), *up = lv.up.data();
  parallel_for(nx, lv.nz / 2, [&](int i0, int i1) {
    const int first = i0 + ((i0 & 1) != parity);
    for (int k = 0; k < lv.nz; ++k) {
      const int row = w * (k + 1) + 1;
      if (zero_guess) {
        for (int i = first; i < i1; i += 2) {
          const int c = row + i;
          x[c] = (b[c] + so[c] * x[c - w]) * inv[c];
        }
      } else {
        for (int i = first; i < i1; i += 2) {
          const int c = row + i;
          x[c] = (b[c] + we[c] * x[c - 1] + we[c + 1] * x[c + 1] + so[c] * x[c - w]) * inv[c];
        }
      }
    }
    for (int k = lv.nz - 2; k >= 0; --k) {
      const int row = w * (k + 1) + 1;
      for (int i = first; i < i1; i += 2) {
        const int c = row + i;
        x[c] += up[c] * x[c + w];
      }
    }
  });
}

namespace {

// zebra line relaxation of R rows of one parity together: the rows are independent, and the
// recurrence along each one (a multiply-add's latency per cell) overlaps with the others'. Each value
// is computed by the same operations in the same order as one row alone.
template <int R, bool ZeroGuess>
void relax_rows(const int* row, int nx, int w, const double* b, const double* we, const double* so, const double* inv,
                const double* up, double* x) {
  for (int i = 0; i < nx; ++i) {
    for (int r = 0; r < R; ++r) {
      const int c = row[r] + i;
      if (ZeroGuess) x[c] = (b[c] + we[c] * x[c - 1]) * inv[c];
      else x[c] = (b[c] + so[c] * x[c - w] + so[c + w] * x[c + w] + we[c] * x[c - 1]) * inv[c];
    }
  }
  for (int i = nx - 2; i >= 0; --i)
    for (int r = 0; r < R; ++r) x[row[r] + i] += up[row[r] + i] * x[row[r] + i + 1];
}

template <int R>
void relax_rows(bool zero_guess, const int* row, int nx, int w, const double* b, const double* we, const double* so,
                const double* inv, const double* up, double* x) {
  if (zero_guess) relax_rows<R, true>(row, nx, w, b, we, so, inv, up, x);
  else relax_rows<R, false>(row, nx, w, b, we, so, inv, up, x);
}

}  // namespace

void Multigrid::smooth_rows(const MultigridLevel& lv, const double* b, double* x, int parity, bool zero_guess) {
  // the same over the rows of one parity, for grids coupled more strongly along x; four rows at a time,
  // a thread taking a piece of the rows (row m of the parity: k = parity + 2 m)
  const int w = lv.w, nx = lv.nx;
  const double *we = lv.west.data(), *so = lv.south.data(), *inv = lv.inv.data(), *up = lv.up.data();
  const int rows = (lv.nz - parity + 1) / 2;
  parallel_for(rows, nx / 2, [&](int m0, int m1) {
    int m = m0;
    for (; m + 4 <= m1; m += 4) {
      const int k = parity + 2 * m;
      const int row[4] = {w * (k + 1) + 1, w * (k + 3) + 1, w * (k + 5) + 1, w * (k + 7) + 1};
      relax_rows<4>(zero_guess, row, nx, w, b, we, so, inv, up, x);
    }
    for (; m < m1; ++m) {
      const int row[1] = {w * (parity + 2 * m + 1) + 1};
      relax_rows<1>(zero_guess, row, nx, w, b, we, so, inv, up, x);
    }
  });
}

void Multigrid::restrict_residual(const MultigridLevel& f, const double* b, const double* x, MultigridLevel& c) {
  // residual row by row into a buffer (one per thread), then summed over the 2 (or 3) columns of each
  // parent; a coarse row's fine rows in their order on one thread
  std::fill(c.b.begin(), c.b.end(), 0.0);
  const int w = f.w, nx = f.nx, nxc = c.nx;
  const double *we = f.west.data(), *so = f.south.data(), *d = f.diag.data();
  const int count = loop_threads(c.nz, 2LL * nx);
  if (row_.size() < static_cast<std::size_t>(count) * w) row_.resize(static_cast<std::size_t>(count) * w);
  parallel_team(count, [&](int id, int team) {
    int kc0, kc1;
    piece(c.nz, id, team, kc0, kc1);
    if (kc0 >= kc1) return;
    double* res = row_.data() + static_cast<std::size_t>(id) * w;
    const int k1 = kc1 == c.nz ? f.nz : first_child_row(f, kc1);
    for (int k = first_child_row(f, kc0); k < k1; ++k) {
      const int row = w * (k + 1) + 1;
      for (int i = 0; i < nx; ++i) {
        const int j = row + i;
        res[i] = b[j] - d[j] * x[j] + we[j] * x[j - 1] + we[j + 1] * x[j + 1] + so[j] * x[j - w] + so[j + w] * x[j + w];
      }
      double* cb = c.b.data() + c.w * (f.parent_k[k] + 1) + 1;
      if (nxc == nx) {
        for (int i = 0; i < nx; ++i) cb[i] += res[i];
      } else {
        for (int ic = 0; ic < nxc; ++ic) cb[ic] += res[2 * ic] + res[2 * ic + 1];
        if (nx % 2) cb[nxc - 1] += res[nx - 1];
      }
    }
  });
}

void Multigrid::prolong(const MultigridLevel& f, double* xf, const MultigridLevel& c) {
  const double sc = scale_;
  const int nx = f.nx, nxc = c.nx;
  parallel_for(f.nz, nx, [&, sc](int k0, int k1) {
    for (int k = k0; k < k1; ++k) {
      double* x = xf + f.w * (k + 1) + 1;
      const double* m = f.mask.data() + f.w * (k + 1) + 1;
      const double* cx = c.x.data() + c.w * (f.parent_k[k] + 1) + 1;
      if (nxc == nx) {
        for (int i = 0; i < nx; ++i) x[i] += sc * m[i] * cx[i];
      } else {
        for (int ic = 0; ic < nxc; ++ic) {
          const double v = sc * cx[ic];
          x[2 * ic] += m[2 * ic] * v;
          x[2 * ic + 1] += m[2 * ic + 1] * v;
        }
        if (nx % 2) x[nx - 1] += sc * m[nx - 1] * cx[nxc - 1];
      }
    }
  });
}

void Multigrid::cycle(int l, const double* b, double* x) {
  const MultigridLevel& lv = levels_[l];
  if (l + 1 == levels()) {
    for (int k = 0; k < lv.nz; ++k)
      for (int i = 0; i < lv.nx; ++i) coarse_rhs_[i + lv.nx * k] = b[lv.index(i, k)] * lv.mask[lv.index(i, k)];
    coarse_llt_.solveInPlace(coarse_rhs_);
    for (int k = 0; k < lv.nz; ++k)
      for (int i = 0; i < lv.nx; ++i) x[lv.index(i, k)] = coarse_rhs_[i + lv.nx * k] * lv.mask[lv.index(i, k)];
    return;
  }
  // the first half-sweep starts from x = 0 (x holds anything before), the rest are full sweeps
  for (int s = 0; s < sweeps_; ++s) {
    smooth(lv, b, x, 0, s == 0);
    smooth(lv, b, x, 1, false);
  }
  MultigridLevel& coarse = levels_[l + 1];
  restrict_residual(lv, b, x, coarse);
  cycle(l + 1, coarse.b.data(), coarse.x.data());
  prolong(lv, x, coarse);
  for (int s = 0; s < sweeps_; ++s) {
    smooth(lv, b, x, 1, false);
    smooth(lv, b, x, 0, false);
  }
}

void Multigrid::apply(const double* r, double* z) { cycle(0, r, z); }

double Multigrid::multiply(const double* x, double* q) const {
  const MultigridLevel& f = levels_[0];
  const int w = f.w, nx = f.nx;
  const double *we = f.west.data(), *so = f.south.data(), *d = f.diag.data();
  auto product_row = [&](int k) {
    const int row = w * (k + 1) + 1;
    for (int j = row; j < row + nx; ++j)
      q[j] = d[j] * x[j] - we[j] * x[j - 1] - we[j + 1] * x[j + 1] - so[j] * x[j - w] - so[j + w] * x[j + w];
  };
  // several threads: the rows of q on them first
  const bool threads = loop_threads(f.nz, nx) > 1;
  if (threads)
    parallel_for(f.nz, nx, [&](int k0, int k1) {
      for (int k = k0; k < k1; ++k) product_row(k);
    });
  // x . q row by row with four partial sums: a single chain of adds waits on their latency; the order
  // is fixed, and one thread keeps it (threads.h). On one thread each row's q right before (in cache)
  double s0 = 0.0, s1 = 0.0, s2 = 0.0, s3 = 0.0;
  for (int k = 0; k < f.nz; ++k) {
    if (!threads) product_row(k);
    const int row = w * (k + 1) + 1;
    int j = row;
    for (; j + 4 <= row + nx; j += 4) {
      s0 += x[j] * q[j];
      s1 += x[j + 1] * q[j + 1];
      s2 += x[j + 2] * q[j + 2];
      s3 += x[j + 3] * q[j + 3];
    }
    for (; j < row + nx; ++j) s0 += x[j] * q[j];
  }
  return (s0 + s1) + (s2 + s3);
}

}  // namespace vofdem::detail
