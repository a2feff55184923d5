#!/usr/bin/env python3
"""Calibration of the 3D sphere stones (scenes/maeno2008_spheres.toml) on the two laboratory experiments of
vofdem.calibration, never on the weir's failure, for rolling friction mu_r on a grid (stone-stone and
stone-wall alike, with the paper's Coulomb friction 0.577 / 0.176):

1. Dry angle of repose of 3D heaps (calibration_3d.pour_cone: spheres poured from a funnel onto a rough
   disc of fixed spheres, no side walls near, the cone fitted on its surface stones' tops against their
   distance from the axis), against quarried stone's 37-41 deg.
2. The paper's pull-out test (Fig. 5, Table 1: 2.81 / 3.04 / 4.75 N vertical / normal / horizontal) on
   the 3D-packed weir across the flume's 0.5 m: surface stones of the downstream slope at least 1.5 d
   from the side walls, pulled in x-z (nothing across the width), and the horizontal / vertical ratio
   (the paper's 1.69).

A mu_r meets the measurements if its mean angle lies in 37-41 deg and each pull's mean is within 20 % of
the paper's (the 2D study's criterion). The script reports which, if any; it changes no scene.

usage: PYTHONPATH=python python3 benchmarks/sphere_calibration.py [--mu-r 0 0.1 0.2 0.4] [--seeds 3]
       [--stones 500] [--weirs 3] [--per-seed 2] [--hold 3] [--jobs 1]
Writes benchmarks/results/sphere_calibration.md, sphere_calibration_heap.png and sphere_calibration_pull.png.
--check-hold 3: only the pulls of two stones with every stone free and with the stones beyond 3 d held
(sphere_calibration_hold.md): what PullSetup.hold_beyond changes.
CPU times are each job's own process time (time.process_time), not wall-clock.
"""
import argparse
import os
import sys
import time
from concurrent.futures import ProcessPoolExecutor

import numpy as np

from vofdem import calibration as cal
from vofdem import calibration_3d as c3
from vofdem.scene import load_scene

HERE = os.path.dirname(os.path.abspath(__file__))
SCENE = os.path.join(HERE, "..", "scenes", "maeno2008_spheres.toml")
PULL_TOLERANCE = 0.2


def scene(mu_r):
    return cal.with_rolling(load_scene(SCENE), mu_r)


def heap_job(args):
    mu_r, seed, n = args
    t = time.process_time()
    r = cal.pour_heap(scene(mu_r), seed, setup=cal.ReposeSetup(n_stones=n, release_interval=0.04,
                                                                settle_time_max=10.0))
    return mu_r, r, time.process_time() - t


def pull_job(args):
    mu_r, seed, per_seed, hold = args
    t = time.process_time()
    rs = cal.pull_test(scene(mu_r), [seed], per_seed, setup=cal.PullSetup(hold_beyond=hold))
    return mu_r, rs, time.process_time() - t


def _run(fn, jobs, n_workers):
    if n_workers <= 1:
        return [fn(j) for j in jobs]
    with ProcessPoolExecutor(n_workers) as ex:
        return list(ex.map(fn, jobs))


def pull_means(rs):
    return {name: cal.mean_spread([r.peak for r in rs if r.direction == name]) for name in cal.PAPER_PULL_N}


