#!/usr/bin/env python3
"""Calibration of the disc stones on the two laboratory experiments of vofdem.calibration, never on the
weir's failure.

1. Dry angle of repose of 300-stone heaps poured from a funnel (3 seeds, --heaps N for more) for rolling friction mu_r on a
   grid (stone-stone and stone-wall alike), with the paper's Coulomb friction (0.577 stone-stone, 0.176
   stone-wall). A heap's angle scatters by several degrees from seed to seed, more than the mean moves
   between neighbouring grid values, so the calibrated mu_r is read from a quadratic least-squares fit of
   every heap's angle against mu_r: where the fit crosses 39 degrees, the middle of quarried stone's 37-41,
   rounded to 0.05. The script picks it, nobody else; if it is off the grid, 3 more heaps measure it.
2. For discs without rolling resistance and for the calibrated mu_r: the submerged angle of repose (3
   seeds) and the paper's pull-out test (5 packed weirs x 2 slope stones, vertical, normal to the slope,
   horizontal), next to the paper's Table 1.
3. Sensitivity: the pull's spring stiffness and anchor speed halved and doubled; the heap's release
   interval.

With --polygons, the polygon stones instead (scenes/maeno2008_polygons.toml, the paper's friction, no
rolling resistance: a polygon's shape is its rolling resistance):

4. A small sweep of the shape parameters, one at a time from the scene's default (vertex counts 4-5 /
   5-8 / 7-9, aspect ratio 1.0 / 1.5 / 2.0, radial jitter 0 / 0.2 / 0.4), then the shape that takes
   every parameter at its best value (if two or more moved): per shape the dry angle of repose (3 heaps) and the
   pull-out test (5 weirs x 2 stones x 3 directions). A shape's miss is the worst of its four relative misses beyond the targets:
   the dry angle's distance outside 37-41 deg over 39 deg, and each pull's |mean / paper - 1| beyond 0.2.
   The best shape (the smallest miss) is picked by the script; its submerged heaps are measured, and it
   is put next to the discs (mu_r = 0 and the calibrated 0.4, rerun here) in one table. Elongated or
   angular shapes whose stable step falls below the scene's DEM step get a shorter step with the same
   contact stiffness (DEM step x contact_steps kept).

usage: PYTHONPATH=python python3 validation/dem_calibration.py [--jobs 2] [--quick] [--polygons]
Writes validation/results/dem_calibration.md, dem_calibration_heap.png and dem_calibration_pull.png;
with --polygons dem_calibration_polygons.md, dem_calibration_polygon_heap.png and
dem_calibration_polygon_pull.png.
--quick: 100-stone heaps, 2 seeds, 2 weirs x 1 stone, a 3-value grid or 2 shapes (a smoke run of the script).
"""
import argparse
import math
import os
import sys
import time
from concurrent.futures import ProcessPoolExecutor

import numpy as np

from vofdem import builder
from vofdem import calibration as cal
from vofdem.scene import Scene, load_scene

HERE = os.path.dirname(os.path.abspath(__file__))
TARGET = 39.0
ROUND = 0.05
# polygon shapes (vertices_min, vertices_max, aspect_ratio, radial_jitter): the scene's default, and the
# values of each parameter tried one at a time from it
POLY_DEFAULT = (5, 8, 1.5, 0.2)
POLY_AXES = {"vertices": [(4, 5), (5, 8), (7, 9)], "aspect_ratio": [1.0, 1.5, 2.0], "radial_jitter": [0.0, 0.2, 0.4]}
PULL_TOLERANCE = 0.2


def stones(model):
    """The scene of a stone model: a number mu_r gives the paper's discs with that rolling friction at
    stone-stone and stone-wall contacts; a tuple (vertices_min, vertices_max, aspect_ratio,
    radial_jitter) gives the polygon scene with that shape."""
    if isinstance(model, tuple):
        return polygon_scene(model)
    return cal.with_rolling(Scene.maeno2008(), model)


