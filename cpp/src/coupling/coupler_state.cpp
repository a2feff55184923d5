// State of the Coupler: the union of the flow's (FlowState), the stones' (DEMState) and its own (time,
// exchanged forces, base porosity), as one typed value. The guard's snapshot copies it every step into
// a reused CouplerState (array copies, no allocation once sized, no keys); a user branches a run with
// it; the checkpoint maps it to named flat arrays ("coupler/...", "fluid/...", "turbulence/...", "dem/...").
#include <algorithm>
#include <stdexcept>
#include <utility>

#include "common/state_fields.h"
#include "vofdem/common/check.h"
#include "vofdem/coupling/coupler.h"

namespace vofdem {

namespace {
using state::entry;
using state::StateMap;
}  // namespace

void Coupler::export_state(CouplerState& s) const { export_state(s, true); }

void Coupler::import_state(const CouplerState& s) { import_state(s, true); }

void Coupler::export_state(CouplerState& s, bool with_base) const {
  s.time = time_;
  s.steps = steps_;
  s.mapped = mapped_;
  s.redistributed = redistributed_;
  s.stone_force_drag = stone_force_drag;
  s.stone_force_pressure = stone_force_pressure;
  s.stone_relative_speed = stone_vrel_;
  s.has_drag_slope = params_.stone_drag == StoneDragModel::kBed;
  if (s.has_drag_slope) s.stone_drag_slope = stone_drag_slope_;
  if (fluid_) {
    if (with_base) {
      s.cell_base_porosity = cell_base_porosity;
      s.cell_base_diameter = cell_base_diameter;
    }
    fluid_->export_state(s.fluid);
  }
  if (stones_) stones_->export_state(s.stones);
}

void Coupler::import_state(const CouplerState& s, bool with_base) {
  const std::size_t n = static_cast<std::size_t>(n_);
  // check every part before writing anything
  require_size("coupler/stone_force_drag", s.stone_force_drag, 2 * n);
  require_size("coupler/stone_force_pressure", s.stone_force_pressure, 2 * n);
  require_size("coupler/stone_relative_speed", s.stone_relative_speed, n);
  if (s.has_drag_slope) require_size("coupler/stone_drag_slope", s.stone_drag_slope, n);
  if (fluid_) {
    const std::size_t nc = static_cast<std::size_t>(fluid_->grid().ncell());
    if (with_base) {
      require_size("coupler/cell_base_porosity", s.cell_base_porosity, nc);
      require_size("coupler/cell_base_diameter", s.cell_base_diameter, nc);
    }
    fluid_->check_state(s.fluid);
  }
  if (stones_) stones_->check_state(s.stones);
  if (fluid_) {
    if (with_base) {
      state::copy_into(cell_base_porosity, s.cell_base_porosity);
      state::copy_into(cell_base_diameter, s.cell_base_diameter);
      if (kernel_) make_kernel();  // its solid cells are the base porosity's
    }
    fluid_->import_state(s.fluid);
  }
  if (stones_) stones_->import_state(s.stones);
  time_ = s.time;
  steps_ = s.steps;
  mapped_ = s.mapped;
  redistributed_ = s.redistributed;
  state::copy_into(stone_force_drag, s.stone_force_drag);
  state::copy_into(stone_force_pressure, s.stone_force_pressure);
  state::copy_into(stone_vrel_, s.stone_relative_speed);
  forces_applied_ = false;
  for (std::size_t i = 0; i < stone_force_drag.size(); ++i)
    if (stone_force_drag[i] != 0.0 || stone_force_pressure[i] != 0.0) forces_applied_ = true;
  // written with the bed drag only (older states and the sphere drag: none)
  if (s.has_drag_slope) state::copy_into(stone_drag_slope_, s.stone_drag_slope);
  else std::fill(stone_drag_slope_.begin(), stone_drag_slope_.end(), 0.0);
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
  s["coupler/stone_force_drag"] = std::move(t.stone_force_drag);
  s["coupler/stone_force_pressure"] = std::move(t.stone_force_pressure);
  s["coupler/stone_relative_speed"] = std::move(t.stone_relative_speed);
  if (t.has_drag_slope) s["coupler/stone_drag_slope"] = std::move(t.stone_drag_slope);
  if (fluid_) {
    s["coupler/cell_base_porosity"] = std::move(t.cell_base_porosity);
    s["coupler/cell_base_diameter"] = std::move(t.cell_base_diameter);
    state::flow_to_map(t.fluid, s);
  }
  if (stones_)
    for (auto& kv : dem_state_to_map(std::move(t.stones))) s["dem/" + kv.first] = std::move(kv.second);
  return s;
}

void Coupler::import_state(const std::map<std::string, std::vector<double>>& checkpoint) {
  StateMap renamed;
  const StateMap& s = state::with_stone_keys(checkpoint, "coupler/", renamed);
  const std::size_t n = static_cast<std::size_t>(n_);
  CouplerState t;
  t.time = entry(s, "coupler/time", 1)[0];
  t.stone_force_drag = entry(s, "coupler/stone_force_drag", 2 * n);
  t.stone_force_pressure = entry(s, "coupler/stone_force_pressure", 2 * n);
  t.stone_relative_speed = entry(s, "coupler/stone_relative_speed", n);
  t.has_drag_slope = s.count("coupler/stone_drag_slope") > 0;
  if (t.has_drag_slope) t.stone_drag_slope = entry(s, "coupler/stone_drag_slope", n);
  if (stones_) {
    StateMap dem;
    for (const auto& kv : s)
      if (kv.first.rfind("dem/", 0) == 0) dem[kv.first.substr(4)] = kv.second;
    if (dem.empty()) throw std::invalid_argument("state: no 'dem/' entries for the stones");
    t.stones = dem_state_from_map(dem, stones_->params().walls.size());
  }
  if (fluid_) {
    const std::size_t nc = static_cast<std::size_t>(fluid_->grid().ncell());
    t.cell_base_porosity = entry(s, "coupler/cell_base_porosity", nc);
    t.cell_base_diameter = entry(s, "coupler/cell_base_diameter", nc);
    t.fluid = state::flow_from_map(s, fluid_->grid());
  }
  t.steps = static_cast<long long>(entry(s, "coupler/steps", 1)[0]);
  t.mapped = entry(s, "coupler/mapped", 1)[0] != 0.0;
  t.redistributed = entry(s, "coupler/redistributed", 1)[0];
  import_state(t);
}

}  // namespace vofdem
