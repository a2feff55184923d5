// Clump stones across the flume (clump_model.h): the shapes and their mass properties, the contact loops
// over the sub-spheres of listed pairs and of the planes, the histories they keep, and their part of the
// state.
#include "vofdem/stones/clump_model.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <functional>
#include <limits>
#include <map>
#include <memory>
#include <stdexcept>
#include <string>

#include <Eigen/Eigenvalues>

#include "common/state_fields.h"
#include "stones/clump_packing.h"
#include "stones/sphere_kernels.h"
#include "stones/sphere_loads.h"
#include "vofdem/common/check.h"
#include "vofdem/common/numbers.h"
#include "vofdem/coupling/drag.h"
#include "vofdem/coupling/drag_exchange.h"
#include "vofdem/coupling/fluid_forces.h"
#include "vofdem/coupling/porosity_map.h"
#include "vofdem/stones/clump.h"
#include "vofdem/stones/dem_contact.h"
#include "vofdem/stones/dem_system.h"
#include "vofdem/stones/sphere_model.h"
#include "vofdem/stones/stone_packing.h"

namespace vofdem {

namespace {
using sphere_loads::apply;
using sphere_loads::at3;
using sphere_loads::histories;
using sphere_loads::push3;
using sphere_loads::push_histories;
using sphere_loads::zero;

// the spheres of one stone (4 values each) in the offsets' layout, checked
void check_layout(std::size_t n, const std::vector<double>& sphere, const std::vector<int>& offset) {
  if (offset.size() != n + 1 || offset[0] != 0 || sphere.size() != 4 * static_cast<std::size_t>(offset[n]))
    throw std::invalid_argument("clump offsets: " + std::to_string(offset.size()) + " offsets for " +
                                std::to_string(n) + " stones and " + std::to_string(sphere.size() / 4) +
                                " spheres; allowed: n + 1 offsets from 0 to the sphere count");
  for (std::size_t i = 0; i < n; ++i) {
    const int k = offset[i + 1] - offset[i];
    if (k < 1 || k > kClumpMaxSpheres)
      throw std::invalid_argument("clump stone " + std::to_string(i) + " has " + std::to_string(k) +
                                  " spheres, allowed range [1, " + std::to_string(kClumpMaxSpheres) + "]");
  }
  for (std::size_t g = 0; g < sphere.size() / 4; ++g) {
    const double* c = &sphere[4 * g];
    if (!(std::isfinite(c[0]) && std::isfinite(c[1]) && std::isfinite(c[2]) && c[3] > 0.0 && std::isfinite(c[3])))
      throw std::invalid_argument("clump sphere " + std::to_string(g) +
                                  ": centre must be finite and radius in (0, inf) [m]");
  }
}
}  // namespace

// ---- shapes and mass properties

void ClumpModel::set_shapes(int n, const std::vector<double>& sphere, const std::vector<int>& offset) {
  const std::size_t un = static_cast<std::size_t>(n);
  check_layout(un, sphere, offset);
  // stones of the same input shape share one integration (the quadrature dominates the cost)
  std::map<std::vector<double>, Clump> made;
  std::vector<const Clump*> of(un);
  for (std::size_t i = 0; i < un; ++i) {
    const std::vector<double> key(sphere.begin() + 4 * offset[i], sphere.begin() + 4 * offset[i + 1]);
    auto it = made.find(key);
    if (it == made.end()) {
      std::vector<ClumpSphere> parts;
      for (std::size_t g = 0; g < key.size(); g += 4)
        parts.push_back({Eigen::Vector3d(key[g], key[g + 1], key[g + 2]), key[g + 3]});
      it = made.emplace(key, Clump(parts)).first;
    }
    of[i] = &it->second;
  }
  adopt(of);
}

void ClumpModel::set_shapes(const std::vector<Clump>& clumps) {
  std::vector<const Clump*> of(clumps.size());
  for (std::size_t i = 0; i < clumps.size(); ++i) {
    const int k = static_cast<int>(clumps[i].spheres().size());
    if (k > kClumpMaxSpheres)
      throw std::invalid_argument("clump stone " + std::to_string(i) + " has " + std::to_string(k) +
                                  " spheres, allowed range [1, " + std::to_string(kClumpMaxSpheres) + "]");
    of[i] = &clumps[i];
  }
  adopt(of);
}

// the stones' shapes, volumes, moments and bounding radii from their clumps (principal frames)
void ClumpModel::adopt(const std::vector<const Clump*>& of) {
  const std::size_t un = of.size();
  std::vector<int> offset(un + 1, 0);
  for (std::size_t i = 0; i < un; ++i) offset[i + 1] = offset[i] + static_cast<int>(of[i]->spheres().size());
  std::vector<double> out(4 * static_cast<std::size_t>(offset[un])), volume(un), moment(3 * un), bound(un);
  for (std::size_t i = 0; i < un; ++i) {
    const Clump& c = *of[i];
    volume[i] = c.volume();
    for (int k = 0; k < 3; ++k) moment[3 * i + k] = c.principal_inertia()[k];
    for (std::size_t k = 0; k < c.spheres().size(); ++k) {
      const ClumpSphere& p = c.spheres()[k];
      double* o = &out[4 * (offset[i] + k)];
      o[0] = p.centre[0], o[1] = p.centre[1], o[2] = p.centre[2], o[3] = p.radius;
    }
    bound[i] = c.bounding_radius();
  }
  sphere_.swap(out), offset_.swap(offset), volume_.swap(volume), moment_.swap(moment), bound_.swap(bound);
  shaped_ = true;
  derive_levers();
}

// each stone's largest a_n^2 and a_t^2 over its sub-spheres (clump_model.h, stable step), per unit density
void ClumpModel::derive_levers() {
  const std::size_t n = volume_.size();
  lever_.assign(2 * n, 0.0);
  for (std::size_t i = 0; i < n; ++i) {
    const Eigen::Vector3d inv(1.0 / moment_[3 * i], 1.0 / moment_[3 * i + 1], 1.0 / moment_[3 * i + 2]);
    const double inv_root_j1 = 1.0 / std::sqrt(std::min({moment_[3 * i], moment_[3 * i + 1], moment_[3 * i + 2]}));
    for (int g = offset_[i]; g < offset_[i + 1]; ++g) {
      const Eigen::Vector3d c(sphere_[4 * g], sphere_[4 * g + 1], sphere_[4 * g + 2]);
      Eigen::Matrix3d cx;
      cx << 0.0, -c[2], c[1], c[2], 0.0, -c[0], -c[1], c[0], 0.0;
      const Eigen::Matrix3d a = cx.transpose() * inv.asDiagonal() * cx;
      const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig(a, Eigen::EigenvaluesOnly);
      const double an2 = std::max(0.0, eig.eigenvalues()[2]);
      const double at = std::sqrt(an2) + sphere_[4 * g + 3] * inv_root_j1;
      lever_[2 * i] = std::max(lever_[2 * i], an2);
      lever_[2 * i + 1] = std::max(lever_[2 * i + 1], at * at);
    }
  }
}

// without shapes set: one sphere of stone_radius per stone (the sphere model's stone)
void ClumpModel::default_shapes(const DEMSystem& s) {
  const std::size_t n = static_cast<std::size_t>(s.n());
  sphere_.assign(4 * n, 0.0), offset_.resize(n + 1), volume_.resize(n), moment_.resize(3 * n), bound_.resize(n);
  for (std::size_t i = 0; i < n; ++i) {
    const double r = s.stone_radius[i];
    sphere_[4 * i + 3] = r, offset_[i] = static_cast<int>(i), bound_[i] = r;
    volume_[i] = 4.0 / 3.0 * kPi * r * r * r;
    for (int k = 0; k < 3; ++k) moment_[3 * i + k] = 0.4 * volume_[i] * r * r;
  }
  offset_[n] = static_cast<int>(n);
  derive_levers();
}

double ClumpModel::volume(const DEMSystem&, int i) const { return volume_[i]; }

std::array<double, 3> ClumpModel::principal_inertia(const DEMSystem& s, int i, double mass) const {
  (void)s;
  const double rho = mass / volume_[i];
  return {rho * moment_[3 * i], rho * moment_[3 * i + 1], rho * moment_[3 * i + 2]};
}

// about the world's y axis (the plane's normal) at the present orientation
double ClumpModel::inertia(const DEMSystem& s, int i, double mass) const {
  const std::array<double, 3> j = principal_inertia(s, i, mass);
  if (s.stone_quat.size() < 4 * static_cast<std::size_t>(i + 1)) return j[1];
  const double* q = &s.stone_quat[4 * i];
  const Eigen::Matrix3d r = Eigen::Quaterniond(q[0], q[1], q[2], q[3]).normalized().toRotationMatrix();
  return j[0] * r(1, 0) * r(1, 0) + j[1] * r(1, 1) * r(1, 1) + j[2] * r(1, 2) * r(1, 2);
}

double ClumpModel::nominal_diameter(const DEMSystem&, int i) const { return std::cbrt(6.0 * volume_[i] / kPi); }

double ClumpModel::projected_area(const DEMSystem& s, int i) const {
  const double d = nominal_diameter(s, i);
  return 0.25 * kPi * d * d;
}

double ClumpModel::projected_area(const DEMSystem& s, int i, double, double) const { return projected_area(s, i); }

double ClumpModel::stable_dt(const DEMSystem& s) const {
  const DEMParams& p = s.params();
  const bool rot = p.flags & kDEMRotation;
  const double kn = s.stiffness_normal(), kt = s.stiffness_tangential();
  double w2 = 0.0, m_min = std::numeric_limits<double>::infinity();
  for (int i = 0; i < s.n(); ++i) {
    if (!s.stone_active[i] || s.stone_fixed[i]) continue;
    // without rotation the levers do not count (an infinite density divides them away)
    const double m = s.mass(i), rho = rot ? m / volume_[i] : std::numeric_limits<double>::infinity();
    m_min = std::min(m_min, m);
    const double a = kn * (1.0 / m + lever_[2 * i] / rho), c = kt * (1.0 / m + lever_[2 * i + 1] / rho);
    const double b = std::sqrt(kn * kt * lever_[2 * i] * lever_[2 * i + 1]) / rho;
    w2 = std::max(w2, 0.5 * (a + c) + std::hypot(0.5 * (a - c), b));  // the 2 x 2 form's largest eigenvalue
  }
  if (!(w2 > 0.0) || kn <= 0.0) return std::numeric_limits<double>::infinity();
  const double w = std::sqrt(2.0 * w2 + rolling_spin_stiffness(s, m_min));  // two such stones
  // explicit dashpots in a packing: the disc model's bound (disc_model.cpp)
  const double zeta = (p.flags & kDEMDamping) ? s.damping_ratio() : 0.0;
  const double a = std::sqrt(DEMSystem::kPackedContacts), az = a * zeta;
  const double damped = 2.0 / (a * w * (az + std::sqrt(1.0 + az * az)));
  return std::min(kPi / (10.0 * w), damped);
}

void ClumpModel::check_params(const DEMParams& p) const {
  if (!(p.width > 0.0))
    throw std::invalid_argument("width = " + format_value(p.width) +
                                " m: 3D stones need the flume's width between its side walls, allowed range (0, inf)");
}

// before the steps of a call: the default shapes (no shapes set), the radii, the planes, the histories
void ClumpModel::prepare(DEMSystem& s) {
  const std::size_t n = static_cast<std::size_t>(s.n());
  if (!shaped_ || offset_.size() != n + 1) {
    shaped_ = false;
    default_shapes(s);
  }
  for (std::size_t i = 0; i < n; ++i) s.stone_radius[i] = bound_[i];
  planes_ = SphereModel::planes(s.params());
  const std::size_t size = sphere_.size() / 4 * planes_.size();
  if (wall_history_.size() != size) wall_history_.assign(size, SphereContactHistory());
  world_.resize(3 * (sphere_.size() / 4));
}

// ---- contacts

// the centres of every sub-sphere in the world
void ClumpModel::world_spheres(const DEMSystem& s) {
  for (int i = 0; i < s.n(); ++i) {
    const double* q = &s.stone_quat[4 * i];
    const Eigen::Matrix3d r = Eigen::Quaterniond(q[0], q[1], q[2], q[3]).toRotationMatrix();
    const Eigen::Vector3d x(s.stone_pos[2 * i], s.stone_y[i], s.stone_pos[2 * i + 1]);
    for (int g = offset_[i]; g < offset_[i + 1]; ++g) {
      const Eigen::Vector3d c = x + r * Eigen::Vector3d(sphere_[4 * g], sphere_[4 * g + 1], sphere_[4 * g + 2]);
      world_[3 * g] = c[0], world_[3 * g + 1] = c[1], world_[3 * g + 2] = c[2];
    }
  }
}

// sub-sphere g of stone i as a sphere of its body, with the mass its contacts' dashpots use (+inf: fixed)
SphereOfBody ClumpModel::body(const DEMSystem& s, int i, int g, double mass) const {
  SphereOfBody b;
  b.centre = {world_[3 * g], world_[3 * g + 1], world_[3 * g + 2]};
  b.com = {s.stone_pos[2 * i], s.stone_y[i], s.stone_pos[2 * i + 1]};
  b.radius = sphere_[4 * g + 3];
  b.vel = {s.stone_vel[2 * i], s.stone_vel_y[i], s.stone_vel[2 * i + 1]};
  b.omega = {s.stone_omega_3d[3 * i], s.stone_omega_3d[3 * i + 1], s.stone_omega_3d[3 * i + 2]};
  b.mass = mass;
  b.inertia = inertia_3d(s)[3 * i];
  return b;
}

ContactTally ClumpModel::contact_forces(DEMSystem& s, double dt) {
  const SphereContactLaw law = sphere_loads::law(s);
  const double zeta = damping_ratio_from_restitution(law.restitution);  // once per loop, not per contact
  std::vector<ContactPair>& list = pairs(s);
  if (pair_history_.size() != list.size())
    throw std::logic_error("clump model: the pair histories do not follow the neighbour list");
  world_spheres(s);
  const std::vector<double>& inv_m = contact_inv_mass(s);
  const double* w = world_.data();
  ContactTally t;
  for (std::size_t k = 0; k < list.size(); ++k) {
    const int i = list[k].i, j = list[k].j;
    std::vector<SubContact>& hist = pair_history_[k];
    const double dx = s.stone_pos[2 * j] - s.stone_pos[2 * i], dy = s.stone_y[j] - s.stone_y[i];
    const double dz = s.stone_pos[2 * j + 1] - s.stone_pos[2 * i + 1], rs = bound_[i] + bound_[j];
    for (SubContact& c : hist) c.touched = false;
    if (dx * dx + dy * dy + dz * dz >= rs * rs) {
      t.dissipated += open_untouched(i, j, hist, law);
      continue;
    }
    for (int a = offset_[i]; a < offset_[i + 1]; ++a)
      for (int b = offset_[j]; b < offset_[j + 1]; ++b) {
        const double ex = w[3 * b] - w[3 * a], ey = w[3 * b + 1] - w[3 * a + 1], ez = w[3 * b + 2] - w[3 * a + 2];
        const double r = sphere_[4 * a + 3] + sphere_[4 * b + 3];
        if (ex * ex + ey * ey + ez * ez >= r * r) continue;
        const int la = a - offset_[i], lb = b - offset_[j];
        auto it = std::find_if(hist.begin(), hist.end(), [&](const SubContact& c) { return c.a == la && c.b == lb; });
        if (it == hist.end()) it = hist.insert(hist.end(), SubContact{la, lb, false, SphereContactHistory()});
        it->touched = true;
        const SphereContactLoads f = sphere_sphere_contact_unchecked(
            body(s, i, a, 1.0 / inv_m[i]), body(s, j, b, 1.0 / inv_m[j]), it->h, law, zeta, dt);
        apply(s, i, j, f, t, dt);
      }
    t.dissipated += open_untouched(i, j, hist, law);
  }
  return t;
}

// the sub-sphere pairs of stones i, j not touched in this pass opened: they leave the history, and their
// springs' energy is dissipated (returned [J])
double ClumpModel::open_untouched(int i, int j, std::vector<SubContact>& hist, const SphereContactLaw& law) const {
  double e = 0.0;
  for (SubContact& c : hist)
    if (!c.touched) {
      const double ra = sphere_[4 * (offset_[i] + c.a) + 3], rb = sphere_[4 * (offset_[j] + c.b) + 3];
      e += sphere_kernels::release(c.h, law, ra * rb / (ra + rb));
    }
  hist.erase(std::remove_if(hist.begin(), hist.end(), [](const SubContact& c) { return !c.touched; }), hist.end());
  return e;
}

ContactTally ClumpModel::wall_forces(DEMSystem& s, double dt) {
  const SphereContactLaw law = sphere_loads::law(s);
  const double zeta = damping_ratio_from_restitution(law.restitution);  // once per loop, not per contact
  const std::vector<double>& inv_m = inv_mass(s);
  const std::vector<double>& m_eff = mass_eff(s);
  const std::size_t nplane = np();
  ContactTally t;
  // contact_forces has made the world centres of this evaluation
  for (int i = 0; i < s.n(); ++i) {
    if (inv_m[i] == 0.0) continue;
    for (int g = offset_[i]; g < offset_[i + 1]; ++g) {
      const Eigen::Vector3d c(world_[3 * g], world_[3 * g + 1], world_[3 * g + 2]);
      for (std::size_t w = 0; w < nplane; ++w) {
        SphereContactHistory& h = wall_history_[static_cast<std::size_t>(g) * nplane + w];
        const double gap = (c - planes_[w].point).dot(planes_[w].normal);
        // (and once more as it leaves, so that its histories start again from zero)
        if (gap >= sphere_[4 * g + 3] && zero(h)) continue;
        const SphereContactLoads f =
            sphere_plane_contact_unchecked(body(s, i, g, m_eff[i]), planes_[w], h, law, zeta, dt);
        if (f.touching)
          apply(s, i, -1, f, t, dt);
        else
          t.dissipated += f.energy_slip;  // it opened
      }
    }
  }
  return t;
}

void ClumpModel::pairs_rebuilt(DEMSystem&, const std::vector<int>& from) {
  std::vector<std::vector<SubContact>> carried(from.size());
  for (std::size_t k = 0; k < from.size(); ++k)
    if (from[k] >= 0 && static_cast<std::size_t>(from[k]) < pair_history_.size())
      carried[k].swap(pair_history_[from[k]]);
  pair_history_.swap(carried);
}

// ---- state: the shapes and their properties, the touching sub-sphere pairs' histories (sorted by
// (i, j), as the list), and every (sub-sphere, plane) history

void ClumpModel::export_state(const DEMSystem& s, DEMState& t) const {
  ClumpModel shapes;  // an unprepared system's default shapes, made as prepare would
  const ClumpModel& m = (shaped_ || offset_.size() == static_cast<std::size_t>(s.n()) + 1) ? *this : shapes;
  if (&m == &shapes) shapes.default_shapes(s);
  t.clump_sphere = m.sphere_;
  t.clump_offset = m.offset_;
  for (std::size_t i = 0; i < m.volume_.size(); ++i)
    t.clump_property.insert(t.clump_property.end(),
                            {m.volume_[i], m.moment_[3 * i], m.moment_[3 * i + 1], m.moment_[3 * i + 2]});
  const std::vector<ContactPair>& list = pairs(const_cast<DEMSystem&>(s));
  std::vector<std::size_t> order(std::min(list.size(), pair_history_.size()));
  for (std::size_t k = 0; k < order.size(); ++k) order[k] = k;
  std::sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) {
    return list[a].i != list[b].i ? list[a].i < list[b].i : list[a].j < list[b].j;
  });
  for (std::size_t k : order)
    for (const SubContact& c : pair_history_[k]) {
      if (zero(c.h)) continue;
      t.clump_contact.insert(t.clump_contact.end(), {list[k].i, list[k].j, c.a, c.b});
      push3(t.clump_contact_spring, c.h.spring);
      push3(t.clump_contact_rolling, c.h.rolling);
    }
  const std::size_t size = m.sphere_.size() / 4 * (s.params().walls.size() + 2);
  push_histories(wall_history_, size, t.clump_wall_spring, t.clump_wall_rolling);
}

