"""The whole Maeno 2008 scenario with both couplings, before and after the step-count work, in one run.

For each of scenes/maeno2008.toml (the paper's coupling) and scenes/maeno2008_consistent.toml (bed drag,
bulk porosity mapping) it runs the scenario twice, one after the other in this process, on one core:

- before: the former numerics reached through the scene's parameters: forward-Euler convection
  (numerics.time_scheme = "euler"), point-implicit k-epsilon ("point_implicit"), the drag held over
  the exchange step ("held"), CFL 0.3, pressure tolerance 1e-8, the explicit viscous stresses in one step
  (numerics.viscous_substeps = 1), the column solves of the vertical stresses from the step's start
  (numerics.viscous_scheme = "implicit_vertical_from_start", whose step bound is the row sums of the
  explicit stresses, numerics.viscous_bound = "row_sum"), and the grid's remainder under the top as a row of
  its own (grid.merge_fraction = 0: a 0.5 cm sliver row under the open top), the domain 0.45 m high
  (flume.height) and the start water filled before the stones, which push it up over the weir
  (flume.initial_water = "displaced"), and the inlet's discharge spread over its rows by water fraction
  (numerics.inlet_profile = "water_fraction"). (Two changes are not switchable: the stones' step limit per
  direction, where the former one bound both directions by the smallest cell; and the open end's
  outflow, whose own momentum flux is now implicit and whose Courant number counts half in the step.)
- after: the scene as it is (Adams-Bashforth 2, column-implicit k-epsilon, implicit drag exchange,
  CFL 0.5, pressure tolerance 1e-5, up to 8 viscous substeps, the column solves after the explicit
  stresses, the energy bound of their step, the sliver joined to the row below it, the domain 0.38 m
  high, the start water at rest in the pores, the inlet's discharge over the rows below its level).
- candidate (with --candidate KEY=VALUE ...): the scene with those settings, e.g. the viscous stresses'
  rows implicit and the k-epsilon model's step limit off:
  --candidate numerics.viscous_scheme=implicit numerics.turbulence_step_limit=false

Writes benchmarks/results/maeno2008_before_after.md: wall and CPU time (time.process_time: the machine
is shared, CPU time is the steadier figure), steps, which limit bound the steps, the per-stage
profile, and the stage table of each run.

    OMP_NUM_THREADS=1 PYTHONPATH=python python3 benchmarks/maeno2008_before_after.py [--end-time T]
        [--variants after candidate --candidate KEY=VALUE ... --out FILE]
"""
import argparse
import dataclasses
import os
import platform
import tempfile
import time
from pathlib import Path

import numpy as np

os.environ.setdefault("OMP_NUM_THREADS", "1")
ROOT = Path(__file__).resolve().parents[1]

from vofdem.builder import build_simulation  # noqa: E402
from vofdem.ensemble import with_settings  # noqa: E402
from vofdem.run import run_scene  # noqa: E402
from vofdem.scene import load_scene  # noqa: E402
from vofdem.study import write_page  # noqa: E402

BEFORE = dict(time_scheme="euler", turbulence_scheme="point_implicit", drag_exchange="held", cfl=0.3,
              pressure_tolerance=1e-8, viscous_substeps=1, viscous_scheme="implicit_vertical_from_start", viscous_bound="row_sum",
              inlet_profile="water_fraction")
BEFORE_GRID = dict(merge_fraction=0.0)
BEFORE_FLUME = dict(height=0.45, initial_water="displaced")


def variant(scene, which, candidate=()):
    if which == "after":
        return scene
    if which == "candidate":
        return with_settings(scene, candidate)
    return scene.replace(numerics=dataclasses.replace(scene.numerics, **BEFORE),
                         grid=dataclasses.replace(scene.grid, **BEFORE_GRID),
                         flume=dataclasses.replace(scene.flume, **BEFORE_FLUME))


def run_one(scene, tmp):
    """Runs a scene to its end without figures; returns a dict of its figures and tables."""
    sim = build_simulation(scene)
    load0 = os.getloadavg()[0]
    cpu0, wall0 = time.process_time(), time.perf_counter()
    res = run_scene(scene, tmp, sim=sim, progress=False, figures=False, animation=False, log=lambda *a: None)
    cpu, wall = time.process_time() - cpu0, time.perf_counter() - wall0
    limits = dict(sim.step_limits())
    return dict(steps=int(sim.step_count), cpu=cpu, wall=wall, simulated=res.simulated_seconds, limits=limits,
                where=where_text(sim),
                profile=res.profile_table, stages=res.analysis.stage_table_markdown(),
                load=(load0, os.getloadavg()[0]))


