// The medium the stones lie in and the flow is made of: water, air and gravity (SI units).
//
// One value for both solvers, as MuJoCo's mjOption holds the gravity, density and viscosity of the
// medium for the whole model and Box2D's world definition its gravity. The flow's FlowParams::medium is
// the owner in a coupled run: a Coupler hands it to the stones (DEMParams::medium) when it is built and
// before every step, so the two cannot disagree and no caller copies a density or a gravity by hand.
// A DEM run alone keeps its own DEMParams::medium (dry unless DEMParams::submerged).
#pragma once

#include <array>

namespace vofdem {

struct Medium {
  double rho_water = 998.2;                   // water density [kg/m^3], 998.2 at 20 C
  double rho_air = 1.204;                     // air density [kg/m^3], 1.204 at 20 C
  double nu_water = 1.004e-6;                 // water kinematic viscosity [m^2/s], 1.004e-6 at 20 C
  double nu_air = 1.516e-5;                   // air kinematic viscosity [m^2/s], 1.516e-5 at 20 C
  std::array<double, 2> gravity{0.0, -9.81};  // gravitational acceleration (x along the flume, z up) [m/s^2]

  // throws std::invalid_argument naming the first bad field
  void validate() const;
  bool operator==(const Medium& o) const {
    return rho_water == o.rho_water && rho_air == o.rho_air && nu_water == o.nu_water && nu_air == o.nu_air &&
           gravity == o.gravity;
  }
  bool operator!=(const Medium& o) const { return !(*this == o); }
};

}  // namespace vofdem