def polygon_scene(shape):
    """scenes/maeno2008_polygons.toml with the polygon shape; the DEM step shortened (DEM step x
    contact_steps kept: the same stiffness) if a sample of 300 such stones has a stable step below 1.1 x
    the scene's."""
    s = load_scene(os.path.join(HERE, "..", "scenes", "maeno2008_polygons.toml"))
    st = s.stones
    st.polygon_vertices_min, st.polygon_vertices_max, st.aspect_ratio, st.polygon_radial_jitter = shape
    rng = np.random.default_rng(0)
    d = st.diameter * (1.0 + st.diameter_spread * rng.uniform(-1.0, 1.0, 300))
    sample = builder.stone_system(s, cal.repose_params(s, False, 100.0), np.c_[0.2 * np.arange(300), np.zeros(300)],
                                  d, np.zeros(300, bool), builder.stone_shapes(s, d, 0))
    n = s.numerics
    if sample.stable_dt() < 1.1 * n.dem_dt:
        span = n.dem_dt * n.dem_contact_steps
        steps = math.ceil(1.1 * span / sample.stable_dt())
        n.dem_dt, n.dem_contact_steps = span / steps, float(steps)
    return s.validate()


def heap_job(args):
    mu_r, seed, submerged, setup = args
    return mu_r, cal.pour_heap(stones(mu_r), seed, submerged, setup)


def pull_job(args):
    mu_r, seed, per_seed, setup = args
    return mu_r, cal.pull_test(stones(mu_r), [seed], per_seed, setup=setup)


def pack_job(args):
    """(mu_r, seed, stones, fixed, 2D porosity, outline error [m]) of the scene's weir packed with mu_r."""
    from vofdem.builder import build_stones

    mu_r, seed = args
    _, rep = build_stones(stones(mu_r).replace(seed=seed))
    return mu_r, seed, rep.n_stones, rep.n_fixed, rep.porosity, rep.outline_error


def run_all(pool, fn, jobs):
    return list(pool.map(fn, jobs))


def calibrate(heaps, grid):
    """(mu_r, fit coefficients, standard error of the fit's mean at mu_r [deg]): where a quadratic fit of
    the dry heaps' angles against mu_r crosses TARGET, rounded to ROUND."""
    mu = np.array([m for m, r in heaps if not r.submerged])
    angle = np.array([r.angle for m, r in heaps if not r.submerged])
    coef = np.polyfit(mu, angle, 2)
    xs = np.linspace(min(grid), max(grid), 2001)
    fit = np.polyval(coef, xs)
    x = xs[np.argmin(np.abs(fit - TARGET))]
    mu_cal = round(round(x / ROUND) * ROUND, 4)
    # standard error of the fitted mean at mu_cal, from the residuals
    design = np.vander(mu, 3)
    resid = angle - design @ coef
    cov = np.linalg.inv(design.T @ design) * (resid @ resid) / (len(mu) - 3)
    v = np.vander([mu_cal], 3)[0]
    return mu_cal, coef, float(np.sqrt(v @ cov @ v))


def fmt(values, digits=1):
    m, s, n = cal.mean_spread(values)
    return f"{m:.{digits}f} +- {s:.{digits}f}"


def sweep_table(heaps, grid):
    lines = ["| mu_r | dry angle of repose [deg], mean +- spread | per seed (left / right flank) |", "|---|---|---|"]
    for mu in grid:
        rs = [r for m, r in heaps if m == mu and not r.submerged]
        per = "; ".join(f"{r.seed}: {r.angle:.1f} ({r.left.angle:.1f} / {r.right.angle:.1f})" for r in rs)
        lines.append(f"| {mu:.2f} | {fmt([r.angle for r in rs])} | {per} |")
    return "\n".join(lines)


def pull_summary(pulls, name):
    rs = [r for r in pulls if r.direction == name]
    m, s, n = cal.mean_spread([r.peak for r in rs])
    return m, s, n


