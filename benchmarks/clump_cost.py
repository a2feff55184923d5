"""The cost of clump stones (clump_model.h) against spheres (sphere_model.h): the same settling bed of ~300
stones of one volume-equivalent diameter, spheres or the library's clumps (pair_2, triangle_3, tetra_4, box_8 in
turn), dropped into a flume and settling, the CPU time per stone-step (time.process_time) over a measured
stretch at the same step, in one process.

    OMP_NUM_THREADS=1 PYTHONPATH=python python3 benchmarks/clump_cost.py
"""
import argparse
import os
import platform
import time
from pathlib import Path

os.environ.setdefault("OMP_NUM_THREADS", "1")
ROOT = Path(__file__).resolve().parents[1]

import numpy as np  # noqa: E402

import vofdem  # noqa: E402
from vofdem import _core  # noqa: E402

D_EQ = 0.03  # volume-equivalent diameter [m]
LENGTH, WIDTH = 0.6, 0.15  # flume [m]


def bed(model, n, seed=0):
    """n stones on a grid above a flume, the model's shapes set, turned at random."""
    p = vofdem.DEMParams()
    p.add_flume(0.0, LENGTH, 0.0, 0.3)
    p.width = WIDTH
    p.stiffness_normal = 1e5
    p.restitution = 0.3
    p.dt = 1e-5
    g = np.random.default_rng(seed)
    nx, ny = 13, 3
    cells = [(k % nx, (k // nx) % ny, k // (nx * ny)) for k in range(n)]
    pos = np.array([[0.025 + 0.044 * i + 0.002 * g.random(), 0.03 + 0.044 * k] for i, _, k in cells])
    s = vofdem.DEMSystem(p, pos=pos, density=[2650.0], radius=np.full(n, 0.5 * D_EQ))
    if model == "clump":
        names = _core.quarried_stone_names()
        shapes = [_core.quarried_stone(names[k % len(names)], D_EQ) for k in range(n)]
        offset = np.concatenate([[0], np.cumsum([len(c) for c in shapes])]).astype(int)
        s.set_clumps(np.vstack(shapes), offset.tolist())
        q = g.normal(size=(n, 4))
        s.stone_quat[:] = q / np.linalg.norm(q, axis=1)[:, None]
    else:
        s.set_model("sphere")
    s.stone_y[:] = np.array([0.03 + 0.045 * j for _, j, _ in cells]) + 0.002 * g.random(n)
    return s


STAGES = ("contacts", "walls", "integrate")  # the DEM's per-stage timer (DEMSystem.profile)


def measure(model, n, settle, duration):
    s = bed(model, n)
    s.advance(settle)
    before = dict(zip(s.profile.names, s.profile.seconds))
    c0, k0 = time.process_time(), s.steps
    s.advance(duration)
    cpu, steps = time.process_time() - c0, s.steps - k0
    spent = {k: v - before.get(k, 0.0) for k, v in zip(s.profile.names, s.profile.seconds)}
    timed = sum(spent.values())
    spheres = len(s.export_state()["clump_sphere"]) // 4 if model == "clump" else n
    return {"cpu": cpu, "steps": steps, "per": cpu / (steps * n), "per_sphere": cpu / (steps * spheres),
            "share": {k: spent.get(k, 0.0) / timed for k in STAGES}, "contacts": s.contact_count,
            "walls": s.wall_contact_count, "kinetic": s.energy().kinetic}


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--n", type=int, default=297, help="stones")
    ap.add_argument("--settle", type=float, default=0.6, help="simulated time before the measure [s]")
    ap.add_argument("--duration", type=float, default=0.1, help="measured simulated time [s]")
    ap.add_argument("--repeats", type=int, default=3, help="runs of each model, in turn")
    ap.add_argument("--out", type=Path, default=ROOT / "benchmarks" / "results" / "clump_cost.md")
    args = ap.parse_args(argv)
    # the models in turn, repeated: each row the repeat of the median CPU (the host's speed drifts)
    runs = {"sphere": [], "clump": []}
    for _ in range(args.repeats):
        for m in runs:
            runs[m].append(measure(m, args.n, args.settle, args.duration))
    rows = {m: sorted(r, key=lambda x: x["per"])[len(r) // 2] for m, r in runs.items()}
    ratio = rows["clump"]["per"] / rows["sphere"]["per"]
    spread = ", ".join(f"{m} {min(x['per'] for x in r) * 1e6:.3f}-{max(x['per'] for x in r) * 1e6:.3f} us"
                       for m, r in runs.items())
    lines = [
        "# Clump stones' cost against spheres",
        "",
        f"A bed of {args.n} stones of d_eq = {D_EQ} m dropped into a flume {LENGTH} m long and {WIDTH} m wide "
        f"(k_n = 1e5 N/m, e = 0.3, dt = 1e-5 s), after {args.settle} s of settling the next {args.duration} s "
        "measured (the bed still settling): "
        "CPU time (time.process_time, one thread) per stone-step. Clumps: the library's pair_2, triangle_3, "
        "tetra_4 and box_8 in turn (4.25 spheres per stone on average), turned at random. "
        f"`benchmarks/clump_cost.py --repeats {args.repeats}` on {platform.machine()}, a machine shared with other "
        f"jobs: the models measured in turn {args.repeats} times in one process, each row the median run "
        f"(per stone-step over the repeats: {spread}).",
        "",
        "| stones | steps | CPU [s] | CPU per stone-step [us] | per sphere-step [us] | "
        + " | ".join(f"{k} [share]" for k in STAGES) + " | stone contacts | wall contacts | kinetic energy [J] |",
        "|---|---|---|---|---|" + "---|" * len(STAGES) + "---|---|---|",
    ]
    for m, r in rows.items():
        shares = " | ".join(f"{r['share'][k]:.2f}" for k in STAGES)
        lines.append(f"| {m} | {r['steps']} | {r['cpu']:.2f} | {1e6 * r['per']:.3f} | {1e6 * r['per_sphere']:.3f} | "
                     f"{shares} | {r['contacts']} | {r['walls']} | {r['kinetic']:.2e} |")
    per_sphere = rows["clump"]["per_sphere"] / rows["sphere"]["per_sphere"]
    lines += ["", f"Clumps over spheres: {ratio:.2f} times the CPU per stone-step (aim: at most 4); "
              f"{per_sphere:.2f} times per sphere-step (a clump's sub-spheres each count as one). Shares: of the "
              "DEM's per-stage timer over the measured stretch (its other stages, the checks and the neighbour "
              "list, make up the rest)."]
    args.out.write_text("\n".join(lines) + "\n")
    print("\n".join(lines))


if __name__ == "__main__":
    main()
