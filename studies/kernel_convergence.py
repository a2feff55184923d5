"""The kernel mapping's convergence with the grid: the water's loads on the held stones and the fixed
bed's head drop on the paper's grid and on grids twice and four times as fine in x and z, with the
cell and the kernel mapping and the kernel at several widths b (numerics.coupling_bandwidth).

Grids (--grids, refinement factors r): dx = 2.5 / r cm, dz = 1 / r cm, bed row dz_bed = bed layer =
0.5 / r cm (r = 1 the paper's grid, numerics.fidelity 'standard'; r = 2 'fine'). Bandwidths
(--bandwidths, factors f of the stones' mean diameter, kernel only): b = f x the value the kernel takes
unset (the mean diameter of the packing), f = 1 being the default. Every stone is held (the bed is
fixed); for each packing (--seeds), mapping, width and grid the scene (with --base) runs to each of
--times and records:

- the downstream slope's summed horizontal load (drag + pressure-gradient force, [N]) and the largest
  mobility F_x / W' of its stones (W' the submerged weight of a sphere of the stone's diameter), the
  quantities of studies/stone_loads_grid.py;
- the fixed bed's head drop: the water depth 0.5 m upstream of the weir's toe (h_up) and 0.3 m
  downstream of its downstream toe (h_down), from the columns' water fractions, and the bed pressure's
  drop between those two columns, dp = p_up - p_down [Pa] (lowest row; the upstream level at a held
  discharge is what the weir's resistance and overflow set);
- the steps so far and the CPU per coupled step (process time, this process alone).

Each run is cached (--cache, one JSON line per run) so that runs can be split between processes
(--only) and the tables written from the cache by a final call with the whole set. Writes --out.

    OMP_NUM_THREADS=1 PYTHONPATH=python python3 studies/kernel_convergence.py --seeds 0 1 --times 20 50 \
        --grids 1 2 4 --mappings cell kernel --bandwidths 1
"""
import argparse
import json
import os
import platform
import sys
import time
from pathlib import Path

os.environ.setdefault("OMP_NUM_THREADS", "1")
ROOT = Path(__file__).resolve().parents[1]

import numpy as np  # noqa: E402

from vofdem.analysis import classify_regions  # noqa: E402
from vofdem.builder import build_simulation  # noqa: E402
from vofdem.ensemble import with_settings  # noqa: E402
from vofdem.scene import load_scene  # noqa: E402
from vofdem.study import sphere_volume, submerged_weight, write_page  # noqa: E402

UPSTREAM = 0.5  # m before the upstream toe: the approach depth column
DOWNSTREAM = 0.3  # m past the downstream toe: the tailwater column


def grid_settings(r):
    """The scene keys of the grid refined r times in x and z from the paper's."""
    return [f"grid.dx={0.025 / r!r}", f"grid.dz={0.01 / r!r}", f"grid.dz_bed={0.005 / r!r}",
            f"grid.bed_layer_height={0.005 / r!r}"]


def column_state(sim, x):
    """(water depth [m], bed pressure [Pa]) of the cell column holding x."""
    g = sim.fluid.grid
    i = int((x - g.x0) / g.dx)
    dz = np.diff(np.asarray(g.z_faces))
    f = np.asarray(sim.fluid.cell_F)[:, i]
    n = np.asarray(sim.fluid.cell_porosity)[:, i]
    return float((f * n * dz).sum()), float(np.asarray(sim.fluid.cell_p)[0, i])


def run(scene, settings, times):
    """Per time: the downstream slope's summed F_x [N], its largest mobility, h_up, h_down [m], dp [Pa],
    steps and CPU [s] of the steps so far (the build's apart); and the bandwidth the kernel used [m]."""
    t0 = time.process_time()
    sim = build_simulation(with_settings(scene, settings))
    st = sim.stones
    mobile = np.asarray(st.stone_fixed) == 0
    st.stone_fixed[:] = True
    d = 2.0 * np.asarray(st.stone_radius)[mobile]
    weight = submerged_weight(sphere_volume(d), np.asarray(st.stone_density)[mobile])
    t0, built = time.process_time(), time.process_time() - t0  # the packing's build is not a coupled step
    x = np.asarray(st.stone_pos)[mobile, 0].copy()
    down = classify_regions(x, scene.weir, 0.0) == "downstream slope"
    rows = []
    for t in times:
        sim.advance(t)
        fx = (np.asarray(sim.stone_force_drag)[mobile, 0] + np.asarray(sim.stone_force_pressure)[mobile, 0])
        h_up, p_up = column_state(sim, scene.weir.toe_x - UPSTREAM)
        h_dn, p_dn = column_state(sim, scene.weir.x_toe_down + DOWNSTREAM)
        rows.append({"t": t, "load": float(fx[down].sum()), "largest": float((fx / weight)[down].max()),
                     "h_up": h_up, "h_down": h_dn, "dp": p_up - p_dn, "steps": int(sim.step_count),
                     "cpu": time.process_time() - t0, "build_cpu": built})
    return rows, float(sim.kernel_bandwidth)