def side_by_side(heaps, pulls, models):
    head = "| quantity | measured (target) | " + " | ".join(label for label, _ in models) + " |"
    lines = [head, "|---" * (2 + len(models)) + "|"]

    def row(label, target, cells):
        lines.append(f"| {label} | {target} | " + " | ".join(cells) + " |")

    for sub, label in ((False, "angle of repose, dry [deg]"), (True, "angle of repose, submerged [deg]")):
        cells = []
        for _, mu in models:
            rs = [r for m, r in heaps if m == mu and r.submerged == sub]
            cells.append(f"{fmt([r.angle for r in rs])} ({len(rs)} heaps)" if rs else "-")
        row(label, "37-41 (quarried stone)" if not sub else "-", cells)
    for name, paper in cal.PAPER_PULL_N.items():
        cells = []
        for _, mu in models:
            m, s, n = pull_summary([r for mm, rs in pulls if mm == mu for r in rs], name)
            cells.append(f"{m:.2f} +- {s:.2f} ({m / paper:.2f} of the paper's, {n} pulls)")
        row(f"pull-out force, {name} [N]", f"{paper:.2f}", cells)
    return "\n".join(lines)


def shape_label(shape):
    vmin, vmax, ar, jit = shape
    return f"{vmin}-{vmax} vertices, aspect {ar:g}, jitter {jit:g}"


def misses(heaps, pulls, model):
    """(worst, {target: relative miss beyond it}) of a model: the dry angle's distance outside 37-41 deg
    over 39 deg; each pull direction's |mean / paper - 1| beyond PULL_TOLERANCE."""
    lo, hi = cal.REPOSE_TARGET_DEG
    a = cal.mean_spread([r.angle for m, r in heaps if m == model and not r.submerged])[0]
    out = {"dry angle": max(0.0, lo - a, a - hi) / TARGET}
    for name, paper in cal.PAPER_PULL_N.items():
        m = pull_summary([r for mm, rs in pulls if mm == model for r in rs], name)[0]
        out[f"{name} pull"] = max(0.0, abs(m / paper - 1.0) - PULL_TOLERANCE)
    return max(out.values()), out


def sweep_shapes(pool, seeds, pull_seeds, per_seed, rsetup, psetup, heaps, pulls):
    """One parameter at a time from POLY_DEFAULT, then the shape with every parameter at its best value
    (if two or more differ from the default); heaps and pulls of every shape appended to `heaps` and
    `pulls`. Returns the shapes in the order run."""
    shapes = [POLY_DEFAULT]
    for axis, values in POLY_AXES.items():
        for v in values:
            shape = ((*v, *POLY_DEFAULT[2:]) if axis == "vertices" else
                     POLY_DEFAULT[:2] + ((v, POLY_DEFAULT[3]) if axis == "aspect_ratio" else (POLY_DEFAULT[2], v)))
            if shape not in shapes:
                shapes.append(shape)

    def measure(todo):
        heaps.extend(run_all(pool, heap_job, [(sh, sd, False, rsetup) for sh in todo for sd in seeds]))
        pulls.extend(run_all(pool, pull_job, [(sh, sd, per_seed, psetup) for sh in todo for sd in pull_seeds]))
        for sh in todo:
            print(f"{shape_label(sh)}: miss {misses(heaps, pulls, sh)[0]:.3f}", flush=True)

    measure(shapes)
    # each parameter's best value among its one-at-a-time shapes (the default among them)
    best = {}
    for k, (axis, values) in enumerate(POLY_AXES.items()):
        on_axis = [sh for sh in shapes if all(sh[j] == POLY_DEFAULT[j] for j in range(4) if j not in
                                              ((0, 1) if k == 0 else (k + 1,)))]
        best[axis] = min(on_axis, key=lambda sh: misses(heaps, pulls, sh)[0])
    moved = [k for k, axis in enumerate(POLY_AXES) if best[axis] != POLY_DEFAULT]
    combined = list(POLY_DEFAULT)
    for k in moved:
        src = best[list(POLY_AXES)[k]]
        for j in ((0, 1) if k == 0 else (k + 1,)):
            combined[j] = src[j]
    combos = [tuple(combined)] if len(moved) >= 2 and tuple(combined) not in shapes else []
    shapes += combos
    if combos:
        measure(combos)
    return shapes


