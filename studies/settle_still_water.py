"""The packed weir settled in still water before the flow starts (hydrograph.settle_in_still_water) or
not: the release failures over the same packings of a scene, and the settling's CPU cost per packing.

Runs (or resumes) two ensembles of the scene, settle off and on (studies/maeno2008_fragility.py's
run_ensemble, one member after the other in this process), times the settling alone on each packing
(process CPU time of builder.settle_stones), then pairs the two ensembles member by member with
studies/ensemble_pair.py into studies/results/settle_still_water.md.

    PYTHONPATH=python python3 studies/settle_still_water.py --quick --seeds 0-29
"""
import argparse
import os
import sys
from pathlib import Path
from statistics import median

sys.path.insert(0, str(Path(__file__).resolve().parent))
import ensemble_pair  # noqa: E402
from vofdem.builder import build_simulation, settle_stones  # noqa: E402
from vofdem.ensemble import parse_seeds, run_ensemble  # noqa: E402
from vofdem.scene import load_scene  # noqa: E402

ROOT = Path(__file__).resolve().parents[1]


def settle_cpu(scene, seeds) -> list:
    """(seed, CPU seconds, simulated seconds, rested) of the settling alone on each packing."""
    rows = []
    for seed in seeds:
        sim = build_simulation(scene.replace(seed=seed), settle=False)
        t0 = os.times()
        r = settle_stones(sim, scene)
        t1 = os.times()
        rows.append((seed, (t1.user + t1.system) - (t0.user + t0.system), r.time, r.rested))
    return rows


def main(argv=None) -> Path:
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--scene", type=Path, default=ROOT / "scenes" / "maeno2008.toml")
    p.add_argument("--seeds", default="0-29")
    p.add_argument("--quick", action="store_true", help="the scene's quick variant")
    p.add_argument("--end-time", type=float, default=None, help="stop each member at this time [s] (for tests)")
    p.add_argument("--out", type=Path, default=ROOT / "out" / "settle_still_water", help="the two ensembles' directory")
    p.add_argument("--before", type=Path, default=None,
                   help="an ensemble directory of the same scene and seeds run without the settling (e.g. by the "
                        "build before it) to pair with, instead of running the 'off' ensemble here")
    p.add_argument("--before-note", default="", help="how --before was run (into the table's text)")
    p.add_argument("--results", type=Path, default=ROOT / "studies" / "results" / "settle_still_water.md")
    args = p.parse_args(argv)
    scene = load_scene(args.scene)
    scene = scene.quick() if args.quick else scene
    if args.end_time is not None:
        scene = scene.replace(end_time=args.end_time)
    seeds = parse_seeds(args.seeds)
    for on in ((True,) if args.before else (False, True)):
        s = scene.with_value("hydrograph.settle_in_still_water", on)
        run_ensemble(s, seeds, args.out / ("on" if on else "off"), workers=0, figures=False, animation=False)
    before = args.before or args.out / "off"
    cpu = settle_cpu(scene.with_value("hydrograph.settle_in_still_water", True), seeds)
    c, t = [r[1] for r in cpu], [r[2] for r in cpu]
    rested = sum(r[3] for r in cpu)
    rerun = (f"`PYTHONPATH=python python3 studies/settle_still_water.py --scene scenes/{args.scene.name}"
             f"{' --quick' if args.quick else ''} --seeds {args.seeds}`")
    preamble = (f"Scene `{args.scene.name}`{' (quick variant)' if args.quick else ''}, seeds {args.seeds}, each member "
                f"run once with `hydrograph.settle_in_still_water = false` (before) and once with it `true` (after: "
                f"the packed stones settle in the still pool, buoyant by the water each sits in, the flow frozen, "
                f"until every free stone is slower than 1e-3 m/s for 0.2 s or for settle_time_max = "
                f"{scene.hydrograph.settle_time_max:g} s; then the hold and spin-up as before), one member after the "
                f"other in one process on a machine shared with other builds (CPU rows are no exact cost "
                f"comparison). Rerun: {rerun}.\n\n"
                f"The settling alone (process CPU time around `builder.settle_stones`, {len(cpu)} packings): "
                f"median {median(c):.2f} s CPU per packing (range {min(c):.2f}-{max(c):.2f} s) for a median "
                f"{median(t):.2f} s of the stones' time (range {min(t):.2f}-{max(t):.2f} s); {rested} of {len(cpu)} "
                f"packings came to rest before the cap.")
    if args.before_note:
        preamble += f" Before: {args.before_note}"
    ensemble_pair.main([str(before), str(args.out / "on"), "--title",
                        "Settling the packed weir in still water before the flow: the release over the same packings, "
                        "off and on", "--preamble", preamble, "--out", str(args.results)])
    return args.results


if __name__ == "__main__":
    main()
