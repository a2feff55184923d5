// Two-way VOF-DEM coupling of the flow (VOFGrid) and the stones (DEMSystem): seed paper sections 2.2
// and 2.4, eqs. (8)-(18).
//
//   stones -> flow:  n = (A_f + A_s n_exp) / (A_f + A_s)                                     (11)
//                    porous resistance R on u - n u_s (u_s: the stones' velocity, optional)    (5)-(7)
//   flow -> stones:  F_x, F_z of eqs. (8)-(9) = drag + pressure-gradient force F_S, the drag either
//                    the single-sphere drag (16)-(18) (the paper's, default) or the bed drag, the
//                    reaction of the porous resistance (5)-(7) on the stones (bed_drag.h)
//                    buoyancy and added mass through the DEM's wet fraction w (eq. 9)
//
// One coupling step of dt [s] runs these stages in this order, each timed into profile() and each
// skipped when its effect is off or has nothing to act on:
//   1. "porosity"      stones -> cell and face porosity (exact disc or polygon areas, or the paper's lookup
//                      table for discs),
//                      water volume n F V kept per cell (water_redistribution.h), stones' velocity at
//                      the faces for the relative-velocity resistance
//   2. "fluid_forces"  pore velocity and pressure gradient averaged over each stone's cells
//                      (fluid_forces.h) -> stone_force_drag, stone_force_pressure, stone_wet, stone_force_ext
//   3. "dem"           the stones advance by dt in substeps of their own step (DEMParams::dt, 1e-4 s)
//   4. "fluid"         the flow advances by dt (VOF advection, momentum, porous resistance, projection)
//   5. "checks"        non-finite forces or stone state -> std::runtime_error
// With kCoupleOverflowLoad, "overflow_load" times the overflow load inside stage 2 (the stones' protrusion,
// the approach band's sample, F_D + F_L; overflow_load.h) and its reaction on the flow's faces before stage 4;
// without the flag it does not run and is not in the profile.
// With CouplerParams::mapping = kKernel, "kernel" times the smoothing (kernel_smoothing.h) inside stages 1
// and 2 (their times include it); with kCell (the default) it does not run and is not in the profile.
// and before them "snapshot", the copy of the state that a failing stage restores (coupled scenes only);
// "stable_dt" times each call of stable_dt() (every module's limits, before each step of advance()).
// The pressure-gradient force is held over the DEM substeps of a step (exchange once per fluid step);
// the drag is linearised in the stone's velocity at the exchange and integrated implicitly by the DEM
// (drag_exchange.h), or held too (CouplerParams::implicit_drag = false).
//
// Time step: stable_dt() = min(fluid's stable step, max_dt, a stone crossing at most stone_cfl of a cell
// in each direction (dx along x, the smallest row height along z); a held drag also drag_relaxation x
// the drag relaxation time of the lightest stone).
// The DEM's own stable step bounds its substeps, not the exchange step.
//
// Guards: a failure in any stage (non-finite value, CFL breach, ...) restores the state of the start of
// the step (fluid, stones, porosity, forces) and throws std::runtime_error naming the stage, the stone
// or cell and the time. advance() takes a step whose flow breaches the CFL again, shorter (step_retry.h). The snapshot is taken only when both modules are stepped; a scene with one
// module relies on that module's own restore and pays nothing extra. Within advance() (no progress
// callback) the snapshot is taken every few steps only, up to max_snapshot_interval: a failing step
// restores the last snapshot and takes the steps since then again, with the same steps and the same
// state between them (the run is deterministic), so the state restored is the same to the bit as with
// a snapshot every step. The interval doubles after each one without a failure and falls back to 1 at
// a failure; a retried step thus replays at most the steps of one interval.
//
// Settling in still water (settle(), before the first step; coupler_settle.cpp): the stones alone step in
// the flow's water as it stands, each loaded by its weight less its buoyancy (eq. 9),
//   F_z = -(rho_s - w rho_w) V g,   w the stone's wet fraction in the still water (wet_fraction.h),
// w measured once by the force stage's own sampling (only kCoupleWetFraction: no drag, no pressure
// gradient) and followed over the substeps through the level it implies; the flow frozen, the coupler's
// time kept (the stones' own clock runs). It ends when every free stone has been slower than rest_speed
// for `hold` seconds (the weir packing's criterion, weir_packing.h) or at max_time; the stones' state and
// contact springs stay for the run. Timed as the stage "settle" (added at its first call).
//
// Reference: S. Maeno and A. Tomita (2008), Destruction prediction of a rubble mound weir using a
// VOF-DEM coupled model, ICHE 2008, Nagoya.
#pragma once

