#include "flow/pressure_system.h"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

#include "common/parallel.h"
#include "vofdem/common/check.h"

namespace vofdem::detail {

namespace {

void require_size(const char* name, std::size_t size, int expected) {
  if (size != static_cast<std::size_t>(expected))
    throw std::invalid_argument(std::string(name) + " has size " + std::to_string(size) + ", expected " +
                                std::to_string(expected));
}

[[noreturn]] void refuse_open_face(const char* name, int face, int i, int k, double a) {
  throw std::invalid_argument(std::string(name) + "[" + std::to_string(face) + "] = " + format_value(a) +
                              " at face (i, k) = (" + std::to_string(i) + ", " + std::to_string(k) +
                              ") touches an inactive cell; allowed value: 0");
}

}  // namespace

void PressureSystem::build(const Grid2D& grid, const PressureProblem& pb) {
  const int nx = grid.nx(), nz = grid.nz();
  require_size("face_x_coef", pb.face_x_coef.size(), grid.nface_x());
  require_size("face_z_coef", pb.face_z_coef.size(), grid.nface_z());
  require_size("face_x_bc", pb.face_x_bc.size(), grid.nface_x());
  require_size("face_z_bc", pb.face_z_bc.size(), grid.nface_z());
  require_size("cell_active", pb.cell_active.size(), grid.ncell());
  if (nx != nx_ || nz != nz_) {
    groups_valid_ = false;
    nx_ = nx;
    nz_ = nz;
    g_.assign(grid.ncell(), 0.0);
    group_.assign(grid.ncell(), -1);
    stack_.reserve(grid.ncell());
    singular_cells_.reserve(grid.ncell());
    singular_start_.reserve(grid.ncell() + 1);
  }
  ax_ = pb.face_x_coef;
  az_ = pb.face_z_coef;
  active_ = pb.cell_active;
  close_negligible_faces(grid);

  // checks, and the pattern of open faces and active cells: the groups change only with it
  const int nfx = grid.nface_x(), nfz = grid.nface_z();
  const bool had_pattern = groups_valid_ && pattern_.size() == static_cast<std::size_t>(nfx + nfz + grid.ncell());
  groups_valid_ = false;  // until this build completes
  pattern_.resize(nfx + nfz + grid.ncell());
  if (!pattern_checked(grid, pb, had_pattern)) check_pattern(grid, pb);
  const bool same = had_pattern && !pattern_changed_;
  nactive_ = 0;
  for (int c = 0; c < grid.ncell(); ++c) nactive_ += active_[c];

  // boundary source g
  std::fill(g_.begin(), g_.end(), 0.0);
  for (int k = 0; k < nz; ++k) {
    g_[nx * k] += ax_[grid.face_x(0, k)] * pb.face_x_bc[grid.face_x(0, k)];
    g_[nx - 1 + nx * k] += ax_[grid.face_x(nx, k)] * pb.face_x_bc[grid.face_x(nx, k)];
  }
  for (int i = 0; i < nx; ++i) {
    g_[i] += az_[grid.face_z(i, 0)] * pb.face_z_bc[grid.face_z(i, 0)];
    g_[i + nx * (nz - 1)] += az_[grid.face_z(i, nz)] * pb.face_z_bc[grid.face_z(i, nz)];
  }

  if (!same) find_groups();
  groups_valid_ = true;
}

namespace {

// one row of the pattern: the flags v[i] written into pat; true if any changed. The arrays never overlap
// (restrict: a store of a byte could otherwise alias every pointer the loop reads)
template <class Flag>
bool note_row(int count, Flag flag, std::uint8_t* __restrict pat) {
  bool changed = false;
  for (int i = 0; i < count; ++i) {
    const std::uint8_t v = flag(i);
    changed |= pat[i] != v;
    pat[i] = v;
  }
  return changed;
}

// a row of inner faces passes the checks: a coefficient finite and >= 0, an open face between two active cells
bool inner_faces_ok(int count, const double* __restrict a, const std::uint8_t* __restrict act_lo,
                    const std::uint8_t* __restrict act_hi) {
  bool ok = true;
  for (int i = 0; i < count; ++i) {
    const double v = a[i];
    ok &= (v >= 0.0) & (v <= std::numeric_limits<double>::max());
    ok &= (v <= 0.0) | ((act_lo[i] != 0) & (act_hi[i] != 0));
  }
  return ok;
}

// a boundary face passes: a coefficient finite and >= 0; open, its one cell active and its value finite
bool boundary_face_ok(double a, std::uint8_t active, double bc) {
  if (!(a >= 0.0 && a <= std::numeric_limits<double>::max())) return false;
  return !(a > 0.0) || (active != 0 && std::isfinite(bc));
}

}  // namespace

// The pattern of open faces and active cells written on the threads (rows of cells, x-faces and z-faces),
// with whether it changed; true if every value passed the checks (else check_pattern names the first
// that fails)
bool PressureSystem::pattern_checked(const Grid2D& grid, const PressureProblem& pb, bool had_pattern) {
  const int nx = grid.nx(), nz = grid.nz(), sx = nx + 1, nfx = grid.nface_x(), nfz = grid.nface_z();
  std::atomic<bool> ok{true}, changed{!had_pattern};
  const std::uint8_t* act = active_.data();
  const double *ax = ax_.data(), *az = az_.data(), *bx = pb.face_x_bc.data(), *bz = pb.face_z_bc.data();
  std::uint8_t* pat = pattern_.data();
  detail::parallel_for(nz + 1, 3 * nx, [&](int k0, int k1) {
    bool good = true, diff = false;
    for (int k = k0; k < k1; ++k) {
      const double* a = az + nx * k;
      diff |= note_row(nx, [a](int i) { return static_cast<std::uint8_t>(a[i] > 0.0); }, pat + nfx + nx * k);
      if (k == 0 || k == nz) {
        const std::uint8_t* cells = act + nx * (k == 0 ? 0 : nz - 1);
        for (int i = 0; i < nx; ++i) good &= boundary_face_ok(a[i], cells[i], bz[nx * k + i]);
      } else {
        good &= inner_faces_ok(nx, a, act + nx * (k - 1), act + nx * k);
      }
      if (k == nz) continue;
      const std::uint8_t* cells = act + nx * k;
      for (int i = 0; i < nx; ++i) good &= cells[i] <= 1;
      diff |= note_row(nx, [cells](int i) { return cells[i]; }, pat + nfx + nfz + nx * k);
      const double* b = ax + sx * k;
      diff |= note_row(sx, [b](int i) { return static_cast<std::uint8_t>(b[i] > 0.0); }, pat + sx * k);
      good &= inner_faces_ok(nx - 1, b + 1, cells, cells + 1);
      good &= boundary_face_ok(b[0], cells[0], bx[sx * k]);
      good &= boundary_face_ok(b[nx], cells[nx - 1], bx[sx * k + nx]);
    }
    if (!good) ok.store(false, std::memory_order_relaxed);
    if (diff) changed.store(true, std::memory_order_relaxed);
  });
  pattern_changed_ = changed.load();
  return ok.load();
}

// the checks of pattern_checked one value after the other: throws naming the first that fails
void PressureSystem::check_pattern(const Grid2D& grid, const PressureProblem& pb) const {
  const int nx = grid.nx(), nz = grid.nz();
  for (int c = 0; c < grid.ncell(); ++c)
    if (active_[c] > 1) require_in_closed("cell_active", active_[c], 0, 1);
  auto act = [&](int i, int k) { return active_[i + nx * k] != 0; };
  for (int k = 0; k < nz; ++k)
    for (int i = 0; i <= nx; ++i) {
      const int f = i + (nx + 1) * k;
      const double a = ax_[f];
      if (!(a >= 0.0 && a <= std::numeric_limits<double>::max())) require_non_negative("face_x_coef", a);
      if (a == 0.0) continue;
      const bool boundary = (i == 0 || i == nx);
      if (boundary ? !act(i == 0 ? 0 : nx - 1, k) : !(act(i - 1, k) && act(i, k)))
        refuse_open_face("face_x_coef", f, i, k, a);
      if (boundary) require_finite("face_x_bc", pb.face_x_bc[f]);
    }
  for (int k = 0; k <= nz; ++k)
    for (int i = 0; i < nx; ++i) {
      const int f = i + nx * k;
      const double a = az_[f];
      if (!(a >= 0.0 && a <= std::numeric_limits<double>::max())) require_non_negative("face_z_coef", a);
      if (a == 0.0) continue;
      const bool boundary = (k == 0 || k == nz);
      if (boundary ? !act(i, k == 0 ? 0 : nz - 1) : !(act(i, k - 1) && act(i, k)))
        refuse_open_face("face_z_coef", f, i, k, a);
      if (boundary) require_finite("face_z_bc", pb.face_z_bc[f]);
    }
}

void PressureSystem::close_negligible_faces(const Grid2D& grid) {
  const int nx = grid.nx(), nz = grid.nz(), sx = nx + 1;
  cell_amax_.assign(grid.ncell(), 0.0);
  detail::parallel_for(nz, nx, [&](int k0, int k1) {
    for (int k = k0; k < k1; ++k)
      for (int i = 0; i < nx; ++i) {
        const int c = i + nx * k;
        // NaN or negative values are left to the checks that follow
        cell_amax_[c] = std::max(std::max(ax_[i + sx * k], ax_[i + 1 + sx * k]), std::max(az_[c], az_[c + nx]));
      }
  });
  // the faces read the cells' largest of the faces as they came (one pass for all, then these)
  detail::parallel_for(nz, 2 * nx, [&](int k0, int k1) {
    for (int k = k0; k < k1; ++k) {
      for (int i = 1; i < nx; ++i) {
        double& a = ax_[i + sx * k];
        if (a > 0.0 && a < kNegligibleFace * std::max(cell_amax_[i - 1 + nx * k], cell_amax_[i + nx * k])) a = 0.0;
      }
      if (k == 0) continue;
      for (int i = 0; i < nx; ++i) {
        double& a = az_[i + nx * k];
        if (a > 0.0 && a < kNegligibleFace * std::max(cell_amax_[i + nx * (k - 1)], cell_amax_[i + nx * k])) a = 0.0;
      }
    }
  });
}

void PressureSystem::find_groups() {
  // connected groups through open faces; keep those without a Dirichlet face
  const int nx = nx_, nz = nz_;
  std::fill(group_.begin(), group_.end(), -1);
  singular_cells_.clear();
  singular_start_.clear();
  singular_start_.push_back(0);
  int ngroup = 0;
  for (int seed = 0; seed < nx * nz; ++seed) {
    if (!active_[seed] || group_[seed] >= 0) continue;
    const std::size_t first = singular_cells_.size();
    bool dirichlet = false;
    stack_.clear();
    stack_.push_back(seed);
    group_[seed] = ngroup;
    while (!stack_.empty()) {
      const int c = stack_.back();
      stack_.pop_back();
      singular_cells_.push_back(c);
      const int i = c % nx, k = c / nx;
      const double aw = ax_[i + (nx + 1) * k], ae = ax_[i + 1 + (nx + 1) * k];
      const double as = az_[c], an = az_[c + nx];
      if ((i == 0 && aw > 0) || (i == nx - 1 && ae > 0) || (k == 0 && as > 0) || (k == nz - 1 && an > 0))
        dirichlet = true;
      auto visit = [&](bool open, int nb) {
        if (open && group_[nb] < 0) {
          group_[nb] = ngroup;
          stack_.push_back(nb);
        }
      };
      visit(i > 0 && aw > 0, c - 1);
      visit(i < nx - 1 && ae > 0, c + 1);
      visit(k > 0 && as > 0, c - nx);
      visit(k < nz - 1 && an > 0, c + nx);
    }
    ++ngroup;
    if (dirichlet)
      singular_cells_.resize(first);
    else
      singular_start_.push_back(static_cast<int>(singular_cells_.size()));
  }
}

void PressureSystem::source(const std::vector<double>& rhs, std::vector<double>& f, bool project) const {
  require_size("rhs", rhs.size(), ncell());
  f.resize(ncell());
  std::atomic<bool> finite{true};
  detail::parallel_range(ncell(), [&](long long c0, long long c1) {
    bool ok = true;
    for (long long c = c0; c < c1; ++c) {
      ok &= !active_[c] || std::isfinite(rhs[c]);
      f[c] = active_[c] ? g_[c] - rhs[c] : 0.0;
    }
    if (!ok) finite.store(false, std::memory_order_relaxed);
  });
  for (int c = 0; !finite.load() && c < ncell(); ++c)
    if (active_[c] && !std::isfinite(rhs[c]))
      throw std::invalid_argument("rhs[" + std::to_string(c) + "] = " + format_value(rhs[c]) +
                                  " is outside the allowed range (finite values)");
  if (!project) return;
  // twice: the first removal leaves a mean of its round-off, eps times the mean removed, that a solve
  // cannot reduce (and that the direct solver's pinned cell turns into a point source); the second
  // leaves eps times the source's own size
  remove_singular_means(f.data());
  remove_singular_means(f.data());
}

void PressureSystem::remove_singular_means(double* x) const {
  for (std::size_t s = 0; s + 1 < singular_start_.size(); ++s) {
    const int b = singular_start_[s], e = singular_start_[s + 1];
    double sum = 0.0;
    for (int j = b; j < e; ++j) sum += x[singular_cells_[j]];
    const double mean = sum / (e - b);
    for (int j = b; j < e; ++j) x[singular_cells_[j]] -= mean;
  }
}

std::vector<int> PressureSystem::singular_anchor_cells() const {
  std::vector<int> anchors;
  for (std::size_t s = 0; s + 1 < singular_start_.size(); ++s) anchors.push_back(singular_cells_[singular_start_[s]]);
  return anchors;
}

void PressureSystem::residual(const std::vector<double>& f, const std::vector<double>& x,
                              std::vector<double>& r) const {
  const int nx = nx_, nz = nz_;
  r.resize(ncell());
  for (int k = 0; k < nz; ++k)
    for (int i = 0; i < nx; ++i) {
      const int c = i + nx * k;
      if (!active_[c]) {
        r[c] = 0.0;
        continue;
      }
      const double aw = ax_[i + (nx + 1) * k], ae = ax_[i + 1 + (nx + 1) * k];
      const double as = az_[c], an = az_[c + nx];
      double mx = (aw + ae + as + an) * x[c];
      if (i > 0 && aw > 0) mx -= aw * x[c - 1];
      if (i < nx - 1 && ae > 0) mx -= ae * x[c + 1];
      if (k > 0 && as > 0) mx -= as * x[c - nx];
      if (k < nz - 1 && an > 0) mx -= an * x[c + nx];
      r[c] = f[c] - mx;
    }
}

}  // namespace vofdem::detail
