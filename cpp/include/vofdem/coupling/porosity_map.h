// Porosity of the cells from the stones that cover them: seed paper section 2.4, eq. (11).
//
//   n = (A_f + A_s n_exp) / (A_f + A_s),   A_f + A_s = A_c                                  (11)
//
// A stone is a disc (a 2D cylinder) of centre (x, z) [m] and radius r [m]. A_s [m^2] is the area of
// the cell covered by stones, the sum over the discs of the exact disc-rectangle intersection areas,
// capped at the cell area A_c = dx dz (overlapping discs never cover more than the whole cell), and
// A_f = A_c - A_s the free area. A cell fully covered by stones gets the packing porosity n_exp
// (0.41 measured for the paper's stones), not zero: the 2D discs stand for a 3D matrix of spheres
// whose pores stay open. So n = 1 - (1 - n_exp) A_s / A_c lies in [n_exp, 1].
//
// Two ways to obtain the areas:
//  * exact: the closed-form area of a disc in a rectangle (disc_rect_area below), evaluated through
//    the primitive Phi at the grid nodes around the disc (its square roots and arc tangents depend
//    on the node's column or row alone, so a disc costs a few of them per row and column).
//  * lookup: the paper's precomputed table. The cell holding the disc centre is split into m x m
//    sub-areas; for the centre placed at each sub-area's centre, the covered area of every cell of
//    the stencil around it is tabulated once. Mapping a disc is then a read and a sum per stencil
//    cell. Because x is uniform, a table depends only on the z-faces near the centre row and on the
//    radius: rows with the same faces within reach (all rows of a uniformly spaced region) share one
//    table; radii are tabulated at nodes r_min, r_min + dr, ..., r_max, the tables hold A / r^2 and
//    are interpolated linearly in r between the two nodes around the disc's radius, then multiplied
//    by r^2 (so a disc inside the grid keeps exactly pi r^2). Tables are built at construction.
//    Error: snapping the centre by at most half a sub-area (dx/2m, dz/2m) moves each cell's area by
//    at most about (arc length in the cell) x (dx + dz) / 2m, first order in 1/m; the radius
//    interpolation adds O(dr^2) away from tangency. A disc's total area is pi r^2 to round-off.
//    Discs whose centre lies outside the grid use the exact method. Measured costs and errors:
//    docs/porosity.md and benchmarks/results/porosity_lookup_cost.md.
//
// Polygon stones (map_polygons, polygon_porosity.cpp): each convex polygon is clipped to the columns of
// its bounding box and each column strip to the rows (Sutherland-Hodgman against axis-aligned lines),
// so the areas are exact up to round-off and sum to the polygon's area; they feed the same per-stone
// cell lists and eq. (11). The lookup table is built for discs and is refused for polygons.
//
// 3D spheres across a flume of width B (map_spheres, sphere_porosity.cpp): each cell gets the sphere's
// exact volume in its slab dx x dz x B over B (slab_volume.h), an area per unit width whose parts sum to
// V / B; with n_exp = 0, eq. (11) is then the true solid fraction n = 1 - V_s / (dx dz B).
//
// 3D clumps of spheres (map_clumps, sphere_porosity.cpp): each sub-sphere's slab volumes scaled by
// V_union / sum_k V_k (slab_volume.h), summed per cell into one cell list per stone, so a stone's parts
// sum to its union volume / width and a cell reached by several of its sub-spheres is listed once.
//
// Reference: S. Maeno and A. Tomita (2008), Destruction prediction of a rubble mound weir using
// VOF-DEM coupled model, ICHE 2008, Nagoya, section 2.4 and Fig. 3.
#pragma once

#include <algorithm>
#include <cstdint>
#include <stdexcept>
#include <string>
#include <vector>

#include "vofdem/common/grid.h"
#include "vofdem/common/profile.h"