#include <cstdint>
#include <functional>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "vofdem/stones/dem_system.h"
#include "vofdem/coupling/bed_drag.h"
#include "vofdem/coupling/drag.h"
#include "vofdem/coupling/kernel_smoothing.h"
#include "vofdem/coupling/overflow_load.h"
#include "vofdem/coupling/porosity_map.h"
#include "vofdem/common/profile.h"
#include "vofdem/flow/vof_grid.h"
#include "vofdem/flow/water_redistribution.h"

namespace vofdem {

// effects of the coupling, one bit each (CouplerParams::flags)
enum CouplerEffect : unsigned {
  kCoupleDEM = 1u << 0,               // step the stones
  kCoupleFluid = 1u << 1,             // step the flow (off: a frozen flow field still acts on the stones)
  kCouplePorosity = 1u << 2,          // two-way feedback: the porosity (and water volume) follows the stones
  kCoupleDrag = 1u << 3,              // drag on the stones, eqs. (16)-(18)
  kCouplePressureGradient = 1u << 4,  // F_S = -V (grad p - rho_w F g) on the stones
  // 1u << 5 retired: the porous resistance on the velocity relative to the stones is the flow's own
  // effect (kFlowRelativeVelocity), owned by FlowParams::flags; the coupler maps the stones' velocity
  // to the faces whenever that flag is on
  kCoupleWetFraction = 1u << 6,       // stone_wet from the water fraction (buoyancy, added mass); off: w kept
  kCoupleChecks = 1u << 7,            // non-finite forces / stone state checked every step
  kCoupleLookupPorosity = 1u << 8,    // porosity from the paper's lookup table instead of exact disc areas
  kCoupleDisplaceFlow = 1u << 9,      // porosity changes drive the flow (dn/dt + div u = 0 in the flow's projection,
                                      // F kept) instead of moving the displaced water by volume
  kCoupleOverflowLoad = 1u << 10,     // drag and lift of the overflow on the stones' exposed parts, the reaction
                                      // taken from the flow (overflow_load.h); not in the defaults
  kCoupleForces = kCoupleDrag | kCouplePressureGradient,
  kCoupleOneWay = kCoupleDEM | kCoupleFluid | kCoupleForces | kCoupleWetFraction | kCoupleChecks,
  kCoupleTwoWay = kCoupleOneWay | kCouplePorosity,
  kCoupleDefault = kCoupleTwoWay,
};

// the drag on the stones (CouplerParams::stone_drag); one of the two, never both (that would count
// the drag twice)
enum class StoneDragModel {
  kSphere = 0,  // single sphere in the pore velocity, eqs. (16)-(18) (the paper's)
  kBed = 1,     // reaction of the flow's porous resistance, rho n R per bulk volume (bed_drag.h)
};

// how the stones and the flow exchange cell fields (CouplerParams::mapping), validated in validate()
enum class CouplingMapping {
  kCell = 0,    // each stone's exact footprint over the raw cells (the paper's; the default)
  kKernel = 1,  // the footprints and the flow smoothed by a Gaussian of physical width (kernel_smoothing.h)
};

// parameters of the coupling, constant while stepping (SI units)
struct CouplerParams {
  unsigned flags = kCoupleDefault;        // CouplerEffect bits
  double n_exp = 0.41;                    // packing porosity of the stones, eq. (11) [-]; 0.41 in the paper
  int lookup_m = 8;                       // sub-areas per side of the lookup table [-]; 8 (2 .. 64)
  double lookup_dr = 5e-4;                // radius spacing of the lookup tables [m]; 5e-4
  DragLaw drag_law = DragLaw::kPaper;     // C_D = 0.4 + 24/Re (paper) or Schiller-Naumann (sphere drag)
  StoneDragModel stone_drag = StoneDragModel::kSphere;  // drag model of kCoupleDrag; kSphere (paper)
  double max_dt = 0.01;                   // largest exchange step [s]; 0.01 (sets the step without water)
  // a stone moves at most this fraction of a cell per step, along x of dx, along z of the smallest dz [-]; 0.5
  double stone_cfl = 0.5;
  // the drag linearised in each stone's velocity and integrated implicitly by the DEM (drag_exchange.h):
  // stable for any exchange step; false: held over the step, bounded by drag_relaxation
  bool implicit_drag = true;
  double drag_relaxation = 0.5;           // held drag: step at most this fraction of its relaxation time [-]; 0.5
  double min_dt = 1e-7;                   // a stable step below this is a failure [s]; 1e-7
  // a stone whose measured wet fraction is within this of 1 (of 0) is taken as under water (in the air)
  // [-], [0, 0.5]; 1e-6 (wet_fraction.h: traces of air under water; 0: every measured value is followed)
  double wet_fraction_tolerance = 1e-6;
  // within advance(), the guard's snapshot is taken at most this many steps apart [steps], [1, 4096];
  // 32 (1: every step). A copy costs about 5 % of a flow step on the weir scenes; a failure replays up to this many
  int max_snapshot_interval = 32;
  // kKernel: the solid fraction the flow sees is the smoothed sum of the stones' footprints, n = 1 -
  // (1 - n_exp) S(a_s / A) floored at n_exp; a stone sees the smoothed flow over its footprint; the bed
  // drag is the smoothed reaction of the flow's resistance. kCell (default): the paper's cell-wise mapping
  CouplingMapping mapping = CouplingMapping::kCell;
  // kKernel: the Gaussian's width b in exp(-r^2/b^2) [m], (0, 1], sigma = b / sqrt(2); 0 = unset: 1.0 x
  // the stones' mean nominal diameter
  double bandwidth = 0.0;
  // kCoupleOverflowLoad: C_D, C_L and the approach band's height (overflow_load.h; the scene's
  // numerics.overflow_*): drag_coefficient (0, 5] [-], 0.91; lift_coefficient [0, 5] [-], 0.178;
  // band_height (0, 5] stone diameters, 1
  OverflowLoadParams overflow;

