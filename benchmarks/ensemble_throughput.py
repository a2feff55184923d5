"""Throughput of an ensemble: members per hour on a Dask LocalCluster of 1 and of 2 worker processes
(one thread each), and in this process without Dask, for the quick Maeno 2008 scene.

The same seeds run in every variant, each into its own fresh directory (no figures, no animation).
The variants alternate within one run, `--rounds` times (in-process, 1 worker, 2 workers, then
again), and each round's 2-worker / 1-worker ratio is reported, with the machine's load average
before and after each measurement: on a shared machine the ratio falls below what the cores
allow. A cluster is started before its timing begins and closed after it ends, so the figure is the
throughput of the members, not of the cluster's start. Writes
benchmarks/results/ensemble_throughput.md.

    PYTHONPATH=python python3 benchmarks/ensemble_throughput.py [--seeds 0-7] [--rounds 2]
"""
import argparse
import os
import shutil
import tempfile
import time
from pathlib import Path

import numpy as np

from vofdem.ensemble import parse_seeds, run_ensemble
from vofdem.scene import Scene

OUT = Path(__file__).resolve().parent / "results" / "ensemble_throughput.md"


def measure(scene, seeds, workers, work_dir: Path):
    """(wall seconds of the members, load average before, after, members completed, the members' own
    wall seconds added up)."""
    from distributed import Client, LocalCluster

    out = Path(tempfile.mkdtemp(dir=work_dir))
    opts = dict(progress=False, n_boot=0, log=lambda *a: None)
    load0 = os.getloadavg()[0]
    if workers == 0:
        t0 = time.perf_counter()
        df = run_ensemble(scene, seeds, out, workers=0, **opts)
        wall = time.perf_counter() - t0
    else:
        with LocalCluster(n_workers=workers, threads_per_worker=1, processes=True, dashboard_address=":0") as cl, \
                Client(cl) as client:
            client.wait_for_workers(workers)
            t0 = time.perf_counter()
            df = run_ensemble(scene, seeds, out, client=client, **opts)
            wall = time.perf_counter() - t0
    load1 = os.getloadavg()[0]
    shutil.rmtree(out)
    return wall, load0, load1, int((df["status"] == "completed").sum()), float(df["wall_seconds"].sum())


def main(argv=None):
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--seeds", default="0-7", help="the members' seeds (default 0-7)")
    p.add_argument("--rounds", type=int, default=2)
    p.add_argument("--end-time", type=float, default=None, help="shorter members (for a test) [s]")
    p.add_argument("--out", type=Path, default=OUT)
    args = p.parse_args(argv)
    seeds = parse_seeds(args.seeds)
    scene = Scene.maeno2008().quick()
    if args.end_time is not None:
        scene = scene.replace(end_time=args.end_time)
    variants = [("in this process, no Dask", 0), ("LocalCluster, 1 worker", 1), ("LocalCluster, 2 workers", 2)]
    rows = {name: [] for name, _ in variants}
    with tempfile.TemporaryDirectory() as work:
        for r in range(args.rounds):
            for name, workers in variants:
                res = measure(scene, seeds, workers, Path(work))
                rows[name].append(res)
                print(f"round {r + 1}: {name}: {res[0]:.1f} s for {res[3]} members, {res[4] / res[0]:.2f} at once "
                      f"(load {res[1]:.2f} -> {res[2]:.2f})", flush=True)
    text = report(scene, seeds, args.rounds, rows)
    args.out.parent.mkdir(parents=True, exist_ok=True)
    args.out.write_text(text, encoding="utf-8")
    print(text)


def report(scene, seeds, rounds, rows) -> str:
    n = len(seeds)
    lines = [f"# Ensemble throughput: {scene.name}, {n} members (seeds {seeds[0]}-{seeds[-1]}), {rounds} rounds",
             "", f"{os.cpu_count()} cores; each member {scene.duration:g} s simulated, no figures, no animation. "
             "Variants alternate within each round; the load average (1 min) is the machine's, before and after "
             "each measurement. Members at once: the members' own wall times added up over the ensemble's wall "
             "time, how many ran side by side on average (the scheduling, whatever the machine's load).", "",
             "| variant | round | wall [s] | members per hour | members at once | load before / after |",
             "|---|---|---|---|---|---|"]
    for name, res in rows.items():
        for r, (wall, l0, l1, done, member_wall) in enumerate(res, start=1):
            lines.append(f"| {name} | {r} | {wall:.1f} | {3600 * done / wall:.0f} | {member_wall / wall:.2f} | "
                         f"{l0:.2f} / {l1:.2f} |")
    one, two = rows["LocalCluster, 1 worker"], rows["LocalCluster, 2 workers"]
    ratios = [a[0] / b[0] for a, b in zip(one, two)]
    inproc = rows["in this process, no Dask"]
    lines += ["", f"2 workers / 1 worker, members per hour, per round: {', '.join(f'{x:.2f}' for x in ratios)} "
              f"(median {np.median(ratios):.2f}; the aim on a quiet 2-core machine is at least 1.8).",
              f"1 worker / in this process: {', '.join(f'{b[0] / a[0]:.2f}' for a, b in zip(one, inproc))} "
              "(wall time in this process over wall time on 1 worker: the cost of running a member as a Dask "
              "task is its shortfall from 1)."]
    return "\n".join(lines) + "\n"


if __name__ == "__main__":
    main()
