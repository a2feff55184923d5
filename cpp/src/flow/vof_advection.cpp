// Geometric (PLIC) VOF advection through a porous medium, seed eq. (4); see vof_advection.h.
//
// One sweep along x updates, for every fluid cell of volume V and porosity n,
//   n V F* = n V F + Phi_left - Phi_right + c dt dz (u_right - u_left),   c = [F^start > 1/2]
// where Phi is the water volume crossing a face in dt (positive along +x): the upwind cell's
// porosity times the water area of its PLIC polygon inside the strip of width |u| dt / n_up next to
// the face. The c term (Weymouth & Yue 2010) cancels over the two sweeps because the discrete
// divergence of (u, w) vanishes, so sum(n F V) changes only by the boundary fluxes.
#include "vofdem/flow/vof_advection.h"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <limits>
#include <mutex>
#include <stdexcept>
#include <string>

#include "common/parallel.h"
#include "vofdem/common/check.h"

namespace vofdem {

namespace {

// area fraction of {m1 x + m2 z <= a} in the unit square, m1, m2 >= 0, m1 + m2 = 1
inline double unit_area(double m1, double m2, double a) {
  if (a <= 0.0) return 0.0;
  if (a >= 1.0) return 1.0;
  const double m = std::min(m1, m2), big = std::max(m1, m2);
  // central symmetry keeps the evaluation in the lower half
  const bool flip = a > 0.5;
  if (flip) a = 1.0 - a;
  // triangle below the first corner, then a trapezoid (big >= 1/2, so no division by zero)
  const double f = a < m ? a * a / (2.0 * m * big) : (a - 0.5 * m) / big;
  return flip ? 1.0 - f : f;
}

// inverse of unit_area for f in [0, 1]
inline double unit_alpha(double m1, double m2, double f) {
  f = std::clamp(f, 0.0, 1.0);
  const double m = std::min(m1, m2), big = std::max(m1, m2);
  const bool flip = f > 0.5;
  if (flip) f = 1.0 - f;
  const double a = 2.0 * big * f < m ? std::sqrt(2.0 * m * big * f) : f * big + 0.5 * m;
  return flip ? 1.0 - a : a;
}

inline double area_below(double mx, double mz, double dx, double dz, double alpha) {
  const double ax = std::abs(mx) * dx, az = std::abs(mz) * dz, s = ax + az;
  // move to the frame where both components are >= 0 (reflections of the rectangle)
  const double a = alpha - std::min(mx, 0.0) * dx - std::min(mz, 0.0) * dz;
  if (!(s > 0.0)) return a >= 0.0 ? dx * dz : 0.0;
  return dx * dz * unit_area(ax / s, az / s, a / s);
}

inline double line_constant(double mx, double mz, double dx, double dz, double f) {
  const double ax = std::abs(mx) * dx, az = std::abs(mz) * dz, s = ax + az;
  if (!(s > 0.0)) return 0.0;
  return s * unit_alpha(ax / s, az / s, f) + std::min(mx, 0.0) * dx + std::min(mz, 0.0) * dz;
}

// fractions this close to 0 or 1 are fluxed as pure cells (no reconstruction); harmless to
// conservation (a flux is a flux) and to boundedness (the flux stays within the cell's water)
constexpr double kPure = 1e-12;

// arguments of a one-directional sweep
struct SweepArgs {
  const Grid2D& g;
  const double* n;
  const double* vel;  // face_u or face_w
  const VofBoundaryInflow& inflow;
  double dt;
  const double* c;
  double* F;              // F at the sweep's start (updated at its end)
  const double* F_below;  // the row below a cell's as its stencil reads it: F, or the rows already swept
  double* flux;           // face_flux_x or face_flux_z
  VofNormal normal;
};

// the clipping report of a thread's cells, added to the scratch's at the end (a count and a largest
// value: the same for any order)
struct ClipReport {
  long long count = 0;
  double max = 0.0;
  void add_to(VofScratch& scratch, std::mutex& lock) const {
    const std::lock_guard<std::mutex> hold(lock);
    scratch.clip_count += count;
    scratch.clip_max = std::max(scratch.clip_max, max);
  }
};

// the 3x3 stencil v[a][b] of F around cell (i, k) (a along x, b along z), the row below from F_below.
// A neighbour outside the domain or solid is replaced by the nearest fluid cell of the stencil along the
// grid lines (zero-gradient ghost), else by the cell itself, so a level surface next to a wall stays level.
void stencil(const Grid2D& g, const double* n, const double* F, const double* F_below, int i, int k,
             double v[3][3]) {
  const int nx = g.nx(), nz = g.nz();
  auto fluid = [&](int ii, int kk) { return ii >= 0 && ii < nx && kk >= 0 && kk < nz && n[g.cell(ii, kk)] > 0.0; };
  for (int b = -1; b <= 1; ++b)
    for (int a = -1; a <= 1; ++a) {
      const int ii = i + a, kk = k + b;
      const double* row_F = b < 0 ? F_below : F;
      double val;
      if (fluid(ii, kk))
        val = row_F[g.cell(ii, kk)];
      else if (fluid(i, kk))
        val = row_F[g.cell(i, kk)];
      else if (fluid(ii, k))
        val = F[g.cell(ii, k)];
      else
        val = F[g.cell(i, k)];
      v[a + 1][b + 1] = val;
    }
}

// row heights below, at and above row k (ghost rows take the cell's own) and centre distances
struct RowGeometry {
  double dzb, dz0, dzt, hb, ht;
  RowGeometry(const Grid2D& g, int k) {
    const int nz = g.nz();
    dz0 = g.dz(k);
    dzb = k > 0 ? g.dz(k - 1) : dz0;
    dzt = k + 1 < nz ? g.dz(k + 1) : dz0;
    hb = 0.5 * (dzb + dz0);
    ht = 0.5 * (dz0 + dzt);
  }
};

// Youngs' normal (pointing out of the water): minus the mean of the four corner gradients of F,
// each from the 2x2 cells around the corner, with the centre distances of non-uniform rows
void youngs(const double v[3][3], double dx, const RowGeometry& r, double& mx, double& mz) {
  // x gradient: lower corners use rows (k-1, k), upper corners rows (k, k+1)
  const double gx = ((v[2][0] + 2.0 * v[2][1] + v[2][2]) - (v[0][0] + 2.0 * v[0][1] + v[0][2])) / (8.0 * dx);
  const double gz = ((v[0][2] + 2.0 * v[1][2] + v[2][2]) - (v[0][1] + 2.0 * v[1][1] + v[2][1])) / (8.0 * r.ht) +
                    ((v[0][1] + 2.0 * v[1][1] + v[2][1]) - (v[0][0] + 2.0 * v[1][0] + v[2][0])) / (8.0 * r.hb);
  mx = -gx;
  mz = -gz;
}

// mixed Youngs-centred normal (Aulisa et al. 2007): of the two height-function normals of the
// 3x3 block, the one with the smaller slope, unless Youngs' normal is steeper relative to the
// same axis (then the height function is not resolved by the block and Youngs' is used)
void mixed_youngs_centered(const double v[3][3], double dx, const RowGeometry& r, double& mx, double& mz) {
  // water heights [m] of the left/right columns and widths [m] of the bottom/top rows
  const double hl = v[0][0] * r.dzb + v[0][1] * r.dz0 + v[0][2] * r.dzt;
  const double hr = v[2][0] * r.dzb + v[2][1] * r.dz0 + v[2][2] * r.dzt;
  const double wb = (v[0][0] + v[1][0] + v[2][0]) * dx, wt = (v[0][2] + v[1][2] + v[2][2]) * dx;
  // slopes [-] of the interface as z(x) and as x(z)
  const double sx = (hl - hr) / (2.0 * dx), sz = (wb - wt) / (r.hb + r.ht);
  double yx, yz;
  youngs(v, dx, r, yx, yz);
  if (std::abs(sx) <= std::abs(sz)) {
    mx = sx;
    mz = wb > wt ? 1.0 : -1.0;  // water below: the normal points up
    if (std::abs(yx) > std::abs(sx) * std::abs(yz)) {
      mx = yx;
      mz = yz;
    }
  } else {
    mx = hl > hr ? 1.0 : -1.0;  // water on the left: the normal points to +x
    mz = sz;
    if (std::abs(yz) > std::abs(sz) * std::abs(yx)) {
      mx = yx;
      mz = yz;
    }
  }
}

// interface normal (pointing out of the water) of cell (i, k)
void interface_normal(const Grid2D& g, const double* n, const double* F, const double* F_below, int i, int k,
                      VofNormal method, double& mx, double& mz) {
  double v[3][3];
  stencil(g, n, F, F_below, i, k, v);
  const RowGeometry r(g, k);
  if (method == VofNormal::kMixedYoungsCentered)
    mixed_youngs_centered(v, g.dx(), r, mx, mz);
  else
    youngs(v, g.dx(), r, mx, mz);
  // a flat stencil gives no direction: a horizontal surface, water below
  if (mx == 0.0 && mz == 0.0) mz = 1.0;
}

// water volumes [m^2 per metre of width] leaving the mixed cell (i, k) in dt through its lower and
// upper face along `dir`, for the outward speeds lo, hi >= 0 (0 = no outflow there): the cell's
// porosity times the area of its PLIC polygon in the strip of width speed dt / n next to the face
void mixed_outflow(const SweepArgs& s, int dir, int i, int k, double lo, double hi, double* out_lo, double* out_hi) {
  const int cell = s.g.cell(i, k);
  const double f = s.F[cell], n = s.n[cell];
  const double dx = s.g.dx(), dz = s.g.dz(k);
  double mx, mz;
  interface_normal(s.g, s.n, s.F, s.F_below, i, k, s.normal, mx, mz);
  const double alpha = line_constant(mx, mz, dx, dz, f);
  const double wlo = lo * s.dt / n, whi = hi * s.dt / n;  // strip widths
  if (dir == 0) {
    *out_lo = lo > 0.0 ? n * area_below(mx, mz, wlo, dz, alpha) : 0.0;
    *out_hi = hi > 0.0 ? n * area_below(mx, mz, whi, dz, alpha - mx * (dx - whi)) : 0.0;
  } else {
    *out_lo = lo > 0.0 ? n * area_below(mx, mz, dx, wlo, alpha) : 0.0;
    *out_hi = hi > 0.0 ? n * area_below(mx, mz, dx, whi, alpha - mz * (dz - whi)) : 0.0;
  }
}

// signed fluxes (along +x or +z) through the lower face `flo` and the upper face `fhi` of cell
// (i, k) of porosity n, fraction f, for the face velocities vlo, vhi and face length len: only
// the faces the cell is upwind of are written (the others stay as set by their upwind cell)
inline void cell_outflows(const SweepArgs& s, int dir, int i, int k, double n, double f, double vlo, double vhi,
                          double len, double* flo, double* fhi) {
  if (!(n > 0.0) || f <= kPure || (vlo >= 0.0 && vhi <= 0.0)) return;
  if (f >= 1.0 - kPure) {
    // a full cell: the whole strip is water
    if (vhi > 0.0) *fhi = vhi * s.dt * len;
    if (vlo < 0.0) *flo = vlo * s.dt * len;
    return;
  }
  double out_lo, out_hi;
  mixed_outflow(s, dir, i, k, std::max(-vlo, 0.0), std::max(vhi, 0.0), &out_lo, &out_hi);
  if (vhi > 0.0) *fhi = out_hi;
  if (vlo < 0.0) *flo = -out_lo;
}

void clip(double& f, ClipReport& report) {
  if (f >= 0.0 && f <= 1.0) return;
  const double excess = f < 0.0 ? -f : f - 1.0;
  if (excess > kVofClipTolerance) {
    ++report.count;
    report.max = std::max(report.max, excess);
  }
  f = std::clamp(f, 0.0, 1.0);
}

// true if a flux of cell (i, k) reads its PLIC stencil: a fluid cell between pure ones with an outflow
inline bool reconstructs(double n, double f, double vlo, double vhi) {
  return n > 0.0 && f > kPure && !(vlo >= 0.0 && vhi <= 0.0) && f < 1.0 - kPure;
}

// row k of the sweep along x on the columns [c0, c1) of a thread: the fluxes of the cells beside them
// (their own and one more on each side, the same values as their owners compute) into `local` (faces
// c0 - 1 to c1 + 1), the new F into F_swept (the array s.F_below), the faces [c0, c1) (and the last) into
// s.flux
void sweep_x_row(const SweepArgs& s, double* F_swept, int k, int c0, int c1, double* local, ClipReport& clip_report) {
  const Grid2D& g = s.g;
  const int nx = g.nx();
  const double dx = g.dx(), dt = s.dt, dz = g.dz(k);
  const double* u = s.vel + g.face_x(0, k);
  const double* n = s.n + g.cell(0, k);
  const double* F = s.F + g.cell(0, k);
  const double* c = s.c + g.cell(0, k);
  double* F_new = F_swept + g.cell(0, k);
  const int lo = std::max(c0 - 1, 0), hi = std::min(c1 + 1, nx);
  double* flux = local - lo;  // flux[f] for the faces lo..hi
  std::fill(flux + lo, flux + hi + 1, 0.0);
  // each face's flux from its upwind cell
  for (int i = lo; i < hi; ++i) cell_outflows(s, 0, i, k, n[i], F[i], u[i], u[i + 1], dz, &flux[i], &flux[i + 1]);
  // boundary faces where the flow enters carry the given fraction
  if (c0 == 0 && u[0] > 0.0) flux[0] = u[0] * dt * dz * (s.inflow.left.empty() ? 0.0 : s.inflow.left[k]);
  if (c1 == nx && u[nx] < 0.0) flux[nx] = u[nx] * dt * dz * (s.inflow.right.empty() ? 0.0 : s.inflow.right[k]);
  for (int i = c0; i < c1; ++i) {
    F_new[i] = F[i];
    if (!(n[i] > 0.0)) continue;
    const double dv = flux[i] - flux[i + 1] + c[i] * dt * dz * (u[i + 1] - u[i]);
    F_new[i] += dv / (n[i] * dx * dz);
    clip(F_new[i], clip_report);
  }
  double* out = s.flux + g.face_x(0, k);
  for (int f = c0; f < c1; ++f) out[f] = flux[f];
  if (c1 == nx) out[nx] = flux[nx];
}

// The sweep along x. Row by row, a flux of a reconstructed cell reads the rows below as already swept
// and the rest at the sweep's start (the order of one thread): the new rows go to a copy of F, which the
// stencils read for the row below, and the threads take pieces of each row's columns. Before a row
// whose fluxes read the row below, the threads wait for each other (a barrier); a row of pure cells
// reads nothing outside itself
void sweep_x(const SweepArgs& s, VofScratch& scratch) {
  const Grid2D& g = s.g;
  const int nx = g.nx(), nz = g.nz();
  const int team = detail::loop_threads(nx, 4LL * nz);
  scratch.row_flux.resize(std::max(scratch.row_flux.size(), static_cast<std::size_t>(team) * (nx + 3)));
  std::mutex lock;
  if (team == 1) {
    // one thread: the rows in place, as the copy would hold them
    const SweepArgs in_place{s.g, s.n, s.vel, s.inflow, s.dt, s.c, s.F, s.F, s.flux, s.normal};
    ClipReport report;
    for (int k = 0; k < nz; ++k) sweep_x_row(in_place, s.F, k, 0, nx, scratch.row_flux.data(), report);
    report.add_to(scratch, lock);
    return;
  }
  double* F_swept = scratch.cell_F_new.data();  // s.F_below
  std::vector<unsigned char>& reads_below = scratch.row_reads_below;
  reads_below.resize(nz);
  detail::parallel_for(nz, nx, [&](int k0, int k1) {
    for (int k = k0; k < k1; ++k) {
      const double* u = s.vel + g.face_x(0, k);
      const double* n = s.n + g.cell(0, k);
      const double* F = s.F + g.cell(0, k);
      bool any = false;
      for (int i = 0; i < nx; ++i) any |= reconstructs(n[i], F[i], u[i], u[i + 1]);
      reads_below[k] = any;
    }
  });
  detail::parallel_team(team, [&](int id, int count) {
    int c0, c1;
    detail::piece(nx, id, count, c0, c1);
    double* local = scratch.row_flux.data() + static_cast<std::size_t>(id) * (nx + 3);
    ClipReport report;
    for (int k = 0; k < nz; ++k) {
      if (k > 0 && reads_below[k]) detail::team_barrier();
      if (c0 < c1) sweep_x_row(s, F_swept, k, c0, c1, local, report);
    }
    report.add_to(scratch, lock);
  });
  detail::parallel_range(g.ncell(), [&](long long j0, long long j1) {
    std::copy(F_swept + j0, F_swept + j1, s.F + j0);
  });
}

// The sweep along z: every flux from F at the sweep's start (rows on the threads; a face is written by its
// one upwind cell), then every cell's update
void sweep_z(const SweepArgs& s, VofScratch& scratch) {
  const Grid2D& g = s.g;
  const int nx = g.nx(), nz = g.nz();
  const double dx = g.dx(), dt = s.dt;
  std::fill(s.flux, s.flux + g.nface_z(), 0.0);
  detail::parallel_for(nz, 4 * nx, [&, dx](int k0, int k1) {
    for (int k = k0; k < k1; ++k) {
      const double* wb = s.vel + g.face_z(0, k);
      const double* wt = s.vel + g.face_z(0, k + 1);
      double* fb = s.flux + g.face_z(0, k);
      double* ft = s.flux + g.face_z(0, k + 1);
      const double* n = s.n + g.cell(0, k);
      const double* F = s.F + g.cell(0, k);
      for (int i = 0; i < nx; ++i) cell_outflows(s, 1, i, k, n[i], F[i], wb[i], wt[i], dx, &fb[i], &ft[i]);
    }
  });
  const double* w = s.vel;
  for (int i = 0; i < nx; ++i) {
    const int fb = g.face_z(i, 0), ft = g.face_z(i, nz);
    if (w[fb] > 0.0) s.flux[fb] = w[fb] * dt * dx * (s.inflow.bottom.empty() ? 0.0 : s.inflow.bottom[i]);
    if (w[ft] < 0.0) s.flux[ft] = w[ft] * dt * dx * (s.inflow.top.empty() ? 0.0 : s.inflow.top[i]);
  }
  std::mutex lock;
  detail::parallel_for(nz, nx, [&, dx, dt](int k0, int k1) {
    ClipReport report;
    for (int k = k0; k < k1; ++k) {
      const double dz = g.dz(k);
      const double* wb = s.vel + g.face_z(0, k);
      const double* wt = s.vel + g.face_z(0, k + 1);
      const double* fb = s.flux + g.face_z(0, k);
      const double* ft = s.flux + g.face_z(0, k + 1);
      const double* n = s.n + g.cell(0, k);
      double* F = s.F + g.cell(0, k);
      const double* c = s.c + g.cell(0, k);
      for (int i = 0; i < nx; ++i) {
        if (!(n[i] > 0.0)) continue;
        const double dv = fb[i] - ft[i] + c[i] * dt * dx * (wt[i] - wb[i]);
        F[i] += dv / (n[i] * dx * dz);
        clip(F[i], report);
      }
    }
    report.add_to(scratch, lock);
  });
}

void check_inflow_size(const char* name, const std::vector<double>& v, int size) {
  if (!v.empty() && static_cast<int>(v.size()) != size)
    throw std::invalid_argument(std::string("inflow.") + name + " has size " + std::to_string(v.size()) +
                                "; allowed: 0 or " + std::to_string(size));
}

std::string face_name(const Grid2D& g, int dir, int f) {
  if (dir == 0) {
    const int k = f / (g.nx() + 1), i = f % (g.nx() + 1);
    return "x-face (i=" + std::to_string(i) + ", k=" + std::to_string(k) + ")";
  }
  const int k = f / g.nx(), i = f % g.nx();
  return "z-face (i=" + std::to_string(i) + ", k=" + std::to_string(k) + ")";
}

// largest directional CFL number over the faces of direction `dir` and their fluid neighbours;
// *worst receives the face index. Solid neighbours must see a zero velocity.
double max_cfl(const Grid2D& g, const double* n, const double* vel, int dir, double dt, int* worst) {
  const int nx = g.nx(), nz = g.nz();
  double cmax = 0.0;
  *worst = -1;
  const int nfi = dir == 0 ? nx + 1 : nx, nfk = dir == 0 ? nz : nz + 1;
  for (int k = 0; k < nfk; ++k)
    for (int i = 0; i < nfi; ++i) {
      const int f = dir == 0 ? g.face_x(i, k) : g.face_z(i, k);
      const double v = vel[f];
      if (!std::isfinite(v))
        throw std::runtime_error("vof advection: velocity " + format_value(v) + " on " + face_name(g, dir, f) +
                                 " is not finite");
      if (v == 0.0) continue;
      // the two cells sharing the face (either may lie outside the domain)
      const int i0 = dir == 0 ? i - 1 : i, k0 = dir == 0 ? k : k - 1;
      const int cells[2][2] = {{i0, k0}, {i, k}};
      for (const auto& ck : cells) {
        if (ck[0] < 0 || ck[0] >= nx || ck[1] < 0 || ck[1] >= nz) continue;
        const double nc = n[g.cell(ck[0], ck[1])];
        if (!(nc > 0.0))
          throw std::invalid_argument("face velocity " + format_value(v) + " on " + face_name(g, dir, f) +
                                      " next to a solid cell (porosity 0); allowed: 0");
        const double h = dir == 0 ? g.dx() : g.dz(ck[1]);
        const double cfl = std::abs(v) * dt / (nc * h);
        if (cfl > cmax) {
          cmax = cfl;
          *worst = f;
        }
      }
    }
  return cmax;
}

// true if every face passes |v| dt <= n h for its fluid neighbours, with zero velocity next to solid
// cells (n = 0) and finite velocities; multiplications only (NaN fails every comparison)
bool faces_pass(const Grid2D& g, const double* n, const double* u, const double* w, double dt) {
  const int nx = g.nx(), nz = g.nz();
  std::atomic<bool> all_ok{true};
  const double dx = g.dx();
  // the rows on the threads (an and in any order)
  detail::parallel_for(nz + 1, 2 * nx, [&, dx, dt](int k0, int k1) {
    bool ok = true;
    for (int k = k0; k < k1; ++k) {
      if (k < nz) {
        const double* nr = n + g.cell(0, k);
        const double* ur = u + g.face_x(0, k);
        ok &= std::abs(ur[0]) * dt <= nr[0] * dx;
        ok &= std::abs(ur[nx]) * dt <= nr[nx - 1] * dx;
        for (int i = 1; i < nx; ++i) ok &= std::abs(ur[i]) * dt <= std::min(nr[i - 1], nr[i]) * dx;
      }
      const double* wr = w + g.face_z(0, k);
      const double* nb = n + g.cell(0, std::max(k - 1, 0));
      const double* nt = n + g.cell(0, std::min(k, nz - 1));
      const double hb = g.dz(std::max(k - 1, 0)), ht = g.dz(std::min(k, nz - 1));
      for (int i = 0; i < nx; ++i) {
        const double a = std::abs(wr[i]) * dt;
        ok &= a <= nb[i] * hb;
        ok &= a <= nt[i] * ht;
      }
    }
    if (!ok) all_ok.store(false, std::memory_order_relaxed);
  });
  return all_ok.load();
}

// sizes a work array for the grid: allocates on first use or when the grid changed, never per step
void ensure_size(std::vector<double>& v, std::size_t size) {
  if (v.size() != size) v.assign(size, 0.0);
}

}  // namespace

void VofBoundaryInflow::resize(const Grid2D& grid, double value) {
  require_in_closed("value", value, 0.0, 1.0);
  left.assign(grid.nz(), value);
  right.assign(grid.nz(), value);
  bottom.assign(grid.nx(), value);
  top.assign(grid.nx(), value);
}

double plic_area_below(double mx, double mz, double dx, double dz, double alpha) {
  require_finite("mx", mx);
  require_finite("mz", mz);
  require_positive("dx", dx);
  require_positive("dz", dz);
  require_finite("alpha", alpha);
  return area_below(mx, mz, dx, dz, alpha);
}

double plic_line_constant(double mx, double mz, double dx, double dz, double f) {
  require_finite("mx", mx);
  require_finite("mz", mz);
  require_positive("dx", dx);
  require_positive("dz", dz);
  require_in_closed("f", f, 0.0, 1.0);
  return line_constant(mx, mz, dx, dz, f);
}

double vof_stable_dt(const Grid2D& grid, const double* cell_porosity, const double* face_u, const double* face_w,
                     double cfl) {
  require_positive("cfl", cfl);
  // the face checks name a non-finite velocity or one on a solid cell's face
  int worst = -1;
  max_cfl(grid, cell_porosity, face_u, 0, 1.0, &worst);
  max_cfl(grid, cell_porosity, face_w, 1, 1.0, &worst);
  // per fluid cell and direction, the rate [1/s] whose product with dt is max(C_in, C_out / 2)
  double rate = 0.0;
  const int nx = grid.nx(), nz = grid.nz();
  for (int k = 0; k < nz; ++k) {
    const double dz = grid.dz(k);
    for (int i = 0; i < nx; ++i) {
      const double n = cell_porosity[grid.cell(i, k)];
      if (!(n > 0.0)) continue;
      const double ul = face_u[grid.face_x(i, k)], ur = face_u[grid.face_x(i + 1, k)];
      const double wb = face_w[grid.face_z(i, k)], wt = face_w[grid.face_z(i, k + 1)];
      const double in_x = std::max(ul, 0.0) + std::max(-ur, 0.0), out_x = std::max(-ul, 0.0) + std::max(ur, 0.0);
      const double in_z = std::max(wb, 0.0) + std::max(-wt, 0.0), out_z = std::max(-wb, 0.0) + std::max(wt, 0.0);
      rate = std::max(rate, std::max(in_x, 0.5 * out_x) / (n * grid.dx()));
      rate = std::max(rate, std::max(in_z, 0.5 * out_z) / (n * dz));
    }
  }
  return rate > 0.0 ? cfl / rate : std::numeric_limits<double>::infinity();
}

namespace {
void require_size(const char* name, std::size_t size, int allowed) {
  if (static_cast<long long>(size) != allowed)
    throw std::invalid_argument(std::string(name) + " has size " + std::to_string(size) + "; allowed: " +
                                std::to_string(allowed));
}

void require_sizes(const Grid2D& grid, const std::vector<double>& cell_porosity, const std::vector<double>& face_u,
                   const std::vector<double>& face_w) {
  require_size("cell_porosity", cell_porosity.size(), grid.ncell());
  require_size("face_u", face_u.size(), grid.nface_x());
  require_size("face_w", face_w.size(), grid.nface_z());
}
}  // namespace

double vof_stable_dt(const Grid2D& grid, const std::vector<double>& cell_porosity, const std::vector<double>& face_u,
                     const std::vector<double>& face_w, double cfl) {
  require_sizes(grid, cell_porosity, face_u, face_w);
  return vof_stable_dt(grid, cell_porosity.data(), face_u.data(), face_w.data(), cfl);
}

void advect_vof(const Grid2D& grid, const double* cell_porosity, const double* face_u, const double* face_w,
                const VofBoundaryInflow& inflow, double dt, bool x_first, double* cell_F, VofScratch& scratch,
                VofNormal normal) {
  require_positive("dt", dt);
  check_inflow_size("left", inflow.left, grid.nz());
  check_inflow_size("right", inflow.right, grid.nz());
  check_inflow_size("bottom", inflow.bottom, grid.nx());
  check_inflow_size("top", inflow.top, grid.nx());
  // refuse a step that cannot stay bounded before touching F (the slow pass names the culprit)
  if (!faces_pass(grid, cell_porosity, face_u, face_w, dt)) {
    for (int dir = 0; dir < 2; ++dir) {
      int worst = -1;
      const double cfl = max_cfl(grid, cell_porosity, dir == 0 ? face_u : face_w, dir, dt, &worst);
      if (cfl > 1.0)
        throw CflBreach("vof advection: CFL number " + format_value(cfl) + " > 1 on " + face_name(grid, dir, worst) +
                            " at dt = " + format_value(dt) + " s",
                        cfl);
    }
  }
  const int ncell = grid.ncell();
  ensure_size(scratch.face_flux_x, static_cast<std::size_t>(grid.nface_x()));
  ensure_size(scratch.face_flux_z, static_cast<std::size_t>(grid.nface_z()));
  ensure_size(scratch.cell_c, static_cast<std::size_t>(ncell));
  // the divergence-correction indicator is frozen at the start of the step for both sweeps
  std::atomic<bool> all_finite{true};
  detail::parallel_range(ncell, [&](long long c0, long long c1) {
    bool finite = true;
    for (long long c = c0; c < c1; ++c) {
      scratch.cell_c[c] = cell_F[c] > 0.5 ? 1.0 : 0.0;
      finite &= std::isfinite(cell_F[c]);
    }
    if (!finite) all_finite.store(false, std::memory_order_relaxed);
  });
  if (!all_finite.load())
    for (int c = 0; c < ncell; ++c)
      if (!std::isfinite(cell_F[c]) && cell_porosity[c] > 0.0)
        throw std::runtime_error("vof advection: F = " + format_value(cell_F[c]) + " in cell (i=" +
                                 std::to_string(c % grid.nx()) + ", k=" + std::to_string(c / grid.nx()) +
                                 ") is not finite");
  ensure_size(scratch.cell_F_new, static_cast<std::size_t>(ncell));
  const double* c = scratch.cell_c.data();
  const SweepArgs sx{grid,   cell_porosity, face_u, inflow, dt, c, cell_F, scratch.cell_F_new.data(),
                     scratch.face_flux_x.data(), normal};
  const SweepArgs sz{grid, cell_porosity, face_w, inflow, dt, c, cell_F, cell_F, scratch.face_flux_z.data(), normal};
  if (x_first) {
    sweep_x(sx, scratch);
    sweep_z(sz, scratch);
  } else {
    sweep_z(sz, scratch);
    sweep_x(sx, scratch);
  }
}

void advect_vof(const Grid2D& grid, const std::vector<double>& cell_porosity, const std::vector<double>& face_u,
                const std::vector<double>& face_w, const VofBoundaryInflow& inflow, double dt, bool x_first,
                std::vector<double>& cell_F, VofScratch& scratch, VofNormal normal) {
  require_sizes(grid, cell_porosity, face_u, face_w);
  require_size("cell_F", cell_F.size(), grid.ncell());
  advect_vof(grid, cell_porosity.data(), face_u.data(), face_w.data(), inflow, dt, x_first, cell_F.data(), scratch,
             normal);
}

}  // namespace vofdem