  // throws std::invalid_argument naming the first bad parameter
  void validate() const;
};

// the stones' settling in still water before the first step (Coupler::settle), SI units
struct SettleParams {
  double max_time = 5.0;     // simulated settling time allowed [s], (0, 600]; 5
  double rest_speed = 1e-3;  // at rest below this speed of every free stone, spin times radius included [m/s],
                             // (0, 1]; 1e-3 (the packing's WeirSpec::rest_speed)
  double hold = 0.2;         // ... for this long [s], [0, 10]; 0.2
  double chunk = 0.01;       // the speed is checked every chunk of simulated time [s], (0, 1]; 0.01
  // throws std::invalid_argument naming the first bad parameter
  void validate() const;
};

// what a settling did
struct SettleReport {
  double time = 0.0;       // simulated time the stones stepped [s]
  double max_speed = 0.0;  // the largest free stone's speed at its end [m/s]
  bool rested = false;     // ended by the rest criterion (false: at max_time, or nothing to settle)
};

// the whole coupled state as one typed value: the flow's, the stones' and the coupler's own (time,
// the exchanged forces, the base porosity). Copying it is a copy of arrays (a reused CouplerState
// allocates nothing once sized): the guard's snapshot, and a user's branch point
struct CouplerState {
  FlowState fluid;   // unused without a fluid
  DEMState stones;   // unused without stones
  double time = 0.0;  // [s]
  long long steps = 0;
  bool mapped = false;
  double redistributed = 0.0;  // [m^2]
  std::vector<double> stone_force_drag, stone_force_pressure, stone_relative_speed;
  bool has_drag_slope = false;  // the bed drag's slopes (false: zero)
  std::vector<double> stone_drag_slope;
  std::vector<double> cell_base_porosity, cell_base_diameter;
};

class Coupler {
 public:
  // couples `fluid` and `stones` (either may be null: a scene without water or without stones); both
  // must outlive the coupler. The porosity of the fluid at construction is kept as the base porosity
  // (walls, fixed porous zones) that the stones' porosity is combined with (the smaller one wins).
  // With both, the flow's medium (water, gravity) is handed to the stones, submerged (medium.h); so
  // again before every step if either was changed since. The flow's flags are the flow's own.
  Coupler(VOFGrid* fluid, DEMSystem* stones, const CouplerParams& params);
  Coupler(const Coupler&) = delete;
  Coupler& operator=(const Coupler&) = delete;

