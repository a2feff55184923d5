// Free-surface flow over and through a porous medium on a vertical 2D MAC grid: seed paper eqs. (1)-(4).
//
//   du/dx + dw/dz = 0                                                                        (1)
//   du/dt + div(u u / n) = n (-(1/rho) grad p + g + R) + (1/rho) div(mu_e (grad u + grad u^T))   (2)-(3)
//   n dF/dt + div(u F) = 0                                                                   (4)
//   (with porosity changed by moving stones between steps: dn/dt + div u = 0 in place of (1))
//
// u = (u, w) are the superficial (mesh-averaged) velocities of the paper, n the porosity, F the water
// fraction, rho = F rho_w + (1 - F) rho_a and mu = F mu_w + (1 - F) mu_a the one-fluid density and
// viscosity (two phases: air pockets in the rubble and plunging jets behave), mu_e = mu + rho nu_t.
//
// Form of the terms (documented choices):
// - eq. (2) of the paper divided by n. The convective term is written div(u u / n) = div(n U U) with
//   the pore velocity U = u / n, the consistent volume-averaged form; for uniform n it is the paper's
//   (1/n) d(uu)/dx. The momentum of a face is convected with its pore velocity u_f / n_f.
// - R is the closure law of porous_resistance.h, which carries its own minus sign: R = -u (a + b |u|)
//   points against the flow. In steady uniform flow the equation gives -dp/dx = rho u (a + b |u|).
//   R is treated semi-implicitly, u^{n+1} (1 + dt n (a + b |u^n|)) = ..., so any n in (0, 1] (down to
//   1e-6 next to fast flow) stays bounded. With the relative-velocity option R uses u - n u_s, u_s the
//   stones' velocity at the face.
// - The viscous term acts on the superficial velocity (porosity gradients in it are neglected, as in
//   most VARANS codes); the -2/3 grad k of the paper is absorbed into the pressure (p is then the
//   modified pressure p + 2/3 rho k, the usual practice).
// - Turbulence (switchable): the standard k-epsilon model of k_epsilon.h supplies nu_t (lagged by one
//   step: the model advances with the velocities of the step's start) and, on the bed and end walls,
//   the log-law wall shear that replaces the slip / no-slip condition there.
// - Pressure projection: u^{n+1} = u* - beta_f grad p, beta_f = dt n_f / (rho_f (1 + dt n_f R'_f)),
//   p the absolute pressure [Pa] with p = 0 at the open top (see pressure_solver.h). A multigrid-CG
//   solve that does not converge within its iteration limit (many scattered near-solid cells) is
//   redone by the direct solver, and counted (pressure_fallbacks()); the step goes on.
//
// Porosity at faces (documented rule): a face is as open as its tighter neighbour,
//   n_f = min(n_L, n_R) (0 when either side is solid), D_f = D of that neighbour (mean on a tie),
// so a nearly closed cell (n = 1e-6) is nearly closed on every face and its pore velocity stays bounded.
// A boundary face takes the porosity of its cell.
//
// Boundaries: left end wall or discharge inlet Q(t) [m^3/s] / flume width B spread over the inlet
// rows below its water level (inflow.h; water fraction 1 entering, inlet level free);
// right end wall, free overfall (the end face is the brink, open to still air outside: the
// hydrostatic air pressure from p = 0 at the top; the water falls freely out) or a fixed tailwater
// level (hydrostatic water pressure below it); open faces carry zero-gradient momentum outflow; bed
// and end walls slip or no-slip; top open to the atmosphere (p = 0) or a slip lid.
//
// A step runs the stages momentum -> porous_resistance -> turbulence -> pressure -> correct ->
// advect_vof -> checks: F moves with the projected velocities u^{n+1}, whose divergence is exactly
// the step's porosity source, so water is conserved also when stones move.
//
// References: S. Maeno and A. Tomita (2008), ICHE 2008 (eqs. 1-7); F. H. Harlow and J. E. Welch (1965)
// (MAC grid); A. J. Chorin (1968) (projection); P. Higuera, J. L. Lara and I. J. Losada (2014), Coastal
// Eng. 83 (VARANS with semi-implicit porous resistance).
#pragma once

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "vofdem/common/grid.h"
#include "vofdem/flow/inflow.h"
#include "vofdem/flow/k_epsilon.h"
#include "vofdem/common/medium.h"
#include "vofdem/flow/momentum.h"
#include "vofdem/flow/porous_resistance.h"
#include "vofdem/flow/pressure_solver.h"
#include "vofdem/common/profile.h"
#include "vofdem/flow/vof_advection.h"

