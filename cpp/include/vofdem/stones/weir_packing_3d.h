// Packing generator of a trapezoidal rubble mound weir of 3D stones across the flume (Maeno & Tomita
// 2008, sec. 2.3: "the lowest particles are fixed to the bottom and other particles were packed using
// free packing method due to gravity").
//
// The weir is the prism across the flume's width B (DEMParams::width, between the side walls y = 0 and
// y = B) of the trapezoid of weir_packing.h. Steps, as in the plane's generator:
//   (1) a bottom layer of touching stones fixed on the bed over the base [x_toe, x_end]: rows along x,
//       spaced evenly across the width by at least the largest bounding diameter;
//   (2) free stones on a loose 3D lattice (face-centred: square layers a pitch / sqrt(2) apart, alternate
//       ones shifted half a pitch in x and y, pitch 1.04 times the largest bounding diameter, centres
//       jittered by +-0.02 d_mean in x and y) filling the trapezoid extended upwards (its slopes continued
//       to 1.3 H), inside temporary walls along the two slopes, dropped
//       under gravity with the DEM until at rest, in rounds that refill the room the compaction left;
//   (3) stones whose centres lie above the crest by more than d_mean / 4 removed (the plane's criterion,
//       in x-z);
//   (4) the slope walls removed and the mound settled until every stone moves slower than rest_speed;
//       stones that rolled off a toe (centre more than d_mean / 2 outside the trapezoid in x-z) removed
//       and the rest settled again.
// Diameters and jitter come from std::mt19937_64 with the plane generator's conversion
// (packing_random.h), site by site in the order: diameter, x jitter, y jitter; so a seed gives the same
// weir bit for bit. The plane's last steps (topping up hollows, stones laid by hand) are not made.
//
// What depends on the stone's shape is asked of the model's StonePacking (stone_packing.h): a stone of
// nominal diameter d (its bounding radius and shape), whether stones rolling off a toe are removed, and
// the DEM system of the placed stones. Free sites are tested with bounding spheres; the volume in the
// porosity is the model's footprint on a fine grid (StoneModel::map_footprint, each cell's slab across
// the width) or the packing's own (StonePacking::porosity_3d: clumps sample their sub-spheres on a 3D
// point grid, weir_porosity_3d_spheres).
#pragma once

#include <vector>

#include "vofdem/stones/dem_system.h"
#include "vofdem/stones/weir_packing.h"

namespace vofdem {

// packs the weir of 3D stones (a model of dimensions() == 3; pack_weir calls it for them) with the
// contact law and width of `params` (its walls kept if any, else the bed z = z_bed added); returns the
// DEM system at rest and fills `report` (porosity: that of the prism; stones_across)
DEMSystem pack_weir_3d(const WeirSpec& spec, const DEMParams& params, WeirPackingReport& report);

// the porosity [-] of the trapezoid's prism across the width: 1 - (stone volume inside) / (area B), the
// stones' volume in each cell of a grid of spacing h [m] from the model's footprint, cells counted
// inside when their centre is
double weir_porosity_3d(const DEMSystem& system, const WeirSpec& spec, double h = 0.002);

// the same from stones given as spheres (x, y, z, r) [m] each (a clump's sub-spheres: their union counted
// once): 1 - (points of a grid of spacing h [m] over the prism, y in [0, width], inside a sphere) / (points
// of the grid inside the prism), the points at the cells' centres
double weir_porosity_3d_spheres(const std::vector<double>& sphere, double width, const WeirSpec& spec,
                                double h = 0.002);

// the mean number of stones [-] a line across the flume through the trapezoid crosses: the stones'
// x-z outlines (StoneModel::covers) counted at the points of a grid of spacing h [m] inside
double weir_stones_across(const DEMSystem& system, const WeirSpec& spec, double h = 0.004);

}  // namespace vofdem
