// Sphere stones across the flume (sphere_model.h): the contact loops over the plane's neighbour list and
// the walls, the histories they keep, and their part of the state.
#include "vofdem/stones/sphere_model.h"

#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

#include "common/state_fields.h"
#include "stones/sphere_kernels.h"
#include "stones/sphere_kernels_x2.h"
#include "stones/sphere_loads.h"
#include "vofdem/common/check.h"
#include "vofdem/coupling/porosity_map.h"
#include "vofdem/stones/dem_contact.h"
#include "vofdem/stones/dem_system.h"
#include "vofdem/stones/stone_packing.h"

namespace vofdem {

namespace {
using sphere_loads::apply;
using sphere_loads::at3;
using sphere_loads::histories;
using sphere_loads::push3;
using sphere_loads::push_histories;
using sphere_loads::zero;
constexpr double kInf = std::numeric_limits<double>::infinity();
using Vec3 = Eigen::Vector3d;

// stone i as a sphere of its body (inertia: the principal moments, 3 per stone), with the mass its
// contacts' dashpots use (+inf: fixed); a local inline function, which the contact loops compile in
inline SphereOfBody sphere_of(const DEMSystem& s, const double* inertia, int i, double mass) {
  SphereOfBody b;
  b.centre = {s.stone_pos[2 * i], s.stone_y[i], s.stone_pos[2 * i + 1]};
  b.com = b.centre;
  b.radius = s.stone_radius[i];
  b.vel = {s.stone_vel[2 * i], s.stone_vel_y[i], s.stone_vel[2 * i + 1]};
  b.omega = {s.stone_omega_3d[3 * i], s.stone_omega_3d[3 * i + 1], s.stone_omega_3d[3 * i + 2]};
  b.mass = mass;
  b.inertia = inertia[3 * i];
  return b;
}

}  // namespace

void SphereModel::check_params(const DEMParams& p) const {
  if (!(p.width > 0.0))
    throw std::invalid_argument("width = " + format_value(p.width) +
                                " m: 3D stones need the flume's width between its side walls, allowed range (0, inf)");
}

std::vector<ContactPlane> SphereModel::planes(const DEMParams& p) {
  std::vector<ContactPlane> out;
  const double mu_r = (p.flags & kDEMRollingResistance) ? p.rolling_friction_wall : 0.0;
  const double mu_on = (p.flags & kDEMFriction) ? 1.0 : 0.0;
  for (const DEMWall& w : p.walls) {
    const auto [wx, wz] = DEMSystem::wall_unit_normal(w);
    out.push_back({{w.point[0], 0.0, w.point[1]}, {wx, 0.0, wz}, mu_on * w.friction, mu_r});
  }
  out.push_back({{0.0, 0.0, 0.0}, {0.0, 1.0, 0.0}, mu_on * p.side_wall_friction, mu_r});
  out.push_back({{0.0, p.width, 0.0}, {0.0, -1.0, 0.0}, mu_on * p.side_wall_friction, mu_r});
  return out;
}

// before the steps of a call (parameters change only between calls): the planes, the histories' size
void SphereModel::prepare(DEMSystem& s) {
  planes_ = planes(s.params());
  const std::size_t size = static_cast<std::size_t>(s.n()) * planes_.size();
  if (wall_history_.size() != size) wall_history_.assign(size, SphereContactHistory());
  pair_constants_current_ = false;  // the masses, inertia and law are set anew after this
}

// each listed pair's constants from the contacts' masses and the inertia of the call (DEMSystem::prepare
// sets them; a removal changes them only for stones that leave the list)
void SphereModel::update_pair_constants(DEMSystem& s, const SphereContactLaw& law, double zeta) {
  const std::vector<ContactPair>& list = pairs(s);
  const std::vector<double>& inv_m = contact_inv_mass(s);
  const double* inertia = inertia_3d(s).data();
  pair_constants_.resize(list.size());
  for (std::size_t k = 0; k < list.size(); ++k) {
    const int i = list[k].i, j = list[k].j;
    pair_constants_[k] = sphere_kernels::pair_constants(sphere_of(s, inertia, i, 1.0 / inv_m[i]),
                                                        sphere_of(s, inertia, j, 1.0 / inv_m[j]), law, zeta);
  }
  pair_constants_current_ = true;
}

// stone i as a sphere of its body, with the mass its contacts' dashpots use (+inf: fixed)
SphereOfBody SphereModel::body(const DEMSystem& s, int i, double mass) const {
  return sphere_of(s, inertia_3d(s).data(), i, mass);
}

ContactTally SphereModel::contact_forces(DEMSystem& s, double dt) {
  const SphereContactLaw law = sphere_loads::law(s);
  const double zeta = damping_ratio_from_restitution(law.restitution);  // once per loop, not per contact
  std::vector<ContactPair>& list = pairs(s);
  if (pair_history_.size() != list.size())
    throw std::logic_error("sphere model: the pair histories do not follow the neighbour list");
  if (!pair_constants_current_ || pair_constants_.size() != list.size()) update_pair_constants(s, law, zeta);
  const double* pos = s.stone_pos.data();
  const double* y = s.stone_y.data();
  const double* radius = s.stone_radius.data();
  const double* inertia = inertia_3d(s).data();
  ContactTally t;
  // the pairs whose spheres overlap, and their geometry; the others' histories start again from zero
  overlap_.resize(list.size());
  std::size_t m = 0;
  for (std::size_t k = 0; k < list.size(); ++k) {
    const int i = list[k].i, j = list[k].j;
    const double dx = pos[2 * j] - pos[2 * i], dy = y[j] - y[i], dz = pos[2 * j + 1] - pos[2 * i + 1];
    const double rs = radius[i] + radius[j];
    if (dx * dx + dy * dy + dz * dz >= rs * rs) {
      if (!zero(pair_history_[k]))
        t.dissipated += sphere_kernels::release(pair_history_[k], law, pair_constants_[k].r_eff);
      continue;
    }
    overlap_[m++].k = k;
  }
  auto geometry_at = [&](Overlap& o) {
    o.touching = sphere_kernels::pair_geometry(sphere_of(s, inertia, list[o.k].i, 0.0),
                                               sphere_of(s, inertia, list[o.k].j, 0.0), law, o.g, o.arm_i, o.arm_j);
  };
  std::size_t c0 = 0;
#ifdef VOFDEM_SPHERE_X2
  const sphere_kernels::x2::Stones stones{pos,           y, radius, s.stone_vel.data(), s.stone_vel_y.data(),
                                          s.stone_omega_3d.data()};
  for (; c0 + 1 < m; c0 += 2) {
    Overlap &a = overlap_[c0], &b = overlap_[c0 + 1];
    const int touching = sphere_kernels::x2::pair_geometry(stones, list[a.k].i, list[a.k].j, list[b.k].i, list[b.k].j,
                                                           law, a.g, a.arm_i, a.arm_j, b.g, b.arm_i, b.arm_j);
    a.touching = touching & 1, b.touching = touching & 2;
  }
#endif
  for (; c0 < m; ++c0) geometry_at(overlap_[c0]);
  // their loads (the law inline; the masses are in the pair's constants), two at a time where the
  // processor has SSE2 (sphere_kernels_x2.h: the same bits)
  loads_.resize(m);
  auto keep = [&](std::size_t c, const SphereContactLoads& f) {
    loads_[c] = PairLoads{f.force_i, f.torque_i, f.torque_j, f.energy_spring, f.power_damp, f.energy_slip};
  };
  auto law_at = [&](std::size_t c) {
    const Overlap& o = overlap_[c];
    keep(c, sphere_kernels::apply_law(o.g, pair_constants_[o.k], o.arm_i, o.arm_j, pair_history_[o.k], law, dt));
  };
#ifdef VOFDEM_SPHERE_X2
  std::size_t waiting = m;  // an overlap whose law waits for a second one
  auto contact = [&](std::size_t c, SphereContactLoads& f) -> sphere_kernels::x2::Contact {
    const Overlap& o = overlap_[c];
    return {&o.g, &pair_constants_[o.k], &o.arm_i, &o.arm_j, &pair_history_[o.k], &f};
  };
#endif
  for (std::size_t c = 0; c < m; ++c) {
    const Overlap& o = overlap_[c];
    if (!o.touching) {  // the contact opened
      t.dissipated += sphere_kernels::release(pair_history_[o.k], law, pair_constants_[o.k].r_eff);
      loads_[c] = PairLoads{Vec3::Zero(), Vec3::Zero(), Vec3::Zero(), 0.0, 0.0, 0.0};
      continue;
    }
#ifdef VOFDEM_SPHERE_X2
    if (waiting == m) {
      waiting = c;
      continue;
    }
    SphereContactLoads fa, fb;
    sphere_kernels::x2::apply_law(contact(waiting, fa), contact(c, fb), law, dt);
    keep(waiting, fa), keep(c, fb);
    waiting = m;
#else
    law_at(c);
#endif
  }
#ifdef VOFDEM_SPHERE_X2
  if (waiting < m) law_at(waiting);
#endif
  // added to the stones in the list's order
  for (std::size_t c = 0; c < m; ++c) apply(s, list[overlap_[c].k].i, list[overlap_[c].k].j, loads_[c], t, dt);
  return t;
}

ContactTally SphereModel::wall_forces(DEMSystem& s, double dt) {
  const std::vector<ContactPlane>& plane = planes_;
  const std::size_t np = plane.size(), nw = s.params().walls.size();
  const SphereContactLaw law = sphere_loads::law(s);
  const double zeta = damping_ratio_from_restitution(law.restitution);  // once per loop, not per contact
  const std::vector<double>& inv_m = inv_mass(s);
  const std::vector<double>& m_eff = mass_eff(s);
  const WallCandidates cand = wall_candidates(s);
  const double* inertia = inertia_3d(s).data();
  ContactTally t;
  auto touch = [&](int i, std::size_t w) {
    SphereContactHistory& h = wall_history_[static_cast<std::size_t>(i) * np + w];
    const SphereContactLoads f =
        sphere_kernels::sphere_plane(sphere_of(s, inertia, i, m_eff[i]), plane[w], h, law, zeta, dt);
    if (f.touching)
      apply(s, i, -1, f, t, dt);
    else
      t.dissipated += f.energy_slip;  // it opened
  };
  // the plane's walls: the stones near each (the neighbour build's candidates)
  for (std::size_t w = 0; w < nw; ++w)
    for (int c = cand.start[w]; c < cand.start[w + 1]; ++c)
      if (inv_m[cand.index[c]] > 0.0) touch(cand.index[c], w);
  // the side walls: every mobile stone within reach
  for (int i = 0; i < s.n(); ++i) {
    if (inv_m[i] == 0.0) continue;
    const double r = s.stone_radius[i];
    for (std::size_t w = nw; w < np; ++w) {
      const double gap = (w == nw) ? s.stone_y[i] : s.params().width - s.stone_y[i];
      // (and once more as it leaves, so that its histories start again from zero)
      const SphereContactHistory& h = wall_history_[static_cast<std::size_t>(i) * np + w];
      if (gap < r || h.spring.squaredNorm() > 0.0 || h.rolling.squaredNorm() > 0.0) touch(i, w);
    }
  }
  return t;
}

void SphereModel::pairs_rebuilt(DEMSystem&, const std::vector<int>& from) {
  std::vector<SphereContactHistory> carried(from.size());
  for (std::size_t k = 0; k < from.size(); ++k)
    if (from[k] >= 0 && static_cast<std::size_t>(from[k]) < pair_history_.size()) carried[k] = pair_history_[from[k]];
  pair_history_.swap(carried);
  pair_constants_current_ = false;
}

// ---- state: the pairs' histories that are not zero, and every (stone, plane) history

void SphereModel::export_state(const DEMSystem& s, DEMState& t) const {
  const std::vector<ContactPair>& list = pairs(const_cast<DEMSystem&>(s));
  for (std::size_t k = 0; k < list.size() && k < pair_history_.size(); ++k) {
    const SphereContactHistory& h = pair_history_[k];
    if (zero(h)) continue;
    t.sphere_contact_i.push_back(list[k].i);
    t.sphere_contact_j.push_back(list[k].j);
    push3(t.sphere_contact_spring, h.spring);
    push3(t.sphere_contact_rolling, h.rolling);
  }
  const std::size_t size = static_cast<std::size_t>(s.n()) * (s.params().walls.size() + 2);
  push_histories(wall_history_, size, t.sphere_wall_spring, t.sphere_wall_rolling);
}

void SphereModel::check_state(const DEMSystem& s, const DEMState& t) const {
  check_params(s.params());
  const std::size_t n = t.stone_radius.size(), np = t.sphere_contact_i.size();
  const std::size_t nw = n * (s.params().walls.size() + 2);
  require_size("sphere_contact_j", t.sphere_contact_j, np);
  require_size("sphere_contact_spring", t.sphere_contact_spring, 3 * np);
  require_size("sphere_contact_rolling", t.sphere_contact_rolling, 3 * np);
  require_size("sphere_wall_spring", t.sphere_wall_spring, 3 * nw);
  require_size("sphere_wall_rolling", t.sphere_wall_rolling, 3 * nw);
  state::check_sorted_pairs("sphere contact", t.sphere_contact_i, t.sphere_contact_j, n);
}

// after check_state: the listed pairs are those with a history (the next build carries them over)
void SphereModel::import_state(DEMSystem& s, const DEMState& t) {
  std::vector<ContactPair>& list = pairs(s);
  list.clear();
  pair_history_.clear();
  for (std::size_t k = 0; k < t.sphere_contact_i.size(); ++k) {
    list.push_back({t.sphere_contact_i[k], t.sphere_contact_j[k], 0.0, 0.0});
    pair_history_.push_back({at3(t.sphere_contact_spring, k), at3(t.sphere_contact_rolling, k)});
  }
  wall_history_ = histories(t.sphere_wall_spring, t.sphere_wall_rolling);
  pair_constants_current_ = false;
}

void SphereModel::state_to_map(DEMState& t, StateMap& m) const {
  using state::to_double;
  m["sphere_contact_i"] = to_double(t.sphere_contact_i);
  m["sphere_contact_j"] = to_double(t.sphere_contact_j);
  m["sphere_contact_spring"] = std::move(t.sphere_contact_spring);
  m["sphere_contact_rolling"] = std::move(t.sphere_contact_rolling);
  m["sphere_wall_spring"] = std::move(t.sphere_wall_spring);
  m["sphere_wall_rolling"] = std::move(t.sphere_wall_rolling);
}

void SphereModel::state_from_map(const StateMap& m, std::size_t n, std::size_t nwalls, DEMState& t) const {
  using state::entry;
  using state::from_double;
  const std::size_t nw = n * (nwalls + 2);
  const auto& ci = entry(m, "sphere_contact_i", state::kAnySize);
  from_double(t.sphere_contact_i, ci);
  from_double(t.sphere_contact_j, entry(m, "sphere_contact_j", ci.size()));
  t.sphere_contact_spring = entry(m, "sphere_contact_spring", 3 * ci.size());
  t.sphere_contact_rolling = entry(m, "sphere_contact_rolling", 3 * ci.size());
  t.sphere_wall_spring = entry(m, "sphere_wall_spring", 3 * nw);
  t.sphere_wall_rolling = entry(m, "sphere_wall_rolling", 3 * nw);
}

// ---- the flow's view: the exact volume in each cell's slab across the width, the true solid fraction

void SphereModel::require_true_void_fraction(const PorosityMapper& m, const char* shape) {
  if (m.params().n_exp != 0.0)
    throw std::invalid_argument("n_exp = " + format_value(m.params().n_exp) +
                                " is outside the allowed range [0, 0] with 3D stones (stones.shape = '" + shape +
                                "'): their footprint is their volume, so the porosity is the true void fraction "
                                "without eq. (11)'s packing porosity (CouplerParams.n_exp = 0)");
}

void SphereModel::map_footprint(const DEMSystem& s, PorosityMapper& m, const double* x, const double* z) const {
  require_true_void_fraction(m, "sphere");
  m.map_spheres(s.n(), x, z, s.stone_radius.data(), s.params().width, s.stone_active.data());
}

namespace {
// spheres in the 3D packing generator (weir_packing_3d.h): the drawn diameter, placed at (x, y, z)
class SpherePacking final : public StonePacking {
 public:
  PackedStone draw(double d) override { return PackedStone{0.5 * d}; }
  // spheres roll off the slopes' toes onto the bed like discs
  bool drop_toe_rollers() const override { return true; }
  DEMSystem make(const DEMParams& p, const PackedStones& pile, double density) const override {
    if (pile.y.size() != pile.size() || pile.quat.size() != 4 * pile.size())
      throw std::invalid_argument("sphere packing: every stone needs its y and quaternion");
    DEMSystem s(p, pile.pos, pile.radius, {density}, pile.fixed);
    s.set_model("sphere");
    s.stone_y = pile.y;
    s.stone_quat = pile.quat;
    return s;
  }
};
}  // namespace

std::unique_ptr<StonePacking> SphereModel::packing(const WeirSpec&) const { return std::make_unique<SpherePacking>(); }

}  // namespace vofdem
