// Rotation of a 3D rigid body (quaternion.h): frame changes, a torque-free spin about a principal axis,
// an asymmetric top's angular momentum and energy over many steps, the scheme's second order against a
// fine-step solution, a constant torque about a principal axis, determinism and bad input.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <stdexcept>
#include <string>
#include <utility>

#include "vofdem/stones/quaternion.h"

using namespace vofdem;

namespace {

Quat tilted() { return Quat(Eigen::AngleAxisd(0.7, Vec3(1.0, -2.0, 0.5).normalized())); }

// angle [rad] between two orientations
double angle_between(const Quat& a, const Quat& b) { return a.angularDistance(b); }

}  // namespace

TEST(Quaternion, BodyWorldRoundTripAndHandComputed) {
  // a quarter turn about z takes the body x axis to the world y axis
  const Quat q(Eigen::AngleAxisd(0.5 * M_PI, Vec3::UnitZ()));
  const Vec3 w = body_to_world(q, Vec3::UnitX());
  EXPECT_NEAR(w.x(), 0.0, 1e-15);
  EXPECT_NEAR(w.y(), 1.0, 1e-15);
  EXPECT_NEAR(w.z(), 0.0, 1e-15);
  const Vec3 v(0.3, -1.2, 2.5);
  EXPECT_LT((world_to_body(tilted(), body_to_world(tilted(), v)) - v).norm(), 1e-15 * v.norm() * 4);
}

// a spin about the largest or smallest principal axis is stable and stays put over 1 s (10^4 steps);
// about the middle axis it is unstable (the tennis-racket effect: round-off grows as exp(lambda t),
// lambda = omega sqrt((I2 - I1)(I3 - I2) / (I1 I3)) = 17 1/s here), so it is followed for 0.1 s only
TEST(Quaternion, TorqueFreeSpinAboutPrincipalAxisStaysPut) {
  const Vec3 inertia(1.0e-4, 2.0e-4, 3.0e-4);
  for (int k = 0; k < 3; ++k) {
    const int n = k == 1 ? 1000 : 10000;
    Quat q = tilted();
    const Vec3 axis = body_to_world(q, Vec3::Unit(k));
    Vec3 omega = 30.0 * axis;
    for (int s = 0; s < n; ++s) rotation_step(q, omega, inertia, Vec3::Zero(), 1e-4);
    // the spin axis stays the body axis k, the rate stays 30 rad/s (round-off of n steps)
    EXPECT_LT((omega - 30.0 * axis).norm(), 1e-11 * 30.0) << "axis " << k;
    EXPECT_LT((body_to_world(q, Vec3::Unit(k)) - axis).norm(), 1e-11) << "axis " << k;
    // it has turned by 30 rad/s x n dt about that axis
    const Quat expected = Quat(Eigen::AngleAxisd(30.0 * n * 1e-4, axis)) * tilted();
    EXPECT_LT(angle_between(q, expected), 1e-10) << "axis " << k;
  }
}

// an asymmetric top (1 : 2 : 3) spun near its unstable middle axis tumbles; over 10^5 steps of
// omega dt = 0.01 its L stays to round-off (1e-10 after 10^5 steps) and its kinetic energy within 5e-6 (measured 7e-7)
// (the bounded O(dt^2) oscillation of the splitting), with no drift between the first and last
// thousand steps
TEST(Quaternion, AsymmetricTopConservesMomentumAndEnergy) {
  const Vec3 inertia(1.0, 2.0, 3.0);
  Quat q = tilted();
  Vec3 omega = body_to_world(q, Vec3(0.05, 1.0, 0.05));
  const Vec3 l0 = angular_momentum(q, inertia, omega);
  const double e0 = rotational_energy(q, inertia, omega);
  const double dt = 0.01;
  double max_de = 0.0, max_dl = 0.0, mean_first = 0.0, mean_last = 0.0;
  double min_l_mid = 1.0;  // body component of L along the middle axis, over |L|
  const int n = 100000;
  for (int s = 0; s < n; ++s) {
    rotation_step(q, omega, inertia, Vec3::Zero(), dt);
    const Vec3 l = angular_momentum(q, inertia, omega);
    const double de = rotational_energy(q, inertia, omega) / e0 - 1.0;
    max_de = std::max(max_de, std::fabs(de));
    max_dl = std::max(max_dl, (l - l0).norm() / l0.norm());
    if (s < 1000) mean_first += de / 1000;
    if (s >= n - 1000) mean_last += de / 1000;
    min_l_mid = std::min(min_l_mid, world_to_body(q, l)[1] / l.norm());
  }
  EXPECT_LT(max_dl, 1e-10);
  EXPECT_LT(max_de, 5e-6);
  EXPECT_LT(std::fabs(mean_last - mean_first), 1e-7);
  // the body did tumble: its middle axis turned over (the body component of L along it changed sign)
  EXPECT_LT(min_l_mid, -0.9);
  std::printf("asymmetric top, 1e5 steps at omega dt = 0.01: max |dL|/L %.2e, max |dE|/E %.2e, drift %.2e\n",
              max_dl, max_de, mean_last - mean_first);
}

