// Standard k-epsilon turbulence model with log-law wall functions, in the porosity-weighted form of
// the seed paper's flow equations (1)-(4): it supplies nu_t for nu_e = nu + nu_t and k for the
// -2/3 dk/dx, -2/3 dk/dz terms of eqs. (2)-(3).
//
//   n dk/dt   + u.grad k   = div(n (nu + nu_t/sigma_k)   grad k)   + n (P - eps)                  (K)
//   n deps/dt + u.grad eps = div(n (nu + nu_t/sigma_eps) grad eps) + n eps/k (C1 P - C2 eps)      (E)
//   nu_t = C_mu k^2 / eps,   P = nu_t S^2,   S^2 = 2 (dU/dx)^2 + 2 (dW/dz)^2 + (dU/dz + dW/dx)^2
//
// Production options (KEpsilonParams::production, production_limit), standard remedies of the
// overproduction of k where the strain is irrotational (stagnation point of a plunging jet):
//   Kato-Launder:  P = nu_t S Omega,  Omega = |dU/dz - dW/dx|   (Kato & Launder 1993)
//   limiter:       P <= production_limit * eps                  (Menter 1994: 10)
// and, in porous cells, the cross derivatives of the pore velocity from each neighbour's own pore velocity
// (default), from the superficial velocities over the cell's own porosity, or from the pore velocities
// over a porosity filtered on a physical length (KEpsilonParams::pore_strain)
//
// n is the cell porosity [-], u = (u, w) the superficial (mesh-averaged) velocity [m/s] of the flow
// solver's faces and U = u / n the pore velocity [m/s] whose strain rate S [1/s] produces k. The
// advection term is written in advective form u.grad k = div(u k) - k div u, equal to the
// conservative form for the divergence-free u of eq. (1) and bounded when it is not exactly so.
// In porous cells (0 < n < 1) the same model is used with the porosity weighting above and the pore
// velocity strain; no extra porous production or dissipation term is added (such closures, e.g.
// Nakayama & Kuwahara 1999, are not part of the seed paper's model).
//
// Discretisation (cell-centred k, eps on the MAC grid of grid.h): first-order upwind advection,
// central diffusion with the face conductance of the two half cells in series (harmonic mean of
// n (nu + nu_t/sigma)), backward Euler in time with the
// sinks linearised (Patankar): the eps sink of (K) is (eps/k)^old k^new and that of (E) is
// C2 (eps/k)^old eps^new; production uses the nu_t of the start of the step. Each equation is
// advanced by a predictor and `sweeps` Jacobi sweeps of the backward-Euler system. In a cell whose
// explicit limit dt sum(a) <= n holds (a: upwind-inflow and diffusion coefficients of its faces),
// the predictor is explicit in transport and implicit in the sink; elsewhere it is the local
// source/sink balance alone. Both keep a uniform decaying field exactly, the first also a steady
// state. Every pass is a convex combination of positive values plus a non-negative source, so k
// and eps stay positive and bounded for any dt. For dt below stable_dt() the scheme is first-order
// accurate in time; above it transport between cells lags (more sweeps approach the fully
// implicit solution) but the solution stays positive and bounded.
//
// Walls (bed, end walls, faces of solid cells n = 0) use the standard log-law wall function
// (Launder & Spalding 1974): in a water cell next to a wall, at distance y from it (half the cell
// size), the tangential pore velocity U_t fixes the shear velocity u_tau through
//   U_t / u_tau = (1/kappa) ln(y / z0),  z0 = nu / (E u_tau) + k_s / 30    (log law, smooth to rough:
//                                                                         Christoffersen & Jonsson 1985)
//   U_t / u_tau = y u_tau / nu                                              (viscous sublayer)
// taking the larger u_tau of the two (the composite law U+ = min(y+, log law)). The cell's values are
// then fixed at k = u_tau^2 / sqrt(C_mu), eps = u_tau^3 / (kappa y), so nu_t = kappa u_tau y; in a
// corner the wall giving the larger eps is kept. The kinematic wall shear stress -u_tau^2 U_t/|U_t|
// [m^2/s^2] is written on each wall face for the momentum equation.
//
// Free surface and air: cells with water fraction F < params.water_fraction_min are not solved:
// they hold k = k_min, eps = eps_min, nu_t = 0 (no eddy viscosity in air), and the faces between
// them and water cells carry no flux (zero gradient at the free surface). The flow solver should
// evaluate the -2/3 grad k term between water cells only.
//
// References: B. E. Launder and D. B. Spalding (1974), Comput. Methods Appl. Mech. Eng. 3, 269-289;
// W. Rodi (1993), Turbulence models and their application in hydraulics, IAHR; J. B. Christoffersen
// and I. G. Jonsson (1985), Ocean Eng. 12, 387-423; S. V. Patankar (1980), Numerical heat transfer
// and fluid flow; S. Maeno and A. Tomita (2008), ICHE 2008 (seed paper, eqs. (2)-(3)).
#pragma once