  VOFGrid* fluid() { return fluid_; }
  DEMSystem* stones() { return stones_; }
  const CouplerParams& params() const { return params_; }
  // replaces the parameters after checking them (a refused set changes nothing): the porosity mapper
  // follows them (the flow's flags are the flow's own)
  void set_params(const CouplerParams& params);
  int n() const { return n_; }

  // ---- time stepping ----
  double time() const { return time_; }
  long long step_count() const { return steps_; }
  double stable_dt();
  // steps of advance() bound by each limit: the fluid's terms ("advective", "viscous", "gravity",
  // "turbulence", "max_dt", "growth"), "stone_cfl", "drag_relaxation", "coupler_max_dt", "t_end" (a step
  // cut to reach the end time), "cfl_retry" (a step taken again, shorter: step_retry.h); and per term
  // the steps bound in each cell (ncell counts; the cell of the binding face, k-epsilon cell or stone
  // centre; empty without a fluid). A diagnostic: not part of the checkpoint, cleared by
  // clear_step_limits()
  const std::map<std::string, long long>& step_limits() const { return limit_steps_; }
  // steps taken again from the guard's snapshot after a failure (advance(): see max_snapshot_interval)
  long long replayed_steps() const { return replayed_steps_; }
  const std::map<std::string, std::vector<long long>>& step_limit_cells() const { return limit_cells_; }
  void clear_step_limits();
  // one coupling step of stable_dt() / of dt [s]
  void step();
  void step(double dt);
  // steps of stable_dt() until time() reaches t_end [s] (the loop of advance.h, shared with
  // VOFGrid::advance); returns the number of steps. progress (optional) is called
  // after every step with the time [s] (C++ callers; the Python front polls time between calls)
  long long advance(double t_end, const std::function<void(double)>& progress = nullptr);

  // the stones settle in the still water before the first step (header comment): the DEM alone steps,
  // buoyant by the water each stone sits in, until rest or max_time. Nothing to do (a report of zeros)
  // without stones or with kCoupleDEM off; a held system does not move. The flow's porosity follows the
  // settled stones at update_porosity() or the first step's mapping. Throws std::invalid_argument for
  // bad parameters, std::runtime_error if the DEM fails (its state restored by the DEM)
  SettleReport settle(const SettleParams& p = SettleParams());

  // inflow hydrograph Q(t): times [s] (increasing), discharge Q [m^3/s] (forwarded to the fluid)
  void set_inflow_table(const std::vector<double>& times, const std::vector<double>& discharge);
  // maps the stones onto the porosity now (the first step does it too). keep_water_volume: true keeps
  // n F V per cell (displaced water moves to neighbours, as while stepping); false keeps F, so the pores
  // of stones placed into a filled scene hold water and the volume drops by the stones' share (scene set-up)
  void update_porosity(bool keep_water_volume = true);
  // recomputes the fluid forces now (stone_force_drag, stone_force_pressure, stone_wet, stone_force_ext)
  void update_fluid_forces();
  // the fluid's water volume sum(n F V) per unit width [m^2] (0 without fluid)
  double water_volume() const;
  // water moved between cells by the redistribution, accumulated [m^2]
  double redistributed_volume() const { return redistributed_; }