def check_hold(hold):
    """The same stones pulled with every stone free and with those beyond `hold` d held: what holding costs."""
    sc = scene(0.0)
    sys_, state = cal.pull_weir(sc, 0)
    dirs = cal.pull_directions(sc)
    lines = ["# Pulls of 3D spheres with the far stones held", "",
             "Command: `PYTHONPATH=python python3 benchmarks/sphere_calibration.py --check-hold " + f"{hold:g}`", "",
             f"Weir of spheres packed from seed 0 (`scenes/maeno2008_spheres.toml`, mu_r = 0), two surface stones of "
             f"its downstream slope pulled from the same packed state with every stone free and with the stones "
             f"farther than {hold:g} d from the pulled one held fixed (`PullSetup.hold_beyond`). CPU: process time.", "",
             "| stone | direction | peak, all free [N] | peak, held [N] | difference | CPU free [s] | CPU held [s] |",
             "|---:|---|---:|---:|---:|---:|---:|"]
    for i in cal.pick_evenly(cal.surface_stones(sys_, sc), 2):
        for name, e in dirs.items():
            out = []
            for h in (0.0, hold):
                t = time.process_time()
                r = cal.pull_stone(sys_, state, i, e, cal.PullSetup(hold_beyond=h))
                out.append((r.peak, time.process_time() - t))
            lines.append(f"| {i} | {name} | {out[0][0]:.3f} | {out[1][0]:.3f} | {out[1][0] / out[0][0] - 1.0:+.1%} | "
                         f"{out[0][1]:.1f} | {out[1][1]:.1f} |")
    with open(os.path.join(HERE, "results", "sphere_calibration_hold.md"), "w", encoding="utf-8") as f:
        f.write("\n".join(lines) + "\n")
    print("\n".join(lines))


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--check-hold", type=float, default=None, metavar="HOLD",
                    help="only compare pulls with every stone free and with those beyond HOLD d held "
                         "(writes results/sphere_calibration_hold.md)")
    ap.add_argument("--mu-r", type=float, nargs="+", default=[0.0, 0.1, 0.2, 0.4])
    ap.add_argument("--seeds", type=int, default=3, help="heaps per mu_r")
    ap.add_argument("--stones", type=int, default=500, help="spheres poured per heap")
    ap.add_argument("--weirs", type=int, default=3, help="packed weirs per mu_r for the pulls")
    ap.add_argument("--per-seed", type=int, default=2, help="stones pulled per weir")
    ap.add_argument("--hold", type=float, default=3.0,
                    help="stones farther than this many d from the pulled one are held during a pull (0: none)")
    ap.add_argument("--jobs", type=int, default=1)
    a = ap.parse_args()
    if a.check_hold is not None:
        return check_hold(a.check_hold)
    t0 = time.process_time()
    heaps = _run(heap_job, [(m, s, a.stones) for m in a.mu_r for s in range(a.seeds)], a.jobs)
    for m, r, c in heaps:
        print(f"mu_r {m}: heap seed {r.seed}: {r.angle:.1f} deg ({r.left.angle:.1f} / {r.right.angle:.1f}), "
              f"at rest {r.settled}, CPU {c:.0f} s", file=sys.stderr, flush=True)
    pulls = _run(pull_job, [(m, s, a.per_seed, a.hold) for m in a.mu_r for s in range(a.weirs)], a.jobs)
    cmd = "PYTHONPATH=python python3 benchmarks/sphere_calibration.py " + " ".join(sys.argv[1:])
    lines = ["# Calibration of the 3D spheres: angle of repose and pull-out test", "",
             "Scene `scenes/maeno2008_spheres.toml` (spheres d 4.8 cm +- 10 %, 2650 kg/m3, friction 0.577 "
             "stone-stone, 0.176 walls, DEM step 1e-4 s; with mu_r > 0 32 steps per contact at the same "
             "stiffness), rolling friction mu_r stone-stone and stone-wall alike (`calibration.with_rolling`).", "",
             f"Command: `{cmd}`", "",
             f"Heaps: {a.stones} spheres poured from a funnel (one every 0.04 s, 1 d above the heap's top, "
             "within d/4 of the axis) onto a rough disc of fixed spheres on a triangular lattice, no wall "
             "within the cone at 20 deg; angle: straight-line fit of the surface stones' tops (highest per "
             "plan cell d wide) against their distance from the axis between 0.2 and 0.8 of the heap's "
             "height; halves: the same fit on x < axis and x > axis. Pulls: `calibration.pull_test` on the "
             "3D-packed weir (B = 0.5 m), surface stones of the downstream slope between 0.2 and 0.8 of "
             "the weir's height and at least 1.5 d from the side walls, spring 50 N/m, anchor 0.02 m/s, "
             f"directions in x-z, the stones farther than {a.hold:g} d from the pulled one held fixed during "
             "its pull (0: none). CPU: each job's process time.", ""] + c3.heaps_markdown(heaps)
    lines += ["", "## Summary per mu_r (mean +- sample standard deviation; in brackets the ratio to the paper)", "",
              "| mu_r | angle [deg] (37-41) | vertical [N] (2.81) | normal [N] (3.04) | horizontal [N] (4.75) | "
              "horizontal / vertical (1.69) | pulls | meets all |", "|---:|---|---|---|---|---:|---:|---|"]
    verdict = []
    for m in a.mu_r:
        am, asd, an = cal.mean_spread([r.angle for mm, r, _ in heaps if mm == m])
        rs = [r for mm, rr, _ in pulls if mm == m for r in rr]
        pm = pull_means(rs)
        ok_a = 37.0 <= am <= 41.0
        ok_p = all(abs(pm[k][0] / v - 1.0) <= PULL_TOLERANCE for k, v in cal.PAPER_PULL_N.items())
        verdict.append((m, ok_a and ok_p, am))
        cells = " | ".join(f"{pm[k][0]:.2f} +- {pm[k][1]:.2f} ({pm[k][0] / v:.2f})" for k, v in cal.PAPER_PULL_N.items())
        lines.append(f"| {m:g} | {am:.1f} +- {asd:.1f} ({an}) | {cells} | "
                     f"{pm['horizontal'][0] / pm['vertical'][0]:.2f} | {len(rs)} | {'yes' if ok_a and ok_p else 'no'} |")
    lines += ["", "## Pulls per mu_r", ""]
    for m in a.mu_r:
        rs = [r for mm, rr, _ in pulls if mm == m for r in rr]
        cpu = sum(c for mm, _, c in pulls if mm == m)
        lines += [f"mu_r = {m:g} (CPU {cpu:.0f} s for the weirs' packing and pulls):", "", cal.pull_markdown(rs), ""]
    good = [m for m, ok, _ in verdict if ok]
    lines += ["## Verdict (written by the script)", "",
              (f"mu_r meeting the angle of repose and the three pulls: {', '.join(f'{m:g}' for m in good)}."
               if good else "No mu_r of the grid meets the angle of repose and the three pulls together."), ""]
    lines.append(f"Total CPU of the script's jobs: {sum(c for *_, c in heaps) + sum(c for *_, c in pulls):.0f} s "
                 f"(main process {time.process_time() - t0:.0f} s).")
    res = os.path.join(HERE, "results")
    with open(os.path.join(res, "sphere_calibration.md"), "w", encoding="utf-8") as f:
        f.write("\n".join(lines) + "\n")
    # figures: the heap of the largest mu_r, a pull of its first weir
    m_fig = max(a.mu_r)
    h = next(r for mm, r, _ in heaps if mm == m_fig)
    cal.fig_heap(h).savefig(os.path.join(res, "sphere_calibration_heap.png"), dpi=90)
    sc = scene(m_fig)
    sys_, state = cal.pull_weir(sc, 0)
    i = cal.pick_evenly(cal.surface_stones(sys_, sc), a.per_seed)[0]
    fig = cal.fig_pull([r for mm, rr, _ in pulls if mm == m_fig for r in rr],
                       f"pull-out test of 3D spheres, mu_r = {m_fig:g}")
    side = c3.fig_pull_3d(sys_, state, i, sc, cal.pull_directions(sc)["horizontal"])
    _stack(fig, side, os.path.join(res, "sphere_calibration_pull.png"))
    print("\n".join(lines))


def _stack(top, bottom, path):
    """Two figures one above the other in one PNG."""
    import io

    from matplotlib.figure import Figure
    from matplotlib.image import imread

    imgs = []
    for f in (top, bottom):
        buf = io.BytesIO()
        f.savefig(buf, format="png", dpi=90)
        buf.seek(0)
        imgs.append(imread(buf))
    w = max(i.shape[1] for i in imgs)
    pad = [np.pad(i, ((0, 0), (0, w - i.shape[1]), (0, 0)), constant_values=1.0) for i in imgs]
    both = np.concatenate(pad, axis=0)
    fig = Figure(figsize=(w / 90, both.shape[0] / 90))
    ax = fig.add_axes([0, 0, 1, 1])
    ax.imshow(both)
    ax.axis("off")
    fig.savefig(path, dpi=90)


if __name__ == "__main__":
    main()
