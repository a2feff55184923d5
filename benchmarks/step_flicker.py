"""What drives the advective limit's two-step flicker on the grid four times as fine.

The Maeno spin-up (maeno2008_consistent, stones held, one thread) on a grid `--factor` times as fine as the
paper's is advanced from rest to --t0 with the given --set options (as benchmarks/grid_cost.py builds it),
its state copied, and then stepped one step at a time from that same state under variants of the
numerics, --steps steps each:

- `adaptive`: the steps as the run takes them (the stable step, its growth cap);
- `fixed dt`: every step the same length, the median step of `adaptive` times --fixed-scale: if the
  advective limit still flickers at a constant step the flow oscillates by itself; if not, the flicker is
  the step controller and the flow feeding each other (a step's length sets the velocities that set
  the next step's limit);
- `alternate dt`: steps alternating between 0.9 and 1.1 times that fixed step: the advective limit's
  response to the step's length, d log(limit after the step) / d log(dt);
- the adaptive steps with other values of one key (--vary KEY=V1,V2: e.g. numerics.time_scheme=euler).

A step that breaches the CFL is taken again at half its length (at most 4 times), as advance() does.

Reported per variant: the steps per simulated second, the share of the steps each limit set, the
flicker (the median of |log(L[n+1] / L[n])| of the advective limit L and the lag-one correlation of
its changes: -1 is a clean two-step cycle), the cells that bound it, and the first steps one by one at
the cell that bound most (dt, the limit, the velocities on the cell's faces, the porosities).

    PYTHONPATH=python python3 benchmarks/step_flicker.py [--factor 4] [--t0 3] [--steps 300] \
        [--set KEY=VALUE] [--vary KEY=V1,V2] [--tag TAG]
"""
import argparse
import math
import os
import platform
import sys
import time
from collections import Counter
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))
os.environ.setdefault("OMP_NUM_THREADS", "1")

import numpy as np  # noqa: E402

from vofdem import _core  # noqa: E402
from vofdem.builder import build_simulation, flow_params  # noqa: E402
from vofdem.ensemble import with_settings  # noqa: E402
from vofdem.scene import load_scene  # noqa: E402

import grid_cost  # noqa: E402
from grid_cost import cpu_seconds  # noqa: E402

ROOT = Path(__file__).resolve().parents[1]
SHOWN = 12  # steps printed one by one per variant
RETRIES = 4  # a breaching step taken again, halved, at most this often


def build(factor: float, settings) -> tuple:
    scene = load_scene(ROOT / "scenes" / "maeno2008_consistent.toml")
    scene = with_settings(scene, [*grid_cost.grid_settings(factor), *settings])
    sim = build_simulation(scene)
    sim.stones.stone_fixed[:] = True  # held, as in a run's spin-up
    return scene, sim


def cell_faces(sim, cell: int) -> dict:
    """The velocities [m/s] and porosities [-] on the four faces of a cell, its own porosity."""
    f = sim.fluid
    g = f.grid
    nx = g.nx
    i, k = cell % nx, cell // nx
    u, w = np.asarray(f.face_u).ravel(), np.asarray(f.face_w).ravel()
    nu, nw = np.asarray(f.face_x_porosity).ravel(), np.asarray(f.face_z_porosity).ravel()
    west, east = k * (nx + 1) + i, k * (nx + 1) + i + 1
    south, north = k * nx + i, (k + 1) * nx + i
    return dict(i=i, k=k, n=float(np.asarray(f.cell_porosity).ravel()[cell]), F=float(np.asarray(f.cell_F).ravel()[cell]),
                u_w=float(u[west]), u_e=float(u[east]), w_s=float(w[south]), w_n=float(w[north]),
                n_w=float(nu[west]), n_e=float(nu[east]), n_s=float(nw[south]), n_n=float(nw[north]))


def step_once(sim, dt=None) -> dict:
    """One coupled step (the stable one, or dt [s]), with the limits measured at its start."""
    terms = sim.fluid.stable_dt_terms()
    stable = sim.stable_dt()
    names = dict(advective=terms.advective, turbulence=terms.turbulence, growth=terms.growth,
                 max_dt=terms.max_dt, viscous=terms.viscous, gravity=terms.gravity)
    binding = min(names, key=names.get)
    if stable < names[binding]:
        binding = "coupler"
    h = stable if dt is None else dt
    row = dict(t=float(sim.time), dt=h, stable=stable, binding=binding, advective=terms.advective,
               cell=int(terms.advective_cell), growth=terms.growth, turbulence=terms.turbulence, retries=0)
    # a step that breaches the CFL is taken again at half its length, as advance() does (step_retry.h)
    for retry in range(RETRIES + 1):
        try:
            sim.step(row["dt"])
            return row
        except RuntimeError as e:
            if "CFL" not in str(e) or retry == RETRIES:
                raise
            row["dt"] *= 0.5
            row["retries"] += 1
    return row