namespace vofdem {

struct ProjectionFields;    // projection.h
struct ProjectionBoundary;  // projection.h

// physical effects of the flow solver, one bit each (FlowParams::flags)
enum FlowEffect : std::uint32_t {
  kFlowFreeSurface = 1u << 0,         // two phases and VOF advection; off: water everywhere, F = 1
  kFlowPorousDarcy = 1u << 1,         // linear (Darcy) term nu/K of eqs. (5)-(7)
  kFlowPorousForchheimer = 1u << 2,   // quadratic term C/sqrt(K) |u| of eqs. (5)-(7)
  kFlowTurbulence = 1u << 3,          // k-epsilon eddy viscosity nu_t (laminar when off)
  kFlowViscosity = 1u << 4,           // viscous stresses
  kFlowGravity = 1u << 5,             // gravity
  kFlowRelativeVelocity = 1u << 6,    // porous resistance on the velocity relative to the stones
  kFlowConvection = 1u << 7,          // momentum convection
  kFlowPorousResistance = kFlowPorousDarcy | kFlowPorousForchheimer,
  // the scenes' effects (python/vofdem/scene.py Effects): everything but the relative velocity
  kFlowDefault = kFlowFreeSurface | kFlowPorousResistance | kFlowTurbulence | kFlowViscosity | kFlowGravity |
                 kFlowConvection,
};

enum class InletBoundary { kWall = 0, kDischarge = 1 };
enum class OutletBoundary { kWall = 0, kFreeOverfall = 1, kTailwater = 2 };
enum class TopBoundary { kOpen = 0, kWall = 1 };
enum class WallCondition { kSlip = 0, kNoSlip = 1 };
// time stepping of the viscous (molecular + eddy) stresses: forward Euler throughout, or the vertical
// diffusion by backward Euler (a tridiagonal solve per column for u and w; x-diffusion and cross terms
// explicit), which lifts the step limit dz^2 / (4 nu_t) of the fine rows. kImplicitVertical solves the
// columns from the velocities after the explicit stresses (stable up to the step limit);
// kImplicitVerticalFromStart, the former scheme, from u^n with the explicit increment added beside
// it: unstable above about 0.7 of the limit for modes the columns damp (momentum.h), kept to
// reproduce runs made with it. kImplicit also solves the horizontal diffusions by rows before the
// columns (MomentumTerms::implicit_horizontal): only the cross terms stay explicit, and the viscous
// stresses bound no step (checked on the whole step's matrix to 1e4 times kImplicitVertical's limit)
enum class ViscousScheme { kExplicit = 0, kImplicitVertical = 1, kImplicitVerticalFromStart = 2, kImplicit = 3 };
// viscosity of a cell corner (where the shear stress mu (du/dz + dw/dx) lives) from its four cells:
// arithmetic mean, or (kHarmonic) the molecular part by arithmetic and the eddy part rho nu_t by
// harmonic mean (Patankar 1980, sec. 4.2-3: diffusivities in series across an interface), which is
// zero when a cell carries none (air, solid): the water's eddy viscosity does not act on the air faces
// above it, whose density is the air's. Laminar flow is the same under both.
enum class CornerViscosity { kArithmetic = 0, kHarmonic = 1 };
// time integration of the convective term: forward Euler, or the variable-step Adams-Bashforth 2, the
// term evaluated at the velocity extrapolated to the middle of the step, u^n + dt_n / (2 dt_{n-1})
// (u^n - u^{n-1}) (for a linear operator exactly AB2: (1 + r/2) C u^n - (r/2) C u^{n-1},
// r = dt_n / dt_{n-1}). The viscous stresses stay forward Euler (explicit part) and backward Euler
// (vertical part): AB2's real-axis stability is half Euler's and would halve the viscous limit. The
// projection and the semi-implicit porous resistance are kept. The first step (and one after
// clear_step_history()) is forward Euler
enum class MomentumTimeScheme { kEuler = 0, kAdamsBashforth2 = 1 };
// the advective limit a step is taken under: the Courant number's of the step's start (kThisStep), or
// the smaller of that and the last step's (kTwoSteps). With AB2 at cfl 0.5 the limit can flicker from
// one step to the next (by 0.83 / 1.20 in the overflow of the Maeno grid four times as fine,
// docs/vof_grid.md); kTwoSteps does not chase its high points, each of which the growth cap then cuts
enum class StepControl { kThisStep = 0, kTwoSteps = 1 };

// the largest accepted FlowParams::cfl: the split VOF advection stays bounded up to it (vof_advection.h)
constexpr double kMaxFlowCfl = 0.5;

// parameters of the flow, constant while stepping (SI units)
struct FlowParams {
  Medium medium;               // water, air and gravity (medium.h); shared with the stones by a Coupler
  double cfl = 0.5;            // target advective Courant number (pore velocity) [-], (0, kMaxFlowCfl], 0.5
  double max_dt = 0.01;        // largest time step [s], 0.01
  // first step [s] (from rest the velocity terms impose no limit yet), 1e-3: a gravity wave of a
  // 0.5 m deep flow, sqrt(g h) = 2.2 m/s, crosses 0.44 of a 5 mm cell in it
  double initial_dt = 1e-3;
  // growth limit of the step [-]: dt <= max_dt_growth * the last step, 1.2 (range [1, 10])
  double max_dt_growth = 1.2;
  double min_dt = 1e-8;        // a stable step below this [s] is a failure (velocity blow-up), 1e-8
  double k1 = kPaperK1;        // linear resistance coefficient of eq. (7) [-], > 0 (Ergun 150)
  double k2 = kPaperK2;        // quadratic resistance coefficient of eq. (7) [-], >= 0 (Ergun 1.75)
  double flume_width = 0.5;    // flume width B [m] dividing Q(t) into a discharge per unit width, 0.5 (the scenes')
  PressureSolverKind pressure_solver = PressureSolverKind::kMultigridCG;  // projection solver (Eigen: reference)
  double pressure_tol = 1e-5;   // relative residual of the iterative pressure solve [-], > 0, 1e-5
  InletBoundary inlet = InletBoundary::kWall;          // left end (x = x0)
  // the discharge's spread over the inlet rows (inflow.h); kWaterFraction: the former profile
  InletProfile inlet_profile = InletProfile::kEquivalentDepth;
  OutletBoundary outlet = OutletBoundary::kFreeOverfall;  // right end (x = x0 + length)
  double tailwater_level = 0.0;                        // water level [m] at the right end for kTailwater
  TopBoundary top = TopBoundary::kOpen;                // top of the domain
  WallCondition walls = WallCondition::kSlip;          // bed and end walls
  ViscousScheme viscous_scheme = ViscousScheme::kImplicitVertical;  // kExplicit: the forward-Euler reference
  bool implicit_vertical() const { return viscous_scheme != ViscousScheme::kExplicit; }
  // the viscous step's bound (momentum.h): kEnergy, proven for kImplicitVertical, or kRowSum (cross
  // terms in, 2.25 times shorter in uniform water at dx / dz = 2.5). The other schemes always take
  // kRowSum: forward Euler of every stress has no looser bound, and the former splitting grows at it
  ViscousBound viscous_bound = ViscousBound::kEnergy;
  ViscousBound step_bound() const {
    return viscous_scheme == ViscousScheme::kImplicitVertical ? viscous_bound : ViscousBound::kRowSum;
  }
  // the viscous stresses in up to this many substeps of a flow step [-], [1, 64], 8: a step longer than
  // their explicit limit takes ceil(dt / limit) substeps of the viscous part alone (MomentumTerms), so
  // that limit binds the step only at this many times its value; 1: one explicit step
  int viscous_substeps = 8;
  CornerViscosity corner_viscosity = CornerViscosity::kHarmonic;    // kArithmetic: the plain mean
  MomentumTimeScheme time_scheme = MomentumTimeScheme::kAdamsBashforth2;  // convection; kEuler: first order
  StepControl step_control = StepControl::kThisStep;  // the advective limit of one step or the last two
  std::uint32_t flags = kFlowDefault;                  // FlowEffect bits
  KEpsilonParams turbulence;  // k-epsilon constants, wall roughness, inflow turbulence (kFlowTurbulence)