void ClumpModel::check_state(const DEMSystem& s, const DEMState& t) const {
  check_params(s.params());
  const std::size_t n = t.stone_radius.size();
  check_layout(n, t.clump_sphere, t.clump_offset);
  const std::size_t ns = t.clump_sphere.size() / 4, nc = t.clump_contact.size() / 4;
  require_size("clump_property", t.clump_property, 4 * n);
  require_size("clump_contact", t.clump_contact, 4 * nc);
  require_size("clump_contact_spring", t.clump_contact_spring, 3 * nc);
  require_size("clump_contact_rolling", t.clump_contact_rolling, 3 * nc);
  require_size("clump_wall_spring", t.clump_wall_spring, 3 * ns * (s.params().walls.size() + 2));
  require_size("clump_wall_rolling", t.clump_wall_rolling, 3 * ns * (s.params().walls.size() + 2));
  for (std::size_t k = 0; k < nc; ++k) {
    const int* c = &t.clump_contact[4 * k];
    const bool pair = c[0] >= 0 && c[0] < c[1] && c[1] < static_cast<int>(n);
    const bool sorted = k == 0 || c[-4] < c[0] || (c[-4] == c[0] && c[-3] <= c[1]);
    if (!pair || !sorted || c[2] < 0 || c[2] >= t.clump_offset[c[0] + 1] - t.clump_offset[c[0]] || c[3] < 0 ||
        c[3] >= t.clump_offset[c[1] + 1] - t.clump_offset[c[1]])
      throw std::invalid_argument("import_state: clump contact " + std::to_string(k) +
                                  " is outside 0 <= i < j < n, its spheres outside their stones, or not sorted");
  }
}

