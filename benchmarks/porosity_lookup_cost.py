"""What accuracy costs: the paper's porosity lookup table against the exact disc-cell areas.

On a weir-like packing of ~300 stones of 4.8 cm +-10 % on the paper's grid (2.5 cm x 1.0 cm cells,
0.5 cm rows up to 2 cm above the bed), maps the cell porosity of eq. (11) with the exact method and
with the lookup table for m = 2 .. 32 sub-areas per side, and reports the error of the lookup
(max and RMS of the cell porosity over the cells the stones touch) and the time per disc of one
mapping. Writes benchmarks/results/porosity_lookup_cost.md.

    python3 benchmarks/porosity_lookup_cost.py [--reps N] [--out PATH]
"""
from __future__ import annotations

import argparse
import os
import platform
import time

import numpy as np

import vofdem  # noqa: E402
from vofdem.packing import trapezoid_weir_discs  # noqa: E402

HERE = os.path.dirname(os.path.abspath(__file__))


def best_time_per_call(mapper, x, z, r, reps, rounds=15):
    """Best of `rounds` averages over `reps` calls [s] of process CPU time: the least disturbed by the
    other processes of a shared machine."""
    best = np.inf
    for _ in range(rounds):
        t0 = time.process_time()
        for _ in range(reps):
            mapper.map(x, z, r)
        best = min(best, (time.process_time() - t0) / reps)
    return best


def per_disc_cost(mapper, x, z, r, reps):
    """Time per disc [s]: a call with the discs minus an empty call (clearing + eq. 11 on every cell)."""
    empty = np.empty(0)
    t_empty = best_time_per_call(mapper, empty, empty, empty, reps)
    t_full = best_time_per_call(mapper, x, z, r, reps)
    return (t_full - t_empty) / x.size, t_full, t_empty


def errors(lookup, exact):
    touched = (lookup < 1.0) | (exact < 1.0)
    diff = (lookup - exact)[touched]
    return np.abs(diff).max(), np.sqrt(np.mean(diff**2)), int(touched.sum())


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--reps", type=int, default=100, help="calls per timing round")
    ap.add_argument("--out", default=os.path.join(HERE, "results", "porosity_lookup_cost.md"))
    args = ap.parse_args(argv)

    grid = vofdem.Grid2D.graded(nx=120, length_x=3.0, height_z=0.6, dz=0.01, dz_bed=0.005, z_bed_top=0.02)
    x, z, d = trapezoid_weir_discs(height=0.5, crest=0.5, slope_deg=27.0, d_mean=0.048, spread=0.10,
                                   x_toe=0.2, seed=1)
    r = 0.5 * d
    rmin, rmax = 0.9 * 0.024, 1.1 * 0.024
    n = x.size

    exact = vofdem.make_porosity_mapper(grid, rmin, rmax, method="exact", max_discs=n)
    exact.map(x, z, r)
    n_exact = np.array(exact.cell_porosity)
    t_exact, t_exact_call, t_empty = per_disc_cost(exact, x, z, r, args.reps)

    rows = []
    for m in (2, 4, 8, 16, 32):
        t0 = time.perf_counter()
        lk = vofdem.make_porosity_mapper(grid, rmin, rmax, method="lookup", m=m, dr=1e-3, max_discs=n)
        build = time.perf_counter() - t0
        lk.map(x, z, r)
        emax, erms, ntouched = errors(np.array(lk.cell_porosity), n_exact)
        t_disc, _, _ = per_disc_cost(lk, x, z, r, args.reps)
        rows.append((m, emax, erms, t_disc, t_exact / t_disc, build, lk.table_bytes / 2**20, lk.table_count))
        print(f"m={m:3d}  max|dn|={emax:.4f}  rms={erms:.5f}  {t_disc * 1e9:7.0f} ns/disc  "
              f"speed-up {t_exact / t_disc:5.1f}  tables {lk.table_bytes / 2**20:6.1f} MiB built in {build:.2f} s")

    # the radius interpolation alone: m fixed, the spacing of the radius nodes varied
    dr_rows = []
    for dr in (2e-3, 1e-3, 5e-4, 2.5e-4):
        lk = vofdem.make_porosity_mapper(grid, rmin, rmax, method="lookup", m=16, dr=dr, max_discs=n)
        lk.map(x, z, r)
        emax, erms, _ = errors(np.array(lk.cell_porosity), n_exact)
        dr_rows.append((dr, emax, erms, lk.table_bytes / 2**20))

    lines = [
        "# Porosity from stones: lookup table vs exact areas",
        "",
        f"{n} discs of 4.8 cm +-10 % (trapezoidal packing, 0.5 m high, 27 degree slopes) on the paper's grid "
        f"({grid.nx} x {grid.nz} cells, 2.5 cm x 1.0 cm, 0.5 cm rows up to 2 cm); {ntouched} cells touched. "
        "Error: cell porosity of eq. (11), lookup minus exact, over the touched cells. Time: one mapping "
        "call with the discs minus an empty call (clearing and eq. (11) on every cell, "
        f"{t_empty * 1e6:.1f} us here), divided by the number of discs; best of 15 rounds of "
        f"{args.reps} calls, process CPU time. Radius nodes every 1 mm (linear interpolation of A/r^2).",
        "",
        f"Exact method: **{t_exact * 1e9:.0f} ns per disc** ({t_exact_call * 1e6:.1f} us per call with {n} discs).",
        "",
        "| m | max abs error of n | RMS error of n | time per disc [ns] | speed-up vs exact | tables [MiB] | table build [s] |",
        "|---|---|---|---|---|---|---|",
    ]
    for m, emax, erms, t_disc, speed, build, mib, _ in rows:
        lines.append(f"| {m} | {emax:.4f} | {erms:.5f} | {t_disc * 1e9:.0f} | {speed:.1f} | {mib:.1f} | {build:.2f} |")
    lines += [
        "",
        "Radius interpolation alone (m = 16): error against the spacing of the radius nodes.",
        "",
        "| dr [mm] | max abs error of n | RMS error of n | tables [MiB] |",
        "|---|---|---|---|",
    ]
    for dr, emax, erms, mib in dr_rows:
        lines.append(f"| {dr * 1e3:.2f} | {emax:.4f} | {erms:.5f} | {mib:.1f} |")
    lines += ["", f"Machine: {platform.machine()}, {os.cpu_count()} cores shared; Python {platform.python_version()}.", ""]
    os.makedirs(os.path.dirname(os.path.abspath(args.out)), exist_ok=True)
    with open(args.out, "w") as f:
        f.write("\n".join(lines))
    print(f"exact: {t_exact * 1e9:.0f} ns/disc; wrote {args.out}")


if __name__ == "__main__":
    main()
