"""Is a change of the numerics within the packings' spread? The same Maeno scenes over the same seeds
at two values of one numerics key (by default the pressure solve's relative tolerance), compared with
the spread between packings.

A whole run of the weir is chaotic in its stones: any change of the numerics, down to the last bit,
moves the stones of a seed differently, so the stage table of one seed cannot tell a change of the
numerics from a change of the packing. What can: the distribution over packings. For each scene this
runs an ensemble over --seeds at each of --values of --key (`vofdem.ensemble`, on a local Dask cluster;
resumable), then writes studies/results/<key's name>_spread.md with
  - per value, the fragility tables of the events (`vofdem.fragility`), and the mean, median and
    members' 16-84 % range of the stones removed and the crest lowering, with the permutation p-value
    of the difference of their means;
  - the same seed at the two values against two packings at one value: the mean absolute
    difference of the stones removed between the two runs of a seed, and between seeds i and i + 1;
  - the flow alone (stones held, the first 20 s, seed 0): the largest difference of the water depth
    over the flume between the values, against that between seeds 0 and 1 at the first value, and the
    water the solve's residual divergence made per step (VOFGrid.dilatation_volume).

    OMP_NUM_THREADS=1 PYTHONPATH=python python3 studies/pressure_tolerance_spread.py [--seeds 0-19]
    OMP_NUM_THREADS=1 PYTHONPATH=python python3 studies/pressure_tolerance_spread.py \
        --key numerics.wet_fraction_tolerance --values 0 1e-6 --scenes maeno2008_rolling_consistent maeno2008_rolling
    OMP_NUM_THREADS=1 PYTHONPATH=python python3 studies/pressure_tolerance_spread.py \
        --key numerics.viscous_scheme --values implicit_vertical_from_start implicit_vertical \
        --scenes maeno2008 maeno2008_consistent maeno2008_rolling maeno2008_rolling_consistent
"""
import argparse
import time
from pathlib import Path

import numpy as np

from vofdem.builder import build_simulation
from vofdem.cluster import default_workers
from vofdem.ensemble import parse_seeds, run_ensemble, with_settings
from vofdem.fragility import EVENTS, combination_of, fragility_by_combination, fragility_markdown
from vofdem.scene import load_scene
from vofdem.study import event_arrays, median_shift

ROOT = Path(__file__).resolve().parents[1]
KEY = "numerics.pressure_tolerance"  # the default key


def _v(value) -> str:
    """a value of the key as the tables print it (a number in %g, a switch as a scene file writes it, a
    choice as it is): also the value in the members' names"""
    if isinstance(value, bool):
        return str(value).lower()
    return f"{value:g}" if isinstance(value, float) else str(value)


def _number_or_choice(text: str):
    if text in ("true", "false"):  # a switch, as a scene file writes it
        return text == "true"
    try:
        return float(text)
    except ValueError:
        return text


def _band(values, fmt: str = "{:.1f}"):
    """median [16-84 %] of the members' values"""
    v = np.asarray(values, dtype=float)
    lo, mid, hi = (fmt.format(x) for x in (np.percentile(v, 16), np.median(v), np.percentile(v, 84)))
    return f"{mid} [{lo}-{hi}]"


def permutation_p(a, b, n: int = 10000, seed: int = 0) -> float:
    """two-sided p-value of the difference of the means of a and b under random relabelling"""
    a, b = np.asarray(a, dtype=float), np.asarray(b, dtype=float)
    pooled = np.concatenate([a, b])
    observed = abs(a.mean() - b.mean())
    rng = np.random.default_rng(seed)
    hits = 0
    for _ in range(n):
        rng.shuffle(pooled)
        hits += abs(pooled[:a.size].mean() - pooled[a.size:].mean()) >= observed - 1e-12
    return (hits + 1) / (n + 1)


def _lps(v) -> str:
    return "not reached" if v is None else f"{v:.2f}"