  // ---- whole state (fluid fields, stones, contact histories, time, hydrograph, forces) ----
  // typed: copied into s (its arrays reused); restored (every part checked first: a refused state
  // changes nothing), written into the arrays in place (the numpy views stay valid)
  void export_state(CouplerState& s) const;
  void import_state(const CouplerState& s);
  // the checkpoint: the same state as named flat arrays ("coupler/...", "fluid/...", "turbulence/...",
  // "dem/..."); entries added since are optional on import, with what older runs had
  std::map<std::string, std::vector<double>> export_state() const;
  void import_state(const std::map<std::string, std::vector<double>>& state);

  // wall-clock seconds and calls per coupled stage; cpu_profile() the same stages' CPU seconds, the process's
  // (all threads), which a machine shared with other work leaves unchanged (coupler_stage.h). Reset apart
  StageProfile& profile() { return profile_; }
  StageProfile& cpu_profile() { return cpu_profile_; }

  // ---- kernel mapping (CouplerParams::mapping = kKernel) ----
  // the smoothing operator (null with kCell or without fluid or stones) and its width b [m]
  const KernelSmoother* kernel() const { return kernel_.get(); }
  double kernel_bandwidth() const { return kernel_ ? kernel_->params().bandwidth : 0.0; }
  // the solid area [m^2 per unit width] the porosity floor n >= n_exp removed at the last mapping (0 when
  // the smoothed solid fraction never exceeds the packing's): the solid volume the flow does not see
  double floored_solid_area() const { return floored_solid_area_; }

  // ---- state arrays ----
  std::vector<double> stone_force_drag;      // drag on each stone (sphere or bed drag) [N], 2n (x, z)
  std::vector<double> stone_force_pressure;  // pressure-gradient force on each stone [N], 2n
  // kCoupleOverflowLoad: the overflow's drag and lift on each stone [N], 2n (x, z), its exposed share phi
  // of the projected area [-], n, and the reaction per cell [N per metre of flume width], 2 ncell (x, z),
  // the sum over the cells times B equal to minus the stones' sum; zeros while the effect is off (not in
  // the checkpoint: recomputed at each exchange)
  std::vector<double> stone_force_overflow;
  std::vector<double> stone_exposed_share;
  std::vector<double> cell_overflow_reaction;
  std::vector<double> cell_base_porosity;   // porosity without the stones [-], ncell (from the fluid at construction)
  std::vector<double> cell_base_diameter;   // stone diameter of the base porosity [m], ncell

 private:
  void share_medium();
  void check_params(const CouplerParams& p) const;
  // stable_dt() and which limit binds (term, cell: -1 where it has no place)
  double stable_dt_limits(const char** term, int* cell);
  void count_limit(const char* term, int cell);
  int stone_cell(int j) const;  // the cell of stone j's centre (-1 outside the grid)
  void make_mapper();
  void make_kernel();
  void deposit_stones();
  void smooth_solid();
  void smooth_flow(bool bed, const BedDragParams& bp);
  void smooth_area_field(std::vector<double>& v);
  DragForce kernel_bed_drag(int j, double* slope) const;
  void stage_porosity(bool keep_water_volume = true);
  void stage_fluid_forces();
  void stage_fluid_forces(unsigned flags);  // with these effects instead of params_.flags
  void overflow_loads(double rho);
  void apply_overflow_reaction(double dt);
  std::string non_finite_cell(int count, const int* cells) const;
  // with both force effects off: zeroes the fluid forces the stones still hold (once, on the switch)
  void clear_fluid_forces();
  void stage_dem(double dt);
  void stage_fluid(double dt);
  void stage_checks();
  void solid_velocity_at_faces();
  void map_stones();
  void save();
  // back to the state at the start of the step being taken: the snapshot, then the steps since it again
  void restore();
  void replay();
  // the stages of one step (step() without the guard's bookkeeping)
  void run_stages(double dt);
  // the state without what no step changes (the base porosity and diameter): the guard's copy
  void export_state(CouplerState& s, bool with_base) const;
  void import_state(const CouplerState& s, bool with_base);
  // courant > 0: a CFL breach, thrown as CflBreach (a shorter step may pass)
  [[noreturn]] void fail(const std::string& stage, const std::string& what, double courant = 0.0);
  bool has_fluid() const { return fluid_ != nullptr; }
  bool has_stones() const { return stones_ != nullptr && n_ > 0; }