def where_text(sim, top: int = 3) -> str:
    """The cells where each limit bound most often: (x, z) of the cell centre [m] and its steps."""
    g = sim.fluid.grid
    zf = np.asarray(g.z_faces)
    parts = []
    for term, counts in sorted(sim.step_limit_cells().items()):
        best = np.argsort(counts)[::-1][:top]
        cells = [f"({(c % g.nx + 0.5) * g.dx:.3f}, {0.5 * (zf[c // g.nx] + zf[c // g.nx + 1]):.4f}) m: {counts[c]}"
                 for c in best if counts[c] > 0]
        parts.append(f"{term} at " + ", ".join(cells))
    return "; ".join(parts)


def variants_text(variants, candidate) -> str:
    """what each variant run is"""
    parts = []
    if "before" in variants:
        parts.append("before = " + ", ".join([f"{k} = {v}" for k, v in BEFORE.items()] +
                                             [f"grid.{k} = {v}" for k, v in BEFORE_GRID.items()] +
                                             [f"flume.{k} = {v}" for k, v in BEFORE_FLUME.items()]) +
                     " (the former numerics through the scene's parameters)")
    if "after" in variants:
        parts.append("after = the scene files as they are")
    if "candidate" in variants:
        parts.append(f"candidate = the scene files with {', '.join(candidate)}")
    return "; ".join(parts) + "."


def limits_text(limits, steps):
    items = sorted(limits.items(), key=lambda kv: -kv[1])
    return ", ".join(f"{k} {v} ({100.0 * v / steps:.0f} %)" for k, v in items)


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--end-time", type=float, default=None, help="stop at this simulated time [s]")
    ap.add_argument("--scenes", nargs="+", default=["maeno2008", "maeno2008_consistent"])
    ap.add_argument("--out", type=Path, default=ROOT / "benchmarks" / "results" / "maeno2008_before_after.md")
    ap.add_argument("--variants", nargs="+", choices=("before", "after", "candidate"), default=["before", "after"])
    ap.add_argument("--candidate", nargs="+", default=[], metavar="KEY=VALUE",
                    help="the candidate variant's settings (scene keys)")
    args = ap.parse_args(argv)
    if ("candidate" in args.variants) != bool(args.candidate):
        ap.error("--candidate KEY=VALUE ... goes with --variants ... candidate, and only with it")
    rows, details = [], []
    for name in args.scenes:
        scene = load_scene(ROOT / "scenes" / f"{name}.toml")
        if args.end_time is not None:
            scene = scene.replace(end_time=args.end_time)
        for which in args.variants:
            print(f"{name} {which} ...", flush=True)
            with tempfile.TemporaryDirectory() as tmp:
                r = run_one(variant(scene, which, args.candidate), tmp)
            print(f"  {r['steps']} steps, CPU {r['cpu']:.1f} s, wall {r['wall']:.1f} s", flush=True)
            rows.append(f"| {name} | {which} | {r['steps']} | {r['cpu']:.1f} | {r['cpu'] / r['simulated']:.3f} | "
                        f"{r['wall']:.1f} | {r['wall'] / r['simulated']:.3f} | {1e3 * r['cpu'] / r['steps']:.3f} | "
                        f"{r['load'][0]:.1f} / {r['load'][1]:.1f} |")
            details += [f"### {name}, {which}", "", f"Steps bound by: {limits_text(r['limits'], r['steps'])}.", "",
                        f"Where (cell centres x, z and steps, the three most frequent per limit): {r['where']}.", "",
                        r["profile"], "", r["stages"], ""]
    text = ["# The Maeno 2008 scenario before and after the step-count work, both couplings", "",
            f"Generated by `benchmarks/maeno2008_before_after.py` on {time.strftime('%Y-%m-%d %H:%M UTC', time.gmtime())}, "
            f"{platform.processor() or platform.machine()}, Python {platform.python_version()}, one process, "
            "one core (OMP_NUM_THREADS=1), runs one after the other; the machine is shared (load average at the "
            "start / end of each run in the last column). Real-time factor = time / simulated time.", "",
            variants_text(args.variants, args.candidate), "",
            "| scene | numerics | steps | CPU s | CPU / simulated | wall s | wall / simulated | CPU ms per step | load |",
            "|---|---|---|---|---|---|---|---|---|", *rows, "", "## Each run", "", *details]
    return write_page(args.out, text)


if __name__ == "__main__":
    main()