// the splitting is second order: the orientation after 1 s at dt and dt/2 against dt/64
TEST(Quaternion, SecondOrderAgainstFineSteps) {
  const Vec3 inertia(1.0, 2.0, 3.0);
  auto run = [&](double dt) {
    Quat q = tilted();
    Vec3 omega = body_to_world(q, Vec3(0.3, 1.0, -0.4));
    const int n = static_cast<int>(std::lround(1.0 / dt));
    for (int s = 0; s < n; ++s) rotation_step(q, omega, inertia, Vec3(0.02, -0.01, 0.03), dt);
    return q;
  };
  const Quat ref = run(0.05 / 64);
  const double e1 = angle_between(run(0.05), ref), e2 = angle_between(run(0.025), ref);
  const double order = std::log2(e1 / e2);
  EXPECT_GT(order, 1.9);
  EXPECT_LT(order, 2.1);
}

// a constant torque about a principal axis: omega = tau t / I to round-off, the axis never moves
TEST(Quaternion, ConstantTorqueAboutPrincipalAxis) {
  const Vec3 inertia(2.0e-4, 3.0e-4, 5.0e-4);
  const double tau = 1.5e-3, dt = 1e-4;
  for (int k = 0; k < 3; ++k) {
    Quat q = tilted();
    const Vec3 axis = body_to_world(q, Vec3::Unit(k));
    Vec3 omega = Vec3::Zero();
    const int n = 5000;
    for (int s = 0; s < n; ++s) rotation_step(q, omega, inertia, tau * axis, dt);
    const double expected = tau * n * dt / inertia[k];
    EXPECT_NEAR(omega.dot(axis), expected, 1e-12 * expected) << "axis " << k;
    EXPECT_LT((omega - omega.dot(axis) * axis).norm(), 1e-12 * expected) << "axis " << k;
    // and the angle turned is tau t^2 / (2 I), exactly for the kick-drift-kick sequence
    const double t = n * dt;
    const Quat turned = Quat(Eigen::AngleAxisd(0.5 * tau * t * t / inertia[k], axis)) * tilted();
    EXPECT_LT(angle_between(q, turned), 1e-9) << "axis " << k;
  }
}

