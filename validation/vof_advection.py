"""Accuracy and cost of the geometric VOF advection; writes validation/results/vof_advection.md.

Accuracy: Rider & Kothe's reversed single vortex (T = 2 and 8) at 32, 64, 128 cells per side,
Zalesak's slotted disc (one revolution), and the boundedness against the CFL number.
Cost: runs the Google Benchmark binary bench_vof_advection (built with -DVOFDEM_BENCHMARKS=ON) if
given, and tabulates its CPU time per cell and step.

    PYTHONPATH=python python3 validation/vof_advection.py [--bench build-bench/bench_vof_advection]
"""
from __future__ import annotations

import argparse
import json
import pathlib
import platform
import subprocess
import time

import numpy as np

import vofdem

RESULTS = pathlib.Path(__file__).resolve().parent / "results" / "vof_advection.md"


def face_velocities(grid, psi):
    """Discretely divergence-free (u, w) from a stream function at the cell corners."""
    xf = grid.x0 + grid.dx * np.arange(grid.nx + 1)
    zf = np.asarray(grid.z_faces)
    node = psi(xf[None, :], zf[:, None])
    u = (node[1:, :] - node[:-1, :]) / np.diff(zf)[:, None]
    w = -(node[:, 1:] - node[:, :-1]) / grid.dx
    return np.ascontiguousarray(u.ravel()), np.ascontiguousarray(w.ravel())


def fractions(grid, inside, ns=16):
    """Cell fractions of the region inside(x, z) by ns x ns sub-sampling (uniform grids)."""
    nx, nz = grid.nx, grid.nz
    zf = np.asarray(grid.z_faces)
    s = (np.arange(ns) + 0.5) / ns
    x = grid.x0 + grid.dx * (np.arange(nx)[:, None] + s[None, :])  # (nx, ns)
    dz = np.diff(zf)
    z = zf[:-1, None] + dz[:, None] * s[None, :]  # (nz, ns)
    X = x[None, :, None, :]
    Z = z[:, None, :, None]
    return inside(X, Z).mean(axis=(2, 3)).ravel()


def vortex_psi(x, z):
    return np.sin(np.pi * x) ** 2 * np.sin(np.pi * z) ** 2 / np.pi


def reversed_vortex(N, period, cfl=0.3, normal=vofdem.VofNormal.YOUNGS):
    g = vofdem.Grid2D.uniform(N, N, 1.0, 1.0)
    n = np.ones(g.ncell)
    u0, w0 = face_velocities(g, vortex_psi)
    f = fractions(g, lambda x, z: (x - 0.5) ** 2 + (z - 0.75) ** 2 < 0.15**2)
    f0 = f.copy()
    steps = int(np.ceil(period / vofdem.vof_stable_dt(g, n, u0, w0, cfl)))
    dt = period / steps
    inflow, scratch = vofdem.VofBoundaryInflow(), vofdem.VofScratch()
    u, w = u0.copy(), w0.copy()
    area = g.dx * g.dx
    v0 = f.sum() * area
    for s in range(steps):
        scale = np.cos(np.pi * (s + 0.5) * dt / period)
        np.multiply(u0, scale, out=u)
        np.multiply(w0, scale, out=w)
        vofdem.advect_vof(g, n, u, w, inflow, dt, s % 2 == 0, f, scratch, normal)
    return {
        "N": N,
        "steps": steps,
        "l1": np.abs(f - f0).sum() * area,
        "dvol": abs(f.sum() * area / v0 - 1.0),
        "fmin": f.min(),
        "fmax": f.max(),
        "clips": scratch.clip_count,
    }


def zalesak(N, normal=vofdem.VofNormal.YOUNGS):
    # domain 100 x 100, disc r = 15 at (50, 75), slot 5 wide from z = 60 to 85, one revolution
    g = vofdem.Grid2D.uniform(N, N, 100.0, 100.0)
    n = np.ones(g.ncell)
    omega = 2 * np.pi / 628.0
    u, w = face_velocities(g, lambda x, z: -0.5 * omega * ((x - 50) ** 2 + (z - 50) ** 2))

    def disc(x, z):
        return ((x - 50) ** 2 + (z - 75) ** 2 < 15**2) & ~((np.abs(x - 50) < 2.5) & (z < 85))

    f = fractions(g, disc)
    f0 = f.copy()
    steps = int(np.ceil(628.0 / vofdem.vof_stable_dt(g, n, u, w, 0.3)))
    dt = 628.0 / steps
    inflow, scratch = vofdem.VofBoundaryInflow(g, 0.0), vofdem.VofScratch()
    for s in range(steps):
        vofdem.advect_vof(g, n, u, w, inflow, dt, s % 2 == 0, f, scratch, normal)
    return {"N": N, "steps": steps, "rel_l1": np.abs(f - f0).sum() / f0.sum(), "clips": scratch.clip_count}


