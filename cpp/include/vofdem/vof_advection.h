// Geometric VOF advection of the water fraction F through a porous medium: seed paper eq. (4).
//
//   n dF/dt + d(u F)/dx + d(w F)/dz = 0                                                    (4)
//
// with (u, w) the superficial face velocities (div u = 0) and n the cell porosity. The interface in
// each cell is a PLIC line (normal from Youngs' gradient of F); fluxes are the exact water areas
// swept through each face, operator-split by direction with the alternating order of Strang
// splitting and the divergence correction of Weymouth & Yue (2010), so that the water volume
// sum(n F V) is conserved to round-off in a closed box and F stays in [0, 1] for a CFL below 1/2.
//
// References: D. L. Youngs (1982); G. D. Weymouth and D. K.-P. Yue (2010), J. Comput. Phys. 229,
// 2853-2865; R. Scardovelli and S. Zaleski (2000), J. Comput. Phys. 164, 228-237 (line-area
// relations).
#pragma once

#include <vector>

#include "vofdem/grid.h"

namespace vofdem {

// water fraction carried in by each boundary face where the flow enters the domain; faces where the
// flow leaves take the fraction of the cell they leave. Sizes: left/right nz, bottom/top nx.
struct VofBoundaryInflow {
  std::vector<double> left, right, bottom, top;
  void resize(const Grid2D& grid, double value = 0.0);
};

// work arrays reused from step to step so that advection allocates nothing while stepping
struct VofScratch {
  std::vector<double> flux, cell_c, f_tmp;
};

// advances cell_F (size ncell) by dt [s]. cell_porosity: n per cell, 0 = solid (never changed);
// face_u (size nface_x), face_w (size nface_z): superficial velocities [m/s]. x_first chooses the
// sweep order (alternate it from step to step). Throws std::runtime_error if the advective CFL
// (|u| dt / (n dx), per direction) exceeds 1.
void advect_vof(const Grid2D& grid, const std::vector<double>& cell_porosity, const std::vector<double>& face_u,
                const std::vector<double>& face_w, const VofBoundaryInflow& inflow, double dt, bool x_first,
                std::vector<double>& cell_F, VofScratch& scratch);

// the largest stable advection step [s] for these velocities at a directional CFL number `cfl`
double vof_stable_dt(const Grid2D& grid, const std::vector<double>& cell_porosity, const std::vector<double>& face_u,
                     const std::vector<double>& face_w, double cfl);

// PLIC helpers (unit square cell scaled to dx x dz), exposed for tests:
// line constant alpha such that the area below m.x = alpha inside [0,dx]x[0,dz] equals f dx dz
double plic_line_constant(double mx, double mz, double dx, double dz, double f);
// area of {m.x <= alpha} inside the rectangle [0,dx]x[0,dz]
double plic_area_below(double mx, double mz, double dx, double dz, double alpha);

}  // namespace vofdem
