"""Cost of the flow against its grid: the Maeno spin-up on the paper's grid and on the grids two and four
times as fine in both directions (dx, dz, the bed row and its layer divided by 2 and 4).

For each grid the scene maeno2008_consistent is built with its stones held (a run's spin-up at 10 l/s)
and advanced from rest to --seconds of simulated time on one thread. Reported per grid: cells, steps,
the CPU time (getrusage, user + system: this process alone), the CPU per cell-step of each stage (the
profiles of the coupler, the flow and the k-epsilon model; stages nest: the flow's are parts of the
coupler's `fluid`, k-epsilon's of the flow's `turbulence`), the steps each time-step limit set
(Coupler.step_limits), the pressure solve's CG iterations per solve, and the answers at the end: the
held stones' loads (the sum of the drag and pressure forces on them), the upstream water level at
x = 0.49 m and the eddy viscosity's mean over the water. Ratios are to the first grid of the run (the
paper's). The aim of the grid study: twice as fine at most 9 times the paper grid's CPU (4 times the
cells, 2 times the steps), four times as fine at most 70 times.

--set KEY=VALUE sets scene values on every grid (e.g. numerics.turbulence_scheme=alternating_lines).
--small: the quick scene (Scene.quick: a shorter flume) on the draft grid and the grids two and four
times as fine as it, for 0.2 s (a test at tiny size). Writes benchmarks/results/grid_cost[_<tag>].md.

    PYTHONPATH=python python3 benchmarks/grid_cost.py [--seconds 20] [--factors 1 2 4] [--set KEY=VALUE]
"""
import argparse
import os
import platform
import resource
import time
from pathlib import Path

os.environ.setdefault("OMP_NUM_THREADS", "1")

import numpy as np  # noqa: E402

from vofdem import _core  # noqa: E402
from vofdem.builder import build_simulation  # noqa: E402
from vofdem.ensemble import with_settings  # noqa: E402
from vofdem.scene import load_scene  # noqa: E402

ROOT = Path(__file__).resolve().parents[1]
# the paper's grid [m]: cells dx x dz, the bed row dz_bed and its layer
PAPER = {"grid.dx": 0.025, "grid.dz": 0.01, "grid.dz_bed": 0.005, "grid.bed_layer_height": 0.005}
DRAFT_SCALE = 0.5  # --small: the draft grid (twice as coarse as the paper's) as its first grid
AIMS = {2: 9.0, 4: 70.0}  # the grid study's CPU aims against the paper's grid [-]


def grid_settings(factor: float) -> list:
    """The scene settings of a grid `factor` times as fine as the paper's in both directions."""
    return [f"{key}={value / factor!r}" for key, value in PAPER.items()]


def cpu_seconds() -> float:
    """CPU time of this process, user + system [s] (getrusage's resolution, not os.times' 10 ms)."""
    r = resource.getrusage(resource.RUSAGE_SELF)
    return r.ru_utime + r.ru_stime


def ratio(a: float, b: float) -> float:
    return a / b if b > 0 else float("nan")


def profiles(sim):
    return [("coupler", sim.profile), ("flow", sim.fluid.profile), ("k-epsilon", sim.fluid.turbulence_profile)]


def held_loads(sim) -> dict:
    """The drag + pressure forces [N] on the held (fixed) stones: their sum and the largest on one."""
    fixed = np.asarray(sim.stones.stone_fixed, bool)
    f = np.asarray(sim.stone_force_drag, float) + np.asarray(sim.stone_force_pressure, float)
    f = f[fixed] if fixed.any() else f[:0]
    mag = np.hypot(f[:, 0], f[:, 1]) if len(f) else np.zeros(0)
    return dict(fx=float(f[:, 0].sum()) if len(f) else 0.0, fz=float(f[:, 1].sum()) if len(f) else 0.0,
                largest=float(mag.max()) if len(mag) else 0.0, forces=f)


UPSTREAM_X = 0.49  # m: where the upstream water level is read (docs/k_epsilon.md's measure)


