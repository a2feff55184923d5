"""Fragility of the Maeno 2008 weir over packings: an ensemble of the whole scene (the paper's grid and
hydrograph), by default 30 seeds on a local Dask cluster, with the time it took on how many workers.

Writes the ensemble into --out (one run directory per member; resumable: a second call runs only the
members not finished), then studies/results/<name>_fragility.md (the fragility tables, the
members' table, the wall time, workers and cores) and the figure docs/figures/<name>_fragility.png.

    PYTHONPATH=python python3 studies/maeno2008_fragility.py                  # 30 seeds, one worker per core
    PYTHONPATH=python python3 studies/maeno2008_fragility.py --scene scenes/maeno2008_consistent.toml
    PYTHONPATH=python python3 studies/maeno2008_fragility.py --scheduler tcp://host:8786  # a cluster
    PYTHONPATH=python python3 studies/maeno2008_fragility.py --quick --seeds 0-19   # the quick variant
"""
import argparse
import json
import os
import shutil
import time
from pathlib import Path

from vofdem.cluster import default_workers
from vofdem.ensemble import parse_seeds, run_ensemble
from vofdem.scene import load_scene

ROOT = Path(__file__).resolve().parents[1]


def _completed(out: Path) -> int:
    """members already completed in the ensemble directory `out`"""
    files = out.glob("**/outcome.json") if out.exists() else []
    return sum(json.loads(f.read_text(encoding="utf-8")).get("status") == "completed" for f in files)


def main(argv=None) -> Path:
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--scene", type=Path, default=ROOT / "scenes" / "maeno2008.toml")
    p.add_argument("--seeds", default="0-29")
    p.add_argument("--workers", type=int, default=None, help="local worker processes (default: one per core)")
    p.add_argument("--scheduler", default=None, help="an existing Dask cluster's address instead")
    p.add_argument("--quick", action="store_true", help="the scene's quick variant (coarser, ramp 4x faster)")
    p.add_argument("--end-time", type=float, default=None, help="stop each member at this time [s] (for tests)")
    p.add_argument("--out", type=Path, default=None, help="ensemble directory (default out/<name>_fragility)")
    p.add_argument("--results", type=Path, default=ROOT / "studies" / "results")
    p.add_argument("--figures", type=Path, default=ROOT / "docs" / "figures")
    p.add_argument("--retry-failed", action="store_true", help="run the members that failed before again")
    args = p.parse_args(argv)
    scene = load_scene(args.scene)
    if args.quick:
        scene = scene.quick()
    if args.end_time is not None:
        scene = scene.replace(end_time=args.end_time)
    seeds = parse_seeds(args.seeds)
    out = args.out or ROOT / "out" / f"{scene.name}_fragility"
    workers = args.workers if args.workers is not None else default_workers()
    before = _completed(out)
    t0 = time.perf_counter()
    df = run_ensemble(scene, seeds, out, workers=workers, scheduler=args.scheduler, figures=False,
                      animation=False, retry_failed=args.retry_failed)
    wall = time.perf_counter() - t0
    args.figures.mkdir(parents=True, exist_ok=True)
    figure = args.figures / f"{scene.name}_fragility.png"
    shutil.copyfile(out / "fragility.png", figure)
    where = f"on the cluster at {args.scheduler}" if args.scheduler else (
        f"on {workers} local worker process(es)" if workers else "in this process, one member after the other")
    done = df[df["status"] == "completed"]
    member_wall = done["wall_seconds"].sum()
    text = [f"# Fragility of {scene.name} over {len(seeds)} packings (seeds {args.seeds})", "",
            f"Scene `{args.scene.name}`{' (quick variant)' if args.quick else ''}, {scene.duration:g} s simulated per "
            f"member. The last call ran {len(seeds) - before} members (found {before} completed) in {wall / 60:.1f} min "
            f"{where} ({os.cpu_count()} cores on this machine, load average {os.getloadavg()[0]:.1f} at the end). "
            f"The {len(done)} completed members cost {member_wall / 3600:.2f} core-hours in all "
            f"({member_wall / max(len(done), 1):.0f} s each on average).",
            f"Rerun: `PYTHONPATH=python python3 studies/maeno2008_fragility.py --scene scenes/{args.scene.name}"
            f"{' --quick' if args.quick else ''} --seeds {args.seeds}`. Figure: `docs/figures/{figure.name}`.", "",
            (out / "ensemble.md").read_text(encoding="utf-8").split("\n", 2)[2]]
    args.results.mkdir(parents=True, exist_ok=True)
    md = args.results / f"{scene.name}_fragility.md"
    md.write_text("\n".join(text), encoding="utf-8")
    print(f"wrote {md} and {figure}")
    return md


if __name__ == "__main__":
    main()
