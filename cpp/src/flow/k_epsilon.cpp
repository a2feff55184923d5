#include "vofdem/flow/k_epsilon.h"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

#include "common/parallel.h"
#include "vofdem/common/check.h"

namespace vofdem {

namespace {

bool has(unsigned flags, unsigned bit) { return (flags & bit) != 0u; }

void require_size(const char* name, std::size_t size, int expected, bool allow_empty = false) {
  if (allow_empty && size == 0) return;
  if (size != static_cast<std::size_t>(expected))
    throw std::invalid_argument(std::string(name) + " has size " + std::to_string(size) + ", expected " +
                                std::to_string(expected) + (allow_empty ? " (or 0)" : ""));
}

std::string cell_name(const Grid2D& g, int c) {
  return "cell (i=" + std::to_string(c % g.nx()) + ", k=" + std::to_string(c / g.nx()) + ")";
}

}  // namespace

void check_k_epsilon_params(const KEpsilonParams& p) {
  require_positive("c_mu", p.c_mu);
  require_positive("c1", p.c1);
  if (!(std::isfinite(p.c2) && p.c2 > 1.0))
    throw std::invalid_argument("c2 = " + format_value(p.c2) + " is outside the allowed range (1, inf)");
  require_positive("sigma_k", p.sigma_k);
  require_positive("sigma_eps", p.sigma_eps);
  require_positive("kappa", p.kappa);
  if (!(std::isfinite(p.log_law_e) && p.log_law_e > 1.0))
    throw std::invalid_argument("log_law_e = " + format_value(p.log_law_e) + " is outside the allowed range (1, inf)");
  require_non_negative("bed_roughness", p.bed_roughness);
  require_non_negative("wall_roughness", p.wall_roughness);
  require_positive("k_min", p.k_min);
  require_positive("eps_min", p.eps_min);
  require_positive("nut_max_ratio", p.nut_max_ratio);
  require_non_negative("inflow_intensity", p.inflow_intensity);
  require_positive("inflow_length_scale", p.inflow_length_scale);
  require_in_closed("water_fraction_min", p.water_fraction_min, 0.0, 1.0);
  if (p.sweeps < 0 || p.sweeps > 1000)
    throw std::invalid_argument("sweeps = " + std::to_string(p.sweeps) + " is outside the allowed range [0, 1000]");
  require_in_open_closed("cfl", p.cfl, 0.0, 1.0);
  require_non_negative("production_limit", p.production_limit);
  const int form = static_cast<int>(p.pore_strain);
  if (form < 0 || form > 2)
    throw std::invalid_argument("pore_strain = " + std::to_string(form) +
                                " is outside the allowed values {0 (kNeighbours), 1 (kLocal), 2 (kFiltered)}");
  require_non_negative("pore_filter_length", p.pore_filter_length);
  if (p.pore_strain == KEpsilonPoreStrain::kFiltered && !(p.pore_filter_length > 0.0))
    throw std::invalid_argument("pore_filter_length = " + format_value(p.pore_filter_length) +
                                " is outside the allowed range (0, inf) with pore_strain kFiltered");
  const int scheme = static_cast<int>(p.time_scheme);
  if (scheme < 0 || scheme > 2)
    throw std::invalid_argument("time_scheme = " + std::to_string(scheme) +
                                " is outside the allowed values {0 (kPointImplicit), 1 (kVerticalLines), "
                                "2 (kAlternatingLines)}");
  if (!p.limit_step && p.time_scheme == KEpsilonTimeScheme::kPointImplicit)
    throw std::invalid_argument("limit_step = false needs time_scheme kVerticalLines or kAlternatingLines: the "
                                "point-implicit scheme's step is bounded by all four faces");
}

double wall_shear_velocity(double u_t, double y, double nu, double ks, double kappa, double log_law_e) {
  if (!(u_t > 0.0)) return 0.0;
  // viscous sublayer: u_t = u_tau^2 y / nu
  const double u_lin = std::sqrt(nu * u_t / y);
  // log law u_t = u_tau/kappa ln(y/z0(u_tau)) by Newton from the sublayer value; ln(y/z0) is kept
  // >= 1 so that a cell inside the roughness (y < e z0) still gets a finite, positive u_tau
  double u = u_lin;
  for (int it = 0; it < 60; ++it) {
    const double z0 = nu / (log_law_e * u) + ks / 30.0;
    double lg = std::log(y / z0);
    double dlg = nu / (log_law_e * u * u) / z0;  // d ln(y/z0) / du_tau
    if (lg < 1.0) {
      lg = 1.0;
      dlg = 0.0;
    }
    const double h = u * lg - kappa * u_t;
    double next = u - h / (lg + u * dlg);
    if (!(next > 0.0)) next = 0.5 * u;
    const bool done = std::abs(next - u) <= 1e-13 * u;
    u = next;
    if (done) break;
  }
  // composite law U+ = min(y+, log law): the larger shear velocity of the two branches
  return std::max(u, u_lin);
}

namespace {
// length [m] of the overlap of [a0, a1] and [b0, b1]
double overlap(double a0, double a1, double b0, double b1) {
  return std::max(0.0, std::min(a1, b1) - std::max(a0, b0));
}
}  // namespace

void filter_porosity(const Grid2D& g, const std::vector<double>& n, double length, std::vector<double>& out,
                     std::vector<double>& work) {
  const int nx = g.nx(), nz = g.nz();
  const double dx = g.dx(), half = 0.5 * length;
  // separable: along x the sums of n and of the weights (cell width inside the box, solid cells 0), then
  // along z the same with the cell heights inside the box
  work.assign(2 * n.size(), 0.0);
  double* sum_n = work.data();
  double* sum_w = work.data() + n.size();
  const int hx = static_cast<int>(std::ceil(half / dx + 0.5));
  detail::parallel_for(nz, nx * (2 * hx + 1), [&, dx, half](int k0, int k1) {
    for (int k = k0; k < k1; ++k)
      for (int i = 0; i < nx; ++i)
        for (int o = std::max(-hx, -i); o <= std::min(hx, nx - 1 - i); ++o) {
          const double nn = n[g.cell(i + o, k)];
          const double w = nn > 0.0 ? overlap((o - 0.5) * dx, (o + 0.5) * dx, -half, half) : 0.0;
          sum_n[g.cell(i, k)] += w * nn;
          sum_w[g.cell(i, k)] += w;
        }
  });
  out.assign(n.size(), 0.0);
  detail::parallel_for(nz, nx * 4, [&, half](int k0, int k1) {
    for (int k = k0; k < k1; ++k) {
      const double z0 = g.z_center(k) - half, z1 = g.z_center(k) + half;
      int lo = k, hi = k;
      while (lo > 0 && g.z_face(lo) > z0) --lo;
      while (hi < nz - 1 && g.z_face(hi + 1) < z1) ++hi;
      for (int i = 0; i < nx; ++i) {
        if (!(n[g.cell(i, k)] > 0.0)) continue;
        double num = 0.0, den = 0.0;
        for (int kk = lo; kk <= hi; ++kk) {
          const double w = overlap(g.z_face(kk), g.z_face(kk + 1), z0, z1);
          num += w * sum_n[g.cell(i, kk)];
          den += w * sum_w[g.cell(i, kk)];
        }
        out[g.cell(i, k)] = num / den;
      }
    }
  });
}

// one face of a cell: coefficients a [1/s] per unit volume of advection-in plus diffusion for k
// (a[0], sigma_k) and eps (a[1], sigma_eps), the neighbour cell, or -1 for a boundary face whose
// value comes from the inflow pore speed inflow_u [m/s]
KEpsilonModel::KEpsilonModel(const Grid2D& grid, const KEpsilonParams& params, const KEpsilonBoundaries& boundaries)
    : grid_(grid), params_(params), boundaries_(boundaries) {
  check_k_epsilon_params(params_);
  const int n = grid_.ncell();
  cell_k.assign(n, params_.k_min);
  cell_eps.assign(n, params_.eps_min);
  cell_nut.assign(n, 0.0);
  cell_u_tau.assign(n, 0.0);
  face_x_wall_shear.assign(grid_.nface_x(), 0.0);
  face_z_wall_shear.assign(grid_.nface_z(), 0.0);
  cell_role_.assign(n, kSolved);
  cell_role_prev_.assign(n, kSolved);
  cell_prod_.assign(n, 0.0);
  k_old_.assign(n, 0.0);
  eps_old_.assign(n, 0.0);
  nut_old_.assign(n, 0.0);
  wall_k_.assign(n, 0.0);
  wall_eps_.assign(n, 0.0);
  scratch_.assign(n, 0.0);
  scratch_eps_.assign(n, 0.0);
  rows_k_.reserve(n);
  rows_eps_.reserve(n);
  for (int e = 0; e < 2; ++e) half_res_x_[e].assign(n, 0.0), half_res_z_[e].assign(n, 0.0);
  stage_setup_ = profile_.add_stage("k-eps setup");
  stage_wall_ = profile_.add_stage("k-eps wall functions");
  stage_production_ = profile_.add_stage("k-eps production");
  stage_transport_ = profile_.add_stage("k-eps transport");
  stage_viscosity_ = profile_.add_stage("k-eps eddy viscosity");
  stage_check_ = profile_.add_stage("k-eps checks");
}

void KEpsilonModel::initialize(double k, double eps, double nu) {
  require_non_negative("k", k);
  require_non_negative("eps", eps);
  require_positive("nu", nu);
  const double kk = std::max(k, params_.k_min), ee = std::max(eps, params_.eps_min);
  std::fill(cell_k.begin(), cell_k.end(), kk);
  std::fill(cell_eps.begin(), cell_eps.end(), ee);
  std::fill(cell_nut.begin(), cell_nut.end(), std::min(params_.c_mu * kk * kk / ee, params_.nut_max_ratio * nu));
  std::fill(cell_role_prev_.begin(), cell_role_prev_.end(), kSolved);
}

std::vector<double> KEpsilonModel::cell_roles() const { return std::vector<double>(cell_role_.begin(), cell_role_.end()); }

void KEpsilonModel::cell_roles(std::vector<double>& out) const { out.assign(cell_role_.begin(), cell_role_.end()); }

void KEpsilonModel::set_cell_roles(const std::vector<double>& roles) {
  if (roles.size() != cell_role_.size())
    throw std::invalid_argument("cell roles: " + std::to_string(roles.size()) + " values, expected " +
                                std::to_string(cell_role_.size()) + " (one per cell)");
  for (double r : roles) require_in_closed("cell role", r, 0.0, 2.0);
  for (std::size_t c = 0; c < roles.size(); ++c) cell_role_[c] = static_cast<std::uint8_t>(roles[c]);
}

void KEpsilonModel::set_flags(unsigned flags) {
  params_.flags = flags;
  if (has(flags, kKEpsWallFunctions)) return;
  std::fill(cell_u_tau.begin(), cell_u_tau.end(), 0.0);
  std::fill(face_x_wall_shear.begin(), face_x_wall_shear.end(), 0.0);
  std::fill(face_z_wall_shear.begin(), face_z_wall_shear.end(), 0.0);
}

double KEpsilonModel::inflow_k(double u_in) const {
  const double iu = params_.inflow_intensity * std::abs(u_in);
  return std::max(1.5 * iu * iu, params_.k_min);
}

double KEpsilonModel::inflow_eps(double u_in) const {
  const double k = inflow_k(u_in);
  return std::max(std::pow(params_.c_mu, 0.75) * k * std::sqrt(k) / params_.inflow_length_scale, params_.eps_min);
}

void KEpsilonModel::check_sizes(const std::vector<double>& face_u, const std::vector<double>& face_w,
                                const std::vector<double>& cell_porosity, const std::vector<double>& cell_F,
                                const std::vector<double>& cell_nu) const {
  require_size("face_u", face_u.size(), grid_.nface_x());
  require_size("face_w", face_w.size(), grid_.nface_z());
  require_size("cell_porosity", cell_porosity.size(), grid_.ncell());
  require_size("cell_F", cell_F.size(), grid_.ncell(), true);
  require_size("cell_nu", cell_nu.size(), grid_.ncell());
}

void KEpsilonModel::half_cell_resistances(const std::vector<double>& cell_porosity, const std::vector<double>& cell_F,
                                          const std::vector<double>& cell_nu, bool x_only) const {
  if (!has(params_.flags, kKEpsDiffusion)) return;
  const double inv_sigma[2] = {1.0 / params_.sigma_k, 1.0 / params_.sigma_eps};
  const double half_x = 0.5 * grid_.dx();
  detail::parallel_for(grid_.nz(), grid_.nx(), [&, half_x, inv_sigma](int k0, int k1) {
    for (int k = k0; k < k1; ++k) {
      const double half_z = 0.5 * grid_.dz(k);
      for (int i = 0; i < grid_.nx(); ++i) {
        const int c = grid_.cell(i, k);
        if (!is_active(c, cell_porosity, cell_F)) continue;  // neither a solved cell nor a neighbour
        const double n = cell_porosity[c];
        for (int e = 0; e < 2; ++e) {
          const double cond = n * (cell_nu[c] + cell_nut[c] * inv_sigma[e]);
          half_res_x_[e][c] = half_x / cond;
          if (!x_only) half_res_z_[e][c] = half_z / cond;
        }
      }
    }
  });
}

void KEpsilonModel::classify_cells(const std::vector<double>& cell_porosity, const std::vector<double>& cell_F) {
  const int nx = grid_.nx(), nz = grid_.nz();
  detail::parallel_range(grid_.ncell(), [&](long long c0, long long c1) {
    for (int c = static_cast<int>(c0); c < c1; ++c)
      cell_role_[c] = is_active(c, cell_porosity, cell_F) ? kSolved : kInactive;
  });
  // a cell that just filled with water starts from the mean of its neighbours that held water (which
  // did not just fill: no cell reads a value this loop writes)
  detail::parallel_for(nz, nx, [&](int k0, int k1) {
    for (int k = k0; k < k1; ++k) {
      for (int i = 0; i < nx; ++i) {
        const int c = grid_.cell(i, k);
        if (cell_role_[c] == kInactive || cell_role_prev_[c] != kInactive) continue;
        double sk = 0.0, se = 0.0;
        int count = 0;
        const int nbs[4][2] = {{i - 1, k}, {i + 1, k}, {i, k - 1}, {i, k + 1}};
        for (const auto& nb : nbs) {
          if (nb[0] < 0 || nb[0] >= nx || nb[1] < 0 || nb[1] >= nz) continue;
          const int cn = grid_.cell(nb[0], nb[1]);
          if (cell_role_prev_[cn] == kInactive || cell_role_[cn] == kInactive) continue;
          sk += k_old_[cn];
          se += eps_old_[cn];
          ++count;
        }
        // the step starts from these values (also what a failed step leaves there)
        cell_k[c] = k_old_[c] = count ? sk / count : params_.k_min;
        cell_eps[c] = eps_old_[c] = count ? se / count : params_.eps_min;
      }
    }
  });
}

bool KEpsilonModel::is_wall_face(int i, int k, int di, int dk, const std::vector<double>& cell_porosity) const {
  const int in = i + di, kn = k + dk;
  if (in < 0) return boundaries_.left == KEpsilonBoundary::kWall;
  if (in >= grid_.nx()) return boundaries_.right == KEpsilonBoundary::kWall;
  if (kn < 0) return boundaries_.bottom == KEpsilonBoundary::kWall;
  if (kn >= grid_.nz()) return boundaries_.top == KEpsilonBoundary::kWall;
  return cell_porosity[grid_.cell(in, kn)] <= 0.0;
}

void KEpsilonModel::apply_wall_functions(const std::vector<double>& face_u, const std::vector<double>& face_w,
                                         const std::vector<double>& cell_porosity,
                                         const std::vector<double>& cell_nu) {
  const KEpsilonParams& p = params_;
  const double sqrt_cmu = std::sqrt(p.c_mu);
  std::fill(face_x_wall_shear.begin(), face_x_wall_shear.end(), 0.0);
  std::fill(face_z_wall_shear.begin(), face_z_wall_shear.end(), 0.0);
  std::fill(cell_u_tau.begin(), cell_u_tau.end(), 0.0);
  // a wall face is a side of the domain or a face of a solid cell: without solid cells only the cells
  // along the sides are visited (the same values; each cell writes its own faces)
  const int nx = grid_.nx(), nz = grid_.nz();
  bool solid = false;
  for (int c = 0; c < grid_.ncell(); ++c) solid |= cell_porosity[c] <= 0.0;
  // rows on the threads: a wall face belongs to the one fluid cell beside it
  detail::parallel_for(nz, nx, [&, sqrt_cmu](int k0, int k1) {
    for (int k = k0; k < k1; ++k) {
      // an inner row without solid cells: its two end cells
      const int step = solid || k == 0 || k == nz - 1 ? 1 : std::max(nx - 1, 1);
      for (int i = 0; i < nx; i += step) {
        const int c = grid_.cell(i, k);
        if (cell_role_[c] == kInactive) continue;
        const double n = cell_porosity[c];
        // tangential pore velocities: x along horizontal walls, z along vertical ones
        const double ut_h = 0.5 * (face_u[grid_.face_x(i, k)] + face_u[grid_.face_x(i + 1, k)]) / n;
        const double ut_v = 0.5 * (face_w[grid_.face_z(i, k)] + face_w[grid_.face_z(i, k + 1)]) / n;
        double best_eps = -1.0, best_k = 0.0, best_ut = 0.0;
        // (di, dk) of the four neighbours: west, east, south, north
        const int dirs[4][2] = {{-1, 0}, {1, 0}, {0, -1}, {0, 1}};
        for (const auto& d : dirs) {
          if (!is_wall_face(i, k, d[0], d[1], cell_porosity)) continue;
          const bool vertical_wall = d[0] != 0;
          const double y = 0.5 * (vertical_wall ? grid_.dx() : grid_.dz(k));
          const double ut = vertical_wall ? ut_v : ut_h;
          const double ks = (d[1] == -1 && k == 0) ? p.bed_roughness : p.wall_roughness;
          const double u_tau = wall_shear_velocity(std::abs(ut), y, cell_nu[c], ks, p.kappa, p.log_law_e);
          const double tau = ut > 0.0 ? -u_tau * u_tau : (ut < 0.0 ? u_tau * u_tau : 0.0);
          if (vertical_wall)
            face_x_wall_shear[grid_.face_x(d[0] < 0 ? i : i + 1, k)] = tau;
          else
            face_z_wall_shear[grid_.face_z(i, d[1] < 0 ? k : k + 1)] = tau;
          const double e = u_tau * u_tau * u_tau / (p.kappa * y);
          if (e > best_eps) {
            best_eps = e;
            best_k = u_tau * u_tau / sqrt_cmu;
            best_ut = u_tau;
          }
        }
        if (best_eps < 0.0) continue;
        cell_role_[c] = kWallFixed;
        wall_k_[c] = std::max(best_k, p.k_min);
        wall_eps_[c] = std::max(best_eps, p.eps_min);
        cell_u_tau[c] = best_ut;
      }
    }
  });
}

void KEpsilonModel::compute_production(const std::vector<double>& face_u, const std::vector<double>& face_w,
                                       const std::vector<double>& cell_porosity) {
  const int nx = grid_.nx(), nz = grid_.nz();
  const double dx = grid_.dx();
  const bool local = params_.pore_strain == KEpsilonPoreStrain::kLocal;
  // kFiltered: the neighbours' form over the porosity filtered on pore_filter_length
  const bool filtered = params_.pore_strain == KEpsilonPoreStrain::kFiltered;
  if (filtered) filter_porosity(grid_, cell_porosity, params_.pore_filter_length, pore_n_, pore_work_);
  const std::vector<double>& pn = filtered ? pore_n_ : cell_porosity;
  // a neighbour's centred velocity over its own porosity (kNeighbours) or over this cell's n (kLocal)
  auto uc = [&](int i, int k, double n) {
    return 0.5 * (face_u[grid_.face_x(i, k)] + face_u[grid_.face_x(i + 1, k)]) / (local ? n : pn[grid_.cell(i, k)]);
  };
  auto wc = [&](int i, int k, double n) {
    return 0.5 * (face_w[grid_.face_z(i, k)] + face_w[grid_.face_z(i, k + 1)]) / (local ? n : pn[grid_.cell(i, k)]);
  };
  auto usable = [&](int i, int k) { return i >= 0 && i < nx && k >= 0 && k < nz && cell_role_[grid_.cell(i, k)]; };
  detail::parallel_for(nz, nx, [&, dx](int k0, int k1) {
    for (int k = k0; k < k1; ++k) {
      for (int i = 0; i < nx; ++i) {
        const int c = grid_.cell(i, k);
        if (cell_role_[c] != kSolved) {
          cell_prod_[c] = 0.0;
          continue;
        }
        const double n = pn[c];
        const double dudx = (face_u[grid_.face_x(i + 1, k)] - face_u[grid_.face_x(i, k)]) / (n * dx);
        const double dwdz = (face_w[grid_.face_z(i, k + 1)] - face_w[grid_.face_z(i, k)]) / (n * grid_.dz(k));
        // cross derivatives from the centred pore velocities of neighbours holding water (one-sided at
        // walls, air and the domain edge)
        const bool s = usable(i, k - 1), nn = usable(i, k + 1), w = usable(i - 1, k), e = usable(i + 1, k);
        double dudz = 0.0, dwdx = 0.0;
        if (s || nn) {
          const int ka = nn ? k + 1 : k, kb = s ? k - 1 : k;
          dudz = (uc(i, ka, n) - uc(i, kb, n)) / (grid_.z_center(ka) - grid_.z_center(kb));
        }
        if (w || e) {
          const int ia = e ? i + 1 : i, ib = w ? i - 1 : i;
          dwdx = (wc(ia, k, n) - wc(ib, k, n)) / (dx * (ia - ib));
        }
        const double shear = dudz + dwdx;
        const double s2 = 2.0 * dudx * dudx + 2.0 * dwdz * dwdz + shear * shear;
        double prod = params_.production == KEpsilonProduction::kKatoLaunder
                          ? cell_nut[c] * std::sqrt(s2) * std::abs(dudz - dwdx)
                          : cell_nut[c] * s2;
        if (params_.production_limit > 0.0) prod = std::min(prod, params_.production_limit * cell_eps[c]);
        cell_prod_[c] = prod;
      }
    }
  });
}

void KEpsilonModel::face_coefficients(int i, int k, const std::vector<double>& face_u,
                                      const std::vector<double>& face_w, const std::vector<double>& cell_porosity,
                                      const std::vector<double>& cell_F, const std::vector<double>& cell_nu,
                                      FaceCoef* out, bool x_only) const {
  const unsigned flags = params_.flags;
  const bool adv = has(flags, kKEpsAdvection), dif = has(flags, kKEpsDiffusion);
  const double inv_sigma[2] = {1.0 / params_.sigma_k, 1.0 / params_.sigma_eps};
  const int c = grid_.cell(i, k);
  const double dx = grid_.dx(), dz = grid_.dz(k);
  const double n_p = cell_porosity[c];
  // per face: neighbour (in, kn), superficial velocity into the cell [m/s], cell length normal to it
  const double u_w = face_u[grid_.face_x(i, k)], u_e = face_u[grid_.face_x(i + 1, k)];
  const double w_s = face_w[grid_.face_z(i, k)], w_n = face_w[grid_.face_z(i, k + 1)];
  const int nbi[4] = {i - 1, i + 1, i, i};
  const int nbk[4] = {k, k, k - 1, k + 1};
  const double vin[4] = {u_w, -u_e, w_s, -w_n};
  const double len[4] = {dx, dx, dz, dz};
  const int nfaces = x_only ? 2 : 4;
  for (int f = 0; f < nfaces; ++f) {
    FaceCoef& o = out[f];
    o.nb = -1;
    o.a[0] = o.a[1] = 0.0;
    o.inflow_u = 0.0;
    const int in = nbi[f], kn = nbk[f];
    const bool inside = in >= 0 && in < grid_.nx() && kn >= 0 && kn < grid_.nz();
    if (inside) {
      const int cn = grid_.cell(in, kn);
      if (!is_active(cn, cell_porosity, cell_F)) continue;  // wall of a solid cell, or the free surface
      o.nb = cn;
      const double a_adv = adv ? std::max(vin[f], 0.0) / len[f] : 0.0;
      o.a[0] = o.a[1] = a_adv;
      if (dif) {
        // series resistance of the two half cells (Patankar's harmonic mean): exact for the flux
        // of the log layer's eps ~ 1/z with n (nu + nu_t/sigma) ~ z, on any z spacing
        for (int e = 0; e < 2; ++e) {
          const double* res = f < 2 ? half_res_x_[e].data() : half_res_z_[e].data();
          o.a[e] += 1.0 / (len[f] * (res[c] + res[cn]));
        }
      }
      continue;
    }
    const KEpsilonBoundary side = f == 0   ? boundaries_.left
                                  : f == 1 ? boundaries_.right
                                  : f == 2 ? boundaries_.bottom
                                           : boundaries_.top;
    // only an inflow side where the flow enters brings k, eps in; every other side is closed to them
    if (side != KEpsilonBoundary::kInflow || !(vin[f] > 0.0)) continue;
    o.inflow_u = vin[f] / n_p;
    for (int e = 0; e < 2; ++e) {
      if (adv) o.a[e] += vin[f] / len[f];
      if (dif) o.a[e] += n_p * (cell_nu[c] + cell_nut[c] * inv_sigma[e]) / (len[f] * 0.5 * len[f]);
    }
  }
}

void KEpsilonModel::start_values() {
  const KEpsilonParams& p = params_;
  detail::parallel_range(grid_.ncell(), [&](long long c0, long long c1) {
    for (long long c = c0; c < c1; ++c) {
      const std::uint8_t role = cell_role_[c];
      scratch_[c] = role == kInactive ? p.k_min : role == kWallFixed ? wall_k_[c] : cell_k[c];
      scratch_eps_[c] = role == kInactive ? p.eps_min : role == kWallFixed ? wall_eps_[c] : cell_eps[c];
    }
  });
}

KEpsilonModel::SourceSink KEpsilonModel::source_sink(int c, bool prod_on) const {
  const double rate = eps_old_[c] / k_old_[c];  // 1/s, > 0 by the floors
  const double prod = prod_on ? cell_prod_[c] : 0.0;
  return {{prod, params_.c1 * rate * prod}, {rate, params_.c2 * rate}};
}

void KEpsilonModel::solve_transport(double dt, const std::vector<double>& face_u, const std::vector<double>& face_w,
                                    const std::vector<double>& cell_porosity, const std::vector<double>& cell_F,
                                    const std::vector<double>& cell_nu) {
  const KEpsilonParams& p = params_;
  const bool prod_on = has(p.flags, kKEpsProduction);
  std::vector<double>* target[2] = {&cell_k, &cell_eps};
  std::vector<double>* scratch[2] = {&scratch_, &scratch_eps_};
  const std::vector<double>* old[2] = {&k_old_, &eps_old_};
  const double floor[2] = {p.k_min, p.eps_min};
  // values that no pass changes (air/solid and wall cells) and the starting values of solved cells,
  // in both buffers
  start_values();
  std::copy(scratch_.begin(), scratch_.end(), cell_k.begin());
  std::copy(scratch_eps_.begin(), scratch_eps_.end(), cell_eps.begin());
  // k and eps are independent within a step (both use the time scale eps/k and the production of
  // the old state), so one pass over the cells assembles both. Pass 0 is the predictor: below
  // the cell's explicit limit (dt sum(a) <= n), explicit transport with the implicit sink, which
  // keeps a uniform decaying field and a steady state exactly; above it, the local source/sink
  // balance alone (the uniform decay still exact). Passes 1..sweeps are Jacobi sweeps of the
  // backward-Euler system. Every pass is a convex combination of positive values plus a
  // non-negative source. Passes alternate between target and scratch; the last writes target.
  half_cell_resistances(cell_porosity, cell_F, cell_nu);
  rows_k_.clear();  // capacity ncell reserved at construction: no allocation here
  rows_eps_.clear();
  std::vector<JacobiRow>* rows[2] = {&rows_k_, &rows_eps_};
  const bool first_to_target = p.sweeps % 2 == 0;
  FaceCoef fc[4];
  for (int k = 0; k < grid_.nz(); ++k) {
    for (int i = 0; i < grid_.nx(); ++i) {
      const int c = grid_.cell(i, k);
      if (cell_role_[c] != kSolved) continue;
      face_coefficients(i, k, face_u, face_w, cell_porosity, cell_F, cell_nu, fc);
      const double n = cell_porosity[c];
      const SourceSink ss = source_sink(c, prod_on);
      const double* source = ss.source;
      const double* sink = ss.sink;
      for (int e = 0; e < 2; ++e) {
        const std::vector<double>& cur = first_to_target ? *scratch[e] : *target[e];
        std::vector<double>& dst = first_to_target ? *target[e] : *scratch[e];
        const double x_old = (*old[e])[c];
        const double num0 = n * x_old / dt + n * source[e];
        const double den0 = n / dt + n * sink[e];
        JacobiRow row{c, {c, c, c, c}, {0.0, 0.0, 0.0, 0.0}, num0, den0};
        double flux = 0.0, asum = 0.0;
        for (int f = 0; f < 4; ++f) {
          const double a = fc[f].a[e];
          if (a == 0.0) continue;
          if (fc[f].nb >= 0) {
            row.nb[f] = fc[f].nb;
            row.a[f] = a;
            flux += a * cur[fc[f].nb];
          } else {
            const double vin = e == 0 ? inflow_k(fc[f].inflow_u) : inflow_eps(fc[f].inflow_u);
            row.num += a * vin;
            flux += a * vin;
          }
          asum += a;
        }
        row.den += asum;
        // explicit transport is a convex combination only below the cell's explicit limit
        const double v = dt * asum <= n ? (num0 + flux - asum * x_old) / den0 : num0 / den0;
        dst[c] = std::max(v, floor[e]);
        if (p.sweeps > 0) rows[e]->push_back(row);
      }
    }
  }
  jacobi_sweeps(rows_k_, p.k_min, cell_k, scratch_);
  jacobi_sweeps(rows_eps_, p.eps_min, cell_eps, scratch_eps_);
}

void KEpsilonModel::jacobi_sweeps(const std::vector<JacobiRow>& rows, double floor, std::vector<double>& target,
                                  std::vector<double>& scratch) const {
  const int sweeps = params_.sweeps;
  for (int pass = 1; pass <= sweeps; ++pass) {
    const bool to_target = (sweeps - pass) % 2 == 0;
    std::vector<double>& dst = to_target ? target : scratch;
    const std::vector<double>& cur = to_target ? scratch : target;
    for (const JacobiRow& r : rows) {
      const double num =
          r.num + r.a[0] * cur[r.nb[0]] + r.a[1] * cur[r.nb[1]] + r.a[2] * cur[r.nb[2]] + r.a[3] * cur[r.nb[3]];
      dst[r.c] = std::max(num / r.den, floor);
    }
  }
}

void KEpsilonModel::update_eddy_viscosity(const std::vector<double>& cell_nu) {
  const KEpsilonParams& p = params_;
  detail::parallel_range(grid_.ncell(), [&](long long c0, long long c1) {
    for (long long c = c0; c < c1; ++c) {
      if (cell_role_[c] == kInactive) {
        cell_nut[c] = 0.0;
        continue;
      }
      const double k = cell_k[c];
      cell_nut[c] = std::min(p.c_mu * k * k / cell_eps[c], p.nut_max_ratio * cell_nu[c]);
    }
  });
}

void KEpsilonModel::check_finite(double t) {
  // the common case (every value finite and positive) on the threads; a failure is named by the search
  // below, which finds the first failing cell as before
  std::atomic<bool> bad{false};
  detail::parallel_range(grid_.ncell(), [&](long long c0, long long c1) {
    bool ok = true;
    for (long long c = c0; c < c1; ++c) {
      const double k = cell_k[c], e = cell_eps[c], nt = cell_nut[c];
      ok &= std::isfinite(k) & std::isfinite(e) & std::isfinite(nt) & (k > 0.0) & (e > 0.0);
    }
    if (!ok) bad.store(true, std::memory_order_relaxed);
  });
  if (!bad.load()) return;
  for (int c = 0; c < grid_.ncell(); ++c) {
    const double k = cell_k[c], e = cell_eps[c], nt = cell_nut[c];
    if (std::isfinite(k) && std::isfinite(e) && std::isfinite(nt) && k > 0.0 && e > 0.0) continue;
    const std::string msg = "k-epsilon step: k = " + format_value(k) + ", eps = " + format_value(e) +
                            ", nu_t = " + format_value(nt) + " in " + cell_name(grid_, c) + " at t = " +
                            format_value(t) + " s (state before the step restored)";
    cell_k = k_old_;
    cell_eps = eps_old_;
    cell_nut = nut_old_;
    cell_role_prev_.swap(cell_role_);
    throw std::runtime_error(msg);
  }
}

void KEpsilonModel::step(double dt, const std::vector<double>& face_u, const std::vector<double>& face_w,
                         const std::vector<double>& cell_porosity, const std::vector<double>& cell_F,
                         const std::vector<double>& cell_nu) {
  require_positive("dt", dt);
  check_sizes(face_u, face_w, cell_porosity, cell_F, cell_nu);
  const unsigned flags = params_.flags;
  {
    ScopedStage timer(profile_, stage_setup_);
    // the start of the step, floored: k and eps set by hand to 0 must not make eps/k infinite
    detail::parallel_range(grid_.ncell(), [&](long long c0, long long c1) {
      for (long long c = c0; c < c1; ++c) {
        cell_k[c] = k_old_[c] = std::max(cell_k[c], params_.k_min);
        cell_eps[c] = eps_old_[c] = std::max(cell_eps[c], params_.eps_min);
      }
    });
    nut_old_ = cell_nut;
    cell_role_prev_.swap(cell_role_);
    classify_cells(cell_porosity, cell_F);
  }
  if (has(flags, kKEpsWallFunctions)) {
    ScopedStage timer(profile_, stage_wall_);
    apply_wall_functions(face_u, face_w, cell_porosity, cell_nu);
  }
  if (has(flags, kKEpsProduction)) {
    ScopedStage timer(profile_, stage_production_);
    compute_production(face_u, face_w, cell_porosity);
  }
  {
    ScopedStage timer(profile_, stage_transport_);
    if (params_.time_scheme == KEpsilonTimeScheme::kVerticalLines)
      solve_transport_lines(dt, face_u, face_w, cell_porosity, cell_F, cell_nu);
    else if (params_.time_scheme == KEpsilonTimeScheme::kAlternatingLines)
      solve_transport_alternating(dt, face_u, face_w, cell_porosity, cell_F, cell_nu);
    else
      solve_transport(dt, face_u, face_w, cell_porosity, cell_F, cell_nu);
  }
  {
    ScopedStage timer(profile_, stage_viscosity_);
    update_eddy_viscosity(cell_nu);
  }
  {
    ScopedStage timer(profile_, stage_check_);
    check_finite(time + dt);
  }
  time += dt;
}

double KEpsilonModel::stable_dt(const std::vector<double>& face_u, const std::vector<double>& face_w,
                                const std::vector<double>& cell_porosity, const std::vector<double>& cell_F,
                                const std::vector<double>& cell_nu, int* cell) const {
  check_sizes(face_u, face_w, cell_porosity, cell_F, cell_nu);
  // the column solves take the vertical faces (and the boundary inflow) implicitly
  const bool alternating = params_.time_scheme == KEpsilonTimeScheme::kAlternatingLines;
  const bool lines = params_.time_scheme == KEpsilonTimeScheme::kVerticalLines || alternating;
  // no bound (KEpsilonParams::limit_step; the alternating lines without advection), nothing computed
  if (lines && (!params_.limit_step || (alternating && !has(params_.flags, kKEpsAdvection)))) {
    if (cell) *cell = -1;
    return std::numeric_limits<double>::infinity();
  }
  // the alternating lines take every face implicitly: the horizontal advection's limit alone, each face's
  // Courant number as the flow's CFL takes it (a sum over a cell's inflow faces bound the explicit
  // faces' stability, which an implicit face does not need; where water converges on a cell, the sum
  // bound the steps of the fine grids before the flow's own CFL did)
  if (alternating) {
    int worst = -1;
    const double rate = lines_stable_rate(face_u, cell_porosity, cell_F, worst, false);
    if (cell) *cell = worst;
    return rate > 0.0 ? params_.cfl / rate : std::numeric_limits<double>::infinity();
  }
  const int nfaces = lines ? 2 : 4;
  half_cell_resistances(cell_porosity, cell_F, cell_nu, lines);
  double rate_max = 0.0;
  int worst = -1;
  if (lines) {
    rate_max = lines_stable_rate(face_u, cell_porosity, cell_F, worst);
    if (cell) *cell = worst;
    return rate_max > 0.0 ? params_.cfl / rate_max : std::numeric_limits<double>::infinity();
  }
  FaceCoef fc[4];
  for (int k = 0; k < grid_.nz(); ++k) {
    for (int i = 0; i < grid_.nx(); ++i) {
      const int c = grid_.cell(i, k);
      if (!is_active(c, cell_porosity, cell_F)) continue;
      face_coefficients(i, k, face_u, face_w, cell_porosity, cell_F, cell_nu, fc, lines);
      double sum_k = 0.0, sum_eps = 0.0;
      for (int f = 0; f < nfaces; ++f) {
        if (lines && fc[f].nb < 0) continue;
        sum_k += fc[f].a[0];
        sum_eps += fc[f].a[1];
      }
      const double rate = std::max(sum_k, sum_eps) / cell_porosity[c];
      if (rate > rate_max) rate_max = rate, worst = c;
    }
  }
  if (cell) *cell = worst;
  return rate_max > 0.0 ? params_.cfl / rate_max : std::numeric_limits<double>::infinity();
}

}  // namespace vofdem