  // throws std::invalid_argument naming the first bad parameter
  void validate() const;
};

// each term's largest stable step [s] (infinity when the term imposes none)
struct FlowStableDt {
  double advective = 0;   // cfl * min over faces of h / |u / n| (pore velocity)
  double viscous = 0;     // viscous_substeps x the Gershgorin bound of the explicit stresses,
                          // ~ 1 / (4 nu_max (1/dx^2 + 1/dz^2)); with kImplicitVertical of the x-diffusion
                          // and cross terms only; with kImplicit none (infinity)
  double gravity = 0;     // cfl * sqrt(2 h_min / |g|): a cell crossed by a fall from rest
  double turbulence = 0;  // from the k-epsilon model when on
  double max_dt = 0;      // FlowParams::max_dt
  double growth = 0;      // initial_dt before the first step, then max_dt_growth * the last step
  int advective_cell = -1;   // the cell beside the face that binds the advective limit (-1: none)
  int turbulence_cell = -1;  // the cell that binds the k-epsilon limit (-1: none)
  int viscous_cell = -1;     // the cell beside the face that binds the viscous limit (-1: none)
  double min() const;
  // the name of the binding term ("advective", "viscous", "gravity", "turbulence", "max_dt", "growth")
  // and its cell (-1 where the term has no place)
  const char* binding(int* cell = nullptr) const;
};

// the whole state of a VOFGrid as one typed value (export_state / import_state): what a run needs to
// continue bit-for-bit. Copying it is a copy of arrays (a reused FlowState allocates nothing once sized)
struct FlowState {
  std::vector<double> face_u, face_w, cell_p, cell_F, cell_porosity, cell_stone_diameter, cell_nut;
  std::vector<double> face_x_solid_u, face_z_solid_w;
  // the Adams-Bashforth history: the last step's start velocities and its length [s] (0: none)
  std::vector<double> face_u_prev, face_w_prev;
  double prev_dt = 0.0;
  double time = 0.0, last_dt = 0.0;  // [s]
  double last_advective = 0.0;  // the advective limit the last step was measured under [s] (0: none)
  long long step_count = 0;
  double inlet_volume = 0.0, net_inflow_volume = 0.0, dilatation_volume = 0.0;  // [m^2]
  DischargeTable discharge;
  // the k-epsilon model (has_turbulence false: the model is kept as it is; has_roles false: its cell roles)
  bool has_turbulence = false, has_roles = false;
  std::vector<double> turbulence_k, turbulence_eps, turbulence_nut, turbulence_u_tau;
  std::vector<double> turbulence_face_x_wall_shear, turbulence_face_z_wall_shear, turbulence_role;
};

class VOFGrid {
 public:
  VOFGrid(const Grid2D& grid, const FlowParams& params);
  ~VOFGrid();
  VOFGrid(const VOFGrid&) = delete;
  VOFGrid& operator=(const VOFGrid&) = delete;

