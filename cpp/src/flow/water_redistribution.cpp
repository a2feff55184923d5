#include "vofdem/flow/water_redistribution.h"

#include <algorithm>

namespace vofdem {

WaterRedistribution::WaterRedistribution(const Grid2D& grid) : grid_(grid) {
  const int nc = grid_.ncell();
  excess_cells_.reserve(nc);
  excess_volume_.reserve(nc);
  queue_.assign(nc, 0);
  stamp_.assign(nc, 0u);
}

int WaterRedistribution::apply(const std::vector<double>& n_old, const std::vector<double>& n_new,
                               std::vector<double>& F) {
  const int nx = grid_.nx(), nz = grid_.nz();
  excess_cells_.clear();
  excess_volume_.clear();
  moved_ = 0.0;
  // every cell's new fraction first, so that cells a stone left can take the water of cells it entered
  for (int k = 0; k < nz; ++k) {
    const double area = grid_.cell_area(k);
    for (int i = 0; i < nx; ++i) {
      const int c = i + nx * k;
      const double no = n_old[c], nn = n_new[c];
      if (no == nn) continue;
      if (nn <= 0.0) {  // a cell closed by a solid: its water has to go elsewhere
        const double v = no * F[c] * area;
        F[c] = 0.0;
        if (v > 0.0) excess_cells_.push_back(c), excess_volume_.push_back(v);
        continue;
      }
      const double v = no * F[c] * area;
      const double room = nn * area;
      if (v > room) {
        F[c] = 1.0;
        excess_cells_.push_back(c);
        excess_volume_.push_back(v - room);
      } else {
        F[c] = v / room;
      }
    }
  }
  int failed = -1;
  for (std::size_t e = 0; e < excess_cells_.size(); ++e) {
    const int c = excess_cells_[e];
    moved_ += excess_volume_[e];
    if (spread(c, excess_volume_[e], n_new, F) >= 0 && failed < 0) failed = c;
  }
  return failed;
}

// breadth-first from cell c over open cells; fills each cell with room until the excess is placed
int WaterRedistribution::spread(int c, double excess, const std::vector<double>& n, std::vector<double>& F) {
  const int nx = grid_.nx(), nz = grid_.nz();
  if (++stamp_now_ == 0u) {  // wrapped: clear the marks once every 2^32 calls
    std::fill(stamp_.begin(), stamp_.end(), 0u);
    stamp_now_ = 1u;
  }
  int head = 0, tail = 0;
  queue_[tail++] = c;
  stamp_[c] = stamp_now_;
  while (head < tail && excess > 0.0) {
    const int d = queue_[head++];
    const int i = d % nx, k = d / nx;
    if (d != c && n[d] > 0.0) {
      const double cap = n[d] * grid_.cell_area(k);
      const double room = cap * (1.0 - F[d]);
      if (room > 0.0) {
        if (room <= excess) {
          F[d] = 1.0;
          excess -= room;
        } else {
          F[d] += excess / cap;
          excess = 0.0;
        }
      }
    }
    // neighbours: up, left, right, down (displaced water rises first); only through open cells
    const int nb[4] = {k + 1 < nz ? d + nx : -1, i > 0 ? d - 1 : -1, i + 1 < nx ? d + 1 : -1, k > 0 ? d - nx : -1};
    for (int q : nb) {
      if (q < 0 || stamp_[q] == stamp_now_ || n[q] <= 0.0) continue;
      stamp_[q] = stamp_now_;
      queue_[tail++] = q;
    }
  }
  if (excess > 0.0) {
    // no room anywhere: keep the water in the cell (F > 1 is caught by the fluid's checks)
    F[c] += excess / (n[c] > 0.0 ? n[c] * grid_.cell_area(c / nx) : grid_.cell_area(c / nx));
    return c;
  }
  return -1;
}

}  // namespace vofdem
