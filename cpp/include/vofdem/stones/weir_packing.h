// Packing generator of a trapezoidal rubble mound weir (Maeno & Tomita 2008, sec. 2.3: "the lowest
// particles are fixed to the bottom and other particles were packed using free packing method due to
// gravity").
//
// The weir occupies, above the bed z_bed, the trapezoid of height H, crest length L_c and slopes
// a_up, a_down starting at x_toe:  z - z_bed <= min(H, (x - x_toe) tan a_up, (x_end - x) tan a_down),
// x_end = x_toe + H / tan a_up + L_c + H / tan a_down.
// Steps: (1) a bottom row of touching stones, fixed to the bed, along the trapezoid's base; (2) free
// stones on a loose lattice filling the trapezoid extended upwards, inside temporary walls along the
// two slopes, dropped under gravity with the DEM until at rest; (3) stones reaching above the crest
// removed; (4) the slope walls removed and the mound settled until every stone moves slower than
// rest_speed. Diameters are d_mean (1 + d_spread (2u - 1)), u uniform in [0, 1) from std::mt19937_64
// with our own conversion (so a seed gives the same weir with any standard library).
//
// What depends on the stone model (how a stone is drawn, the bottom row, whether a stone fits at a
// point, the DEM system of the placed stones) is the model's StonePacking (stone_packing.h): discs in
// disc_model.cpp, polygons in polygon_packing.cpp. Models of dimensions() == 3 (spheres) are packed by
// the 3D generator, weir_packing_3d.h, which pack_weir calls for them.
#pragma once

#include <cstdint>
#include <string>

#include "vofdem/stones/clump.h"
#include "vofdem/stones/dem_system.h"
#include "vofdem/stones/polygon.h"

namespace vofdem {

struct WeirSpec {
  double height = 0.25;         // H [m], crest above the bed
  double crest = 0.20;          // L_c [m], crest length
  double slope_up_deg = 27.0;   // upstream slope [deg]
  double slope_down_deg = 27.0; // downstream slope [deg] (paper: 27)
  double x_toe = 1.0;           // upstream toe [m] along the flume
  double z_bed = 0.0;           // bed height [m]
  // the stones' material: no default (0: unset, refused by check_weir_spec); the scene's stones.diameter
  // and stones.density give them. The trapezoid above keeps the Maeno weir's shape as a default: a shape
  // packs any stones alike, while a default size or density would silently set every stone's weight
  double d_mean = 0.0;          // mean stone diameter [m], > 0, required
  double d_spread = 0.1;        // half-width of the uniform diameter distribution, relative [-]
  double density = 0.0;         // stone density [kg/m^3], > 0, required
  std::uint64_t seed = 0;       // random seed of the diameters and lattice jitter
  double settle_time_max = 6.0; // simulated time allowed for each settling phase [s]
  double rest_speed = 1e-3;     // packing is at rest when every stone is slower [m/s]
  // 3D models: the stone-stone friction [-] of the pour's rounds, in [0, 2], a compaction (the weir's own
  // friction returns for a last settling before the trim); -1: the model's own (StonePacking::pour_friction:
  // 0.1 for clumps, the weir's friction throughout for spheres). The plane's generator refuses any other
  double compaction_friction = -1.0;
  // the stone model drawn (stone_model.h), by its registered name; the model must have a packing
  std::string shape = "disc";
  PolygonSpec polygon;          // how polygon stones are drawn (shape "polygon")
  ClumpMix clump;               // which library shapes clump stones draw (shape "clump"; clump.h)

  double x_end() const;                 // downstream toe [m]
  double top(double x) const;           // trapezoid's height above the bed at x [m] (0 outside)
  double area() const;                  // trapezoid area [m^2]
};

struct WeirPackingReport {
  int n_stones = 0;            // stones in the weir (fixed included)
  int n_fixed = 0;             // fixed bottom stones
  // porosity of the trapezoid [-]: 2D models 1 - (stone area inside) / area; 3D models (weir_packing_3d.h)
  // that of the prism across the width, 1 - (stone volume inside) / (area B)
  double porosity = 0.0;
  // 3D models: the mean number of stones a line across the flume through the trapezoid crosses [-] (0 in
  // the plane)
  double stones_across = 0.0;
  double max_speed = 0.0;      // largest stone speed at the end [m/s]
  double settle_time = 0.0;    // simulated time used by the settling phases [s]
  double outline_error = 0.0;  // weir_outline_error() of the result [m]
  double wall_seconds = 0.0;   // wall-clock time of the generation [s]
};

// throws std::invalid_argument naming the first bad field of the spec
void check_weir_spec(const WeirSpec& spec);

// packs the weir with the contact law of `params` (its walls are kept if any, else the bed z = z_bed
// is added); returns the DEM system, at rest, and fills `report`
DEMSystem pack_weir(const WeirSpec& spec, const DEMParams& params, WeirPackingReport& report);

// largest deviation [m] of the packing from the trapezoid: the larger of (a) how far any stone reaches
// outside the trapezoid and (b) how far any point of the trapezoid's slopes and crest lies from the
// nearest stone (discs or polygons)
double weir_outline_error(const DEMSystem& system, const WeirSpec& spec);

// 2D porosity of the trapezoid filled by the stones (discs or polygons), sampled on a grid of spacing h [m]
double weir_porosity(const DEMSystem& system, const WeirSpec& spec, double h = 0.002);

}  // namespace vofdem