// after check_state: the listed pairs are those with a history (the next build carries them over)
void ClumpModel::import_state(DEMSystem& s, const DEMState& t) {
  const std::size_t n = t.clump_offset.size() - 1;
  sphere_ = t.clump_sphere, offset_ = t.clump_offset;
  volume_.resize(n), moment_.resize(3 * n), bound_.assign(n, 0.0);
  std::vector<ClumpSphere> parts;
  for (std::size_t i = 0; i < n; ++i) {
    volume_[i] = t.clump_property[4 * i];
    for (int k = 0; k < 3; ++k) moment_[3 * i + k] = t.clump_property[4 * i + 1 + k];
    parts.clear();
    for (int g = offset_[i]; g < offset_[i + 1]; ++g)
      parts.push_back({Eigen::Vector3d(sphere_[4 * g], sphere_[4 * g + 1], sphere_[4 * g + 2]), sphere_[4 * g + 3]});
    // as set_shapes takes it (the same bits: a restart's radii are the run's)
    bound_[i] = bounding_radius(parts);
  }
  shaped_ = true;
  derive_levers();
  std::vector<ContactPair>& list = pairs(s);
  list.clear();
  pair_history_.clear();
  for (std::size_t k = 0; k < t.clump_contact.size() / 4; ++k) {
    const int* c = &t.clump_contact[4 * k];
    if (list.empty() || list.back().i != c[0] || list.back().j != c[1]) {
      list.push_back({c[0], c[1], 0.0, 0.0});
      pair_history_.emplace_back();
    }
    pair_history_.back().push_back({c[2], c[3], true, {at3(t.clump_contact_spring, k), at3(t.clump_contact_rolling, k)}});
  }
  wall_history_ = histories(t.clump_wall_spring, t.clump_wall_rolling);
  world_.resize(3 * (sphere_.size() / 4));
}

