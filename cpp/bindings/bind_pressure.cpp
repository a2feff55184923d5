#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include "views.h"
#include "vofdem/flow/pressure_solver.h"

namespace py = pybind11;

namespace vofdem::bind {

namespace {

using DoubleArray = py::array_t<double, py::array::c_style | py::array::forcecast>;

std::vector<double> to_vector(const DoubleArray& a) { return std::vector<double>(a.data(), a.data() + a.size()); }

// the pressure written back into a caller's float64 array, in place
void copy_into(const std::vector<double>& v, py::array_t<double, py::array::c_style>& a) {
  std::copy(v.begin(), v.end(), a.mutable_data());
}

}  // namespace

void bind_pressure(py::module_& m) {
  py::enum_<PressureSolverKind>(m, "PressureSolverKind", "Solver of the pressure Poisson problem of the projection (FlowParams.pressure_solver).")
      .value("EIGEN_DIRECT", PressureSolverKind::kEigenDirect, "Eigen sparse LDL^T: exact to round-off, the reference")
      .value("MULTIGRID_CG", PressureSolverKind::kMultigridCG,
             "conjugate gradient preconditioned by a geometric multigrid V-cycle: the default");

  py::class_<PressureProblem>(m, "PressureProblem",
                              "Face coefficients a_f, Dirichlet boundary values [Pa] and active cells of the pressure "
                              "equation sum_f a_f (p_nb - p_c) = b_c. Arrays are zero-copy numpy views.")
      .def(py::init([](const Grid2D& g) {
             PressureProblem p;
             p.resize(g);
             return p;
           }),
           py::arg("grid"))
      .def_property_readonly("face_x_coef", [](py::object s) { return view(s.cast<PressureProblem&>().face_x_coef, s); },
           "face coefficient a_f >= 0 on the x-faces, (nx + 1) nz [m^3 s/kg] (0 closes a face), zero-copy view")
      .def_property_readonly("face_z_coef", [](py::object s) { return view(s.cast<PressureProblem&>().face_z_coef, s); },
           "face coefficient a_f >= 0 on the z-faces, nx (nz + 1) [m^3 s/kg], zero-copy view")
      .def_property_readonly("face_x_bc", [](py::object s) { return view(s.cast<PressureProblem&>().face_x_bc, s); },
           "Dirichlet pressure on the boundary x-faces (i = 0, nx) [Pa], zero-copy view")
      .def_property_readonly("face_z_bc", [](py::object s) { return view(s.cast<PressureProblem&>().face_z_bc, s); },
           "Dirichlet pressure on the boundary z-faces (k = 0, nz) [Pa], zero-copy view")
      .def_property_readonly("cell_active",
                             [](py::object s) { return view(s.cast<PressureProblem&>().cell_active, s); },
           "1: an unknown of the equation, 0: a solid cell (ncell), zero-copy view");

  py::class_<PressureSolveStats>(m, "PressureSolveStats", "Outcome of one pressure solve.")
      .def_readonly("iterations", &PressureSolveStats::iterations, "CG iterations (0 for the direct solver)")
      .def_readonly("residual", &PressureSolveStats::residual, "final relative residual ||f - M p|| / ||f||")
      .def_readonly("setup_seconds", &PressureSolveStats::setup_seconds, "last setup wall time [s]")
      .def_readonly("solve_seconds", &PressureSolveStats::solve_seconds, "solve wall time [s]")
      .def("__repr__", [](const PressureSolveStats& s) {
        return "PressureSolveStats(iterations=" + std::to_string(s.iterations) +
               ", residual=" + std::to_string(s.residual) + ")";
      });

  py::class_<PressureSolver>(m, "PressureSolver", "Solver of the pressure projection equation.")
      .def(py::init([](PressureSolverKind kind, int max_iterations, int smoothing_sweeps, int coarsest_cells) {
             PressureSolverParams prm;
             prm.max_iterations = max_iterations;
             prm.smoothing_sweeps = smoothing_sweeps;
             prm.coarsest_cells = coarsest_cells;
             return make_pressure_solver(kind, prm);
           }),
           py::arg("kind") = PressureSolverKind::kMultigridCG, py::arg("max_iterations") = 200,
           py::arg("smoothing_sweeps") = 1, py::arg("coarsest_cells") = 64)
      .def_property_readonly("kind", &PressureSolver::kind,
           "the solver (PressureSolverKind) chosen at construction")
      .def("setup", &PressureSolver::setup, py::arg("grid"), py::arg("problem"),
           py::call_guard<py::gil_scoped_release>(), "takes new coefficients (call after any change)")
      .def(
          "solve",
          [](PressureSolver& s, const DoubleArray& rhs, py::array_t<double, py::array::c_style> p, double tol) {
            std::vector<double> b = to_vector(rhs), x(p.data(), p.data() + p.size());
            PressureSolveStats st;
            {
              py::gil_scoped_release release;
              st = s.solve(b, x, tol);
            }
            copy_into(x, p);
            return st;
          },
          py::arg("rhs"), py::arg("p").noconvert(), py::arg("tol") = 1e-8,
          "solves for p [Pa] in place (a C-contiguous float64 array of ncell values, also the initial guess); returns PressureSolveStats");

  m.def(
      "pressure_residual",
      [](const Grid2D& g, const PressureProblem& pb, const DoubleArray& rhs, const DoubleArray& p) {
        std::vector<double> r;
        pressure_residual(g, pb, to_vector(rhs), to_vector(p), r);
        return py::array_t<double>(static_cast<py::ssize_t>(r.size()), r.data());
      },
      py::arg("grid"), py::arg("problem"), py::arg("rhs"), py::arg("p"), "b - A p on active cells (0 elsewhere)");
}

}  // namespace vofdem::bind
