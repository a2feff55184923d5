// The implicit parts of the viscous stresses (momentum.h): backward Euler of the vertical diffusion by
// one tridiagonal solve per column, of the horizontal diffusion by one per row, and their ordering
// with the explicit cross terms.
#include "flow/momentum_implicit.h"

#include <cstddef>

#include "common/parallel.h"

namespace vofdem {

namespace {

// one row of the vertical diffusion's systems (the open neighbours not yet checked): r = dt / (rho h),
// lo = c_lo mu_lo / h_lo, up = c_up mu_up / h_up; diagonal 1 + r (lo + up) on an open face (1 on a
// closed one), below -r lo, above -r up, right-hand side v. The arrays never overlap (restrict: GCC
// vectorises no loop that needs this many overlap checks)
struct DiffusionRowScales {
  double dt, h, lo_c, lo_h, up_c, up_h;
};
void diffusion_row(int i0, int i1, const DiffusionRowScales& q, const double* __restrict rho,
                   const double* __restrict mu_lo, const double* __restrict mu_up, const double* __restrict n,
                   const double* __restrict v, double* __restrict a, double* __restrict b, double* __restrict c,
                   double* __restrict d) {
  const double dt = q.dt, h = q.h, lo_c = q.lo_c, lo_h = q.lo_h, up_c = q.up_c, up_h = q.up_h;
  for (int i = i0; i < i1; ++i) {
    const double r = dt / (rho[i] * h);
    const double lo = lo_c * mu_lo[i] / lo_h, up = up_c * mu_up[i] / up_h;
    b[i] = n[i] > 0.0 ? 1.0 + r * (lo + up) : 1.0;
    a[i] = -r * lo;
    c[i] = -r * up;
    d[i] = v[i];
  }
}

// a row's sub- and superdiagonal kept where the face and its neighbour below / above are open, else 0
// (a closed face's row is the identity, a closed neighbour a known zero). A loop of its own: with the
// assembly's select on the face alone in the same loop, GCC 12 finds control flow and vectorises neither
void keep_open_neighbours(int i0, int i1, bool has_lo, bool has_up, const double* n, const double* n_lo,
                          const double* n_up, double* a, double* c) {
  for (int i = i0; i < i1; ++i) {
    const bool open = n[i] > 0.0;
    const double below = a[i], above = c[i];
    a[i] = open & has_lo & (n_lo[i] > 0.0) ? below : 0.0;
    c[i] = open & has_up & (n_up[i] > 0.0) ? above : 0.0;
  }
}

// the tridiagonal work arrays, (nx + 1) x (nz + 1) row-major (row k of column i at i + (nx + 1) k)
void size_systems(const Grid2D& g, MomentumScratch& s) {
  const std::size_t size = static_cast<std::size_t>(g.nx() + 1) * (g.nz() + 1);
  s.tri_a.resize(size), s.tri_b.resize(size), s.tri_c.resize(size), s.tri_d.resize(size);
}

// the columns of u (implicit_vertical_diffusion); leaves v in s.tri_d at each x-face's own index
void vertical_u(const Grid2D& g, const MomentumFields& f, const MomentumBoundary& bc, double dt, const double* u0,
                std::vector<double>& u_star, MomentumScratch& s) {
  const int nx = g.nx(), nz = g.nz(), sx = nx + 1;
  // the systems of all columns solved together row by row: the same operations per column as
  // solve_tridiagonal, in an order the compiler can vectorise
  size_systems(g, s);
  double *a = s.tri_a.data(), *b = s.tri_b.data(), *c = s.tri_c.data(), *d = s.tri_d.data();
  const bool bed_no_slip = bc.no_slip && !f.face_z_wall_shear;
  // u on the interior x-faces i = 1..nx-1: rows k = 0..nz-1, stress-free top, no-slip bed (ghost -u) or wall shear.
  // A closed face's row is the identity (it stays 0); a closed neighbour is a known zero, its coefficient
  // drops out. Each face's values computed, then selected (no branch; the same values)
  detail::parallel_for(nz, sx, [&, dt](int k0, int k1) {
    for (int k = k0; k < k1; ++k) {
      const double dz_lo = k > 0 ? g.z_center(k) - g.z_center(k - 1) : 0.0;
      const double dz_up = k < nz - 1 ? g.z_center(k + 1) - g.z_center(k) : 0.0;
      const double dzk = g.dz(k);
      const bool has_lo = k > 0, has_up = k < nz - 1;
      // lo = c mu / h below and above (the same operations as mu / h, 2 mu / dz0 on a no-slip bed, or 0)
      const double lo_c = has_lo ? 1.0 : (bed_no_slip ? 2.0 : 0.0), lo_h = has_lo ? dz_lo : g.dz(0);
      const double up_c = has_up ? 1.0 : 0.0, up_h = has_up ? dz_up : 1.0;
      const double* n = f.face_x_porosity + sx * k;
      const double* n_lo = has_lo ? n - sx : n;  // unused on the bed row
      const double* n_up = has_up ? n + sx : n;  // unused on the top row
      const double* mu_lo = s.corner_mu.data() + sx * k;
      const double* mu_up = s.corner_mu.data() + sx * (has_up ? k + 1 : k);
      const double* rho = f.face_x_rho + sx * k;
      const double* u = u0 + sx * k;
      const std::size_t row = static_cast<std::size_t>(sx) * k;
      diffusion_row(1, nx, {dt, dzk, lo_c, lo_h, up_c, up_h}, rho, mu_lo, mu_up, n, u, a + row, b + row, c + row,
                    d + row);
      keep_open_neighbours(1, nx, has_lo, has_up, n, n_lo, n_up, a + row, c + row);
    }
  });
  solve_tridiagonal_rows(nz, 1, nx, sx, a, b, c, d);
  detail::parallel_for(nz, sx, [&](int k0, int k1) {
    for (int k = k0; k < k1; ++k) {
      for (int i = 1; i < nx; ++i) {
        const int j = i + sx * k;
        const double old = u_star[j], diffused = old + (d[j] - u0[j]);
        u_star[j] = f.face_x_porosity[j] > 0.0 ? diffused : old;
      }
    }
  });
}

// the columns of w (implicit_vertical_diffusion)
void vertical_w(const Grid2D& g, const MomentumFields& f, double dt, const double* w0, std::vector<double>& w_star,
                MomentumScratch& s) {
  const int nx = g.nx(), nz = g.nz(), sx = nx + 1;
  size_systems(g, s);
  double *a = s.tri_a.data(), *b = s.tri_b.data(), *c = s.tri_c.data(), *d = s.tri_d.data();
  // w on the interior z-faces k = 1..nz-1 (system row k - 1); bed w = 0 and the top face's w^n are known
  if (nz < 2) return;
  const int m = nz - 1;
  detail::parallel_for(nz - 1, nx, [&, dt](int k0, int k1) {
    for (int k = k0 + 1; k <= k1; ++k) {
      const double dzc = g.z_center(k) - g.z_center(k - 1);
      const double dz_lo = g.dz(k - 1), dz_up = g.dz(k);
      const bool has_lo = k > 1, top = k == nz - 1;
      const double* n = f.face_z_porosity + nx * k;
      const double* n_lo = n - nx;
      const double* n_up = top ? n : n + nx;  // unused on the top row
      const double* mu_lo = f.cell_mu + nx * (k - 1);
      const double* mu_up = f.cell_mu + nx * k;
      const double* rho = f.face_z_rho + nx * k;
      const double* w = w0 + nx * k;
      const double* w_top = f.face_w + nx * (k + 1);  // the top face's w^n, known (0 under a lid)
      const std::size_t row = static_cast<std::size_t>(sx) * (k - 1);
      diffusion_row(0, nx, {dt, dzc, 2.0, dz_lo, 2.0, dz_up}, rho, mu_lo, mu_up, n, w, a + row, b + row, c + row,
                    d + row);
      // an open top row: the top face's w^n is known, w + r up w_top (c = -r up, not yet dropped)
      if (top)
        for (int i = 0; i < nx; ++i) d[row + i] = n[i] > 0.0 ? w[i] - c[row + i] * w_top[i] : w[i];
      keep_open_neighbours(0, nx, has_lo, !top, n, n_lo, n_up, a + row, c + row);
    }
  });
  solve_tridiagonal_rows(m, 0, nx, sx, a, b, c, d);
  detail::parallel_for(nz - 1, nx, [&](int k0, int k1) {
    for (int k = k0 + 1; k <= k1; ++k) {
      for (int i = 0; i < nx; ++i) {
        const int j = i + nx * k;
        const double old = w_star[j], diffused = old + (d[i + sx * (k - 1)] - w0[j]);
        w_star[j] = f.face_z_porosity[j] > 0.0 ? diffused : old;
      }
    }
  });
}

// The rows' systems are stored transposed, position p of system q at q + (number of systems) p, and
// solved together by solve_tridiagonal_rows: the same operations per row as solve_tridiagonal, with
// the rows' independent recurrences interleaved (one row's Thomas sweep waits on each division)

// the rows of u (implicit_row_diffusion): interior x-faces i = 1..nx-1 of each row k (system k), the
// end faces' u^n known (moved to the right side); writes s.rowed_u
void row_u(const Grid2D& g, const MomentumFields& f, double dt, const double* u0, std::vector<double>& u_star,
           MomentumScratch& s) {
  const int nx = g.nx(), nz = g.nz(), sx = nx + 1;
  const double inv_dx = 1.0 / g.dx();
  size_systems(g, s);
  s.rowed_u.assign(u0, u0 + g.nface_x());
  if (nx < 2) return;
  double *a = s.tri_a.data(), *b = s.tri_b.data(), *c = s.tri_c.data(), *d = s.tri_d.data();
  const double* n = f.face_x_porosity;
  detail::parallel_for(nx - 1, nz, [&, dt, inv_dx](int i0, int i1) {
    for (int i = i0 + 1; i <= i1; ++i) {
      for (int k = 0; k < nz; ++k) {
        const int j = i + sx * k, q = k + nz * i, cell = i + nx * k;  // cell right of face j; cell - 1 left
        const double r = dt * inv_dx / f.face_x_rho[j];
        const double lo = r * 2.0 * f.cell_mu[cell - 1] * inv_dx, up = r * 2.0 * f.cell_mu[cell] * inv_dx;
        const bool open = n[j] > 0.0;
        b[q] = open ? 1.0 + lo + up : 1.0;
        a[q] = open && n[j - 1] > 0.0 ? -lo : 0.0;
        c[q] = open && n[j + 1] > 0.0 ? -up : 0.0;
        d[q] = u0[j];
      }
    }
  });
  for (int k = 0; k < nz; ++k) {
    d[k + nz] -= a[k + nz] * f.face_u[sx * k];
    d[k + nz * (nx - 1)] -= c[k + nz * (nx - 1)] * f.face_u[nx + sx * k];
  }
  solve_tridiagonal_rows(nx - 1, 0, nz, nz, a + nz, b + nz, c + nz, d + nz);
  detail::parallel_for(nz, sx, [&](int k0, int k1) {
    for (int k = k0; k < k1; ++k) {
      for (int i = 1; i < nx; ++i) {
        const int j = i + sx * k;
        if (n[j] <= 0.0) continue;
        const double v = d[k + nz * i];
        s.rowed_u[j] = v;
        u_star[j] += v - u0[j];
      }
    }
  });
}

// the rows of w (implicit_row_diffusion): z-faces i = 0..nx-1 of the interior rows k (system k - 1);
// an end corner's ghost -w (corner_shear) adds to the diagonal, a stress-free end nothing; writes s.rowed_w
void row_w(const Grid2D& g, const MomentumFields& f, const MomentumBoundary& bc, double dt, const double* w0,
           std::vector<double>& w_star, MomentumScratch& s) {
  const int nx = g.nx(), nz = g.nz(), sx = nx + 1, m = nz - 1;
  const double inv_dx = 1.0 / g.dx();
  size_systems(g, s);
  s.rowed_w.assign(w0, w0 + g.nface_z());
  if (m < 1) return;
  double *a = s.tri_a.data(), *b = s.tri_b.data(), *c = s.tri_c.data(), *d = s.tri_d.data();
  const double* n = f.face_z_porosity;
  const double cl0 = left_w_ghost(f, bc) ? 2.0 : 0.0, cu1 = right_w_ghost(f, bc) ? 2.0 : 0.0;
  detail::parallel_for(nx, nz, [&, dt, inv_dx, cl0, cu1](int i0, int i1) {
    for (int i = i0; i < i1; ++i) {
      const double cl = i > 0 ? 1.0 : cl0, cu = i < nx - 1 ? 1.0 : cu1;
      for (int k = 1; k < nz; ++k) {
        const int j = i + nx * k, q = k - 1 + m * i, corner = i + sx * k;  // the corners left and right: corner, + 1
        const double r = dt * inv_dx / f.face_z_rho[j];
        const double lo = r * cl * s.corner_mu[corner] * inv_dx, up = r * cu * s.corner_mu[corner + 1] * inv_dx;
        const bool open = n[j] > 0.0;
        b[q] = open ? 1.0 + lo + up : 1.0;
        a[q] = open && i > 0 && n[j - 1] > 0.0 ? -lo : 0.0;
        c[q] = open && i < nx - 1 && n[j + 1] > 0.0 ? -up : 0.0;
        d[q] = w0[j];
      }
    }
  });
  solve_tridiagonal_rows(nx, 0, m, m, a, b, c, d);
  detail::parallel_for(nz - 1, nx, [&](int k0, int k1) {
    for (int k = k0 + 1; k <= k1; ++k) {
      for (int i = 0; i < nx; ++i) {
        const int j = i + nx * k;
        if (n[j] <= 0.0) continue;
        const double v = d[k - 1 + m * i];
        s.rowed_w[j] = v;
        w_star[j] += v - w0[j];
      }
    }
  });
}

// the w-equation's cross term d/dx(mu du/dz) moved from u^n to the new u (the u-solves' v in s.tri_d
// at each x-face's index): dt d/dx(mu d/dz (v - u^n)) / rho added to w* and to the rows' start s.stressed_w
// on open interior z-faces. End corners keep u^n's: their end faces are not solved (v = u^n there)
void cross_term_from_new_u(const Grid2D& g, const MomentumFields& f, double dt, std::vector<double>& w_star,
                           MomentumScratch& s) {
  const int nx = g.nx(), nz = g.nz(), sx = nx + 1;
  const double inv_dx = 1.0 / g.dx();
  const double* v = s.tri_d.data();
  double* corner = s.corner_tau_w.data();  // reused row by row: the explicit part is already applied
  detail::parallel_for(nz - 1, sx, [&, dt, inv_dx](int k0, int k1) {
    for (int k = k0 + 1; k <= k1; ++k) {
      const double inv_dzc = 1.0 / (g.z_center(k) - g.z_center(k - 1));
      const double* cm = s.corner_mu.data() + sx * k;
      const double* u0 = f.face_u + sx * (k - 1);
      const double* u1 = f.face_u + sx * k;
      const double* v0 = v + sx * (k - 1);
      const double* v1 = v + sx * k;
      const double* n0 = f.face_x_porosity + sx * (k - 1);
      const double* n1 = f.face_x_porosity + sx * k;
      double* t = corner + sx * k;
      t[0] = t[nx] = 0.0;
      for (int ii = 1; ii < nx; ++ii) {
        const double d1 = n1[ii] > 0.0 ? v1[ii] - u1[ii] : 0.0, d0 = n0[ii] > 0.0 ? v0[ii] - u0[ii] : 0.0;
        t[ii] = cm[ii] * (d1 - d0) * inv_dzc;
      }
      const double* n = f.face_z_porosity + nx * k;
      const double* rho = f.face_z_rho + nx * k;
      for (int i = 0; i < nx; ++i) {
        if (n[i] <= 0.0) continue;
        const double dw = dt * (t[i + 1] - t[i]) * inv_dx / rho[i];
        w_star[i + nx * k] += dw;
        s.stressed_w[i + nx * k] += dw;
      }
    }
  });
}

}  // namespace

// backward Euler of the vertical diffusion, column by column, after the explicit stresses:
// (I - dt/rho d/dz mu d/dz) v = u0, u* += v - u0, u0 = u^n + dt (explicit viscous term). Diffusing u0
// rather than u* keeps the gravity increment (balanced by the pressure only afterwards) out of the
// viscous stress, so still water stays still. Closed faces stay 0 and act as u = 0 neighbours, as in
// the explicit stencil
void implicit_vertical_diffusion(const Grid2D& g, const MomentumFields& f, const MomentumBoundary& bc, double dt,
                                 const double* u0, const double* w0, std::vector<double>& u_star,
                                 std::vector<double>& w_star, MomentumScratch& s) {
  vertical_u(g, f, bc, dt, u0, u_star, s);
  vertical_w(g, f, dt, w0, w_star, s);
}

// backward Euler of the horizontal diffusion, row by row, after the explicit cross terms (momentum.h)
void implicit_row_diffusion(const Grid2D& g, const MomentumFields& f, const MomentumBoundary& bc, double dt,
                            const double* u0, const double* w0, std::vector<double>& u_star,
                            std::vector<double>& w_star, MomentumScratch& s) {
  row_u(g, f, dt, u0, u_star, s);
  row_w(g, f, bc, dt, w0, w_star, s);
}

void implicit_rows_and_columns(const Grid2D& g, const MomentumFields& f, const MomentumBoundary& bc, double dt,
                               std::vector<double>& u_star, std::vector<double>& w_star, MomentumScratch& s) {
  row_u(g, f, dt, s.stressed_u.data(), u_star, s);
  vertical_u(g, f, bc, dt, s.rowed_u.data(), u_star, s);
  cross_term_from_new_u(g, f, dt, w_star, s);
  row_w(g, f, bc, dt, s.stressed_w.data(), w_star, s);
  vertical_w(g, f, dt, s.rowed_w.data(), w_star, s);
}

namespace {

// solve_tridiagonal_rows on the columns [i0, i1) of one thread
void solve_tridiagonal_piece(int m, int i0, int i1, int stride, const double* a, double* b, const double* c,
                             double* d) {
  for (int k = 1; k < m; ++k) {
    const int r = stride * k, p = r - stride;
    for (int i = i0; i < i1; ++i) {
      const double q = a[r + i] / b[p + i];
      b[r + i] -= q * c[p + i];
      d[r + i] -= q * d[p + i];
    }
  }
  const int last = stride * (m - 1);
  for (int i = i0; i < i1; ++i) d[last + i] /= b[last + i];
  for (int k = m - 2; k >= 0; --k) {
    const int r = stride * k, n = r + stride;
    for (int i = i0; i < i1; ++i) d[r + i] = (d[r + i] - c[r + i] * d[n + i]) / b[r + i];
  }
}

}  // namespace

// the columns split over the threads: each column's recurrence stays on one
void solve_tridiagonal_rows(int m, int i0, int i1, int stride, const double* a, double* b, const double* c,
                            double* d) {
  detail::parallel_for(i1 - i0, m, [&](int p0, int p1) {
    solve_tridiagonal_piece(m, i0 + p0, i0 + p1, stride, a, b, c, d);
  });
}

void solve_tridiagonal(int m, const double* a, double* b, const double* c, double* d) {
  for (int k = 1; k < m; ++k) {
    const double q = a[k] / b[k - 1];
    b[k] -= q * c[k - 1];
    d[k] -= q * d[k - 1];
  }
  d[m - 1] /= b[m - 1];
  for (int k = m - 2; k >= 0; --k) d[k] = (d[k] - c[k] * d[k + 1]) / b[k];
}

}  // namespace vofdem
