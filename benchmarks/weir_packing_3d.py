#!/usr/bin/env python3
"""The Maeno weir packed with 3D spheres (weir_packing_3d.h), and the quick Maeno scene run with spheres.

Packing: the scene scenes/maeno2008.toml (H 0.25 m, crest 0.20 m, slopes 27 deg, d 4.8 cm +- 10 %, the
scene's contact law, dry) with stones.shape = 'sphere' across the flume width B (--width, default the
scene's 0.5 m), packed for each seed by the scene's own route (builder.build_stones -> pack_weir): stones,
fixed, the porosity of the trapezoid's prism (1 - stone volume inside / (area B)) against the experiment's
0.41, the mean number of stones a line across the flume crosses, the outline error, the simulated settling
time and the packing's CPU time (time.process_time of the process, one solver thread).

The quick scene's run with spheres (scenes/maeno2008_spheres.toml --quick) against discs is measured
with the CLI under /usr/bin/time (the commands are in the results file), its rows added there by hand.

usage: PYTHONPATH=python python3 benchmarks/weir_packing_3d.py [--width 0.5] [--seeds 0 1 2]
Writes benchmarks/results/weir_packing_3d.md.
"""
import argparse
import os
import time

os.environ.setdefault("OMP_NUM_THREADS", "1")  # the process's CPU time is the solver's alone
os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")

import vofdem  # noqa: E402
from vofdem import builder  # noqa: E402

HERE = os.path.dirname(os.path.abspath(__file__))
SCENE = os.path.join(HERE, "..", "scenes", "maeno2008.toml")
N_EXPERIMENT = 0.41


def sphere_scene(width, seed):
    s = vofdem.load_scene(SCENE).with_value("stones.shape", "sphere").with_value("flume.width", width)
    s.seed = seed
    return s.validate()


def pack(width, seed):
    scene = sphere_scene(width, seed)
    t0 = time.process_time()
    system, report = builder.build_stones(scene)
    cpu = time.process_time() - t0
    print(f"seed {seed}: {report!r}, CPU {cpu:.1f} s", flush=True)
    return {"seed": seed, "stones": report.n_stones, "fixed": report.n_fixed, "porosity": report.porosity,
            "across": report.stones_across, "outline": report.outline_error, "settle": report.settle_time,
            "max_speed": report.max_speed, "cpu": cpu, "n": system.n}


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--width", type=float, default=0.5, help="flume width B [m]")
    ap.add_argument("--seeds", type=int, nargs="+", default=[0, 1, 2])
    a = ap.parse_args()

    rows = [pack(a.width, seed) for seed in a.seeds]
    out = ["# Weir of 3D spheres packed as the laboratory built it", "",
           f"Maeno weir (H 0.25 m, crest 0.20 m, 27 deg, d 4.8 cm +- 10 %) of spheres across B = {a.width:g} m, "
           "packed by `pack_weir` (weir_packing_3d.h) from the scene `scenes/maeno2008.toml` with "
           "`stones.shape = 'sphere'`; CPU time of the process (`time.process_time`, one thread).", "",
           f"Command: `PYTHONPATH=python python3 benchmarks/weir_packing_3d.py --width {a.width:g} --seeds "
           + " ".join(str(s) for s in a.seeds) + "`", "",
           "| seed | stones | fixed | porosity (3D prism) | vs 0.41 | stones across B | outline error [m] | "
           "settle [s simulated] | max speed [m/s] | CPU [s] |",
           "|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|"]
    for r in rows:
        out.append(f"| {r['seed']} | {r['stones']} | {r['fixed']} | {r['porosity']:.4f} | "
                   f"{r['porosity'] - N_EXPERIMENT:+.4f} | {r['across']:.2f} | {r['outline']:.4f} | {r['settle']:.2f} | "
                   f"{r['max_speed']:.1e} | {r['cpu']:.1f} |")
    mean = sum(r["porosity"] for r in rows) / len(rows)
    out += ["", f"Mean porosity {mean:.4f} against the experiment's {N_EXPERIMENT} ({mean - N_EXPERIMENT:+.4f})."]
    out += ["", "## The quick scene with spheres", "",
            "Measured by the CLI, not by this script (a run of the quick scene takes minutes): "
            "`/usr/bin/time -f '%U %S' vofdem run scenes/maeno2008_spheres.toml --quick --threads 1 --no-figures "
            "--no-animation --no-progress` against the same with scenes/maeno2008.toml (discs); the CPU time "
            "(user + sys) of each, packing included."]
    path = os.path.join(HERE, "results", "weir_packing_3d.md")
    with open(path, "w") as f:
        f.write("\n".join(out) + "\n")
    print("\n".join(out))


if __name__ == "__main__":
    main()