def flicker(rows) -> tuple:
    """(median |log(L[n+1]/L[n])|, lag-one correlation of log(L[n+1]/L[n])) of the advective limit L."""
    lim = np.log([r["advective"] for r in rows])
    d = np.diff(lim)
    med = float(np.median(np.abs(d))) if len(d) else float("nan")
    # changes alike to round-off have no correlation to speak of
    corr = float(np.corrcoef(d[:-1], d[1:])[0, 1]) if len(d) > 2 and np.ptp(d) > 1e-12 else float("nan")
    return med, corr


def response(rows) -> float:
    """d log(L after a step) / d log(dt of that step), fitted over the rows (steps of varied length)."""
    dt = np.log([r["dt"] for r in rows[:-1]])
    after = np.log([r["advective"] for r in rows[1:]])
    if np.std(dt) == 0:
        return float("nan")
    return float(np.polyfit(dt, after, 1)[0])


def varied(params, scene, setting: str):
    """The flow's `params` with what the scene setting changes in the scene's FlowParams (the rest as run)."""
    base, other = flow_params(scene), flow_params(with_settings(scene, [setting]))
    out = params  # VOFGrid.params hands out a copy
    changed = [a for a in dir(base) if not a.startswith("_") and not callable(getattr(base, a))
               and repr(getattr(base, a)) != repr(getattr(other, a))]
    if not changed:
        raise ValueError(f"--vary {setting}: changes nothing in the flow's parameters")
    for a in changed:
        setattr(out, a, getattr(other, a))
    return out


def run_variant(sim, state, params, steps, dts=None, last_dt=None) -> dict:
    """`steps` steps from `state` under the flow's `params`; dts: each step's length (None: adaptive)."""
    sim.set_state(state)
    sim.fluid.params = params
    if last_dt is not None:
        sim.fluid.last_dt = last_dt
    rows, cells, faces = [], Counter(), []
    cpu0 = cpu_seconds()
    error = ""
    for s in range(steps):
        try:
            rows.append(step_once(sim, None if dts is None else dts[s % len(dts)]))
        except (RuntimeError, ValueError) as e:
            error = str(e).splitlines()[0][:200]
            break
        cells[rows[-1]["cell"]] += 1
    cpu = cpu_seconds() - cpu0
    top = cells.most_common(1)[0][0] if cells else -1
    return dict(rows=rows, cells=cells, top=top, cpu=cpu, error=error)


def replay_faces(sim, state, params, rows, cell, last_dt=None) -> list:
    """The first SHOWN steps again with the faces of `cell` read before each (the steps as taken)."""
    sim.set_state(state)
    sim.fluid.params = params
    if last_dt is not None:
        sim.fluid.last_dt = last_dt
    out = []
    for r in rows[:SHOWN]:
        out.append({**r, **cell_faces(sim, cell)})
        sim.step(r["dt"])
    return out


def summary(name, res, g) -> str:
    rows = res["rows"]
    if not rows:
        return f"| {name} | - | - | - | - | - | - | - | - | {res['error']} |"
    span = rows[-1]["t"] + rows[-1]["dt"] - rows[0]["t"]
    shares = Counter(r["binding"] for r in rows)
    share = ", ".join(f"{k} {100.0 * v / len(rows):.0f} %" for k, v in shares.most_common())
    med, corr = flicker(rows)
    top = ", ".join(f"({c % g.nx}, {c // g.nx}) {100.0 * v / len(rows):.0f} %" for c, v in res["cells"].most_common(3))
    mean_adv = float(np.exp(np.mean(np.log([r["advective"] for r in rows]))))
    retried = sum(1 for r in rows if r["retries"])
    return (f"| {name} | {len(rows)} | {len(rows) / span:.0f} | {1e3 * np.mean([r['dt'] for r in rows]):.4f} | "
            f"{1e3 * mean_adv:.4f} | {med:.3f} ({math.exp(-med):.2f} / {math.exp(med):.2f}) | {corr:+.2f} | "
            f"{share} | {retried} | {top} |{' stopped: ' + res['error'] if res['error'] else ''}")


