"""Stress study of the multigrid-CG pressure solver against the direct one (not part of the test suite).

300 random problems up to 90 x 45 cells: water (rho 1000) under a wavy free surface and air (rho 1),
15 % of the cells porous with n = 10^(-3 U), up to 30 % scattered solid cells, random open top faces
(or none: closed boxes), a graded z grid, and a block whose face coefficients are scaled by a further
1e-3. Writes benchmarks/results/pressure_stress.md (iteration percentiles, agreement, failures).
Usage: PYTHONPATH=python python3 benchmarks/pressure_stress.py
"""
from __future__ import annotations

import sys
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT / "tests"))
from test_pressure_solver import random_case  # noqa: E402

from vofdem import PressureSolver, PressureSolverKind  # noqa: E402


def main(cases: int = 300, tol: float = 1e-8) -> None:
    rng = np.random.default_rng(123)
    iterations, errors, failures = [], [], []
    for _ in range(cases):
        nx, nz = int(rng.integers(1, 91)), int(rng.integers(1, 46))
        solid = 0.0 if rng.random() < 0.3 else 0.3 * rng.random()
        open_fraction = 0.0 if rng.random() < 0.3 else rng.random()
        grid, pb, rhs = random_case(rng, nx, nz, solid, open_fraction)
        i0, k0 = int(rng.integers(nx)), int(rng.integers(nz))
        i1, k1 = min(nx, i0 + int(rng.integers(20))), min(nz, k0 + int(rng.integers(10)))
        ax = pb.face_x_coef.reshape(nz, nx + 1)
        az = pb.face_z_coef.reshape(nz + 1, nx)
        ax[k0:k1, i0:i1 + 1] *= 1e-3
        az[k0:k1 + 1, i0:i1] *= 1e-3
        pd, pm = np.zeros(grid.ncell), np.zeros(grid.ncell)
        direct = PressureSolver(PressureSolverKind.EIGEN_DIRECT)
        direct.setup(grid, pb)
        direct.solve(rhs, pd, tol)
        mg = PressureSolver(PressureSolverKind.MULTIGRID_CG)
        mg.setup(grid, pb)
        try:
            st = mg.solve(rhs, pm, tol)
        except RuntimeError as e:
            failures.append(f"{nx} x {nz}, solid {solid:.2f}, open {open_fraction:.2f}: {e}")
            continue
        iterations.append(st.iterations)
        scale = np.abs(pd).max()
        errors.append(np.abs(pm - pd).max() / scale if scale > 0 else 0.0)
    it = np.array(iterations)
    err = np.array(errors)
    lines = [
        "# Pressure solver stress study",
        "",
        f"{cases} random problems (see benchmarks/pressure_stress.py), tol {tol:g}.",
        "",
        "| quantity | median | 90th percentile | max |",
        "|---|---:|---:|---:|",
        f"| multigrid CG iterations | {np.median(it):.0f} | {np.percentile(it, 90):.0f} | {it.max()} |",
        f"| max abs(p_mg - p_direct) / max abs(p_direct) | {np.median(err):.1e} | {np.percentile(err, 90):.1e} | "
        f"{err.max():.1e} |",
        "",
        f"Solves that stopped above tol: {len(failures)} of {cases}.",
    ] + [f"- {f}" for f in failures]
    dest = ROOT / "benchmarks" / "results" / "pressure_stress.md"
    dest.write_text("\n".join(lines) + "\n")
    print("\n".join(lines))


if __name__ == "__main__":
    main()