def flow_answers(sim) -> dict:
    """The flow's state the grids should agree on: the upstream water level [m] at UPSTREAM_X (the water
    fraction summed over its column) and the eddy viscosity's mean over the water cells (F >= 0.5) [m^2/s]."""
    g = sim.fluid.grid
    F, nut = np.asarray(sim.fluid.cell_F, float), np.asarray(sim.fluid.cell_nut, float)
    zf = np.asarray(g.z_faces, float)
    i = min(int((UPSTREAM_X - g.x0) / g.dx), g.nx - 1)
    water = F >= 0.5
    return dict(level=float(zf[0] + np.sum(F[:, i] * np.diff(zf))),
                nut_mean=float(nut[water].mean()) if water.any() else 0.0)


def held_spinup(factor: float, settings=(), small: bool = False, seed: int = 0):
    """(simulation, scene, factor on the paper's grid): the Maeno scene (consistent coupling) on the grid
    `factor` times as fine as the paper's, its stones held as in a run's spin-up (small: the quick scene,
    `factor` times as fine as the draft grid)."""
    scene = load_scene(ROOT / "scenes" / "maeno2008_consistent.toml").replace(seed=seed)
    if small:
        scene = scene.quick()
        factor = factor * DRAFT_SCALE
    scene = with_settings(scene, [*grid_settings(factor), *settings])
    sim = build_simulation(scene)
    sim.stones.stone_fixed[:] = True
    return sim, scene, factor


def run_grid(factor: float, seconds: float, settings=(), small: bool = False, keep=None) -> dict:
    """The spin-up (stones held) from rest to `seconds` on the grid `factor` times as fine as the paper's
    (--small: as the draft grid, on the quick scene): cost, steps, limits, pressure iterations, loads.
    keep(sim, result): a hook that adds to the result what else it needs of the simulation."""
    sim, scene, factor = held_spinup(factor, settings, small)
    for _, p in profiles(sim):
        p.reset()
    sim.clear_step_limits()
    it0, steps0, cpu0 = sim.fluid.pressure_iterations, sim.step_count, cpu_seconds()
    sim.advance(seconds)
    cpu, steps = cpu_seconds() - cpu0, sim.step_count - steps0
    stages = {f"{label} / {name}": (s, c) for label, p in profiles(sim)
              for name, s, c in zip(p.names, p.seconds, p.calls)}
    solves = dict(zip(sim.fluid.profile.names, sim.fluid.profile.calls)).get("pressure", 0)
    g = sim.fluid.grid
    res = dict(factor=factor, dx=scene.grid.dx, dz=scene.grid.dz, nx=g.nx, nz=g.nz, cells=g.nx * g.nz, seconds=seconds,
               steps=steps, cpu=cpu, stages=stages, limits={k: int(v) for k, v in dict(sim.step_limits()).items()},
               iterations=sim.fluid.pressure_iterations - it0, solves=int(solves), loads=held_loads(sim),
               time=float(sim.time), **flow_answers(sim))
    return keep(sim, res) if keep else res


def limit_shares(res) -> str:
    """'turbulence 80.1 %, advective 19.9 %': the share of the steps each limit set, largest first."""
    total = sum(res["limits"].values()) or 1
    items = sorted(res["limits"].items(), key=lambda kv: -kv[1])
    return ", ".join(f"{k} {100.0 * v / total:.1f} %" for k, v in items)


def per_solve(res) -> float:
    return res["iterations"] / res["solves"] if res["solves"] else float("nan")


def summary_rows(results) -> list:
    base = results[0]
    rows = ["| grid dx [cm] | cells | steps | steps / paper's | CPU [s] | CPU / paper's | CPU per cell-step [us] | "
            "CG iterations per pressure solve | held stones' load sum x, z [N] | upstream level [m] | "
            "mean nu_t in the water [m2/s] |",
            "|---|---|---|---|---|---|---|---|---|---|---|"]
    for r in results:
        rows.append(f"| {100 * r['dx']:.4g} | {r['nx']} x {r['nz']} = {r['cells']} | {r['steps']} | "
                    f"{r['steps'] / base['steps']:.2f} | {r['cpu']:.3g} | {ratio(r['cpu'], base['cpu']):.2f} | "
                    f"{1e6 * r['cpu'] / (r['cells'] * r['steps']):.3f} | {per_solve(r):.2f} | "
                    f"{r['loads']['fx']:.4f}, {r['loads']['fz']:.4f} | {r['level']:.4f} | {r['nut_mean']:.3e} |")
    return rows


