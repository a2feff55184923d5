#!/usr/bin/env python3
"""Dry angle of repose of a heap of 300 stones collapsed from a column onto a rough base: polygons
against discs.

The protocol of tests/test_dem.py (discs): the base is a row of fixed stones of the same kind lying on
the bed (polygons on their longest edge) from x = -2.5 to 2.5 m; 300 free stones (nominal diameter
4.8 cm +- 10 %, density 2650, friction 0.577 between stones, 0.176 on the bed, restitution 0 as in the
scenes) start on a lattice column 20 stones wide just above the base (pitch 1.12 d for discs, 1.12 d x
1.47 for polygons: their bounding discs must not overlap) and collapse into a heap. When every stone
is slower than 1 mm/s (or after `--time` s) the heap's surface is taken as the highest stone point in
bins of one diameter, and a straight line is fitted to each flank, as it runs continuously down from the
peak, between 25 % and 85 % of the heap's height; the angle of repose is the mean of the two flanks'
angles. With --pour the stones are poured two at a time onto the middle of the base instead (a funnel). Polygons: random convex 5-8-gons of aspect
ratio 1.5 at random orientations, DEM step 4e-5 s with 50 steps per contact (the discs' stiffness);
discs: the same with their own shape. Uncalibrated shape parameters: a first measurement, not a fit.

usage: PYTHONPATH=python python3 validation/polygon_repose.py [--seeds 0 1 2] [--n 300] [--aspect-ratio 1.5]
       [--vertices 5 8] [--shapes disc polygon] [--out FILE]
Writes validation/results/polygon_repose.md.
"""
import argparse
import math
import os
import time

import numpy as np

import vofdem

HERE = os.path.dirname(os.path.abspath(__file__))
D, SPREAD, RHO, MU = 0.048, 0.10, 2650.0, 0.577
X0, X1 = -2.5, 2.5
SHAPE = {}  # polygon shape parameters of vofdem.random_polygons (command line)


def rest_angle(v):
    """Rotation [rad] that lays the polygon's longest edge at the bottom."""
    e = np.roll(v, -1, axis=0) - v
    k = int(np.argmax(np.hypot(e[:, 0], e[:, 1])))
    return -0.5 * math.pi - math.atan2(-e[k, 0], e[k, 1])


def rotate(v, a):
    c, s = math.cos(a), math.sin(a)
    return v @ np.array([[c, -s], [s, c]]).T


