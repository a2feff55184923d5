// Disc stones (disc_model.h).
#include "vofdem/stones/disc_model.h"

#include <algorithm>
#include <cmath>
#include <memory>

#include "vofdem/common/numbers.h"
#include "vofdem/coupling/drag_exchange.h"
#include "vofdem/coupling/fluid_forces.h"
#include "vofdem/coupling/porosity_map.h"
#include "vofdem/stones/dem_contact.h"
#include "vofdem/stones/dem_system.h"
#include "vofdem/stones/rolling_resistance.h"
#include "vofdem/stones/stone_packing.h"
#include "vofdem/stones/weir_packing.h"

namespace vofdem {

double DiscModel::volume(const DEMSystem& s, int i) const {
  const double r = s.stone_radius[i];
  return 4.0 / 3.0 * kPi * r * r * r;
}

double DiscModel::inertia(const DEMSystem& s, int i, double mass) const {
  return s.params().inertia_factor * mass * s.stone_radius[i] * s.stone_radius[i];
}

double DiscModel::nominal_diameter(const DEMSystem& s, int i) const { return 2.0 * s.stone_radius[i]; }

double DiscModel::projected_area(const DEMSystem& s, int i) const {
  return kPi * s.stone_radius[i] * s.stone_radius[i];
}

double DiscModel::projected_area(const DEMSystem& s, int i, double, double) const { return projected_area(s, i); }

double DiscModel::stable_dt(const DEMSystem& s) const {
  const DEMParams& p = s.params();
  double m_min = INFINITY;
  for (int i = 0; i < s.n(); ++i)
    if (s.stone_active[i] && !s.stone_fixed[i]) m_min = std::min(m_min, s.mass(i));
  const double kn = s.stiffness_normal(), kt = s.stiffness_tangential();
  if (!std::isfinite(m_min) || kn <= 0.0) return INFINITY;
  // two of the lightest stones: normal mode and the tangential mode that includes their spin
  const double w2_n = 2.0 * kn / m_min;
  const double rot = (p.flags & kDEMRotation) ? 1.0 / p.inertia_factor : 0.0;
  const double w2_t = 2.0 * kt * (1.0 + rot) / m_min + rolling_spin_stiffness(s, m_min);
  const double w = std::sqrt(std::max(w2_n, w2_t));
  // explicit dashpots: a mode of frequency a w and damping ratio a zeta (dashpots proportional to the
  // springs) is stable for dt <= 2 / (a w (a zeta + sqrt(1 + a^2 zeta^2))); a stone packed among
  // kPackedContacts neighbours has modes up to a = sqrt(kPackedContacts) times the pair's. Measured on
  // six packed weirs (critical damping): the energy grew at 0.7-0.8 of the undamped bound alone, never
  // at 0.65; this bound is 0.61 of it there, and the undamped one where the damping is weak
  const double zeta = (p.flags & kDEMDamping) ? s.damping_ratio() : 0.0;
  const double a = std::sqrt(DEMSystem::kPackedContacts), az = a * zeta;
  const double damped = 2.0 / (a * w * (az + std::sqrt(1.0 + az * az)));
  return std::min(kPi / (10.0 * w), damped);
}

ContactTally DiscModel::contact_forces(DEMSystem& s, double dt) {
  const DEMParams& p = s.params();
  const auto [friction, damp, kt] = contact_law(s);
  const double kn = s.stiffness_normal();
  const double kt_roll = s.stiffness_tangential();  // the rolling springs' k_t, friction or not
  const double ct_factor = p.tangential_damping_factor;
  const bool rolling = rolling_stones(s);
  const double* pos = s.stone_pos.data();
  const double* vel = s.stone_vel.data();
  const double* omega = s.stone_omega.data();
  const double* radius = s.stone_radius.data();
  double* force = s.stone_force.data();
  double* torque = s.stone_torque.data();
  ContactTally t;
  for (ContactPair& c : pairs(s)) {
    const int i = c.i, j = c.j;
    const double dx = pos[2 * j] - pos[2 * i];
    const double dz = pos[2 * j + 1] - pos[2 * i + 1];
    const double ri = radius[i], rj = radius[j];
    const double rs = ri + rj;
    const double d2 = dx * dx + dz * dz;
    if (d2 >= rs * rs) {
      if (c.xi != 0.0 || c.mr != 0.0)
        t.dissipated += opened_energy(c.xi, kt, c.mr, rolling_stiffness(kt_roll, c.roll_r));
      c.xi = 0.0;
      c.mr = 0.0;
      continue;
    }
    ++t.count;
    const double d = std::sqrt(d2);
    const double inv_d = d > 0.0 ? 1.0 / d : 0.0;
    const double nx = d > 0.0 ? dx * inv_d : 1.0, nz = dz * inv_d;
    const double vrx = vel[2 * i] - vel[2 * j];
    const double vrz = vel[2 * i + 1] - vel[2 * j + 1];
    const double vn = vrx * nx + vrz * nz;
    const double vt = -vrx * nz + vrz * nx + omega[i] * ri + omega[j] * rj;
    const double cn = damp * c.sqrt_m;
    const ContactForce f = friction ? linear_contact(rs - d, vn, vt, c.xi, dt, kn, kt, cn, ct_factor * cn,
                                                     p.friction_stone, true)
                                    : linear_contact(rs - d, vn, 0.0, c.xi, dt, kn, 0.0, cn, 0.0, 0.0, false);
    // force on i: -f_n n + f_s t, with t = (-n_z, n_x)
    const double fx = -f.fn * nx - f.ft * nz;
    const double fz = -f.fn * nz + f.ft * nx;
    force[2 * i] += fx;
    force[2 * i + 1] += fz;
    force[2 * j] -= fx;
    force[2 * j + 1] -= fz;
    torque[i] += ri * f.ft;
    torque[j] += rj * f.ft;
    t.elastic += f.energy_spring;
    t.dissipated += f.power_damp * dt + f.energy_slip;
    if (rolling) rolling_contact(s, c, f.fn, dt, t);
  }
  return t;
}

ContactTally DiscModel::wall_forces(DEMSystem& s, double dt) {
  const DEMParams& p = s.params();
  const auto [friction, damp, kt] = contact_law(s);
  const double kn = s.stiffness_normal();
  const double kt_roll = s.stiffness_tangential();  // the rolling springs' k_t, friction or not
  const bool rolling = rolling_walls(s);
  const std::size_t nw = p.walls.size();
  const WallCandidates cand = wall_candidates(s);
  const std::vector<double>& inv_m = inv_mass(s);
  const std::vector<double>& m_eff = mass_eff(s);
  std::vector<double>& wall_xi = wall_spring(s);
  std::vector<double>& wall_mr = wall_rolling_spring(s);
  ContactTally t;
  for (std::size_t w = 0; w < nw; ++w) {
    const DEMWall& wall = p.walls[w];
    const auto [wx, wz] = DEMSystem::wall_unit_normal(wall);
    // contact normal from the stone into the wall
    const double nx = -wx, nz = -wz;
    for (int c = cand.start[w]; c < cand.start[w + 1]; ++c) {
      const int i = cand.index[c];
      if (inv_m[i] == 0.0) continue;
      double& xi = wall_xi[static_cast<std::size_t>(i) * nw + w];
      const double r = s.stone_radius[i];
      const double d = (s.stone_pos[2 * i] - wall.point[0]) * wx + (s.stone_pos[2 * i + 1] - wall.point[1]) * wz;
      if (d >= r) {
        double& mr = wall_mr[static_cast<std::size_t>(i) * nw + w];
        if (xi != 0.0 || mr != 0.0) t.dissipated += opened_energy(xi, kt, mr, rolling_stiffness(kt_roll, r));
        xi = 0.0;
        mr = 0.0;
        continue;
      }
      ++t.count;
      const double vx = s.stone_vel[2 * i], vz = s.stone_vel[2 * i + 1];
      const double vn = vx * nx + vz * nz;
      const double vt = -vx * nz + vz * nx + s.stone_omega[i] * r;
      const double cn = damp * std::sqrt(m_eff[i]);
      const ContactForce f = friction ? linear_contact(r - d, vn, vt, xi, dt, kn, kt, cn,
                                                       p.tangential_damping_factor * cn, wall.friction, true)
                                      : linear_contact(r - d, vn, 0.0, xi, dt, kn, 0.0, cn, 0.0, 0.0, false);
      s.stone_force[2 * i] += -f.fn * nx - f.ft * nz;
      s.stone_force[2 * i + 1] += -f.fn * nz + f.ft * nx;
      s.stone_torque[i] += r * f.ft;
      t.elastic += f.energy_spring;
      t.dissipated += f.power_damp * dt + f.energy_slip;
      if (rolling) rolling_wall(s, i, wall_mr[static_cast<std::size_t>(i) * nw + w], f.fn, dt, t);
    }
  }
  return t;
}

void DiscModel::map_footprint(const DEMSystem& s, PorosityMapper& m, const double* x, const double* z) const {
  m.map(s.n(), x, z, s.stone_radius.data(), s.stone_active.data());
}

DragForce DiscModel::drag(const DEMSystem& s, int i, const StoneFlowSample& f, double up, double wp, double rho,
                          double nu, DragLaw law, double* slope) const {
  const double d = 2.0 * s.stone_radius[i];
  if (slope) *slope = sphere_drag_slope(f, up, wp, d, rho, nu, law);
  return stone_drag(f, up, wp, d, rho, nu, law);
}

double DiscModel::drag_relaxation_dt(const DEMSystem& s, int i, double relaxation, double mass, double vrel, double w,
                                     double rho, double nu) const {
  const double r = s.stone_radius[i];
  const double slope = drag_slope(vrel, 2.0 * r, w * 0.5 * rho * kPi * r * r, nu, DragLaw::kPaper);
  return relaxation * (mass / slope);
}

double DiscModel::gap(const DEMSystem& s, int i, double x, double z) const {
  return std::max(std::hypot(x - s.stone_pos[2 * i], z - s.stone_pos[2 * i + 1]) - s.stone_radius[i], 0.0);
}

bool DiscModel::covers(const DEMSystem& s, int i, double x, double z) const {
  const double dx = x - s.stone_pos[2 * i], dz = z - s.stone_pos[2 * i + 1];
  const double r = s.stone_radius[i];
  return dx * dx + dz * dz < r * r;
}

double DiscModel::outline_max(const DEMSystem& s, int i, const std::function<double(double, double)>& f) const {
  return f(s.stone_pos[2 * i], s.stone_pos[2 * i + 1]) + s.stone_radius[i];
}

}  // namespace vofdem