def key_of(seed, mapping, f, r):
    return f"{seed}|{mapping}|{f:g}|{r:g}"


def configs(args):
    for seed in args.seeds:
        for mapping in args.mappings:
            for f in (args.bandwidths if mapping == "kernel" else [1.0]):
                for r in args.grids:
                    yield seed, mapping, f, r


def measure(args, base, cache):
    """Every configuration of args not yet in the cache, appended to it."""
    done = {}
    if args.cache.exists():
        for line in args.cache.read_text().splitlines():
            rec = json.loads(line)
            done[rec["key"]] = rec
    only = set(args.only or [])
    unset = {}
    for seed, mapping, f, r in configs(args):
        key = key_of(seed, mapping, f, r)
        if key in done:  # measured, perhaps to fewer times (the table shows those it has)
            continue
        if only and key not in only:
            continue
        scene = base.replace(seed=seed)
        settings = [*args.base, *grid_settings(r), f"numerics.coupling_mapping={mapping}"]
        if mapping == "kernel" and f != 1.0:
            if seed not in unset:  # the width the kernel takes unset: the packing's mean diameter
                unset[seed] = build_simulation(with_settings(scene, [*args.base, "numerics.coupling_mapping=kernel"])).kernel_bandwidth
            settings.append(f"numerics.coupling_bandwidth={f * unset[seed]!r}")
        rows, b = run(scene, settings, args.times)
        rec = {"key": key, "seed": seed, "mapping": mapping, "f": f, "r": r, "b": b, "rows": rows}
        print(json.dumps(rec), flush=True)
        with cache.open("a") as fh:
            fh.write(json.dumps(rec) + "\n")
        done[key] = rec
    return done


def pct(a, b):
    return "-" if a is None or b is None or a == 0.0 else f"{100.0 * (b - a) / a:+.1f} %"


def fmt(v, spec):
    return "-" if v is None else format(v, spec)


def at(rec, t, name):
    """The run's value of name at time t, None when the run did not go that far."""
    for row in rec["rows"]:
        if row["t"] == t:
            return row[name]
    return None


def value(args, rec, t, name):
    """A recorded value, or the approach depth's head over the weir's crest, h_up - H [m] ('head')."""
    if rec is None:
        return None
    v = at(rec, t, "h_up" if name == "head" else name)
    return None if v is None else (v - args.weir_height if name == "head" else v)


def table_rows(args, done, name, spec, scale=1.0):
    """Per packing, time, mapping and width: the value per grid and its change per grid pair."""
    grids = sorted(args.grids)
    pairs = list(zip(grids[:-1], grids[1:]))
    out = []
    for seed in args.seeds:
        for mapping in args.mappings:
            for f in (args.bandwidths if mapping == "kernel" else [1.0]):
                recs = {r: done.get(key_of(seed, mapping, f, r)) for r in grids}
                if all(rec is None for rec in recs.values()):
                    continue
                label = f"kernel, {f:g}" if mapping == "kernel" else "cell, -"
                for t in args.times:
                    v = {r: value(args, rec, t, name) for r, rec in recs.items()}
                    v = {r: None if x is None else scale * x for r, x in v.items()}
                    if all(x is None for x in v.values()):
                        continue
                    out.append(f"| {seed} | {t:g} | {label} | " + " | ".join(fmt(v[r], spec) for r in grids) + " | "
                               + " | ".join(pct(v[a], v[b]) for a, b in pairs) + " |")
    return out