namespace vofdem {

// exact area [m^2] of the disc of centre (cx, cz) [m] and radius r [m] inside the rectangle
// [x0, x1] x [z0, z1] [m]; valid for any relative position. Checks: finite values, r >= 0,
// x0 <= x1, z0 <= z1.
double disc_rect_area(double cx, double cz, double r, double x0, double x1, double z0, double z1);
// the same without argument checks, for inner loops
double disc_rect_area_unchecked(double cx, double cz, double r, double x0, double x1, double z0, double z1);

// Phi(X, Z) = signed area of {0 < x < X, 0 < z < Z} inside the disc of radius r centred at the
// origin; odd in X and in Z. The rectangle area is Phi(x1,z1) - Phi(x0,z1) - Phi(x1,z0) + Phi(x0,z0)
// in coordinates relative to the centre.
double disc_corner_primitive(double X, double Z, double r);

// eq. (11) for one cell: porosity [-] from covered area a_s [m^2], cell area a_c [m^2] and n_exp [-]
// (the clamp only removes round-off: the formula itself lies in [n_exp, 1] for 0 <= a_s <= a_c)
inline double porosity_eq11(double a_s, double a_c, double n_exp) {
  const double s = a_s < a_c ? a_s : a_c;
  const double n = (a_c - s + s * n_exp) / a_c;
  return n < n_exp ? n_exp : (n > 1.0 ? 1.0 : n);
}

enum class PorosityMethod {
  kExact = 0,   // closed-form disc-rectangle areas
  kLookup = 1,  // the paper's precomputed sub-area table
};

struct PorosityParams {
  PorosityMethod method = PorosityMethod::kExact;
  // sub-areas per side of the centre cell for the lookup table [-]; usual 8 (2 .. 64)
  int m = 8;
  // packing porosity of the stones, eq. (11) [-]; 0.41 in the paper
  double n_exp = 0.41;
  // smallest and largest disc radius that will be mapped [m]; usual 0.0216 and 0.0264 (4.8 cm +-10 %)
  double r_min = 0.024;
  double r_max = 0.024;
  // spacing of the radius nodes of the lookup tables [m]; usual 1e-3 (1 mm: finer gains nothing at m <= 32)
  double dr = 1e-3;
  // largest number of discs one call maps (sizes the per-disc cell lists) [-]
  int max_discs = 1024;
};

class PorosityMapper {
 public:
  // builds the stencils (and, for the lookup method, the tables) for `grid`; allocation happens here only
  PorosityMapper(const Grid2D& grid, const PorosityParams& params);

  // maps n discs of centres (disc_x, disc_z) [m] and radii disc_r [m] onto cell_solid_area and
  // cell_porosity; stone_active (may be null) skips discs whose flag is 0. Allocates nothing.
  // Throws std::invalid_argument for n > max_discs, a non-finite centre or a radius outside
  // [r_min, r_max].
  void map(int n, const double* disc_x, const double* disc_z, const double* disc_r,
           const std::uint8_t* stone_active = nullptr);
  void map(const std::vector<double>& disc_x, const std::vector<double>& disc_z, const std::vector<double>& disc_r);
  // maps n convex polygon stones (centres (x, z) [m], angles [rad] counter-clockwise, body-frame vertices
  // poly_vertex (x, z pairs) [m] of stone j from poly_offset[j] to poly_offset[j+1]-1, as DEMSystem holds
  // them) onto the same outputs as map(), with exact polygon-cell areas. Throws std::invalid_argument
  // for the lookup method, n > max_discs, a non-finite centre, 3 > vertices > 16 or a polygon reaching
  // farther than r_max from its centre. Allocates nothing.
  void map_polygons(int n, const double* x, const double* z, const double* angle, const double* poly_vertex,
                    const int* poly_offset, const std::uint8_t* active = nullptr);

  // maps n 3D spheres across a flume of width [m] (centres (x, z) [m], radii r [m]) onto the same outputs:
  // each cell's "area" is the sphere's exact volume in the cell's slab dx x dz x width over the width
  // (sphere_porosity.cpp), so that eq. (11) with n_exp = 0 gives the true solid fraction. Throws
  // std::invalid_argument for the lookup method, width <= 0, n > max_discs, a non-finite centre or a
  // radius outside [r_min, r_max]. Allocates nothing.
  void map_spheres(int n, const double* x, const double* z, const double* r, double width,
                   const std::uint8_t* active = nullptr);
  // maps n 3D clumps across a flume of width [m] onto the same outputs: stone j at (x, z) [m] turned by
  // quat[4j..4j+3] (w, x, y, z; principal frame to world) owns the sub-spheres sphere[4g..4g+3] (x, y, z, r
  // [m] in its principal frame) for g in [offset[j], offset[j+1]), of union volume volume[j] [m^3]; each
  // sub-sphere's slab volumes are scaled by volume[j] / sum_g V_g and summed per cell (one entry per cell,
  // cells in the order of map_spheres). Throws std::invalid_argument for the lookup method, width <= 0,
  // n > max_discs, a non-finite centre or quaternion, 1 > sub-spheres > 8, a volume outside (0, inf) or a
  // clump reaching farther than r_max from its centre. Allocates nothing.
  void map_clumps(int n, const double* x, const double* z, const double* quat, const double* sphere,
                  const int* offset, const double* volume, double width, const std::uint8_t* active = nullptr);

  const Grid2D& grid() const { return grid_; }
  const PorosityParams& params() const { return params_; }