  const Grid2D& grid() const { return grid_; }
  const FlowParams& params() const { return params_; }
  // replaces the parameters between steps (checked)
  void set_params(const FlowParams& params);
  void set_discharge(const DischargeTable& table);
  const DischargeTable& discharge() const { return discharge_; }

  // ---- state (flat arrays; cells (nz, nx), x-faces (nz, nx + 1), z-faces (nz + 1, nx)) ----
  std::vector<double> face_u;               // superficial x-velocity [m/s] on x-faces
  std::vector<double> face_w;               // superficial z-velocity [m/s] on z-faces
  std::vector<double> cell_p;               // pressure [Pa] (0 at the open top)
  std::vector<double> cell_F;               // water fraction [-] in [0, 1]
  std::vector<double> cell_porosity;        // n [-] in [0, 1], 0 = solid; call update_face_porosity()
  std::vector<double> face_x_porosity;      // n_f on x-faces (derived: min of the two cells)
  std::vector<double> face_z_porosity;      // n_f on z-faces (derived)
  // D_sp of eq. (7) [m], > 0 where 0 < n < 1; 0 (none) until the stones or the scene give it: a porous
  // cell without one is refused by update_face_porosity
  std::vector<double> cell_stone_diameter;
  std::vector<double> cell_nut;             // eddy viscosity nu_t [m^2/s], 0 when turbulence is off
  // the k-epsilon model (its cell_k [m^2/s^2] and cell_eps [m^2/s^3]); advanced when kFlowTurbulence is on
  KEpsilonModel& turbulence() { return *turbulence_; }
  const KEpsilonModel& turbulence() const { return *turbulence_; }
  std::vector<double> face_x_solid_u;       // stones' x-velocity at x-faces [m/s], 0
  std::vector<double> face_z_solid_w;       // stones' z-velocity at z-faces [m/s], 0
  // the last step's start velocities u^{n-1}, w^{n-1} [m/s] and its length [s] (0: no history, the next
  // step is forward Euler), read by MomentumTimeScheme::kAdamsBashforth2; part of the state (checkpoints)
  std::vector<double> face_u_prev, face_w_prev;
  double prev_dt() const { return prev_dt_; }
  void set_prev_dt(double dt);
  // forgets the last step (the next one is forward Euler): after velocities were set by hand
  void clear_step_history() { prev_dt_ = 0.0; }