#include <cstdint>
#include <vector>

#include "vofdem/common/grid.h"
#include "vofdem/common/profile.h"

namespace vofdem {

// effect flags of the model; a cleared bit removes that term and skips its stage
enum KEpsilonFlag : unsigned {
  kKEpsAdvection = 1u << 0,      // u.grad k, u.grad eps
  kKEpsDiffusion = 1u << 1,      // div(n (nu + nu_t/sigma) grad .)
  kKEpsProduction = 1u << 2,     // P and C1 eps/k P
  kKEpsWallFunctions = 1u << 3,  // log-law values in wall cells and the wall shear output
  kKEpsAll = 0xFu,
};

// what a side of the domain is for k and eps
enum class KEpsilonBoundary {
  kWall = 0,          // no-slip wall: wall functions in the adjacent cells, no flux
  kInflow = 1,        // where the flow enters: k, eps from the inflow intensity and length scale
                      // (advected and diffused in); where it leaves: zero gradient
  kZeroGradient = 2,  // outflow, open top, free surface, symmetry: no diffusive flux, upwind outflow
};

struct KEpsilonBoundaries {
  KEpsilonBoundary left = KEpsilonBoundary::kInflow;
  KEpsilonBoundary right = KEpsilonBoundary::kZeroGradient;
  KEpsilonBoundary bottom = KEpsilonBoundary::kWall;
  KEpsilonBoundary top = KEpsilonBoundary::kZeroGradient;
};

// time stepping of the transport (KEpsilonParams::time_scheme)
enum class KEpsilonTimeScheme {
  // predictor (explicit transport where dt sum(a) <= n) and `sweeps` Jacobi sweeps of the backward-Euler
  // system; stable_dt() is the explicit limit of all four faces
  kPointImplicit = 0,
  // backward Euler along each column (vertical advection and diffusion, sinks) by one tridiagonal solve
  // per column, the horizontal faces explicit (lagged-implicit in a cell above their own limit);
  // stable_dt() is the explicit limit of the horizontal faces only (k_epsilon_lines.cpp)
  kVerticalLines = 1,
  // backward Euler of the whole system approximately factored into alternating lines, in delta form:
  // each row's tridiagonal system (horizontal faces), then each column's (vertical faces); stable for
  // any dt, a steady state and a uniform decay kept exactly, k and eps kept at their floors.
  // stable_dt() is the horizontal advection's limit alone: no diffusion limit, which grows as 1/dx^2
  // with the grid and with nu_t (k_epsilon_lines.cpp)
  kAlternatingLines = 2,
};

// which velocity's cross derivatives dU/dz, dW/dx enter the strain S of the production
enum class KEpsilonPoreStrain {
  // each neighbour's own pore velocity u / n_neighbour: across a jump of porosity (a cell inside a stone
  // next to open water) the difference is the jump of 1/n, not a shear of the flow
  kNeighbours = 0,
  // the neighbours' superficial velocities over this cell's porosity, (u_a - u_b) / (n dz), as the
  // normal derivatives dU/dx = du/(n dx) already are: no strain from the porosity's jumps, but a small n
  // of its own amplifies the shear next to a stone (runs away in 4 of 16 Maeno packings: docs/k_epsilon.md)
  kLocal = 1,
  // each neighbour's pore velocity u / n_f over n_f, the porosity averaged over a box of side
  // pore_filter_length around the cell (the averaging volume of the volume-averaged equations, e.g. one
  // stone diameter; solid cells n = 0 left out): a jump of porosity within the box is no strain, and the
  // strain does not grow as the grid resolves the stones (docs/k_epsilon.md)
  kFiltered = 2,
};

// production term of k (and through C1 P of eps)
enum class KEpsilonProduction {
  kStrain = 0,       // P = nu_t S^2 (standard)
  kKatoLaunder = 1,  // P = nu_t S Omega: vanishes in irrotational strain (stagnation points)
};

// model constants and numerical settings, constant while stepping (Launder & Spalding 1974 values)
struct KEpsilonParams {
  double c_mu = 0.09;      // [-] eddy viscosity constant, usual 0.09
  double c1 = 1.44;        // [-] production constant of eps, usual 1.44
  double c2 = 1.92;        // [-] dissipation constant of eps, usual 1.92 (> 1)
  double sigma_k = 1.0;    // [-] turbulent Prandtl number of k, usual 1.0
  double sigma_eps = 1.3;  // [-] turbulent Prandtl number of eps, usual 1.3
  double kappa = 0.41;     // [-] von Karman constant, usual 0.41
  double log_law_e = 9.8;  // [-] smooth-wall log-law constant E, usual 9.8 (B = ln(E)/kappa = 5.57;
                           //     B = 5.2 is E = 8.43)
  double bed_roughness = 0.0;   // [m] equivalent sand roughness k_s of the bottom boundary, 0 = smooth;
                                //     e.g. 2-3 d50 of a gravel bed
  double wall_roughness = 0.0;  // [m] k_s of the end walls, the top (if a wall) and solid cells, 0 = smooth
  double k_min = 1e-10;    // [m^2/s^2] floor of k, usual 1e-10
  double eps_min = 1e-12;  // [m^2/s^3] floor of eps, usual 1e-12 (nu_t = C_mu k_min^2/eps_min ~ 1e-9)
  double nut_max_ratio = 1e5;  // [-] cap of nu_t / nu, usual 1e5
  double inflow_intensity = 0.05;     // [-] turbulence intensity I at an inflow: k = 1.5 (I |U|)^2; usual 0.02-0.1
  double inflow_length_scale = 0.01;  // [m] length scale L at an inflow: eps = C_mu^0.75 k^1.5 / L;
                                      //     usual 0.07 x hydraulic diameter (~0.1 x depth)
  double water_fraction_min = 0.1;  // [-] cells with F below this are air (not solved), usual 0.1
  int sweeps = 1;                   // [-] Jacobi sweeps after the predictor, in [0, 1000], usual 0-4
  double cfl = 0.5;                 // [-] safety factor of stable_dt(), in (0, 1], usual 0.5
  KEpsilonTimeScheme time_scheme = KEpsilonTimeScheme::kVerticalLines;  // columns implicit (the scenes')
  // kVerticalLines, kAlternatingLines: stable_dt() returns the horizontal faces' explicit limit (the
  // advection's alone with kAlternatingLines) (true) or none (false:
  // above that limit a cell's horizontal faces are lagged-implicit, k and eps stay positive and bounded
  // for any step, first order in time there); kPointImplicit always limits the step. False is not
  // accurate in the weir: nu_t runs to its cap and the upstream level rises (docs/k_epsilon.md)
  bool limit_step = true;
  unsigned flags = kKEpsAll;        // effect flags (KEpsilonFlag)
  KEpsilonProduction production = KEpsilonProduction::kStrain;  // kKatoLaunder: Kato & Launder (1993)
  double production_limit = 0.0;  // [-] P <= production_limit * eps, 0 = off; Menter (1994): 10
  KEpsilonPoreStrain pore_strain = KEpsilonPoreStrain::kNeighbours;  // kLocal, kFiltered: see there
  double pore_filter_length = 0.0;  // [m] side of kFiltered's averaging box (> 0 with kFiltered), e.g. d_50
};

// n_f: the porosity cell_porosity averaged over a box of side length [m] centred on each cell, each cell
// weighted by its area inside the box; cells of n = 0 (solid) are left out, and a solid cell's n_f is 0.
// work: the row sums (resized to 2 ncell; kept by a caller that filters every step)
void filter_porosity(const Grid2D& grid, const std::vector<double>& cell_porosity, double length,
                     std::vector<double>& out, std::vector<double>& work);

// refuses constants outside their physical ranges with std::invalid_argument naming them
void check_k_epsilon_params(const KEpsilonParams& params);

// shear velocity u_tau [m/s] of the composite wall law for tangential speed u_t >= 0 [m/s] at
// distance y > 0 [m] from a wall of roughness ks >= 0 [m], kinematic viscosity nu > 0 [m^2/s];
// no argument checks (an inner-loop function); u_t that is not > 0 gives 0
double wall_shear_velocity(double u_t, double y, double nu, double ks, double kappa, double log_law_e);

class KEpsilonModel {
 public:
  KEpsilonModel(const Grid2D& grid, const KEpsilonParams& params = {}, const KEpsilonBoundaries& boundaries = {});

