#include "flow/pressure_direct.h"

#include <chrono>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

#include "vofdem/common/check.h"

namespace vofdem::detail {

namespace {
double seconds_since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}
}  // namespace

void EigenDirectPressureSolver::setup(const Grid2D& grid, const PressureProblem& problem) {
  const auto t0 = std::chrono::steady_clock::now();
  sys_.build(grid, problem);
  const int nx = sys_.nx(), nz = sys_.nz(), n = sys_.ncell();
  const auto& act = sys_.cell_active();
  const auto& ax = sys_.face_x_coef();
  const auto& az = sys_.face_z_coef();

  unknown_.assign(n, -1);
  pinned_.assign(n, 0);
  for (int c : sys_.singular_anchor_cells()) pinned_[c] = 1;
  std::vector<int> key;
  key.reserve(n + 2);
  key.push_back(nx);
  key.push_back(nz);
  int m = 0;
  for (int c = 0; c < n; ++c)
    if (act[c]) {
      unknown_[c] = m++;
      key.push_back(pinned_[c] ? -c - 1 : c);
    }

  // M = -A0: diagonal = sum of the open faces, off-diagonal -a_f between active cells
  triplets_.clear();
  for (int k = 0; k < nz; ++k)
    for (int i = 0; i < nx; ++i) {
      const int c = i + nx * k;
      if (!act[c]) continue;
      const int u = unknown_[c];
      if (pinned_[c]) {
        triplets_.emplace_back(u, u, 1.0);
        continue;
      }
      const double aw = ax[i + (nx + 1) * k], ae = ax[i + 1 + (nx + 1) * k];
      const double as = az[c], an = az[c + nx];
      triplets_.emplace_back(u, u, aw + ae + as + an);
      // keep every structural neighbour (zero or not) so the pattern depends on the active set only
      auto couple = [&](bool inside, int nb, double a) {
        if (inside && act[nb] && !pinned_[nb]) triplets_.emplace_back(u, unknown_[nb], -a);
      };
      couple(i > 0, c - 1, aw);
      couple(i < nx - 1, c + 1, ae);
      couple(k > 0, c - nx, as);
      couple(k < nz - 1, c + nx, an);
    }
  matrix_.resize(m, m);
  matrix_.setFromTriplets(triplets_.begin(), triplets_.end());
  if (!ready_ || key != pattern_key_) {
    ldlt_.analyzePattern(matrix_);
    pattern_key_ = std::move(key);
  }
  ldlt_.factorize(matrix_);
  ready_ = ldlt_.info() == Eigen::Success;
  if (!ready_) throw std::runtime_error("pressure setup (Eigen LDLT): factorisation failed");
  b_.resize(m);
  x_.resize(m);
  setup_seconds_ = seconds_since(t0);
}

PressureSolveStats EigenDirectPressureSolver::solve(const std::vector<double>& rhs, std::vector<double>& p,
                                                    double tol) {
  if (!ready_) throw std::logic_error("pressure solve (Eigen LDLT): setup() was not called");
  require_positive("tol", tol);
  if (p.size() != static_cast<std::size_t>(sys_.ncell()))
    throw std::invalid_argument("p has size " + std::to_string(p.size()) + ", expected " +
                                std::to_string(sys_.ncell()));
  const auto t0 = std::chrono::steady_clock::now();
  sys_.source(rhs, f_);
  const int n = sys_.ncell();
  for (int c = 0; c < n; ++c)
    if (unknown_[c] >= 0) b_[unknown_[c]] = pinned_[c] ? 0.0 : f_[c];
  x_ = ldlt_.solve(b_);
  work_.assign(n, 0.0);
  for (int c = 0; c < n; ++c)
    if (unknown_[c] >= 0) work_[c] = x_[unknown_[c]];
  sys_.remove_singular_means(work_.data());

  PressureSolveStats st;
  st.setup_seconds = setup_seconds_;
  double ff = 0.0;
  for (int c = 0; c < n; ++c) ff += f_[c] * f_[c];
  // iterative refinement with the same factors while round-off leaves the residual above tol and
  // refinement still reduces it (coefficient ratios of 1e9 and more: density, porosity and resistance
  // jumps combined); a direct solve has nothing else to do, so a residual stuck at the round-off floor
  // is reported, not refused
  double previous = std::numeric_limits<double>::infinity();
  for (int refinement = 0;; ++refinement) {
    sys_.residual(f_, work_, r_);
    double rr = 0.0;
    for (int c = 0; c < n; ++c) rr += r_[c] * r_[c];
    st.residual = ff > 0 ? std::sqrt(rr / ff) : 0.0;
    if (!std::isfinite(st.residual))
      throw std::runtime_error("pressure solve (Eigen LDLT): non-finite residual (coefficients out of range?)");
    if (st.residual <= tol || refinement == 3 || !(st.residual < 0.5 * previous)) break;
    previous = st.residual;
    for (int c = 0; c < n; ++c)
      if (unknown_[c] >= 0) b_[unknown_[c]] = pinned_[c] ? 0.0 : r_[c];
    x_ = ldlt_.solve(b_);
    for (int c = 0; c < n; ++c)
      if (unknown_[c] >= 0) work_[c] += x_[unknown_[c]];
    sys_.remove_singular_means(work_.data());
  }
  for (int c = 0; c < n; ++c)
    if (unknown_[c] >= 0) p[c] = work_[c];
  st.solve_seconds = seconds_since(t0);
  return st;
}

}  // namespace vofdem::detail
