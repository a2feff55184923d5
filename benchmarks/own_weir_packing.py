"""Packing of weirs of any outline with sieve curves and zones (vofdem.outline_packing), measured over seeds:

0. the sampler alone: 320 stones drawn by mass in stratified blocks against independent draws, the
   largest difference of their mass curve from the requested one over 20 seeds;
1. a graded weir of 300+ stones (d15 / d50 / d85 = 18 / 25 / 36 mm, trapezoidal outline): the packed
   grading against the requested one (largest difference of mass fraction passing, d15 / d50 / d85),
   stones drawn but left over, porosity, outline error, wall time;
2. a weir with a berm and an armour layer (6 cm; armour 40 / 50 / 60 mm over a 20 / 30 / 45 mm core):
   how well the zones are kept (share of each zone's stones whose centre lies in it, the farthest);
3. scenes/own_weir.toml: the packed weir drawn by zone, its grading figure and table, and (unless
   --no-run) its quick run, whose hydrograph figure goes to the docs, and its quick --until-failure run.

Writes benchmarks/results/own_weir_packing.md and docs/figures/own_weir_{packed,grading,hydrograph}.png.
    PYTHONPATH=python python3 benchmarks/own_weir_packing.py [--seeds 10] [--no-run]
"""
from __future__ import annotations

import argparse
import os
import shutil
import subprocess
import sys
import time
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT / "python"))

from vofdem.builder import build_stones, dem_params  # noqa: E402
from vofdem.grading import grading_deviation, packed_d  # noqa: E402
from vofdem.reports import packed_report  # noqa: E402
from vofdem.outline_packing import reach_outside  # noqa: E402
from vofdem.scene import Scene, load_scene  # noqa: E402

GRADED = """
[weir]
outline = [[1.0, 0.0], [1.45, 0.22], [1.7, 0.22], [2.15, 0.0]]
[stones]
d15 = "18 mm"
d50 = "25 mm"
d85 = "36 mm"
"""
BERM = """
[weir]
outline = [[1.0, 0.0], [1.3, 0.15], [1.5, 0.15], [1.7, 0.25], [1.9, 0.25], [2.3, 0.0]]
[stones]
d15 = 0.02
d50 = 0.03
d85 = 0.045
[[zones]]
name = "armour"
thickness = 0.06
d15 = 0.04
d50 = 0.05
d85 = 0.06
"""


def _arrays(stones):
    return np.asarray(stones.stone_pos).reshape(-1, 2), 2.0 * np.asarray(stones.stone_radius)


def sampler_rows(n_seeds: int = 20, n: int = 320):
    from vofdem.grading import BLOCK, Grading, Sampler

    g = Grading.from_d(0.02, 0.03, 0.045)
    strat, iid = [], []
    for seed in range(n_seeds):
        s = Sampler(g, np.random.default_rng(seed))
        strat.append(grading_deviation(g, np.array([s.draw() for _ in range(n)])))
        iid.append(grading_deviation(g, g.inverse_number_cdf(np.random.default_rng(seed).random(n))))
    return [f"{n} stones drawn by mass from d15 / d50 / d85 = 20 / 30 / 45 mm, {n_seeds} seeds: largest difference "
            f"of the mass curve from the requested one {np.mean(strat):.3f} on average (at most {np.max(strat):.3f}) "
            f"in stratified blocks of {BLOCK}, against {np.mean(iid):.3f} (at most {np.max(iid):.3f}) for independent "
            f"draws."]


def graded_rows(seeds):
    rows = ["| seed | stones | left over | rolled off | max dF | d15 / d50 / d85 [mm] | porosity | outline error [mm] "
            "| centre outside, most [d50] | wall [s] |", "|---|---|---|---|---|---|---|---|---|---|"]
    devs = []
    for seed in seeds:
        s = Scene.from_toml(GRADED).replace(seed=seed)
        t0 = time.perf_counter()
        st, rep = build_stones(s)
        wall = time.perf_counter() - t0
        pos, d = _arrays(st)
        dev = grading_deviation(s.stones.grading(), d)
        devs.append(dev)
        out = reach_outside(s.weir.body(), pos, np.zeros(d.size)).max() / 0.025
        rows.append(f"| {seed} | {rep.n_stones} | {rep.left_over} | {rep.rolled_off} | {dev:.3f} | "
                    + " / ".join(f"{1e3 * packed_d(d, p):.1f}" for p in (0.15, 0.5, 0.85))
                    + f" | {rep.porosity:.3f} | {1e3 * rep.outline_error:.1f} | {out:.2f} | {wall:.1f} |")
    rows += ["", f"Requested d15 / d50 / d85: 18.0 / 25.0 / 36.0 mm. Largest dF over the seeds: {max(devs):.3f} "
             f"(median {np.median(devs):.3f})."]
    return rows


def zone_rows(seeds):
    rows = ["| seed | stones | armour stones | armour centres in the layer | farthest below it [d] | core centres "
            "under the layer | farthest into it [d] | dF armour / core |", "|---|---|---|---|---|---|---|---|"]
    for seed in seeds:
        s = Scene.from_toml(BERM).replace(seed=seed)
        st, rep = build_stones(s)
        pos, d = _arrays(st)
        depth = s.weir.body().depth(pos[:, 0], pos[:, 1])
        arm, core = rep.zone == 0, rep.zone == -1
        th = s.zones[0].thickness
        rows.append(f"| {seed} | {rep.n_stones} | {arm.sum()} | {np.mean(depth[arm] < th):.2f} | "
                    f"{((depth[arm] - th) / d[arm]).max():.2f} | {np.mean(depth[core] >= th):.2f} | "
                    f"{((th - depth[core]) / d[core]).max():.2f} | "
                    f"{grading_deviation(s.zones[0].grading(), d[arm]):.3f} / "
                    f"{grading_deviation(s.stones.grading(), d[core]):.3f} |")
    return rows


