#include "vofdem/coupling/coupler.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>
#include <stdexcept>

#include "vofdem/coupling/bed_drag.h"
#include "vofdem/common/check.h"
#include "vofdem/coupling/drag.h"
#include "vofdem/coupling/drag_exchange.h"
#include "vofdem/coupling/fluid_forces.h"
#include "vofdem/common/advance.h"
#include "vofdem/stones/stone_model.h"
#include "vofdem/stones/wet_fraction.h"
#include "coupling/coupler_stage.h"

namespace vofdem {

namespace {
constexpr double kInf = std::numeric_limits<double>::infinity();
}  // namespace

void CouplerParams::validate() const {
  if (flags >= (1u << 11))
    throw std::invalid_argument("flags = " + std::to_string(flags) + " is outside the allowed range [0, 2047]");
  if (flags & (1u << 5))
    throw std::invalid_argument("flags = " + std::to_string(flags) + ": bit 5 (the former relative-velocity "
                                "coupling) is retired: the effect is the flow's own flag, FlowEffect.RELATIVE_VELOCITY "
                                "(kFlowRelativeVelocity)");
  require_in_closed("n_exp", n_exp, 0.0, 1.0);
  if (lookup_m < 2 || lookup_m > 64)
    throw std::invalid_argument("lookup_m = " + std::to_string(lookup_m) + " is outside the allowed range [2, 64]");
  require_positive("lookup_dr", lookup_dr);
  require_positive("max_dt", max_dt);
  require_in_open_closed("stone_cfl", stone_cfl, 0.0, 1.0);
  require_positive("drag_relaxation", drag_relaxation);
  require_positive("min_dt", min_dt);
  require_in_closed("wet_fraction_tolerance", wet_fraction_tolerance, 0.0, 0.5);
  if (max_snapshot_interval < 1 || max_snapshot_interval > 4096)
    throw std::invalid_argument("max_snapshot_interval = " + std::to_string(max_snapshot_interval) +
                                " is outside the allowed range [1, 4096]");
  const int map = static_cast<int>(mapping);
  if (map < 0 || map > 1)
    throw std::invalid_argument("mapping = " + std::to_string(map) +
                                " is outside the allowed values {0 (kCell), 1 (kKernel)}");
  if (!(std::isfinite(bandwidth) && bandwidth >= 0.0 && bandwidth <= 1.0))
    throw std::invalid_argument("bandwidth = " + format_value(bandwidth) +
                                " m is outside the allowed range (0, 1] m (0: unset, 1.0 x the stones' mean diameter)");
  const int model = static_cast<int>(stone_drag);
  if (model < 0 || model > 1)
    throw std::invalid_argument("stone_drag = " + std::to_string(model) +
                                " is outside the allowed values {0 (kSphere), 1 (kBed)}");
  overflow.validate();
}

// ---------------------------------------------------------------------------------------------
// construction

Coupler::Coupler(VOFGrid* fluid, DEMSystem* stones, const CouplerParams& params)
    : fluid_(fluid), stones_(stones), params_(params) {
  n_ = stones_ ? stones_->n() : 0;
  check_params(params_);
  share_medium();
  stone_force_drag.assign(2 * static_cast<std::size_t>(n_), 0.0);
  stone_force_pressure.assign(2 * static_cast<std::size_t>(n_), 0.0);
  stone_force_overflow.assign(2 * static_cast<std::size_t>(n_), 0.0);
  stone_exposed_share.assign(static_cast<std::size_t>(n_), 0.0);
  stone_extent_.assign(static_cast<std::size_t>(n_), StoneExtent{0.0, 0.0, 0.0, 0.0});
  stone_active_u8_.assign(static_cast<std::size_t>(n_), 0);
  band_offsets_.assign(static_cast<std::size_t>(n_) + 1, 0);
  stone_vrel_.assign(static_cast<std::size_t>(n_), 0.0);
  stone_drag_slope_.assign(static_cast<std::size_t>(n_), 0.0);
  stone_x_.assign(static_cast<std::size_t>(n_), 0.0);
  stone_z_.assign(static_cast<std::size_t>(n_), 0.0);
  if (fluid_) {
    const Grid2D& g = fluid_->grid();
    const std::size_t nc = static_cast<std::size_t>(g.ncell());
    cell_base_porosity = fluid_->cell_porosity;
    cell_base_diameter = fluid_->cell_stone_diameter;
    n_old_.assign(nc, 0.0);
    cell_U_.assign(nc, 0.0);
    cell_W_.assign(nc, 0.0);
    cell_dpdx_.assign(nc, 0.0);
    cell_dpdz_.assign(nc, 0.0);
    cell_solid_sum_.assign(nc, 0.0);
    cell_solid_u_.assign(nc, 0.0);
    cell_solid_w_.assign(nc, 0.0);
    cell_diam_sum_.assign(nc, 0.0);
    cell_overflow_reaction.assign(2 * nc, 0.0);
    band_U_.assign(nc, 0.0);
    band_W_.assign(nc, 0.0);
    redistribution_ = std::make_unique<WaterRedistribution>(g);
    make_mapper();
    make_kernel();
  }
  time_ = fluid_ ? fluid_->time() : (stones_ ? stones_->time() : 0.0);
  st_snapshot_ = add_stage("snapshot");
  st_porosity_ = add_stage("porosity");
  st_forces_ = add_stage("fluid_forces");
  st_dem_ = add_stage("dem");
  st_fluid_ = add_stage("fluid");
  st_checks_ = add_stage("checks");
  st_stable_dt_ = add_stage("stable_dt");
}

int Coupler::add_stage(const std::string& name) {
  cpu_profile_.add_stage(name);
  return profile_.add_stage(name);
}

// the stones feel the flow's water and gravity (buoyancy, added mass, weight): one medium, the flow's
void Coupler::share_medium() {
  if (!fluid_ || !stones_ || n_ == 0) return;
  const Medium& m = fluid_->params().medium;
  const DEMParams& d = stones_->params();
  if (d.submerged && d.medium == m) return;
  DEMParams p = d;
  p.medium = m;
  p.submerged = true;
  stones_->set_params(p);
}

void Coupler::make_mapper() {
  mapper_.reset();
  if (!fluid_ || n_ == 0) return;
  double rmin = INFINITY, rmax = 0.0;
  for (int j = 0; j < n_; ++j) {
    const double r = stones_->stone_radius[j];
    if (r > 0.0) rmin = std::min(rmin, r), rmax = std::max(rmax, r);
  }
  if (!(rmax > 0.0)) return;
  PorosityParams p;
  p.method = (params_.flags & kCoupleLookupPorosity) ? PorosityMethod::kLookup : PorosityMethod::kExact;
  p.m = params_.lookup_m;
  p.n_exp = params_.n_exp;
  p.r_min = rmin;
  p.r_max = rmax;
  p.dr = params_.lookup_dr;
  p.max_discs = n_;
  mapper_ = std::make_unique<PorosityMapper>(fluid_->grid(), p);
  csr_current_ = false;
}

// the kernel of CouplerParams::mapping = kKernel on the flow grid, its solid cells the base porosity's
// walls (n = 0); the width unset (0): the stones' mean nominal diameter
void Coupler::make_kernel() {
  kernel_.reset();
  kernel_solid_current_ = false;
  floored_solid_area_ = 0.0;
  if (params_.mapping != CouplingMapping::kKernel || !fluid_ || !mapper_) return;
  KernelParams kp;
  kp.bandwidth = params_.bandwidth;
  if (!(kp.bandwidth > 0.0)) {
    double sum = 0.0;
    int count = 0;
    for (int j = 0; j < n_; ++j)
      if (stones_->stone_radius[j] > 0.0) sum += stones_->nominal_diameter(j), ++count;
    kp.bandwidth = sum / count;  // count > 0: the mapper exists
  }
  const Grid2D& g = fluid_->grid();
  const std::size_t nc = static_cast<std::size_t>(g.ncell());
  std::vector<std::uint8_t> solid(nc, 0);
  for (std::size_t c = 0; c < nc; ++c) solid[c] = cell_base_porosity[c] <= 0.0;
  kernel_ = std::make_unique<KernelSmoother>(g, kp, &solid);
  cell_kernel_porosity_.assign(nc, 1.0);
  cell_kernel_F_.assign(nc, 0.0);
  cell_bed_x_.assign(nc, 0.0);
  cell_bed_z_.assign(nc, 0.0);
  cell_bed_slope_.assign(nc, 0.0);
  if (st_kernel_ < 0) st_kernel_ = add_stage("kernel");
}

// the parameters' limits that depend on the scene (checked before anything changes)
void Coupler::check_params(const CouplerParams& p) const {
  p.validate();
  if (fluid_ && stones_ && !stones_->model().lookup_footprint() && (p.flags & kCoupleLookupPorosity))
    throw std::invalid_argument("CouplerParams.flags = " + std::to_string(p.flags) +
                                ": the lookup porosity (kCoupleLookupPorosity, the paper's table of disc areas) is "
                                "for disc stones; " + stones_->model().name() +
                                " stones need the exact mapping (clear the flag)");
}

void Coupler::set_params(const CouplerParams& params) {
  check_params(params);
  const bool remap = (params.flags ^ params_.flags) & kCoupleLookupPorosity || params.n_exp != params_.n_exp ||
                     params.lookup_m != params_.lookup_m || params.lookup_dr != params_.lookup_dr;
  const bool rekernel = params.mapping != params_.mapping || params.bandwidth != params_.bandwidth;
  const CouplerParams old = params_;
  params_ = params;
  try {
    if (fluid_ && remap) make_mapper();
    if (fluid_ && (remap || rekernel)) make_kernel();
  } catch (...) {  // a width the stones' diameters put out of range: nothing changes
    params_ = old;
    if (fluid_ && remap) make_mapper();
    if (fluid_) make_kernel();
    throw;
  }
  mapped_ = false;
}

void Coupler::set_inflow_table(const std::vector<double>& times, const std::vector<double>& discharge) {
  if (!fluid_) throw std::invalid_argument("set_inflow_table: this scene has no fluid (fluid = null)");
  DischargeTable t;
  t.times = times;
  t.discharge = discharge;
  fluid_->set_discharge(t);
}

double Coupler::water_volume() const { return fluid_ ? fluid_->water_volume() : 0.0; }

// ---------------------------------------------------------------------------------------------
// stages

void Coupler::map_stones() {
  for (int j = 0; j < n_; ++j) {
    stone_x_[j] = stones_->stone_pos[2 * j];
    stone_z_[j] = stones_->stone_pos[2 * j + 1];
  }
  stones_->model().map_footprint(*stones_, *mapper_, stone_x_.data(), stone_z_.data());
  csr_current_ = true;
}

void Coupler::update_porosity(bool keep_water_volume) {
  if (!fluid_ || !mapper_) return;
  stage_porosity(keep_water_volume);
}

// each stone's exact footprint summed per cell: solid area, area x diameter, area x velocity [m^2, m^3, m^3/s]
void Coupler::deposit_stones() {
  std::fill(cell_solid_sum_.begin(), cell_solid_sum_.end(), 0.0);
  std::fill(cell_diam_sum_.begin(), cell_diam_sum_.end(), 0.0);
  std::fill(cell_solid_u_.begin(), cell_solid_u_.end(), 0.0);
  std::fill(cell_solid_w_.begin(), cell_solid_w_.end(), 0.0);
  const std::vector<int>& off = mapper_->stone_cell_offsets();
  const std::vector<int>& idx = mapper_->stone_cell_index();
  const std::vector<double>& area = mapper_->stone_cell_area();
  for (int j = 0; j < n_; ++j) {
    const double d = stones_->nominal_diameter(j);
    const double u = stones_->stone_vel[2 * j], w = stones_->stone_vel[2 * j + 1];
    for (int p = off[j]; p < off[j + 1]; ++p) {
      const int c = idx[p];
      cell_solid_sum_[c] += area[p];
      cell_diam_sum_[c] += area[p] * d;
      cell_solid_u_[c] += area[p] * u;
      cell_solid_w_[c] += area[p] * w;
    }
  }
}

// a per-cell area field [m^2 x q] smoothed as the density q per unit cell area (what the kernel conserves)
void Coupler::smooth_area_field(std::vector<double>& v) {
  const Grid2D& g = fluid_->grid();
  for (int k = 0; k < g.nz(); ++k) {
    const double inv = 1.0 / g.cell_area(k);
    for (int i = 0; i < g.nx(); ++i) v[g.cell(i, k)] *= inv;
  }
  kernel_->smooth(v);
  for (int k = 0; k < g.nz(); ++k) {
    const double a = g.cell_area(k);
    for (int i = 0; i < g.nx(); ++i) v[g.cell(i, k)] *= a;
  }
}

// kernel mapping: the deposit smoothed, then eq. (11) on the smoothed solid fraction phi with the floor
// n >= n_exp (phi <= 1: a cell holds no more stone than a packing of the stones does), before the
// resistance law; the solid area the floor removes is counted, never clipped silently
void Coupler::smooth_solid() {
  CoupledStage timer(profile_, cpu_profile_, st_kernel_);
  smooth_area_field(cell_solid_sum_);
  smooth_area_field(cell_diam_sum_);
  if (fluid_->params().flags & kFlowRelativeVelocity) {
    smooth_area_field(cell_solid_u_);
    smooth_area_field(cell_solid_w_);
  }
  const Grid2D& g = fluid_->grid();
  const double ne = params_.n_exp;
  double floored = 0.0;
  for (int k = 0; k < g.nz(); ++k) {
    const double a = g.cell_area(k);
    for (int i = 0; i < g.nx(); ++i) {
      const int c = g.cell(i, k);
      const double phi = cell_solid_sum_[c] / a, s = phi < 1.0 ? phi : 1.0;
      floored += (phi - s) * a * (1.0 - ne);
      const double n = 1.0 - (1.0 - ne) * s;
      cell_kernel_porosity_[c] = n < ne ? ne : n;  // the round-off of 1 - (1 - n_exp) at s = 1
    }
  }
  floored_solid_area_ = floored;
  kernel_solid_current_ = true;
}

void Coupler::stage_porosity(bool keep_water_volume) {
  CoupledStage timer(profile_, cpu_profile_, st_porosity_);
  map_stones();
  const Grid2D& g = fluid_->grid();
  const int nc = g.ncell();
  deposit_stones();
  if (kernel_) smooth_solid();  // the stones' porosity against the base one (walls, fixed porous zones): the tighter wins. Written
  // into the flow's own array (its numpy views stay live), the old values kept in n_old_
  const std::vector<double>& nm = kernel_ ? cell_kernel_porosity_ : mapper_->cell_porosity();
  std::vector<double>& n_new = fluid_->cell_porosity;
  for (int c = 0; c < nc; ++c) {
    n_old_[c] = n_new[c];
    if (nm[c] < cell_base_porosity[c]) {
      n_new[c] = nm[c];
      fluid_->cell_stone_diameter[c] = cell_diam_sum_[c] / cell_solid_sum_[c];
    } else {
      n_new[c] = cell_base_porosity[c];
      fluid_->cell_stone_diameter[c] = cell_base_diameter[c];
    }
  }
  // water volume per cell kept (a single-phase flow has no free surface to take displaced water)
  // the first mapping sets the scene up (nothing flows); later changes drive the flow if asked
  const bool displace = keep_water_volume && mapped_ && (params_.flags & kCoupleDisplaceFlow);
  if (keep_water_volume && !displace && (fluid_->params().flags & kFlowFreeSurface)) {
    const int bad = redistribution_->apply(n_old_, n_new, fluid_->cell_F);
    redistributed_ += redistribution_->moved_volume();
    if (bad >= 0) {
      std::copy(n_old_.begin(), n_old_.end(), n_new.begin());  // as it was, also without a snapshot
      fail("porosity", "no room for the water displaced from cell (i=" + std::to_string(bad % g.nx()) +
                           ", k=" + std::to_string(bad / g.nx()) + "): the domain is full");
    }
  }
  fluid_->update_face_porosity(displace);
  if (fluid_->params().flags & kFlowRelativeVelocity) solid_velocity_at_faces();
  mapped_ = true;
}

// area-weighted velocity of the stones in the two cells of each face [m/s]
void Coupler::solid_velocity_at_faces() {
  const Grid2D& g = fluid_->grid();
  // a boundary face has its one cell on both sides: counted once
  auto mean = [&](const FaceCells& c, const std::vector<double>& v) {
    const double s = cell_solid_sum_[c.a] + (c.a != c.b ? cell_solid_sum_[c.b] : 0.0);
    const double m = v[c.a] + (c.a != c.b ? v[c.b] : 0.0);
    return s > 0.0 ? m / s : 0.0;
  };
  for (int k = 0; k < g.nz(); ++k)
    for (int i = 0; i <= g.nx(); ++i) fluid_->face_x_solid_u[g.face_x(i, k)] = mean(g.face_x_cells(i, k), cell_solid_u_);
  for (int k = 0; k <= g.nz(); ++k)
    for (int i = 0; i < g.nx(); ++i) fluid_->face_z_solid_w[g.face_z(i, k)] = mean(g.face_z_cells(i, k), cell_solid_w_);
}

void Coupler::update_fluid_forces() {
  if (!fluid_ || !mapper_) return;
  csr_current_ = false;
  kernel_solid_current_ = false;
  stage_fluid_forces();
}

// names the first of a stone's cells whose flow is not finite (the cause of a non-finite force), or ""
std::string Coupler::non_finite_cell(int count, const int* cells) const {
  const int nx = fluid_->grid().nx();
  for (int m = 0; m < count; ++m) {
    const int c = cells[m];
    const double v[] = {fluid_->cell_F[c], cell_U_[c], cell_W_[c], cell_dpdx_[c], cell_dpdz_[c]};
    const char* names[] = {"water fraction", "pore velocity U", "pore velocity W", "dp/dx", "dp/dz"};
    for (int q = 0; q < 5; ++q)
      if (!std::isfinite(v[q]))
        return "; the flow is not finite in its cell (i=" + std::to_string(c % nx) + ", k=" + std::to_string(c / nx) +
               "): " + names[q] + " = " + format_value(v[q]);
  }
  return "";
}

void Coupler::stage_fluid_forces() { stage_fluid_forces(params_.flags); }

void Coupler::stage_fluid_forces(unsigned fl) {
  CoupledStage timer(profile_, cpu_profile_, st_forces_);
  // one-way coupling: the stones' cell lists without touching the flow's porosity
  if (!csr_current_) map_stones();
  const FlowParams& fp = fluid_->params();
  const std::vector<int>& off = mapper_->stone_cell_offsets();
  const std::vector<int>& idx = mapper_->stone_cell_index();
  const double rho = fp.medium.rho_water, nu = fp.medium.nu_water;
  const bool bed = params_.stone_drag == StoneDragModel::kBed;
  const WetLaw wet_law = stones_->model().wet_law();
  // the flow's own water, closure law, terms and relative velocity: the reaction of what it removes
  const BedDragParams bp(fp);
  if (kernel_) {
    smooth_flow(bed && (fl & kCoupleDrag), bp);
  } else {
    // the flow is sampled in the stones' cells only (the other entries are not read)
    const int ncs = off[n_];
    fluid_->pore_velocity_at_cells(ncs, idx.data(), cell_U_, cell_W_);
    // without the pressure-gradient effect the sample's gradient is unused: zeros
    if (fl & kCouplePressureGradient) fluid_->pressure_gradient_at_cells(ncs, idx.data(), cell_dpdx_, cell_dpdz_);
    else std::fill(cell_dpdx_.begin(), cell_dpdx_.end(), 0.0), std::fill(cell_dpdz_.begin(), cell_dpdz_.end(), 0.0);
  }
  // the water fraction the stones see: the flow's, or smoothed with the kernel
  const double* cell_F = kernel_ ? cell_kernel_F_.data() : fluid_->cell_F.data();
  const std::vector<double>& area = mapper_->stone_cell_area();
  const bool over = fl & kCoupleOverflowLoad;
  if (over) overflow_loads(rho);
  const unsigned forces = kCoupleForces | kCoupleOverflowLoad;
  for (int j = 0; j < n_; ++j) {
    double* fd = &stone_force_drag[2 * j];
    double* fs = &stone_force_pressure[2 * j];
    fd[0] = fd[1] = fs[0] = fs[1] = 0.0;
    stone_vrel_[j] = 0.0;
    stone_drag_slope_[j] = 0.0;
    if (!stones_->stone_active[j]) continue;
    const StoneFlowSample s = sample_flow_at_stone(off[j + 1] - off[j], idx.data() + off[j], area.data() + off[j],
                                                   cell_F, cell_U_.data(), cell_W_.data(), cell_dpdx_.data(),
                                                   cell_dpdz_.data(), rho, fp.medium.gravity[0], fp.medium.gravity[1]);
    const double up = stones_->stone_vel[2 * j], wp = stones_->stone_vel[2 * j + 1];
    stone_vrel_[j] = s.wet > 0.0 ? std::hypot(s.u - up, s.w_vel - wp) : 0.0;
    if ((fl & kCoupleDrag) && !bed) {
      const DragForce f = stones_->model().drag(*stones_, j, s, up, wp, rho, nu, params_.drag_law,
                                                params_.implicit_drag ? &stone_drag_slope_[j] : nullptr);
      fd[0] = f.fx, fd[1] = f.fz;
    } else if ((fl & kCoupleDrag) && kernel_) {
      const DragForce f = kernel_bed_drag(j, &stone_drag_slope_[j]);
      fd[0] = f.fx, fd[1] = f.fz;
    } else if (fl & kCoupleDrag) {
      const DragForce f = bed_drag(off[j + 1] - off[j], idx.data() + off[j], area.data() + off[j], fluid_->cell_F.data(),
                                   fluid_->cell_porosity.data(), fluid_->cell_stone_diameter.data(), cell_U_.data(),
                                   cell_W_.data(), up, wp, stones_->volume(j), bp, &stone_drag_slope_[j]);
      fd[0] = f.fx, fd[1] = f.fz;
    }
    if (over) {
      // the exposed share is loaded by the overflow instead of the pore velocity (overflow_load.h)
      const double keep = 1.0 - stone_exposed_share[j];
      fd[0] *= keep, fd[1] *= keep;
      stone_drag_slope_[j] *= keep;
    }
    if (fl & kCouplePressureGradient) {
      const auto f = stone_pressure_force(s, stones_->volume(j));
      fs[0] = f[0], fs[1] = f[1];
    }
    if (fl & forces) {
      forces_applied_ = true;
      // the drag linearised in the stone's velocity (implicit in the DEM), or held over the step
      const LinearDrag ld = params_.implicit_drag ? linearise_drag({fd[0], fd[1]}, stone_drag_slope_[j], up, wp)
                                                  : LinearDrag();
      const bool held = ld.coef == 0.0;
      stones_->stone_force_ext[2 * j] = (held ? fd[0] : 0.0) + fs[0];
      stones_->stone_force_ext[2 * j + 1] = (held ? fd[1] : 0.0) + fs[1];
      if (over) {  // held over the step: the approach velocity is the overflow's, not the stone's cells'
        stones_->stone_force_ext[2 * j] += stone_force_overflow[2 * j];
        stones_->stone_force_ext[2 * j + 1] += stone_force_overflow[2 * j + 1];
      }
      stones_->stone_drag_coef[j] = ld.coef;
      stones_->stone_drag_vel[2 * j] = ld.vel_x;
      stones_->stone_drag_vel[2 * j + 1] = ld.vel_z;
    }
    if (!std::isfinite(fd[0] + fd[1] + fs[0] + fs[1] + s.wet))
      fail("fluid_forces", "non-finite fluid force on stone " + std::to_string(j) + " (drag " + format_value(fd[0]) +
                               ", " + format_value(fd[1]) + " N; pressure " + format_value(fs[0]) + ", " +
                               format_value(fs[1]) + " N; wet fraction " + format_value(s.wet) + ") at x = " +
                               format_value(stones_->stone_pos[2 * j]) + " m, z = " +
                               format_value(stones_->stone_pos[2 * j + 1]) + " m" +
                               non_finite_cell(off[j + 1] - off[j], idx.data() + off[j]));
    if (fl & kCoupleWetFraction) {
      // w now, and the level that gives it, so that w follows the stone over the DEM's substeps
      const double w = snapped_wet_fraction(std::clamp(s.wet, 0.0, 1.0), params_.wet_fraction_tolerance);
      stones_->set_wet_fraction(j, w);
      stones_->stone_water_level[j] =
          water_level_of_wet_fraction(stones_->stone_pos[2 * j + 1], stones_->wet_radius(j), w, wet_law);
    }
  }
}

// kernel mapping, what the stones see: on every cell the bed drag's densities (from the raw flow and the
// stones' smoothed velocity, as the flow's resistance uses them), then F, F U, F W and the pressure
// gradient smoothed; U = S(F U) / S(F), so the F-weighted average over a footprint is that of S(F U).
// By self-adjointness this equals each stone's smoothed footprint over the raw fields
void Coupler::smooth_flow(bool bed, const BedDragParams& bp) {
  // the stones' velocity per cell for the bed drag: this step's smoothed deposit (one-way coupling: made here)
  if (bed && bp.relative && !kernel_solid_current_) {
    map_stones();
    deposit_stones();
    smooth_solid();
  }
  CoupledStage timer(profile_, cpu_profile_, st_kernel_);
  const int nc = fluid_->grid().ncell();
  const std::vector<double>& F = fluid_->cell_F;
  fluid_->pore_velocity_at_cells(cell_U_, cell_W_);
  if (params_.flags & kCouplePressureGradient) {
    fluid_->pressure_gradient_at_cells(cell_dpdx_, cell_dpdz_);
    kernel_->smooth(cell_dpdx_);
    kernel_->smooth(cell_dpdz_);
  } else {
    std::fill(cell_dpdx_.begin(), cell_dpdx_.end(), 0.0), std::fill(cell_dpdz_.begin(), cell_dpdz_.end(), 0.0);
  }
  if (bed) {
    const std::vector<double>& n = fluid_->cell_porosity;
    const std::vector<double>& D = fluid_->cell_stone_diameter;
    for (int c = 0; c < nc; ++c) {
      const double s = cell_solid_sum_[c];
      const double up = s > 0.0 ? cell_solid_u_[c] / s : 0.0, wp = s > 0.0 ? cell_solid_w_[c] / s : 0.0;
      const BedDragDensity d = bed_drag_density(F[c], n[c], D[c], cell_U_[c], cell_W_[c], up, wp, bp);
      cell_bed_x_[c] = d.fx, cell_bed_z_[c] = d.fz, cell_bed_slope_[c] = d.slope;
    }
    kernel_->smooth(cell_bed_x_);
    kernel_->smooth(cell_bed_z_);
    kernel_->smooth(cell_bed_slope_);
  }
  for (int c = 0; c < nc; ++c) {
    cell_kernel_F_[c] = F[c];
    cell_U_[c] *= F[c];
    cell_W_[c] *= F[c];
  }
  kernel_->smooth(cell_kernel_F_);
  kernel_->smooth(cell_U_);
  kernel_->smooth(cell_W_);
  for (int c = 0; c < nc; ++c) {
    const double f = cell_kernel_F_[c];
    cell_U_[c] = f > 0.0 ? cell_U_[c] / f : 0.0;
    cell_W_[c] = f > 0.0 ? cell_W_[c] / f : 0.0;
  }
}

// kernel mapping, bed drag: V rho_w times the smoothed densities averaged over the stone's footprint.
// Summed over the stones this is the flow's cell-wise removal integrated against the smoothed stone
// volume per cell: the transpose of deposit-then-smooth (Newton's third law to round-off)
DragForce Coupler::kernel_bed_drag(int j, double* slope) const {
  const std::vector<int>& off = mapper_->stone_cell_offsets();
  const std::vector<int>& idx = mapper_->stone_cell_index();
  const std::vector<double>& area = mapper_->stone_cell_area();
  double a_sum = 0.0, fx = 0.0, fz = 0.0, s = 0.0;
  for (int p = off[j]; p < off[j + 1]; ++p) {
    const int c = idx[p];
    a_sum += area[p];
    fx += area[p] * cell_bed_x_[c];
    fz += area[p] * cell_bed_z_[c];
    s += area[p] * cell_bed_slope_[c];
  }
  *slope = 0.0;
  if (a_sum <= 0.0) return {0.0, 0.0};  // outside the grid
  const double scale = stones_->volume(j) * fluid_->params().medium.rho_water / a_sum;
  *slope = scale * s;
  return {scale * fx, scale * fz};
}

// the overflow load (overflow_load.h) on every active stone: its extents, protrusion and exposed share, the
// approach band in the column of its centre, F_D + F_L, and the reaction per cell (per metre of width)
void Coupler::overflow_loads(double rho) {
  if (st_overflow_ < 0) st_overflow_ = add_stage("overflow_load");
  CoupledStage timer(profile_, cpu_profile_, st_overflow_);
  const Grid2D& g = fluid_->grid();
  const StoneModel& model = stones_->model();
  for (int j = 0; j < n_; ++j) {
    stone_active_u8_[j] = stones_->stone_active[j] ? 1 : 0;
    if (!stone_active_u8_[j]) continue;
    StoneExtent& e = stone_extent_[j];
    e.x_hi = model.outline_max(*stones_, j, [](double x, double) { return x; });
    e.x_lo = -model.outline_max(*stones_, j, [](double x, double) { return -x; });
    e.z_hi = model.outline_max(*stones_, j, [](double, double z) { return z; });
    e.z_lo = -model.outline_max(*stones_, j, [](double, double z) { return -z; });
  }
  // the bands: cells of the centre's column from the top up to band_height diameters, weights l_c F_c
  const double* fxn = fluid_->face_x_porosity.data();
  const double* fzn = fluid_->face_z_porosity.data();
  const std::vector<double>& F = fluid_->cell_F;
  band_cells_.clear();
  band_weights_.clear();
  for (int j = 0; j < n_; ++j) {
    band_offsets_[j] = static_cast<int>(band_cells_.size());
    stone_exposed_share[j] = 0.0;
    if (!stone_active_u8_[j]) continue;
    const StoneExtent& e = stone_extent_[j];
    const double share =
        exposed_share(stone_protrusion(j, n_, stone_extent_.data(), stone_active_u8_.data()), e.z_hi - e.z_lo);
    if (share <= 0.0) continue;
    stone_exposed_share[j] = share;
    const double z0 = e.z_hi, z1 = e.z_hi + params_.overflow.band_height * stones_->nominal_diameter(j);
    const int i = g.locate_x(0.5 * (e.x_lo + e.x_hi));
    for (int k = g.locate_z(z0); k <= g.locate_z(z1); ++k) {
      const double len = std::min(z1, g.z_face(k + 1)) - std::max(z0, g.z_face(k));
      if (len <= 0.0 || !overflow_band_cell(g, i, k, fxn, fzn)) continue;
      band_cells_.push_back(g.cell(i, k));
      band_weights_.push_back(len);
    }
  }
  band_offsets_[n_] = static_cast<int>(band_cells_.size());
  const int nb = band_offsets_[n_];
  if (nb > 0) fluid_->pore_velocity_at_cells(nb, band_cells_.data(), band_U_, band_W_);
  std::fill(cell_overflow_reaction.begin(), cell_overflow_reaction.end(), 0.0);
  const double inv_b = 1.0 / fluid_->params().flume_width;
  for (int j = 0; j < n_; ++j) {
    stone_force_overflow[2 * j] = stone_force_overflow[2 * j + 1] = 0.0;
    double len = 0.0, wet = 0.0, u = 0.0, w = 0.0;
    for (int q = band_offsets_[j]; q < band_offsets_[j + 1]; ++q) {
      const int c = band_cells_[q];
      const double lf = band_weights_[q] * F[c];
      len += band_weights_[q], wet += lf, u += lf * band_U_[c], w += lf * band_W_[c];
    }
    if (!(wet > 0.0)) {  // a dry band, or none: nothing, and the cell drag stays whole
      stone_exposed_share[j] = 0.0;
      continue;
    }
    u /= wet, w /= wet;
    const double ur = u - stones_->stone_vel[2 * j], wr = w - stones_->stone_vel[2 * j + 1];
    const double ap = (ur != 0.0 || wr != 0.0) ? model.projected_area(*stones_, j, ur, wr)
                                               : model.projected_area(*stones_, j);
    const DragForce f = overflow_force(stone_exposed_share[j] * ap, ur, wr, wet / len, rho, params_.overflow);
    stone_force_overflow[2 * j] = f.fx, stone_force_overflow[2 * j + 1] = f.fz;
    // the reaction from the band's cells, by their share of the sample
    for (int q = band_offsets_[j]; q < band_offsets_[j + 1]; ++q) {
      const int c = band_cells_[q];
      const double share = band_weights_[q] * F[c] / wet * inv_b;
      cell_overflow_reaction[2 * c] -= share * f.fx;
      cell_overflow_reaction[2 * c + 1] -= share * f.fz;
    }
  }
  overflow_pending_ = true;
}

void Coupler::apply_overflow_reaction(double dt) {
  CoupledStage timer(profile_, cpu_profile_, st_overflow_);
  vofdem::apply_overflow_reaction(fluid_->grid(), fluid_->face_x_porosity.data(), fluid_->face_z_porosity.data(),
                                  cell_overflow_reaction.data(), dt, fluid_->params().medium.rho_water,
                                  fluid_->face_u.data(), fluid_->face_w.data());
  overflow_pending_ = false;
}

void Coupler::clear_fluid_forces() {
  std::fill(stone_force_drag.begin(), stone_force_drag.end(), 0.0);
  std::fill(stone_force_pressure.begin(), stone_force_pressure.end(), 0.0);
  std::fill(stone_force_overflow.begin(), stone_force_overflow.end(), 0.0);
  std::fill(stones_->stone_force_ext.begin(), stones_->stone_force_ext.end(), 0.0);
  std::fill(stones_->stone_drag_coef.begin(), stones_->stone_drag_coef.end(), 0.0);
  std::fill(stones_->stone_drag_vel.begin(), stones_->stone_drag_vel.end(), 0.0);
  forces_applied_ = false;
}

void Coupler::stage_dem(double dt) {
  CoupledStage timer(profile_, cpu_profile_, st_dem_);
  try {
    stones_->advance(dt);
  } catch (const std::runtime_error& e) {
    fail("dem", e.what());
  }
}

void Coupler::stage_fluid(double dt) {
  CoupledStage timer(profile_, cpu_profile_, st_fluid_);
  try {
    // the guard's snapshot holds the whole start: the flow need not copy its own
    if (snapshot_valid_) fluid_->step_guarded(dt);
    else fluid_->step(dt);
  } catch (const CflBreach& e) {
    fail("fluid", e.what(), e.courant());
  } catch (const std::runtime_error& e) {
    fail("fluid", e.what());
  }
}

void Coupler::stage_checks() {
  CoupledStage timer(profile_, cpu_profile_, st_checks_);
  for (int j = 0; j < n_; ++j) {
    if (!stones_->stone_active[j]) continue;
    const double* x = &stones_->stone_pos[2 * j];
    const double* v = &stones_->stone_vel[2 * j];
    if (!std::isfinite(x[0] + x[1] + v[0] + v[1]))
      fail("checks", "non-finite state of stone " + std::to_string(j) + " (x = " + format_value(x[0]) + ", " +
                         format_value(x[1]) + " m; v = " + format_value(v[0]) + ", " + format_value(v[1]) + " m/s)");
  }
}

// ---------------------------------------------------------------------------------------------
// stepping

double Coupler::stable_dt() { return stable_dt_limits(nullptr, nullptr); }

double Coupler::stable_dt_limits(const char** term, int* cell) {
  CoupledStage timer(profile_, cpu_profile_, st_stable_dt_);
  double dt = params_.max_dt;
  const char* why = "coupler_max_dt";
  int where = -1;
  const unsigned fl = params_.flags;
  if (fluid_ && (fl & kCoupleFluid)) {
    const FlowStableDt s = fluid_->stable_dt_terms();
    if (s.min() < dt) dt = s.min(), why = s.binding(&where);
  }
  if (fluid_ && has_stones() && (fl & kCoupleDEM)) {
    const Grid2D& g = fluid_->grid();
    const double inv_hx = 1.0 / g.dx(), inv_hz = 1.0 / g.min_dz();
    const DEMParams& dp = stones_->params();
    const bool added = (dp.flags & kDEMAddedMass) && dp.water_density() > 0.0;
    const double rho = fluid_->params().medium.rho_water, nu = fluid_->params().medium.nu_water;
    // a drag held over the step (explicit exchange) relaxes the stone in (M + M') / slope: a step stays
    // below drag_relaxation of that (the slope of eq. 18', drag.h); the implicit exchange needs no such
    // bound (drag_exchange.h)
    auto relaxation_dt = [&](int j) {
      const double w = stones_->stone_wet[j];
      const double mass = stones_->mass(j) + (added ? rho * dp.added_mass_coefficient * stones_->volume(j) * w : 0.0);
      if (params_.stone_drag == StoneDragModel::kBed) {
        // bed drag: its slope in the stone's velocity from the last exchange
        const double slope = stone_drag_slope_[j];
        return slope > 0.0 ? params_.drag_relaxation * mass / slope : kInf;
      }
      if (!(w > 0.0)) return kInf;
      return stones_->model().drag_relaxation_dt(*stones_, j, params_.drag_relaxation, mass, stone_vrel_[j], w, rho, nu);
    };
    for (int j = 0; j < n_; ++j) {
      if (!stones_->stone_active[j] || stones_->stone_fixed[j]) continue;
      // a stone crosses at most stone_cfl of a cell per exchange in each direction (smooth porosity changes)
      const double rate =
          std::max(std::abs(stones_->stone_vel[2 * j]) * inv_hx, std::abs(stones_->stone_vel[2 * j + 1]) * inv_hz);
      if (rate * dt > params_.stone_cfl) dt = params_.stone_cfl / rate, why = "stone_cfl", where = stone_cell(j);
      if (params_.implicit_drag || !(fl & kCoupleDrag)) continue;
      const double relax = relaxation_dt(j);
      if (relax < dt) dt = relax, why = "drag_relaxation", where = stone_cell(j);
    }
  }
  if (term) *term = why;
  if (cell) *cell = where;
  return dt;
}

int Coupler::stone_cell(int j) const {
  const Grid2D& g = fluid_->grid();
  const int i = g.locate_x(stones_->stone_pos[2 * j]), k = g.locate_z(stones_->stone_pos[2 * j + 1]);
  return i >= 0 && k >= 0 ? g.cell(i, k) : -1;
}

void Coupler::count_limit(const char* term, int cell) {
  ++limit_steps_[term];
  if (!fluid_ || cell < 0) return;
  std::vector<long long>& c = limit_cells_[term];
  c.resize(static_cast<std::size_t>(fluid_->grid().ncell()), 0);
  ++c[static_cast<std::size_t>(cell)];
}

void Coupler::clear_step_limits() {
  limit_steps_.clear();
  limit_cells_.clear();
}

void Coupler::step() { step(stable_dt()); }

void Coupler::save() {
  if (!(fluid_ && has_stones())) {  // one module: it restores itself
    snapshot_valid_ = false;
    return;
  }
  const double last_dt = fluid_->last_dt();
  if (sparse_snapshots_ && snapshot_valid_ && static_cast<int>(replay_.size()) < snapshot_interval_) {
    replay_.push_back({std::numeric_limits<double>::quiet_NaN(), last_dt});
    return;
  }
  // a whole interval without a failure (not the first snapshot): the next one may be twice as long
  if (sparse_snapshots_ && snapshot_valid_)
    snapshot_interval_ = std::min(2 * snapshot_interval_, params_.max_snapshot_interval);
  CoupledStage timer(profile_, cpu_profile_, st_snapshot_);
  export_state(snapshot_, false);
  snapshot_valid_ = true;
  replay_.assign(1, {std::numeric_limits<double>::quiet_NaN(), last_dt});
}

void Coupler::restore() {
  if (!snapshot_valid_) return;
  import_state(snapshot_, false);
  if (replay_.size() > 1) {
    replay();
    // the retries of this step start from here: a snapshot of its start, the interval back to 1
    CoupledStage timer(profile_, cpu_profile_, st_snapshot_);
    export_state(snapshot_, false);
    snapshot_interval_ = 1;
  }
  replay_.clear();
}

// the steps since the snapshot (all but the failing one) as they were taken: the flow's last_dt set
// between them as the advance loop set it, and the stable step measured before each (it prepares
// what the step reads, e.g. the phases' viscosities)
void Coupler::replay() {
  replaying_ = true;
  try {
    for (std::size_t s = 0; s + 1 < replay_.size(); ++s) {
      fluid_->set_last_dt(replay_[s].fluid_last_dt);
      stable_dt_limits(nullptr, nullptr);
      run_stages(replay_[s].dt);
      ++replayed_steps_;
    }
  } catch (...) {
    replaying_ = false;
    throw;
  }
  replaying_ = false;
  fluid_->set_last_dt(replay_.back().fluid_last_dt);
}

void Coupler::fail(const std::string& stage, const std::string& what, double courant) {
  const double t = time_;
  // the steps replayed were taken before without a failure: this one is a bug, not a retry
  if (replaying_)
    throw std::logic_error("Coupler: replaying the steps since the guard's snapshot failed at t = " +
                           format_value(t) + " s in stage '" + stage + "': " + what);
  restore();
  if (time_ != t)
    throw std::logic_error("Coupler: the guard restored t = " + format_value(time_) + " s for a step that started at " +
                           format_value(t) + " s");
  std::ostringstream os;
  os << "Coupler stage '" << stage << "' at t = " << format_value(t) << " s (step " << steps_ << "): " << what
     << "; coupled state restored to t = " << format_value(time_) << " s";
  if (courant > 0.0) throw CflBreach(os.str(), courant);
  throw std::runtime_error(os.str());
}

void Coupler::step(double dt) {
  require_positive("dt", dt);
  if (stones_ && stones_->n() != n_)
    throw std::invalid_argument("stones.n = " + std::to_string(stones_->n()) + " changed since the coupler was built (" +
                                std::to_string(n_) + "): build a new Coupler after a resize");
  save();
  run_stages(dt);
  if (snapshot_valid_) replay_.back().dt = dt;
}

void Coupler::run_stages(double dt) {
  share_medium();
  const unsigned fl = params_.flags;
  const bool stones_move = has_stones() && (fl & kCoupleDEM);
  csr_current_ = false;
  kernel_solid_current_ = false;
  // the force stage skipped: the stones must not keep the last fluid force it wrote
  if (forces_applied_ && !(fl & (kCoupleForces | kCoupleOverflowLoad)) && stones_) clear_fluid_forces();
  if (fluid_ && mapper_ && (fl & kCouplePorosity) && (stones_move || !mapped_)) stage_porosity();
  overflow_pending_ = false;
  if (fluid_ && mapper_ && (fl & (kCoupleForces | kCoupleWetFraction | kCoupleOverflowLoad)) && stones_move)
    stage_fluid_forces();
  // the overflow's reaction goes to the flow that is stepped (a frozen flow stays as it is)
  if (overflow_pending_ && (fl & kCoupleFluid)) apply_overflow_reaction(dt);
  if (stones_move) stage_dem(dt);
  if (fluid_ && (fl & kCoupleFluid)) stage_fluid(dt);
  if (has_stones() && (fl & kCoupleChecks)) stage_checks();
  csr_current_ = false;
  kernel_solid_current_ = false;
  time_ += dt;
  ++steps_;
}

long long Coupler::advance(double t_end, const std::function<void(double)>& progress) {
  const char* term = nullptr;
  int cell = -1;
  auto limits = [&] {
    const double dt = stable_dt_limits(&term, &cell);
    return AdvanceLimits{dt, params_.min_dt, fluid_ ? fluid_->params().cfl : 1.0};
  };
  auto collapse = [this](double dt) {
    snapshot_valid_ = false;
    fail("step", "time step collapsed to " + format_value(dt) + " s (below min_dt = " + format_value(params_.min_dt) +
                     " s)");
  };
  auto stepped = [&](const AdvanceStep& a) {
    const bool retried = a.retries > 0;
    if (retried) count_limit("cfl_retry", -1);
    else count_limit(a.dt < a.stable ? "t_end" : term, cell);
    // a step cut to reach t_end is no stability decision: the flow's growth limit goes on from the stable step
    if (fluid_ && (params_.flags & kCoupleFluid) && a.dt < a.stable && !retried) fluid_->set_last_dt(a.stable);
    if (progress) progress(time_);
  };
  // a progress callback may write the flow's fields between the steps: then every limit is measured afresh
  // and the snapshot is taken every step (a replay would not see what it wrote)
  const StepEndCourantReuse reuse(fluid_ && !progress ? fluid_ : nullptr);
  const SparseSnapshots sparse(*this, !progress);
  return advance_until(
      t_end, [this] { return time_; }, limits, collapse, [this](double h) { step(h); }, [](double) {}, stepped);
}

// the state may be written between two calls of advance(): the first snapshot of a call is taken afresh
Coupler::SparseSnapshots::SparseSnapshots(Coupler& c, bool on) : c_(c) {
  c_.snapshot_valid_ = false;
  c_.sparse_snapshots_ = on;
}

Coupler::SparseSnapshots::~SparseSnapshots() {
  c_.snapshot_valid_ = false;
  c_.sparse_snapshots_ = false;
}

}  // namespace vofdem
