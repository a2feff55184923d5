// The flow's whole state as one typed value (FlowState): export_state() copies it out, import_state()
// back in place, so a coupled run can be copied and branched (as MuJoCo's mj_copyData) and the
// coupler's guard snapshot costs array copies only. The coupler's checkpoint maps it to named arrays.
#include <algorithm>
#include <string>

#include "vofdem/check.h"
#include "vofdem/vof_grid.h"

namespace vofdem {

namespace {
void need_size(const char* name, const std::vector<double>& v, int n) {
  if (static_cast<int>(v.size()) != n)
    throw std::invalid_argument(std::string("state: '") + name + "' has " + std::to_string(v.size()) +
                                " values, expected " + std::to_string(n));
}

// same size: written in place, so the numpy views of dst stay valid
void copy_into(std::vector<double>& dst, const std::vector<double>& src) { std::copy(src.begin(), src.end(), dst.begin()); }
}  // namespace

void VOFGrid::export_state(FlowState& s) const {
  s.face_u = face_u;
  s.face_w = face_w;
  s.cell_p = cell_p;
  s.cell_F = cell_F;
  s.cell_porosity = cell_porosity;
  s.cell_stone_diameter = cell_stone_diameter;
  s.cell_nut = cell_nut;
  s.face_x_solid_u = face_x_solid_u;
  s.face_z_solid_w = face_z_solid_w;
  s.face_u_prev = face_u_prev;
  s.face_w_prev = face_w_prev;
  s.prev_dt = prev_dt_;
  s.time = time_;
  s.step_count = step_count_;
  s.last_dt = last_dt_;
  s.inlet_volume = inlet_volume_;
  s.net_inflow_volume = net_inflow_volume_;
  s.dilatation_volume = dilatation_volume_;
  s.discharge = discharge_;
  const KEpsilonModel& t = *turbulence_;
  s.has_turbulence = s.has_roles = true;
  s.turbulence_k = t.cell_k;
  s.turbulence_eps = t.cell_eps;
  s.turbulence_nut = t.cell_nut;
  s.turbulence_u_tau = t.cell_u_tau;
  s.turbulence_face_x_wall_shear = t.face_x_wall_shear;
  s.turbulence_face_z_wall_shear = t.face_z_wall_shear;
  t.cell_roles(s.turbulence_role);
}

void VOFGrid::check_state(const FlowState& s) const {
  const int nc = grid_.ncell(), nfx = grid_.nface_x(), nfz = grid_.nface_z();
  for (const auto& [name, v] : {std::pair<const char*, const std::vector<double>*>{"cell_p", &s.cell_p},
                                {"cell_F", &s.cell_F},
                                {"cell_porosity", &s.cell_porosity},
                                {"cell_stone_diameter", &s.cell_stone_diameter},
                                {"cell_nut", &s.cell_nut}})
    need_size(name, *v, nc);
  need_size("face_u", s.face_u, nfx);
  need_size("face_x_solid_u", s.face_x_solid_u, nfx);
  need_size("face_w", s.face_w, nfz);
  need_size("face_z_solid_w", s.face_z_solid_w, nfz);
  require_non_negative("last_dt", s.last_dt);
  require_non_negative("prev_dt", s.prev_dt);
  if (s.prev_dt > 0.0) need_size("face_u_prev", s.face_u_prev, nfx), need_size("face_w_prev", s.face_w_prev, nfz);
  if (s.has_turbulence) {
    need_size("turbulence/cell_k", s.turbulence_k, nc);
    need_size("turbulence/cell_eps", s.turbulence_eps, nc);
    need_size("turbulence/cell_nut", s.turbulence_nut, nc);
    need_size("turbulence/cell_u_tau", s.turbulence_u_tau, nc);
    need_size("turbulence/face_x_wall_shear", s.turbulence_face_x_wall_shear, nfx);
    need_size("turbulence/face_z_wall_shear", s.turbulence_face_z_wall_shear, nfz);
    if (s.has_roles) {
      need_size("turbulence/cell_role", s.turbulence_role, nc);
      for (double r : s.turbulence_role) require_in_closed("turbulence/cell_role", r, 0.0, 2.0);
    }
  }
  s.discharge.validate();
}

void VOFGrid::import_state(const FlowState& s) {
  check_state(s);
  viscous_limit_step_ = -1;
  discharge_ = s.discharge;
  copy_into(face_u, s.face_u);
  copy_into(face_w, s.face_w);
  copy_into(cell_p, s.cell_p);
  copy_into(cell_F, s.cell_F);
  copy_into(cell_porosity, s.cell_porosity);
  copy_into(cell_stone_diameter, s.cell_stone_diameter);
  copy_into(cell_nut, s.cell_nut);
  copy_into(face_x_solid_u, s.face_x_solid_u);
  copy_into(face_z_solid_w, s.face_z_solid_w);
  time_ = s.time;
  step_count_ = s.step_count;
  last_dt_ = s.last_dt;
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
  copy_into(t.cell_k, s.turbulence_k);
  copy_into(t.cell_eps, s.turbulence_eps);
  copy_into(t.cell_nut, s.turbulence_nut);
  copy_into(t.cell_u_tau, s.turbulence_u_tau);
  copy_into(t.face_x_wall_shear, s.turbulence_face_x_wall_shear);
  copy_into(t.face_z_wall_shear, s.turbulence_face_z_wall_shear);
  // older states: the roles as they are (a cell filling in the next step may start differently)
  if (s.has_roles) t.set_cell_roles(s.turbulence_role);
}

}  // namespace vofdem