def median_shifts(a, b, t0, t1, n_boot: int = 1000):
    """Markdown lines: each event's Kaplan-Meier median at the two values over the seeds both completed,
    and its shift with the paired bootstrap 16-84 % interval over those seeds (`vofdem.study.median_shift`)."""
    lines = [f"| event | median at {_v(t0)} [l/s] | median at {_v(t1)} [l/s] | shift [l/s] [paired bootstrap "
             "16-84 %] | resamples left out |", "|---|---|---|---|---|"]
    for event, (_, label) in EVENTS.items():
        s = median_shift(a, b, event, n_boot=n_boot)
        shift = "-" if s.shift is None else f"{s.shift:+.2f}"
        band = "" if s.shift is None or np.isnan(s.lo) else f" [{s.lo:+.2f} to {s.hi:+.2f}]"
        left = "-" if np.isnan(s.left_out) else f"{s.left_out:.0%}"
        lines.append(f"| {label} | {_lps(s.reference)} | {_lps(s.setting)} | {shift}{band} | {left} |")
    lines += ["", f"Over the {s.seeds} seeds both values completed; a resample in which either median is not reached "
              "(beyond the runs' last discharge) is left out of the interval."]
    return lines


def by_value(frame, values, key=KEY):
    """{value: its completed members, by seed}"""
    done = frame[frame["status"] == "completed"]
    combos = {t: f"{key}={t!r}" if isinstance(t, float) else f"{key}={_v(t)}" for t in values}  # the members' names
    return {t: done[[combination_of(m) == c for m in done["member"]]].sort_values("seed") for t, c in combos.items()}


def paired_figure(frame, values, path: Path, title: str, key=KEY) -> Path:
    """Each seed's discharge of each event at the second value against the first (hollow: it never
    happened, drawn at the run's last discharge), with the line of equal answers."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    by = by_value(frame, values, key)
    a, b = (by[t].set_index("seed") for t in values[:2])
    seeds = a.index.intersection(b.index)
    fig, axes = plt.subplots(1, len(EVENTS), figsize=(3.2 * len(EVENTS), 3.6), sharex=True, sharey=True,
                             layout="constrained")
    q = np.concatenate([event_arrays(m.loc[seeds], e)[0] for m in (a, b) for e in EVENTS])
    lo, hi = 0.95 * q.min(), 1.05 * q.max()
    for ax, (event, (_, label)) in zip(axes, EVENTS.items()):
        qa, oa = event_arrays(a.loc[seeds], event)
        qb, ob = event_arrays(b.loc[seeds], event)
        for both, style in ((oa & ob, dict(color="C0")), (~(oa & ob), dict(facecolor="none", edgecolor="C1"))):
            ax.scatter(qa[both], qb[both], s=28, **style)
        points, counts = np.unique(np.round(np.c_[qa, qb], 2), axis=0, return_counts=True)
        for (x, y), n in zip(points, counts):
            if n > 1:  # packings on the same point
                ax.annotate(f"x{n}", (x, y), xytext=(5, -9), textcoords="offset points", fontsize=7)
        ax.plot([lo, hi], [lo, hi], color="0.6", lw=0.8)
        ax.set(xlim=(lo, hi), ylim=(lo, hi), title=label, xlabel=f"Q at {_v(values[0])} [l/s]")
    axes[0].set_ylabel(f"Q at {_v(values[1])} [l/s]")
    fig.suptitle(f"{title}: each packing's events (hollow: not at both values, at the run's end)", fontsize=9)
    path.parent.mkdir(parents=True, exist_ok=True)
    fig.savefig(path, dpi=110)
    plt.close(fig)
    return path


def compare_members(frame, tolerances, key=KEY):
    """Markdown: each value's fragility tables, then the stones and crest per value of `key` with the
    permutation p-value of their means' difference, and the paired differences."""
    done = frame[frame["status"] == "completed"]
    name = key.rpartition(".")[2]
    by = by_value(frame, tolerances, key)
    t0, t1 = tolerances[:2]
    lines = [fragility_markdown(fragility_by_combination(done)),
             "| measure | " + " | ".join(f"{name} {_v(t)}" for t in tolerances) + " | means' difference: p |",
             "|---|" + "---|" * (len(tolerances) + 1)]
    for col, label in (("removed", "stones removed"), ("crest_lowering_mm", "crest lowering [mm]"),
                       ("stages", "stages")):
        a, b = by[t0][col].astype(float), by[t1][col].astype(float)
        lines.append(f"| {label}: mean, median [members' 16-84 %] | " +
                     " | ".join(f"{by[t][col].astype(float).mean():.1f}, {_band(by[t][col])}" for t in tolerances) +
                     f" | {permutation_p(a, b):.2f} |")
    for n in (2, 3):
        lines.append(f"| members with {n} stages or more | " +
                     " | ".join(f"{int((by[t]['stages'] >= n).sum())} of {len(by[t])}" for t in tolerances) + " | |")
    lines.append("| CPU per member [s] (mean; two members at a time) | " +
                 " | ".join(f"{by[t]['cpu_seconds'].mean():.1f}" for t in tolerances) + " | |")
    lines.append("| steps per member: mean, median [members' 16-84 %] | " +
                 " | ".join(f"{by[t]['steps'].astype(float).mean():,.0f}, {_band(by[t]['steps'], '{:,.0f}')}" for t in tolerances) +
                 f" | {permutation_p(by[t0]['steps'].astype(float), by[t1]['steps'].astype(float)):.2f} |")
    a, b = (by[t].set_index("seed")["removed"].astype(float) for t in (t0, t1))
    seeds = a.index.intersection(b.index)
    paired = np.abs(a[seeds] - b[seeds])
    across = np.abs(np.diff(a.to_numpy()))
    across_text = f"{across.mean():.1f}" if across.size else "- (one seed)"
    lines += ["", f"p: the share of 10,000 random relabellings of the members between the values whose means "
              f"differ at least as much (a small p: a shift beyond the packings' spread). Stones removed, the same "
              f"seed at {_v(t0)} and {_v(t1)}: mean absolute difference {paired.mean():.1f} ({int((paired == 0).sum())} "
              f"of {len(seeds)} seeds equal); two packings (seeds i and i + 1) at {_v(t0)}: {across_text}.", "",
              *median_shifts(by[t0], by[t1], t0, t1)]
    return "\n".join(lines)


