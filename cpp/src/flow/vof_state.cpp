// The flow's whole state as one typed value (FlowState): export_state() copies it out, import_state()
// back in place, so a coupled run can be copied and branched (as MuJoCo's mj_copyData) and the
// coupler's guard snapshot costs array copies only. The checkpoint maps it to named arrays
// ("fluid/...", "turbulence/..."). The arrays are listed once, in the two tables below.
#include <string>

#include "common/state_fields.h"
#include "vofdem/common/check.h"
#include "vofdem/flow/vof_grid.h"

namespace vofdem {

namespace {
using state::StateMap;
enum Where { kCells, kFacesX, kFacesZ };

// the flow's arrays (checked in this order): checkpoint key "fluid/<key>"
using FlowField = state::Field<FlowState, VOFGrid, double>;
const FlowField kFlowFields[] = {
    {"cell_p", &FlowState::cell_p, &VOFGrid::cell_p, kCells, 1, false, 0.0},
    {"cell_F", &FlowState::cell_F, &VOFGrid::cell_F, kCells, 1, false, 0.0},
    {"cell_porosity", &FlowState::cell_porosity, &VOFGrid::cell_porosity, kCells, 1, false, 0.0},
    {"cell_stone_diameter", &FlowState::cell_stone_diameter, &VOFGrid::cell_stone_diameter, kCells, 1, false, 0.0},
    {"cell_nut", &FlowState::cell_nut, &VOFGrid::cell_nut, kCells, 1, false, 0.0},
    {"face_u", &FlowState::face_u, &VOFGrid::face_u, kFacesX, 1, false, 0.0},
    {"face_x_solid_u", &FlowState::face_x_solid_u, &VOFGrid::face_x_solid_u, kFacesX, 1, false, 0.0},
    {"face_w", &FlowState::face_w, &VOFGrid::face_w, kFacesZ, 1, false, 0.0},
    {"face_z_solid_w", &FlowState::face_z_solid_w, &VOFGrid::face_z_solid_w, kFacesZ, 1, false, 0.0},
};

// the k-epsilon model's own state (the next step reads its k, eps, nu_t and wall shear): "turbulence/<key>"
using TurbulenceField = state::Field<FlowState, KEpsilonModel, double>;
const TurbulenceField kTurbulenceFields[] = {
    {"cell_k", &FlowState::turbulence_k, &KEpsilonModel::cell_k, kCells, 1, false, 0.0},
    {"cell_eps", &FlowState::turbulence_eps, &KEpsilonModel::cell_eps, kCells, 1, false, 0.0},
    {"cell_nut", &FlowState::turbulence_nut, &KEpsilonModel::cell_nut, kCells, 1, false, 0.0},
    {"cell_u_tau", &FlowState::turbulence_u_tau, &KEpsilonModel::cell_u_tau, kCells, 1, false, 0.0},
    {"face_x_wall_shear", &FlowState::turbulence_face_x_wall_shear, &KEpsilonModel::face_x_wall_shear, kFacesX, 1,
     false, 0.0},
    {"face_z_wall_shear", &FlowState::turbulence_face_z_wall_shear, &KEpsilonModel::face_z_wall_shear, kFacesZ, 1,
     false, 0.0},
};

std::size_t size_of(const Grid2D& g, int where) {
  return static_cast<std::size_t>(where == kCells ? g.ncell() : where == kFacesX ? g.nface_x() : g.nface_z());
}
}  // namespace

void VOFGrid::export_state(FlowState& s) const {
  for (const FlowField& f : kFlowFields) s.*f.state = this->*f.live;
  s.face_u_prev = face_u_prev;
  s.face_w_prev = face_w_prev;
  s.prev_dt = prev_dt_;
  s.time = time_;
  s.step_count = step_count_;
  s.last_dt = last_dt_;
  s.last_advective = last_advective_;
  s.inlet_volume = inlet_volume_;
  s.net_inflow_volume = net_inflow_volume_;
  s.dilatation_volume = dilatation_volume_;
  s.discharge = discharge_;
  const KEpsilonModel& t = *turbulence_;
  s.has_turbulence = s.has_roles = true;
  for (const TurbulenceField& f : kTurbulenceFields) s.*f.state = t.*f.live;
  t.cell_roles(s.turbulence_role);
}

void VOFGrid::check_state(const FlowState& s) const {
  for (const FlowField& f : kFlowFields) require_size(f.key, s.*f.state, size_of(grid_, f.where));
  require_non_negative("last_dt", s.last_dt);
  require_non_negative("last_advective", s.last_advective);
  require_non_negative("prev_dt", s.prev_dt);
  if (s.prev_dt > 0.0) {
    require_size("face_u_prev", s.face_u_prev, size_of(grid_, kFacesX));
    require_size("face_w_prev", s.face_w_prev, size_of(grid_, kFacesZ));
  }
  if (s.has_turbulence) {
    for (const TurbulenceField& f : kTurbulenceFields)
      require_size(("turbulence/" + std::string(f.key)).c_str(), s.*f.state, size_of(grid_, f.where));
    if (s.has_roles) {
      require_size("turbulence/cell_role", s.turbulence_role, size_of(grid_, kCells));
      for (double r : s.turbulence_role) require_in_closed("turbulence/cell_role", r, 0.0, 2.0);
    }
  }
  s.discharge.validate();
}

void VOFGrid::import_state(const FlowState& s) {
  check_state(s);
  viscous_limit_step_ = -1;
  discharge_ = s.discharge;
  for (const FlowField& f : kFlowFields) state::copy_into(this->*f.live, s.*f.state);
  time_ = s.time;
  step_count_ = s.step_count;
  last_dt_ = s.last_dt;
  last_advective_ = s.last_advective;
  advective_seen_ = {};
  // the step history of AB2 (none: the next step is forward Euler)
  if (s.prev_dt > 0.0) {
    face_u_prev = s.face_u_prev;
    face_w_prev = s.face_w_prev;
  }
  prev_dt_ = s.prev_dt;
  inlet_volume_ = s.inlet_volume;
  net_inflow_volume_ = s.net_inflow_volume;
  dilatation_volume_ = s.dilatation_volume;
  update_face_porosity();
  // states written before the k-epsilon model was part of them keep the model as it is
  if (!s.has_turbulence) return;
  KEpsilonModel& t = *turbulence_;
  for (const TurbulenceField& f : kTurbulenceFields) state::copy_into(t.*f.live, s.*f.state);
  // older states: the roles as they are (a cell filling in the next step may start differently)
  if (s.has_roles) t.set_cell_roles(s.turbulence_role);
}

// ---- the checkpoint: named flat arrays

void state::flow_to_map(FlowState& f, StateMap& s) {
  for (const FlowField& a : kFlowFields) s[std::string("fluid/") + a.key] = std::move(f.*a.state);
  s["fluid/time"] = {f.time};
  s["fluid/step_count"] = {static_cast<double>(f.step_count)};
  s["fluid/last_dt"] = {f.last_dt};
  s["fluid/last_advective"] = {f.last_advective};
  s["fluid/prev_dt"] = {f.prev_dt};
  s["fluid/face_u_prev"] = std::move(f.face_u_prev);
  s["fluid/face_w_prev"] = std::move(f.face_w_prev);
  s["fluid/inlet_volume"] = {f.inlet_volume};
  s["fluid/net_inflow_volume"] = {f.net_inflow_volume};
  s["fluid/dilatation_volume"] = {f.dilatation_volume};
  s["fluid/discharge_times"] = std::move(f.discharge.times);
  s["fluid/discharge_q"] = std::move(f.discharge.discharge);
  for (const TurbulenceField& a : kTurbulenceFields) s[std::string("turbulence/") + a.key] = std::move(f.*a.state);
  s["turbulence/cell_role"] = std::move(f.turbulence_role);  // which cells held water: a cell that fills starts from them
}

FlowState state::flow_from_map(const StateMap& s, const Grid2D& g) {
  using state::entry;
  FlowState f;
  for (const FlowField& a : kFlowFields) f.*a.state = entry(s, std::string("fluid/") + a.key, size_of(g, a.where));
  // optional scalars: older states have no last step (the next one starts from FlowParams::initial_dt),
  // no AB2 history (the next step is forward Euler), no boundary budget (it restarts from 0)
  auto scalar = [&s](const char* key, bool optional) {
    return optional && !s.count(key) ? 0.0 : entry(s, key, 1)[0];
  };
  f.time = scalar("fluid/time", false);
  f.step_count = static_cast<long long>(scalar("fluid/step_count", false));
  f.last_dt = scalar("fluid/last_dt", true);
  f.last_advective = scalar("fluid/last_advective", true);
  f.prev_dt = scalar("fluid/prev_dt", true);
  if (f.prev_dt > 0.0) {
    f.face_u_prev = entry(s, "fluid/face_u_prev", size_of(g, kFacesX));
    f.face_w_prev = entry(s, "fluid/face_w_prev", size_of(g, kFacesZ));
  }
  f.inlet_volume = scalar("fluid/inlet_volume", false);
  f.net_inflow_volume = scalar("fluid/net_inflow_volume", true);
  f.dilatation_volume = scalar("fluid/dilatation_volume", true);
  f.discharge.times = entry(s, "fluid/discharge_times", state::kAnySize);
  f.discharge.discharge = entry(s, "fluid/discharge_q", state::kAnySize);
  // states written before the k-epsilon model was part of the checkpoint keep the model as it is
  f.has_turbulence = s.count("turbulence/cell_k") > 0;
  if (f.has_turbulence) {
    for (const TurbulenceField& a : kTurbulenceFields)
      f.*a.state = entry(s, std::string("turbulence/") + a.key, size_of(g, a.where));
    f.has_roles = s.count("turbulence/cell_role") > 0;
    if (f.has_roles) f.turbulence_role = entry(s, "turbulence/cell_role", size_of(g, kCells));
  }
  return f;
}

}  // namespace vofdem