def fig_packed(scene, pos, d, zone):
    from matplotlib.collections import EllipseCollection
    from matplotlib.figure import Figure

    fig = Figure(figsize=(9.0, 2.8), layout="constrained")
    ax = fig.add_subplot()
    colors = np.where(zone == 0, "tab:orange", "tan")
    ax.add_collection(EllipseCollection(d, d, np.zeros(d.size), units="xy", offsets=pos, offset_transform=ax.transData,
                                        facecolors=list(colors), edgecolors="0.2", linewidths=0.4))
    x, z = scene.weir.outline_xz()
    ax.plot(x, z, color="k", lw=1.2, label="outline")
    ax.plot([], [], "o", color="tab:orange", label=f"{scene.zones[0].name} stones")
    ax.plot([], [], "o", color="tan", label="core")
    ax.set_aspect("equal")
    ax.set_xlim(min(x) - 0.05, max(x) + 0.05)
    ax.set_ylim(0.0, max(z) + 0.06)
    ax.set_xlabel("x [m]")
    ax.set_ylabel("z [m]")
    ax.legend(fontsize=7, loc="upper right")
    ax.set_title(f"{scene.name}: {d.size} stones packed from seed {scene.seed}", fontsize=10)
    return fig


def main() -> int:
    p = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    p.add_argument("--seeds", type=int, default=10, help="seeds of part 1 (part 2 takes 6 of them at most)")
    p.add_argument("--no-run", action="store_true", help="skip the quick run of scenes/own_weir.toml")
    args = p.parse_args()
    figs = ROOT / "docs" / "figures"
    t0 = time.perf_counter()
    own = load_scene(ROOT / "scenes" / "own_weir.toml")
    st, rep = build_stones(own)
    pos, d = _arrays(st)
    md_grading, fig = packed_report(own, pos, d, rep.zone)
    fig.savefig(figs / "own_weir_grading.png", dpi=100)
    fig_packed(own, pos, d, rep.zone).savefig(figs / "own_weir_packed.png", dpi=100)
    pdem = dem_params(own)
    lines = ["# Packing weirs of any outline: sieve curves and zones", "",
             "Made by `benchmarks/own_weir_packing.py` (numbers of one machine; wall times on a shared 2-core "
             "machine).", "", "## 0. The sampler", ""]
    lines += sampler_rows()
    lines += ["", "## 1. A graded weir of 300+ stones: the packed grading", ""]
    lines += graded_rows(range(args.seeds))
    lines += ["", "## 2. A berm and an armour layer: zones kept", ""]
    lines += zone_rows(range(min(6, args.seeds)))
    lines += ["", "## 3. scenes/own_weir.toml", "",
              f"{rep.n_stones} stones ({rep.n_fixed} fixed), porosity {rep.porosity:.3f}, outline error "
              f"{1e3 * rep.outline_error:.1f} mm, {rep.left_over} drawn stones left over, packed in "
              f"{rep.wall_seconds:.1f} s. DEM step {pdem.dt:.3g} s for its smallest stones against the scene's "
              f"{own.numerics.dem_dt:g} s: {own.numerics.dem_dt / pdem.dt:.2f}x the DEM steps.", "",
              md_grading.split("\n", 2)[2]]
    if not args.no_run:
        out = ROOT / "out" / "own_weir_quick"
        t1 = time.perf_counter()
        subprocess.run([sys.executable, "-m", "vofdem", "run", "scenes/own_weir.toml", "--quick", "--out", str(out),
                        "--no-progress", "--no-animation"], cwd=ROOT, check=True, stdout=subprocess.DEVNULL,
                       env={**os.environ, "PYTHONPATH": str(ROOT / "python")})
        shutil.copyfile(out / "figures" / "hydrograph.png", figs / "own_weir_hydrograph.png")
        lines += ["", f"Quick run (`vofdem run scenes/own_weir.toml --quick`): {time.perf_counter() - t1:.0f} s wall; "
                  "its stage table:", "", (out / "stage_table.md").read_text(encoding="utf-8")]
        uf = ROOT / "out" / "own_weir_quick_until_failure"
        t1 = time.perf_counter()
        subprocess.run([sys.executable, "-m", "vofdem", "run", "scenes/own_weir.toml", "--quick", "--until-failure",
                        "--out", str(uf), "--no-progress", "--no-animation", "--no-figures"], cwd=ROOT, check=True,
                       stdout=subprocess.DEVNULL, env={**os.environ, "PYTHONPATH": str(ROOT / "python")})
        lines += ["", f"Quick until-failure run (`vofdem run scenes/own_weir.toml --quick --until-failure`): "
                  f"{time.perf_counter() - t1:.0f} s wall:", "",
                  (uf / "until_failure.md").read_text(encoding="utf-8").split("\n", 2)[2]]
    lines += ["", f"Total {time.perf_counter() - t0:.0f} s."]
    res = ROOT / "benchmarks" / "results" / "own_weir_packing.md"
    res.write_text("\n".join(lines) + "\n", encoding="utf-8")
    print(res.read_text(encoding="utf-8"))
    return 0


if __name__ == "__main__":
    sys.exit(main())