  VOFGrid* fluid_;
  DEMSystem* stones_;
  CouplerParams params_;
  int n_ = 0;
  double time_ = 0.0;
  long long steps_ = 0;
  bool mapped_ = false;  // the porosity reflects the stones (needed again only if they move)
  bool forces_applied_ = false;  // stone_force_ext holds fluid forces (cleared when the effects go off)
  double redistributed_ = 0.0;

  std::unique_ptr<PorosityMapper> mapper_;
  std::unique_ptr<WaterRedistribution> redistribution_;
  CouplerState snapshot_;  // state at the start of the step (guards), or of the first of replay_
  bool snapshot_valid_ = false;
  // the steps since the snapshot, the one being taken last: its dt [s] (NaN while it runs) and the
  // flow's last_dt at its start [s] (the advance loop sets it between steps)
  struct ReplayStep {
    double dt, fluid_last_dt;
  };
  std::vector<ReplayStep> replay_;
  bool sparse_snapshots_ = false;  // within advance() without a progress callback
  class SparseSnapshots {  // sparse_snapshots_ on for advance()'s lifetime
   public:
    SparseSnapshots(Coupler& c, bool on);
    ~SparseSnapshots();
    SparseSnapshots(const SparseSnapshots&) = delete;
    SparseSnapshots& operator=(const SparseSnapshots&) = delete;

   private:
    Coupler& c_;
  };
  bool replaying_ = false;
  long long replayed_steps_ = 0;
  int snapshot_interval_ = 1;  // [steps], doubles up to max_snapshot_interval
  bool csr_current_ = false;  // the mapper's per-stone cell lists match the stones' positions
  // scratch (sized at construction)
  std::vector<double> stone_x_, stone_z_;
  std::vector<double> n_old_;  // the flow's porosity before the porosity stage
  std::vector<double> cell_U_, cell_W_, cell_dpdx_, cell_dpdz_;
  std::vector<double> stone_vrel_;  // relative speed |U - u_p| of each stone at the last exchange [m/s]
  std::vector<double> stone_drag_slope_;  // |dF / du_p| of each stone's drag at the last exchange [N s/m]
  std::vector<double> cell_solid_sum_, cell_solid_u_, cell_solid_w_, cell_diam_sum_;
  // kernel mapping: the operator, its porosity, the smoothed water fraction, the bed drag's smoothed
  // densities (x, z, slope per unit stone volume and water density), sized by make_kernel()
  std::unique_ptr<KernelSmoother> kernel_;
  bool kernel_solid_current_ = false;  // cell_solid_* hold this step's smoothed deposit
  double floored_solid_area_ = 0.0;
  std::vector<double> cell_kernel_porosity_, cell_kernel_F_, cell_bed_x_, cell_bed_z_, cell_bed_slope_;

  std::map<std::string, long long> limit_steps_;
  std::map<std::string, std::vector<long long>> limit_cells_;

  StageProfile profile_, cpu_profile_;
  int st_snapshot_, st_porosity_, st_forces_, st_dem_, st_fluid_, st_checks_, st_stable_dt_;
  int st_kernel_ = -1;  // added with the first kernel
  int st_overflow_ = -1;  // added with the first overflow load
  int st_settle_ = -1;    // added with the first settle()
  int add_stage(const std::string& name);  // to both profiles, at the same index
  // the overflow load's scratch: each stone's extents, the approach bands' cells (CSR) and weights l_c F_c,
  // the pore velocity at them; the reaction waits for the step's dt
  std::vector<StoneExtent> stone_extent_;
  std::vector<std::uint8_t> stone_active_u8_;
  std::vector<int> band_offsets_, band_cells_;
  std::vector<double> band_weights_, band_U_, band_W_;
  bool overflow_pending_ = false;
};

}  // namespace vofdem