  // sets k [m^2/s^2] and eps [m^2/s^3] uniformly (floored) and nu_t = C_mu k^2/eps (capped with nu [m^2/s])
  void initialize(double k, double eps, double nu);

  // advances k and eps by dt [s], then nu_t. face_u (nface_x), face_w (nface_z): superficial
  // velocities [m/s]; cell_porosity (ncell): n in [0, 1], 0 = solid; cell_F (ncell): water fraction
  // in [0, 1], or empty for all water; cell_nu (ncell): molecular kinematic viscosity [m^2/s].
  // Throws std::invalid_argument on wrong sizes or dt <= 0, and std::runtime_error naming the cell
  // and the time if k, eps or nu_t became non-finite (the state before the step is then restored).
  void step(double dt, const std::vector<double>& face_u, const std::vector<double>& face_w,
            const std::vector<double>& cell_porosity, const std::vector<double>& cell_F,
            const std::vector<double>& cell_nu);

  // the explicit advection-diffusion limit [s] times params.cfl for these fields and the current
  // nu_t (kVerticalLines: of the horizontal faces only); dt above it stays positive and bounded but
  // transports k, eps less accurately. cell (optional) receives the binding cell (-1: none)
  double stable_dt(const std::vector<double>& face_u, const std::vector<double>& face_w,
                   const std::vector<double>& cell_porosity, const std::vector<double>& cell_F,
                   const std::vector<double>& cell_nu, int* cell = nullptr) const;

