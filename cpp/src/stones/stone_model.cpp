// The stone models' registry and the base class's access to DEMSystem (stone_model.h).
#include "vofdem/stones/stone_model.h"

#include <algorithm>
#include <mutex>
#include <stdexcept>
#include <utility>

#include "vofdem/stones/dem_system.h"
#include "vofdem/stones/clump_model.h"
#include "vofdem/stones/disc_model.h"
#include "vofdem/stones/polygon_model.h"
#include "vofdem/stones/sphere_model.h"
#include "vofdem/stones/stone_packing.h"

namespace vofdem {

double StoneModel::wet_radius(const DEMSystem& s, int i) const { return s.stone_radius[i]; }

namespace {
template <class Model>
std::unique_ptr<StoneModel> make_model() {
  return std::make_unique<Model>();
}

struct Registry {
  std::mutex lock;
  std::vector<std::pair<std::string, StoneModelFactory>> models;
  Registry() {
    // the built-in models, one line each (here, not at namespace scope: a program's models may be
    // registered during static initialisation, before such a table would be made)
    models.emplace_back("disc", make_model<DiscModel>);
    models.emplace_back("polygon", make_model<PolygonModel>);
    models.emplace_back("sphere", make_model<SphereModel>);
    models.emplace_back("clump", make_model<ClumpModel>);
  }
};

Registry& registry() {
  static Registry r;
  return r;
}

std::string quoted_names(const std::vector<std::pair<std::string, StoneModelFactory>>& models) {
  std::string out;
  for (const auto& m : models) out += (out.empty() ? "'" : ", '") + m.first + "'";
  return out;
}
}  // namespace

std::unique_ptr<StonePacking> StoneModel::packing(const WeirSpec&) const { return nullptr; }

void register_stone_model(const std::string& name, StoneModelFactory make) {
  Registry& r = registry();
  std::lock_guard<std::mutex> g(r.lock);
  if (name.empty() || !make) throw std::invalid_argument("register_stone_model: a model needs a name and a factory");
  for (const auto& m : r.models)
    if (m.first == name)
      throw std::invalid_argument("register_stone_model: the name '" + name + "' is taken (registered: " +
                                  quoted_names(r.models) + ")");
  r.models.emplace_back(name, std::move(make));
}

std::unique_ptr<StoneModel> make_stone_model(const std::string& name) {
  Registry& r = registry();
  StoneModelFactory make;
  {
    std::lock_guard<std::mutex> g(r.lock);
    for (const auto& m : r.models)
      if (m.first == name) make = m.second;
    if (!make)
      throw std::invalid_argument("shape = '" + name + "' is not one of the registered stone models " +
                                  quoted_names(r.models));
  }
  return make();
}

std::vector<std::string> stone_model_names() {
  Registry& r = registry();
  std::lock_guard<std::mutex> g(r.lock);
  std::vector<std::string> out;
  for (const auto& m : r.models) out.push_back(m.first);
  return out;
}

std::string stone_model_of_checkpoint(const std::function<bool(const std::string&)>& has_key) {
  for (const std::string& name : stone_model_names()) {
    const std::string key = make_stone_model(name)->checkpoint_key();
    if (!key.empty() && has_key(key)) return name;
  }
  return "disc";
}

// ---- DEMSystem's insides, for the models

std::vector<ContactPair>& StoneModel::pairs(DEMSystem& s) { return s.pairs_; }
const std::vector<double>& StoneModel::inv_mass(const DEMSystem& s) { return s.inv_mass_; }
const std::vector<double>& StoneModel::mass_eff(const DEMSystem& s) { return s.mass_eff_; }
const std::vector<double>& StoneModel::contact_inv_mass(const DEMSystem& s) { return s.contact_inv_mass_; }
const std::vector<double>& StoneModel::inertia_3d(const DEMSystem& s) { return s.inertia_3d_; }
std::vector<double>& StoneModel::wall_spring(DEMSystem& s) { return s.wall_xi_; }
std::vector<double>& StoneModel::wall_rolling_spring(DEMSystem& s) { return s.wall_mr_; }
std::vector<PointSprings>& StoneModel::wall_point_springs(DEMSystem& s) { return s.wall_points_; }
ContactLaw StoneModel::contact_law(const DEMSystem& s) { return s.contact_law(); }
StoneModel::WallCandidates StoneModel::wall_candidates(const DEMSystem& s) {
  return {s.wall_cand_start_.data(), s.wall_cand_.data()};
}
bool StoneModel::rolling_stones(const DEMSystem& s) { return s.rolling_stones(); }
bool StoneModel::rolling_walls(const DEMSystem& s) { return s.rolling_walls(); }

void StoneModel::rolling_contact(DEMSystem& s, ContactPair& c, double fn, double dt, ContactTally& t) {
  const DEMSystem::RollingEnergy e = s.rolling_contact(c, fn, dt);
  t.elastic += e.elastic;
  t.dissipated += e.dissipated;
}

void StoneModel::rolling_wall(DEMSystem& s, int i, double& mr, double fn, double dt, ContactTally& t) {
  const DEMSystem::RollingEnergy e = s.rolling_wall(i, mr, fn, dt);
  t.elastic += e.elastic;
  t.dissipated += e.dissipated;
}

double StoneModel::rolling_spin_stiffness(const DEMSystem& s, double m_min) { return s.rolling_spin_stiffness(m_min); }

void StoneModel::shapes_changed(DEMSystem& s) { s.shapes_changed(); }

}  // namespace vofdem
