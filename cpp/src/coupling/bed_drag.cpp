#include "vofdem/coupling/bed_drag.h"

#include <cmath>

#include "vofdem/flow/porous_resistance.h"

namespace vofdem {

BedDragParams::BedDragParams(const FlowParams& flow)
    : rho_w(flow.medium.rho_water),
      nu_w(flow.medium.nu_water),
      k1(flow.k1),
      k2(flow.k2),
      linear(flow.flags & kFlowPorousDarcy),
      quadratic(flow.flags & kFlowPorousForchheimer),
      relative(flow.flags & kFlowRelativeVelocity) {}

DragForce bed_drag(int count, const int* cells, const double* areas, const double* F, const double* n,
                   const double* D, const double* U, const double* W, double up, double wp, double volume,
                   const BedDragParams& p, double* slope) {
  double a_sum = 0.0, fx = 0.0, fz = 0.0, s = 0.0;
  for (int q = 0; q < count; ++q) a_sum += areas[q];
  if (slope) *slope = 0.0;
  if (a_sum <= 0.0) return {0.0, 0.0};  // outside the grid
  for (int q = 0; q < count; ++q) {
    const int c = cells[q];
    const double nc = n[c], dc = D[c];
    // no porous medium, a wall, no stone size, or dry: nothing
    if (nc <= 0.0 || nc >= 1.0 || dc <= 0.0 || F[c] <= 0.0) continue;
    const PorousCoefficients k = bed_coefficients_unchecked(nc, dc, p.nu_w, p.k1, p.k2);
    const double lin = p.linear ? k.linear : 0.0, quad = p.quadratic ? k.quadratic : 0.0;
    // superficial velocity relative to the stone, as the flow's resistance sees it
    const double ur = nc * (U[c] - (p.relative ? up : 0.0)), wr = nc * (W[c] - (p.relative ? wp : 0.0));
    const double mag = std::hypot(ur, wr);
    const double wgt = areas[q] * F[c];
    const double coef = wgt * (lin + quad * mag);
    fx += coef * ur;
    fz += coef * wr;
    // d|u_r| u_r / du_p = -n (|u_r| + u_r u_r / |u_r|): at most 2 n |u_r| for the quadratic part
    if (p.relative) s += wgt * nc * (lin + 2.0 * quad * mag);
  }
  const double scale = volume * p.rho_w / a_sum;
  if (slope) *slope = scale * s;
  return {scale * fx, scale * fz};
}

BedDragDensity bed_drag_density(double F, double n, double D, double U, double W, double up, double wp,
                                const BedDragParams& p) {
  BedDragDensity d;
  // no porous medium, a wall, no stone size, or dry: nothing (as bed_drag)
  if (n <= 0.0 || n >= 1.0 || D <= 0.0 || F <= 0.0) return d;
  const PorousCoefficients k = bed_coefficients_unchecked(n, D, p.nu_w, p.k1, p.k2);
  const double lin = p.linear ? k.linear : 0.0, quad = p.quadratic ? k.quadratic : 0.0;
  const double ur = n * (U - (p.relative ? up : 0.0)), wr = n * (W - (p.relative ? wp : 0.0));
  const double mag = std::hypot(ur, wr);
  const double coef = F * (lin + quad * mag);
  d.fx = coef * ur;
  d.fz = coef * wr;
  if (p.relative) d.slope = F * n * (lin + 2.0 * quad * mag);
  return d;
}

}  // namespace vofdem