  // sets cell_porosity (size ncell, values in [0, 1]) and recomputes the face porosities.
  // displace = false (scene building): the new field is the reference, nothing flows.
  // displace = true (stones moved): the change dn since the last step is a source of the next step's
  // continuity equation, dn/dt + div u = 0, so the water a stone displaces flows away (F is kept; the
  // water volume sum(n F V) is conserved where the cells are full of water or of air). A cell that
  // turns solid or opens from solid takes no source.
  void set_porosity(const std::vector<double>& porosity, bool displace = false);
  // recomputes face_*_porosity and the face stone diameters from the cell arrays (after writing
  // cell_porosity or cell_stone_diameter directly); closes the faces of solid cells (u = 0);
  // displace as in set_porosity
  void update_face_porosity(bool displace = false);

  // ---- scene helpers (rectangles [x0, x1] x [z0, z1] in m; a cell belongs if its centre is inside) ----
  // F = 1 below `level` [m] (partial fraction in the cut row), 0 above
  void fill_water_below(double level);
  // F = 1 inside the rectangle (cells whose centre is inside), untouched elsewhere
  void fill_water_box(double x0, double x1, double z0, double z1, double value = 1.0);
  // porosity n and stone diameter d [m] inside the rectangle; n = 0 makes solid cells
  void set_porosity_box(double x0, double x1, double z0, double z1, double n, double d);
  // hydrostatic pressure from the water fraction, p = 0 at the top
  void set_hydrostatic_pressure();

