#include "vofdem/projection.h"

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
  const int nx = g.nx(), nz = g.nz();
  const double dx = g.dx();
  for (int k = 0; k < nz; ++k) {
    const double dz = g.dz(k);
    for (int i = 0; i <= nx; ++i) {
      const int j = g.face_x(i, k);
      double a = 0.0;
      if (f.face_x_porosity[j] > 0.0) {
        if (i > 0 && i < nx) a = f.face_x_beta[j] * dz / dx;
        else if (i == nx && bc.right_open) a = f.face_x_beta[j] * dz / (0.5 * dx);
      }
      pb.face_x_coef[j] = a;
      pb.face_x_bc[j] = i == nx ? open_end_pressure(g, bc, k) : 0.0;
      // fluid drawn in from the still outside: the outside pressure less 1/2 rho U^2 (see the header)
      if (i == nx && a > 0.0 && f.face_u[j] < 0.0)
        pb.face_x_bc[j] -= drawn_in_head(f.face_x_rho[j], f.face_u[j], f.face_x_porosity[j]);
    }
  }
}

// z-faces: a = beta dx / (z_c(k) - z_c(k-1)) inside; the top face half a cell from the centre (p = 0)
void assemble_z_faces(const Grid2D& g, const ProjectionFields& f, PressureProblem& pb) {
  const int nx = g.nx(), nz = g.nz();
  const double dx = g.dx();
  for (int k = 0; k <= nz; ++k) {
    for (int i = 0; i < nx; ++i) {
      const int j = g.face_z(i, k);
      double a = 0.0;
      if (f.face_z_porosity[j] > 0.0) {
        if (k > 0 && k < nz) a = f.face_z_beta[j] * dx / (g.z_center(k) - g.z_center(k - 1));
        else if (k == nz) a = f.face_z_beta[j] * dx / (0.5 * g.dz(nz - 1));
      }
      pb.face_z_coef[j] = a;
      pb.face_z_bc[j] = 0.0;
      // air drawn in through the open top starts from rest, as the water at an open end
      if (k == nz && a > 0.0 && f.face_w && f.face_w[j] < 0.0)
        pb.face_z_bc[j] = -drawn_in_head(f.face_z_rho[j], f.face_w[j], f.face_z_porosity[j]);
    }
  }
}

// b = net outflow of u* per metre of width [m^2/s], less the outflow the porosity change asks for:
// dn/dt + div u = 0, so the corrected velocities leave a cell at the rate -dn/dt dx dz
void assemble_rhs(const Grid2D& g, const ProjectionFields& f, const PressureProblem& pb, double dt,
                  std::vector<double>& rhs) {
  const int nx = g.nx(), nz = g.nz();
  const double dx = g.dx();
  const double inv_dt = dt > 0.0 ? 1.0 / dt : 0.0;
  for (int k = 0; k < nz; ++k) {
    const double dz = g.dz(k);
    for (int i = 0; i < nx; ++i) {
      const int c = g.cell(i, k);
      double b = 0.0;
      if (pb.cell_active[c]) {
        b = (f.u_star[g.face_x(i + 1, k)] - f.u_star[g.face_x(i, k)]) * dz +
            (f.w_star[g.face_z_above(c)] - f.w_star[g.face_z_below(c)]) * dx;
        const double dn = f.cell_porosity[c] - f.cell_porosity_prev[c];
        if (dn != 0.0 && f.cell_porosity_prev[c] > 0.0) b += dn * inv_dt * dx * dz;
      }
      rhs[c] = b;
    }
  }
}

}  // namespace

void assemble_pressure_problem(const Grid2D& grid, const ProjectionFields& fields, const ProjectionBoundary& bc,
                               double dt, PressureProblem& problem, std::vector<double>& rhs) {
  for (int c = 0; c < grid.ncell(); ++c) problem.cell_active[c] = fields.cell_porosity[c] > 0.0;
  assemble_x_faces(grid, fields, bc, problem);
  assemble_z_faces(grid, fields, problem);
  assemble_rhs(grid, fields, problem, dt, rhs);
}

void correct_velocities(const Grid2D& g, const ProjectionFields& f, const PressureProblem& problem,
                        const std::vector<double>& cell_p, std::vector<double>& face_u, std::vector<double>& face_w) {
  const int nx = g.nx(), nz = g.nz();
  const double dx = g.dx();
  for (int k = 0; k < nz; ++k) {
    for (int i = 0; i <= nx; ++i) {
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
  for (int k = 0; k <= nz; ++k) {
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
