// Geometric VOF advection of the water fraction F through a porous medium: seed paper eq. (4).
//
//   n dF/dt + d(u F)/dx + d(w F)/dz = 0                                                    (4)
//
// with (u, w) the superficial face velocities (div u = 0) and n the cell porosity. The interface in
// each cell is a PLIC line (normal from Youngs' gradient of F, or the mixed Youngs-centred normal);
// fluxes are the exact water areas swept through each face, operator-split by direction with the
// alternating order of Strang splitting and the divergence correction of Weymouth & Yue (2010), so
// that the water volume sum(n F V) is conserved to round-off in a closed box and F stays in [0, 1]
// for a CFL number up to 1/2 (see vof_stable_dt).
//
// References: D. L. Youngs (1982); G. D. Weymouth and D. K.-P. Yue (2010), J. Comput. Phys. 229,
// 2853-2865; R. Scardovelli and S. Zaleski (2000), J. Comput. Phys. 164, 228-237 (line-area
// relations); E. Aulisa, S. Manservisi, R. Scardovelli and S. Zaleski (2007), J. Comput. Phys. 225,
// 2301-2319 (mixed Youngs-centred normal).
#pragma once

#include <vector>

#include "vofdem/common/grid.h"

namespace vofdem {

// water fraction carried in by each boundary face where the flow enters the domain; faces where the
// flow leaves take the fraction of the cell they leave. Sizes: left/right nz, bottom/top nx
// (fractions in [0, 1], e.g. 1 below the inflow water level). An empty vector means 0 on that side.
struct VofBoundaryInflow {
  std::vector<double> left, right, bottom, top;
  void resize(const Grid2D& grid, double value = 0.0);
};

// work arrays reused from step to step so that advection allocates nothing while stepping (they are
// sized on first use, or again if the grid changes), the water fluxes of the last step and the
// clipping report
struct VofScratch {
  // water volume [m^2 per metre of width] that crossed each face during the last step, signed along
  // +x (size nface_x) and +z (size nface_z); e.g. the discharge through the right end is
  // sum over k of face_flux_x[face_x(nx, k)] / dt [m^2/s]
  std::vector<double> face_flux_x, face_flux_z;
  std::vector<double> cell_c;  // divergence-correction indicator of the last step (0 or 1)
  // F leaves [0, 1] only by round-off when the CFL limit holds; such excursions are clipped silently.
  // Larger ones (beyond kVofClipTolerance) are clipped too but counted here, summed over the steps since
  // the caller last set them to 0 (VOFGrid does so before each step's advection):
  long long clip_count = 0;  // number of cell updates clipped by more than kVofClipTolerance
  double clip_max = 0.0;     // largest such excursion [-]
  // the sweep along x: the new F of the rows done (its fluxes read the row below as updated), one row
  // of fluxes per thread, and which rows read the row below (a reconstructed cell with an outflow)
  std::vector<double> cell_F_new, row_flux;
  std::vector<unsigned char> row_reads_below;
};

// interface normal of the PLIC reconstruction
enum class VofNormal {
  kYoungs = 0,               // Youngs (1982): weighted 3x3 gradient of F; the default
  kMixedYoungsCentered = 1,  // Aulisa et al. (2007): height-function normal of the 3x3 block, else Youngs
};

// excursions of F outside [0, 1] up to this size [-] are round-off and clipped without report
constexpr double kVofClipTolerance = 1e-12;

// advances cell_F (size ncell) by dt [s]. cell_porosity: n per cell, 0 = solid (never changed);
// face_u (size nface_x), face_w (size nface_z): superficial velocities [m/s], zero on every face of a
// solid cell. x_first chooses the sweep order (alternate it from step to step). Throws
// std::invalid_argument for wrong sizes, dt <= 0 or a non-zero velocity on a solid cell's face, and
// std::runtime_error (cell_F untouched) if F in a fluid cell or a velocity is not finite, or if the
// directional CFL number |u| dt / (n dx) (resp. |w| dt / (n dz)) of a face and a fluid cell next to
// it exceeds 1; F stays in [0, 1] for a step from vof_stable_dt with cfl <= 1/2. `normal` picks the
// interface normal. Both sweeps' water fluxes are left in scratch.face_flux_x/z.
void advect_vof(const Grid2D& grid, const std::vector<double>& cell_porosity, const std::vector<double>& face_u,
                const std::vector<double>& face_w, const VofBoundaryInflow& inflow, double dt, bool x_first,
                std::vector<double>& cell_F, VofScratch& scratch, VofNormal normal = VofNormal::kYoungs);

// the same on raw arrays of the sizes above (the numpy binding's entry: cell_F updated in place)
void advect_vof(const Grid2D& grid, const double* cell_porosity, const double* face_u, const double* face_w,
                const VofBoundaryInflow& inflow, double dt, bool x_first, double* cell_F, VofScratch& scratch,
                VofNormal normal = VofNormal::kYoungs);

// the largest stable advection step [s] at the CFL number `cfl` (usual value 0.3-0.45): in every
// fluid cell and direction, the inflow CFL numbers (|u| dt / (n dx) over the faces where water may
// enter) add up to at most cfl and the outflow ones to at most 2 cfl. In a uniform flow this is
// |u| dt / (n dx) <= cfl. With cfl <= 1/2 a sweep whose indicator c matches F at its start maps
// [0, 1] into [0, 1] (Weymouth & Yue's argument; the sums matter where the flow converges into a
// cell); the second sweep, whose c is frozen at the step's start for conservation, has needed no
// clipping in any test (VofScratch::clip_count). +inf when nothing moves.
double vof_stable_dt(const Grid2D& grid, const std::vector<double>& cell_porosity, const std::vector<double>& face_u,
                     const std::vector<double>& face_w, double cfl);
double vof_stable_dt(const Grid2D& grid, const double* cell_porosity, const double* face_u, const double* face_w,
                     double cfl);

// PLIC helpers (unit square cell scaled to dx x dz), exposed for tests. The normal (mx, mz) points out
// of the water, any length; coordinates are relative to the rectangle's lower-left corner [m].
// line constant alpha [m x |m|] such that the area below m.x = alpha inside [0,dx]x[0,dz] equals
// f dx dz (f in [0, 1]); exact (Scardovelli & Zaleski 2000)
double plic_line_constant(double mx, double mz, double dx, double dz, double f);
// area [m^2] of {m.x <= alpha} inside the rectangle [0,dx]x[0,dz]
double plic_area_below(double mx, double mz, double dx, double dz, double alpha);

}  // namespace vofdem