namespace vofdem {

namespace {
// discs in the weir's packing generator (stone_packing.h): circles of the drawn diameter
class DiscPacking final : public StonePacking {
 public:
  PackedStone draw(double d) override { return PackedStone{0.5 * d}; }

  // touching discs on the bed
  void bottom_row(const WeirSpec& spec, const std::function<double()>& next_diameter, PackedStones& pile) override {
    const double x_end = spec.x_end();
    double r = 0.5 * next_diameter();
    double x = spec.x_toe + r;
    while (x + r <= x_end + 1e-12) {
      pile.add(x, spec.z_bed + r, PackedStone{r}, 1);
      const double r_next = 0.5 * next_diameter();
      x += r + r_next;
      r = r_next;
    }
  }

  bool fits(const PackedStones& pile, double x, double z, const PackedStone& s, double margin) const override {
    for (std::size_t i = 0; i < pile.size(); ++i)
      if (std::hypot(x - pile.pos[2 * i], z - pile.pos[2 * i + 1]) - pile.radius[i] - s.radius <= margin) return false;
    return true;
  }

  DEMSystem make(const DEMParams& p, const PackedStones& pile, double density) const override {
    return DEMSystem(p, pile.pos, pile.radius, {density}, pile.fixed);
  }
};
}  // namespace

std::unique_ptr<StonePacking> DiscModel::packing(const WeirSpec&) const { return std::make_unique<DiscPacking>(); }

}  // namespace vofdem
