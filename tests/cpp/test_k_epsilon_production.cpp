// Production options of the k-epsilon model (KEpsilonParams::production, production_limit):
// Kato-Launder production (Kato & Launder 1993) and the production limiter (Menter 1994), on
// homogeneous strain fields in a box closed to fluxes.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <vector>

#include "vofdem/grid.h"
#include "vofdem/k_epsilon.h"

using namespace vofdem;

namespace {

constexpr double kNu = 1e-6;

KEpsilonBoundaries closed_box() {
  KEpsilonBoundaries b;
  b.left = b.right = b.bottom = b.top = KEpsilonBoundary::kZeroGradient;
  return b;
}

// one step of the model from uniform k0, eps0 under the given faces' velocities; returns k of an
// interior cell
double step_k(const Grid2D& g, const KEpsilonParams& p, const std::vector<double>& u, const std::vector<double>& w,
              double dt, int nsteps = 1) {
  KEpsilonModel m(g, p, closed_box());
  m.initialize(1e-3, 1e-4, kNu);
  std::vector<double> n(g.ncell(), 1.0), F(g.ncell(), 1.0), nu(g.ncell(), kNu);
  for (int s = 0; s < nsteps; ++s) m.step(dt, u, w, n, F, nu);
  return m.cell_k[g.cell(g.nx() / 2, g.nz() / 2)];
}

struct Strain {
  std::vector<double> u, w;
};

// irrotational plane strain U = a x, W = -a z (a stagnation-point flow): S^2 = 4 a^2, Omega = 0
Strain plane_strain(const Grid2D& g, double a) {
  Strain s{std::vector<double>(g.nface_x()), std::vector<double>(g.nface_z())};
  for (int k = 0; k < g.nz(); ++k)
    for (int i = 0; i <= g.nx(); ++i) s.u[g.face_x(i, k)] = a * (i * g.dx() - 0.5 * g.length_x());
  for (int k = 0; k <= g.nz(); ++k)
    for (int i = 0; i < g.nx(); ++i) s.w[g.face_z(i, k)] = -a * (g.z_face(k) - 0.5 * g.height_z());
  return s;
}

// simple shear U = G z: S = Omega = G
Strain simple_shear(const Grid2D& g, double gr) {
  Strain s{std::vector<double>(g.nface_x(), 0.0), std::vector<double>(g.nface_z(), 0.0)};
  for (int k = 0; k < g.nz(); ++k)
    for (int i = 0; i <= g.nx(); ++i) s.u[g.face_x(i, k)] = gr * g.z_center(k);
  return s;
}

}  // namespace

TEST(KEpsilonProduction, KatoLaunderEqualsTheStandardTermInSimpleShear) {
  const Grid2D g = Grid2D::uniform(8, 8, 0.2, 0.2);
  const Strain s = simple_shear(g, 5.0);
  KEpsilonParams std_p, kl_p;
  kl_p.production = KEpsilonProduction::kKatoLaunder;
  const double k_std = step_k(g, std_p, s.u, s.w, 1e-3, 20), k_kl = step_k(g, kl_p, s.u, s.w, 1e-3, 20);
  EXPECT_GT(k_std, 1e-3);  // the shear produces k
  EXPECT_NEAR(k_kl, k_std, 1e-12 * k_std);
}

TEST(KEpsilonProduction, KatoLaunderProducesNothingInIrrotationalStrain) {
  // at a stagnation point the standard term produces nu_t 4 a^2 (k grows), Kato-Launder nothing: k
  // decays exactly as with production switched off
  const Grid2D g = Grid2D::uniform(8, 8, 0.2, 0.2);
  const Strain s = plane_strain(g, 5.0);
  KEpsilonParams std_p, kl_p, off_p;
  kl_p.production = KEpsilonProduction::kKatoLaunder;
  off_p.flags &= ~kKEpsProduction;
  const double k_std = step_k(g, std_p, s.u, s.w, 1e-3, 20);
  const double k_kl = step_k(g, kl_p, s.u, s.w, 1e-3, 20), k_off = step_k(g, off_p, s.u, s.w, 1e-3, 20);
  EXPECT_GT(k_std, 1e-3);
  EXPECT_LT(k_kl, 1e-3);
  EXPECT_NEAR(k_kl, k_off, 1e-12 * k_off);
}