// a body of equal moments spun at omega = (pi/2) / (n dt) about the unit axis (1, 2, 2)/3 turns by a quarter
// turn in n exact rotations: q = (cos(pi/4), sin(pi/4) axis) q_0 by hand, to the round-off of n products
TEST(Quaternion, SphericalRotationQuarterTurnByHand) {
  const Vec3 axis = Vec3(1.0, 2.0, 2.0) / 3.0;
  const int n = 1000;
  const double dt = 1e-3, rate = 0.5 * M_PI / (n * dt);
  const double c = std::sqrt(0.5);
  Quat q = Quat::Identity();
  for (int s = 0; s < n; ++s) spherical_rotation(q, rate * axis, dt);
  EXPECT_NEAR(q.w(), c, 1e-12);
  EXPECT_NEAR(q.x(), c / 3.0, 1e-12);
  EXPECT_NEAR(q.y(), 2.0 * c / 3.0, 1e-12);
  EXPECT_NEAR(q.z(), 2.0 * c / 3.0, 1e-12);
  // from a tilted start the quarter turn is applied in the world frame: the body x axis of tilted() is
  // turned about the world axis by pi/2
  Quat p = tilted();
  for (int s = 0; s < n; ++s) spherical_rotation(p, rate * axis, dt);
  const Vec3 x0 = body_to_world(tilted(), Vec3::UnitX());
  const Vec3 x_hand = axis.dot(x0) * axis + axis.cross(x0);  // Rodrigues at pi/2: cos 0, sin 1
  EXPECT_LT((body_to_world(p, Vec3::UnitX()) - x_hand).norm(), 1e-12);
  // no spin: the orientation is kept bit for bit; a bad step is refused by name
  Quat r = tilted();
  spherical_rotation(r, Vec3::Zero(), dt);
  EXPECT_EQ(std::memcmp(r.coeffs().data(), tilted().coeffs().data(), sizeof(double) * 4), 0);
  try {
    spherical_rotation(r, axis, -1e-3);
    FAIL() << "negative dt accepted";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("dt"), std::string::npos);
  }
}

// on a body of equal moments the exact rotation does not depend on the step (a spin held over 1 s in steps
// of 1e-3 or 5e-4 s: the same orientation to round-off), and the principal axes' splitting converges to it
// at second order: halving the step divides their difference by 4 (an oblique spin, omega dt = 0.01)
TEST(Quaternion, SphericalRotationIsTheLimitOfTheSplittingForEqualMoments) {
  const Vec3 inertia(2.0e-4, 2.0e-4, 2.0e-4);
  const Vec3 omega0 = 10.0 * Vec3(1.0, -2.0, 0.5).normalized();
  auto run = [&](int n) {
    const double dt = 1.0 / n;
    Quat split = tilted(), exact = tilted();
    Vec3 omega = omega0;
    for (int s = 0; s < n; ++s) {
      rotation_step(split, omega, inertia, Vec3::Zero(), dt);
      spherical_rotation(exact, omega0, dt);
    }
    return std::make_pair(split, exact);
  };
  const auto coarse = run(1000), fine = run(2000);
  EXPECT_LT(angle_between(coarse.second, fine.second), 1e-12);
  const double e1 = angle_between(coarse.first, coarse.second), e2 = angle_between(fine.first, fine.second);
  EXPECT_GT(e1, 0.0);
  const double order = std::log2(e1 / e2);
  EXPECT_NEAR(order, 2.0, 0.1) << "errors " << e1 << " and " << e2;
}

TEST(Quaternion, DeterministicBitForBit) {
  auto run = [] {
    Quat q = tilted();
    Vec3 omega(1.0, -2.0, 0.5);
    for (int s = 0; s < 1000; ++s) rotation_step(q, omega, Vec3(1.0, 1.5, 2.5), Vec3(0.1, 0.0, -0.2), 1e-3);
    return std::make_pair(Eigen::Vector4d(q.coeffs()), omega);
  };
  const auto a = run(), b = run();
  EXPECT_EQ(std::memcmp(a.first.data(), b.first.data(), sizeof(double) * 4), 0);
  EXPECT_EQ(std::memcmp(a.second.data(), b.second.data(), sizeof(double) * 3), 0);
}

TEST(Quaternion, BadInputNamesParameter) {
  Quat q = Quat::Identity();
  Vec3 omega = Vec3::Zero();
  try {
    rotation_step(q, omega, Vec3(1.0, 0.0, 1.0), Vec3::Zero(), 1e-3);
    FAIL() << "zero inertia accepted";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("inertia"), std::string::npos);
  }
  try {
    rotation_step(q, omega, Vec3(1.0, 1.0, 1.0), Vec3::Zero(), -1e-3);
    FAIL() << "negative dt accepted";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("dt"), std::string::npos);
  }
  EXPECT_THROW(rotation_step(q, omega, Vec3(1.0, NAN, 1.0), Vec3::Zero(), 1e-3), std::invalid_argument);
}
