"""Pressure projection solvers: hand-computed systems, direct vs multigrid-CG, convergence order."""
from __future__ import annotations

import numpy as np
import pytest

import vofdem
from vofdem import Grid2D, PressureProblem, PressureSolver, PressureSolverKind

DIRECT = PressureSolverKind.EIGEN_DIRECT
MGCG = PressureSolverKind.MULTIGRID_CG
KINDS = [DIRECT, MGCG]


def fv_problem(grid, beta, active, open_top, top_bc):
    """Finite-volume coefficients beta_f * face length / centre distance, harmonic face beta [m^3 s/kg]."""
    nx, nz = grid.nx, grid.nz
    zf = np.asarray(grid.z_faces)
    dz = np.diff(zf)
    zc = 0.5 * (zf[1:] + zf[:-1])
    beta = beta.reshape(nz, nx)
    act = active.reshape(nz, nx).astype(bool)
    pb = PressureProblem(grid)
    pb.cell_active[:] = act.ravel()
    hm = lambda a, b: 2 * a * b / (a + b)  # noqa: E731
    ax = pb.face_x_coef.reshape(nz, nx + 1)
    ax[:, 1:nx] = np.where(act[:, 1:] & act[:, :-1], hm(beta[:, 1:], beta[:, :-1]), 0.0) * (dz[:, None] / grid.dx)
    az = pb.face_z_coef.reshape(nz + 1, nx)
    dzc = np.diff(zc)
    az[1:nz, :] = np.where(act[1:, :] & act[:-1, :], hm(beta[1:, :], beta[:-1, :]), 0.0) * (grid.dx / dzc[:, None])
    top = open_top & act[-1]
    az[nz, :] = np.where(top, beta[-1] * grid.dx / (0.5 * dz[-1]), 0.0)
    pb.face_z_bc.reshape(nz + 1, nx)[nz, :] = np.where(top, top_bc, 0.0)
    return pb


def random_case(rng, nx, nz, solid_fraction=0.05, open_fraction=0.3):
    """Water (rho 1000) under a wavy free surface, air (rho 1) above, porous and solid cells, graded z."""
    zf = np.concatenate([[0.0], np.cumsum(0.01 * (0.5 + rng.random(nz)))])
    grid = Grid2D(nx, 0.02, list(zf))
    xc = 0.02 * (np.arange(nx) + 0.5)
    zc = 0.5 * (zf[1:] + zf[:-1])
    h = zf[-1] * (0.3 + 0.4 * rng.random())
    eta = h + 0.2 * h * np.sin((2 + 6 * rng.random()) * xc / (0.02 * nx))
    rho = np.where(zc[:, None] < eta[None, :], 1000.0, 1.0)
    n = np.where(rng.random((nz, nx)) < 0.15, 10.0 ** (-3 * rng.random((nz, nx))), 1.0)
    beta = (1e-3 * n / rho).ravel()
    active = (rng.random(nx * nz) >= solid_fraction).astype(np.uint8)
    pb = fv_problem(grid, beta, active, rng.random(nx) < open_fraction, 100 * (rng.random(nx) - 0.5))
    rhs = np.where(active > 0, 1e-6 * (rng.random(nx * nz) - 0.5), 0.0)
    return grid, pb, rhs


@pytest.mark.parametrize("kind", KINDS)
def test_two_cells_by_hand(kind):
    # cell 0: 1 (p1 - p0) + 2 (0 - p0) = 0; cell 1: 1 (p0 - p1) = 1  ->  p = (-0.5, -1.5)
    g = Grid2D.uniform(2, 1, 2.0, 1.0)
    pb = PressureProblem(g)
    pb.face_x_coef[:2] = [2.0, 1.0]
    s = PressureSolver(kind)
    s.setup(g, pb)
    p = np.zeros(2)
    s.solve(np.array([0.0, 1.0]), p, 1e-12)
    np.testing.assert_allclose(p, [-0.5, -1.5], atol=1e-12)


@pytest.mark.parametrize("kind", KINDS)
def test_singular_box_returns_zero_mean_solution(kind):
    rng = np.random.default_rng(3)
    grid, pb, rhs = random_case(rng, 13, 9, solid_fraction=0.0, open_fraction=0.0)
    rhs -= rhs.mean()
    s = PressureSolver(kind)
    s.setup(grid, pb)
    p = np.zeros(grid.ncell)
    st = s.solve(rhs, p, 1e-10)
    assert st.residual < 1e-10
    assert abs(p.mean()) < 1e-12 * np.abs(p).max()
    r = vofdem.pressure_residual(grid, pb, rhs, p)
    assert np.abs(r).max() < 1e-9 * np.abs(rhs).max()


def test_problem_arrays_are_views_that_keep_the_owner_alive():
    g = Grid2D.uniform(3, 2, 3.0, 2.0)
    pb = PressureProblem(g)
    a = pb.face_z_coef
    a[4] = 2.5
    del pb
    assert a.shape == (g.nx * (g.nz + 1),) and a[4] == 2.5


def test_bad_input_is_a_value_error():
    g = Grid2D.uniform(3, 2, 3.0, 2.0)
    pb = PressureProblem(g)
    pb.face_x_coef[1] = -1.0
    with pytest.raises(ValueError, match="face_x_coef"):
        PressureSolver(DIRECT).setup(g, pb)


@pytest.mark.parametrize(
    ("nx", "nz", "solid", "open_fraction"),
    [(35, 12, 0.05, 0.3), (100, 35, 0.02, 0.5), (17, 40, 0.1, 0.0), (64, 3, 0.0, 1.0)],
)
def test_multigrid_cg_agrees_with_direct(nx, nz, solid, open_fraction):
    rng = np.random.default_rng(nx * 1000 + nz)
    grid, pb, rhs = random_case(rng, nx, nz, solid, open_fraction)
    pd = np.zeros(grid.ncell)
    pm = np.zeros(grid.ncell)
    direct = PressureSolver(DIRECT)
    direct.setup(grid, pb)
    direct.solve(rhs, pd, 1e-9)
    mg = PressureSolver(MGCG)
    mg.setup(grid, pb)
    st = mg.solve(rhs, pm, 1e-12)
    assert st.residual <= 1e-12 and 0 < st.iterations < 40
    np.testing.assert_allclose(pm, pd, rtol=0, atol=1e-8 * np.abs(pd).max())
    if open_fraction > 0:  # (a singular rhs is not compatible: its residual is the removed mean)
        r = vofdem.pressure_residual(grid, pb, rhs, pm)
        # b - A p, relative to the size of the terms a_f (p_nb - p_c) of the equation
        scale = max(pb.face_x_coef.max(), pb.face_z_coef.max()) * np.abs(pm).max()
        assert np.abs(r).max() < 1e-10 * scale


def test_non_convergence_is_a_runtime_error():
    rng = np.random.default_rng(1)
    grid, pb, rhs = random_case(rng, 48, 24)
    s = PressureSolver(MGCG, max_iterations=1)
    s.setup(grid, pb)
    p = np.ones(grid.ncell)
    with pytest.raises(RuntimeError, match="no convergence after 1 iterations"):
        s.solve(rhs, p, 1e-10)
    assert np.all(p == 1.0)


def test_solve_refuses_a_p_it_cannot_write_in_place():
    g = Grid2D.uniform(2, 1, 2.0, 1.0)
    s = PressureSolver(MGCG)
    s.setup(g, PressureProblem(g))
    with pytest.raises(TypeError):
        s.solve(np.zeros(2), np.zeros(2, dtype=np.float32))
