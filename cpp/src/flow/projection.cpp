#include "vofdem/flow/projection.h"

#include <cstdint>

#include "common/parallel.h"

namespace vofdem {

double open_end_pressure(const Grid2D& grid, const ProjectionBoundary& bc, int k) {
  // still fluid outside, hydrostatic from p = 0 at the top: an end face at p = 0 over its whole height
  // would leave the air in the last columns unbalanced by rho_a g and let it fall through the domain
  const double g = bc.gravity;
  const double z = grid.z_center(k);
  const double top = grid.z_face(grid.nz());
  // single phase: water outside too, up to the tailwater level or the top
  if (!bc.two_phase) return bc.rho_water * g * ((bc.tailwater ? bc.tailwater_level : top) - z);
  double p = bc.rho_air * g * (top - z);
  if (bc.tailwater && bc.tailwater_level > z) p += (bc.rho_water - bc.rho_air) * g * (bc.tailwater_level - z);
  return p;
}

namespace {

// 1/2 rho U^2 [Pa] of fluid entering an open face at the superficial velocity v (U = v / n)
inline double drawn_in_head(double rho, double v, double n) {
  const double U = v / n;
  return 0.5 * rho * U * U;
}

// x-faces: a = beta dz / dx inside; an open end is a Dirichlet face half a cell from the centre
void assemble_x_faces(const Grid2D& g, const ProjectionFields& f, const ProjectionBoundary& bc, PressureProblem& pb) {
  const int nx = g.nx(), nz = g.nz(), sx = nx + 1;
  const double dx = g.dx();
  detail::parallel_for(nz, sx, [&, dx](int k0, int k1) {
    for (int k = k0; k < k1; ++k) {
      const double dz = g.dz(k);
      const int row = sx * k;
      const double* n = f.face_x_porosity + row;
      const double* beta = f.face_x_beta + row;
      double* coef = pb.face_x_coef.data() + row;
      double* value = pb.face_x_bc.data() + row;
      // the inner faces: every coefficient computed, then kept where the face is open (vectorised)
      for (int i = 1; i < nx; ++i) {
        const double a = beta[i] * dz / dx;
        coef[i] = n[i] > 0.0 ? a : 0.0;
        value[i] = 0.0;
      }
      coef[0] = value[0] = 0.0;
      const double a = n[nx] > 0.0 && bc.right_open ? beta[nx] * dz / (0.5 * dx) : 0.0;
      coef[nx] = a;
      value[nx] = open_end_pressure(g, bc, k);
      // fluid drawn in from the still outside: the outside pressure less 1/2 rho U^2 (see the header)
      if (a > 0.0 && f.face_u[row + nx] < 0.0)
        value[nx] -= drawn_in_head(f.face_x_rho[row + nx], f.face_u[row + nx], n[nx]);
    }
  });
}

// z-faces: a = beta dx / (z_c(k) - z_c(k-1)) inside; the top face half a cell from the centre (p = 0)
void assemble_z_faces(const Grid2D& g, const ProjectionFields& f, PressureProblem& pb) {
  const int nx = g.nx(), nz = g.nz();
  const double dx = g.dx();
  detail::parallel_for(nz + 1, nx, [&, dx](int k0, int k1) {
    for (int k = k0; k < k1; ++k) {
      const int row = nx * k;
      const double* n = f.face_z_porosity + row;
      const double* beta = f.face_z_beta + row;
      double* coef = pb.face_z_coef.data() + row;
      double* value = pb.face_z_bc.data() + row;
      // the bed is closed; the top face half a cell from the centre; every coefficient of a row computed,
      // then kept where the face is open (vectorised)
      const double h = k == 0 ? 1.0 : k < nz ? g.z_center(k) - g.z_center(k - 1) : 0.5 * g.dz(nz - 1);
      const bool closed = k == 0;
      for (int i = 0; i < nx; ++i) {
        const double a = beta[i] * dx / h;
        coef[i] = (n[i] > 0.0) & !closed ? a : 0.0;
        value[i] = 0.0;
      }
      // air drawn in through the open top starts from rest, as the water at an open end
      if (k == nz && f.face_w)
        for (int i = 0; i < nx; ++i)
          if (coef[i] > 0.0 && f.face_w[row + i] < 0.0)
            value[i] = -drawn_in_head(f.face_z_rho[row + i], f.face_w[row + i], n[i]);
    }
  });
}

// b = net outflow of u* per metre of width [m^2/s], less the outflow the porosity change asks for:
// dn/dt + div u = 0, so the corrected velocities leave a cell at the rate -dn/dt dx dz
void assemble_rhs(const Grid2D& g, const ProjectionFields& f, const PressureProblem& pb, double dt,
                  std::vector<double>& rhs) {
  const int nx = g.nx(), nz = g.nz();
  const double dx = g.dx();
  const double inv_dt = dt > 0.0 ? 1.0 / dt : 0.0;
  detail::parallel_for(nz, nx, [&, dx, inv_dt](int k0, int k1) {
    for (int k = k0; k < k1; ++k) {
      const double dz = g.dz(k);
      const double* u = f.u_star + (nx + 1) * k;
      const double* w = f.w_star + nx * k;  // w[i] below cell i, w[i + nx] above it
      const double* n = f.cell_porosity + nx * k;
      const double* n_prev = f.cell_porosity_prev + nx * k;
      const std::uint8_t* active = pb.cell_active.data() + nx * k;
      double* b = rhs.data() + nx * k;
      // every cell's value computed, then kept where the cell is active (bitwise &: no branch)
      for (int i = 0; i < nx; ++i) {
        const double flux = (u[i + 1] - u[i]) * dz + (w[i + nx] - w[i]) * dx;
        const double dn = n[i] - n_prev[i];
        const double with_source = flux + dn * inv_dt * dx * dz;
        const double v = (dn != 0.0) & (n_prev[i] > 0.0) ? with_source : flux;
        b[i] = active[i] ? v : 0.0;
      }
    }
  });
}

}  // namespace

void assemble_pressure_problem(const Grid2D& grid, const ProjectionFields& fields, const ProjectionBoundary& bc,
                               double dt, PressureProblem& problem, std::vector<double>& rhs) {
  detail::parallel_range(grid.ncell(), [&](long long c0, long long c1) {
    for (long long c = c0; c < c1; ++c) problem.cell_active[c] = fields.cell_porosity[c] > 0.0;
  });
  assemble_x_faces(grid, fields, bc, problem);
  assemble_z_faces(grid, fields, problem);
  assemble_rhs(grid, fields, problem, dt, rhs);
}

void correct_velocities(const Grid2D& g, const ProjectionFields& f, const PressureProblem& problem,
                        const std::vector<double>& cell_p, std::vector<double>& face_u, std::vector<double>& face_w) {
  const int nx = g.nx(), nz = g.nz(), sx = nx + 1;
  const double dx = g.dx();
  // the inner faces row by row, every correction computed, then kept where the face is open
  // (vectorised); the boundary faces one by one, as the general rule below
  detail::parallel_for(nz, sx, [&, dx](int k0, int k1) {
    for (int k = k0; k < k1; ++k) {
      const double* star = f.u_star + sx * k;
      const double* beta = f.face_x_beta + sx * k;
      const double* coef = problem.face_x_coef.data() + sx * k;
      const double* p = cell_p.data() + nx * k;  // p[i - 1], p[i]: the cells left and right of face i
      double* u = face_u.data() + sx * k;
      for (int i = 1; i < nx; ++i) {
        const double corrected = star[i] - beta[i] * (p[i] - p[i - 1]) / dx;
        u[i] = coef[i] > 0.0 ? corrected : star[i];
      }
    }
  });
  detail::parallel_for(nz - 1, nx, [&](int k0, int k1) {
    for (int k = k0 + 1; k <= k1; ++k) {
      const double dist = g.z_center(k) - g.z_center(k - 1);
      const double* star = f.w_star + nx * k;
      const double* beta = f.face_z_beta + nx * k;
      const double* coef = problem.face_z_coef.data() + nx * k;
      const double* below = cell_p.data() + nx * (k - 1);
      const double* above = cell_p.data() + nx * k;
      double* w = face_w.data() + nx * k;
      for (int i = 0; i < nx; ++i) {
        const double corrected = star[i] - beta[i] * (above[i] - below[i]) / dist;
        w[i] = coef[i] > 0.0 ? corrected : star[i];
      }
    }
  });
  for (int k = 0; k < nz; ++k) {
    for (int i = 0; i <= nx; i += nx) {
      const int j = g.face_x(i, k);
      double u = f.u_star[j];
      if (problem.face_x_coef[j] > 0.0) {
        const double pl = i > 0 ? cell_p[g.cell(i - 1, k)] : 0.0;
        const double pr = i < nx ? cell_p[g.cell(i, k)] : problem.face_x_bc[j];
        const double dist = (i == 0 || i == nx) ? 0.5 * dx : dx;
        u -= f.face_x_beta[j] * (pr - pl) / dist;
      }
      face_u[j] = u;
    }
  }
  for (int k = 0; k <= nz; k += nz) {
    for (int i = 0; i < nx; ++i) {
      const int j = g.face_z(i, k);
      double w = f.w_star[j];
      if (problem.face_z_coef[j] > 0.0) {
        const double pb = k > 0 ? cell_p[g.cell(i, k - 1)] : 0.0;
        const double pt = k < nz ? cell_p[g.cell(i, k)] : problem.face_z_bc[j];
        const double dist = k == nz ? 0.5 * g.dz(nz - 1) : g.z_center(k) - g.z_center(k - 1);
        w -= f.face_z_beta[j] * (pt - pb) / dist;
      }
      face_w[j] = w;
    }
  }
}

}  // namespace vofdem