void ClumpModel::state_to_map(DEMState& t, StateMap& m) const {
  using state::to_double;
  m["clump_sphere"] = std::move(t.clump_sphere);
  m["clump_offset"] = to_double(t.clump_offset);
  m["clump_property"] = std::move(t.clump_property);
  m["clump_contact"] = to_double(t.clump_contact);
  m["clump_contact_spring"] = std::move(t.clump_contact_spring);
  m["clump_contact_rolling"] = std::move(t.clump_contact_rolling);
  m["clump_wall_spring"] = std::move(t.clump_wall_spring);
  m["clump_wall_rolling"] = std::move(t.clump_wall_rolling);
}

void ClumpModel::state_from_map(const StateMap& m, std::size_t n, std::size_t nwalls, DEMState& t) const {
  using state::entry;
  using state::from_double;
  from_double(t.clump_offset, entry(m, "clump_offset", n + 1));
  const std::vector<double>& sphere = entry(m, "clump_sphere", state::kAnySize);
  t.clump_sphere = sphere;
  const std::size_t ns = sphere.size() / 4;
  t.clump_property = entry(m, "clump_property", 4 * n);
  const std::vector<double>& c = entry(m, "clump_contact", state::kAnySize);
  from_double(t.clump_contact, c);
  t.clump_contact_spring = entry(m, "clump_contact_spring", 3 * (c.size() / 4));
  t.clump_contact_rolling = entry(m, "clump_contact_rolling", 3 * (c.size() / 4));
  t.clump_wall_spring = entry(m, "clump_wall_spring", 3 * ns * (nwalls + 2));
  t.clump_wall_rolling = entry(m, "clump_wall_rolling", 3 * ns * (nwalls + 2));
}