def sweep_shape_table(heaps, pulls, shapes):
    lines = ["| shape | DEM step [s] | dry angle [deg] (per seed) | vertical [N] | normal [N] | horizontal [N] | "
             "worst miss |", "|---|---|---|---|---|---|---|"]
    for sh in shapes:
        rs = [r for m, r in heaps if m == sh and not r.submerged]
        per = ", ".join(f"{r.angle:.1f}" for r in rs)
        cells = []
        for name, paper in cal.PAPER_PULL_N.items():
            m, sd, _ = pull_summary([r for mm, ps in pulls if mm == sh for r in ps], name)
            cells.append(f"{m:.2f} +- {sd:.2f} ({m / paper:.2f})")
        worst, each = misses(heaps, pulls, sh)
        which = max(each, key=each.get)
        lines.append(f"| {shape_label(sh)} | {polygon_scene(sh).numerics.dem_dt:.3g} | {fmt([r.angle for r in rs])} "
                     f"({per}) | " + " | ".join(cells) + f" | {100 * worst:.1f} % ({which}) |")
    return "\n".join(lines)


def main_polygons(args):
    """The polygon stones' sweep and the three stone models side by side (see the module's doc)."""
    t0 = time.perf_counter()
    if args.quick:
        seeds, pull_seeds, per_seed, rsetup = [0, 1], [0, 1], 1, cal.ReposeSetup(n_stones=100)
        POLY_AXES.update(vertices=[(5, 8)], aspect_ratio=[1.5, 2.0], radial_jitter=[0.2])
    else:
        seeds, pull_seeds, per_seed, rsetup = [0, 1, 2], [0, 1, 2, 3, 4], 2, cal.ReposeSetup()
    psetup = cal.PullSetup()
    heaps, pulls = [], []
    with ProcessPoolExecutor(max_workers=args.jobs) as pool:
        shapes = sweep_shapes(pool, seeds, pull_seeds, per_seed, rsetup, psetup, heaps, pulls)
        best = min(shapes, key=lambda sh: misses(heaps, pulls, sh)[0])
        print(f"best: {shape_label(best)}", flush=True)
        discs = [0.0, 0.4]
        heaps += run_all(pool, heap_job, [(m, sd, sub, rsetup) for m in discs for sd in seeds for sub in (False, True)])
        heaps += run_all(pool, heap_job, [(best, sd, True, rsetup) for sd in seeds])
        pulls += run_all(pool, pull_job, [(m, sd, per_seed, psetup) for m in discs for sd in pull_seeds])
        packs = run_all(pool, pack_job, [(best, sd) for sd in pull_seeds])
    wall = time.perf_counter() - t0
    res = os.path.join(HERE, "results")
    heap0 = next(r for m, r in heaps if m == best and not r.submerged and r.seed == seeds[0])
    cal.fig_heap(heap0, f"polygons ({shape_label(best)}), dry, seed {heap0.seed}: {heap0.angle:.1f}°").savefig(
        os.path.join(res, "dem_calibration_polygon_heap.png"), dpi=90)
    cal.fig_pull([r for m, rs in pulls if m == best for r in rs],
                 f"pull-out test, polygons ({shape_label(best)}; {len(pull_seeds)} weirs x {per_seed} stones)").savefig(
        os.path.join(res, "dem_calibration_polygon_pull.png"), dpi=90)
    worst, each = misses(heaps, pulls, best)
    models = [("discs, mu_r = 0", 0.0), ("discs, mu_r = 0.4 (calibrated)", 0.4),
              (f"polygons, {shape_label(best)} (best)", best)]
    lines = ["# Calibration of the polygon stones: angle of repose and the paper's pull-out test", "",
             f"`validation/dem_calibration.py --polygons{' --quick' if args.quick else ''}` (vofdem.calibration). "
             "scenes/maeno2008_polygons.toml: friction 0.577 stone-stone and 0.176 stone-wall (the paper's), no "
             "rolling resistance, stones of nominal diameter 4.8 cm +- 10 %, 2650 kg/m3. Heaps and pulls as in "
             f"dem_calibration.md: {rsetup.n_stones} stones poured one every {rsetup.release_interval} s (polygons in "
             f"random orientations), seeds {seeds[0]}-{seeds[-1]}; pulls on weirs of seeds {pull_seeds[0]}-"
             f"{pull_seeds[-1]}, {per_seed} slope stone(s) each. Spread: sample standard deviation; in brackets the "
             f"ratio to the paper's mean. Wall time {wall:.0f} s with {args.jobs} processes.", "",
             "## 1. The shape sweep", "", sweep_shape_table(heaps, pulls, shapes), "",
             "A shape's miss is the worst of: the dry angle's distance outside 37-41 deg over 39 deg, and each pull "
             f"direction's |mean / paper - 1| beyond {PULL_TOLERANCE:g}. The first rows vary one parameter at a time "
             "from the scene's default (5-8 vertices, aspect 1.5, jitter 0.2); the last combines each parameter's "
             "best value.", "",
             f"**Best: {shape_label(best)}**, worst miss {100 * worst:.1f} % ("
             + ", ".join(f"{k} {100 * v:.1f} %" for k, v in each.items()) + ").", "",
             "## 2. The three stone models next to the measurements", "", side_by_side(heaps, pulls, models), "",
             "The pull-out forces are the paper's Table 1 (3D natural stones, dry, mean of ten pulls); the angle of "
             "repose of quarried stone is 37-41 deg (Chow 1959).", "",
             "### Best polygons: heaps", "", cal.repose_markdown([r for m, r in heaps if m == best]), "",
             "### Best polygons: pulls", "", cal.pull_markdown([r for m, rs in pulls if m == best for r in rs]), "",
             "### The weirs the best polygons were pulled on", "",
             "| seed | stones (fixed) | 2D porosity | outline error [cm] |", "|---|---|---|---|"]
    for _, seed, n, nf, por, err in packs:
        lines.append(f"| {seed} | {n} ({nf}) | {por:.3f} | {100 * err:.2f} |")
    lines += ["", "Figures: `dem_calibration_polygon_heap.png` (the best polygons' dry heap of seed 0, its envelope "
              "and fitted flanks), `dem_calibration_polygon_pull.png` (spring force against anchor travel of every "
              "pull of the best polygons, the paper's means dashed)."]
    path = os.path.join(res, "dem_calibration_polygons.md")
    with open(path, "w") as f:
        f.write("\n".join(lines) + "\n")
    print("wrote", path)


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--jobs", type=int, default=2)
    ap.add_argument("--quick", action="store_true")
    ap.add_argument("--polygons", action="store_true", help="the polygon stones' sweep (see above)")
    ap.add_argument("--heaps", type=int, default=None,
                    help="dry heaps per mu_r of the sweep (seeds 0..N-1; default 3, --quick 2): more heaps "
                         "narrow the fit where the angle levels off")
    args = ap.parse_args()
    if args.polygons:
        return main_polygons(args)
    t0 = time.perf_counter()
    if args.quick:
        grid, seeds, pull_seeds, per_seed = [0.0, 0.2, 0.4], [0, 1], [0, 1], 1
        rsetup = cal.ReposeSetup(n_stones=100)
    else:
        grid, seeds, pull_seeds, per_seed = [0.0, 0.1, 0.2, 0.3, 0.4, 0.5, 0.6], [0, 1, 2], [0, 1, 2, 3, 4], 2
        rsetup = cal.ReposeSetup()
    if args.heaps is not None:
        seeds = list(range(args.heaps))
    psetup = cal.PullSetup()
    with ProcessPoolExecutor(max_workers=args.jobs) as pool:
        # 1. the dry sweep and the choice of mu_r
        heaps = run_all(pool, heap_job, [(mu, s, False, rsetup) for mu in grid for s in seeds])
        means = {mu: cal.mean_spread([r.angle for m, r in heaps if m == mu])[0] for mu in grid}
        mu_cal, coef, se = calibrate(heaps, grid)
        print(f"dry sweep: {', '.join(f'{mu}: {a:.1f}' for mu, a in means.items())} -> mu_r = {mu_cal}", flush=True)
        if mu_cal not in grid:
            heaps += run_all(pool, heap_job, [(mu_cal, s, False, rsetup) for s in seeds])
        mu_fit = float(np.polyval(coef, mu_cal))
        dry_cal_mean = cal.mean_spread([r.angle for m, r in heaps if m == mu_cal and not r.submerged])[0]
        models = [("discs, mu_r = 0", 0.0), (f"discs, calibrated mu_r = {mu_cal}", mu_cal)]
        # 2. submerged heaps and pull tests of both models
        heaps += run_all(pool, heap_job, [(mu, s, True, rsetup) for _, mu in models for s in seeds])
        nearby = [mu for mu in grid if 0.0 < abs(mu - mu_cal) <= 0.1 + 1e-9]  # grid values within 0.1
        pulls = run_all(pool, pull_job, [(mu, s, per_seed, psetup) for mu in [m for _, m in models] + nearby
                                         for s in pull_seeds])
        print("pulls done", flush=True)
        # 3. sensitivity of the pull (calibrated stones, the first two weirs) and of the heap's pour rate
        variants = [("spring 50 N/m, 2 cm/s (the test's)", psetup),
                    ("spring 25 N/m", cal.PullSetup(spring=25.0)), ("spring 100 N/m", cal.PullSetup(spring=100.0)),
                    ("speed 1 cm/s", cal.PullSetup(speed=0.01)), ("speed 4 cm/s", cal.PullSetup(speed=0.04))]
        sens = {label: run_all(pool, pull_job, [(mu_cal, s, per_seed, st) for s in pull_seeds[:2]])
                for label, st in variants}
        packs = run_all(pool, pack_job, [(mu, s) for _, mu in models for s in pull_seeds])
        rates = [0.1, 0.25]
        rate_heaps = {r: run_all(pool, heap_job, [(mu_cal, s, False, cal.ReposeSetup(
            n_stones=rsetup.n_stones, release_interval=r)) for s in seeds]) for r in rates}
    wall = time.perf_counter() - t0

    # figures: the calibrated dry heap of seed 0 and the calibrated pulls
    res = os.path.join(HERE, "results")
    os.makedirs(res, exist_ok=True)
    heap0 = next(r for m, r in heaps if m == mu_cal and not r.submerged and r.seed == seeds[0])
    cal.fig_heap(heap0, f"discs with rolling friction mu_r = {mu_cal}, dry, seed {heap0.seed}: "
                        f"{heap0.angle:.1f}°").savefig(os.path.join(res, "dem_calibration_heap.png"), dpi=90)
    pulls_cal = [r for m, rs in pulls if m == mu_cal for r in rs]
    cal.fig_pull(pulls_cal, f"pull-out test, discs with mu_r = {mu_cal} ({len(pull_seeds)} weirs x {per_seed} "
                            "stones)").savefig(os.path.join(res, "dem_calibration_pull.png"), dpi=90)

    lines = ["# Calibration of the disc stones: angle of repose and the paper's pull-out test", "",
             f"`validation/dem_calibration.py{' --quick' if args.quick else ''}"
             f"{f' --heaps {args.heaps}' if args.heaps is not None else ''}` (vofdem.calibration). Friction "
             "0.577 stone-stone and 0.176 stone-wall (the paper's) throughout; rolling friction mu_r at stone-stone "
             "and stone-wall contacts alike, rolling damping 0.3; stones 4.8 cm +- 10 %, 2650 kg/m3, DEM step "
             f"1e-4 s (20 steps per contact) without rolling friction, {1e-4 * 20 / cal.ROLLING_CONTACT_STEPS:.3g} s "
             f"({cal.ROLLING_CONTACT_STEPS:g} steps per contact, the same stiffness) with it. Heaps: {rsetup.n_stones} stones poured one every {rsetup.release_interval} s from a funnel "
             f"{rsetup.drop_height} d above the heap's top onto a row of fixed stones, flanks fitted between "
             f"{rsetup.fit_low} and {rsetup.fit_high} of the height. Pulls: spring {psetup.spring} N/m, anchor "
             f"{psetup.speed * 100:.0f} cm/s, weirs of seeds {pull_seeds[0]}-{pull_seeds[-1]}, {per_seed} slope "
             f"stone(s) each (centres between {psetup.z_low} and {psetup.z_high} of the height, nothing outward "
             f"of them). Spread: sample standard deviation. Wall time {wall:.0f} s with {args.jobs} processes.", "",
             "## 1. Dry angle of repose against mu_r", "", sweep_table(heaps, grid), "",
             f"Quadratic least-squares fit of the {len(grid) * len(seeds)} heaps' angles: angle = "
             f"{coef[0]:.1f} mu_r^2 + {coef[1]:.1f} mu_r + {coef[2]:.1f} deg; it crosses {TARGET:.0f} deg at "
             f"**mu_r = {mu_cal}** (rounded to {ROUND}), where the fit gives {mu_fit:.1f} +- {se:.1f} deg (standard "
             f"error of the fitted mean) and the heaps of mu_r = {mu_cal} measure {dry_cal_mean:.1f} deg, "
             f"{'inside' if 37.0 <= dry_cal_mean <= 41.0 else 'outside'} 37-41 deg.", "",
             "## 2. Both models next to the measurements", "", side_by_side(heaps, pulls, models), "",
             "The pull-out forces are the paper's Table 1 (3D natural stones, dry, mean of ten pulls); the angle of "
             "repose of quarried stone is 37-41 deg (Chow 1959).", ""]
    for label, mu in models:
        lines += [f"### {label}: heaps", "", cal.repose_markdown([r for m, r in heaps if m == mu]), "",
                  f"### {label}: pulls", "", cal.pull_markdown([r for m, rs in pulls if m == mu for r in rs]), ""]
    lines += [f"### Pull-out forces of the grid's neighbours of mu_r = {mu_cal}", "",
              "| mu_r | dry angle [deg] | vertical [N] | normal [N] | horizontal [N] |", "|---|---|---|---|---|"]
    for mu in sorted(nearby + [mu_cal]):
        cells = [fmt([r.peak for mm, rs in pulls if mm == mu for r in rs if r.direction == n], 2)
                 for n in cal.PAPER_PULL_N]
        lines.append(f"| {mu} | {fmt([r.angle for m, r in heaps if m == mu and not r.submerged])} | "
                     + " | ".join(cells) + " |")
    lines += ["", "### The weirs the pulls were made on (pack_weir with each model's stones)", "",
              "| mu_r | seed | stones (fixed) | 2D porosity | outline error [cm] |", "|---|---|---|---|---|"]
    for mu, seed, n, nf, por, err in packs:
        lines.append(f"| {mu} | {seed} | {n} ({nf}) | {por:.3f} | {100 * err:.2f} |")
    lines += ["", "## 3. Sensitivity", "",
              f"Pull of the calibrated stones (weirs {pull_seeds[0]}-{pull_seeds[min(1, len(pull_seeds) - 1)]}, "
              f"{per_seed} stone(s) each), mean peak force [N] per direction:", "",
              "| pull | vertical | normal | horizontal | largest change from the test's settings |",
              "|---|---|---|---|---|"]
    base = {n: pull_summary([r for _, rs in sens[variants[0][0]] for r in rs], n)[0] for n in cal.PAPER_PULL_N}
    for label, _ in variants:
        ms = {n: pull_summary([r for _, rs in sens[label] for r in rs], n)[0] for n in cal.PAPER_PULL_N}
        change = max(abs(ms[n] / base[n] - 1.0) for n in ms)
        lines.append(f"| {label} | {ms['vertical']:.2f} | {ms['normal']:.2f} | {ms['horizontal']:.2f} | "
                     f"{100 * change:.1f} % |")
    dry_cal = [r.angle for m, r in heaps if m == mu_cal and not r.submerged]
    lines += ["", f"Dry heaps of the calibrated stones against the funnel's release interval ({len(seeds)} seeds):",
              "", "| release interval [s] | angle of repose [deg] |", "|---|---|",
              f"| {rsetup.release_interval} (the test's) | {fmt(dry_cal)} |"]
    for r in rates:
        lines.append(f"| {r} | {fmt([h.angle for _, h in rate_heaps[r]])} |")
    lines += ["", "Figures: `dem_calibration_heap.png` (a calibrated dry heap, its envelope and fitted flanks), "
              "`dem_calibration_pull.png` (spring force against anchor travel of every calibrated pull, the paper's "
              "means dashed)."]
    path = os.path.join(res, "dem_calibration.md")
    with open(path, "w") as f:
        f.write("\n".join(lines) + "\n")
    print("wrote", path)


if __name__ == "__main__":
    sys.exit(main())