  // k, eps of an inflow face with pore speed u_in [m/s] (floored)
  double inflow_k(double u_in) const;
  double inflow_eps(double u_in) const;

  const Grid2D& grid() const { return grid_; }
  const KEpsilonParams& params() const { return params_; }
  const KEpsilonBoundaries& boundaries() const { return boundaries_; }
  // switches effects on/off (KEpsilonFlag bits); switching wall functions off zeroes the wall outputs
  void set_flags(unsigned flags);
  // the role of each cell in the last step [-] (0 inactive, 1 solved, 2 wall-fixed), ncell: a checkpoint
  // holds it, since the next step starts a cell that has just filled from its neighbours
  std::vector<double> cell_roles() const;
  void cell_roles(std::vector<double>& out) const;  // into out (its storage reused)
  // the production P [m^2/s^3] of each cell in the last step (0 where not solved), ncell
  const std::vector<double>& cell_production() const { return cell_prod_; }
  // sets those roles (values 0, 1, 2; ncell of them), as cell_roles() gave them
  void set_cell_roles(const std::vector<double>& roles);
  const StageProfile& profile() const { return profile_; }
  StageProfile& profile() { return profile_; }

  // state: what a step writes (sizes fixed at construction)
  std::vector<double> cell_k;    // turbulent kinetic energy [m^2/s^2], ncell
  std::vector<double> cell_eps;  // its dissipation rate [m^2/s^3], ncell
  std::vector<double> cell_nut;  // eddy viscosity [m^2/s], ncell; 0 in air and solid cells
  // wall outputs of the last step (zero away from walls or with wall functions off)
  std::vector<double> cell_u_tau;         // shear velocity [m/s] of wall cells (largest-eps wall), ncell
  std::vector<double> face_x_wall_shear;  // kinematic wall shear [m^2/s^2] on wall x-faces, z component
                                          // acting on the fluid cell beside the face, nface_x
  std::vector<double> face_z_wall_shear;  // kinematic wall shear [m^2/s^2] on wall z-faces, x component
                                          // acting on the fluid cell beside the face, nface_z
  double time = 0.0;  // model time [s], advanced by each successful step