// ---- the flow's view: the union's volume in each cell's slab, the drag of the volume-equivalent sphere

// shapes set: each stone's sub-spheres into one cell list; else (not prepared since the model was set,
// or the stones resized) the spheres of stone_radius that prepare() makes the stones
void ClumpModel::map_footprint(const DEMSystem& s, PorosityMapper& m, const double* x, const double* z) const {
  SphereModel::require_true_void_fraction(m, "clump");
  if (!shaped_ || offset_.size() != static_cast<std::size_t>(s.n()) + 1) {
    m.map_spheres(s.n(), x, z, s.stone_radius.data(), s.params().width, s.stone_active.data());
    return;
  }
  m.map_clumps(s.n(), x, z, s.stone_quat.data(), sphere_.data(), offset_.data(), volume_.data(), s.params().width,
               s.stone_active.data());
}

DragForce ClumpModel::drag(const DEMSystem& s, int i, const StoneFlowSample& f, double up, double wp, double rho,
                           double nu, DragLaw law, double* slope) const {
  const double d = nominal_diameter(s, i);
  if (slope) *slope = sphere_drag_slope(f, up, wp, d, rho, nu, law);
  return stone_drag(f, up, wp, d, rho, nu, law);
}

double ClumpModel::drag_relaxation_dt(const DEMSystem& s, int i, double relaxation, double mass, double vrel, double w,
                                      double rho, double nu) const {
  const double d = nominal_diameter(s, i);
  const double slope = drag_slope(vrel, d, w * 0.5 * rho * projected_area(s, i), nu, DragLaw::kPaper);
  return relaxation * (mass / slope);
}

