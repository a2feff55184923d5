#include "vofdem/coupling/drag.h"

#include <cmath>
#include <stdexcept>

#include "vofdem/common/check.h"
#include "vofdem/common/numbers.h"

namespace vofdem {

namespace {
constexpr double kSchillerNaumannReMax = 1000.0;

// C_D * Re / 24 of Schiller & Naumann; continuous at Re = 1000 to within 0.2 %
double schiller_naumann_correction(double re) {
  if (re < kSchillerNaumannReMax) return 1.0 + 0.15 * std::pow(re, 0.687);
  return 0.44 * re / 24.0;
}
}  // namespace

double drag_coefficient(double re, DragLaw law) {
  require_positive("re", re);
  switch (law) {
    case DragLaw::kPaper: return 0.4 + 24.0 / re;
    case DragLaw::kSchillerNaumann: return 24.0 / re * schiller_naumann_correction(re);
  }
  throw std::invalid_argument("unknown drag law");
}

DragForce drag_force_unchecked(double u, double w, double up, double wp, double d, double rho, double nu,
                               DragLaw law) {
  return drag_force_area_unchecked(u, w, up, wp, d, 0.25 * kPi * d * d, rho, nu, law);
}

DragForce drag_force_area_unchecked(double u, double w, double up, double wp, double d, double area, double rho,
                                    double nu, DragLaw law) {
  const double vx = u - up, vz = w - wp;
  const double speed = std::hypot(vx, vz);
  // 1/2 rho A C_D |v| = 1/2 rho A (24 nu / d) (C_D Re / 24): finite as |v| -> 0
  double coef;
  if (law == DragLaw::kPaper) {
    coef = 0.5 * rho * area * (0.4 * speed + 24.0 * nu / d);
  } else {
    coef = 0.5 * rho * area * (24.0 * nu / d) * schiller_naumann_correction(speed * d / nu);
  }
  return {coef * vx, coef * vz};
}

double drag_slope(double speed, double d, double half_rho_area, double nu, DragLaw law) {
  // eq. (18): c = 1/2 rho A (0.4 |v| + 24 nu / d)
  if (law == DragLaw::kPaper) return half_rho_area * (0.8 * speed + 24.0 * nu / d);
  // c = 1/2 rho A (24 nu / d) (1 + 0.15 Re^0.687) below Re = 1000, 1/2 rho A 0.44 |v| above
  const double re = speed * d / nu;
  return re < kSchillerNaumannReMax ? half_rho_area * (24.0 * nu / d) * (1.0 + 0.15 * 1.687 * std::pow(re, 0.687))
                                    : half_rho_area * 0.88 * speed;
}

DragForce drag_force(double u, double w, double up, double wp, double d, double rho, double nu, DragLaw law) {
  require_finite("u", u);
  require_finite("w", w);
  require_finite("up", up);
  require_finite("wp", wp);
  require_positive("d", d);
  require_positive("rho", rho);
  require_positive("nu", nu);
  return drag_force_unchecked(u, w, up, wp, d, rho, nu, law);
}

}  // namespace vofdem
