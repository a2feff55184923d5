// Linear spring-dashpot contact of 3D spheres with the tangential spring and the rolling spring kept as
// 3-vectors (sphere_contact.h): the geometry of a sphere pair or a sphere and a plane, then one law.
#include "vofdem/stones/sphere_contact.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include "stones/sphere_kernels.h"
#include "vofdem/stones/dem_contact.h"

namespace vofdem {

using Vec3 = Eigen::Vector3d;

namespace {

void require(bool ok, const char* name, const char* range, double value) {
  if (!ok) {
    throw std::invalid_argument(std::string(name) + ": must be " + range + ", got " + std::to_string(value));
  }
}

void check_sphere(const SphereOfBody& s, const char* who) {
  require(std::isfinite(s.radius) && s.radius > 0.0, who, "a radius finite and > 0 [m]", s.radius);
  require(s.mass > 0.0, who, "a mass > 0 [kg] (+inf: a fixed body)", s.mass);
  require(s.inertia >= 0.0, who, "an inertia >= 0 [kg m^2] (+inf: a body that does not turn)", s.inertia);
}

void check_dt(double dt) { require(std::isfinite(dt) && dt >= 0.0, "dt", "finite and >= 0 [s]", dt); }

}  // namespace

void SphereContactLaw::check() const {
  require(std::isfinite(stiffness_normal) && stiffness_normal > 0.0, "stiffness_normal", "finite and > 0 [N/m]",
          stiffness_normal);
  require(std::isfinite(stiffness_ratio) && stiffness_ratio >= 0.0, "stiffness_ratio", "finite and >= 0 [-]",
          stiffness_ratio);
  require(restitution >= 0.0 && restitution <= 1.0, "restitution", "in [0, 1] [-]", restitution);
  require(std::isfinite(tangential_damping_factor) && tangential_damping_factor >= 0.0, "tangential_damping_factor",
          "finite and >= 0 [-]", tangential_damping_factor);
  require(std::isfinite(friction) && friction >= 0.0, "friction", "finite and >= 0 [-]", friction);
  require(std::isfinite(rolling_friction) && rolling_friction >= 0.0, "rolling_friction", "finite and >= 0 [-]",
          rolling_friction);
  require(rolling_damping >= 0.0 && rolling_damping <= 1.0, "rolling_damping", "in [0, 1] [-]", rolling_damping);
}

SphereContactLoads sphere_sphere_contact(const SphereOfBody& i, const SphereOfBody& j, SphereContactHistory& h,
                                         const SphereContactLaw& law, double dt) {
  law.check();
  check_sphere(i, "sphere i");
  check_sphere(j, "sphere j");
  check_dt(dt);
  return sphere_sphere_contact_unchecked(i, j, h, law, damping_ratio_from_restitution(law.restitution), dt);
}

SphereContactLoads sphere_sphere_contact_unchecked(const SphereOfBody& i, const SphereOfBody& j,
                                                   SphereContactHistory& h, const SphereContactLaw& law, double zeta,
                                                   double dt) {
  return sphere_kernels::sphere_pair(i, j, h, law, zeta, dt);
}

SphereContactLoads sphere_plane_contact(const SphereOfBody& i, const ContactPlane& plane, SphereContactHistory& h,
                                        const SphereContactLaw& law, double dt) {
  law.check();
  check_sphere(i, "sphere i");
  check_dt(dt);
  require(std::fabs(plane.normal.norm() - 1.0) < 1e-9, "plane.normal", "of unit length (within 1e-9) [-]; its length",
          plane.normal.norm());
  require(std::isfinite(plane.friction) && plane.friction >= 0.0, "plane.friction", "finite and >= 0 [-]",
          plane.friction);
  require(std::isfinite(plane.rolling_friction) && plane.rolling_friction >= 0.0, "plane.rolling_friction",
          "finite and >= 0 [-]", plane.rolling_friction);
  return sphere_plane_contact_unchecked(i, plane, h, law, damping_ratio_from_restitution(law.restitution), dt);
}

SphereContactLoads sphere_plane_contact_unchecked(const SphereOfBody& i, const ContactPlane& plane,
                                                  SphereContactHistory& h, const SphereContactLaw& law, double zeta,
                                                  double dt) {
  return sphere_kernels::sphere_plane(i, plane, h, law, zeta, dt);
}

}  // namespace vofdem
