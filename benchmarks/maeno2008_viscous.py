"""Time-step limits of the Maeno 2008 flow on the paper's grid (147 x 46 cells, k-epsilon on), stones
held: forward-Euler viscous stresses against the implicit vertical diffusion (FlowParams.viscous_scheme),
and where the eddy viscosity grows.

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


def binding_viscous_face(fl, implicit):
    """The face whose Gershgorin row sets the viscous limit (numpy copy of viscous_stable_dt): returns
    'x' or 'z', its column, row, the water fractions of the cells around it and its density."""
    g = fl.grid
    nx, nz, dx = g.nx, g.nz, g.dx
    zf = np.asarray(g.z_faces)
    dz = np.diff(zf)
    zc = 0.5 * (zf[1:] + zf[:-1])
    F = np.clip(np.asarray(fl.cell_F), 0, 1)
    p = fl.params
    rho = F * p.rho_water + (1 - F) * p.rho_air
    mu = F * p.rho_water * p.nu_water + (1 - F) * p.rho_air * p.nu_air + rho * np.asarray(fl.cell_nut)
    eddy = rho * np.asarray(fl.cell_nut)

    def corners(a):
        pad = np.pad(a, 1, mode="edge")
        return np.stack([pad[:-1, :-1], pad[:-1, 1:], pad[1:, :-1], pad[1:, 1:]])

    cm = corners(mu).mean(axis=0)
    if str(p.corner_viscosity).endswith("HARMONIC"):
        e = corners(eddy)
        allpos = (e > 0).all(axis=0)
        harm = np.where(allpos, 4.0 / np.where(e > 0, 1.0 / np.where(e > 0, e, 1.0), 0.0).sum(axis=0).clip(1e-300), 0.0)
        cm = cm - e.mean(axis=0) + harm
    zfac = 0.0 if implicit else 1.0
    nfx = np.asarray(fl.face_x_porosity)
    nfz = np.asarray(fl.face_z_porosity)
    rfx = 0.5 * (rho[:, :-1] + rho[:, 1:])
    ml, mr = mu[:, :-1], mu[:, 1:]
    mn, ms = cm[1:, 1:-1], cm[:-1, 1:-1]
    d = dz[:, None]
    rate_x = (2 * (2 * (ml + mr) / dx**2 + zfac * (mn + ms) / d**2) + 2 * (mn + ms) / (dx * d)) / rfx
    rate_x[nfx[:, 1:-1] <= 0] = 0
    rfz = 0.5 * (rho[:-1, :] + rho[1:, :])
    dzc = np.diff(zc)[:, None]
    hz = np.minimum(dz[1:], dz[:-1])[:, None]
    mb, mt = mu[:-1, :], mu[1:, :]
    me, mw = cm[1:-1, 1:], cm[1:-1, :-1]
    rate_z = (2 * (zfac * 2 * (mb + mt) / (dzc * hz) + (me + mw) / dx**2) + 2 * (me + mw) / (dx * hz)) / rfz
    rate_z[nfz[1:-1, :] <= 0] = 0
    if rate_x.max() >= rate_z.max():
        k, i = np.unravel_index(np.argmax(rate_x), rate_x.shape)
        return f"x-face ({i + 1},{k}) F={F[k, i]:.2f}|{F[k, i + 1]:.2f} rho={rfx[k, i]:.0f} dt={2 / rate_x.max():.1e}"
    k, i = np.unravel_index(np.argmax(rate_z), rate_z.shape)
    return f"z-face ({i},{k + 1}) F={F[k, i]:.2f}|{F[k + 1, i]:.2f} rho={rfz[k, i]:.0f} dt={2 / rate_z.max():.1e}"


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--scheme", choices=["explicit", "implicit"], default="implicit")
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
               f"{binding_viscous_face(fl, args.scheme == 'implicit')} |")
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
            "n(nu_t>1e-3) | shares | face binding the viscous limit |",
            "|---|---|---|---|---|---|---|---|---|---|---|---|---|"] + rows
    suffix = "" if args.production == "strain" else "_" + args.production
    out = ROOT / "benchmarks" / "results" / f"maeno2008_viscous_{args.scheme}_{args.corner}{suffix}.md"
    out.write_text("\n".join(text) + "\n", encoding="utf-8")
    print("\n".join(text[:3]))


if __name__ == "__main__":
    main()
