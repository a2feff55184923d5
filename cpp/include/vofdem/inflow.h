// Inflow boundary: a prescribed discharge Q(t) entering the flume at x = x0.
//
//   q(t) = Q(t) / B,      u_k = q F_k / sum_j(F_j dz_j)     (inlet rows k, water fraction 1 entering)
//
// Q [m^3/s] is a piecewise-linear table of time [s] (the Python front samples any callable into it),
// B [m] the flume width, q [m^2/s] the discharge per unit width. The discharge is spread over the
// wetted inlet rows in proportion to their water fraction F_k, so the inlet water level is free to
// adjust to what the flow downstream needs; a dry inlet feeds its bottom row.
//
// Reference: S. Maeno and A. Tomita (2008), ICHE 2008 (discharge raised 10 -> 25 l/s over 120 s).
#pragma once

#include <vector>

namespace vofdem {

// piecewise-linear discharge Q(t) [m^3/s] held in C++ so that stepping runs without Python;
// held constant before the first and after the last time
struct DischargeTable {
  std::vector<double> times;      // [s], strictly increasing
  std::vector<double> discharge;  // Q [m^3/s], >= 0

  // Q at time t [s]
  double at(double t) const;
  // checks sizes, ordering and values (std::invalid_argument)
  void validate() const;
  // a linear ramp from q0 to q1 [m^3/s] over [t0, t1] [s] (the paper: 0.010 -> 0.025 over 0 -> 120)
  static DischargeTable ramp(double q0, double q1, double t0, double t1);
  static DischargeTable constant(double q);
};

// inlet face velocities u_k [m/s] (size nz) for discharge per unit width q [m^2/s] over rows of height
// dz [m] holding water fractions F (both size nz); rows with active == 0 (solid) get nothing
void inlet_velocities(double q, const std::vector<double>& dz, const double* F, const double* porosity, int stride,
                      std::vector<double>& u);

}  // namespace vofdem
