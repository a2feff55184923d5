#!/usr/bin/env python3
"""Energy of packed polygon weirs at rest, stepped at the polygons' stable step and at the scenes' step.

The discs' stable step is also bounded by the explicit dashpots of a packed stone (critical damping), a
bound found on packed disc weirs whose energy grew at the pair's undamped bound alone (docs/dem.md). The
polygons' stable step is the trace bound of a two-point face contact, omega^2 <= 4 k (1/m + R^2/I), without
that second bound. This script packs the paper's trapezoid (height 0.25 m, crest 0.2 m, 27/27 degrees) with
polygon stones of 4.8 cm +- 10 % under critical damping (restitution 0) for seeds 0-5, then steps each at
rest for 1 s at exactly stable_dt() and at 4e-5 s (scenes/maeno2008_polygons.toml), and reports the
relative change of the total energy.

usage: PYTHONPATH=python python3 validation/polygon_packed_energy.py [--seeds 6] [--duration 1.0]
Writes validation/results/polygon_packed_energy.md.
"""
import argparse
import os

import vofdem

HERE = os.path.dirname(os.path.abspath(__file__))
SCENE_DT = 4e-5


def packed(seed):
    p = vofdem.DEMParams()
    p.add_flume(0.0, 1.4, 0.0)
    p.dt, p.contact_steps = SCENE_DT, 50.0
    spec = vofdem.WeirSpec()  # the Maeno weir's slopes; its stones (4.8 cm +- 10 %, 2650 kg/m^3) set here
    spec.d_mean, spec.density = 0.048, 2650.0
    spec.shape, spec.height, spec.crest, spec.x_toe, spec.seed = "polygon", 0.25, 0.2, 0.2, seed
    s, _ = vofdem.pack_weir(spec, p)
    return s


def growth(s, dt, duration):
    s.step(dt)
    e0 = s.energy().total
    for _ in range(int(duration / dt)):
        s.step(dt)
    return (s.energy().total - e0) / abs(e0)


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--seeds", type=int, default=6)
    ap.add_argument("--duration", type=float, default=1.0)
    ap.add_argument("--out", default=os.path.join(HERE, "results", "polygon_packed_energy.md"))
    args = ap.parse_args()
    lines = ["# Packed polygon weirs at rest: energy over time at the stable step", "",
             f"`validation/polygon_packed_energy.py`: the paper's trapezoid packed with polygon stones (critical "
             f"damping), {args.duration:g} s at rest; relative change of the total energy.", "",
             "| seed | stones | stable_dt [s] | at stable_dt | at 4e-5 s (dt / stable_dt) |", "|---|---|---|---|---|"]
    for seed in range(args.seeds):
        sd = packed(seed).stable_dt()
        g1 = growth(packed(seed), sd, args.duration)
        s = packed(seed)
        g2 = growth(s, SCENE_DT, args.duration)
        lines.append(f"| {seed} | {s.n} | {sd:.3g} | {g1:.2e} | {g2:.2e} ({SCENE_DT / sd:.2f}) |")
        print(lines[-1], flush=True)
    text = "\n".join(lines) + "\n"
    with open(args.out, "w", encoding="utf-8") as f:
        f.write(text)
    print(text)


if __name__ == "__main__":
    main()