def flow_alone_run(scene, t_end):
    """the water depth [m] of every column after the flow alone (stones held) to t_end, the columns'
    centres [m], and the water the pressure solve's residual divergence made per step, relative to the
    water volume"""
    sim = build_simulation(scene)
    sim.stones.stone_fixed[:] = True
    sim.advance(t_end)
    f = sim.fluid
    g = f.grid
    F = np.asarray(f.cell_F).reshape(g.nz, g.nx)
    dz = np.diff(np.asarray(g.z_faces))
    x = g.x0 + g.dx * (np.arange(g.nx) + 0.5)
    return (F * dz[:, None]).sum(axis=0), x, abs(f.dilatation_volume) / f.water_volume() / sim.step_count


def flow_alone(scene, tolerances, t_end, key=KEY):
    """the flow's difference between two values of `key` against that between packings (markdown)"""
    tol = [scene.with_value(key, t) for t in tolerances]
    d0, x0, made0 = flow_alone_run(tol[0].replace(seed=0), t_end)
    d_tol, x1, made1 = flow_alone_run(tol[1].replace(seed=0), t_end)
    d_tol = np.interp(x0, x1, d_tol)  # the first value's columns (a key of the grid changes them)
    d_seed, _, _ = flow_alone_run(tol[0].replace(seed=1), t_end)
    return (f"The flow alone (stones held, seed 0, t = {t_end:g} s): the water depth differs by at most "
            f"{1e3 * np.abs(d_tol - d0).max():.3f} mm over the flume between the values "
            f"(mean {1e3 * np.abs(d_tol - d0).mean():.4f} mm); between seeds 0 and 1 at {_v(tolerances[0])}, "
            f"by {1e3 * np.abs(d_seed - d0).max():.3f} mm (mean {1e3 * np.abs(d_seed - d0).mean():.4f} mm). "
            f"Water made by the residual divergence, per step and relative to the water volume: "
            f"{made0:.1e} at {_v(tolerances[0])}, {made1:.1e} at {_v(tolerances[1])}.")


