#!/usr/bin/env python3
"""The failure's mechanism in one weir of an ensemble: which stones each destruction stage removed, where
they lay (cross-section and plan view) and what the water pulled on them just before.

The weir shown is the ensemble's median member: its members (completed, ensemble.csv) ordered by the
discharge of their first stage, ties (e.g. stages at the release) by their second stage's, then their
third's, then their first removal (a missing event after every discharge), then by seed; the lower median
of that order. For it, per stage: its discharge and
stones, where they lay at the start (the regions of vofdem.analysis; height above the bed over the weir's
height; for 3D stones the share lying within one diameter of a side wall), and the water's force on them
at the last snapshot before the stage began (the drag and the pressure-gradient force the run writes,
force_drag + force_pressure, in units of each stone's submerged weight (rho_s - rho_w) g pi d^3 / 6):
their mean and largest downstream (x) and upward (z) components, next to the same means over the
loose stones of the same regions that stayed in place until then. The overflow's drag and lift
(numerics.overflow_load) is not written by runs, so it is not in these loads; a scene that turns it on is
said so in the results.

Figures: the weir's cross-section at the end with the stones coloured by the stage that removed them
(plots.fig_destruction) and, for 3D stones, the plan view at the start and the end (plots.fig_plan_view).

    python3 studies/failure_mechanism.py ENSEMBLE_DIR --tag NAME [--results studies/results]
        [--figures docs/figures]

Writes studies/results/failure_mechanism_<tag>.md and docs/figures/failure_mechanism_<tag>_destruction.png
(and _plan_view.png for 3D stones).
"""
from __future__ import annotations

import argparse
import math
from pathlib import Path

import numpy as np
import pandas as pd

from vofdem.io import RunData
from vofdem.run import analyse_run
from vofdem.study import number_or_dash as _f, shown_path, sphere_volume, submerged_weight

ROOT = Path(__file__).resolve().parents[1]


