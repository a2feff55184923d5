// Kernel smoothing of cell fields on the flow grid: diffusion-based coarse graining with a physical
// bandwidth, so that what the stones and the flow exchange does not depend on the cell size.
//
//   d phi / d tau = div(grad phi)   for 0 < tau < T = b^2 / 4,   zero flux at every boundary     (SX 10)
//
// On an unbounded domain this is the convolution with the Gaussian kernel
//   K(r) = exp(-r^2 / b^2) / (pi b^2)      (2D),   per direction variance sigma^2 = 2 T = b^2 / 2,
// so the bandwidth b [m] is the Gaussian's width in exp(-r^2/b^2) and sigma = b / sqrt(2). The scene key
// (coupling_bandwidth) is b. b ~ 1 stone diameter here: the weir is about 5 stones high and the overflow
// 1-1.6 stones deep, so the literature's 3-6 d would smear the whole weir.
//
// Discretisation (finite volumes, cell volume V_c = dx dz_k per unit width): m backward Euler steps of
// tau = T / m, each split into the x and z directions in the palindromic order
//   S = X(tau/2) [Z(tau) X(tau)]^(m-1) Z(tau) X(tau/2),     X(t) = (V - t K_x)^-1 V,  Z likewise,
// K the symmetric flux matrix (conductance 1 / centre distance, zero across the domain boundary and
// across the faces of solid cells). Why this choice:
//  * each factor is (V - t K)^-1 V with K symmetric and K 1 = 0: it keeps sum V phi exactly (column sums),
//    keeps a uniform field uniform, is positive (an M-matrix inverse: no negative fractions, no clipping)
//    and is self-adjoint in <a, c> = sum V a c; a palindromic product of self-adjoint factors is
//    self-adjoint, with or without solid cells (which break the commutation of X and Z). Self-adjoint
//    means "deposit then smooth" is the transpose of "smooth then average": Newton's third law holds
//    to round-off between what the stones take and what the flow gives.
//  * backward Euler is stable for any tau; each factor is a tridiagonal solve per grid line, factorised
//    once at construction (Thomas), so a call costs (2m + 1) sweeps of about 5 flops per cell.
//  * on a uniform line the discrete second moment of one step (I - t L)^-1 is 2 t exactly (L x^2 = 2),
//    so the m steps give b^2/2 per direction for any m; the kernel is the m-fold convolution of
//    Laplace kernels (exact for m -> infinity), excess kurtosis 3/m (m = 4: 0.75). An exact Gaussian
//    per line would cost a dense solve per line.
// Solid cells (base porosity 0: walls) take no flux and keep their value; the rest is conservative.
//
// References: R. Sun and H. Xiao (2015), Diffusion-based coarse graining in hybrid continuum-discrete
// solvers: theoretical formulation and a priori tests, Int. J. Multiphase Flow 72, 233-247 (sediFoam,
// lammpsFoam/enhancedCloud.C); J. Capecelatro and O. Desjardins (2013), An Euler-Lagrange strategy for
// simulating particle-laden flows, J. Comput. Phys. 238, 1-31 (filtering at a fixed physical width).
#pragma once

#include <cstdint>
#include <vector>

#include "vofdem/common/grid.h"

namespace vofdem {

struct KernelParams {
  // Gaussian width b of exp(-r^2/b^2) [m], (0, 1]; required (0: unset, refused): the caller gives it, usually
  // about one stone diameter (the coupler: CouplerParams::bandwidth or the stones' mean diameter)
  double bandwidth = 0.0;
  int steps = 4;             // backward Euler steps in pseudo-time [-], [1, 64]; 4
  // throws std::invalid_argument naming the bad parameter and its range
  void validate() const;
};

class KernelSmoother {
 public:
  // factorises the line systems for `grid`; cell_solid (optional, size ncell): nonzero marks a solid
  // cell (no flux across its faces, its value kept). Allocation happens here only.
  KernelSmoother(const Grid2D& grid, const KernelParams& params, const std::vector<std::uint8_t>* cell_solid = nullptr);

  // smooths a cell field (size ncell) in place; allocates nothing
  void smooth(double* field);
  void smooth(std::vector<double>& field);

  const KernelParams& params() const { return params_; }
  double pseudo_time() const { return params_.bandwidth * params_.bandwidth / 4.0; }  // T = b^2/4 [m^2]
  double sigma() const;  // b / sqrt(2) [m]
  int ncell() const { return nx_ * nz_; }

 private:
  // one factorised line operator (V - t K)^-1 V: per cell the lower coupling, the Thomas factors and V
  struct LineOp {
    std::vector<double> lo, cp, inv, w;
  };
  void sweep_x(const LineOp& op, double* f);
  void sweep_z(const LineOp& op, double* f);

  int nx_ = 0, nz_ = 0;
  KernelParams params_;
  LineOp x_half_, x_full_, z_full_;
};

}  // namespace vofdem
