// Inflow boundary: a prescribed discharge Q(t) entering the flume at x = x0.
//
//   q(t) = Q(t) / B,   h = sum_j(F_j dz_j),   u_k = q w_k / h     (inlet rows k, water fraction 1 entering)
//
//   kEquivalentDepth:  w_k = clamp((h - z_k) / dz_k, 0, 1)    (z_k: open depth below row k)
//   kWaterFraction:    w_k = F_k                              (the former profile)
//
// Q [m^3/s] is a piecewise-linear table of time [s] (the Python front samples any callable into it),
// B [m] the flume width, q [m^2/s] the discharge per unit width. The inlet's water level h is free to
// adjust to what the flow downstream needs; a dry inlet feeds its bottom row. Both profiles are the
// same for a sharp column (full rows under one partial row). They differ where the column holds traces
// of water above its level: kWaterFraction feeds a trace with water of fraction 1, so it grows by
// itself at a rate of about q / (h dx) (3.6 /s in the Maeno flume at 14 l/s) and pours water in above
// the surface; kEquivalentDepth feeds only the rows below the level h.
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

// how the inlet spreads the discharge over its rows (above)
enum class InletProfile { kWaterFraction = 0, kEquivalentDepth = 1 };

// inlet face velocities u_k [m/s] (size nz) for discharge per unit width q [m^2/s] over rows of height
// dz [m] holding water fractions F (both size nz); rows with porosity 0 (solid) get nothing
void inlet_velocities(double q, const std::vector<double>& dz, const double* F, const double* porosity, int stride,
                      InletProfile profile, std::vector<double>& u);

}  // namespace vofdem
