#include "flow/pressure_mgcg.h"

#include <chrono>
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
double seconds_since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

// dot products and updates of the CG vectors with four partial sums: one serial chain of adds would
// wait on the add latency; the fixed order keeps the result deterministic
double dot(const double* a, const double* b, std::size_t n) {
  double s0 = 0.0, s1 = 0.0, s2 = 0.0, s3 = 0.0;
  std::size_t j = 0;
  for (; j + 4 <= n; j += 4) {
    s0 += a[j] * b[j];
    s1 += a[j + 1] * b[j + 1];
    s2 += a[j + 2] * b[j + 2];
    s3 += a[j + 3] * b[j + 3];
  }
  for (; j < n; ++j) s0 += a[j] * b[j];
  return (s0 + s1) + (s2 + s3);
}

// x += alpha d, r -= alpha q; returns r . r. On one thread in one pass (while r is in cache); on several,
// the updates on the threads, then the norm in its one order
double update_and_norm(double alpha, const double* d, const double* q, double* x, double* r, std::size_t n) {
  if (loop_threads((static_cast<long long>(n) + 1023) / 1024, 1024) > 1) {
    parallel_range(static_cast<long long>(n), [&, alpha](long long j0, long long j1) {
      for (long long j = j0; j < j1; ++j) {
        x[j] += alpha * d[j];
        r[j] -= alpha * q[j];
      }
    });
    return dot(r, r, n);
  }
  double s0 = 0.0, s1 = 0.0, s2 = 0.0, s3 = 0.0;
  std::size_t j = 0;
  for (; j + 4 <= n; j += 4) {
    for (std::size_t l = 0; l < 4; ++l) {
      x[j + l] += alpha * d[j + l];
      r[j + l] -= alpha * q[j + l];
    }
    s0 += r[j] * r[j];
    s1 += r[j + 1] * r[j + 1];
    s2 += r[j + 2] * r[j + 2];
    s3 += r[j + 3] * r[j + 3];
  }
  for (; j < n; ++j) {
    x[j] += alpha * d[j];
    r[j] -= alpha * q[j];
    s0 += r[j] * r[j];
  }
  return (s0 + s1) + (s2 + s3);
}
}  // namespace

MultigridCGPressureSolver::MultigridCGPressureSolver(const PressureSolverParams& params) : params_(params) {
  if (params.max_iterations < 1)
    throw std::invalid_argument("max_iterations = " + std::to_string(params.max_iterations) +
                                " is outside the allowed range [1, inf)");
  if (params.smoothing_sweeps < 1 || params.smoothing_sweeps > 8)
    throw std::invalid_argument("smoothing_sweeps = " + std::to_string(params.smoothing_sweeps) +
                                " is outside the allowed range [1, 8]");
  require_in_closed("coarse_correction_scale", params.coarse_correction_scale, 1.0, 1.95);
  if (params.coarsest_cells < 1 || params.coarsest_cells > 4096)
    throw std::invalid_argument("coarsest_cells = " + std::to_string(params.coarsest_cells) +
                                " is outside the allowed range [1, 4096]");
}

void MultigridCGPressureSolver::setup(const Grid2D& grid, const PressureProblem& problem) {
  const auto t0 = std::chrono::steady_clock::now();
  ready_ = false;
  sys_.build(grid, problem);
  const int nx = grid.nx(), nz = grid.nz();
  if (!mg_.allocated_for(nx, nz)) {
    mg_.allocate(nx, nz, params_);
    const std::size_t n = static_cast<std::size_t>(mg_.level(0).size());
    for (auto* v : {&b_, &x_, &r_, &z_, &d_, &q_}) v->assign(n, 0.0);
    group_cells_.reserve(grid.ncell());
    group_start_.reserve(grid.ncell() + 1);
  }
  mg_.setup(sys_.face_x_coef(), sys_.face_z_coef(), sys_.cell_active());
  // singular groups in padded indices
  const MultigridLevel& f = mg_.level(0);
  group_cells_.clear();
  group_start_.assign(1, 0);
  for (int c : sys_.singular_cells()) group_cells_.push_back(f.index(c % nx, c / nx));
  group_start_ = sys_.singular_start();
  setup_seconds_ = seconds_since(t0);
  ready_ = true;
}

void MultigridCGPressureSolver::project(double* v) const {
  for (std::size_t s = 0; s + 1 < group_start_.size(); ++s) {
    const int b = group_start_[s], e = group_start_[s + 1];
    double sum = 0.0;
    for (int j = b; j < e; ++j) sum += v[group_cells_[j]];
    const double mean = sum / (e - b);
    for (int j = b; j < e; ++j) v[group_cells_[j]] -= mean;
  }
}

