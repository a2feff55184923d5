// Production options of the k-epsilon model (KEpsilonParams::production, production_limit):
// Kato-Launder production (Kato & Launder 1993) and the production limiter (Menter 1994), on
// homogeneous strain fields in a box closed to fluxes.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <utility>
#include <vector>

#include "vofdem/common/grid.h"
#include "vofdem/flow/k_epsilon.h"
#include "common/pinned_params.h"

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
  KEpsilonParams bad = test::pinned_k_epsilon_params();
  bad.production_limit = -1.0;
  EXPECT_THROW(check_k_epsilon_params(bad), std::invalid_argument);
}

// the production (computed row by row, vectorised) against the obvious cell-by-cell form: a random flow
// over solid, air, wall and solved cells, both production terms, with and without the limiter, the
// three pore strains, one to nine columns; the same values to the bit
TEST(KEpsilonProduction, MatchesTheCellByCellReferenceBitForBit) {
  std::mt19937 rng(9);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  for (int nx : {1, 2, 3, 9})
    for (auto kind : {KEpsilonProduction::kStrain, KEpsilonProduction::kKatoLaunder})
      for (double limit : {0.0, 10.0})
        for (auto form : {KEpsilonPoreStrain::kNeighbours, KEpsilonPoreStrain::kLocal, KEpsilonPoreStrain::kFiltered}) {
          const Grid2D g = Grid2D::graded(nx, 0.04 * nx, 0.08, 0.02, 0.01, 0.02);
          KEpsilonParams p = test::pinned_k_epsilon_params();
          p.production = kind;
          p.production_limit = limit;
          p.pore_strain = form;
          p.pore_filter_length = 0.05;
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
          auto uc = [&](int i, int k) { return 0.5 * (u[g.face_x(i, k)] + u[g.face_x(i + 1, k)]); };
          auto wc = [&](int i, int k) { return 0.5 * (w[g.face_z(i, k)] + w[g.face_z(i, k + 1)]); };
          // kFiltered: kNeighbours over the filtered porosity (filter_porosity: checked by hand below)
          std::vector<double> nf = n, work;
          if (form == KEpsilonPoreStrain::kFiltered) filter_porosity(g, n, p.pore_filter_length, nf, work);
          // (V_a - V_b) / len for neighbours a, b of cell c (a or b may be c itself)
          auto cross = [&](double va, double vb, int a, int b, int c, double len) {
            if (form == KEpsilonPoreStrain::kLocal) return (va / n[c] - vb / n[c]) / len;
            return (va / nf[a] - vb / nf[b]) / len;
          };
          int solved = 0;
          for (int k = 0; k < nz; ++k)
            for (int i = 0; i < nx; ++i) {
              const int c = g.cell(i, k);
              double prod = 0.0;
              if (role[c] == 1.0) {
                ++solved;
                const double dudx = (u[g.face_x(i + 1, k)] - u[g.face_x(i, k)]) / (nf[c] * g.dx());
                const double dwdz = (w[g.face_z(i, k + 1)] - w[g.face_z(i, k)]) / (nf[c] * g.dz(k));
                const bool s = usable(i, k - 1), up = usable(i, k + 1), we = usable(i - 1, k), ea = usable(i + 1, k);
                double dudz = 0.0, dwdx = 0.0;
                if (s || up) {
                  const int ka = up ? k + 1 : k, kb = s ? k - 1 : k;
                  dudz = cross(uc(i, ka), uc(i, kb), g.cell(i, ka), g.cell(i, kb), c, g.z_center(ka) - g.z_center(kb));
                }
                if (we || ea) {
                  const int ia = ea ? i + 1 : i, ib = we ? i - 1 : i;
                  dwdx = cross(wc(ia, k), wc(ib, k), g.cell(ia, k), g.cell(ib, k), c, g.dx() * (ia - ib));
                }
                const double shear = dudz + dwdx;
                const double s2 = 2.0 * dudx * dudx + 2.0 * dwdz * dwdz + shear * shear;
                prod = kind == KEpsilonProduction::kKatoLaunder ? nut[c] * std::sqrt(s2) * std::abs(dudz - dwdx)
                                                                : nut[c] * s2;
                if (limit > 0.0) prod = std::min(prod, limit * eps[c]);
              }
              EXPECT_EQ(m.cell_production()[c], prod) << "nx " << nx << " cell " << c << " form " << int(form);
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

TEST(KEpsilonProduction, PoreStrainsAreTheSameInClearWater) {
  // n = 1 everywhere: all forms divide by 1 (the filtered porosity of 1s is 1), the same bits
  const Grid2D g = Grid2D::uniform(8, 8, 0.2, 0.2);
  const Strain s = simple_shear(g, 5.0);
  KEpsilonParams neighbours, local, filtered;
  local.pore_strain = KEpsilonPoreStrain::kLocal;
  filtered.pore_strain = KEpsilonPoreStrain::kFiltered;
  filtered.pore_filter_length = 0.07;
  const double k_nb = step_k(g, neighbours, s.u, s.w, 1e-3, 20);
  EXPECT_EQ(step_k(g, local, s.u, s.w, 1e-3, 20), k_nb);
  EXPECT_EQ(step_k(g, filtered, s.u, s.w, 1e-3, 20), k_nb);
}

TEST(KEpsilonProduction, PoreStrainsOfACellInsideAStoneByHand) {
  // superficial simple shear u = G z through clear water (cells of 2.5 cm) with one cell of n = 1/4:
  // its dU/dz from the neighbours' pore velocities is G, over its own n G / (1/4); filtered over a
  // 7.5 cm box, the neighbours above and below see n_f = (8 + 1/4) / 9 (the 3 x 3 cells around them hold
  // the stone's cell), so G / n_f. dU/dx = dW/dz = dW/dx = 0, so P = nu_t (dU/dz)^2
  const Grid2D g = Grid2D::uniform(8, 8, 0.2, 0.2);
  const double gr = 5.0;
  const Strain s = simple_shear(g, gr);
  std::vector<double> n(g.ncell(), 1.0), F(g.ncell(), 1.0), nu(g.ncell(), kNu);
  const int c = g.cell(4, 4);
  n[c] = 0.25;
  const std::pair<KEpsilonPoreStrain, double> cases[] = {{KEpsilonPoreStrain::kNeighbours, gr},
                                                         {KEpsilonPoreStrain::kLocal, 4.0 * gr},
                                                         {KEpsilonPoreStrain::kFiltered, gr * 9.0 / 8.25}};
  for (const auto& [form, dudz] : cases) {
    KEpsilonParams p = test::pinned_k_epsilon_params();
    p.pore_strain = form;
    p.pore_filter_length = 0.075;
    KEpsilonModel m(g, p, closed_box());
    m.initialize(1e-3, 1e-4, kNu);
    const double nut = m.cell_nut[c];
    m.step(1e-3, s.u, s.w, n, F, nu);
    EXPECT_NEAR(m.cell_production()[c], nut * dudz * dudz, 1e-12 * nut * dudz * dudz) << int(form);
  }
}

namespace {

// the largest production after one step of a uniform superficial flow u0 over a porosity step (n = 1/4
// in the lower half of the column, 1 above) on nz x nz cells of a 0.2 m box
double largest_production_over_a_porosity_step(const KEpsilonParams& p, int nz) {
  const Grid2D g = Grid2D::uniform(nz, nz, 0.2, 0.2);
  std::vector<double> n(g.ncell()), F(g.ncell(), 1.0), nu(g.ncell(), kNu);
  for (int k = 0; k < nz; ++k)
    for (int i = 0; i < nz; ++i) n[g.cell(i, k)] = k < nz / 2 ? 0.25 : 1.0;
  std::vector<double> u(g.nface_x(), 0.5), w(g.nface_z(), 0.0);
  KEpsilonModel m(g, p, closed_box());
  m.initialize(1e-3, 1e-4, kNu);
  m.step(1e-4, u, w, n, F, nu);
  return *std::max_element(m.cell_production().begin(), m.cell_production().end());
}

}  // namespace

TEST(KEpsilonProduction, FilteredPoreStrainIsBoundedWhereTheNeighboursGrowsWithTheGrid) {
  // the neighbours' pore velocities read the porosity's jump as a shear u0 (1/n_a - 1/n_b) / (2 dz): its
  // production grows as 1/dz^2. Filtered on L = 5 cm, the step is the ramp n_f = 1/4 .. 1 over L on every
  // grid (the box filter of a step at a face is exact at the centres), whose pore shear u0 d(1/n_f)/dz is
  // at most u0 (3/4) / L / (1/4)^2 = 120 1/s: P <= nu_t 120^2 on every grid, rising towards it as the
  // grid resolves the ramp (slowly: 1 / n_f is steep where n_f = 1/4)
  KEpsilonParams neighbours, filtered;
  filtered.pore_strain = KEpsilonPoreStrain::kFiltered;
  filtered.pore_filter_length = 0.05;
  const double nut = 0.09 * 1e-3 * 1e-3 / 1e-4, bound = nut * 120.0 * 120.0;
  double previous = 0.0;
  for (int nz : {8, 16, 32, 64, 128}) {
    const double f = largest_production_over_a_porosity_step(filtered, nz);
    EXPECT_LE(f, bound * (1.0 + 1e-12)) << nz;
    EXPECT_GT(f, previous) << nz;
    previous = f;
  }
  const double nb32 = largest_production_over_a_porosity_step(neighbours, 32);
  const double nb128 = largest_production_over_a_porosity_step(neighbours, 128);
  EXPECT_NEAR(nb128 / nb32, 16.0, 1e-9);
  EXPECT_NEAR(nb128, nut * std::pow(0.5 * 3.0 / (2.0 * 0.2 / 128), 2), 1e-12 * nb128);
}

TEST(KEpsilonProduction, FilteredPorosityByHand) {
  // 5 x 1 cells of 1 cm, n = 1, 1, 0.4, 1, 0 (solid): a 2 cm box around cell 1 covers half of cell 0,
  // cell 1 and half of cell 2: (0.5 + 1 + 0.5 x 0.4) / 2 = 0.85; around cell 3, half of cell 2 and cell 3
  // (cell 4 is solid, left out): (0.5 x 0.4 + 1) / 1.5 = 0.8; cell 0 has no neighbour west: (1 + 0.5) /
  // 1.5 = 1; the solid cell stays 0. A box narrower than a cell gives each cell its own n.
  const Grid2D g = Grid2D::uniform(5, 1, 0.05, 0.01);
  const std::vector<double> n = {1.0, 1.0, 0.4, 1.0, 0.0};
  std::vector<double> f, work;
  filter_porosity(g, n, 0.02, f, work);
  EXPECT_NEAR(f[0], 1.0, 1e-14);
  EXPECT_NEAR(f[1], 0.85, 1e-14);
  EXPECT_NEAR(f[2], (0.5 + 0.4 + 0.5) / 2.0, 1e-14);
  EXPECT_NEAR(f[3], 0.8, 1e-14);
  EXPECT_EQ(f[4], 0.0);
  filter_porosity(g, n, 0.005, f, work);
  for (int c = 0; c < 5; ++c) EXPECT_NEAR(f[c], n[c], 1e-14);
}

TEST(KEpsilonProduction, FilteredPorosityOverAGradedColumnByHand) {
  // one column, rows 1, 1, 2, 4 cm high, n = 0.5, 1, 0.25, 1: a 3 cm box around row 2 (centre 3 cm,
  // 1.5 to 4.5 cm) covers 0.5 cm of row 1, the 2 cm of row 2 and 0.5 cm of row 3
  const Grid2D g(1, 0.01, {0.0, 0.01, 0.02, 0.04, 0.08});
  const std::vector<double> n = {0.5, 1.0, 0.25, 1.0};
  std::vector<double> f, work;
  filter_porosity(g, n, 0.03, f, work);
  EXPECT_NEAR(f[g.cell(0, 2)], (0.5 * 1.0 + 2.0 * 0.25 + 0.5 * 1.0) / 3.0, 1e-14);
}

TEST(KEpsilonProduction, FilteredPoreStrainNeedsItsLength) {
  KEpsilonParams p = test::pinned_k_epsilon_params();
  p.pore_strain = KEpsilonPoreStrain::kFiltered;
  EXPECT_THROW(check_k_epsilon_params(p), std::invalid_argument);
  p.pore_filter_length = 0.048;
  EXPECT_NO_THROW(check_k_epsilon_params(p));
  p.pore_strain = static_cast<KEpsilonPoreStrain>(7);
  EXPECT_THROW(check_k_epsilon_params(p), std::invalid_argument);
}
