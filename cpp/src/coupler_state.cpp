// State of the Coupler: the union of the flow's (FlowState), the stones' (DEMState) and its own (time,
// exchanged forces, base porosity), as one typed value. The guard's snapshot copies it every step into
// a reused CouplerState (array copies, no allocation once sized, no keys); a user branches a run with
// it; the checkpoint maps it to named flat arrays ("coupler/...", "fluid/...", "turbulence/...", "dem/...").
#include <algorithm>
#include <stdexcept>
#include <utility>

#include "vofdem/check.h"
#include "vofdem/coupler.h"

namespace vofdem {

namespace {
using StateMap = std::map<std::string, std::vector<double>>;
constexpr std::size_t kAny = static_cast<std::size_t>(-1);

const std::vector<double>& need(const StateMap& s, const std::string& key, std::size_t size) {
  auto it = s.find(key);
  if (it == s.end()) throw std::invalid_argument("state: missing entry '" + key + "'");
  if (size != kAny && it->second.size() != size)
    throw std::invalid_argument("state: '" + key + "' has " + std::to_string(it->second.size()) +
                                " values, expected " + std::to_string(size));
  return it->second;
}

void need_size(const char* name, const std::vector<double>& v, std::size_t size) {
  if (v.size() != size)
    throw std::invalid_argument(std::string("state: '") + name + "' has " + std::to_string(v.size()) +
                                " values, expected " + std::to_string(size));
}

// same size (checked): written in place, so the numpy views of dst stay valid
void copy_into(std::vector<double>& dst, const std::vector<double>& src) { std::copy(src.begin(), src.end(), dst.begin()); }

// moves the arrays of f into s
void flow_to_map(FlowState& f, StateMap& s) {
  s["fluid/face_u"] = std::move(f.face_u);
  s["fluid/face_w"] = std::move(f.face_w);
  s["fluid/cell_p"] = std::move(f.cell_p);
  s["fluid/cell_F"] = std::move(f.cell_F);
  s["fluid/cell_porosity"] = std::move(f.cell_porosity);
  s["fluid/cell_stone_diameter"] = std::move(f.cell_stone_diameter);
  s["fluid/cell_nut"] = std::move(f.cell_nut);
  s["fluid/face_x_solid_u"] = std::move(f.face_x_solid_u);
  s["fluid/face_z_solid_w"] = std::move(f.face_z_solid_w);
  s["fluid/time"] = {f.time};
  s["fluid/step_count"] = {static_cast<double>(f.step_count)};
  s["fluid/last_dt"] = {f.last_dt};
  s["fluid/prev_dt"] = {f.prev_dt};
  s["fluid/face_u_prev"] = std::move(f.face_u_prev);
  s["fluid/face_w_prev"] = std::move(f.face_w_prev);
  s["fluid/inlet_volume"] = {f.inlet_volume};
  s["fluid/net_inflow_volume"] = {f.net_inflow_volume};
  s["fluid/dilatation_volume"] = {f.dilatation_volume};
  s["fluid/discharge_times"] = std::move(f.discharge.times);
  s["fluid/discharge_q"] = std::move(f.discharge.discharge);
  // the k-epsilon model's own state: the next step reads its k, eps, nu_t and wall shear
  s["turbulence/cell_k"] = std::move(f.turbulence_k);
  s["turbulence/cell_eps"] = std::move(f.turbulence_eps);
  s["turbulence/cell_nut"] = std::move(f.turbulence_nut);
  s["turbulence/cell_u_tau"] = std::move(f.turbulence_u_tau);
  s["turbulence/face_x_wall_shear"] = std::move(f.turbulence_face_x_wall_shear);
  s["turbulence/face_z_wall_shear"] = std::move(f.turbulence_face_z_wall_shear);
  s["turbulence/cell_role"] = std::move(f.turbulence_role);  // which cells held water: a cell that fills starts from them
}

// the flow's part of a checkpoint; entries added since are optional, with what older runs had
FlowState flow_from_map(const StateMap& s, const Grid2D& g) {
  const std::size_t nc = g.ncell(), nfx = g.nface_x(), nfz = g.nface_z();
  FlowState f;
  f.face_u = need(s, "fluid/face_u", nfx);
  f.face_w = need(s, "fluid/face_w", nfz);
  f.cell_p = need(s, "fluid/cell_p", nc);
  f.cell_F = need(s, "fluid/cell_F", nc);
  f.cell_porosity = need(s, "fluid/cell_porosity", nc);
  f.cell_stone_diameter = need(s, "fluid/cell_stone_diameter", nc);
  f.cell_nut = need(s, "fluid/cell_nut", nc);
  f.face_x_solid_u = need(s, "fluid/face_x_solid_u", nfx);
  f.face_z_solid_w = need(s, "fluid/face_z_solid_w", nfz);
  f.time = need(s, "fluid/time", 1)[0];
  f.step_count = static_cast<long long>(need(s, "fluid/step_count", 1)[0]);
  // older states have no last step: the next one starts from FlowParams::initial_dt
  f.last_dt = s.count("fluid/last_dt") ? need(s, "fluid/last_dt", 1)[0] : 0.0;
  // the step history of AB2 (older states: none, the next step is forward Euler)
  f.prev_dt = s.count("fluid/prev_dt") ? need(s, "fluid/prev_dt", 1)[0] : 0.0;
  if (f.prev_dt > 0.0) f.face_u_prev = need(s, "fluid/face_u_prev", nfx), f.face_w_prev = need(s, "fluid/face_w_prev", nfz);
  f.inlet_volume = need(s, "fluid/inlet_volume", 1)[0];
  // older states have no boundary budget: it restarts from 0
  f.net_inflow_volume = s.count("fluid/net_inflow_volume") ? need(s, "fluid/net_inflow_volume", 1)[0] : 0.0;
  f.dilatation_volume = s.count("fluid/dilatation_volume") ? need(s, "fluid/dilatation_volume", 1)[0] : 0.0;
  f.discharge.times = need(s, "fluid/discharge_times", kAny);
  f.discharge.discharge = need(s, "fluid/discharge_q", kAny);
  // states written before the k-epsilon model was part of the checkpoint keep the model as it is
  f.has_turbulence = s.count("turbulence/cell_k") > 0;
  if (f.has_turbulence) {
    f.turbulence_k = need(s, "turbulence/cell_k", nc);
    f.turbulence_eps = need(s, "turbulence/cell_eps", nc);
    f.turbulence_nut = need(s, "turbulence/cell_nut", nc);
    f.turbulence_u_tau = need(s, "turbulence/cell_u_tau", nc);
    f.turbulence_face_x_wall_shear = need(s, "turbulence/face_x_wall_shear", nfx);
    f.turbulence_face_z_wall_shear = need(s, "turbulence/face_z_wall_shear", nfz);
    f.has_roles = s.count("turbulence/cell_role") > 0;
    if (f.has_roles) f.turbulence_role = need(s, "turbulence/cell_role", nc);
  }
  return f;
}
}  // namespace

void Coupler::export_state(CouplerState& s) const {
  s.time = time_;
  s.steps = steps_;
  s.mapped = mapped_;
  s.redistributed = redistributed_;
  s.disc_force_drag = disc_force_drag;
  s.disc_force_pressure = disc_force_pressure;
  s.disc_relative_speed = disc_vrel_;
  s.has_drag_slope = params_.stone_drag == StoneDragModel::kBed;
  if (s.has_drag_slope) s.disc_drag_slope = disc_drag_slope_;
  if (fluid_) {
    s.cell_base_porosity = cell_base_porosity;
    s.cell_base_diameter = cell_base_diameter;
    fluid_->export_state(s.fluid);
  }
  if (stones_) stones_->export_state(s.stones);
}

void Coupler::import_state(const CouplerState& s) {
  const std::size_t n = static_cast<std::size_t>(n_);
  // check every part before writing anything
  need_size("coupler/disc_force_drag", s.disc_force_drag, 2 * n);
  need_size("coupler/disc_force_pressure", s.disc_force_pressure, 2 * n);
  need_size("coupler/disc_relative_speed", s.disc_relative_speed, n);
  if (s.has_drag_slope) need_size("coupler/disc_drag_slope", s.disc_drag_slope, n);
  if (fluid_) {
    const std::size_t nc = static_cast<std::size_t>(fluid_->grid().ncell());
    need_size("coupler/cell_base_porosity", s.cell_base_porosity, nc);
    need_size("coupler/cell_base_diameter", s.cell_base_diameter, nc);
    fluid_->check_state(s.fluid);
  }
  if (stones_) stones_->check_state(s.stones);
  if (fluid_) {
    copy_into(cell_base_porosity, s.cell_base_porosity);
    copy_into(cell_base_diameter, s.cell_base_diameter);
    fluid_->import_state(s.fluid);
  }
  if (stones_) stones_->import_state(s.stones);
  time_ = s.time;
  steps_ = s.steps;
  mapped_ = s.mapped;
  redistributed_ = s.redistributed;
  copy_into(disc_force_drag, s.disc_force_drag);
  copy_into(disc_force_pressure, s.disc_force_pressure);
  copy_into(disc_vrel_, s.disc_relative_speed);
  forces_applied_ = false;
  for (std::size_t i = 0; i < disc_force_drag.size(); ++i)
    if (disc_force_drag[i] != 0.0 || disc_force_pressure[i] != 0.0) forces_applied_ = true;
  // written with the bed drag only (older states and the sphere drag: none)
  if (s.has_drag_slope) copy_into(disc_drag_slope_, s.disc_drag_slope);
  else std::fill(disc_drag_slope_.begin(), disc_drag_slope_.end(), 0.0);
}

// ---------------------------------------------------------------------------------------------
// checkpoint: named flat arrays

std::map<std::string, std::vector<double>> Coupler::export_state() const {
  CouplerState t;
  export_state(t);
  StateMap s;
  s["coupler/time"] = {t.time};
  s["coupler/steps"] = {static_cast<double>(t.steps)};
  s["coupler/mapped"] = {t.mapped ? 1.0 : 0.0};
  s["coupler/redistributed"] = {t.redistributed};
  s["coupler/disc_force_drag"] = std::move(t.disc_force_drag);
  s["coupler/disc_force_pressure"] = std::move(t.disc_force_pressure);
  s["coupler/disc_relative_speed"] = std::move(t.disc_relative_speed);
  if (t.has_drag_slope) s["coupler/disc_drag_slope"] = std::move(t.disc_drag_slope);
  if (fluid_) {
    s["coupler/cell_base_porosity"] = std::move(t.cell_base_porosity);
    s["coupler/cell_base_diameter"] = std::move(t.cell_base_diameter);
    flow_to_map(t.fluid, s);
  }
  if (stones_)
    for (auto& kv : dem_state_to_map(std::move(t.stones))) s["dem/" + kv.first] = std::move(kv.second);
  return s;
}

void Coupler::import_state(const std::map<std::string, std::vector<double>>& s) {
  const std::size_t n = static_cast<std::size_t>(n_);
  CouplerState t;
  t.time = need(s, "coupler/time", 1)[0];
  t.disc_force_drag = need(s, "coupler/disc_force_drag", 2 * n);
  t.disc_force_pressure = need(s, "coupler/disc_force_pressure", 2 * n);
  t.disc_relative_speed = need(s, "coupler/disc_relative_speed", n);
  t.has_drag_slope = s.count("coupler/disc_drag_slope") > 0;
  if (t.has_drag_slope) t.disc_drag_slope = need(s, "coupler/disc_drag_slope", n);
  if (stones_) {
    StateMap dem;
    for (const auto& kv : s)
      if (kv.first.rfind("dem/", 0) == 0) dem[kv.first.substr(4)] = kv.second;
    if (dem.empty()) throw std::invalid_argument("state: no 'dem/' entries for the stones");
    t.stones = dem_state_from_map(dem, stones_->params().walls.size());
  }
  if (fluid_) {
    const std::size_t nc = static_cast<std::size_t>(fluid_->grid().ncell());
    t.cell_base_porosity = need(s, "coupler/cell_base_porosity", nc);
    t.cell_base_diameter = need(s, "coupler/cell_base_diameter", nc);
    t.fluid = flow_from_map(s, fluid_->grid());
  }
  t.steps = static_cast<long long>(need(s, "coupler/steps", 1)[0]);
  t.mapped = need(s, "coupler/mapped", 1)[0] != 0.0;
  t.redistributed = need(s, "coupler/redistributed", 1)[0];
  import_state(t);
}

}  // namespace vofdem
