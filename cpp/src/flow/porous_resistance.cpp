#include "vofdem/flow/porous_resistance.h"

#include <cmath>

#include "vofdem/common/check.h"

namespace vofdem {

double permeability(double n, double d, double k1) {
  require_in_open_closed("n", n, 0.0, 1.0);
  require_positive("d", d);
  require_positive("k1", k1);
  if (n == 1.0) return INFINITY;  // no stones: no resistance
  return n * n * n * d * d / (k1 * (1.0 - n) * (1.0 - n));
}

double forchheimer_coefficient(double n, double k1, double k2) {
  require_in_open_closed("n", n, 0.0, 1.0);
  require_positive("k1", k1);
  require_non_negative("k2", k2);
  return k2 / std::sqrt(k1 * n * n * n);
}

PorousCoefficients porous_coefficients_unchecked(double n, double d, double nu, double k1, double k2) {
  // the expanded forms stay finite at n = 1 (both vanish) where K itself is infinite
  const double m = 1.0 - n;
  const double n3 = n * n * n;
  return {k1 * nu * m * m / (n3 * d * d), k2 * m / (n3 * d)};
}

PorousCoefficients bed_coefficients_unchecked(double n, double d, double nu, double k1, double k2) {
  const double n2 = n * n;
  return {k1 * nu * (1.0 - n) / (n2 * d * d), k2 / (n2 * d)};
}

PorousCoefficients porous_coefficients(double n, double d, double nu, double k1, double k2) {
  require_in_open_closed("n", n, 0.0, 1.0);
  require_positive("d", d);
  require_non_negative("nu", nu);
  require_positive("k1", k1);
  require_non_negative("k2", k2);
  return porous_coefficients_unchecked(n, d, nu, k1, k2);
}

Resistance porous_resistance(double u, double w, double n, double d, double nu, double k1, double k2) {
  require_finite("u", u);
  require_finite("w", w);
  const PorousCoefficients c = porous_coefficients(n, d, nu, k1, k2);
  const double factor = c.linear + c.quadratic * std::hypot(u, w);
  return {-u * factor, -w * factor};
}

}  // namespace vofdem