def stage_rows(results) -> list:
    keys = [k for k in results[0]["stages"]]
    head = "| stage | " + " | ".join(f"dx {100 * r['dx']:.4g} cm" for r in results) + " |"
    rows = ["CPU per cell-step of each stage [ns] (the stage timers):", "", head,
            "|---|" + "---|" * len(results)]
    for key in keys:
        vals = [r["stages"].get(key, (0.0, 0))[0] / (r["cells"] * r["steps"]) for r in results]
        if max(vals) * 1e9 < 0.5:
            continue
        rows.append(f"| {key} | " + " | ".join(f"{1e9 * v:.1f}" for v in vals) + " |")
    return rows


def report(results, title: str, note: str) -> str:
    base = results[0]
    text = [f"# {title}", "",
            f"Generated by `benchmarks/grid_cost.py` on {time.strftime('%Y-%m-%d %H:%M UTC', time.gmtime())}, "
            f"{platform.processor() or platform.machine()}, one thread. {note}", "",
            *summary_rows(results), "", "Steps set by each limit (Coupler.step_limits):", ""]
    for r in results:
        text.append(f"- dx {100 * r['dx']:.4g} cm: {limit_shares(r)}")
    text += ["", *stage_rows(results), ""]
    for r in results[1:]:
        finer = r["factor"] / base["factor"]
        aim = AIMS.get(int(round(finer)))
        if aim:
            cpu = ratio(r["cpu"], base["cpu"])
            text.append(f"Grid {finer:g} times as fine: CPU {cpu:.1f} times the first grid's "
                        f"(aim: at most {aim:g}): {'met' if cpu <= aim else 'NOT met'}.")
    return "\n".join(text) + "\n"


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--seconds", type=float, default=None, help="simulated time from rest [s] (20; --small 0.2)")
    ap.add_argument("--factors", type=float, nargs="+", default=[1.0, 2.0, 4.0],
                    help="grids this many times as fine as the paper's (--small: as the draft grid)")
    ap.add_argument("--set", action="append", default=[], metavar="KEY=VALUE", help="a scene value (repeatable)")
    ap.add_argument("--small", action="store_true", help="the quick scene on the draft grid and finer, 0.2 s")
    ap.add_argument("--tag", default="", help="suffix of the results file's name")
    ap.add_argument("--out", type=Path, default=None)
    args = ap.parse_args(argv)
    seconds = args.seconds if args.seconds is not None else (0.2 if args.small else 20.0)
    if not seconds > 0.0:
        raise ValueError(f"--seconds = {seconds}: must be > 0")
    _core.set_threads(1)
    results = []
    for f in args.factors:
        results.append(run_grid(f, seconds, args.set, args.small))
        r = results[-1]
        print(f"dx {100 * r['dx']:.4g} cm: {r['steps']} steps, {r['cpu']:.1f} s CPU; {limit_shares(r)}; "
              f"{per_solve(r):.2f} CG iterations per solve", flush=True)
    what = ("the quick scene (shortened flume) on the draft grid and finer" if args.small else
            "maeno2008_consistent on the paper's grid and finer")
    note = (f"{what}, stones held (a run's spin-up at 10 l/s), from rest to {seconds:g} s simulated"
            f"{'; settings ' + ', '.join(args.set) if args.set else ''}. Ratios to the first grid. The machine "
            "(2 cores) is shared with other work: CPU times, not wall times.")
    name = "grid_cost" + ("_small" if args.small else "") + (f"_{args.tag}" if args.tag else "")
    out = args.out or ROOT / "benchmarks" / "results" / f"{name}.md"
    out.write_text(report(results, "Cost of the flow against its grid", note), encoding="utf-8")
    print(f"wrote {out}")
    return out


if __name__ == "__main__":
    main()