 private:
  // per-cell role of the last step
  enum : std::uint8_t { kInactive = 0, kSolved = 1, kWallFixed = 2 };
  // one face of a solved cell: neighbour (-1: a boundary), coefficients per unit volume for k and eps
  // [1/s] (upwind inflow + diffusion), pore speed of an inflow boundary face [m/s]
  struct FaceCoef {
    int nb;
    double a[2];
    double inflow_u;
  };
  // one row of the backward-Euler system: x_c = (num + sum a x_nb) / den (a = 0, nb = c on closed faces)
  struct JacobiRow {
    int c;
    int nb[4];
    double a[4];
    double num, den;
  };

  void check_sizes(const std::vector<double>& face_u, const std::vector<double>& face_w,
                   const std::vector<double>& cell_porosity, const std::vector<double>& cell_F,
                   const std::vector<double>& cell_nu) const;
  void classify_cells(const std::vector<double>& cell_porosity, const std::vector<double>& cell_F);
  void compute_production(const std::vector<double>& face_u, const std::vector<double>& face_w,
                          const std::vector<double>& cell_porosity);
  void apply_wall_functions(const std::vector<double>& face_u, const std::vector<double>& face_w,
                            const std::vector<double>& cell_porosity, const std::vector<double>& cell_nu);
  bool is_active(int c, const std::vector<double>& cell_porosity, const std::vector<double>& cell_F) const {
    return cell_porosity[c] > 0.0 && (cell_F.empty() || cell_F[c] >= params_.water_fraction_min);
  }
  // half-cell diffusion resistances of the active cells for face_coefficients (0.5 dx / cond, 0.5 dz / cond;
  // x_only: the first alone)
  void half_cell_resistances(const std::vector<double>& cell_porosity, const std::vector<double>& cell_F,
                             const std::vector<double>& cell_nu, bool x_only = false) const;
  bool is_wall_face(int i, int k, int di, int dk, const std::vector<double>& cell_porosity) const;
  // coefficients (per unit volume) of the 4 faces of cell (i, k) (west, east, south, north), for k and
  // for eps; x_only: the first two alone
  void face_coefficients(int i, int k, const std::vector<double>& face_u,
                         const std::vector<double>& face_w, const std::vector<double>& cell_porosity,
                         const std::vector<double>& cell_F, const std::vector<double>& cell_nu, FaceCoef* out,
                         bool x_only = false) const;
  // the values of k, eps at the step's start into scratch_, scratch_eps_: air/solid cells at the floors,
  // wall cells at the wall-law values, solved cells at cell_k, cell_eps (the old value, or a freshly
  // wetted cell's start)
  void start_values();
  // a solved cell's linearised source and sink of (K) (index 0) and (E) (index 1), with the time scale
  // eps/k of the step's start and the production P of this step (0 with production off):
  // source {P, C1 (eps/k) P} [m^2/s^3, m^2/s^4], sink {eps/k, C2 eps/k} [1/s] (the rate of x^new)
  struct SourceSink {
    double source[2];
    double sink[2];
  };
  SourceSink source_sink(int c, bool prod_on) const;
  void solve_transport(double dt, const std::vector<double>& face_u, const std::vector<double>& face_w,
                       const std::vector<double>& cell_porosity, const std::vector<double>& cell_F,
                       const std::vector<double>& cell_nu);
  // kVerticalLines: the column systems of k and eps, solved by the Thomas algorithm
  void solve_transport_lines(double dt, const std::vector<double>& face_u, const std::vector<double>& face_w,
                             const std::vector<double>& cell_porosity, const std::vector<double>& cell_F,
                             const std::vector<double>& cell_nu);
  // kAlternatingLines: the row systems, then the column systems of k and eps
  void solve_transport_alternating(double dt, const std::vector<double>& face_u, const std::vector<double>& face_w,
                                   const std::vector<double>& cell_porosity, const std::vector<double>& cell_F,
                                   const std::vector<double>& cell_nu);
  // kVerticalLines: stable_dt()'s largest rate [1/s] (cfl / dt) and its first cell (-1: none), from the
  // half-cell resistances of this call
  // (diffusion false: the advection's rates alone, kAlternatingLines)
  double lines_stable_rate(const std::vector<double>& face_u, const std::vector<double>& cell_porosity,
                           const std::vector<double>& cell_F, int& cell, bool diffusion = true) const;
  // passes 1..sweeps of the Jacobi iteration; the last pass writes target
  void jacobi_sweeps(const std::vector<JacobiRow>& rows, double floor, std::vector<double>& target,
                     std::vector<double>& scratch) const;
  void update_eddy_viscosity(const std::vector<double>& cell_nu);
  void check_finite(double t);

