#include "vofdem/flow/porous_stage.h"

#include <algorithm>
#include <cmath>

#include "common/parallel.h"
#include "vofdem/flow/porous_resistance.h"

namespace vofdem {

void porous_resistance_stage(const Grid2D& g, const PorousStageFields& f, const PorousStageTerms& t, double dt,
                             std::vector<double>& u_star, std::vector<double>& w_star,
                             std::vector<double>& face_x_beta, std::vector<double>& face_z_beta) {
  // the index arithmetic on local sizes, not Grid2D's helpers: the call into the closure law in the loops
  // would make the compiler reload the grid's sizes at every face (measured: 20 % more instructions)
  const int nx = g.nx(), nz = g.nz(), sx = nx + 1;
  const bool lin = t.linear, quad = t.quadratic, rel = t.relative;
  const double k1 = t.k1, k2 = t.k2;
  // R' = a + b |u_rel| from the velocity of the last step (Picard), then (1 + dt n R') u = u* + dt n R' n u_s
  // (the scalars by value: each thread's copy keeps them in registers, parallel.h)
  auto apply = [=](double n, double d, double rho, double mu, double u_rel_mag, double us, double& ustar,
                   double& beta) {
    if (n <= 0.0 || n >= 1.0) return;
    const PorousCoefficients pc = porous_coefficients_unchecked(n, d, mu / rho, k1, k2);
    const double r = (lin ? pc.linear : 0.0) + (quad ? pc.quadratic * u_rel_mag : 0.0);
    const double denom = 1.0 + dt * n * r;
    ustar = (ustar + (rel ? dt * n * r * n * us : 0.0)) / denom;
    beta /= denom;
  };
  // the molecular viscosity of eq. (5), not nu + nu_t (see the top of porous_stage.h)
  auto mu_face = [&f](int a, int b) { return 0.5 * (f.cell_rho[a] * f.cell_nu[a] + f.cell_rho[b] * f.cell_nu[b]); };
  // the faces row by row on the threads: each face reads the step's start and writes its own values
  detail::parallel_for(nz, sx, [&, apply, mu_face](int k0, int k1) {
    for (int k = k0; k < k1; ++k) {
      for (int i = 0; i <= nx; ++i) {
        const int j = i + sx * k;
        const double n = f.face_x_porosity[j];
        if (n <= 0.0 || n >= 1.0) continue;
        // the z-faces below and above the two cells beside the face (columns a, b)
        const int a = std::max(i - 1, 0), b = std::min(i, nx - 1);
        auto sum4 = [&](const double* v) {
          return v[a + nx * k] + v[b + nx * k] + v[a + nx * (k + 1)] + v[b + nx * (k + 1)];
        };
        double ur = f.face_u[j], wr = 0.25 * sum4(f.face_w);
        if (rel) {
          ur -= n * f.face_x_solid_u[j];
          wr -= n * 0.25 * sum4(f.face_z_solid_w);
        }
        apply(n, f.face_x_diameter[j], f.face_x_rho[j], mu_face(a + nx * k, b + nx * k), std::hypot(ur, wr),
              f.face_x_solid_u[j], u_star[j], face_x_beta[j]);
      }
    }
  });
  detail::parallel_for(nz + 1, nx, [&, apply, mu_face](int k0, int k1) {
    for (int k = k0; k < k1; ++k) {
      for (int i = 0; i < nx; ++i) {
        const int j = i + nx * k;
        const double n = f.face_z_porosity[j];
        if (n <= 0.0 || n >= 1.0) continue;
        // the x-faces left and right of the two cells beside the face (rows a, b)
        const int a = std::max(k - 1, 0), b = std::min(k, nz - 1);
        auto sum4 = [&](const double* v) {
          return v[i + sx * a] + v[i + 1 + sx * a] + v[i + sx * b] + v[i + 1 + sx * b];
        };
        double ur = 0.25 * sum4(f.face_u), wr = f.face_w[j];
        if (rel) {
          wr -= n * f.face_z_solid_w[j];
          ur -= n * 0.25 * sum4(f.face_x_solid_u);
        }
        apply(n, f.face_z_diameter[j], f.face_z_rho[j], mu_face(i + nx * a, i + nx * b), std::hypot(ur, wr),
              f.face_z_solid_w[j], w_star[j], face_z_beta[j]);
      }
    }
  });
}

}  // namespace vofdem
