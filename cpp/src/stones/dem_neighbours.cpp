// Neighbour search of DEMSystem: a Verlet list with a skin, built in O(N) from a cell grid.
//
// Pairs (i < j) whose gap is below the skin are listed in (i, j) order; the list is rebuilt when a
// stone has moved more than half the skin since the last build, so no contact can be missed. Each
// pair carries its tangential and rolling springs (the contact history); a rebuild carries them over by a
// merge of the two sorted lists, so the order of every force sum is fixed and runs are reproducible.
// 3D stones are binned in x, y and z and their gap is measured in 3D (the skin rule with the 3D move):
// the list holds the same pairs that can touch as the plane's list, in the same order, so every force sum
// adds the same terms in the same order.
#include <algorithm>
#include <cmath>

#include "vofdem/stones/dem_system.h"

namespace vofdem {

bool DEMSystem::neighbours_stale() const {
  if (build_pos_.size() != stone_pos.size()) return true;
  if (neighbours_3d() && build_y_.size() != stone_y.size()) return true;
  for (int i = 0; i < n_; ++i) {
    if (inv_mass_[i] != 0.0 && moved_half_skin(i)) return true;
  }
  return false;
}

// the one test of the skin rule: stone i has moved more than half the skin since the list's build (with
// the 3D list, across the flume too; adding dy^2 >= 0 never lowers the sum, so a plane move that passes
// the limit passes it in 3D)
bool DEMSystem::moved_half_skin(int i) const {
  const double dx = stone_pos[2 * i] - build_pos_[2 * i];
  const double dz = stone_pos[2 * i + 1] - build_pos_[2 * i + 1];
  const double dy = neighbours_3d() ? stone_y[i] - build_y_[i] : 0.0;
  return dx * dx + dy * dy + dz * dz > 0.25 * skin_ * skin_;
}

// stones within the skin of each wall; the others cannot touch it before the next build
void DEMSystem::build_wall_candidates() {
  const std::size_t nw = params_.walls.size();
  wall_cand_.clear();
  wall_cand_start_.assign(nw + 1, 0);
  for (std::size_t w = 0; w < nw; ++w) {
    const DEMWall& wall = params_.walls[w];
    const auto [wx, wz] = wall_unit_normal(wall);
    for (int i = 0; i < n_; ++i) {
      if (!stone_active[i] || stone_fixed[i]) continue;
      const double s = (stone_pos[2 * i] - wall.point[0]) * wx + (stone_pos[2 * i + 1] - wall.point[1]) * wz;
      if (s < stone_radius[i] + skin_) {
        wall_cand_.push_back(i);
      } else {
        wall_xi_[static_cast<std::size_t>(i) * nw + w] = wall_mr_[static_cast<std::size_t>(i) * nw + w] = 0.0;
        wall_points_[static_cast<std::size_t>(i) * nw + w] = PointSprings{};
      }
    }
    wall_cand_start_[w + 1] = static_cast<int>(wall_cand_.size());
  }
}

void DEMSystem::build_neighbours() {
  ++nbuilds_;
  rebuild_ = false;
  build_pos_ = stone_pos;
  if (neighbours_3d())
    build_y_ = stone_y;
  else
    build_y_.clear();
  build_wall_candidates();
  new_pairs_.clear();
  double rmax = 0.0, xmin = INFINITY, xmax = -INFINITY, zmin = INFINITY, zmax = -INFINITY;
  int nact = 0;
  for (int i = 0; i < n_; ++i) {
    if (!stone_active[i]) continue;
    ++nact;
    rmax = std::max(rmax, stone_radius[i]);
    xmin = std::min(xmin, stone_pos[2 * i]);
    xmax = std::max(xmax, stone_pos[2 * i]);
    zmin = std::min(zmin, stone_pos[2 * i + 1]);
    zmax = std::max(zmax, stone_pos[2 * i + 1]);
  }
  if (nact < 2) {
    pairs_.swap(new_pairs_);
    pairs_.clear();
    if (model_->own_pair_history()) model_->pairs_rebuilt(*this, carried_ = {});
    return;
  }
  // cells no smaller than the largest cut-off; at most ~4 cells per stone even if stones spread far
  double h = 2.0 * rmax + skin_;
  const double max_cells = 4.0 * nact + 16.0;
  while (std::floor((xmax - xmin) / h + 1.0) * std::floor((zmax - zmin) / h + 1.0) > max_cells) h *= 1.5;
  const int ncx = static_cast<int>((xmax - xmin) / h) + 1;
  const int ncz = static_cast<int>((zmax - zmin) / h) + 1;
  if (neighbours_3d())
    list_pairs_3d(nact, h, xmin, zmin, ncx, ncz);
  else
    list_pairs_plane(nact, h, xmin, zmin, ncx, ncz);
  // carry the tangential and rolling springs over (both lists sorted by (i, j)); a model with histories
  // of its own hears where each new pair was
  const bool own = model_->own_pair_history();
  if (own) carried_.assign(new_pairs_.size(), -1);
  std::size_t k = 0;
  for (std::size_t m = 0; m < new_pairs_.size(); ++m) {
    Pair& p = new_pairs_[m];
    while (k < pairs_.size() && (pairs_[k].i < p.i || (pairs_[k].i == p.i && pairs_[k].j < p.j))) ++k;
    if (k < pairs_.size() && pairs_[k].i == p.i && pairs_[k].j == p.j) {
      p.xi = pairs_[k].xi;
      p.mr = pairs_[k].mr;
      p.points = pairs_[k].points;
      if (own) carried_[m] = static_cast<int>(k);
    }
  }
  pairs_.swap(new_pairs_);
  if (own) model_->pairs_rebuilt(*this, carried_);
  update_pair_rolling();
}

// the plane's list: cells in x and z, every pair whose x-z projections are within reach
void DEMSystem::list_pairs_plane(int nact, double h, double xmin, double zmin, int ncx, int ncz) {
  // counting sort of the stones by cell: each cell's stones contiguous and in ascending index order
  const std::size_t ncell = static_cast<std::size_t>(ncx) * ncz;
  cell_start_.assign(ncell + 1, 0);
  cell_next_.assign(static_cast<std::size_t>(n_), -1);  // here: the cell of each active stone
  for (int i = 0; i < n_; ++i) {
    if (!stone_active[i]) continue;
    const int cx = std::min(ncx - 1, static_cast<int>((stone_pos[2 * i] - xmin) / h));
    const int cz = std::min(ncz - 1, static_cast<int>((stone_pos[2 * i + 1] - zmin) / h));
    cell_next_[i] = cx + ncx * cz;
    ++cell_start_[static_cast<std::size_t>(cell_next_[i]) + 1];
  }
  for (std::size_t c = 0; c < ncell; ++c) cell_start_[c + 1] += cell_start_[c];
  sorted_.resize(static_cast<std::size_t>(nact));
  {
    std::vector<int>& fill = cell_fill_;
    fill.assign(cell_start_.begin(), cell_start_.end() - 1);
    for (int i = 0; i < n_; ++i) {
      if (!stone_active[i]) continue;
      sorted_[static_cast<std::size_t>(fill[static_cast<std::size_t>(cell_next_[i])]++)] = {
          stone_pos[2 * i], stone_pos[2 * i + 1], stone_radius[i], i, stone_fixed[i] != 0, 0.0};
    }
  }
  for (int i = 0; i < n_; ++i) {
    if (!stone_active[i]) continue;
    const int cx = cell_next_[i] % ncx, cz = cell_next_[i] / ncx;
    const std::size_t first = new_pairs_.size();
    const double xi = stone_pos[2 * i], zi = stone_pos[2 * i + 1], ri = stone_radius[i] + skin_;
    const bool fi = stone_fixed[i] != 0;
    const int kx0 = std::max(0, cx - 1), kx1 = std::min(ncx - 1, cx + 1);
    for (int kz = std::max(0, cz - 1); kz <= std::min(ncz - 1, cz + 1); ++kz) {
      // the three cells of a row are one contiguous range
      const int b0 = cell_start_[static_cast<std::size_t>(kx0 + ncx * kz)];
      const int b1 = cell_start_[static_cast<std::size_t>(kx1 + ncx * kz) + 1];
      for (int k = b0; k < b1; ++k) {
        const SortedStone& o = sorted_[static_cast<std::size_t>(k)];
        if (o.index <= i || (fi && o.fixed)) continue;
        const double dx = o.x - xi, dz = o.z - zi;
        const double cut = ri + o.r;
        if (dx * dx + dz * dz < cut * cut)
          new_pairs_.push_back({i, o.index, 0.0, std::sqrt(1.0 / (contact_inv_mass_[i] + contact_inv_mass_[o.index]))});
      }
    }
    std::sort(new_pairs_.begin() + static_cast<std::ptrdiff_t>(first), new_pairs_.end(),
              [](const Pair& a, const Pair& b) { return a.j < b.j; });
  }
}

// 3D stones: cells in x, y and z (each stone's y in [0, width]), every pair whose centres are within reach
void DEMSystem::list_pairs_3d(int nact, double h, double xmin, double zmin, int ncx, int ncz) {
  // across the flume the same cell size (at least one cell), capped like the plane's cells
  double hy = h;
  const double max_cells = 4.0 * nact + 16.0;
  while (std::floor(params_.width / hy + 1.0) * ncx * ncz > max_cells && hy < params_.width) hy *= 1.5;
  const int ncy = static_cast<int>(params_.width / hy) + 1;
  const std::size_t ncell = static_cast<std::size_t>(ncx) * ncy * ncz;
  auto cell_y = [&](double y) { return std::max(0, std::min(ncy - 1, static_cast<int>(y / hy))); };
  // counting sort by cell (x fastest): each cell's stones contiguous and in ascending index order
  cell_start_.assign(ncell + 1, 0);
  cell_next_.assign(static_cast<std::size_t>(n_), -1);
  for (int i = 0; i < n_; ++i) {
    if (!stone_active[i]) continue;
    const int cx = std::min(ncx - 1, static_cast<int>((stone_pos[2 * i] - xmin) / h));
    const int cz = std::min(ncz - 1, static_cast<int>((stone_pos[2 * i + 1] - zmin) / h));
    cell_next_[i] = cx + ncx * (cell_y(stone_y[i]) + ncy * cz);
    ++cell_start_[static_cast<std::size_t>(cell_next_[i]) + 1];
  }
  for (std::size_t c = 0; c < ncell; ++c) cell_start_[c + 1] += cell_start_[c];
  sorted_.resize(static_cast<std::size_t>(nact));
  cell_fill_.assign(cell_start_.begin(), cell_start_.end() - 1);
  for (int i = 0; i < n_; ++i) {
    if (!stone_active[i]) continue;
    sorted_[static_cast<std::size_t>(cell_fill_[static_cast<std::size_t>(cell_next_[i])]++)] = {
        stone_pos[2 * i], stone_pos[2 * i + 1], stone_radius[i], i, stone_fixed[i] != 0, stone_y[i]};
  }
  for (int i = 0; i < n_; ++i) {
    if (!stone_active[i]) continue;
    const int c = cell_next_[i];
    const int cx = c % ncx, cy = (c / ncx) % ncy, cz = c / (ncx * ncy);
    const std::size_t first = new_pairs_.size();
    const double xi = stone_pos[2 * i], yi = stone_y[i], zi = stone_pos[2 * i + 1], ri = stone_radius[i] + skin_;
    const bool fi = stone_fixed[i] != 0;
    const int kx0 = std::max(0, cx - 1), kx1 = std::min(ncx - 1, cx + 1);
    for (int kz = std::max(0, cz - 1); kz <= std::min(ncz - 1, cz + 1); ++kz) {
      for (int ky = std::max(0, cy - 1); ky <= std::min(ncy - 1, cy + 1); ++ky) {
        // the three cells of a row along x are one contiguous range
        const std::size_t row = static_cast<std::size_t>(ncx) * (ky + static_cast<std::size_t>(ncy) * kz);
        const int b0 = cell_start_[row + kx0], b1 = cell_start_[row + kx1 + 1];
        for (int k = b0; k < b1; ++k) {
          const SortedStone& o = sorted_[static_cast<std::size_t>(k)];
          if (o.index <= i || (fi && o.fixed)) continue;
          const double dx = o.x - xi, dy = o.y - yi, dz = o.z - zi;
          const double cut = ri + o.r;
          if (dx * dx + dy * dy + dz * dz < cut * cut)
            new_pairs_.push_back(
                {i, o.index, 0.0, std::sqrt(1.0 / (contact_inv_mass_[i] + contact_inv_mass_[o.index]))});
        }
      }
    }
    std::sort(new_pairs_.begin() + static_cast<std::ptrdiff_t>(first), new_pairs_.end(),
              [](const Pair& a, const Pair& b) { return a.j < b.j; });
  }
}

std::vector<std::array<int, 2>> DEMSystem::neighbour_pairs() const {
  std::vector<std::array<int, 2>> out;
  out.reserve(pairs_.size());
  for (const Pair& p : pairs_) out.push_back({p.i, p.j});
  return out;
}

std::vector<std::array<int, 2>> DEMSystem::overlapping_pairs_reference() const {
  std::vector<std::array<int, 2>> out;
  for (int i = 0; i < n_; ++i) {
    if (!stone_active[i]) continue;
    for (int j = i + 1; j < n_; ++j) {
      if (!stone_active[j] || (stone_fixed[i] && stone_fixed[j])) continue;
      const double dx = stone_pos[2 * j] - stone_pos[2 * i], dz = stone_pos[2 * j + 1] - stone_pos[2 * i + 1];
      const double rs = stone_radius[i] + stone_radius[j];
      if (dx * dx + dz * dz < rs * rs) out.push_back({i, j});
    }
  }
  return out;
}

std::vector<std::array<int, 2>> DEMSystem::overlapping_pairs() {
  prepare();
  build_neighbours();
  std::vector<std::array<int, 2>> out;
  for (const Pair& p : pairs_) {
    const int i = p.i, j = p.j;
    const double dx = stone_pos[2 * j] - stone_pos[2 * i], dz = stone_pos[2 * j + 1] - stone_pos[2 * i + 1];
    const double rs = stone_radius[i] + stone_radius[j];
    if (dx * dx + dz * dz < rs * rs) out.push_back({i, j});
  }
  return out;
}

}  // namespace vofdem