  Grid2D grid_;
  KEpsilonParams params_;
  KEpsilonBoundaries boundaries_;
  StageProfile profile_;
  int stage_setup_, stage_wall_, stage_production_, stage_transport_, stage_viscosity_, stage_check_;

  // work arrays, allocated at construction
  std::vector<std::uint8_t> cell_role_, cell_role_prev_;
  std::vector<double> cell_prod_;             // P [m^2/s^3]
  std::vector<double> pore_n_, pore_work_;    // kFiltered: the filtered porosity n_f [-], its row sums
  std::vector<double> k_old_, eps_old_, nut_old_;  // state before the step (restored on failure)
  std::vector<double> wall_k_, wall_eps_;     // wall-function values of wall cells
  std::vector<double> scratch_, scratch_eps_;  // Jacobi buffers of k and eps
  std::vector<JacobiRow> rows_k_, rows_eps_;   // the systems of the solved cells, reused by the sweeps
  std::vector<double> tri_[2][4];              // kVerticalLines: sub, diagonal, super, rhs of k and eps
  std::vector<double> row_pass_[2];            // kAlternatingLines: the row systems' solutions y of k and eps
  // half a cell over its conductance n (nu + nu_t / sigma) [s/m], along x and along z, for k and for eps
  mutable std::vector<double> half_res_x_[2], half_res_z_[2];
  // the rows' largest rates, then per thread one row's rates, active cells and faces' conductances of k
  // and eps (lines_stable_rate)
  mutable std::vector<double> row_rate_;
};

}  // namespace vofdem