def median_member(df: pd.DataFrame) -> int:
    """The seed of the lower median member: completed members ordered by their stages' discharges (the
    first, then the second, then the third; none: after any discharge), then by their first removal, then
    by seed."""
    done = df[df["status"] == "completed"]
    if done.empty:
        raise ValueError("the ensemble has no completed member")
    cols = [c for c in ("stage1_lps", "stage2_lps", "stage3_lps", "first_removal_lps") if c in done]
    key = done.assign(**{f"_{c}": done[c].astype(float).fillna(math.inf) for c in cols})
    order = key.sort_values([f"_{c}" for c in cols] + ["seed"], kind="stable")
    return int(order["seed"].iloc[(len(order) - 1) // 2])


def _side_wall_share(data, stones) -> float:
    """Share of the stones lying within one diameter of a side wall at the start (3D stones; else nan)."""
    if data.y is None or len(stones) == 0:
        return math.nan
    y, d = data.y[0, stones], data.diameter[stones]
    return float(np.mean((y < d) | (y > data.width - d)))


def stage_rows(data, analysis, scene) -> list:
    """One row per stage: discharge, stones, where they lay, and their loads just before it began."""
    w = scene.weir
    x0, z0 = data.pos[0, :, 0], data.pos[0, :, 1]
    regions = analysis.region
    weight = submerged_weight(sphere_volume(data.diameter), scene.stones.density)
    rows = []
    for st in analysis.stages:
        k = max(int(np.searchsorted(data.times, st.start_time)) - 1, 0)  # the last snapshot before it
        idx = np.asarray(st.stones, int)
        load = (data.force_drag[k] + data.force_pressure[k]) / weight[:, None]
        in_place = ~np.isfinite(analysis.removal_time) | (analysis.removal_time > st.start_time)
        same = np.isin(regions, np.unique(regions[idx])) & ~data.fixed & data.active[k] & in_place
        same[idx] = False
        rows.append({
            "stage": st.number, "discharge_lps": st.discharge_lps, "stones": idx.size,
            "where": ", ".join(f"{r} {st.region_counts[r]}" for r in st.region_counts if st.region_counts[r]),
            "height": float(np.mean(z0[idx]) / w.height), "x_mean": float(np.mean(x0[idx])),
            "side_wall": _side_wall_share(data, idx), "t_before": float(data.times[k]),
            "load_x": float(np.mean(load[idx, 0])), "load_x_max": float(np.max(load[idx, 0])),
            "load_z": float(np.mean(load[idx, 1])), "load_z_max": float(np.max(load[idx, 1])),
            "others": int(same.sum()),
            "others_x": float(np.mean(load[same, 0])) if same.any() else math.nan,
            "others_z": float(np.mean(load[same, 1])) if same.any() else math.nan,
        })
    return rows


def results_md(ens: Path, tag: str, seed: int, df: pd.DataFrame, scene, analysis, rows, figures) -> str:
    done = df[df["status"] == "completed"]
    lines = [f"# The failure's mechanism: `{scene.name}`, {scene.stones.shape} stones, packing {seed}", "",
             f"Written by `studies/failure_mechanism.py {shown_path(ens, ROOT)} --tag {tag}` "
             f"({len(done)} completed members): the median member by its stages (the module's "
             "docstring), packing (seed) " + str(seed) + ". Loads: the drag and pressure-gradient force of the "
             "last snapshot before each stage began, in units of each stone's submerged weight (x "
             "downstream, z up); 'others': the loose stones of the same regions still in place then.", ""]
    if scene.numerics.overflow_load != "off":
        lines += ["The scene loads the stones with the overflow's drag and lift too; runs do not write that "
                  "load, so it is missing from the loads below.", ""]
    lines += ["| stage | Q [l/s] | stones | where (initial place) | height / H | within 1 d of a side wall | "
              "snapshot before [s] | load x, mean (max) | load z, mean (max) | others: stones | others: load x | "
              "others: load z |", "|---|---|---|---|---|---|---|---|---|---|---|---|"]
    for r in rows:
        lines.append(f"| {r['stage']} | {r['discharge_lps']:.2f} | {r['stones']} | {r['where']} | "
                     f"{r['height']:.2f} | {_f(r['side_wall'])} | {r['t_before']:.1f} | {r['load_x']:.2f} "
                     f"({r['load_x_max']:.2f}) | {r['load_z']:.2f} ({r['load_z_max']:.2f}) | {r['others']} | "
                     f"{_f(r['others_x'])} | {_f(r['others_z'])} |")
    if not rows:
        lines.append("| none | | | | | | | | | | | |")
    n_rem = int(np.isfinite(analysis.removal_time).sum())
    lines += ["", f"Stones removed in all: {n_rem} of {analysis.removal_time.size} ({len(analysis.isolated)} "
              f"outside any stage); crest lowering at the end {1e3 * analysis.crest_lowering[-1]:.1f} mm.", "",
              "Figures: " + ", ".join(f"`{shown_path(p, ROOT)}`" for p in figures),
              ""]
    return "\n".join(lines)


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("ensemble", type=Path, help="an ensemble's directory (ensemble.csv, seed<N>/run.h5)")
    ap.add_argument("--tag", required=True, help="the results' name: failure_mechanism_<tag>")
    ap.add_argument("--seed", type=int, default=None, help="this member instead of the median")
    ap.add_argument("--results", type=Path, default=ROOT / "studies" / "results")
    ap.add_argument("--figures", type=Path, default=ROOT / "docs" / "figures")
    args = ap.parse_args(argv)
    df = pd.read_csv(args.ensemble / "ensemble.csv")
    seed = median_member(df) if args.seed is None else args.seed
    data = RunData(args.ensemble / f"seed{seed}" / "run.h5")
    scene = data.scene()
    analysis = analyse_run(data, scene)
    from vofdem import plots

    args.figures.mkdir(parents=True, exist_ok=True)
    base = args.figures / f"failure_mechanism_{args.tag}"
    figs = [(plots.fig_destruction(analysis, data, scene), Path(f"{base}_destruction.png"))]
    if data.y is not None:
        figs.append((plots.fig_plan_view(data, scene, analysis), Path(f"{base}_plan_view.png")))
    for fig, path in figs:
        fig.savefig(path, dpi=110)
    rows = stage_rows(data, analysis, scene)
    args.results.mkdir(parents=True, exist_ok=True)
    out = args.results / f"failure_mechanism_{args.tag}.md"
    out.write_text(results_md(args.ensemble, args.tag, seed, df, scene, analysis, rows, [p for _, p in figs]), encoding="utf-8")
    print(out)


if __name__ == "__main__":
    main()
