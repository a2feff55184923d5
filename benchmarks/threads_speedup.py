"""Threads for one run: the Maeno scenario on one and on two threads in one process, and what scales.

Builds maeno2008_consistent at each --fidelity (default: fine, the grid twice as fine as the paper's,
and standard, the paper's), holds the stones as a run's spin-up does, and advances it from rest to
--seconds of simulated time (default 3 s at 10 l/s) on 1 and on 2 threads, alternating (--repeats
pairs), each from the same state. Reports the wall time per step (best and median of the repeats,
with the CPU time of the process, which counts every thread), the speed-up, and that both thread
counts end in the same bits and steps. The stage timers (coupler, flow, k-epsilon) of the best runs
give the speed-up per stage. Amdahl's law with the serial fraction measured at two threads
(Karp-Flatt: f = 2 / S2 - 1, the serial work and the threads' overhead together) predicts eight threads:
S8 = 1 / (f + (1 - f) / 8). The 1-minute load average before and after each run is recorded: the
machine is shared, and threads that wait for each other suffer most from other work on the cores.
Writes benchmarks/results/threads_speedup.md.

    PYTHONPATH=python python3 benchmarks/threads_speedup.py [--fidelity fine standard] [--seconds 3] [--repeats 3]
"""
import argparse
import hashlib
import multiprocessing
import os
import platform
import statistics
import time
from pathlib import Path

import numpy as np

from vofdem import _core
from vofdem.builder import build_simulation
from vofdem.ensemble import with_settings
from vofdem.scene import load_scene

ROOT = Path(__file__).resolve().parents[1]
THREADS = (1, 2)
FREE = 1.8  # a run counts as taken on free cores when this many were free before it


def _spin(seconds: float) -> float:
    """Spins for `seconds` of wall time; returns the CPU time it got."""
    cpu0, end = time.process_time(), time.perf_counter() + seconds
    while time.perf_counter() < end:
        pass
    return time.process_time() - cpu0


def free_cores(seconds: float = 1.0) -> float:
    """The cores this job has at the moment: the CPU time two spinning processes get together over the
    wall time they spin (about 2 with both cores free, about 1 while other work holds one)."""
    with multiprocessing.get_context("spawn").Pool(2) as pool:
        pool.map(_spin, [0.01, 0.01], chunksize=1)  # the workers started
        return sum(pool.map(_spin, [seconds, seconds], chunksize=1)) / seconds


def state_hash(sim) -> str:
    """SHA-1 over the keys and bytes of the coupled state: equal hashes are equal bits."""
    h = hashlib.sha1()
    for key, value in sorted(sim.export_state().items()):
        h.update(key.encode())
        h.update(np.ascontiguousarray(value).tobytes())
    return h.hexdigest()[:16]


def profiles(sim):
    return [("coupler", sim.profile), ("flow", sim.fluid.profile), ("k-epsilon", sim.fluid.turbulence_profile)]


def one_run(sim, start, seconds: float, threads: int) -> dict:
    """The spin-up from `start` (a state) to `seconds` on `threads` threads: wall and CPU time, steps,
    the stage timers and the end state's hash."""
    _core.set_threads(threads)
    sim.import_state(start)
    sim.stones.stone_fixed[:] = True  # held, as in a run's spin-up
    for _, p in profiles(sim):
        p.reset()
    load0 = os.getloadavg()[0]
    steps0, wall0, cpu0 = sim.step_count, time.perf_counter(), time.process_time()
    sim.advance(seconds)
    wall, cpu, steps = time.perf_counter() - wall0, time.process_time() - cpu0, sim.step_count - steps0
    stages = {f"{label} / {name}": s for label, p in profiles(sim) for name, s in zip(p.names, p.seconds)}
    return dict(threads=threads, wall=wall, cpu=cpu, steps=steps, stages=stages, hash=state_hash(sim),
                load=(load0, os.getloadavg()[0]))


