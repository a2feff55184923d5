"""The water's loads on the held stones at two values of one key (by default the grid: numerics.fidelity
standard against fine): what the finer cells change before any stone moves.

For each packing (--seeds) and value, the scene (with the --base settings, by default the filtered pore
strain, which keeps the eddy viscosity bounded on both grids) runs with every stone held to each of
--times: the spin-up's end (20 s, 10 l/s) and points of the ramp. At each time and for each mobile stone
(the bed layer is fixed), the drag and the pressure-gradient force the coupler hands to it [N] and their
horizontal sum over the stone's submerged weight, W' = (rho_s - rho_w) g pi d^3 / 6 (the stones have the
mass of spheres): the mobility F_x / W', which a stone resting on others must keep below about its
friction, 0.577, not to slide. The packing does not depend on the grid, so the same stone is compared
between the values. Per region of the weir (upstream slope, crest, downstream slope, by the stone's x):
the mean mobility at each value, the mean and the median per-stone ratio of the second value's to the
first's, the stones above 0.3 at each value, and the summed drag and pressure-gradient forces. Writes
studies/results/stone_loads_grid.md.

    OMP_NUM_THREADS=1 PYTHONPATH=python python3 studies/stone_loads_grid.py --seeds 0 1 --times 20 50 80
"""
import argparse
import os
import platform
import time
from pathlib import Path

os.environ.setdefault("OMP_NUM_THREADS", "1")
ROOT = Path(__file__).resolve().parents[1]

import numpy as np  # noqa: E402

from vofdem.analysis import classify_regions  # noqa: E402
from vofdem.builder import build_simulation  # noqa: E402
from vofdem.ensemble import with_settings  # noqa: E402
from vofdem.scene import load_scene  # noqa: E402
from vofdem.study import sphere_volume, submerged_weight, write_page  # noqa: E402

MOBILE = 0.3  # a mobility counted as high in the table (about half the friction between stones)


def loads(scene, settings, times):
    """Per time: (t, steps, x of each mobile stone, mobility F_x / W' of each, and its drag's and its
    pressure-gradient force's F_x [N])."""
    sim = build_simulation(with_settings(scene, settings))
    st = sim.stones
    mobile = np.asarray(st.stone_fixed) == 0
    st.stone_fixed[:] = True
    d = 2.0 * np.asarray(st.stone_radius)[mobile]
    weight = submerged_weight(sphere_volume(d), np.asarray(st.stone_density)[mobile])
    out = []
    for t in times:
        sim.advance(t)
        drag, pressure = (np.asarray(f)[mobile, 0].copy() for f in (sim.stone_force_drag, sim.stone_force_pressure))
        out.append((t, int(sim.step_count), np.asarray(st.stone_pos)[mobile, 0].copy(), (drag + pressure) / weight,
                    (drag, pressure)))
    return out


def compare(scene, a, b, names):
    """Markdown rows of one time: per region the two values' mobility and the per-stone ratio."""
    (t, na, xa, ma, fa), (_, nb, xb, mb, fb) = a, b
    if not np.allclose(xa, xb, atol=1e-9):
        raise ValueError("the two values placed the stones differently: the loads are not comparable stone by stone")
    rows = []
    where = classify_regions(xa, scene.weir, 0.0)  # the stage tables' regions, without a shoulder
    for region in ("upstream slope", "crest", "downstream slope"):
        sel = where == region
        if not sel.any():
            continue
        ratio = mb[sel] / np.where(np.abs(ma[sel]) > 1e-12, ma[sel], np.nan)
        rows.append(f"| {t:g} | {scene.hydrograph.discharge_lps_at(t):.2f} | {region} | {int(sel.sum())} | {ma[sel].mean():+.3f} | "
                    f"{mb[sel].mean():+.3f} | {np.nanmean(ratio):.2f} / {np.nanmedian(ratio):.2f} | "
                    f"{int((ma[sel] > MOBILE).sum())} / {int((mb[sel] > MOBILE).sum())} | "
                    f"{ma[sel].max():.3f} / {mb[sel].max():.3f} | {fa[0][sel].sum():+.3f} / {fb[0][sel].sum():+.3f} | "
                    f"{fa[1][sel].sum():+.3f} / {fb[1][sel].sum():+.3f} |")
    rows.append(f"| {t:g} | | steps so far | | | | | | {names[0]} {na}, {names[1]} {nb} | | |")
    return rows


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--scene", default="maeno2008_rolling_consistent")
    ap.add_argument("--key", default="numerics.fidelity")
    ap.add_argument("--values", nargs=2, default=["standard", "fine"])
    ap.add_argument("--base", nargs="*", default=["numerics.turbulence_pore_strain=filtered"], metavar="KEY=VALUE")
    ap.add_argument("--seeds", type=int, nargs="+", default=[0, 1])
    ap.add_argument("--times", type=float, nargs="+", default=[20.0, 50.0, 80.0])
    ap.add_argument("--out", type=Path, default=ROOT / "studies" / "results" / "stone_loads_grid.md")
    args = ap.parse_args(argv)
    base = load_scene(ROOT / "scenes" / f"{args.scene}.toml")
    v0, v1 = args.values
    text = [f"# The water's loads on the held stones: `{args.key}` {v0} against {v1}", "",
            f"Generated by `studies/stone_loads_grid.py` on {time.strftime('%Y-%m-%d %H:%M UTC', time.gmtime())}, "
            f"Python {platform.python_version()}: scene {args.scene}, every stone held, settings "
            f"{', '.join(args.base) or 'none'}. Mobility: the horizontal drag and pressure-gradient force over the "
            f"stone's submerged weight; per region the mean at each value, the mean / median per-stone ratio "
            f"{v1} / {v0}, the stones above {MOBILE} and the largest mobility ({v0} / {v1}), and the region's summed "
            f"horizontal drag and pressure-gradient force [N].", ""]
    for seed in args.seeds:
        scene = base.replace(seed=seed)
        t0 = time.process_time()
        a = loads(scene, [*args.base, f"{args.key}={v0}"], args.times)
        t1 = time.process_time()
        b = loads(scene, [*args.base, f"{args.key}={v1}"], args.times)
        t2 = time.process_time()
        text += [f"## Packing {seed}", "", f"CPU: {v0} {t1 - t0:.1f} s, {v1} {t2 - t1:.1f} s.", "",
                 f"| t [s] | Q [l/s] | region | stones | mobility, {v0} | mobility, {v1} | ratio {v1} / {v0}: mean / "
                 f"median | above {MOBILE} | largest | drag F_x [N] | pressure F_x [N] |",
                 "|---|---|---|---|---|---|---|---|---|---|---|"]
        for ra, rb in zip(a, b):
            text += compare(scene, ra, rb, (v0, v1))
        text.append("")
    return write_page(args.out, text)


if __name__ == "__main__":
    main()