def cfl_sweep(N=64, period=2.0):
    rows = []
    for cfl in (0.3, 0.45, 0.5, 0.6, 0.8):
        r = reversed_vortex(N, period, cfl)
        r["cfl"] = cfl
        rows.append(r)
    return rows


def run_bench(binary):
    out = subprocess.run(
        [binary, "--benchmark_format=json", "--benchmark_min_time=0.5"], check=True, capture_output=True, text=True
    ).stdout
    return json.loads(out)["benchmarks"]


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--bench", help="path of the bench_vof_advection binary")
    args = ap.parse_args()
    t0 = time.time()
    lines = ["# VOF advection: accuracy and cost", ""]
    lines += [
        f"Written by `validation/vof_advection.py` on {platform.node()} ({platform.machine()}), "
        f"{time.strftime('%Y-%m-%d %H:%M UTC', time.gmtime())}.",
        "",
    ]
    normals = [("Youngs", vofdem.VofNormal.YOUNGS), ("mixed Youngs-centred", vofdem.VofNormal.MIXED_YOUNGS_CENTERED)]
    for period in (2.0, 8.0):
        for label, normal in normals:
            rows = [reversed_vortex(N, period, normal=normal) for N in (32, 64, 128)]
            lines += [
                f"## Reversed single vortex, T = {period:g}, {label} normal",
                "",
                "CFL 0.3, circle r = 0.15 at (0.5, 0.75); L1 = sum |F(T) - F(0)| dx dz.",
                "",
                "| N | steps | L1 | order | rel. volume change | min F | max F | clips |",
                "|---|---|---|---|---|---|---|---|",
            ]
            for a, r in enumerate(rows):
                order = f"{np.log2(rows[a - 1]['l1'] / r['l1']):.2f}" if a else "-"
                lines.append(
                    f"| {r['N']} | {r['steps']} | {r['l1']:.3e} | {order} | {r['dvol']:.1e} | {r['fmin']:.2g} | "
                    f"{r['fmax']:.17g} | {r['clips']} |"
                )
            lines.append("")
    lines += [
        "## Zalesak's slotted disc, one revolution (CFL 0.3)",
        "",
        "Relative error sum |F - F0| / sum F0.",
        "",
        "| normal | N | steps | rel. L1 | clips |",
        "|---|---|---|---|---|",
    ]
    for label, normal in normals:
        for N in (100, 200):
            r = zalesak(N, normal)
            lines.append(f"| {label} | {r['N']} | {r['steps']} | {r['rel_l1']:.3e} | {r['clips']} |")
    lines.append("")
    rows = cfl_sweep()
    lines += [
        "## Boundedness against the CFL number (reversed vortex T = 2, N = 64)",
        "",
        "clips = cell updates that left [0, 1] by more than 1e-12 (clipped and counted).",
        "",
        "| CFL | L1 | min F | max F | clips |",
        "|---|---|---|---|---|",
    ]
    lines += [
        f"| {r['cfl']:g} | {r['l1']:.3e} | {r['fmin']:.3g} | {r['fmax']:.17g} | {r['clips']} |" for r in rows
    ]
    lines.append("")
    if args.bench:
        bench = run_bench(args.bench)
        lines += [
            "## Cost per cell and step (Google Benchmark, CPU time, both sweeps and the CFL check)",
            "",
            "| case | cells | interface cells | ns / cell / step | us / step |",
            "|---|---|---|---|---|",
        ]
        for b in bench:
            lines.append(
                f"| {b['name']} | {b['cells']:.0f} | {100 * b['mixed_share']:.2f} % | {b['ns_per_cell']:.1f} | "
                f"{b['cpu_time']:.0f} |"
            )
        lines.append("")
    lines.append(f"Total run time of this script: {time.time() - t0:.0f} s.")
    RESULTS.parent.mkdir(parents=True, exist_ok=True)
    RESULTS.write_text("\n".join(lines) + "\n")
    print("\n".join(lines))


if __name__ == "__main__":
    main()
