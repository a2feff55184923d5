#include "vofdem/coupling/fluid_forces.h"

namespace vofdem {

StoneFlowSample sample_flow_at_stone(int count, const int* cells, const double* areas, const double* F,
                                     const double* U, const double* W, const double* dpdx, const double* dpdz,
                                     double rho_w, double grav_x, double grav_z) {
  StoneFlowSample s;
  double a_sum = 0.0, aw_sum = 0.0, su = 0.0, sw = 0.0, sgx = 0.0, sgz = 0.0;
  for (int p = 0; p < count; ++p) {
    const int c = cells[p];
    const double a = areas[p], f = F[c], af = a * f;
    a_sum += a;
    aw_sum += af;
    su += af * U[c];
    sw += af * W[c];
    sgx += a * (dpdx[c] - rho_w * f * grav_x);
    sgz += a * (dpdz[c] - rho_w * f * grav_z);
  }
  s.area = a_sum;
  if (a_sum <= 0.0) return s;  // outside the grid: dry, no force
  s.wet = aw_sum / a_sum;
  if (s.wet > 1.0) s.wet = 1.0;  // round-off of the F-weighted sum
  if (aw_sum > 0.0) {
    s.u = su / aw_sum;
    s.w_vel = sw / aw_sum;
  }
  s.gx = sgx / a_sum;
  s.gz = sgz / a_sum;
  return s;
}

DragForce stone_drag(const StoneFlowSample& s, double up, double wp, double d, double rho_w, double nu_w,
                     DragLaw law) {
  if (s.wet <= 0.0) return {0.0, 0.0};
  DragForce f = drag_force_unchecked(s.u, s.w_vel, up, wp, d, rho_w, nu_w, law);
  f.fx *= s.wet;
  f.fz *= s.wet;
  return f;
}

DragForce stone_drag_area(const StoneFlowSample& s, double up, double wp, double d, double area, double rho_w,
                          double nu_w, DragLaw law) {
  if (s.wet <= 0.0) return {0.0, 0.0};
  DragForce f = drag_force_area_unchecked(s.u, s.w_vel, up, wp, d, area, rho_w, nu_w, law);
  f.fx *= s.wet;
  f.fz *= s.wet;
  return f;
}

std::array<double, 2> stone_pressure_force(const StoneFlowSample& s, double volume) {
  return {-volume * s.gx, -volume * s.gz};
}

}  // namespace vofdem