  // covered area A_s of each cell, capped at the cell area [m^2], size ncell
  std::vector<double>& cell_solid_area() { return cell_solid_area_; }
  // porosity of eq. (11) of each cell [-], size ncell
  std::vector<double>& cell_porosity() { return cell_porosity_; }
  // per-disc overlapped cells in CSR form: disc j covers cells stone_cell_index[p] with area
  // stone_cell_area[p] [m^2] (uncapped) for p in [stone_cell_offsets[j], stone_cell_offsets[j+1]).
  // Sized for max_discs; only the first n + 1 offsets of the last call are meaningful.
  std::vector<int>& stone_cell_offsets() { return stone_cell_offsets_; }
  std::vector<int>& stone_cell_index() { return stone_cell_index_; }
  std::vector<double>& stone_cell_area() { return stone_cell_area_; }
  // number of discs of the last call
  int ndisc() const { return ndisc_; }

  // number of distinct lookup tables (row classes x radius nodes) and their memory [bytes]
  int table_count() const { return static_cast<int>(tables_.size()); }
  std::size_t table_bytes() const;
  // row class of each grid row for the lookup tables (rows with equal z-faces within reach share one)
  const std::vector<int>& row_class() const { return row_class_; }

  StageProfile& profile() { return profile_; }

 private:
  struct RowClass {
    int dk_lo, dk_hi;            // stencil rows k + dk_lo .. k + dk_hi (clipped to the grid)
    std::vector<double> z_rel;   // faces of those rows relative to the centre row's bottom face [m]
  };
  void build_row_classes();
  void build_tables();
  int add_exact(int j, double x, double z, double r, int p);
  int add_lookup(int j, double x, double z, double r, int p);
  int add_polygon(const double* world, int count, int p);
  // the preconditions of mapping 3D stones (shape: "spheres", "clumps") over a slab of width [m]: the exact
  // method and a finite positive width
  void require_slab_mapping(const char* shape, double width) const;
  int add_sphere(double x, double z, double r, double width, int p);
  int add_clump(double x, double z, const double* quat, const double* sphere, int count, double volume, double width,
                int p);
  void apply_eq11();
  // cell c gets area [m^2] of the stone being mapped: the cell's sum and the stone's CSR entry p; returns p + 1
  int append_cell(int c, double area, int p) {
    cell_solid_area_[c] += area;
    stone_cell_index_[p] = c;
    stone_cell_area_[p] = area;
    return p + 1;
  }
  // what map() and map_polygons() share: n checked against max_discs and each active stone by check(j)
  // before any output is touched (a refused call leaves the last map intact), the areas cleared, each
  // active stone's cells added by add(j, p) (returns the next free CSR slot), eq. (11) applied
  template <class Check, class Add>
  void map_each(int n, const std::uint8_t* active, Check&& check, Add&& add) {
    ScopedStage timer(profile_, stage_map_);
    if (n < 0 || n > params_.max_discs)
      throw std::invalid_argument("ndisc = " + std::to_string(n) + " is outside the allowed range [0, " +
                                  std::to_string(params_.max_discs) + "] (max_discs)");
    for (int j = 0; j < n; ++j)
      if (!active || active[j]) check(j);
    std::fill(cell_solid_area_.begin(), cell_solid_area_.end(), 0.0);
    int p = 0;
    for (int j = 0; j < n; ++j) {
      stone_cell_offsets_[j] = p;
      if (!active || active[j]) p = add(j, p);
    }
    stone_cell_offsets_[n] = p;
    ndisc_ = n;
    apply_eq11();
  }

  Grid2D grid_;
  PorosityParams params_;
  int sx_ = 0;       // stencil half-width in columns: offsets -sx .. +sx
  int nradius_ = 1;  // radius nodes of the lookup tables
  int max_cells_per_disc_ = 0;

  std::vector<int> row_class_;
  std::vector<RowClass> classes_;
  // tables_[c * nradius + q]: (m*m) x (ncol * nrow of class c) areas [m^2], sub-area major
  std::vector<std::vector<double>> tables_;

  std::vector<double> cell_solid_area_, cell_porosity_;
  std::vector<int> stone_cell_offsets_, stone_cell_index_;
  std::vector<double> stone_cell_area_;
  std::vector<double> node_phi_;  // scratch of the exact method: node values, then 3 lines of scratch_line_
  int scratch_line_ = 0;
  std::vector<double> poly_scratch_;  // scratch of map_polygons: world vertices, a strip, clip buffers
  std::vector<double> clump_patch_;   // scratch of map_clumps: one stone's volumes on its stencil's cells
  int ndisc_ = 0;

  StageProfile profile_;
  int stage_map_ = 0;
};

}  // namespace vofdem
