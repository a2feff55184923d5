#!/usr/bin/env python3
"""Calibration of 3D clump stones on the laboratory's measurements, next to the spheres' (benchmarks/
sphere_calibration.py), never on the weir's failure: the scene `scenes/maeno2008_spheres.toml` (sizes, density,
friction 0.577 / 0.176, the scene's contact stiffness) with each stone a library clump (calibration_3d.ClumpMix,
default pair_2 / triangle_3 / tetra_4 with equal chances, aspect ratios 1 : 0.8 : 0.6) of its nominal diameter,
turned at random; the DEM step lowered to 0.9 of the clumps' stable step at that stiffness
(calibration_3d.clump_params).

1. Dry angle of repose of a 3D heap (calibration.pour_heap with clumps=), against quarried stone's 37-41 deg.
2. The paper's pull-out test (2.81 / 3.04 / 4.75 N vertical / normal / horizontal; horizontal / vertical 1.69)
   on weirs of clumps packed by pack_weir across the flume's 0.5 m, the stones farther than 3 d from the
   pulled one held.
3. The packed weir's porosity (the prism's, and that sampled in its core), against the experiment's 0.41.

A model meets: the angle if its mean lies in 37-41 deg; the pulls if each direction's mean is within 20 % of
the paper's (the sphere study's criterion); the porosity if the prism's lies within 0.03 of 0.41.

usage: PYTHONPATH=python python3 benchmarks/clump_calibration.py [--mu-r 0] [--stones 500] [--weirs 2]
       [--per-seed 2] [--jobs 2] [--compaction-friction F]
Writes benchmarks/results/clump_calibration.md. CPU times are each job's own process time.
"""
import argparse
import os
import sys
import time
from concurrent.futures import ProcessPoolExecutor

import numpy as np

from vofdem import _core
from vofdem import calibration as cal
from vofdem import calibration_3d as c3
from vofdem.scene import load_scene

HERE = os.path.dirname(os.path.abspath(__file__))
SCENE = os.path.join(HERE, "..", "scenes", "maeno2008_spheres.toml")
PULL_TOLERANCE = 0.2
POROSITY, POROSITY_TOLERANCE = 0.41, 0.03
# the spheres' numbers (results/sphere_calibration.md: 2 heaps of 500 and 12 pulls per mu_r;
# results/weir_packing_3d.md: the prism's porosity over 3 seeds)
SPHERES = {0.0: (20.1, 3.54, 3.11, 4.95), 0.2: (29.9, 2.99, 2.51, 4.89)}
SPHERE_POROSITY = 0.515


WIDTH = [0.5]  # the flume's width B [m] (--width), set in main before the jobs start


def scene(mu_r, width=None):
    sc = load_scene(SCENE)
    sc.flume.width = WIDTH[0] if width is None else width
    return cal.with_rolling(sc, mu_r)


def heap_job(args):
    mu_r, seed, n = args
    t = time.process_time()
    r = cal.pour_heap(scene(mu_r), seed, setup=cal.ReposeSetup(n_stones=n, release_interval=0.04,
                                                                settle_time_max=10.0), clumps=c3.ClumpMix())
    return mu_r, r, time.process_time() - t


def _world_spheres(s):
    """(centres (m, 3), radii) of every sub-sphere of a clump system in the world."""
    sph, off = np.asarray(s.clump_sphere), np.asarray(s.clump_offset)
    q = np.asarray(s.stone_quat)
    st = np.repeat(np.arange(s.n), np.diff(off))
    w, x, y, z = (q[st, k] for k in range(4))
    rot = np.stack([np.c_[1 - 2 * (y * y + z * z), 2 * (x * y - w * z), 2 * (x * z + w * y)],
                    np.c_[2 * (x * y + w * z), 1 - 2 * (x * x + z * z), 2 * (y * z - w * x)],
                    np.c_[2 * (x * z - w * y), 2 * (y * z + w * x), 1 - 2 * (x * x + y * y)]], axis=1)
    c = np.einsum("nij,nj->ni", rot, sph[:, :3])
    P, Y = np.asarray(s.stone_pos), np.asarray(s.stone_y)
    return np.c_[P[st, 0] + c[:, 0], Y[st] + c[:, 1], P[st, 1] + c[:, 2]], sph[:, 3]


def core_porosity(s, box, n=40000, seed=0):
    """Void fraction at n random points of the box ((x0, x1), (y0, y1), (z0, z1)) [m]: the weir's interior."""
    c, r = _world_spheres(s)
    pts = np.random.default_rng(seed).uniform([b[0] for b in box], [b[1] for b in box], (n, 3))
    solid = np.zeros(n, bool)
    for k in range(len(r)):
        solid |= np.sum((pts - c[k]) ** 2, axis=1) <= r[k] ** 2
    return 1.0 - solid.mean()


