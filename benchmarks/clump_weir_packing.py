#!/usr/bin/env python3
"""The Maeno weir packed with clumps (weir_packing_3d.h, clump_packing.cpp): porosity and outline over seeds.

--size maeno (default): the scene scenes/maeno2008_spheres.toml (H 0.25 m, crest 0.20 m, slopes 27 deg, d 4.8
cm +- 10 %, friction 0.577 / 0.176, its contact stiffness), dry, with each stone a clump of the default mix
(pair_2 / triangle_3 / tetra_4, 1 : 0.8 : 0.6) packed by calibration_3d.pack_clump_weir across B (--width) for
each seed: stones, fixed, the porosity of the trapezoid's prism (weir_porosity_3d_spheres), that of its core
(random points within 0.1 m of the crest's middle, 2 d from the side walls, z from 1.5 d to H - d:
clump_calibration's), the outline error (in m and in mean diameters) and the packing's CPU time
(time.process_time, one thread). --size small: the C++ tests' weir (test_clump_packing.cpp: H 8 cm, crest 6
cm, d 2 cm, B 0.1 m), its core the crest's length, d from the side walls, z from d to H - d.
--compaction-friction: the stone-stone friction of the pour's rounds (WeirSpec.compaction_friction, the scene's
stones.compaction_friction; unset: the clumps' own 0.1), the packing protocol's knob.

Each run writes (or replaces) its own section, named by --label, of benchmarks/results/clump_weir_packing.md,
so that the packing protocols before and after a change stand side by side.

usage: PYTHONPATH=python python3 benchmarks/clump_weir_packing.py --label NAME [--size maeno|small] [--width 0.3]
       [--seeds 0 1 2 3 4] [--compaction-friction F]
"""
import argparse
import os
import re
import sys
import time

os.environ.setdefault("OMP_NUM_THREADS", "1")  # the process's CPU time is the solver's alone

import numpy as np  # noqa: E402

from vofdem import _core  # noqa: E402
from vofdem import calibration_3d as c3  # noqa: E402
from vofdem.scene import load_scene  # noqa: E402

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)
from clump_calibration import core_porosity  # noqa: E402

SCENE = os.path.join(HERE, "..", "scenes", "maeno2008_spheres.toml")
OUT = os.path.join(HERE, "results", "clump_weir_packing.md")
N_EXPERIMENT = 0.41


def pack_small(width, seed, compaction):
    """(system, report, core box): the C++ tests' small weir (test_clump_packing.cpp: H 8 cm, crest 6 cm,
    27 deg, d 2 cm +- 10 %, the contact law's defaults at 5e-5 s in 80 steps per contact)."""
    spec = _core.WeirSpec()
    spec.height, spec.crest, spec.d_mean, spec.density, spec.shape, spec.seed = 0.08, 0.06, 0.02, 2650.0, "clump", seed
    spec.settle_time_max = 6.0
    spec.compaction_friction = -1.0 if compaction is None else compaction
    p = _core.DEMParams()
    p.width, p.dt, p.contact_steps = width, 5e-5, 80.0
    system, rep = _core.pack_weir(spec, p)
    xm, d = spec.x_toe + 0.5 * (spec.x_end() - spec.x_toe), spec.d_mean
    return system, rep, d, [(xm - 0.5 * spec.crest, xm + 0.5 * spec.crest), (d, width - d), (d, spec.height - d)]


def pack_maeno(width, seed, compaction):
    sc = load_scene(SCENE)
    sc.flume.width = width
    sc.stones.compaction_friction = compaction
    system, rep = c3.pack_clump_weir(sc, seed, c3.ClumpMix())
    w, d = sc.weir, sc.stones.diameter
    xm = 0.5 * (w.x_crest_up + w.x_crest_down)
    return system, rep, d, [(xm - 0.1, xm + 0.1), (2 * d, width - 2 * d), (1.5 * d, w.height - d)]


def pack(size, width, seed, compaction=None):
    t0 = time.process_time()
    system, rep, d, box = (pack_small if size == "small" else pack_maeno)(width, seed, compaction)
    cpu = time.process_time() - t0
    core = core_porosity(system, box)
    row = dict(seed=seed, n=rep.n_stones, fixed=rep.n_fixed, porosity=rep.porosity, core=core,
               across=rep.stones_across, outline=rep.outline_error, outline_d=rep.outline_error / d,
               speed=rep.max_speed, cpu=cpu)
    print(row, flush=True)
    return row


def section(label, size, width, seeds, rows, compaction=None):
    knob = "" if compaction is None else f" --compaction-friction {compaction:g}"
    head = (f"## {label}\n\nCommand: `PYTHONPATH=python python3 benchmarks/clump_weir_packing.py --label "
            f"\"{label}\" --size {size} --width {width:g} --seeds {' '.join(str(s) for s in seeds)}{knob}`\n\n"
            "| seed | stones | fixed | porosity (prism) | porosity (core) | stones across | outline error [m] | "
            "outline error [d] | max speed [m/s] | CPU [s] |\n|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|\n")
    body = "".join(f"| {r['seed']} | {r['n']} | {r['fixed']} | {r['porosity']:.3f} | {r['core']:.3f} | "
                   f"{r['across']:.2f} | {r['outline']:.4f} | {r['outline_d']:.2f} | {r['speed']:.1e} | "
                   f"{r['cpu']:.0f} |\n" for r in rows)
    mean = {k: np.mean([r[k] for r in rows]) for k in ("porosity", "core", "outline_d")}
    worst = max(r["outline_d"] for r in rows)
    tail = (f"\nMean over {len(rows)} seeds: porosity {mean['porosity']:.3f} (prism), {mean['core']:.3f} (core) "
            f"against the experiment's {N_EXPERIMENT}; outline error {mean['outline_d']:.2f} d (largest "
            f"{worst:.2f} d).\n")
    return head + body + tail


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--label", required=True, help="the section's title (the packing protocol measured)")
    ap.add_argument("--size", choices=("maeno", "small"), default="maeno",
                    help="the Maeno weir of the sphere scene, or the C++ tests' small weir")
    ap.add_argument("--width", type=float, default=0.3, help="flume width B [m] (the small weir's tests: 0.1)")
    ap.add_argument("--seeds", type=int, nargs="+", default=[0, 1, 2, 3, 4])
    ap.add_argument("--compaction-friction", type=float, default=None,
                    help="stone-stone friction of the pour's rounds [-], in [0, 2] (unset: the clumps' own 0.1)")
    a = ap.parse_args()
    rows = [pack(a.size, a.width, s, a.compaction_friction) for s in a.seeds]
    new = section(a.label, a.size, a.width, a.seeds, rows, a.compaction_friction)
    about = __doc__.split("\n\n")[1].replace("\n", " ")
    title = f"# The Maeno weir packed with clumps: porosity and outline\n\n{about}\n\n"
    old = open(OUT).read() if os.path.exists(OUT) else title
    parts = re.split(r"(?m)^(?=## )", old)
    kept = [p for p in parts[1:] if not p.startswith(f"## {a.label}\n")]
    with open(OUT, "w") as f:
        f.write(parts[0] + "".join(kept) + ("\n" if kept and not kept[-1].endswith("\n\n") else "") + new)
    print(new)


if __name__ == "__main__":
    main()
