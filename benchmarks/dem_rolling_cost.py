#!/usr/bin/env python3
"""Cost of the rolling resistance: DEM particle-steps per second with and without it, in one process.

Two cases, each run with three variants alternated over several rounds (CPU time of `DEMSystem.advance`,
the median over the rounds): the rolling-resistance flag off; the flag on with mu_r = 0 (must cost
nothing: the contact loops do not enter the model); the flag on with mu_r = 0.4 at stone-stone and
stone-wall contacts.

* settle: N discs of 4.8 cm +- 10 % released on a square lattice settling onto a floor (the set-up of
  benchmarks/dem_settle.py: automatic stiffness, friction 0.577), 5,000 steps of 1e-4 s from the start;
* heap: the same discs once at rest (every contact loaded; where the rolling springs work), 5,000 steps.

With --baseline DIR (the python/ directory of another build of vofdem, e.g. one from before the rolling
resistance existed), the heap case with the model off is also timed in that build and in this one, in
alternated child processes (one build per process), to show that the model costs nothing when off.

usage: PYTHONPATH=python python3 benchmarks/dem_rolling_cost.py [--sizes 1000 4000] [--rounds 5]
       [--baseline DIR]
Writes benchmarks/results/dem_rolling_cost.md.
"""
import argparse
import math
import os
import subprocess
import sys
import time

import numpy as np

import vofdem

HERE = os.path.dirname(os.path.abspath(__file__))
VARIANTS = [("flag off", False, 0.0), ("flag on, mu_r = 0", True, 0.0), ("flag on, mu_r = 0.4", True, 0.4)]


def params(flag, mu_r, width):
    p = vofdem.DEMParams()
    p.add_flume(0.0, width, 0.0, 0.577)
    if not hasattr(vofdem, "DEM_ROLLING_RESISTANCE"):  # a build from before the model (--baseline)
        return p
    if not flag:
        p.flags = p.flags & ~vofdem.DEM_ROLLING_RESISTANCE
    p.rolling_friction_stone = p.rolling_friction_wall = mu_r
    return p


def lattice(n, seed=1):
    rng = np.random.default_rng(seed)
    nx = int(math.ceil(math.sqrt(n)))
    k = np.arange(n)
    pos = np.c_[(k % nx + 0.5) * 0.055 + rng.uniform(-1e-3, 1e-3, n), (k // nx + 0.5) * 0.055]
    return pos, 0.024 * rng.uniform(0.9, 1.1, n), nx * 0.055


def system(state, flag, mu_r, width):
    s = vofdem.DEMSystem(params(flag, mu_r, width), 0)
    s.import_state(state)
    return s


def cpu_per_particle_step(s, steps):
    c0 = time.process_time()
    s.advance(steps * s.params.dt)
    return (time.process_time() - c0) / (s.n * steps) * 1e9


def measure(n, steps, rounds):
    pos, r, width = lattice(n)
    start = vofdem.DEMSystem(params(False, 0.0, width), pos=pos, density=[2650.0], radius=r)
    settle0 = {k: v.copy() for k, v in start.export_state().items()}
    start.advance(3.0)  # a heap at rest: every stone on its neighbours
    heap0 = {k: v.copy() for k, v in start.export_state().items()}
    vmax = float(np.hypot(*np.asarray(start.stone_vel).T).max())
    out = {}
    for case, state in (("settle", settle0), ("heap", heap0)):
        times = {name: [] for name, _, _ in VARIANTS}
        for _ in range(rounds):
            for name, flag, mu in VARIANTS:
                times[name].append(cpu_per_particle_step(system(state, flag, mu, width), steps))
        out[case] = {name: float(np.median(t)) for name, t in times.items()}
    return out, vmax


def heap_off(n, steps, rounds):
    """CPU ns per particle-step of the heap at rest with the model off (the build imported here)."""
    pos, r, width = lattice(n)
    s = vofdem.DEMSystem(params(False, 0.0, width), pos=pos, density=[2650.0], radius=r)
    s.advance(3.0)
    state = {k: v.copy() for k, v in s.export_state().items()}
    return float(np.median([cpu_per_particle_step(system(state, False, 0.0, width), steps) for _ in range(rounds)]))


def against_baseline(baseline, n, steps, rounds):
    """(this build, baseline) medians over `rounds` alternated child processes of heap_off."""
    here = os.path.join(os.path.dirname(HERE), "python")
    out = {"this": [], "baseline": []}
    for _ in range(rounds):
        for name, path in (("baseline", baseline), ("this", here)):
            env = dict(os.environ, PYTHONPATH=path)
            res = subprocess.run([sys.executable, __file__, "--child", str(n), str(steps)], env=env,
                                 capture_output=True, text=True, check=True)
            out[name].append(float(res.stdout.split()[-1]))
    return float(np.median(out["this"])), float(np.median(out["baseline"]))


def main():
    if len(sys.argv) == 4 and sys.argv[1] == "--child":
        print(heap_off(int(sys.argv[2]), int(sys.argv[3]), 3))
        return 0
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--sizes", type=int, nargs="+", default=[1000, 4000])
    ap.add_argument("--steps", type=int, default=5000)
    ap.add_argument("--rounds", type=int, default=5)
    ap.add_argument("--baseline", default=None, help="python/ directory of another build of vofdem")
    args = ap.parse_args()
    lines = ["# Cost of the rolling resistance (one process, variants alternated)", "",
             f"CPU ns per particle-step of `DEMSystem.advance`, median of {args.rounds} alternated rounds of "
             f"{args.steps} steps of 1e-4 s; `benchmarks/dem_rolling_cost.py`. Ratios are to the flag off.", "",
             "| N | case | flag off | flag on, mu_r = 0 | flag on, mu_r = 0.4 | ratio mu_r = 0 | ratio mu_r = 0.4 |",
             "|---|---|---|---|---|---|---|"]
    for n in args.sizes:
        res, vmax = measure(n, args.steps, args.rounds)
        for case, t in res.items():
            a, b, c = (t[name] for name, _, _ in VARIANTS)
            lines.append(f"| {n} | {case} | {a:.1f} | {b:.1f} | {c:.1f} | {b / a:.3f} | {c / a:.3f} |")
            print(lines[-1], flush=True)
        lines.append(f"| {n} | (heap: largest speed at the start {vmax:.1e} m/s) | | | | | |")
    if args.baseline:
        n = args.sizes[0]
        this, base = against_baseline(args.baseline, n, args.steps, args.rounds)
        lines += ["", f"Against a build from before the rolling resistance (`--baseline`), heap of {n} at rest, model "
                      f"off, medians of {args.rounds} alternated child processes: this build {this:.1f}, the baseline "
                      f"{base:.1f} CPU ns per particle-step, ratio {this / base:.3f}."]
        print(lines[-1])
    lines += ["", f"Machine load while measuring (1-min load average): {os.getloadavg()[0]:.1f} on "
                  f"{os.cpu_count()} cores."]
    path = os.path.join(HERE, "results", "dem_rolling_cost.md")
    os.makedirs(os.path.dirname(path), exist_ok=True)
    with open(path, "w") as f:
        f.write("\n".join(lines) + "\n")
    print("wrote", path)


if __name__ == "__main__":
    sys.exit(main())
