// Wet fraction of a stone crossing the free surface, followed between fluid steps.
//
//   w(s) = (acos(-s) + s sqrt(1 - s^2)) / pi,   s = (h - z) / r clamped to [-1, 1]          (W)
//
// the share of a disc of radius r centred at height z that lies below a level h (a sphere's: a cap's
// volume, sphere_wet_fraction; each stone model gives its law, StoneModel::wet_law) (w = 0 above the
// surface, 1/2 with the centre on it, 1 under water). The coupler measures the wet fraction w of each
// stone from the water fraction of the cells it covers (eq. 9's buoyancy and added mass) once per fluid
// step, and hands the DEM the level h at which (W) gives that w at the stone's present height:
// h = z + r s(w), s(w) the inverse of (W); +infinity for a stone under water, -infinity for one in the
// air. The DEM then moves w with the stone over its substeps instead of holding it over the exchange
// step: a floating stone's buoyancy follows its height without lag (a wet fraction held while the stone
// moves is a restoring force that lags the motion, which feeds the bobbing energy).
//
// A measured w within a tolerance of 1 (of 0) is taken as 1 (0): the VOF leaves traces of air, F = 1 - 1e-7,
// in cells under water, and a stone measured at such a w would follow a level a micrometre below its
// top, at the cost of an acos and an expm1 per DEM substep, for a buoyancy and added mass changed by
// 1e-7 of their value.
#pragma once

#include <algorithm>
#include <cmath>
#include <limits>

#include "vofdem/common/numbers.h"

namespace vofdem {

// the measured wet fraction w in [0, 1] as the DEM takes it: 1 above 1 - tol, 0 below tol, else w
inline double snapped_wet_fraction(double w, double tol) {
  if (w > 1.0 - tol) return 1.0;
  return w < tol ? 0.0 : w;
}

// share of a disc below the level, (W); s = (h - z) / r [-], any value (clamped), NaN -> NaN
inline double disc_wet_fraction(double s) {
  if (std::isnan(s)) return s;
  if (s <= -1.0) return 0.0;
  if (s >= 1.0) return 1.0;
  // clamped: round-off near s = +-1 may step just outside [0, 1]
  const double w = (std::acos(-s) + s * std::sqrt(1.0 - s * s)) / kPi;
  return w < 0.0 ? 0.0 : (w > 1.0 ? 1.0 : w);
}

// dw/ds of (W) [-]
inline double disc_wet_slope(double s) { return 2.0 * std::sqrt(std::max(0.0, 1.0 - s * s)) / kPi; }

// share of a sphere's volume below the level, a cap's: w(s) = (1 + s)^2 (2 - s) / 4 (3D stones); clamped
inline double sphere_wet_fraction(double s) {
  if (std::isnan(s)) return s;
  if (s <= -1.0) return 0.0;
  if (s >= 1.0) return 1.0;
  const double w = (1.0 + s) * (1.0 + s) * (2.0 - s) / 4.0;
  return w < 0.0 ? 0.0 : (w > 1.0 ? 1.0 : w);
}
inline double sphere_wet_slope(double s) { return 0.75 * std::max(0.0, 1.0 - s * s); }

// a stone model's wet fraction law: w(s) and dw/ds (stone_model.h: the disc's, a sphere's)
struct WetLaw {
  double (*fraction)(double s);
  double (*slope)(double s);
};
inline constexpr WetLaw kDiscWetLaw{disc_wet_fraction, disc_wet_slope};
inline constexpr WetLaw kSphereWetLaw{sphere_wet_fraction, sphere_wet_slope};

// the level [m] at which a stone of radius r [m] centred at z [m] has wet fraction w [-]: z + r s with
// law.fraction(s) = w (Newton on law.slope inside a shrinking bracket, bisection where a step leaves it;
// to 1e-13 in s); +inf for w >= 1, -inf for w <= 0
inline double water_level_of_wet_fraction(double z, double r, double w, const WetLaw& law = kDiscWetLaw) {
  if (!(w > 0.0)) return -std::numeric_limits<double>::infinity();
  if (w >= 1.0) return std::numeric_limits<double>::infinity();
  double lo = -1.0, hi = 1.0, s = 2.0 * w - 1.0;
  for (int it = 0; it < 200 && hi - lo > 1e-13; ++it) {
    const double f = law.fraction(s) - w;
    if (f == 0.0) break;
    (f < 0.0 ? lo : hi) = s;
    const double slope = law.slope(s);
    double next = slope > 0.0 ? s - f / slope : 0.5 * (lo + hi);
    if (!(next > lo && next < hi)) next = 0.5 * (lo + hi);
    if (std::abs(next - s) < 1e-14) {
      s = next;
      break;
    }
    s = next;
  }
  return z + r * s;
}

}  // namespace vofdem