def wait_for_free_cores(wait: float, log=print) -> float:
    """Probes every 10 s until FREE cores are free or `wait` seconds passed; returns the last probe."""
    end = time.perf_counter() + wait
    cores = free_cores()
    while cores < FREE and time.perf_counter() < end:
        log(f"  {cores:.2f} cores free: waiting")
        time.sleep(10.0)
        cores = free_cores()
    return cores


def measure(fidelity: str, seconds: float, repeats: int, wait: float = 0.0, log=print) -> dict:
    scene = with_settings(load_scene(ROOT / "scenes" / "maeno2008_consistent.toml"), [f"numerics.fidelity={fidelity}"])
    sim = build_simulation(scene)
    start = {k: np.array(v, copy=True) for k, v in sim.export_state().items()}
    runs = {n: [] for n in THREADS}
    for r in range(repeats):
        for n in THREADS:
            cores = wait_for_free_cores(wait, log)
            run = one_run(sim, start, seconds, n)
            run["free_cores"] = cores
            runs[n].append(run)
            log(f"{fidelity}: repeat {r + 1}, {n} thread(s): {1e3 * run['wall'] / run['steps']:.3f} ms/step, "
                f"load {run['load'][0]:.2f} -> {run['load'][1]:.2f}, free cores {cores:.2f}")
    g = sim.fluid.grid
    return dict(fidelity=fidelity, nx=g.nx, nz=g.nz, runs=runs)


def per_step(run, key="wall"):
    return 1e3 * run[key] / run["steps"]


def amdahl(s2: float, n: int) -> tuple:
    """The serial fraction measured at two threads (Karp-Flatt) and the speed-up it predicts on n."""
    f = 2.0 / s2 - 1.0
    return f, 1.0 / (f + (1.0 - f) / n)


def stage_rows(best1, best2, steps):
    rows = ["| stage | 1 thread [ms/step] | 2 threads [ms/step] | speed-up |", "|---|---|---|---|"]
    for key, s1 in best1["stages"].items():
        s2 = best2["stages"].get(key, 0.0)
        if s1 * 1e3 / steps < 0.01:
            continue
        rows.append(f"| {key} | {1e3 * s1 / steps:.3f} | {1e3 * s2 / steps:.3f} | "
                    f"{(s1 / s2 if s2 > 0 else float('nan')):.2f} |")
    return rows


def speedups(res):
    """Speed-ups on two threads (best runs, medians) over the repeats whose two runs both found FREE cores
    free, and over every repeat; None where there is none."""
    r1, r2 = res["runs"][1], res["runs"][2]
    pairs = [(a, b) for a, b in zip(r1, r2) if a["free_cores"] >= FREE and b["free_cores"] >= FREE]
    out = {}
    for label, sel in (("free", pairs), ("all", list(zip(r1, r2)))):
        if not sel:
            out[label] = None
            continue
        one, two = [a for a, _ in sel], [b for _, b in sel]
        best1, best2 = min(one, key=per_step), min(two, key=per_step)
        out[label] = dict(best=per_step(best1) / per_step(best2),
                          median=statistics.median(map(per_step, one)) / statistics.median(map(per_step, two)),
                          best1=best1, best2=best2, count=len(sel))
    return out


