#!/usr/bin/env python3
"""Cost of polygon stones against discs: particle-steps per second of the DEM, both shapes in one run.

N stones of nominal diameter 0.048 m * U(0.9, 1.1), density 2650, start at rest on a square lattice of
pitch 0.085 m (room for the polygons' bounding discs) and settle onto a floor between two side walls.
The discs and the polygons (random convex 5-8-gons, aspect ratio 1.5, random orientations) have the
same diameters, masses (the polygons' matching stones have the spheres' masses), contact stiffness
(automatic, 50 steps per contact of 4e-5 s = 20 steps of 1e-4 s), restitution 0.5 and friction 0.577,
and both run at the polygons' stable step, 4e-5 s. The two systems are advanced in alternating chunks
of `--chunk` steps within one process, so the machine's load falls on both alike; the cost is the CPU
time of `DEMSystem.advance` per particle-step. The discs alone could run at 1e-4 s (their stable step
at 1e-4 s, the paper's step, 2.5 times the polygons'): the cost per simulated second is reported for
each at its own step too.

usage: PYTHONPATH=python python3 benchmarks/polygon_cost.py [--n 1000] [--steps 50000] [--chunk 2500]
Writes benchmarks/results/polygon_cost.md.
"""
import argparse
import math
import os
import time

os.environ.setdefault("OMP_NUM_THREADS", "1")  # no idle BLAS threads in the process's CPU time
os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")

import numpy as np  # noqa: E402

import vofdem  # noqa: E402

HERE = os.path.dirname(os.path.abspath(__file__))
D_MEAN, SPREAD, RHO, PITCH, DT, STEPS_PER_CONTACT = 0.048, 0.10, 2650.0, 0.085, 4e-5, 50.0


def build(n, shape, seed=12345):
    rng = np.random.default_rng(seed)
    nx = int(math.ceil(math.sqrt(n)))
    k = np.arange(n)
    pos = np.stack([(k % nx + 0.5) * PITCH + rng.uniform(-0.001, 0.001, n), (k // nx + 0.5) * PITCH], axis=1)
    d = D_MEAN * rng.uniform(1.0 - SPREAD, 1.0 + SPREAD, n)
    angle = rng.uniform(0.0, 2.0 * math.pi, n)
    p = vofdem.DEMParams()
    p.dt = DT
    p.contact_steps = STEPS_PER_CONTACT
    p.restitution = 0.5
    p.friction_stone = 0.577
    p.add_flume(0.0, nx * PITCH, 0.0, 0.577)
    s = vofdem.DEMSystem(p, pos=pos, radius=0.5 * d, density=np.array([RHO]))
    if shape == "polygon":
        vertex, offset = vofdem.random_polygons(d, seed=seed)
        s.stone_angle[:] = angle
        s.set_polygons(vertex, offset)
    assert DT <= s.stable_dt(), (shape, s.stable_dt())
    return s


def summary(s):
    v = np.hypot(s.stone_vel[:, 0], s.stone_vel[:, 1])
    return {"contacts": s.contact_count, "walls": s.wall_contact_count, "vmax": float(v.max()),
            "zmax": float(s.stone_pos[:, 1].max()), "builds": s.neighbour_builds,
            "stages": dict(zip(s.profile.names, s.profile.seconds)), "stable_dt": s.stable_dt(),
            "kn": s.stiffness_normal}


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--n", type=int, default=1000)
    ap.add_argument("--steps", type=int, default=50000)
    ap.add_argument("--chunk", type=int, default=2500)
    ap.add_argument("--out", default=os.path.join(HERE, "results", "polygon_cost.md"))
    args = ap.parse_args()
    systems = {shape: build(args.n, shape) for shape in ("disc", "polygon")}
    cpu = {shape: 0.0 for shape in systems}
    done = 0
    while done < args.steps:
        steps = min(args.chunk, args.steps - done)
        for shape, s in systems.items():  # alternated: the same load on both
            c0 = time.process_time()
            s.advance(steps * DT)
            cpu[shape] += time.process_time() - c0
        done += steps
        print(f"{done} steps: disc {cpu['disc']:.1f} s, polygon {cpu['polygon']:.1f} s cpu", flush=True)
    ns = {shape: cpu[shape] / (args.n * args.steps) * 1e9 for shape in systems}
    info = {shape: summary(s) for shape, s in systems.items()}
    ratio = ns["polygon"] / ns["disc"]
    disc_own_dt = 1e-4  # the discs' usual step (the paper's), within their stable step
    assert disc_own_dt <= info["disc"]["stable_dt"]
    lines = ["# Polygon stones against discs: DEM cost per particle-step (one run)", "",
             f"{args.n} stones of each shape, {args.steps} steps of {DT:g} s (both at the polygons' stable step), "
             f"settling from a lattice of pitch {PITCH} m onto a floor; the two systems alternated in chunks of "
             f"{args.chunk} steps in one process; CPU time of `DEMSystem.advance`. k_n = "
             f"{info['disc']['kn']:.4g} N/m for both (automatic, {STEPS_PER_CONTACT:g} steps per contact). "
             "Written by `benchmarks/polygon_cost.py`.", "",
             "| shape | ns per particle-step (cpu) | contacts at the end | wall contacts | max speed at the end [m/s] "
             "| top of the pile [m] | neighbour builds | stable step [s] |",
             "|---|---|---|---|---|---|---|---|"]
    for shape in systems:
        i = info[shape]
        lines.append(f"| {shape} | {ns[shape]:.1f} | {i['contacts']} | {i['walls']} | {i['vmax']:.3g} | "
                     f"{i['zmax']:.4f} | {i['builds']} | {i['stable_dt']:.3g} |")
    lines += ["", f"**Polygons cost {ratio:.2f} x the discs per particle-step** (aim: at most 3 x).", "",
              f"Per simulated second, each shape at its own step (discs at {disc_own_dt:g} s, the paper's step; "
              f"polygons at {DT:g} s): discs {ns['disc'] / disc_own_dt * 1e-3:.0f} us, "
              f"polygons {ns['polygon'] / DT * 1e-3:.0f} us of CPU per stone and simulated second "
              f"({ns['polygon'] / DT / (ns['disc'] / disc_own_dt):.1f} x).", "",
              "Stage shares (seconds of the whole run):", "",
              "| stage | disc [s] | polygon [s] |", "|---|---|---|"]
    for name in info["disc"]["stages"]:
        lines.append(f"| {name} | {info['disc']['stages'][name]:.2f} | {info['polygon']['stages'][name]:.2f} |")
    text = "\n".join(lines) + "\n"
    os.makedirs(os.path.dirname(args.out), exist_ok=True)
    with open(args.out, "w", encoding="utf-8") as f:
        f.write(text)
    print(text)


if __name__ == "__main__":
    main()