  // ---- state ----
  // copies the whole state into s (its arrays reused: no allocation once sized)
  void export_state(FlowState& s) const;
  // throws std::invalid_argument naming the first entry of s that does not fit this grid
  void check_state(const FlowState& s) const;
  // restores a state of export_state() (checked first; a refused one changes nothing), written into
  // the arrays in place: the numpy views stay valid
  void import_state(const FlowState& s);

  // ---- time stepping ----
  double time() const { return time_; }
  void set_time(double t) { time_ = t; }
  long long step_count() const { return step_count_; }
  // restores the step counter (the split advection alternates its sweep order with it): restart only
  void set_step_count(long long n) { step_count_ = n; }
  // the last step [s] that the growth limit of stable_dt() starts from (0: none yet, initial_dt
  // applies); part of the state (checkpoints)
  double last_dt() const { return last_dt_; }
  void set_last_dt(double dt);
  // the advective limit [s] measured at the last step's start (0: none; StepControl::kTwoSteps takes the
  // smaller of it and the next step's); part of the state
  double last_advective() const { return last_advective_; }
  FlowStableDt stable_dt_terms() const;
  double stable_dt() const { return stable_dt_terms().min(); }
  // one step of dt [s] (stages: see the top of this file); throws std::runtime_error naming the stage,
  // the cell and the time after restoring the state of the step's start
  void step(double dt);
  // step() for a caller that restores the whole flow state itself (import_state) when the step throws,
  // as the coupler's guard does: the step's own snapshot then keeps only u^n and w^n (the AB2 history),
  // not the other fields of its start
  void step_guarded(double dt);
  // for a driver that steps in a loop and writes none of the flow's fields between its steps (advance(),
  // the coupler's advance()): on, the largest Courant rate measured at a step's end (its last check) is
  // the next step's advective limit instead of a second pass over the same faces (the same value); off
  // (the default, and whenever a caller may write through the views) every limit is measured afresh.
  // Switching it on forgets any rate measured before
  void reuse_step_end_courant(bool on);
  // steps of stable_dt() until time() reaches t_end [s], a step that breaches the CFL taken again
  // shorter (step_retry.h), the last interval split evenly (advance.h); returns the number of steps
  long long advance(double t_end);
  // steps advance() took again, shorter, since construction
  long long retried_steps() const { return retried_steps_; }

  // ---- diagnostics and coupling helpers ----
  // pore velocity U = u/n, W = w/n at cell centres [m/s] (0 in solid cells); sizes ncell
  void pore_velocity_at_cells(std::vector<double>& U, std::vector<double>& W) const;
  // pressure gradient dp/dx, dp/dz at cell centres [Pa/m] (central, one-sided at walls and solids)
  void pressure_gradient_at_cells(std::vector<double>& dpdx, std::vector<double>& dpdz) const;
  // the same two at the listed cells only (count indices into the cell arrays, repeats allowed): the
  // other entries of the ncell-sized outputs are left as they were (the coupler's stones' cells)
  void pore_velocity_at_cells(int count, const int* cells, std::vector<double>& U, std::vector<double>& W) const;
  void pressure_gradient_at_cells(int count, const int* cells, std::vector<double>& dpdx,
                                  std::vector<double>& dpdz) const;
  // water volume sum(n F V) per metre of flume width [m^2]
  double water_volume() const;
  // discharge per unit width [m^2/s] through x-face column i: the water the VOF advection carried
  // through it in the last step, divided by that step (exact: the water budget's own flux). Before the
  // first step, after a restart and without a free surface: sum of u dz F, F the upwind cell's fraction
  // (1 entering at the inlet), which reads several % high at a free-overfall brink
  double discharge_through(int i) const;
  // water volume per metre of width [m^2] that entered through the inlet since construction
  double inlet_volume() const { return inlet_volume_; }
  // restores the inlet volume counter (restart only)
  void set_inlet_volume(double v) { inlet_volume_ = v; }
  // water volume per metre of width [m^2] that entered through the domain's boundary faces minus what
  // left through them (inlet, outlet end, open top) since construction, summed from the VOF advection's
  // own fluxes: water_volume() - its start value equals this to round-off while the porosity is fixed
  double net_inflow_volume() const { return net_inflow_volume_; }
  // restores the net inflow counter (restart only)
  void set_net_inflow_volume(double v) { net_inflow_volume_ = v; }
  // water volume per metre of width [m^2] made by the advection's divergence correction since
  // construction: dt sum c div(u) V over the steps (vof_advection.h), zero for a divergence-free
  // velocity; with an iterative pressure solve, the water its residual divergence makes. With it the
  // budget closes to round-off while the porosity is fixed: water_volume() - start = net_inflow_volume()
  // + dilatation_volume()
  double dilatation_volume() const { return dilatation_volume_; }
  // restores the dilatation counter (restart only)
  void set_dilatation_volume(double v) { dilatation_volume_ = v; }
  // inlet discharge per unit width now [m^2/s]
  double inlet_discharge_per_width() const;