TEST(KEpsilonProduction, LimiterCapsProductionAtTenDissipations) {
  // k0 = 1e-3, eps0 = 1e-4: nu_t = 9e-4, in plane strain a = 5 /s P = nu_t 4 a^2 = 0.09 = 900 eps.
  // With the cap, one step grows k by at most dt (10 eps - eps) (the sink is implicit, so less);
  // without it by about dt (P - eps). A cap far above P changes nothing.
  const Grid2D g = Grid2D::uniform(8, 8, 0.2, 0.2);
  const Strain s = plane_strain(g, 5.0);
  const double dt = 1e-3, k0 = 1e-3, eps0 = 1e-4;
  KEpsilonParams lim_p, std_p, high_p;
  lim_p.production_limit = 10.0;
  high_p.production_limit = 1e9;
  const double k_lim = step_k(g, lim_p, s.u, s.w, dt), k_std = step_k(g, std_p, s.u, s.w, dt);
  EXPECT_LE(k_lim - k0, dt * 9.0 * eps0 * (1 + 1e-12));
  EXPECT_GT(k_lim - k0, 0.5 * dt * 9.0 * eps0);
  EXPECT_GT(k_std - k0, 0.5 * dt * 0.09);
  EXPECT_EQ(step_k(g, high_p, s.u, s.w, dt), k_std);
  KEpsilonParams bad;
  bad.production_limit = -1.0;
  EXPECT_THROW(check_k_epsilon_params(bad), std::invalid_argument);
}

// the production (computed row by row, vectorised) against the obvious cell-by-cell form: a random flow
// over solid, air, wall and solved cells, both production terms, with and without the limiter, one to
// nine columns; the same values to the bit
TEST(KEpsilonProduction, MatchesTheCellByCellReferenceBitForBit) {
  std::mt19937 rng(9);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  for (int nx : {1, 2, 3, 9})
    for (auto kind : {KEpsilonProduction::kStrain, KEpsilonProduction::kKatoLaunder})
      for (double limit : {0.0, 10.0}) {
        const Grid2D g = Grid2D::graded(nx, 0.04 * nx, 0.08, 0.02, 0.01, 0.02);
        KEpsilonParams p;
        p.production = kind;
        p.production_limit = limit;
        KEpsilonModel m(g, p, closed_box());
        m.initialize(1e-3, 1e-4, kNu);
        std::vector<double> u(g.nface_x()), w(g.nface_z()), n(g.ncell()), F(g.ncell()), nu(g.ncell(), kNu);
        for (double& v : u) v = unit(rng) - 0.5;
        for (double& v : w) v = unit(rng) - 0.5;
        for (int c = 0; c < g.ncell(); ++c) {
          n[c] = unit(rng) < 0.15 ? 0.0 : 0.3 + 0.7 * unit(rng);
          F[c] = unit(rng) < 0.2 ? 0.0 : 1.0;
        }
        // the second step: the cells' roles are those of the first (no cell has just filled)
        m.step(1e-3, u, w, n, F, nu);
        const std::vector<double> nut = m.cell_nut, eps = m.cell_eps;
        m.step(1e-3, u, w, n, F, nu);
        std::vector<double> role;
        m.cell_roles(role);
        const int nz = g.nz();
        auto usable = [&](int i, int k) { return i >= 0 && i < nx && k >= 0 && k < nz && role[g.cell(i, k)] != 0.0; };
        auto uc = [&](int i, int k) { return 0.5 * (u[g.face_x(i, k)] + u[g.face_x(i + 1, k)]) / n[g.cell(i, k)]; };
        auto wc = [&](int i, int k) { return 0.5 * (w[g.face_z(i, k)] + w[g.face_z(i, k + 1)]) / n[g.cell(i, k)]; };
        int solved = 0;
        for (int k = 0; k < nz; ++k)
          for (int i = 0; i < nx; ++i) {
            const int c = g.cell(i, k);
            double prod = 0.0;
            if (role[c] == 1.0) {
              ++solved;
              const double dudx = (u[g.face_x(i + 1, k)] - u[g.face_x(i, k)]) / (n[c] * g.dx());
              const double dwdz = (w[g.face_z(i, k + 1)] - w[g.face_z(i, k)]) / (n[c] * g.dz(k));
              const bool s = usable(i, k - 1), up = usable(i, k + 1), we = usable(i - 1, k), ea = usable(i + 1, k);
              double dudz = 0.0, dwdx = 0.0;
              if (s || up) {
                const int ka = up ? k + 1 : k, kb = s ? k - 1 : k;
                dudz = (uc(i, ka) - uc(i, kb)) / (g.z_center(ka) - g.z_center(kb));
              }
              if (we || ea) {
                const int ia = ea ? i + 1 : i, ib = we ? i - 1 : i;
                dwdx = (wc(ia, k) - wc(ib, k)) / (g.dx() * (ia - ib));
              }
              const double shear = dudz + dwdx;
              const double s2 = 2.0 * dudx * dudx + 2.0 * dwdz * dwdz + shear * shear;
              prod = kind == KEpsilonProduction::kKatoLaunder ? nut[c] * std::sqrt(s2) * std::abs(dudz - dwdx)
                                                              : nut[c] * s2;
              if (limit > 0.0) prod = std::min(prod, limit * eps[c]);
            }
            EXPECT_EQ(m.cell_production()[c], prod) << "nx " << nx << " cell " << c;
          }
        // narrower flumes: every water cell is a wall cell
        if (nx >= 3) {
          EXPECT_GT(solved, 0) << "nx " << nx;
        }
      }
}

