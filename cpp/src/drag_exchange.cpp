#include "vofdem/drag_exchange.h"

#include <cmath>

namespace vofdem {

namespace {
constexpr double kPi = 3.14159265358979323846;
constexpr double kSchillerNaumannReMax = 1000.0;
}  // namespace

namespace {
// d(c(|r|) |r|) / d|r| of F = c(|r|) r for c = half_rho_a (...) [N s/m], scaled by the wet fraction
double drag_slope(const StoneFlowSample& s, double up, double wp, double d, double half_rho_a, double nu_w,
                  DragLaw law) {
  const double speed = std::hypot(s.u - up, s.w_vel - wp);
  double slope;
  if (law == DragLaw::kPaper) {
    slope = half_rho_a * (0.8 * speed + 24.0 * nu_w / d);  // c = 1/2 rho A (0.4 |r| + 24 nu / d)
  } else {
    const double re = speed * d / nu_w;
    // c = 1/2 rho A (24 nu / d) (1 + 0.15 Re^0.687) below Re = 1000, 1/2 rho A 0.44 |r| above
    slope = re < kSchillerNaumannReMax ? half_rho_a * (24.0 * nu_w / d) * (1.0 + 0.15 * 1.687 * std::pow(re, 0.687))
                                       : half_rho_a * 0.88 * speed;
  }
  return s.wet * slope;
}
}  // namespace

double sphere_drag_slope(const StoneFlowSample& s, double up, double wp, double d, double rho_w, double nu_w,
                         DragLaw law) {
  if (s.wet <= 0.0) return 0.0;
  return drag_slope(s, up, wp, d, 0.5 * rho_w * 0.25 * kPi * d * d, nu_w, law);
}

double stone_drag_slope_area(const StoneFlowSample& s, double up, double wp, double d, double area, double rho_w,
                             double nu_w, DragLaw law) {
  if (s.wet <= 0.0) return 0.0;
  return drag_slope(s, up, wp, d, 0.5 * rho_w * area, nu_w, law);
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