  StageProfile& profile() { return profile_; }
  const StageProfile& profile() const { return profile_; }
  const PressureSolveStats& last_pressure_stats() const { return pressure_stats_; }
  // multigrid-CG solves that did not converge and were redone by the direct solver, since construction
  long long pressure_fallbacks() const { return pressure_fallbacks_; }
  // CG iterations of every pressure solve since construction (a fallback counts max_iterations); over the
  // pressure stage's calls (profile) the iterations per solve, which should not grow with the grid
  long long pressure_iterations() const { return pressure_iterations_; }

 private:
  struct Snapshot;
  void check_sizes() const;
  void update_phase_properties() const;
  void stage_advect_vof(double dt);
  double dilatation(double dt) const;  // the water of the last advection's divergence correction [m^2]
  void stage_momentum(double dt);
  // viscous substeps of a step of dt [s]: ceil(dt / explicit limit), at most params.viscous_substeps
  int viscous_substeps(double dt) const;
  void stage_porous_resistance(double dt);
  void stage_turbulence(double dt);
  // pore velocity and pressure gradient of cell c into the four values (unchanged in a solid cell)
  void pore_velocity_at(int c, double& U, double& W) const;
  void pressure_gradient_at(int c, double& dpdx, double& dpdz) const;
  void stage_pressure(double dt);
  void solve_pressure_directly(const std::string& why);
  void stage_correct();
  void stage_checks(double dt);
  // fails with a CflBreach where the velocities cross more than one cell in dt [s]: at the step's start
  // (stage "step") or at its end (the new velocities)
  void check_cfl(const char* stage, double dt);
  // inlet face velocities of Q(t) into u (face_u or u*)
  void apply_inlet(double t, std::vector<double>& u);
  MomentumFields momentum_fields() const;
  MomentumBoundary momentum_boundary() const;
  ProjectionFields projection_fields() const;
  ProjectionBoundary projection_boundary() const;
  // kind: 0 = cell, 1 = x-face, 2 = z-face
  void check_finite(const char* stage, const char* name, const std::vector<double>& a, int kind);
  // courant > 0: a CFL breach, thrown as CflBreach (a shorter step may pass)
  [[noreturn]] void fail(const std::string& stage, const std::string& what, int kind, int index, double courant = 0.0);
  void save_state();
  void restore_state();
  bool guarded_ = false;  // within step_guarded(): save_state() / restore_state() leave the fields to the caller
  // largest directional Courant number |u| dt / (n_f h) and where it is (kind 1 = x-face, 2 = z-face)
  double max_cfl(double dt, int& kind, int& index) const;