def weir_job(args):
    mu_r, seed, per_seed, hold, width, compaction = args
    t = time.process_time()
    sc = scene(mu_r, width)
    sc.stones.compaction_friction = compaction  # the packing protocol (None: the clumps' own)
    sys_, rep = c3.pack_clump_weir(sc, seed, c3.ClumpMix())
    t_pack = time.process_time() - t
    w = sc.weir
    xm = 0.5 * (w.x_crest_up + w.x_crest_down)
    d = sc.stones.diameter
    core = core_porosity(sys_, [(xm - 0.1, xm + 0.1), (2 * d, sc.flume.width - 2 * d), (1.5 * d, w.height - d)])
    p = sys_.params
    p.flags = int(p.flags | _core.DEM_EXTERNAL_FORCE)
    sys_.params = p
    sys_.stone_wet[:] = 0.0
    state = sys_.export_state()
    dirs = cal.pull_directions(sc)
    rs = []
    for i in cal.pick_evenly(cal.surface_stones(sys_, sc), per_seed):
        for name, e in dirs.items():
            rs.append(cal.pull_stone(sys_, state, i, e, cal.PullSetup(hold_beyond=hold), seed=seed, name=name))
    info = dict(seed=seed, n=rep.n_stones, fixed=rep.n_fixed, porosity=rep.porosity, core=core,
                across=rep.stones_across, outline=rep.outline_error, dt=p.dt, steps=p.contact_steps,
                cpu_pack=t_pack)
    return mu_r, info, rs, time.process_time() - t


