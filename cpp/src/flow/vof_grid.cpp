#include "vofdem/flow/vof_grid.h"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <sstream>
#include <stdexcept>
#include <string>

#include "common/parallel.h"
#include "vofdem/common/advance.h"
#include "vofdem/common/check.h"
#include "vofdem/flow/porous_stage.h"
#include "vofdem/flow/projection.h"

namespace vofdem {

namespace {
constexpr double kInf = std::numeric_limits<double>::infinity();
// a water fraction further than this outside [0, 1] is a failure, not round-off
constexpr double kFractionSlack = 1e-6;
}  // namespace

// ---------------------------------------------------------------------------------------------
// parameters

void FlowParams::validate() const {
  medium.validate();
  // the split advection is bounded, and so conserves the water, up to 0.5 (docs/vof_advection.md): a
  // dam break at 0.6 loses 8e-5 of its water, at 0.7-1.0 1e-3 to 3e-3
  if (!(cfl > 0.0 && cfl <= kMaxFlowCfl))
    throw std::invalid_argument("cfl = " + format_value(cfl) + " must lie in (0, 0.5]: above 0.5 the split VOF "
                                "advection is not bounded and loses water");
  require_positive("max_dt", max_dt);
  require_positive("min_dt", min_dt);
  require_positive("initial_dt", initial_dt);
  require_in_closed("max_dt_growth", max_dt_growth, 1.0, 10.0);
  require_positive("k1", k1);
  require_non_negative("k2", k2);
  require_positive("flume_width", flume_width);
  require_positive("pressure_tol", pressure_tol);
  if (!(viscous_substeps >= 1 && viscous_substeps <= 64))
    throw std::invalid_argument("viscous_substeps = " + std::to_string(viscous_substeps) +
                                " is outside the allowed range [1, 64]");
  require_finite("tailwater_level", tailwater_level);
  if (static_cast<int>(time_scheme) < 0 || static_cast<int>(time_scheme) > 1)
    throw std::invalid_argument("time_scheme = " + std::to_string(static_cast<int>(time_scheme)) +
                                " is outside the allowed values {0 (kEuler), 1 (kAdamsBashforth2)}");
  if (static_cast<int>(step_control) < 0 || static_cast<int>(step_control) > 1)
    throw std::invalid_argument("step_control = " + std::to_string(static_cast<int>(step_control)) +
                                " is outside the allowed values {0 (kThisStep), 1 (kTwoSteps)}");
  if (static_cast<int>(viscous_scheme) < 0 || static_cast<int>(viscous_scheme) > 3)
    throw std::invalid_argument("viscous_scheme = " + std::to_string(static_cast<int>(viscous_scheme)) +
                                " is outside the allowed values {0 (kExplicit), 1 (kImplicitVertical), "
                                "2 (kImplicitVerticalFromStart), 3 (kImplicit)}");
  // checked with the model off too: set_params rebuilds the model, which would refuse them half-way
  try {
    check_k_epsilon_params(turbulence);
  } catch (const std::invalid_argument& e) {
    throw std::invalid_argument(std::string("turbulence.") + e.what());
  }
  if (flags >= (1u << 8))
    throw std::invalid_argument("flags = " + std::to_string(flags) + " is outside the allowed range [0, 255]");
}

double FlowStableDt::min() const { return std::min({advective, viscous, gravity, turbulence, max_dt, growth}); }

const char* FlowStableDt::binding(int* cell) const {
  const double m = min();
  if (cell) *cell = -1;
  if (advective == m) {
    if (cell) *cell = advective_cell;
    return "advective";
  }
  if (turbulence == m) {
    if (cell) *cell = turbulence_cell;
    return "turbulence";
  }
  if (viscous == m) {
    if (cell) *cell = viscous_cell;
    return "viscous";
  }
  if (gravity == m) return "gravity";
  if (growth == m) return "growth";
  return "max_dt";
}

struct VOFGrid::Snapshot {
  std::vector<double> face_u, face_w, cell_p, cell_F, cell_nut, cell_k, cell_eps, cell_porosity_prev;
  double time = 0.0, inlet_volume = 0.0, net_inflow_volume = 0.0, dilatation_volume = 0.0;
};

// ---------------------------------------------------------------------------------------------
// construction, parameters, porosity and phase properties

VOFGrid::VOFGrid(const Grid2D& grid, const FlowParams& params)
    : grid_(grid), params_(params), snapshot_(std::make_unique<Snapshot>()) {
  params_.validate();
  const int nc = grid_.ncell(), nfx = grid_.nface_x(), nfz = grid_.nface_z();
  face_u.assign(nfx, 0.0);
  face_w.assign(nfz, 0.0);
  cell_p.assign(nc, 0.0);
  cell_F.assign(nc, 0.0);
  cell_porosity.assign(nc, 1.0);
  cell_porosity_prev_.assign(nc, 1.0);
  face_x_porosity.assign(nfx, 1.0);
  face_z_porosity.assign(nfz, 1.0);
  // no stone size of its own: the stones or the scene give it (a porous cell without one is refused)
  cell_stone_diameter.assign(nc, 0.0);
  cell_nut.assign(nc, 0.0);
  face_x_solid_u.assign(nfx, 0.0);
  face_z_solid_w.assign(nfz, 0.0);
  if (!(params_.flags & kFlowFreeSurface)) std::fill(cell_F.begin(), cell_F.end(), 1.0);
  cell_rho_.assign(nc, 0.0);
  cell_mu_.assign(nc, 0.0);
  cell_mu_eddy_.assign(nc, 0.0);
  cell_nu_.assign(nc, 0.0);
  face_x_rho_.assign(nfx, 0.0);
  face_z_rho_.assign(nfz, 0.0);
  face_x_diameter_.assign(nfx, 0.0);
  face_z_diameter_.assign(nfz, 0.0);
  face_x_beta_.assign(nfx, 0.0);
  face_z_beta_.assign(nfz, 0.0);
  u_star_.assign(nfx, 0.0);
  w_star_.assign(nfz, 0.0);
  rhs_.assign(nc, 0.0);
  cfl_row_.assign(nfx, 0.0);
  inlet_u_.assign(grid_.nz(), 0.0);
  for (int k = 0; k < grid_.nz(); ++k) inlet_dz_.push_back(grid_.dz(k));
  problem_.resize(grid_);
  vof_inflow_.resize(grid_, 0.0);
  solver_ = make_pressure_solver(params_.pressure_solver);
  discharge_ = DischargeTable::constant(0.0);
  update_face_porosity();
  make_turbulence_model();
  st_advect_ = profile_.add_stage("advect_vof");
  st_momentum_ = profile_.add_stage("momentum");
  st_porous_ = profile_.add_stage("porous_resistance");
  st_turbulence_ = profile_.add_stage("turbulence");
  st_pressure_ = profile_.add_stage("pressure");
  st_correct_ = profile_.add_stage("correct");
  st_checks_ = profile_.add_stage("checks");
}

VOFGrid::~VOFGrid() = default;

void VOFGrid::make_turbulence_model() {
  KEpsilonBoundaries b;
  b.left = params_.inlet == InletBoundary::kDischarge ? KEpsilonBoundary::kInflow : KEpsilonBoundary::kWall;
  b.right = params_.outlet == OutletBoundary::kWall ? KEpsilonBoundary::kWall : KEpsilonBoundary::kZeroGradient;
  b.bottom = KEpsilonBoundary::kWall;
  // the open top and the slip lid are both free of shear
  b.top = KEpsilonBoundary::kZeroGradient;
  KEpsilonModel model(grid_, params_.turbulence, b);
  if (!turbulence_) {
    turbulence_ = std::make_unique<KEpsilonModel>(std::move(model));
    return;
  }
  // a fresh model that keeps k, eps, nu_t and the time, moved into the old object with the old arrays:
  // the numpy views of cell_k and cell_eps stay valid (views.h)
  model.cell_k.swap(turbulence_->cell_k);
  model.cell_eps.swap(turbulence_->cell_eps);
  model.cell_nut.swap(turbulence_->cell_nut);
  model.time = turbulence_->time;
  *turbulence_ = std::move(model);
}

void VOFGrid::set_params(const FlowParams& params) {
  params.validate();
  const bool new_solver = params.pressure_solver != params_.pressure_solver;
  params_ = params;
  viscous_limit_step_ = -1;
  if (new_solver) solver_ = make_pressure_solver(params_.pressure_solver);
  make_turbulence_model();
  update_face_porosity();
  if (!(params_.flags & kFlowFreeSurface)) std::fill(cell_F.begin(), cell_F.end(), 1.0);
}

void VOFGrid::set_discharge(const DischargeTable& table) {
  table.validate();
  discharge_ = table;
}

void VOFGrid::check_sizes() const {
  auto need = [](const char* name, const std::vector<double>& a, int n) {
    if (static_cast<int>(a.size()) != n)
      throw std::invalid_argument(std::string(name) + " has " + std::to_string(a.size()) + " values, expected " +
                                  std::to_string(n));
  };
  need("cell_porosity", cell_porosity, grid_.ncell());
  need("cell_stone_diameter", cell_stone_diameter, grid_.ncell());
}

void VOFGrid::set_porosity(const std::vector<double>& porosity, bool displace) {
  if (static_cast<int>(porosity.size()) != grid_.ncell())
    throw std::invalid_argument("porosity has " + std::to_string(porosity.size()) + " values, expected ncell = " +
                                std::to_string(grid_.ncell()));
  for (double n : porosity) require_in_closed("porosity", n, 0.0, 1.0);
  cell_porosity = porosity;
  update_face_porosity(displace);
}

namespace {

// a porous cell's stone diameter is not the core's to assume (the paper's 4.8 cm is a scene's value)
std::string missing_diameter(int c, double n, double d) {
  return "cell_stone_diameter[" + std::to_string(c) + "] = " + std::to_string(d) + " m at porosity " +
         std::to_string(n) + " must be a finite value > 0 m: the stone diameter D of eq. (7) is given by the " +
         "scene (stones.diameter), set_porosity_box's d, or a Coupler mapping the stones";
}

// count faces of a row between cells na[i] and nb[i]: as open as the tighter one, with its stone
// diameter (the mean of both when they are as open); a closed face carries no velocity. Selects without
// a branch; the rows never overlap the face arrays (restrict: GCC would version the loop for 12 pairs)
void face_porosity_row(int count, const double* __restrict na, const double* __restrict nb,
                       const double* __restrict da, const double* __restrict db, double* __restrict fn,
                       double* __restrict fd, double* __restrict vel) {
  for (int i = 0; i < count; ++i) {
    const double a = na[i], b = nb[i], x = da[i], y = db[i], v = vel[i];
    const double open = b < a ? b : a;
    fn[i] = open;
    fd[i] = a < b ? x : b < a ? y : 0.5 * (x + y);
    vel[i] = open == 0.0 ? 0.0 : v;
  }
}

}  // namespace

void VOFGrid::update_face_porosity(bool displace) {
  check_sizes();
  if (!displace) cell_porosity_prev_ = cell_porosity;
  const int nx = grid_.nx(), nz = grid_.nz(), sx = nx + 1;
  const double* n = cell_porosity.data();
  const double* d = cell_stone_diameter.data();
  // the checks' calls (which build the message) only for a value that fails, searched again in order
  auto fails = [&](long long c) {
    return !(n[c] >= 0.0 && n[c] <= 1.0) ||
           (n[c] > 0.0 && n[c] < 1.0 && !(d[c] > 0.0 && d[c] <= std::numeric_limits<double>::max()));
  };
  std::atomic<bool> bad{false};
  detail::parallel_range(grid_.ncell(), [&](long long c0, long long c1) {
    bool any = false;
    for (long long c = c0; c < c1; ++c) any |= fails(c);
    if (any) bad.store(true, std::memory_order_relaxed);
  });
  for (int c = 0; bad.load() && c < grid_.ncell(); ++c) {
    if (!(n[c] >= 0.0 && n[c] <= 1.0)) require_in_closed("cell_porosity", n[c], 0.0, 1.0);
    if (n[c] > 0.0 && n[c] < 1.0 && !(d[c] > 0.0 && d[c] <= std::numeric_limits<double>::max()))
      throw std::invalid_argument(missing_diameter(c, n[c], d[c]));
  }
  // a boundary face has its one cell on both sides
  detail::parallel_for(nz, sx, [&](int k0, int k1) {
    for (int k = k0; k < k1; ++k) {
      const double* nr = n + nx * k;
      const double* dr = d + nx * k;
      double* fn = face_x_porosity.data() + sx * k;
      double* fd = face_x_diameter_.data() + sx * k;
      double* u = face_u.data() + sx * k;
      const int e = nx - 1;
      face_porosity_row(1, nr, nr, dr, dr, fn, fd, u);
      face_porosity_row(nx - 1, nr, nr + 1, dr, dr + 1, fn + 1, fd + 1, u + 1);
      face_porosity_row(1, nr + e, nr + e, dr + e, dr + e, fn + nx, fd + nx, u + nx);
      // walls are closed; the inlet and an open end stay open as far as their cell is
      if (params_.inlet != InletBoundary::kDischarge) fn[0] = 0.0, u[0] = 0.0;
      if (params_.outlet == OutletBoundary::kWall) fn[nx] = 0.0, u[nx] = 0.0;
    }
  });
  detail::parallel_for(nz + 1, nx, [&](int k0, int k1) {
    for (int k = k0; k < k1; ++k) {
      const int below = nx * std::max(k - 1, 0), above = nx * std::min(k, nz - 1);
      double* fn = face_z_porosity.data() + nx * k;
      double* w = face_w.data() + nx * k;
      face_porosity_row(nx, n + below, n + above, d + below, d + above, fn, face_z_diameter_.data() + nx * k, w);
      if (k == 0 || (k == nz && params_.top == TopBoundary::kWall))
        for (int i = 0; i < nx; ++i) fn[i] = 0.0, w[i] = 0.0;
    }
  });
}

void VOFGrid::update_phase_properties() const {
  const bool two_phase = params_.flags & kFlowFreeSurface;
  const double rw = params_.medium.rho_water, ra = params_.medium.rho_air;
  const double mw = rw * params_.medium.nu_water, ma = ra * params_.medium.nu_air;
  const bool turb = params_.flags & kFlowTurbulence;
  detail::parallel_range(grid_.ncell(), [&, rw, ra, mw, ma](long long c0, long long c1) {
    for (long long c = c0; c < c1; ++c) {
      const double f = two_phase ? std::clamp(cell_F[c], 0.0, 1.0) : 1.0;
      cell_rho_[c] = f * rw + (1.0 - f) * ra;
      const double mu = f * mw + (1.0 - f) * ma;
      cell_nu_[c] = mu / cell_rho_[c];
      cell_mu_eddy_[c] = turb ? cell_rho_[c] * cell_nut[c] : 0.0;
      cell_mu_[c] = mu + cell_mu_eddy_[c];
    }
  });
  const int nx = grid_.nx(), nz = grid_.nz(), sx = nx + 1;
  // the faces' mean of the two cells (a boundary face's cell twice), row by row (vectorised)
  detail::parallel_for(nz, sx, [&](int k0, int k1) {
    for (int k = k0; k < k1; ++k) {
      const double* r = cell_rho_.data() + nx * k;
      double* f = face_x_rho_.data() + sx * k;
      f[0] = 0.5 * (r[0] + r[0]);
      for (int i = 1; i < nx; ++i) f[i] = 0.5 * (r[i - 1] + r[i]);
      f[nx] = 0.5 * (r[nx - 1] + r[nx - 1]);
    }
  });
  // an open end faces still fluid outside: water below the tailwater level, air above (two-phase)
  if (two_phase && params_.outlet != OutletBoundary::kWall)
    for (int k = 0; k < nz; ++k) {
      const double f = params_.outlet == OutletBoundary::kTailwater
                           ? std::clamp((params_.tailwater_level - grid_.z_face(k)) / grid_.dz(k), 0.0, 1.0)
                           : 0.0;
      face_x_rho_[grid_.face_x(nx, k)] = 0.5 * (cell_rho_[grid_.cell(nx - 1, k)] + f * rw + (1.0 - f) * ra);
    }
  detail::parallel_for(nz + 1, nx, [&](int k0, int k1) {
    for (int k = k0; k < k1; ++k) {
      const double* r0 = cell_rho_.data() + nx * std::max(k - 1, 0);
      const double* r1 = cell_rho_.data() + nx * std::min(k, nz - 1);
      double* f = face_z_rho_.data() + nx * k;
      for (int i = 0; i < nx; ++i) f[i] = 0.5 * (r0[i] + r1[i]);
    }
  });
}

// ---------------------------------------------------------------------------------------------
// time step

MomentumFields VOFGrid::momentum_fields() const {
  MomentumFields f{face_u.data(),  face_w.data(),      face_x_porosity.data(), face_z_porosity.data(),
                   cell_mu_.data(), face_x_rho_.data(), face_z_rho_.data()};
  f.cell_rho = cell_rho_.data();
  if (params_.corner_viscosity == CornerViscosity::kHarmonic) f.cell_mu_eddy = cell_mu_eddy_.data();
  if ((params_.flags & kFlowTurbulence) && (params_.turbulence.flags & kKEpsWallFunctions)) {
    f.face_z_wall_shear = turbulence_->face_z_wall_shear.data();
    f.face_x_wall_shear = turbulence_->face_x_wall_shear.data();
  }
  return f;
}

MomentumBoundary VOFGrid::momentum_boundary() const {
  MomentumBoundary bc;
  bc.left_inlet = params_.inlet == InletBoundary::kDischarge;
  bc.right_open = params_.outlet != OutletBoundary::kWall;
  bc.top_open = params_.top == TopBoundary::kOpen;
  bc.no_slip = params_.walls == WallCondition::kNoSlip;
  return bc;
}

double VOFGrid::max_cfl(double dt, int& kind, int& index) const {
  const int nx = grid_.nx(), nz = grid_.nz(), sx = nx + 1;
  double worst = 0.0;
  kind = 0;
  index = -1;
  // each row's Courant numbers first (a division per face, vectorised; closed faces 0), then the row's
  // largest, and where it beats the largest so far its first face (the rows on the threads, taken in
  // order). Water leaving through an open boundary face counts half: the VOF sweep stays bounded up to
  // 2 cfl on outflow faces (vof_advection.h) and the face's own momentum outflow is implicit
  // (momentum.h); its limit would otherwise be a numerical one, the fast bed row at a free overfall's brink.
  const bool right_open = params_.outlet != OutletBoundary::kWall;
  // the rows of one kind, `width` faces each, on the threads, then taken in order
  auto take_rows = [&](int rows, int width, int row_kind, auto fill) {
    cfl_row_.resize(std::max(cfl_row_.size(), detail::row_maxima_size(rows, width)));
    detail::row_maxima(rows, width, cfl_row_.data(), fill);
    for (int k = 0; k < rows; ++k)
      if (cfl_row_[k] > worst)
        worst = cfl_row_[k], kind = row_kind, index = width * k + static_cast<int>(cfl_row_[rows + k]);
  };
  take_rows(nz, sx, 1, [&, dt](int k, double* row) {
    const double inv_h = dt / grid_.dx();
    const double* u = face_u.data() + sx * k;
    const double* n = face_x_porosity.data() + sx * k;
    for (int i = 0; i <= nx; ++i) {
      const double c = std::abs(u[i]) / n[i] * inv_h;
      row[i] = n[i] > 0.0 ? c : 0.0;
    }
    if (right_open && u[nx] > 0.0) row[nx] *= 0.5;
    return sx;
  });
  take_rows(nz + 1, nx, 2, [&, dt](int k, double* row) {
    const double h = std::min(grid_.dz(std::max(k - 1, 0)), grid_.dz(std::min(k, nz - 1)));
    const double* w = face_w.data() + nx * k;
    const double* n = face_z_porosity.data() + nx * k;
    for (int i = 0; i < nx; ++i) {
      const double c = std::abs(w[i]) / n[i] * dt / h;
      row[i] = n[i] > 0.0 ? c : 0.0;
    }
    return nx;
  });
  return worst;
}

FlowStableDt VOFGrid::stable_dt_terms() const {
  FlowStableDt s;
  int kind, index;
  const StepEndCourant& e = step_end_courant_;
  const bool reuse = reuse_step_end_courant_ && e.step == step_count_;
  double rate = reuse ? e.rate : max_cfl(1.0, kind, index);
  if (reuse) kind = e.kind, index = e.index;
  // the inlet flow the step will carry (q / dz of the lowest row when the inlet is dry)
  if (params_.inlet == InletBoundary::kDischarge) {
    std::vector<double>& u_in = inlet_u_;
    inlet_velocities(discharge_.at(time_) / params_.flume_width, inlet_dz_, cell_F.data(), cell_porosity.data(),
                     grid_.nx(), params_.inlet_profile, u_in);
    for (int k = 0; k < grid_.nz(); ++k) {
      const double n = face_x_porosity[grid_.face_x(0, k)];
      if (n > 0.0) rate = std::max(rate, std::abs(u_in[k]) / (n * grid_.dx()));
    }
  }
  s.advective = rate > 0.0 ? params_.cfl / rate : kInf;
  advective_seen_ = {step_count_, s.advective};
  // a limit that flickers from one step to the next: its low points, not its high ones
  if (params_.step_control == StepControl::kTwoSteps && last_advective_ > 0.0)
    s.advective = std::min(s.advective, last_advective_);
  // the cell beside the binding face (inside the grid at a boundary face)
  if (index >= 0) {
    const int nx = grid_.nx();
    s.advective_cell = kind == 1 ? grid_.face_x_cells(index % (nx + 1), index / (nx + 1)).b
                                 : grid_.face_z_cells(index % nx, index / nx).b;
  }
  s.viscous = kInf;
  // the viscosities of the current phases (stable_dt may be called between steps): once for both terms
  if (params_.flags & (kFlowViscosity | kFlowTurbulence)) update_phase_properties();
  if ((params_.flags & kFlowViscosity) && params_.viscous_scheme == ViscousScheme::kImplicit) {
    viscous_limit_ = kInf;  // no stress is explicit but the cross terms: no bound (vof_grid.h)
    viscous_limit_step_ = step_count_;
  } else if (params_.flags & kFlowViscosity) {
    viscous_limit_ = viscous_stable_dt(grid_, momentum_fields(), dt_scratch_,
                                       params_.implicit_vertical(), params_.step_bound(), &s.viscous_cell);
    viscous_limit_step_ = step_count_;
    s.viscous = params_.viscous_substeps * viscous_limit_;
  }
  const double g = std::hypot(params_.medium.gravity[0], params_.medium.gravity[1]);
  s.gravity = (params_.flags & kFlowGravity) && g > 0.0
                  ? params_.cfl * std::sqrt(2.0 * std::min(grid_.dx(), grid_.min_dz()) / g)
                  : kInf;
  s.turbulence = kInf;
  if (params_.flags & kFlowTurbulence) {
    s.turbulence =
        turbulence_->stable_dt(face_u, face_w, cell_porosity, turbulence_cells_F(), cell_nu_, &s.turbulence_cell);
  }
  s.max_dt = params_.max_dt;
  // from rest the velocity terms see no flow yet: the step starts small and grows gradually
  // (the velocities gravity and pressure create within one step would breach the CFL otherwise)
  s.growth = last_dt_ > 0.0 ? params_.max_dt_growth * last_dt_ : params_.initial_dt;
  return s;
}

void VOFGrid::save_state() {
  Snapshot& s = *snapshot_;
  s.face_u = face_u;
  s.face_w = face_w;
  s.time = time_;
  s.inlet_volume = inlet_volume_;
  s.net_inflow_volume = net_inflow_volume_;
  s.dilatation_volume = dilatation_volume_;
  if (guarded_) return;
  s.cell_p = cell_p;
  s.cell_F = cell_F;
  s.cell_nut = cell_nut;
  s.cell_k = turbulence_->cell_k;
  s.cell_eps = turbulence_->cell_eps;
  s.cell_porosity_prev = cell_porosity_prev_;
}

void VOFGrid::restore_state() {
  Snapshot& s = *snapshot_;
  turbulence_->time = s.time;
  time_ = s.time;
  inlet_volume_ = s.inlet_volume;
  net_inflow_volume_ = s.net_inflow_volume;
  dilatation_volume_ = s.dilatation_volume;
  flux_dt_ = 0.0;  // the fluxes in the scratch are not those of a completed step
  if (guarded_) return;  // the caller restores the fields
  face_u = s.face_u;
  face_w = s.face_w;
  cell_p = s.cell_p;
  cell_F = s.cell_F;
  cell_nut = s.cell_nut;
  turbulence_->cell_k = s.cell_k;
  turbulence_->cell_eps = s.cell_eps;
  turbulence_->cell_nut = s.cell_nut;
  cell_porosity_prev_ = s.cell_porosity_prev;
}

void VOFGrid::fail(const std::string& stage, const std::string& what, int kind, int index, double courant) {
  restore_state();
  const int nx = grid_.nx();
  int i = 0, k = 0;
  double x = 0, z = 0;
  const char* where = "cell";
  if (kind == 0) {
    i = index % nx, k = index / nx;
    x = grid_.x_center(i), z = grid_.z_center(k);
  } else if (kind == 1) {
    i = index % (nx + 1), k = index / (nx + 1);
    x = grid_.x_face(i), z = grid_.z_center(k);
    where = "x-face";
  } else {
    i = index % nx, k = index / nx;
    x = grid_.x_center(i), z = grid_.z_face(k);
    where = "z-face";
  }
  std::ostringstream os;
  os << "VOFGrid stage '" << stage << "': " << what;
  if (index >= 0)
    os << " at " << where << " (i=" << i << ", k=" << k << ", x=" << format_value(x) << " m, z=" << format_value(z)
       << " m)";
  os << ", t = " << format_value(time_) << " s (step " << step_count_ << "); state restored to t = "
     << format_value(time_) << " s";
  if (courant > 0.0) throw CflBreach(os.str(), courant);
  throw std::runtime_error(os.str());
}

void VOFGrid::check_finite(const char* stage, const char* name, const std::vector<double>& a, int kind) {
  // x - x is +0 (all bits clear) for a finite x and NaN otherwise: one vectorised pass of subtractions
  // and ORs of their bits (pieces on the threads; an OR in any order), searched only on failure
  std::atomic<std::uint64_t> all_bits{0};
  detail::parallel_range(a.size(), [&](long long j0, long long j1) {
    std::uint64_t bits = 0;
    for (long long j = j0; j < j1; ++j) {
      const double d = a[j] - a[j];
      std::uint64_t b;
      std::memcpy(&b, &d, sizeof b);
      bits |= b;
    }
    all_bits.fetch_or(bits, std::memory_order_relaxed);
  });
  if (all_bits.load() == 0) return;
  for (size_t j = 0; j < a.size(); ++j)
    if (!std::isfinite(a[j])) fail(stage, std::string("non-finite ") + name + " (" + format_value(a[j]) + ")", kind,
                                   static_cast<int>(j));
}

void VOFGrid::apply_inlet(double t, std::vector<double>& u) {
  if (params_.inlet != InletBoundary::kDischarge) return;
  const double q = discharge_.at(t) / params_.flume_width;
  inlet_velocities(q, inlet_dz_, cell_F.data(), cell_porosity.data(), grid_.nx(), params_.inlet_profile,
                   inlet_u_);
  for (int k = 0; k < grid_.nz(); ++k) u[grid_.face_x(0, k)] = inlet_u_[k];
}

void VOFGrid::stage_advect_vof(double dt) {
  ScopedStage timer(profile_, st_advect_);
  // the inlet fills with water; an open end lets in water below the tailwater level, air above
  const int nz = grid_.nz();
  if (params_.inlet == InletBoundary::kDischarge)
    for (int k = 0; k < nz; ++k) vof_inflow_.left[k] = 1.0;
  for (int k = 0; k < nz; ++k)
    vof_inflow_.right[k] = params_.outlet == OutletBoundary::kTailwater && grid_.z_center(k) < params_.tailwater_level;
  if (params_.inlet == InletBoundary::kDischarge)
    for (int k = 0; k < nz; ++k) inlet_volume_ += std::max(face_u[grid_.face_x(0, k)], 0.0) * grid_.dz(k) * dt;
  // the grid reads the clipping report of this step alone: a clipped step is taken again
  vof_scratch_.clip_count = 0;
  vof_scratch_.clip_max = 0.0;
  try {
    advect_vof(grid_, cell_porosity, face_u, face_w, vof_inflow_, dt, step_count_ % 2 == 0, cell_F, vof_scratch_);
  } catch (const CflBreach& e) {
    fail("advect_vof", e.what(), 0, -1, e.courant());
  } catch (const std::runtime_error& e) {
    fail("advect_vof", e.what(), 0, -1);
  }
  // F beyond [0, 1] by more than round-off: the split advection was not bounded in this step (its second
  // sweep's correction is frozen at the step's start, and an iterative pressure solve leaves a residual
  // divergence), and the clipping would make or lose water that no budget counts. The step is taken
  // again, half as long, as a CFL breach is (step_retry.h: the breach's Courant number 2 cfl)
  if (vof_scratch_.clip_count != 0)
    fail("advect_vof",
         "the water fraction left [0, 1] by " + format_value(vof_scratch_.clip_max) + " in " +
             std::to_string(vof_scratch_.clip_count) + " cell update(s) (the split advection is not bounded "
             "at this step; clipping would make or lose water)",
         0, -1, 2.0 * params_.cfl);
  check_finite("advect_vof", "water fraction", cell_F, 0);
  // the water budget: what the two sweeps carried through the boundary faces (left, right, bed, top)
  const int nx = grid_.nx();
  const std::vector<double>& fx = vof_scratch_.face_flux_x;
  const std::vector<double>& fz = vof_scratch_.face_flux_z;
  double net = 0.0;
  for (int k = 0; k < nz; ++k) net += fx[grid_.face_x(0, k)] - fx[grid_.face_x(nx, k)];
  for (int i = 0; i < nx; ++i) net += fz[grid_.face_z(i, 0)] - fz[grid_.face_z(i, nz)];
  net_inflow_volume_ += net;
  dilatation_volume_ += dilatation(dt);
  flux_dt_ = dt;
}

// water made by the two sweeps' divergence correction, dt sum c div(u) V (zero for div u = 0): the
// rest of the budget, where the pressure solve leaves a residual divergence
double VOFGrid::dilatation(double dt) const {
  const int nx = grid_.nx(), nz = grid_.nz(), sx = nx + 1;
  const double dx = grid_.dx();
  const double* c = vof_scratch_.cell_c.data();
  double sum = 0.0;
  for (int k = 0; k < nz; ++k) {
    const double dz = grid_.dz(k);
    const double* u = &face_u[sx * k];
    const double* wb = &face_w[nx * k];
    const double* wt = &face_w[nx * (k + 1)];
    const double* n = &cell_porosity[nx * k];
    for (int i = 0; i < nx; ++i)
      if (c[nx * k + i] != 0.0 && n[i] > 0.0) sum += (u[i + 1] - u[i]) * dz + (wt[i] - wb[i]) * dx;
  }
  return sum * dt;
}

int VOFGrid::viscous_substeps(double dt) const {
  // the limit stable_dt_terms() found before this step (the phases it saw are this step's), else anew
  if (params_.viscous_scheme == ViscousScheme::kImplicit) return 1;
  if (viscous_limit_step_ != step_count_) {
    viscous_limit_ = viscous_stable_dt(grid_, momentum_fields(), dt_scratch_,
                                       params_.implicit_vertical(), params_.step_bound(), nullptr);
    viscous_limit_step_ = step_count_;
  }
  if (!(dt > viscous_limit_)) return 1;
  return static_cast<int>(std::min<double>(params_.viscous_substeps, std::ceil(dt / viscous_limit_)));
}

void VOFGrid::stage_momentum(double dt) {
  ScopedStage timer(profile_, st_momentum_);
  MomentumTerms terms;
  terms.convection = params_.flags & kFlowConvection;
  terms.viscosity = params_.flags & kFlowViscosity;
  terms.implicit_vertical = params_.implicit_vertical();
  terms.vertical_from_start = params_.viscous_scheme == ViscousScheme::kImplicitVerticalFromStart;
  terms.implicit_horizontal = params_.viscous_scheme == ViscousScheme::kImplicit;
  if (params_.flags & kFlowGravity) terms.gravity_x = params_.medium.gravity[0], terms.gravity_z = params_.medium.gravity[1];
  if (terms.viscosity && params_.viscous_substeps > 1) terms.viscous_substeps = viscous_substeps(dt);
  const bool ab2 = params_.time_scheme == MomentumTimeScheme::kAdamsBashforth2 && prev_dt_ > 0.0;
  if (!ab2) {
    momentum_explicit(grid_, momentum_fields(), terms, momentum_boundary(), dt, u_star_, w_star_, momentum_scratch_);
  } else {
    // convection at the velocity extrapolated to the step's middle
    const double r = 0.5 * dt / prev_dt_;
    const std::size_t nu = face_u.size(), nw = face_w.size();
    face_u_ext_.resize(nu), face_w_ext_.resize(nw);
    detail::parallel_range(nu, [&, r](long long j0, long long j1) {
      for (long long j = j0; j < j1; ++j) face_u_ext_[j] = face_u[j] + r * (face_u[j] - face_u_prev[j]);
    });
    detail::parallel_range(nw, [&, r](long long j0, long long j1) {
      for (long long j = j0; j < j1; ++j) face_w_ext_[j] = face_w[j] + r * (face_w[j] - face_w_prev[j]);
    });
    MomentumFields f = momentum_fields();
    f.conv_face_u = face_u_ext_.data(), f.conv_face_w = face_w_ext_.data();
    momentum_explicit(grid_, f, terms, momentum_boundary(), dt, u_star_, w_star_, momentum_scratch_);
  }
  // projection coefficients without resistance; the porous stage divides them by 1 + dt n R'
  detail::parallel_range(face_x_beta_.size(), [&, dt](long long j0, long long j1) {
    for (long long j = j0; j < j1; ++j) face_x_beta_[j] = dt * face_x_porosity[j] / face_x_rho_[j];
  });
  detail::parallel_range(face_z_beta_.size(), [&, dt](long long j0, long long j1) {
    for (long long j = j0; j < j1; ++j) face_z_beta_[j] = dt * face_z_porosity[j] / face_z_rho_[j];
  });
  check_finite("momentum", "x-velocity", u_star_, 1);
  check_finite("momentum", "z-velocity", w_star_, 2);
}

void VOFGrid::stage_porous_resistance(double dt) {
  ScopedStage timer(profile_, st_porous_);
  const PorousStageFields f{face_u.data(),           face_w.data(),           face_x_porosity.data(),
                            face_z_porosity.data(),  face_x_diameter_.data(), face_z_diameter_.data(),
                            face_x_rho_.data(),      face_z_rho_.data(),      cell_rho_.data(),
                            cell_nu_.data(),         face_x_solid_u.data(),   face_z_solid_w.data()};
  PorousStageTerms t;
  t.linear = params_.flags & kFlowPorousDarcy;
  t.quadratic = params_.flags & kFlowPorousForchheimer;
  t.relative = params_.flags & kFlowRelativeVelocity;
  t.k1 = params_.k1, t.k2 = params_.k2;
  porous_resistance_stage(grid_, f, t, dt, u_star_, w_star_, face_x_beta_, face_z_beta_);
  check_finite("porous_resistance", "x-velocity", u_star_, 1);
  check_finite("porous_resistance", "z-velocity", w_star_, 2);
}

const std::vector<double>& VOFGrid::turbulence_cells_F() const {
  static const std::vector<double> all_water;
  return (params_.flags & kFlowFreeSurface) ? cell_F : all_water;
}

void VOFGrid::stage_turbulence(double dt) {
  ScopedStage timer(profile_, st_turbulence_);
  // k and eps advance with the velocities of the step's start; nu_t enters the next momentum stage
  try {
    turbulence_->time = time_;
    turbulence_->step(dt, face_u, face_w, cell_porosity, turbulence_cells_F(), cell_nu_);
  } catch (const std::runtime_error& e) {
    fail("turbulence", e.what(), 0, -1);
  }
  cell_nut = turbulence_->cell_nut;
  check_finite("turbulence", "eddy viscosity", cell_nut, 0);
}

ProjectionFields VOFGrid::projection_fields() const {
  return {face_x_porosity.data(), face_z_porosity.data(), face_x_beta_.data(), face_z_beta_.data(),
          face_u.data(),          face_x_rho_.data(),     u_star_.data(),      w_star_.data(),
          cell_porosity.data(),   cell_porosity_prev_.data(), face_w.data(),       face_z_rho_.data()};
}

ProjectionBoundary VOFGrid::projection_boundary() const {
  ProjectionBoundary bc;
  bc.right_open = params_.outlet != OutletBoundary::kWall;
  bc.tailwater = params_.outlet == OutletBoundary::kTailwater;
  bc.tailwater_level = params_.tailwater_level;
  bc.two_phase = params_.flags & kFlowFreeSurface;
  bc.rho_water = params_.medium.rho_water;
  bc.rho_air = params_.medium.rho_air;
  bc.gravity = (params_.flags & kFlowGravity) ? std::abs(params_.medium.gravity[1]) : 0.0;
  return bc;
}

void VOFGrid::stage_pressure(double dt) {
  ScopedStage timer(profile_, st_pressure_);
  assemble_pressure_problem(grid_, projection_fields(), projection_boundary(), dt, problem_, rhs_);
  try {
    solver_->setup(grid_, problem_);
    pressure_stats_ = solver_->solve(rhs_, cell_p, params_.pressure_tol);
  } catch (const std::runtime_error& e) {
    if (solver_->kind() != PressureSolverKind::kMultigridCG) fail("pressure", e.what(), 0, -1);
    solve_pressure_directly(e.what());
  }
  pressure_iterations_ += pressure_stats_.iterations;
  check_finite("pressure", "pressure", cell_p, 0);
}

// a multigrid-CG solve that failed (p left as it was) is redone by the direct solver: exact to round-off
// whatever the coefficients, at the cost of a factorisation
void VOFGrid::solve_pressure_directly(const std::string& why) {
  if (!fallback_solver_) fallback_solver_ = make_pressure_solver(PressureSolverKind::kEigenDirect);
  try {
    fallback_solver_->setup(grid_, problem_);
    const int iterations = PressureSolverParams().max_iterations;
    pressure_stats_ = fallback_solver_->solve(rhs_, cell_p, params_.pressure_tol);
    pressure_stats_.iterations = iterations;
  } catch (const std::runtime_error& e) {
    fail("pressure", why + "; the direct solver failed too: " + e.what(), 0, -1);
  }
  ++pressure_fallbacks_;
}

void VOFGrid::stage_correct() {
  ScopedStage timer(profile_, st_correct_);
  correct_velocities(grid_, projection_fields(), problem_, cell_p, face_u, face_w);
  check_finite("correct", "x-velocity", face_u, 1);
  check_finite("correct", "z-velocity", face_w, 2);
}

void VOFGrid::stage_checks(double dt) {
  ScopedStage timer(profile_, st_checks_);
  // every cell on the threads; a failure is named by the first failing cell, searched again
  auto outside = [&](long long c) { return cell_F[c] < -kFractionSlack || cell_F[c] > 1.0 + kFractionSlack; };
  std::atomic<bool> bad{false};
  detail::parallel_range(grid_.ncell(), [&](long long c0, long long c1) {
    bool any = false;
    for (long long c = c0; c < c1; ++c) any |= outside(c);
    if (any) bad.store(true, std::memory_order_relaxed);
  });
  if (bad.load())
    for (int c = 0; c < grid_.ncell(); ++c)
      if (outside(c)) fail("checks", "water fraction out of [0, 1] (" + format_value(cell_F[c]) + ")", 0, c);
  // the rate per face (the next step's advective limit, kept), times dt: within a few round-offs of the
  // check's own dt / h per face, so that a Courant number near 1 is checked exactly
  int kind, index;
  const double rate = max_cfl(1.0, kind, index);
  if (!(rate * dt <= 1.0 - 1e-9)) check_cfl("checks", dt);
  step_end_courant_ = {step_count_ + 1, rate, kind, index};
}

void VOFGrid::reuse_step_end_courant(bool on) {
  reuse_step_end_courant_ = on;
  step_end_courant_.step = -1;
}

void VOFGrid::check_cfl(const char* stage, double dt) {
  int kind, index;
  const double cfl = max_cfl(dt, kind, index);
  if (!(cfl > 1.0)) return;
  // before the step: the step asked for is too long; after it: the velocities it made are too fast
  const std::string what = std::string(stage) == "step"
                               ? "dt = " + format_value(dt) + " s gives a Courant number " + format_value(cfl) +
                                     " (pore velocity)"
                               : "the new velocity crosses " + format_value(cfl) + " cells in dt = " +
                                     format_value(dt) + " s";
  fail(stage, "CFL breach: " + what, kind, index, cfl);
}

void VOFGrid::step(double dt) {
  require_positive("dt", dt);
  save_state();
  // a state written through the views (or left by a caller) is checked before it spreads
  check_finite("step", "x-velocity", face_u, 1);
  check_finite("step", "z-velocity", face_w, 2);
  check_finite("step", "water fraction", cell_F, 0);
  check_cfl("step", dt);
  update_phase_properties();
  stage_momentum(dt);
  if (params_.flags & kFlowPorousResistance) stage_porous_resistance(dt);
  if (params_.flags & kFlowTurbulence) stage_turbulence(dt);
  apply_inlet(time_ + dt, u_star_);
  stage_pressure(dt);
  stage_correct();
  // F moves with the new, projected velocities: their divergence is exactly the porosity source of
  // this step, so the water volume balances over the same dt
  if (params_.flags & kFlowFreeSurface) stage_advect_vof(dt);
  stage_checks(dt);
  cell_porosity_prev_ = cell_porosity;
  // u^n becomes the history of the next step (the snapshot is rewritten at its start)
  face_u_prev.swap(snapshot_->face_u);
  face_w_prev.swap(snapshot_->face_w);
  prev_dt_ = dt;
  time_ += dt;
  // the limit measured for this step (none when the caller chose dt without asking)
  last_advective_ = advective_seen_.step == step_count_ ? advective_seen_.limit : 0.0;
  ++step_count_;
  last_dt_ = dt;
}

void VOFGrid::step_guarded(double dt) {
  // on for this step only, also when it throws
  struct Guarded {
    bool& on;
    explicit Guarded(bool& flag) : on(flag) { on = true; }
    ~Guarded() { on = false; }
  } guarded(guarded_);
  step(dt);
}

void VOFGrid::set_prev_dt(double dt) {
  require_non_negative("prev_dt", dt);
  require_finite("prev_dt", dt);
  if (dt > 0.0 && (face_u_prev.size() != face_u.size() || face_w_prev.size() != face_w.size()))
    throw std::invalid_argument("prev_dt = " + format_value(dt) + " needs face_u_prev and face_w_prev of the face sizes");
  prev_dt_ = dt;
}

void VOFGrid::set_last_dt(double dt) {
  require_non_negative("last_dt", dt);
  require_finite("last_dt", dt);
  last_dt_ = dt;
}

long long VOFGrid::advance(double t_end) {
  FlowStableDt s;
  auto limits = [&] {
    s = stable_dt_terms();
    return AdvanceLimits{s.min(), params_.min_dt, params_.cfl};
  };
  auto collapse = [&](double dt) {
    int kind, index;
    max_cfl(1.0, kind, index);
    save_state();
    fail("checks", "time step collapsed to " + format_value(dt) + " s (advective " + format_value(s.advective) +
                       ", viscous " + format_value(s.viscous) + ")",
         kind, index);
  };
  // a step cut to reach t_end is no stability decision: the growth goes on from the stable step
  auto stepped = [this](const AdvanceStep& a) { last_dt_ = a.taken < a.dt ? a.taken : std::max(a.dt, a.stable); };
  const StepEndCourantReuse reuse(this);
  return advance_until(
      t_end, [this] { return time_; }, limits, collapse, [this](double h) { step(h); },
      [this](double) { ++retried_steps_; }, stepped);
}

}  // namespace vofdem
