// A minimal stone model for the tests (docs/stone_models.md): a disc that ignores rotation. Its contacts
// are the normal spring-dashpot of dem_contact.h alone (no friction, no torque), so a stone never turns;
// its mass, footprint and drag are those of the sphere of its diameter. Registered by the test that
// uses it (test_stone_model.cpp): a model a program brings needs no change to the library.
#pragma once

#include <algorithm>
#include <cmath>

#include "vofdem/coupling/drag_exchange.h"
#include "vofdem/coupling/fluid_forces.h"
#include "vofdem/coupling/porosity_map.h"
#include "vofdem/stones/dem_contact.h"
#include "vofdem/stones/dem_system.h"

namespace vofdem::test {

class FrictionlessDiscModel final : public StoneModel {
 public:
  static constexpr double kPi = 3.14159265358979323846;
  const char* name() const override { return "frictionless_disc"; }
  double volume(const DEMSystem& s, int i) const override { return kPi / 6.0 * std::pow(2.0 * s.stone_radius[i], 3); }
  double inertia(const DEMSystem& s, int i, double m) const override { return 0.4 * m * std::pow(s.stone_radius[i], 2); }
  double nominal_diameter(const DEMSystem& s, int i) const override { return 2.0 * s.stone_radius[i]; }
  double projected_area(const DEMSystem& s, int i) const override { return kPi * std::pow(s.stone_radius[i], 2); }
  double projected_area(const DEMSystem& s, int i, double, double) const override { return projected_area(s, i); }
  // the normal mode of two of the lightest stones, pi / (10 omega)
  double stable_dt(const DEMSystem& s) const override {
    double m_min = INFINITY;
    for (int i = 0; i < s.n(); ++i)
      if (s.stone_active[i] && !s.stone_fixed[i]) m_min = std::min(m_min, s.mass(i));
    return std::isfinite(m_min) ? kPi / (10.0 * std::sqrt(2.0 * s.stiffness_normal() / m_min)) : INFINITY;
  }
  // the normal force -f_n n on i along the line of centres, its opposite on j
  ContactTally contact_forces(DEMSystem& s, double dt) override {
    ContactTally t;
    for (ContactPair& c : pairs(s)) {
      const double dx = s.stone_pos[2 * c.j] - s.stone_pos[2 * c.i], dz = s.stone_pos[2 * c.j + 1] - s.stone_pos[2 * c.i + 1];
      const double d = std::hypot(dx, dz), rs = s.stone_radius[c.i] + s.stone_radius[c.j];
      if (d >= rs || d == 0.0) continue;
      const double nx = dx / d, nz = dz / d;
      const double vn = (s.stone_vel[2 * c.i] - s.stone_vel[2 * c.j]) * nx + (s.stone_vel[2 * c.i + 1] - s.stone_vel[2 * c.j + 1]) * nz;
      add(s, c.i, c.j, rs - d, vn, nx, nz, contact_law(s).damp * c.sqrt_m, dt, t);
    }
    return t;
  }
  ContactTally wall_forces(DEMSystem& s, double dt) override {
    ContactTally t;
    for (const DEMWall& wall : s.params().walls) {
      const auto [wx, wz] = DEMSystem::wall_unit_normal(wall);
      for (int i = 0; i < s.n(); ++i) {
        if (inv_mass(s)[i] == 0.0) continue;
        const double gap = (s.stone_pos[2 * i] - wall.point[0]) * wx + (s.stone_pos[2 * i + 1] - wall.point[1]) * wz;
        if (gap >= s.stone_radius[i]) continue;
        const double vn = -(s.stone_vel[2 * i] * wx + s.stone_vel[2 * i + 1] * wz);
        add(s, i, -1, s.stone_radius[i] - gap, vn, -wx, -wz, contact_law(s).damp * std::sqrt(mass_eff(s)[i]), dt, t);
      }
    }
    return t;
  }
  void map_footprint(const DEMSystem& s, PorosityMapper& m, const double* x, const double* z) const override {
    m.map(s.n(), x, z, s.stone_radius.data(), s.stone_active.data());
  }
  DragForce drag(const DEMSystem& s, int i, const StoneFlowSample& f, double up, double wp, double rho, double nu,
                 DragLaw law, double* slope) const override {
    const double d = nominal_diameter(s, i), a = projected_area(s, i);
    if (slope) *slope = stone_drag_slope_area(f, up, wp, d, a, rho, nu, law);
    return stone_drag_area(f, up, wp, d, a, rho, nu, law);
  }
  double drag_relaxation_dt(const DEMSystem& s, int i, double relax, double mass, double vrel, double w, double rho,
                            double nu) const override {
    return relax * mass / drag_slope(vrel, nominal_diameter(s, i), w * 0.5 * rho * projected_area(s, i), nu, DragLaw::kPaper);
  }
  double gap(const DEMSystem& s, int i, double x, double z) const override {
    return std::max(std::hypot(x - s.stone_pos[2 * i], z - s.stone_pos[2 * i + 1]) - s.stone_radius[i], 0.0);
  }
  bool covers(const DEMSystem& s, int i, double x, double z) const override { return gap(s, i, x, z) == 0.0; }
  double outline_max(const DEMSystem& s, int i, const std::function<double(double, double)>& f) const override {
    return f(s.stone_pos[2 * i], s.stone_pos[2 * i + 1]) + s.stone_radius[i];
  }

 private:
  // the normal force of overlap delta at closing speed vn on i (along -n) and j (j < 0: a wall)
  static void add(DEMSystem& s, int i, int j, double delta, double vn, double nx, double nz, double cn, double dt,
                  ContactTally& t) {
    double xi = 0.0;
    const ContactForce f = linear_contact(delta, vn, 0.0, xi, dt, s.stiffness_normal(), 0.0, cn, 0.0, 0.0, false);
    s.stone_force[2 * i] -= f.fn * nx, s.stone_force[2 * i + 1] -= f.fn * nz;
    if (j >= 0) s.stone_force[2 * j] += f.fn * nx, s.stone_force[2 * j + 1] += f.fn * nz;
    t.elastic += f.energy_spring, t.dissipated += f.power_damp * dt, ++t.count;
  }
};

}  // namespace vofdem::test