namespace {

// k of a middle cell after nsteps under a uniform superficial flow u0 through rows of porosity rising
// linearly from 0.3 at the bed to 1 at the top (w = 0: divergence-free; k, eps uniform at the start)
double k_through_porosity_rows(const KEpsilonParams& p, double u0, int nsteps) {
  const Grid2D g = Grid2D::uniform(8, 8, 0.2, 0.2);
  std::vector<double> n(g.ncell()), F(g.ncell(), 1.0), nu(g.ncell(), kNu);
  for (int k = 0; k < g.nz(); ++k)
    for (int i = 0; i < g.nx(); ++i) n[g.cell(i, k)] = 0.3 + 0.1 * k;
  std::vector<double> u(g.nface_x(), u0), w(g.nface_z(), 0.0);
  KEpsilonModel m(g, p, closed_box());
  m.initialize(1e-3, 1e-4, kNu);
  for (int s = 0; s < nsteps; ++s) m.step(1e-3, u, w, n, F, nu);
  return m.cell_k[g.cell(g.nx() / 2, g.nz() / 2)];
}

}  // namespace

TEST(KEpsilonProduction, LocalPoreStrainTakesNoShearFromThePorositysJumps) {
  // the same superficial velocity in every row: the pore velocity u0 / n differs from row to row, a
  // jump of 1/n and no shear of the flow. The neighbours' pore velocities make a strain of it (k grows);
  // the local one makes none: k decays exactly as with production switched off
  KEpsilonParams neighbours, local, off;
  local.pore_strain = KEpsilonPoreStrain::kLocal;
  off.flags &= ~kKEpsProduction;
  const double k_nb = k_through_porosity_rows(neighbours, 0.5, 20);
  const double k_local = k_through_porosity_rows(local, 0.5, 20), k_off = k_through_porosity_rows(off, 0.5, 20);
  EXPECT_GT(k_nb, 1.01 * k_off);
  EXPECT_EQ(k_local, k_off);
}

TEST(KEpsilonProduction, LocalPoreStrainIsTheSameInClearWater) {
  // n = 1 everywhere: both forms divide by 1, the same bits
  const Grid2D g = Grid2D::uniform(8, 8, 0.2, 0.2);
  const Strain s = simple_shear(g, 5.0);
  KEpsilonParams neighbours, local;
  local.pore_strain = KEpsilonPoreStrain::kLocal;
  EXPECT_EQ(step_k(g, local, s.u, s.w, 1e-3, 20), step_k(g, neighbours, s.u, s.w, 1e-3, 20));
}
