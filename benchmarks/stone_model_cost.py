"""The stones' cost per particle-step and the coupled step's cost, for discs and polygons, in one run
across builds: each given Python interpreter (each with its own vofdem installed, e.g. a build before a
change and one after) runs the same cases in a child process, the interpreters alternating round by
round on one core, and each case's final state is hashed, so that the table says both what the builds
cost and whether they computed the same bits.

Cases:
- DEM alone: the scene's weir as the builder packs it (seed 0, untimed), advanced `--dem-time` s under
  its buoyant weight without the flow; the cost per particle-step is the CPU time over (stones x DEM
  steps).
- coupled: scenes/maeno2008.toml and scenes/maeno2008_polygons.toml to `--end-time` s (the release of
  the stones included), seed 0; the CPU time per coupled step.

Writes benchmarks/results/stone_model_cost.md (medians over the rounds; ratios against the first
interpreter).

    python3 benchmarks/stone_model_cost.py --python BEFORE/bin/python AFTER/bin/python
        [--label before after] [--rounds 5]
        [--dem-time 2] [--end-time 30] [--out FILE]
"""
import argparse
import hashlib
import json
import os
import platform
import re
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
SCENES = {"disc": "scenes/maeno2008.toml", "polygon": "scenes/maeno2008_polygons.toml"}


def state_hash(state: dict) -> str:
    """sha256 of a state's named arrays, in key order (the bits, not the values' text); the stones' arrays
    under their present names (stone_pos), also for builds that named them disc_pos."""
    import numpy as np

    named = {re.sub(r"(^|/)disc_", r"\1stone_", key): key for key in state}
    h = hashlib.sha256()
    for name in sorted(named):
        h.update(name.encode())
        h.update(np.ascontiguousarray(np.asarray(state[named[name]], dtype=float)).tobytes())
    return h.hexdigest()[:16]


def dem_case(shape: str, duration: float) -> dict:
    from vofdem.builder import build_stones
    from vofdem.scene import load_scene

    stones, _ = build_stones(load_scene(ROOT / SCENES[shape]))
    steps0 = stones.steps
    cpu0 = time.process_time()
    stones.advance(duration)
    cpu = time.process_time() - cpu0
    steps = stones.steps - steps0
    return dict(n=stones.n, steps=steps, cpu=cpu, ns_per_particle_step=1e9 * cpu / (stones.n * steps),
                hash=state_hash(stones.export_state()))


def coupled_case(shape: str, end_time: float) -> dict:
    from vofdem.builder import build_simulation
    from vofdem.run import run_scene
    from vofdem.scene import load_scene

    scene = load_scene(ROOT / SCENES[shape])
    scene = scene.replace(end_time=end_time)
    sim = build_simulation(scene)
    with tempfile.TemporaryDirectory() as tmp:
        cpu0 = time.process_time()
        run_scene(scene, tmp, sim=sim, progress=False, figures=False, animation=False, log=lambda *a: None)
        cpu = time.process_time() - cpu0
    return dict(steps=int(sim.step_count), cpu=cpu, ms_per_step=1e3 * cpu / max(1, sim.step_count),
                hash=state_hash(sim.export_state()))


def child(args) -> None:
    out = {}
    for shape in ("disc", "polygon"):
        out[f"dem/{shape}"] = dem_case(shape, args.dem_time)
        out[f"coupled/{shape}"] = coupled_case(shape, args.end_time)
    print(json.dumps(out))


def run_child(python: str, args) -> dict:
    env = dict(os.environ, OMP_NUM_THREADS="1")
    cmd = [python, str(Path(__file__).resolve()), "--child", "--dem-time", str(args.dem_time),
           "--end-time", str(args.end_time)]
    done = subprocess.run(cmd, capture_output=True, text=True, env=env, cwd="/")
    if done.returncode != 0:
        raise SystemExit(f"{python} failed:\n{done.stderr[-3000:]}")
    return json.loads(done.stdout.strip().splitlines()[-1])


def table(pythons, rounds) -> str:
    cases = list(rounds[0][0])
    lines = ["| case | " + " | ".join(f"build {k}" for k in range(len(pythons))) + " | ratio (last / first) | same bits |",
             "|---|" + "---|" * (len(pythons) + 2)]
    for case in cases:
        key = "ns_per_particle_step" if case.startswith("dem/") else "ms_per_step"
        unit = "ns per particle-step" if case.startswith("dem/") else "ms CPU per coupled step"
        med = [statistics.median(r[k][case][key] for r in rounds) for k in range(len(pythons))]
        hashes = {r[k][case]["hash"] for r in rounds for k in range(len(pythons))}
        lines.append(f"| {case} ({unit}) | " + " | ".join(f"{m:.4g}" for m in med) +
                     f" | {med[-1] / med[0]:.3f} | {'yes' if len(hashes) == 1 else 'NO: ' + ', '.join(sorted(hashes))} |")
    return "\n".join(lines)


def main(argv=None) -> None:
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--python", nargs="+", default=[sys.executable], help="interpreters, each with its vofdem")
    ap.add_argument("--label", nargs="+", help="a name for each interpreter's build (default: its path)")
    ap.add_argument("--rounds", type=int, default=5)
    ap.add_argument("--dem-time", type=float, default=2.0, help="DEM-alone duration [s]")
    ap.add_argument("--end-time", type=float, default=30.0, help="coupled scenes' end time [s]")
    ap.add_argument("--out", default=str(ROOT / "benchmarks" / "results" / "stone_model_cost.md"))
    ap.add_argument("--child", action="store_true", help=argparse.SUPPRESS)
    args = ap.parse_args(argv)
    if args.child:
        return child(args)
    labels = args.label or args.python
    if len(labels) != len(args.python):
        raise SystemExit(f"--label has {len(labels)} names for {len(args.python)} interpreters: give one each")
    rounds, loads = [], []
    for r in range(args.rounds):
        loads.append(os.getloadavg()[0])
        rounds.append([run_child(p, args) for p in args.python])
        print(f"round {r + 1}/{args.rounds} done", file=sys.stderr)
    loads.append(os.getloadavg()[0])
    text = (f"# Stone models: cost per particle-step and per coupled step, across builds\n\n"
            f"`benchmarks/stone_model_cost.py --rounds {args.rounds} --dem-time {args.dem_time} "
            f"--end-time {args.end_time}`, {time.strftime('%Y-%m-%d %H:%M UTC', time.gmtime())}, "
            f"{platform.processor() or platform.machine()}, one core per child (OMP_NUM_THREADS=1), "
            f"builds alternating round by round; load average during the run "
            f"{min(loads):.2f}-{max(loads):.2f}.\n\n"
            + "\n".join(f"- build {k}: {label}" for k, label in enumerate(labels)) +
            "\n\nMedians over the rounds; 'same bits': every round of every build ended in the same state "
            "(sha256 of the exported state's arrays).\n\n" + table(args.python, rounds) + "\n")
    Path(args.out).parent.mkdir(parents=True, exist_ok=True)
    Path(args.out).write_text(text)
    print(text)


if __name__ == "__main__":
    main()
