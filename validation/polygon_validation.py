#!/usr/bin/env python3
"""Polygon stones: restitution of a flat impact, a block on an incline, the packed weir over seeds, and a
figure of the packed polygon weir next to the disc weir of the same seed.

1. A 6 x 3 cm box falls flat onto the bed at 0.5 m/s (no gravity): rebound / impact speed against e,
   resolved by 400 steps per contact and at the automatic stiffness (50 steps of 4e-5 s).
2. The same box on a bed tilted by theta (mu = 0.5): held at tan(theta) = 0.9 mu, sliding at 1.1 mu
   with g (sin - mu cos).
3. The paper's weir (H = 0.25 m, crest 0.20 m, 27/27 degrees, 4.8 cm +- 10 %) packed with polygons
   (5-8 vertices, aspect ratio 1.5) for seeds 0-3: stones, porosity, outline error, settling.

usage: PYTHONPATH=python python3 validation/polygon_validation.py [--seeds 0 1 2 3]
Writes validation/results/polygon_validation.md and docs/figures/polygon_weir.png.
"""
import argparse
import math
import os
import time

import numpy as np

import vofdem

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(HERE)
A, B, RHO, G = 0.03, 0.015, 2650.0, 9.81


def box_system(p, x, z):
    s = vofdem.DEMSystem(p, np.array([[x, z]]), [math.hypot(A, B)], np.array([RHO]))
    s.set_polygons(np.array([[-A, -B], [A, -B], [A, B], [-A, B]]), [0, 4])
    return s


def flat_impact(e, steps_per_contact):
    p = vofdem.DEMParams()
    p.medium.gravity = [0.0, 0.0]
    p.restitution = e
    p.walls = [vofdem.DEMWall(point=[0.0, 0.0], normal=[0.0, 1.0], friction=0.5)]
    zeta = vofdem.damping_ratio_from_restitution(e)
    if steps_per_contact is None:  # the automatic stiffness of the polygon scene
        p.dt, p.contact_steps = 4e-5, 50.0
        s = box_system(p, 0.0, B + 5e-4)
        s.stable_dt()  # prepares: the automatic k_n
        tc = vofdem.contact_duration(2.0 * s.stiffness_normal, s.mass(0), zeta)
    else:
        p.stiffness_normal = 1e5
        s = box_system(p, 0.0, B + 5e-4)
        tc = vofdem.contact_duration(2e5, s.mass(0), zeta)
        p.dt = tc / steps_per_contact
        s.params = p
    s.stone_vel[0, 1] = -0.5
    s.advance(5e-4 / 0.5 + 2.0 * tc)
    return s.stone_vel[0, 1] / 0.5, p.dt


def incline(ratio, mu=0.5):
    th = math.atan(ratio * mu)
    p = vofdem.DEMParams()
    p.medium.gravity = [G * math.sin(th), -G * math.cos(th)]
    p.stiffness_normal = 1e5
    p.dt = 5e-5
    p.walls = [vofdem.DEMWall(point=[0.0, 0.0], normal=[0.0, 1.0], friction=mu)]
    s = box_system(p, 0.0, B)
    s.advance(0.5)
    v0 = s.stone_vel[0, 0]
    s.advance(0.5)
    acc = (s.stone_vel[0, 0] - v0) / 0.5
    return math.degrees(th), acc, max(0.0, G * (math.sin(th) - mu * math.cos(th))), s.stone_pos[0, 0], s.stone_angle[0]


def pack(seed, shape):
    p = vofdem.DEMParams()
    if shape == "polygon":
        p.dt, p.contact_steps = 4e-5, 50.0
    t0 = time.perf_counter()
    spec = vofdem.WeirSpec()  # the Maeno trapezoid of 4.8 cm stones +- 10 %, 2650 kg/m^3
    spec.height, spec.crest, spec.slope_up_deg, spec.slope_down_deg, spec.x_toe = 0.25, 0.20, 27.0, 27.0, 1.0
    spec.d_mean, spec.d_spread, spec.density, spec.seed, spec.shape = 0.048, 0.1, 2650.0, seed, shape
    s, r = vofdem.pack_weir(spec, p)
    return s, r, spec, time.perf_counter() - t0


def outlines(s):
    if s.shape != "polygon":
        return None
    v, off, out = np.asarray(s.poly_vertex), np.asarray(s.poly_offset), []
    for i in range(s.n):
        a = s.stone_angle[i]
        rot = np.array([[math.cos(a), -math.sin(a)], [math.sin(a), math.cos(a)]])
        out.append(v[off[i]:off[i + 1]] @ rot.T + s.stone_pos[i])
    return out


