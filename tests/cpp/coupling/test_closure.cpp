// Closure laws: porous resistance (seed eqs. 5-7) and stone drag (seed eqs. 16-18).
#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <stdexcept>

#include "vofdem/coupling/drag.h"
#include "vofdem/flow/porous_resistance.h"

using namespace vofdem;

namespace {
constexpr double kNu = 1e-6, kRho = 1000.0, kG = 9.81, kPi = 3.14159265358979323846;

// bisection to 1e-12: the slow obvious root finder
double bisect(const std::function<double(double)>& f, double a, double b) {
  double fa = f(a);
  while (b - a > 1e-12) {
    const double c = 0.5 * (a + b), fc = f(c);
    if (fa * fc <= 0) {
      b = c;
    } else {
      a = c;
      fa = fc;
    }
  }
  return 0.5 * (a + b);
}

double settling_velocity(double d, double rho_s, DragLaw law) {
  const double weight = (rho_s - kRho) * kG * kPi * d * d * d / 6.0;
  return bisect([&](double v) { return drag_force(0, 0, 0, -v, d, kRho, kNu, law).fz - weight; }, 1e-6, 20.0);
}
}  // namespace

TEST(PorousResistance, PapersPermeabilityAndForchheimerCoefficient) {
  // hand-computed for n = 0.41, d = 4.8 cm, (k1, k2) = (200, 2.8)
  EXPECT_NEAR(permeability(0.41, 0.048, 200.0), 2.281e-6, 1e-9);
  EXPECT_NEAR(forchheimer_coefficient(0.41, 200.0, 2.8), 0.754, 5e-4);
}

TEST(PorousResistance, ErgunCoefficientsGiveTheErgunEquation) {
  for (double n : {0.3, 0.41, 0.6}) {
    for (double u : {1e-4, 0.02, 0.5, -0.3}) {
      const double d = 0.048;
      const double ergun = kRho * u *
                           (150.0 * kNu * (1 - n) * (1 - n) / (n * n * n * d * d) +
                            1.75 * (1 - n) / (n * n * n * d) * std::fabs(u));
      const Resistance r = porous_resistance(u, 0.0, n, d, kNu, kErgunK1, kErgunK2);
      EXPECT_NEAR(-kRho * r.rx, ergun, 1e-12 * std::fabs(ergun));
    }
  }
}

TEST(PorousResistance, PointsAgainstTheFlowAndVanishesInClearWater) {
  const Resistance r = porous_resistance(0.3, -0.1, 0.41, 0.048, kNu);
  EXPECT_LT(r.rx * 0.3 + r.rz * -0.1, 0.0);
  EXPECT_NEAR(r.rx * -0.1 - r.rz * 0.3, 0.0, 1e-14);
  const Resistance clear = porous_resistance(0.3, -0.1, 1.0, 0.048, kNu);
  EXPECT_EQ(clear.rx, 0.0);
  EXPECT_EQ(clear.rz, 0.0);
}

TEST(PorousResistance, RefusesBadInput) {
  EXPECT_THROW(porous_resistance(0.1, 0, 0.41, 0.0, kNu), std::invalid_argument);
  EXPECT_THROW(porous_resistance(0.1, 0, 0.41, -0.048, kNu), std::invalid_argument);
  EXPECT_THROW(porous_resistance(0.1, 0, 0.0, 0.048, kNu), std::invalid_argument);
  EXPECT_THROW(porous_resistance(0.1, 0, 1.01, 0.048, kNu), std::invalid_argument);
  EXPECT_THROW(porous_resistance(0.1, 0, std::nan(""), 0.048, kNu), std::invalid_argument);
  EXPECT_THROW(porous_resistance(std::nan(""), 0, 0.41, 0.048, kNu), std::invalid_argument);
  try {
    porous_coefficients(1.5, 0.048, kNu);
    FAIL() << "no exception";
  } catch (const std::invalid_argument& e) {
    EXPECT_STREQ(e.what(), "n = 1.5 is outside the allowed range (0, 1]");
  }
}

TEST(Drag, CoefficientOfBothLaws) {
  EXPECT_DOUBLE_EQ(drag_coefficient(100.0), 0.64);
  EXPECT_NEAR(drag_coefficient(100.0, DragLaw::kSchillerNaumann), 0.24 * (1 + 0.15 * std::pow(100.0, 0.687)), 1e-15);
  EXPECT_DOUBLE_EQ(drag_coefficient(1e5, DragLaw::kSchillerNaumann), 0.44);
  EXPECT_THROW(drag_coefficient(0.0), std::invalid_argument);
}

TEST(Drag, ZeroRelativeVelocityGivesExactlyZero) {
  for (DragLaw law : {DragLaw::kPaper, DragLaw::kSchillerNaumann}) {
    const DragForce f = drag_force(0.4, -0.2, 0.4, -0.2, 0.048, kRho, kNu, law);
    EXPECT_EQ(f.fx, 0.0);
    EXPECT_EQ(f.fz, 0.0);
  }
}

TEST(Drag, SettlingVelocityOfAStone) {
  // reference values of REFERENCES.md (3 significant digits) for a 4.8 cm stone of density 2650
  EXPECT_NEAR(settling_velocity(0.048, 2650.0, DragLaw::kPaper), 1.61, 0.005);
  EXPECT_NEAR(settling_velocity(0.048, 2650.0, DragLaw::kSchillerNaumann), 1.53, 0.005);
}

TEST(Drag, RefusesBadInput) {
  EXPECT_THROW(drag_force(0.1, 0, 0, 0, 0.0, kRho, kNu), std::invalid_argument);
  EXPECT_THROW(drag_force(0.1, 0, 0, 0, -0.01, kRho, kNu), std::invalid_argument);
  EXPECT_THROW(drag_force(0.1, 0, std::nan(""), 0, 0.048, kRho, kNu), std::invalid_argument);
}
