#!/usr/bin/env python3
"""The Maeno weir packed with 3D spheres (weir_packing_3d.h), and the quick Maeno scene run with spheres.

Packing: the scene scenes/maeno2008.toml (H 0.25 m, crest 0.20 m, slopes 27 deg, d 4.8 cm +- 10 %, the
scene's contact law, dry) with stones.shape = 'sphere' across the flume width B (--width, default the
scene's 0.5 m), packed for each seed by the scene's own route (builder.build_stones -> pack_weir): stones,
fixed, the porosity of the trapezoid's prism (1 - stone volume inside / (area B)) against the experiment's
0.41, the mean number of stones a line across the flume crosses, the outline error, the simulated settling
time and the packing's CPU time (time.process_time of the process, one solver thread).

Run: the quick scene (Scene.quick) with discs and with spheres (the sphere weir at the same B) to its
end, one after the other in this process: whether it ran to its end, and the CPU time of each, packing
included, with their ratio.

usage: PYTHONPATH=python python3 benchmarks/weir_packing_3d.py [--width 0.5] [--seeds 0 1 2] [--no-run]
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
    return s.with_value("seed", seed).validate()


def pack(width, seed):
    scene = sphere_scene(width, seed)
    t0 = time.process_time()
    system, report = builder.build_stones(scene)
    cpu = time.process_time() - t0
    return {"seed": seed, "stones": report.n_stones, "fixed": report.n_fixed, "porosity": report.porosity,
            "across": report.stones_across, "outline": report.outline_error, "settle": report.settle_time,
            "max_speed": report.max_speed, "cpu": cpu, "n": system.n}


def run(scene):
    import tempfile

    from vofdem.run import run_scene

    t0 = time.process_time()
    try:
        with tempfile.TemporaryDirectory() as out:
            result = run_scene(scene, out, progress=False, figures=False, animation=False, log=lambda *a, **k: None)
        ok, why = True, ""
    except Exception as e:  # the table says why a run stopped
        result, ok, why = None, False, f"{type(e).__name__}: {e}"[:200]
    return {"ok": ok, "why": why, "cpu": time.process_time() - t0, "result": result}


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--width", type=float, default=0.5, help="flume width B [m]")
    ap.add_argument("--seeds", type=int, nargs="+", default=[0, 1, 2])
    ap.add_argument("--no-run", action="store_true", help="the packings alone")
    a = ap.parse_args()

    rows = [pack(a.width, seed) for seed in a.seeds]
    out = ["# Weir of 3D spheres packed as the laboratory built it", "",
           f"Maeno weir (H 0.25 m, crest 0.20 m, 27 deg, d 4.8 cm +- 10 %) of spheres across B = {a.width:g} m, "
           "packed by `pack_weir` (weir_packing_3d.h) from the scene `scenes/maeno2008.toml` with "
           "`stones.shape = 'sphere'`; CPU time of the process (`time.process_time`, one thread).", "",
           f"Command: `PYTHONPATH=python python3 benchmarks/weir_packing_3d.py --width {a.width:g} --seeds "
           + " ".join(str(s) for s in a.seeds) + (" --no-run" if a.no_run else "") + "`", "",
           "| seed | stones | fixed | porosity (3D prism) | vs 0.41 | stones across B | outline error [m] | "
           "settle [s simulated] | max speed [m/s] | CPU [s] |",
           "|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|"]
    for r in rows:
        out.append(f"| {r['seed']} | {r['stones']} | {r['fixed']} | {r['porosity']:.4f} | "
                   f"{r['porosity'] - N_EXPERIMENT:+.4f} | {r['across']:.2f} | {r['outline']:.4f} | {r['settle']:.2f} | "
                   f"{r['max_speed']:.1e} | {r['cpu']:.1f} |")
    mean = sum(r["porosity"] for r in rows) / len(rows)
    out += ["", f"Mean porosity {mean:.4f} against the experiment's {N_EXPERIMENT} ({mean - N_EXPERIMENT:+.4f})."]
    if not a.no_run:
        base = vofdem.load_scene(SCENE).with_value("flume.width", a.width).quick()
        disc = run(base.validate())
        sphere = run(base.with_value("stones.shape", "sphere").validate())
        out += ["", "## The quick scene with spheres", "",
                f"`Scene.quick()` of the Maeno scene at B = {a.width:g} m ({base.duration:g} s simulated), run to "
                "its end one after the other in this process (`run_scene`, no figures), packing included "
                "(the same as `vofdem run scenes/maeno2008_spheres.toml --quick`):", "",
                "| stones | ran to its end | CPU [s] | stop |", "|---|---|---:|---|",
                f"| discs | {disc['ok']} | {disc['cpu']:.1f} | {disc['why']} |",
                f"| spheres | {sphere['ok']} | {sphere['cpu']:.1f} | {sphere['why']} |", "",
                f"CPU ratio spheres / discs: {sphere['cpu'] / disc['cpu']:.2f}."]
    path = os.path.join(HERE, "results", "weir_packing_3d.md")
    with open(path, "w") as f:
        f.write("\n".join(out) + "\n")
    print("\n".join(out))


if __name__ == "__main__":
    main()