def figure(disc, poly, spec, path):
    from matplotlib.collections import EllipseCollection, PolyCollection
    from matplotlib.figure import Figure

    fig = Figure(figsize=(8.0, 4.2), layout="constrained")
    xs = [spec.x_toe, spec.x_toe + spec.height / math.tan(math.radians(spec.slope_up_deg)),
          spec.x_end() - spec.height / math.tan(math.radians(spec.slope_down_deg)), spec.x_end()]
    for k, (s, title) in enumerate(((disc, "discs"), (poly, "polygons"))):
        ax = fig.add_subplot(2, 1, k + 1)
        face = np.where(np.asarray(s.stone_fixed) > 0, "0.5", "tan")
        if s.shape == "polygon":
            ax.add_collection(PolyCollection(outlines(s), facecolors=face, edgecolors="0.2", linewidths=0.4))
        else:
            d = 2 * np.asarray(s.stone_radius)
            ax.add_collection(EllipseCollection(d, d, np.zeros(s.n), units="xy", offsets=np.asarray(s.stone_pos),
                                                offset_transform=ax.transData, facecolors=face, edgecolors="0.2",
                                                linewidths=0.4))
        ax.plot(xs, [0, spec.height, spec.height, 0], color="tab:orange", lw=1.2)
        ax.set_xlim(spec.x_toe - 0.05, spec.x_end() + 0.05)
        ax.set_ylim(0, spec.height * 1.25)
        ax.set_aspect("equal")
        ax.set_title(f"packed weir, seed 0: {s.n} {title}", fontsize=9)
        ax.set_ylabel("z [m]")
    ax.set_xlabel("x [m]")
    fig.savefig(path, dpi=90)


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--seeds", type=int, nargs="+", default=[0, 1, 2, 3])
    ap.add_argument("--out", default=os.path.join(HERE, "results", "polygon_validation.md"))
    ap.add_argument("--figure", default=os.path.join(ROOT, "docs", "figures", "polygon_weir.png"))
    args = ap.parse_args()
    lines = ["# Polygon stones: validation", "", "Written by `validation/polygon_validation.py`.", "",
             "## Flat impact on the bed (box 6 x 3 cm, 0.5 m/s, no gravity)", "",
             "| e | rebound / impact, 400 steps per contact | error | automatic stiffness (50 steps of 4e-5 s) | error |",
             "|---|---|---|---|---|"]
    for e in (0.3, 0.5, 0.9):
        r400, _ = flat_impact(e, 400)
        rauto, _ = flat_impact(e, None)
        lines.append(f"| {e} | {r400:.4f} | {100 * (r400 / e - 1):+.2f} % | {rauto:.4f} | {100 * (rauto / e - 1):+.2f} % |")
    lines += ["", "## Box on an incline (mu = 0.5, k_n = 1e5 N/m, dt = 5e-5 s)", "",
              "| tan(theta) / mu | theta [deg] | acceleration [m/s^2] | g (sin - mu cos) | x after 1 s [m] | turned [rad] |",
              "|---|---|---|---|---|---|"]
    for ratio in (0.9, 1.1, 1.5):
        th, acc, exact, x, ang = incline(ratio)
        lines.append(f"| {ratio} | {th:.2f} | {acc:.5f} | {exact:.5f} | {x:.3g} | {ang:.2g} |")
    lines += ["", "## The paper's weir packed with polygons (5-8 vertices, aspect ratio 1.5) and with discs", "",
              "| seed | shape | stones (fixed) | 2D porosity | outline error [m] | settling [s simulated] | wall [s] |",
              "|---|---|---|---|---|---|---|"]
    first = {}
    for seed in args.seeds:
        for shape in ("disc", "polygon"):
            s, r, spec, wall = pack(seed, shape)
            if seed == args.seeds[0]:
                first[shape] = (s, spec)
            lines.append(f"| {seed} | {shape} | {r.n_stones} ({r.n_fixed}) | {r.porosity:.3f} | {r.outline_error:.4f} | "
                         f"{r.settle_time:.1f} | {wall:.1f} |")
    os.makedirs(os.path.dirname(args.figure), exist_ok=True)
    figure(first["disc"][0], first["polygon"][0], first["polygon"][1], args.figure)
    lines += ["", f"Figure: `{os.path.relpath(args.figure, ROOT)}` (seed {args.seeds[0]})."]
    text = "\n".join(lines) + "\n"
    with open(args.out, "w", encoding="utf-8") as f:
        f.write(text)
    print(text)


if __name__ == "__main__":
    main()
