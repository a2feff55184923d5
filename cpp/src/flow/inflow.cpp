#include "vofdem/flow/inflow.h"

#include <algorithm>
#include <stdexcept>
#include <string>

#include "vofdem/common/check.h"

namespace vofdem {

double DischargeTable::at(double t) const {
  if (times.empty()) return 0.0;
  if (t <= times.front()) return discharge.front();
  if (t >= times.back()) return discharge.back();
  const auto it = std::upper_bound(times.begin(), times.end(), t);
  const size_t j = static_cast<size_t>(it - times.begin());
  const double s = (t - times[j - 1]) / (times[j] - times[j - 1]);
  return discharge[j - 1] + s * (discharge[j] - discharge[j - 1]);
}

void DischargeTable::validate() const {
  if (times.size() != discharge.size())
    throw std::invalid_argument("discharge table: times has " + std::to_string(times.size()) +
                                " entries but discharge has " + std::to_string(discharge.size()));
  if (times.empty()) throw std::invalid_argument("discharge table: needs at least one (time, discharge) pair");
  for (size_t j = 0; j < times.size(); ++j) {
    require_finite("times", times[j]);
    require_non_negative("discharge", discharge[j]);
    if (j > 0 && !(times[j] > times[j - 1]))
      throw std::invalid_argument("discharge table: times must be strictly increasing; times[" + std::to_string(j) +
                                  "] = " + format_value(times[j]) + " <= " + format_value(times[j - 1]));
  }
}

DischargeTable DischargeTable::ramp(double q0, double q1, double t0, double t1) {
  require_non_negative("q0", q0);
  require_non_negative("q1", q1);
  require_finite("t0", t0);
  require_finite("t1", t1);
  if (!(t1 > t0))
    throw std::invalid_argument("t1 = " + format_value(t1) + " is outside the allowed range (t0 = " +
                                format_value(t0) + ", inf)");
  return DischargeTable{{t0, t1}, {q0, q1}};
}

DischargeTable DischargeTable::constant(double q) {
  require_non_negative("q", q);
  return DischargeTable{{0.0}, {q}};
}

void inlet_velocities(double q, const std::vector<double>& dz, const double* F, const double* porosity, int stride,
                      InletProfile profile, std::vector<double>& u) {
  const size_t nz = dz.size();
  u.assign(nz, 0.0);
  double h = 0.0;
  for (size_t k = 0; k < nz; ++k)
    if (porosity[k * stride] > 0.0) h += F[k * stride] * dz[k];
  if (h <= 1e-12) {
    // a dry inlet feeds its lowest open row
    for (size_t k = 0; k < nz; ++k)
      if (porosity[k * stride] > 0.0) {
        u[k] = q / dz[k];
        return;
      }
    return;
  }
  if (profile == InletProfile::kWaterFraction) {
    for (size_t k = 0; k < nz; ++k)
      if (porosity[k * stride] > 0.0) u[k] = q * F[k * stride] / h;
    return;
  }
  double below = 0.0;  // open depth under row k [m]
  for (size_t k = 0; k < nz && below < h; ++k) {
    if (!(porosity[k * stride] > 0.0)) continue;
    u[k] = q * std::min(1.0, (h - below) / dz[k]) / h;
    below += dz[k];
  }
}

}  // namespace vofdem
