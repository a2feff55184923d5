"""Time-step limits of the Maeno 2008 flow on the paper's grid (147 x 46 cells, k-epsilon on), stones
held: forward-Euler viscous stresses against the implicit vertical diffusion (FlowParams.viscous_scheme,
its step bound FlowParams.viscous_bound), and where the eddy viscosity grows.

Builds the scene's coupled simulation (packed weir, porosity from the stones) and steps the flow alone
(the stones held, as in the spin-up), printing every `--every` s: the time-step limits, the largest
nu_t and the cell holding it (its water fraction F, porosity n, production P_k / eps), and the share of
the cells with nu_t above 1e-3 m^2/s that are interface cells (0.01 < F < 0.99), air (F <= 0.01),
porous (n < 1) or clear water. Writes benchmarks/results/maeno2008_viscous_<scheme>.md.

    OMP_NUM_THREADS=1 PYTHONPATH=python python3 benchmarks/maeno2008_viscous.py --scheme implicit --end-time 10
"""
import argparse
import os
import sys
import time
from pathlib import Path

os.environ.setdefault("OMP_NUM_THREADS", "1")
ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT / "python"))

import numpy as np  # noqa: E402

import vofdem  # noqa: E402
from vofdem.builder import build_simulation  # noqa: E402
from vofdem.scene import Scene  # noqa: E402


def where(fl):
    nut = np.asarray(fl.cell_nut)
    F = np.asarray(fl.cell_F)
    n = np.asarray(fl.cell_porosity)
    k, i = np.unravel_index(np.argmax(nut), nut.shape)
    big = nut > 1e-3
    cnt = max(int(big.sum()), 1)
    shares = (int((big & (F > 0.01) & (F < 0.99)).sum()) / cnt, int((big & (F <= 0.01)).sum()) / cnt,
              int((big & (F >= 0.99) & (n < 1)).sum()) / cnt, int((big & (F >= 0.99) & (n >= 1)).sum()) / cnt)
    x = (i + 0.5) * fl.grid.dx
    return nut.max(), x, k, F[k, i], n[k, i], int(big.sum()), shares


def binding_viscous_cell(fl, d):
    """The cell beside the face that sets the viscous limit (FlowStableDt.viscous_cell): its column,
    row and water fraction, and the limit of one viscous substep [s]."""
    if d.viscous_cell < 0:
        return "none"
    k, i = divmod(d.viscous_cell, fl.grid.nx)
    F = np.asarray(fl.cell_F)
    return f"cell ({i},{k}) F={F[k, i]:.2f} dt={d.viscous / fl.params.viscous_substeps:.1e}"


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--scheme", choices=["explicit", "implicit"], default="implicit")
    ap.add_argument("--bound", choices=["energy", "row_sum"], default="energy",
                    help="the implicit scheme's viscous step bound (FlowParams.viscous_bound)")
    ap.add_argument("--corner", choices=["arithmetic", "harmonic"], default="harmonic")
    ap.add_argument("--production", choices=["strain", "kato-launder", "limiter"], default="strain",
                    help="k production: standard, Kato-Launder, or standard capped at 10 eps (Menter)")
    ap.add_argument("--end-time", type=float, default=10.0)
    ap.add_argument("--every", type=float, default=1.0)
    args = ap.parse_args()
    scene = Scene.maeno2008()
    sim = build_simulation(scene)
    fl = sim.fluid
    p = fl.params
    p.viscous_scheme = (vofdem.ViscousScheme.EXPLICIT if args.scheme == "explicit"
                        else vofdem.ViscousScheme.IMPLICIT_VERTICAL)
    p.viscous_bound = vofdem.ViscousBound.ENERGY if args.bound == "energy" else vofdem.ViscousBound.ROW_SUM
    p.corner_viscosity = (vofdem.CornerViscosity.HARMONIC if args.corner == "harmonic"
                          else vofdem.CornerViscosity.ARITHMETIC)
    if args.production == "kato-launder":
        p.turbulence_production = vofdem.KEpsilonProduction.KATO_LAUNDER
    elif args.production == "limiter":
        p.turbulence_production_limit = 10.0
    fl.params = p
    g = fl.grid
    rows = []
    wall = 0.0
    t = 0.0
    steps0 = fl.step_count
    while t < args.end_time - 1e-9:
        t = min(t + args.every, args.end_time)
        s0 = fl.step_count
        w0 = time.perf_counter()
        fl.advance(t)
        dw = time.perf_counter() - w0
        wall += dw
        d = fl.stable_dt_terms()
        nut, x, k, F, n, nbig, sh = where(fl)
        lim = min(("advective", d.advective), ("viscous", d.viscous), ("gravity", d.gravity),
                  ("turbulence", d.turbulence), ("max_dt", d.max_dt), key=lambda v: v[1])[0]
        nsteps = fl.step_count - s0
        row = (f"| {t:.1f} | {nsteps} | {args.every / max(nsteps, 1):.2e} | {d.advective:.2e} | {d.viscous:.2e} | "
               f"{d.turbulence:.2e} | {lim} | {dw / args.every:.1f} | {nut:.2e} | x={x:.3f} z-row {k} F={F:.2f} n={n:.2f} | "
               f"{nbig} | {sh[0]:.2f} / {sh[1]:.2f} / {sh[2]:.2f} / {sh[3]:.2f} | "
               f"{binding_viscous_cell(fl, d)} |")
        print(row, flush=True)
        rows.append(row)
    steps = fl.step_count - steps0
    text = [f"# Maeno 2008 flow, stones held, paper's grid {g.nx} x {g.nz}: viscous scheme '{args.scheme}', corner viscosity '{args.corner}', "
            f"production '{args.production}'", "",
            f"Flow alone (VOFGrid.advance), OMP_NUM_THREADS=1 on a 2-core machine shared with other jobs; "
            f"{steps} steps, wall {wall:.1f} s for {args.end_time:.1f} s simulated: "
            f"**real-time factor {wall / args.end_time:.3g}**, mean dt {args.end_time / steps:.2e} s.", "",
            "Columns: time [s]; steps in the interval; their mean dt [s]; the limits at its end [s]; the binding "
            "limit; wall per simulated second in the interval; largest nu_t [m^2/s] and its cell; cells with "
            "nu_t > 1e-3 m^2/s; their shares interface / air / porous water / clear water.", "",
            "| t | steps | mean dt | advective | viscous | turbulence | binding | wall/sim | nu_t max | at | "
            "n(nu_t>1e-3) | shares | cell beside the face binding the viscous limit |",
            "|---|---|---|---|---|---|---|---|---|---|---|---|---|"] + rows
    suffix = ("" if args.production == "strain" else "_" + args.production) + (
        "_row_sum" if args.scheme == "implicit" and args.bound == "row_sum" else "")
    out = ROOT / "benchmarks" / "results" / f"maeno2008_viscous_{args.scheme}_{args.corner}{suffix}.md"
    out.write_text("\n".join(text) + "\n", encoding="utf-8")
    print("\n".join(text[:3]))


if __name__ == "__main__":
    main()