def tables(args, done):
    """Markdown tables: the downstream slope's load, its largest mobility, the fixed bed's approach depth
    and bed pressure drop, and the cost."""
    grids = sorted(args.grids)
    pairs = list(zip(grids[:-1], grids[1:]))
    quantities = [("load", "summed F_x [N]", ".3f", 1.0), ("largest", "largest F_x / W'", ".3f", 1.0),
                  ("h_up", "h_up [mm]", ".1f", 1e3), ("head", "h_up - H [mm]", ".1f", 1e3), ("h_down", "h_down [mm]", ".1f", 1e3), ("dp", "dp [Pa]", ".1f", 1.0)]
    out = {}
    for name, title, spec, scale in quantities:
        head = (f"| packing | t [s] | mapping, b / d | " + " | ".join(f"{title}, r = {r:g}" for r in grids) + " | "
                + " | ".join(f"change {a:g} -> {b:g}" for a, b in pairs) + " |")
        out[name] = [head, "|" + "---|" * (3 + len(grids) + len(pairs)), *table_rows(args, done, name, spec, scale)]
    cost = ["| packing | mapping, b / d | b [mm] | " + " | ".join(f"steps, r = {r:g}" for r in grids) + " | "
            + " | ".join(f"CPU per step [ms], r = {r:g}" for r in grids) + " |", "|" + "---|" * (3 + 2 * len(grids))]
    for seed in args.seeds:
        for mapping in args.mappings:
            for f in (args.bandwidths if mapping == "kernel" else [1.0]):
                recs = [done.get(key_of(seed, mapping, f, r)) for r in grids]
                if all(rec is None for rec in recs):
                    continue
                last = [None if rec is None else rec["rows"][-1] for rec in recs]
                b = next(rec["b"] for rec in recs if rec is not None)
                label = f"kernel, {f:g}" if mapping == "kernel" else "cell, -"
                cost.append(f"| {seed} | {label} | {1e3 * b:.1f} | "
                            + " | ".join("-" if row is None else f"{row['steps']} to {row['t']:g} s" for row in last) + " | "
                            + " | ".join("-" if row is None else f"{1e3 * row['cpu'] / row['steps']:.2f}" for row in last)
                            + " |")
    return out, cost


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--scene", default="maeno2008_rolling_consistent")
    ap.add_argument("--base", nargs="*", default=["numerics.turbulence_pore_strain=filtered"], metavar="KEY=VALUE")
    ap.add_argument("--seeds", type=int, nargs="+", default=[0, 1])
    ap.add_argument("--times", type=float, nargs="+", default=[20.0, 50.0])
    ap.add_argument("--grids", type=float, nargs="+", default=[1.0, 2.0, 4.0])
    ap.add_argument("--mappings", nargs="+", default=["cell", "kernel"], choices=["cell", "kernel"])
    ap.add_argument("--bandwidths", type=float, nargs="+", default=[1.0])
    ap.add_argument("--only", nargs="*", help="run only these keys SEED|MAPPING|F|R (the others from the cache)")
    ap.add_argument("--cache", type=Path, default=ROOT / "out" / "kernel_convergence.jsonl")
    ap.add_argument("--out", type=Path, default=ROOT / "studies" / "results" / "kernel_convergence.md")
    ap.add_argument("--measure-only", action="store_true", help="run and cache, write no table")
    args = ap.parse_args(argv)
    args.weir_height = None
    args.cache.parent.mkdir(parents=True, exist_ok=True)
    base = load_scene(ROOT / "scenes" / f"{args.scene}.toml")
    args.weir_height = base.weir.height
    done = measure(args, base, args.cache)
    if args.measure_only:
        return None
    t, cost = tables(args, done)
    text = [f"# The kernel mapping's convergence with the grid, held stones", "",
            f"Generated by `studies/kernel_convergence.py` on {time.strftime('%Y-%m-%d %H:%M UTC', time.gmtime())}, "
            f"Python {platform.python_version()}, by `python studies/kernel_convergence.py "
            f"{' '.join(argv if argv is not None else sys.argv[1:])}` (with OMP_NUM_THREADS=1): scene {args.scene}, every stone held, settings "
            f"{', '.join(args.base) or 'none'}; grids r = {', '.join(f'{r:g}' for r in args.grids)} "
            f"(dx = 2.5 / r cm, dz = 1 / r cm, bed row 0.5 / r cm), packings {' '.join(map(str, args.seeds))}, "
            f"times {' '.join(f'{t:g}' for t in args.times)} s (a dash: not run that far), kernel widths b / d = "
            f"{', '.join(f'{f:g}' for f in args.bandwidths)} (d: the packing's mean diameter, the width unset). "
            f"Changes: from the coarser to the finer grid of each pair.", "",
            "## Downstream slope: summed horizontal load (drag + pressure-gradient force)", "", *t["load"], "",
            "## Downstream slope: the most exposed stone's mobility F_x / W'", "", *t["largest"], "",
            f"## Fixed bed: water depth {UPSTREAM:g} m before the upstream toe (h_up)", "", *t["h_up"], "",
            "## Fixed bed: the approach depth's head over the crest, h_up - H (H: the weir's height)", "",
            *t["head"], "",
            f"## Fixed bed: water depth {DOWNSTREAM:g} m past the downstream toe (h_down)", "", *t["h_down"], "",
            "## Fixed bed: bed pressure drop dp = p_up - p_down between those two columns", "", *t["dp"], "",
            "## Cost", "", "CPU of the steps (the build and packing excluded) over their number, to the last time "
            "run, this process alone (time.process_time); the runs shared a loaded 2-core machine.", "", *cost, ""]
    return write_page(args.out, text)


if __name__ == "__main__":
    main()