void MultigridCGPressureSolver::fail(int iterations, double residual, double tol, double fnorm) const {
  // the cell with the largest residual locates the trouble
  const MultigridLevel& f = mg_.level(0);
  int worst_i = 0, worst_k = 0;
  double worst = -1.0, roundoff = 0.0;
  for (int k = 0; k < f.nz; ++k)
    for (int i = 0; i < f.nx; ++i) {
      const int j = f.index(i, k);
      roundoff += (f.diag[j] * x_[j]) * (f.diag[j] * x_[j]);
      if (std::abs(r_[j]) > worst) {
        worst = std::abs(r_[j]);
        worst_i = i;
        worst_k = k;
      }
    }
  // round-off in M x: about eps 2 d_c |x_c| per cell
  const double floor = 2.0 * std::numeric_limits<double>::epsilon() * std::sqrt(roundoff) / fnorm;
  throw std::runtime_error("pressure solve (multigrid CG): no convergence after " + std::to_string(iterations) +
                           " iterations (max_iterations = " + std::to_string(params_.max_iterations) +
                           "): relative residual " + format_value(residual) + " > tol " + format_value(tol) +
                           "; largest residual at cell (i, k) = (" + std::to_string(worst_i) + ", " +
                           std::to_string(worst_k) + "); round-off floor of the residual about " +
                           format_value(floor) + (tol < floor ? " (tol is below it)" : ""));
}

PressureSolveStats MultigridCGPressureSolver::solve(const std::vector<double>& rhs, std::vector<double>& p,
                                                    double tol) {
  if (!ready_) throw std::logic_error("pressure solve (multigrid CG): setup() was not called");
  require_positive("tol", tol);
  const int nx = sys_.nx(), nz = sys_.nz();
  if (p.size() != static_cast<std::size_t>(sys_.ncell()))
    throw std::invalid_argument("p has size " + std::to_string(p.size()) + ", expected " +
                                std::to_string(sys_.ncell()));
  const auto t0 = std::chrono::steady_clock::now();
  sys_.source(rhs, f_);
  const MultigridLevel& lv = mg_.level(0);
  const auto& act = sys_.cell_active();
  std::atomic<bool> finite{true};
  parallel_for(nz, nx, [&](int k0, int k1) {
    bool ok = true;
    for (int k = k0; k < k1; ++k)
      for (int i = 0; i < nx; ++i) {
        const int c = i + nx * k, j = lv.index(i, k);
        b_[j] = f_[c];
        x_[j] = act[c] ? p[c] : 0.0;
        ok &= std::isfinite(x_[j]);
      }
    if (!ok) finite.store(false, std::memory_order_relaxed);
  });
  for (int c = 0; !finite.load() && c < nx * nz; ++c)
    if (act[c] && !std::isfinite(p[c]))
      throw std::invalid_argument("p[" + std::to_string(c) + "] = " + format_value(p[c]) +
                                  " (initial guess) is outside the allowed range (finite values)");
  // the source's norm in its one order (threads.h)
  double ff = 0.0;
  for (int c = 0; c < nx * nz; ++c) ff += f_[c] * f_[c];
  PressureSolveStats st;
  st.setup_seconds = setup_seconds_;
  const double fnorm = std::sqrt(ff);
  if (fnorm == 0.0) {
    for (int c = 0; c < sys_.ncell(); ++c)
      if (act[c]) p[c] = 0.0;
    st.solve_seconds = seconds_since(t0);
    return st;
  }
  const std::size_t n = b_.size();
  // CG from the true residual r = b - M x; restarted from it again if the recursive residual drifted
  int it = 0;
  double rel = 0.0;
  mg_.set_correction_scale(params_.coarse_correction_scale);
  for (int restart = 0;; ++restart) {
    mg_.multiply(x_.data(), q_.data());
    parallel_for(nz, nx, [&](int k0, int k1) {
      for (int k = k0; k < k1; ++k)
        for (int i = 0; i < nx; ++i) r_[lv.index(i, k)] = b_[lv.index(i, k)] - q_[lv.index(i, k)];
    });
    double rr = 0.0;
    for (int k = 0; k < nz; ++k)
      for (int i = 0; i < nx; ++i) rr += r_[lv.index(i, k)] * r_[lv.index(i, k)];
    rel = std::sqrt(rr) / fnorm;
    if (rel <= tol) break;
    if (it >= params_.max_iterations || restart >= 3 || !std::isfinite(rel)) fail(it, rel, tol, fnorm);
    mg_.apply(r_.data(), z_.data());
    project(z_.data());
    double rz = dot(r_.data(), z_.data(), n);
    d_ = z_;
    while (it < params_.max_iterations) {
      ++it;
      const double dq = mg_.multiply(d_.data(), q_.data());
      if (!(dq > 0.0) || !(rz > 0.0) || !std::isfinite(rz)) {
        // the over-corrected V-cycle lost definiteness (or round-off did): plain correction from here on
        mg_.set_correction_scale(1.0);
        break;
      }
      const double alpha = rz / dq;
      rr = update_and_norm(alpha, d_.data(), q_.data(), x_.data(), r_.data(), n);
      if (std::sqrt(rr) <= tol * fnorm) break;
      mg_.apply(r_.data(), z_.data());
      project(z_.data());
      const double rz_new = dot(r_.data(), z_.data(), n);
      const double beta = rz_new / rz;
      rz = rz_new;
      parallel_range(static_cast<long long>(n), [&, beta](long long j0, long long j1) {
        for (long long j = j0; j < j1; ++j) d_[j] = z_[j] + beta * d_[j];
      });
    }
  }
  st.iterations = it;
  st.residual = rel;
  project(x_.data());
  parallel_for(nz, nx, [&](int k0, int k1) {
    for (int k = k0; k < k1; ++k)
      for (int i = 0; i < nx; ++i)
        if (act[i + nx * k]) p[i + nx * k] = x_[lv.index(i, k)];
  });
  st.solve_seconds = seconds_since(t0);
  return st;
}

}  // namespace vofdem::detail