std::unique_ptr<StonePacking> ClumpModel::packing(const WeirSpec& spec) const { return make_clump_packing(spec); }

// ---- outline, for the packing diagnostics: the union of the sub-spheres' sections by the plane y = y_i

// whether the shapes and orientations are there (else, before the first step without shapes: the bounding
// sphere's)
bool ClumpModel::outlined(const DEMSystem& s) const {
  const std::size_t n = static_cast<std::size_t>(s.n());
  return offset_.size() == n + 1 && s.stone_quat.size() == 4 * n;
}

// the centre (x, z) of sub-sphere g of stone i in the world [m]
std::array<double, 2> ClumpModel::world_xz(const DEMSystem& s, int i, int g) const {
  const double* q = &s.stone_quat[4 * i];
  const Eigen::Matrix3d r = Eigen::Quaterniond(q[0], q[1], q[2], q[3]).toRotationMatrix();
  const Eigen::Vector3d c = r * Eigen::Vector3d(sphere_[4 * g], sphere_[4 * g + 1], sphere_[4 * g + 2]);
  return {s.stone_pos[2 * i] + c[0], s.stone_pos[2 * i + 1] + c[2]};
}

double ClumpModel::gap(const DEMSystem& s, int i, double x, double z) const {
  if (!outlined(s)) return DiscModel::gap(s, i, x, z);
  double g_min = std::numeric_limits<double>::infinity();
  for (int g = offset_[i]; g < offset_[i + 1]; ++g) {
    const auto c = world_xz(s, i, g);
    g_min = std::min(g_min, std::hypot(x - c[0], z - c[1]) - sphere_[4 * g + 3]);
  }
  return std::max(g_min, 0.0);
}