def build(shape, n, seed):
    rng = np.random.default_rng(seed)
    n_base = int((X1 - X0) / (0.9 * D)) + 2
    d = D * rng.uniform(1 - SPREAD, 1 + SPREAD, n_base + n)
    pos, angle, fixed = [], [], []
    vertex = offset = None
    if shape == "polygon":
        vertex, offset = vofdem.random_polygons(d, seed=seed, **SHAPE)
    # the base: touching stones lying on the bed
    x = X0
    for i in range(n_base):
        if shape == "polygon":
            v = vertex[offset[i]:offset[i + 1]]
            a = rest_angle(v)
            w = rotate(v, a)
            x_c, z_c, x_next = x - w[:, 0].min(), -w[:, 1].min(), x - w[:, 0].min() + w[:, 0].max()
        else:
            a, x_c, z_c, x_next = 0.0, x + 0.5 * d[i], 0.5 * d[i], x + d[i]
        if x_next > X1:
            break
        pos.append((x_c, z_c)), angle.append(a), fixed.append(1)
        x = x_next
    nb = len(pos)
    pitch, cols = 1.12 * D * (1.47 if shape == "polygon" else 1.0), 20
    for k in range(n):
        pos.append(((k % cols - 0.5 * (cols - 1)) * pitch + 0.002 * rng.standard_normal(),
                    1.6 * D * (1.47 if shape == "polygon" else 1.0) + (k // cols) * pitch))
        angle.append(rng.uniform(0, 2 * math.pi)), fixed.append(0)
    keep = list(range(nb)) + list(range(n_base, n_base + n))
    p = vofdem.DEMParams()
    p.friction_stone = MU
    p.add_flume(X0, X1, 0.0, 0.176)
    if shape == "polygon":
        p.dt, p.contact_steps = 4e-5, 50.0
    s = vofdem.DEMSystem(p, np.array(pos), 0.5 * d[keep], np.array([RHO]), fixed)
    s.stone_angle[:] = angle
    if shape == "polygon":
        v = np.concatenate([vertex[offset[i]:offset[i + 1]] for i in keep])
        off = np.concatenate([[0], np.cumsum([offset[i + 1] - offset[i] for i in keep])])
        s.set_polygons(v, [int(o) for o in off])
    return s, nb


def surface(s, shape, bin_w=D):
    """(x bin centres, highest point of a free stone in each bin)."""
    if shape == "polygon":
        v, off = np.asarray(s.poly_vertex), np.asarray(s.poly_offset)
        pts = np.concatenate([rotate(v[off[i]:off[i + 1]], s.stone_angle[i]) + s.stone_pos[i] for i in range(s.n)
                              if s.stone_active[i] and not s.stone_fixed[i]])
    else:
        t = np.linspace(0, 2 * math.pi, 24, endpoint=False)
        pts = np.concatenate([s.stone_pos[i] + s.stone_radius[i] * np.stack([np.cos(t), np.sin(t)], 1)
                              for i in range(s.n) if s.stone_active[i] and not s.stone_fixed[i]])
    edges = np.arange(X0, X1 + bin_w, bin_w)
    idx = np.digitize(pts[:, 0], edges) - 1
    top = np.full(edges.size - 1, np.nan)
    for b in range(top.size):
        sel = pts[idx == b, 1]
        if sel.size:
            top[b] = sel.max()
    return 0.5 * (edges[1:] + edges[:-1]), top


def flank_angles(x, top):
    """Angles [deg] of the two flanks: line fits to the flank that runs continuously down from the peak,
    between 25 % and 85 % of the heap's height (the rounded top, the toe and stones strewn on the base
    beyond the toe left out)."""
    ok = np.isfinite(top)
    x, top = x[ok], top[ok]
    peak = int(np.argmax(top))
    zt = top[peak]
    out = []
    for step in (-1, 1):
        k, xs, zs = peak, [], []
        while 0 <= k < x.size and top[k] > 0.2 * zt:  # the flank, down to a fifth of the height
            if 0.25 * zt < top[k] < 0.85 * zt:
                xs.append(x[k]), zs.append(top[k])
            k += step
        slope = np.polyfit(xs, zs, 1)[0] if len(xs) >= 3 else float("nan")
        out.append(math.degrees(math.atan(abs(slope))))
    return out, zt


def pour(s, nb, seed, interval=0.05, batch=2):
    """Pours the free stones instead of collapsing the column: they are held (fixed) off the base and
    released `batch` at a time every `interval` s, each dropped from 1.5 d above the top of the settled
    stones at the heap's middle. Returns the simulated time used [s]."""
    rng = np.random.default_rng(seed + 1000)
    free = np.arange(nb, s.n)
    s.stone_pos[free, 0] += X1 + 2.0  # held beside the base, out of reach
    s.stone_fixed[free] = 1
    t = 0.0
    for k in range(0, free.size, batch):
        # the top of the heap: the settled stones near the middle (those still falling do not count)
        released = free[:k]
        speed = np.hypot(s.stone_vel[released, 0], s.stone_vel[released, 1])
        near = released[(np.abs(s.stone_pos[released, 0]) < 2 * D) & (speed < 0.05)]
        top = max([s.stone_pos[i, 1] + s.stone_radius[i] for i in near] + [D])
        for q, i in enumerate(free[k:k + batch]):
            s.stone_pos[i] = [(q - 0.5 * (batch - 1)) * 1.5 * D + rng.uniform(-0.005, 0.005), top + 1.5 * D]
            s.stone_vel[i] = [0.0, 0.0]
            s.stone_omega[i] = 0.0
            s.stone_fixed[i] = 0
        s.advance(interval)
        t += interval
    return t


def run(shape, n, seed, t_max, poured=False):
    s, nb = build(shape, n, seed)
    t0 = time.process_time()
    t = pour(s, nb, seed) if poured else 0.0
    t_max += t
    while t < t_max:
        s.advance(0.1)
        t += 0.1
        free = np.asarray(s.stone_fixed) == 0
        v = np.hypot(s.stone_vel[free, 0], s.stone_vel[free, 1])
        if t > 0.5 and v.max() < 1e-3:
            break
    x, top = surface(s, shape)
    (left, right), h = flank_angles(x, top)
    return {"left": left, "right": right, "height": h, "time": t, "cpu": time.process_time() - t0,
            "vmax": float(v.max()), "lost": int(off_base(s, nb))}


def off_base(s, nb):
    """Free stones that ran off the base's ends."""
    x = s.stone_pos[nb:, 0]
    return np.sum((x < X0) | (x > X1))


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--seeds", type=int, nargs="+", default=[0, 1, 2])
    ap.add_argument("--n", type=int, default=300)
    ap.add_argument("--time", type=float, default=8.0, help="longest settling time [s simulated]")
    ap.add_argument("--out", default=os.path.join(HERE, "results", "polygon_repose.md"))
    ap.add_argument("--aspect-ratio", type=float, default=1.5)
    ap.add_argument("--vertices", type=int, nargs=2, default=[5, 8], metavar=("MIN", "MAX"))
    ap.add_argument("--shapes", nargs="+", default=["disc", "polygon"])
    ap.add_argument("--pour", action="store_true", help="pour the stones two at a time instead of collapsing a column")
    args = ap.parse_args()
    SHAPE.update(aspect_ratio=args.aspect_ratio, vertices_min=args.vertices[0], vertices_max=args.vertices[1])
    lines = ["# Dry angle of repose: polygons against discs", "",
             f"{args.n} stones {'poured two at a time onto' if args.pour else 'collapsed from a column onto'} a rough "
             "base of fixed stones (see the script's docstring), friction 0.577, restitution 0; flanks fitted between "
             f"25 % and 85 % of the heap's height. Polygons: {args.vertices[0]}-{args.vertices[1]} vertices, "
             f"aspect ratio {args.aspect_ratio}. Written by "
             "`validation/polygon_repose.py`.", "",
             "| shape | seed | left flank [deg] | right flank [deg] | mean [deg] | heap height [m] | settled at [s] "
             "| max speed [m/s] | stones off the base | CPU [s] |", "|---|---|---|---|---|---|---|---|---|---|"]
    means = {}
    for shape in args.shapes:
        for seed in args.seeds:
            r = run(shape, args.n, seed, args.time, args.pour)
            mean = 0.5 * (r["left"] + r["right"])
            means.setdefault(shape, []).append(mean)
            lines.append(f"| {shape} | {seed} | {r['left']:.1f} | {r['right']:.1f} | {mean:.1f} | {r['height']:.3f} | "
                         f"{r['time']:.1f} | {r['vmax']:.2g} | {r['lost']} | {r['cpu']:.0f} |")
            print(lines[-1], flush=True)
    lines.append("")
    for shape, m in means.items():
        lines.append(f"- {shape}: mean {np.mean(m):.1f} deg over {len(m)} seeds (range {min(m):.1f}-{max(m):.1f}); "
                     "quarried stone: 37-41 deg (Chow 1959, as quoted in rock-sizing guidance).")
    text = "\n".join(lines) + "\n"
    with open(args.out, "w", encoding="utf-8") as f:
        f.write(text)
    print(text)


if __name__ == "__main__":
    main()