def report(results, seconds: float) -> str:
    text = ["# Threads for one run: one against two threads", "",
            f"Generated by `benchmarks/threads_speedup.py` on {time.strftime('%Y-%m-%d %H:%M UTC', time.gmtime())}, "
            f"{platform.processor() or platform.machine()}, {os.cpu_count()} cores, OpenMP "
            f"{'on' if _core.built_with_openmp() else 'off'}. The scene maeno2008_consistent with its stones held "
            f"(a run's spin-up at 10 l/s) from rest to {seconds:g} s simulated, one and two threads alternating "
            "in one process from the same state. Wall time per step: best and median of the repeats; the CPU "
            "time counts every thread (a waiting thread spins for a while before it sleeps). The machine is "
            "shared with other developers' builds and tests. Before each run the cores free to this job are "
            "measured (the CPU time two processes spinning for 1 s get together: about 2 with both cores free, "
            f"1 while other work holds one; the script waits up to --wait seconds for {FREE:g}), and the 1-minute "
            "load average before and after it is recorded: a run taken while other work held a core is slower "
            "on two threads most (they wait for each other at every parallel loop), so the speed-up is taken "
            f"over the repeats whose two runs both found {FREE:g} or more cores free.", ""]
    for res in results:
        r1, r2 = res["runs"][1], res["runs"][2]
        s = speedups(res)
        use = s["free"] or s["all"]
        s_best, best1, best2 = use["best"], use["best1"], use["best2"]
        f, s8 = amdahl(s_best, 8)
        same = {r["hash"] for r in r1 + r2}, {r["steps"] for r in r1 + r2}
        free_text = (f"{s['free']['best']:.2f} (best runs), {s['free']['median']:.2f} (medians) over the "
                     f"{s['free']['count']} repeat(s) whose runs both found {FREE:g} or more cores free"
                     if s["free"] else f"no repeat found {FREE:g} cores free for both its runs")
        text += [f"## {res['fidelity']} grid ({res['nx']} x {res['nz']} cells)", "",
                 "| threads | repeat | steps | wall [ms/step] | CPU [ms/step] | free cores before | "
                 "load average before -> after |", "|---|---|---|---|---|---|---|"]
        for n in THREADS:
            for i, r in enumerate(res["runs"][n]):
                text.append(f"| {n} | {i + 1} | {r['steps']} | {per_step(r):.3f} | {per_step(r, 'cpu'):.3f} | "
                            f"{r['free_cores']:.2f} | {r['load'][0]:.2f} -> {r['load'][1]:.2f} |")
        text += ["", f"**Speed-up on two threads: {free_text}.** Over every repeat: {s['all']['best']:.2f} (best "
                 f"runs), {s['all']['median']:.2f} (medians). "
                 f"End states: {'the same bits' if len(same[0]) == 1 else 'DIFFERENT bits'} "
                 f"({', '.join(sorted(same[0]))}), {'the same' if len(same[1]) == 1 else 'different'} step counts.",
                 "", (f"Amdahl's law with the serial fraction measured at two threads, f = 2 / S2 - 1 = {f:.3f} "
                      f"(best runs{' on free cores' if s['free'] else ''}; the serial work and the threads' overhead "
                      f"together): eight threads would give S8 = 1 / (f + (1 - f) / 8) = {s8:.2f}." if f < 1.0 else
                      "Two threads were not faster: Amdahl's law predicts nothing for eight."), "",
                 f"Per stage (the best runs{' on free cores' if s['free'] else ''}; stages nest: the flow's are "
                 "parts of the coupler's `fluid`, "
                 "k-epsilon's of the flow's `turbulence`):", "", *stage_rows(best1, best2, best1["steps"]), ""]
    return "\n".join(text)


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--fidelity", nargs="+", default=["fine", "standard"], choices=["draft", "standard", "fine"])
    ap.add_argument("--seconds", type=float, default=3.0, help="simulated time of each run [s]")
    ap.add_argument("--repeats", type=int, default=3, help="pairs of runs (one, two threads) per grid")
    ap.add_argument("--wait", type=float, default=600.0,
                    help=f"before each run, wait up to this long [s] for {FREE:g} free cores (0: no waiting)")
    ap.add_argument("--out", type=Path, default=ROOT / "benchmarks" / "results" / "threads_speedup.md")
    args = ap.parse_args(argv)
    if not args.seconds > 0.0 or args.repeats < 1:
        raise ValueError(f"--seconds {args.seconds} and --repeats {args.repeats}: need seconds > 0, repeats >= 1")
    before = _core.threads()
    try:
        results = [measure(f, args.seconds, args.repeats, args.wait) for f in args.fidelity]
    finally:
        _core.set_threads(before)
    text = report(results, args.seconds)
    args.out.parent.mkdir(parents=True, exist_ok=True)
    args.out.write_text(text + "\n", encoding="utf-8")
    print(text)
    return args.out


if __name__ == "__main__":
    main()