// the x-z outline (each sub-sphere's disc, the projection of the stone on the plane)
bool ClumpModel::covers(const DEMSystem& s, int i, double x, double z) const {
  if (!outlined(s)) return DiscModel::covers(s, i, x, z);
  for (int g = offset_[i]; g < offset_[i + 1]; ++g) {
    const auto c = world_xz(s, i, g);
    const double dx = x - c[0], dz = z - c[1], r = sphere_[4 * g + 3];
    if (dx * dx + dz * dz < r * r) return true;
  }
  return false;
}

double ClumpModel::outline_max(const DEMSystem& s, int i, const std::function<double(double, double)>& f) const {
  if (!outlined(s)) return DiscModel::outline_max(s, i, f);
  double m = -std::numeric_limits<double>::infinity();
  for (int g = offset_[i]; g < offset_[i + 1]; ++g) {
    const auto c = world_xz(s, i, g);
    m = std::max(m, f(c[0], c[1]) + sphere_[4 * g + 3]);
  }
  return m;
}

void set_clumps(DEMSystem& s, const std::vector<double>& sphere, const std::vector<int>& offset) {
  auto model = std::make_unique<ClumpModel>();
  model->set_shapes(s.n(), sphere, offset);
  const std::vector<double> bound = model->bounding_radii();
  s.set_model(std::move(model));
  std::copy(bound.begin(), bound.end(), s.stone_radius.begin());
}

void set_clumps(DEMSystem& s, const std::vector<Clump>& clumps) {
  if (clumps.size() != static_cast<std::size_t>(s.n()))
    throw std::invalid_argument("clumps: " + std::to_string(clumps.size()) + " clumps for " + std::to_string(s.n()) +
                                " stones; allowed: one per stone");
  auto model = std::make_unique<ClumpModel>();
  model->set_shapes(clumps);
  const std::vector<double> bound = model->bounding_radii();
  s.set_model(std::move(model));
  std::copy(bound.begin(), bound.end(), s.stone_radius.begin());
}

}  // namespace vofdem