def detail_rows(name, faces, nx: int) -> list:
    out = [f"{name}: the first steps at the cell that bound most, cell (i, k) = ({faces[0]['i']}, {faces[0]['k']}), "
           f"porosity {faces[0]['n']:.2f}; faces west, east, south, north: porosity "
           f"{faces[0]['n_w']:.2f}, {faces[0]['n_e']:.2f}, {faces[0]['n_s']:.2f}, {faces[0]['n_n']:.2f}", "",
           "| t [s] | dt [ms] | bound by | advective limit [ms] | its cell | u west | u east | w south | w north [m/s] | "
           "water fraction |", "|---|---|---|---|---|---|---|---|---|---|"]
    for r in faces:
        out.append(f"| {r['t']:.5f} | {1e3 * r['dt']:.4f} | {r['binding']} | {1e3 * r['advective']:.4f} | "
                   f"({r['cell'] % nx}, {r['cell'] // nx}) | {r['u_w']:+.4f} | {r['u_e']:+.4f} | "
                   f"{r['w_s']:+.4f} | {r['w_n']:+.4f} | {r['F']:.3f} |")
    return out


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--factor", type=float, default=4.0, help="the grid this many times as fine as the paper's")
    ap.add_argument("--t0", type=float, default=3.0, help="simulated time [s] the variants start from")
    ap.add_argument("--steps", type=int, default=300, help="steps of each variant")
    ap.add_argument("--fixed-scale", type=float, default=1.0, help="the fixed step over the adaptive median step")
    ap.add_argument("--set", action="append", default=[], metavar="KEY=VALUE", help="a scene value (repeatable)")
    ap.add_argument("--vary", action="append", default=[], metavar="KEY=V1,V2",
                    help="the variants again with these values of a scene key (repeatable)")
    ap.add_argument("--tag", default="")
    ap.add_argument("--out", type=Path, default=None)
    args = ap.parse_args(argv)
    if not (args.t0 > 0.0 and args.steps > 2):
        raise ValueError(f"--t0 = {args.t0} must be > 0 and --steps = {args.steps} > 2")
    _core.set_threads(1)
    cpu0 = cpu_seconds()
    scene, sim = build(args.factor, args.set)
    sim.advance(args.t0)
    spin_cpu = cpu_seconds() - cpu0
    state = sim.copy_state()
    last_dt = sim.fluid.last_dt
    g = sim.fluid.grid
    # the flow's params of each value of each varied key: a scene built with it (the state stays this one)
    variants = [("as set", sim.fluid.params)]
    for spec in args.vary:
        key, values = spec.split("=", 1)
        for v in values.split(","):
            variants.append((f"{key}={v}", varied(sim.fluid.params, scene, f"{key}={v}")))
    lines, details = [], []
    for v, (label, params) in enumerate(variants):
        ada = run_variant(sim, state, params, args.steps, last_dt=last_dt)
        lines.append(summary(f"{label}, adaptive", ada, g))
        runs = [(f"{label}, adaptive", ada)]
        # the fixed and the alternating steps of the first variant only (the question they answer is its)
        if ada["rows"] and v == 0:
            fixed = args.fixed_scale * float(np.median([r["dt"] for r in ada["rows"]]))
            fix = run_variant(sim, state, params, args.steps, dts=[fixed], last_dt=last_dt)
            alt = run_variant(sim, state, params, args.steps, dts=[0.9 * fixed, 1.1 * fixed], last_dt=last_dt)
            lines.append(summary(f"{label}, fixed dt {1e3 * fixed:.4f} ms", fix, g))
            lines.append(summary(f"{label}, dt alternating 0.9 / 1.1 of it", alt, g) +
                         f" response d log L / d log dt {response(alt['rows']):+.2f}")
            runs.append((f"{label}, fixed dt", fix))
        for name, res in runs:
            if res["rows"]:
                details += [*detail_rows(name, replay_faces(sim, state, params, res["rows"], res["top"], last_dt), g.nx), ""]
        print(*lines[-len(runs) - (1 if len(runs) > 1 else 0):], sep="\n", flush=True)
    note = (f"maeno2008_consistent, stones held, the grid {args.factor:g} times as fine as the paper's "
            f"({g.nx} x {g.nz} cells), advanced from rest to t0 = {args.t0:g} s ({spin_cpu:.0f} s of CPU), then "
            f"{args.steps} steps of each variant from that state"
            f"{'; settings ' + ', '.join(args.set) if args.set else ''}.")
    text = ["# The advective limit's two-step flicker", "",
            f"Generated by `benchmarks/step_flicker.py` on {time.strftime('%Y-%m-%d %H:%M UTC', time.gmtime())}, "
            f"{platform.processor() or platform.machine()}, one thread. {note}", "",
            "Flicker: the median of |log(L[n+1] / L[n])| of the advective limit L (in brackets the factors it "
            "stands for); lag-one correlation of those changes (-1: a clean two-step cycle). The response: "
            "the slope of log(L after a step) against log(dt of that step).", "",
            "| variant | steps | steps per s | mean dt [ms] | advective limit, geometric mean [ms] | flicker | "
            "lag-one correlation | bound by | steps retried | cells (i, k) that bound the advective limit |",
            "|---|---|---|---|---|---|---|---|---|---|", *lines, "", *details]
    name = "step_flicker" + (f"_{args.tag}" if args.tag else "")
    out = args.out or ROOT / "benchmarks" / "results" / f"{name}.md"
    out.write_text("\n".join(text) + "\n", encoding="utf-8")
    print(f"wrote {out}")
    return out


if __name__ == "__main__":
    main()