def _run(fn, jobs, n_workers):
    if n_workers <= 1:
        return [fn(j) for j in jobs]
    with ProcessPoolExecutor(n_workers) as ex:
        return [f.result() for f in [ex.submit(fn, j) for j in jobs]]


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--mu-r", type=float, nargs="+", default=[0.0])
    ap.add_argument("--stones", type=int, default=500, help="clumps poured per heap")
    ap.add_argument("--weirs", type=int, default=2, help="packed weirs per mu_r for the pulls")
    ap.add_argument("--per-seed", type=int, default=2, help="stones pulled per weir")
    ap.add_argument("--hold", type=float, default=3.0)
    ap.add_argument("--width", type=float, default=0.5, help="flume width B of the packed weirs [m]")
    ap.add_argument("--jobs", type=int, default=1)
    ap.add_argument("--compaction-friction", type=float, default=None,
                    help="stone-stone friction of the weirs' pour rounds [-], in [0, 2] (unset: the clumps' own 0.1)")
    a = ap.parse_args()
    WIDTH[0] = a.width
    t0 = time.process_time()
    jobs = [("heap", (m, 0, a.stones)) for m in a.mu_r] + [
        ("weir", (m, s, a.per_seed, a.hold, a.width, a.compaction_friction)) for m in a.mu_r for s in range(a.weirs)]

    out = _run(_dispatch, jobs, a.jobs)
    heaps = [r for k, r in out if k == "heap"]
    weirs = [r for k, r in out if k == "weir"]
    for m, r, c in heaps:
        print(f"mu_r {m}: heap {r.angle:.1f} deg, at rest {r.settled}, CPU {c:.0f} s", file=sys.stderr)
    cmd = "PYTHONPATH=python python3 benchmarks/clump_calibration.py " + " ".join(sys.argv[1:])
    lines = ["# Calibration of 3D clump stones: angle of repose, pull-out test, packed porosity", "",
             "Scene `scenes/maeno2008_spheres.toml` (d 4.8 cm +- 10 %, 2650 kg/m3, friction 0.577 stone-stone, "
             "0.176 walls, its contact stiffness) with each stone a library clump (`calibration_3d.ClumpMix()`: "
             "pair_2, triangle_3, tetra_4 with equal chances, 1 : 0.8 : 0.6) of its nominal diameter, turned at "
             "random; DEM step 0.9 of the clumps' stable step at the same stiffness (`clump_params`: "
             f"{weirs[0][1]['dt']:.3g} s, {weirs[0][1]['steps']:.1f} steps per contact, against the spheres' "
             "1e-4 s and 20).", "",
             f"Command: `{cmd}` (one run on a machine shared with other jobs; CPU: each job's process time).", "",
             f"Heap: {a.stones} clumps poured as the spheres' (calibration_3d.pour_cone) onto a rough disc of fixed "
             f"clumps. Weirs: `pack_weir` with `WeirSpec.shape = 'clump'` across B = {a.width:g} m (the Maeno trapezoid; "
             + ("the pour's rounds at the clumps' own compaction friction" if a.compaction_friction is None else
                f"the pour's rounds at friction {a.compaction_friction:g}") +
             " (`WeirSpec.compaction_friction`), then the weir's own; "
             "the spheres' across 0.5 m); "
             "porosity of the prism (`weir_porosity_3d_spheres`, 2 mm grid) and of its core (40,000 random "
             "points in x within 0.1 m of the crest's middle, 2 d from the side walls, z from 1.5 d to H - d). "
             f"Pulls: {a.per_seed} surface stones of the downstream slope per weir, 3 directions each, the stones "
             f"farther than {a.hold:g} d held. Spheres: `results/sphere_calibration.md`, "
             "`results/weir_packing_3d.md`.", ""] + c3.heaps_markdown(heaps, lost=True)
    lines += ["", "## Packed weirs", "",
              "| mu_r | seed | stones | fixed | porosity (prism) | porosity (core) | stones across | outline error [m] | "
              "CPU packing [s] | CPU packing + pulls [s] |", "|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|"]
    for m, info, rs, c in weirs:
        lines.append(f"| {m:g} | {info['seed']} | {info['n']} | {info['fixed']} | {info['porosity']:.3f} | "
                     f"{info['core']:.3f} | {info['across']:.2f} | {info['outline']:.3f} | {info['cpu_pack']:.0f} | "
                     f"{c:.0f} |")
    lines += ["", "## Summary against the measurements and the spheres (mean +- sample standard deviation; in "
              "brackets the ratio to the paper)", "",
              "| stones | angle [deg] (37-41) | vertical [N] (2.81) | normal [N] (3.04) | horizontal [N] (4.75) | "
              "horizontal / vertical (1.69) | porosity (0.41) | meets |", "|---|---|---|---|---|---:|---|---|"]
    for m in a.mu_r:
        am = np.mean([r.angle for mm, r, _ in heaps if mm == m])
        rs = [r for mm, _, rr, _ in weirs if mm == m for r in rr]
        pm = {k: cal.mean_spread([r.peak for r in rs if r.direction == k]) for k in cal.PAPER_PULL_N}
        por = np.mean([i["porosity"] for mm, i, _, _ in weirs if mm == m])
        core = np.mean([i["core"] for mm, i, _, _ in weirs if mm == m])
        met = []
        if 37.0 <= am <= 41.0:
            met.append("angle")
        met += [k for k, v in cal.PAPER_PULL_N.items() if abs(pm[k][0] / v - 1.0) <= PULL_TOLERANCE]
        if abs(por - POROSITY) <= POROSITY_TOLERANCE:
            met.append("porosity")
        cells = " | ".join(f"{pm[k][0]:.2f} +- {pm[k][1]:.2f} ({pm[k][0] / v:.2f})" for k, v in cal.PAPER_PULL_N.items())
        lines.append(f"| clumps, mu_r = {m:g} | {am:.1f} | {cells} | {pm['horizontal'][0] / pm['vertical'][0]:.2f} | "
                     f"{por:.3f} (core {core:.3f}) | {', '.join(met) or 'none'} |")
        if m in SPHERES:
            sa, sv, sn, sh = SPHERES[m]
            smet = [k for k, v in zip(cal.PAPER_PULL_N, (sv, sn, sh)) if abs(v / cal.PAPER_PULL_N[k] - 1.0) <= 0.2]
            lines.append(f"| spheres, mu_r = {m:g} | {sa:.1f} | {sv:.2f} | {sn:.2f} | {sh:.2f} | {sh / sv:.2f} | "
                         f"{SPHERE_POROSITY:.3f} | {', '.join(smet) or 'none'} |")
    lines += ["", "## Pulls", ""]
    for m in a.mu_r:
        rs = [r for mm, _, rr, _ in weirs if mm == m for r in rr]
        lines += [f"clumps, mu_r = {m:g}:", "", cal.pull_markdown(rs), ""]
    cpu = sum(c for *_, c in heaps) + sum(c for *_, c in weirs)
    lines.append(f"Total CPU of the script's jobs: {cpu:.0f} s (main process {time.process_time() - t0:.0f} s).")
    with open(os.path.join(HERE, "results", "clump_calibration.md"), "w", encoding="utf-8") as f:
        f.write("\n".join(lines) + "\n")
    print("\n".join(lines))


def _dispatch(job):
    kind, args = job
    return kind, (heap_job(args) if kind == "heap" else weir_job(args))


if __name__ == "__main__":
    main()
