#include "vofdem/coupling/drag_exchange.h"

#include <cmath>

#include "vofdem/common/numbers.h"

namespace vofdem {

namespace {
// the drag law's slope (drag.h) at the sample's relative speed, scaled by the wet fraction
double sample_drag_slope(const StoneFlowSample& s, double up, double wp, double d, double half_rho_a, double nu_w,
                         DragLaw law) {
  return s.wet * drag_slope(std::hypot(s.u - up, s.w_vel - wp), d, half_rho_a, nu_w, law);
}
}  // namespace

double sphere_drag_slope(const StoneFlowSample& s, double up, double wp, double d, double rho_w, double nu_w,
                         DragLaw law) {
  if (s.wet <= 0.0) return 0.0;
  return sample_drag_slope(s, up, wp, d, 0.5 * rho_w * 0.25 * kPi * d * d, nu_w, law);
}

double stone_drag_slope_area(const StoneFlowSample& s, double up, double wp, double d, double area, double rho_w,
                             double nu_w, DragLaw law) {
  if (s.wet <= 0.0) return 0.0;
  return sample_drag_slope(s, up, wp, d, 0.5 * rho_w * area, nu_w, law);
}

LinearDrag linearise_drag(const DragForce& f, double slope, double up, double wp) {
  LinearDrag l;
  if (!(slope > 0.0)) return l;
  l.coef = slope;
  l.vel_x = up + f.fx / slope;
  l.vel_z = wp + f.fz / slope;
  return l;
}

}  // namespace vofdem