def main(argv=None):
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--scenes", nargs="+", default=["maeno2008", "maeno2008_consistent"])
    p.add_argument("--seeds", default="0-19")
    p.add_argument("--key", default=KEY, help=f"the numerics key compared (default {KEY})")
    p.add_argument("--values", "--tolerances", dest="values", nargs=2, type=_number_or_choice,
                   default=None, help="its two values, numbers or choices (default 1e-5 1e-4 for the pressure "
                   "tolerance)")
    p.add_argument("--workers", type=int, default=None,
                   help="local worker processes (default: one per core; 0: no Dask, in this process)")
    p.add_argument("--base", nargs="*", default=[], metavar="KEY=VALUE",
                   help="settings of every member at both values (e.g. numerics.viscous_scheme=implicit)")
    p.add_argument("--quick", action="store_true", help="the scenes' quick variants (coarser, ramp 4x faster)")
    p.add_argument("--end-time", type=float, default=None, help="stop each member at this time [s] (for tests)")
    p.add_argument("--spin-up", type=float, default=20.0, help="the flow-alone comparison's end [s]")
    p.add_argument("--out", type=Path, default=ROOT / "out",
                   help="ensembles in OUT/tol_spread_<scene> (another key: OUT/<its name>_spread_<scene>)")
    p.add_argument("--results", type=Path, default=None,
                   help="default studies/results/<the key's name>_spread.md")
    p.add_argument("--figure", type=Path, default=None, help="each packing's events at the two values, paired "
                   "(a PNG; with several scenes, one per scene: the scene's name appended)")
    args = p.parse_args(argv)
    name = args.key.rpartition(".")[2]
    if args.values is None:
        if args.key != KEY:
            raise ValueError(f"--values: two values of {args.key} are needed")
        args.values = [1e-5, 1e-4]
    args.tolerances = args.values
    results = args.results or ROOT / "studies" / "results" / f"{name}_spread.md"
    prefix = "tol_spread" if args.key == KEY else f"{name}_spread"
    seeds = parse_seeds(args.seeds)
    workers = args.workers if args.workers is not None else default_workers()
    title = "Pressure tolerance" if args.key == KEY else f"`{args.key}`"
    parts = [f"# {title} {_v(args.tolerances[0])} against {_v(args.tolerances[1])}: the packings' spread", "",
             f"Generated by `studies/pressure_tolerance_spread.py` on "
             f"{time.strftime('%Y-%m-%d %H:%M UTC', time.gmtime())}: seeds {args.seeds} at each value, the "
             f"scene to its end, " + (f"{workers} local Dask worker(s)." if workers else "in this process, one member after "
                                     "the other.") + (f" Every member with {', '.join(args.base)}." if args.base else ""), ""]
    for name in args.scenes:
        scene = load_scene(ROOT / "scenes" / f"{name}.toml")
        scene = scene.quick() if args.quick else scene
        if args.end_time is not None:
            scene = scene.replace(end_time=args.end_time)
        scene = with_settings(scene, args.base)
        frame = run_ensemble(scene, seeds, args.out / f"{prefix}_{scene.name}", vary={args.key: list(args.tolerances)},
                             workers=workers, progress=False)
        parts += [f"## {scene.name}", "", compare_members(frame, args.tolerances, args.key), "",
                  flow_alone(scene, args.tolerances, args.spin_up, args.key), ""]
        if args.figure is not None:
            fig = args.figure if len(args.scenes) == 1 else args.figure.with_stem(f"{args.figure.stem}_{scene.name}")
            paired_figure(frame, args.tolerances, fig, f"{scene.name}, {args.key}", args.key)
            parts += [f"Figure: `{fig.relative_to(ROOT) if fig.is_relative_to(ROOT) else fig}`", ""]
    results.write_text("\n".join(parts), encoding="utf-8")
    print(results)
    return results


if __name__ == "__main__":
    main()