  Grid2D grid_;
  FlowParams params_;
  DischargeTable discharge_;
  double time_ = 0.0;
  long long step_count_ = 0;
  double last_dt_ = 0.0;  // see last_dt()
  double last_advective_ = 0.0;  // see last_advective()
  // the advective limit stable_dt_terms() measured and the step it was measured for: step() keeps it
  struct AdvectiveSeen {
    long long step = -1;
    double limit = 0.0;
  };
  mutable AdvectiveSeen advective_seen_;
  long long retried_steps_ = 0;  // see retried_steps()
  double prev_dt_ = 0.0;  // see prev_dt()
  std::vector<double> face_u_ext_, face_w_ext_;  // the extrapolated velocities of AB2
  double inlet_volume_ = 0.0;
  double net_inflow_volume_ = 0.0;
  double dilatation_volume_ = 0.0;
  double flux_dt_ = 0.0;  // the step whose VOF fluxes vof_scratch_ holds [s] (0: none)

  // derived per step
  // phase properties from F (caches: refreshed by const queries too)
  mutable std::vector<double> cell_rho_, cell_mu_, cell_mu_eddy_;
  mutable std::vector<double> face_x_rho_, face_z_rho_;
  std::vector<double> face_x_diameter_, face_z_diameter_;
  std::vector<double> face_x_beta_, face_z_beta_;  // dt n / (rho (1 + dt n R')) of the projection
  mutable std::vector<double> inlet_u_;  // inlet velocities (also read by stable_dt_terms)
  std::vector<double> inlet_dz_;
  MomentumScratch momentum_scratch_;
  std::vector<double> u_star_, w_star_;
  std::vector<double> rhs_;
  PressureProblem problem_;
  std::unique_ptr<PressureSolver> solver_;
  PressureSolveStats pressure_stats_;
  long long pressure_iterations_ = 0;
  std::unique_ptr<PressureSolver> fallback_solver_;  // the direct solver, made on the first fallback
  long long pressure_fallbacks_ = 0;
  VofBoundaryInflow vof_inflow_;
  VofScratch vof_scratch_;
  std::unique_ptr<Snapshot> snapshot_;
  std::unique_ptr<KEpsilonModel> turbulence_;
  mutable std::vector<double> cell_nu_;     // molecular kinematic viscosity of the cell mixture [m^2/s]
  mutable std::vector<double> dt_scratch_;  // work array of stable_dt_terms()
  // the explicit viscous limit [s] stable_dt_terms() found, and the step count it was found at (the
  // momentum stage's substeps reuse it within that step; -1: none)
  mutable double viscous_limit_ = 0.0;
  mutable long long viscous_limit_step_ = -1;
  mutable std::vector<double> cfl_row_;     // each row's largest Courant number, rows per thread (max_cfl)
  // max_cfl(1.0) at the end of the step that made step_count_ = step (see reuse_step_end_courant)
  struct StepEndCourant {
    long long step = -1;
    double rate = 0.0;
    int kind = 0, index = -1;
  };
  StepEndCourant step_end_courant_;
  bool reuse_step_end_courant_ = false;
  std::vector<double> cell_porosity_prev_;   // porosity of the last step (the reference of dn)
  void make_turbulence_model();
  const std::vector<double>& turbulence_cells_F() const;

  StageProfile profile_;
  int st_advect_, st_momentum_, st_porous_, st_turbulence_, st_pressure_, st_correct_, st_checks_;
};

// VOFGrid::reuse_step_end_courant on for its lifetime (a driver's loop; none: nothing), off after it
class StepEndCourantReuse {
 public:
  explicit StepEndCourantReuse(VOFGrid* flow) : flow_(flow) {
    if (flow_) flow_->reuse_step_end_courant(true);
  }
  ~StepEndCourantReuse() {
    if (flow_) flow_->reuse_step_end_courant(false);
  }
  StepEndCourantReuse(const StepEndCourantReuse&) = delete;
  StepEndCourantReuse& operator=(const StepEndCourantReuse&) = delete;

 private:
  VOFGrid* flow_;
};

}  // namespace vofdem
