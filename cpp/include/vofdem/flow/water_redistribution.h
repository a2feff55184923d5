// Water volume kept exact when the porosity of the cells changes (stones moving through the grid).
//
//   n_new F_new V = n_old F_old V        in every cell, then
//   excess (F_new - 1) n_new V > 0      moved to the nearest cells with room (up, left, right, down)
//
// The VOF advection conserves sum(n F V) for a porosity fixed during a step; between steps the coupler
// maps the stones' new positions onto the porosity, and this keeps the water volume of each cell. A
// stone sinking into a full cell displaces water that cannot stay there (F would exceed 1): it goes
// to the neighbours with room, searched breadth-first, the cell above first (displaced water rises),
// then left, right and down, so the volume sum(n F V) is kept to round-off. A cell that a stone leaves
// keeps its water volume too (F drops); displaced water from a neighbour usually refills it, since
// every cell's new fraction is computed before any excess is moved. Cells whose porosity did not
// change are not touched (bit for bit). The velocity field is not altered: the superficial velocities
// stay as they are (the projection does not see dn/dt; documented approximation of the coupling).
//
// Reference: the volume-preserving fraction update follows the porosity-weighted VOF of
// S. Maeno and A. Tomita (2008), eq. (4), n dF/dt + div(u F) = 0, applied to a change of n.
#pragma once

#include <vector>

#include "vofdem/common/grid.h"

namespace vofdem {

class WaterRedistribution {
 public:
  // scratch sized for the grid (the only allocation)
  explicit WaterRedistribution(const Grid2D& grid);

  // rescales F [-] for the porosity change n_old -> n_new (sizes ncell) and moves the excess; returns
  // -1, or the index of a cell whose excess found no room anywhere (the water stays there, F > 1)
  int apply(const std::vector<double>& n_old, const std::vector<double>& n_new, std::vector<double>& F);

  // water moved between cells by the last call, per unit width [m^2]
  double moved_volume() const { return moved_; }

 private:
  int spread(int c, double excess, const std::vector<double>& n, std::vector<double>& F);

  Grid2D grid_;
  std::vector<int> excess_cells_;
  std::vector<double> excess_volume_;
  std::vector<int> queue_;
  std::vector<unsigned> stamp_;
  unsigned stamp_now_ = 0;
  double moved_ = 0.0;
};

}  // namespace vofdem
