"""The Maeno 2008 weir with each stone model and coupling, over packings: per seed, the first removal and
the stage discharges, and whether the failure comes in stages separated by stable periods.

One Dask ensemble per scene (scenes/maeno2008*.toml: the plain discs, the discs with the calibrated
rolling resistance, the polygon stones; each with the paper's and the consistent coupling), the same
seeds for all, on the paper's grid and hydrograph. Each ensemble is resumable (a second call runs only
what is missing). Writes studies/results/stone_models_weir.md (the comparison, then each scene's
members) and docs/figures/stone_models_weir.png (every member's stage discharges next to the
observed and modelled ones of the scenes' [reference] table: the experiment's and the paper's model's).

    PYTHONPATH=python python3 studies/stone_models_weir.py                 # 10 seeds, all scenes
    PYTHONPATH=python python3 studies/stone_models_weir.py --seeds 0-2 --scenes maeno2008_rolling
    PYTHONPATH=python python3 studies/stone_models_weir.py --quick --end-time 30 --seeds 0-1   # a smoke test
"""
import argparse
import os
import time
from pathlib import Path

import numpy as np

from vofdem.cluster import default_workers
from vofdem.ensemble import collect_outcomes, outcomes_frame, parse_seeds, run_ensemble
from vofdem.scene import load_scene
from vofdem.study import coupling, stone_model

ROOT = Path(__file__).resolve().parents[1]
SCENES = ("maeno2008", "maeno2008_consistent", "maeno2008_rolling", "maeno2008_rolling_consistent",
          "maeno2008_polygons", "maeno2008_polygons_consistent")


def reference_lines(ref):
    """((observed discharge [l/s], label), ...) and (modelled discharge, ...) of the scenes' [reference]."""
    obs = [(q, f"observed: stage {k}") for k, (q, _) in sorted(ref.stages().items())]
    mod = [q for _, (q, _) in sorted(ref.stages(model=True).items())]
    return obs, mod


def reference_text(ref) -> str:
    """The reference's values in words (the scenes' [reference] table), '' when it has none."""
    if not ref.given:
        return ""
    obs = " / ".join(f"{q:g}" for _, (q, _) in sorted(ref.stages().items()))
    mod = ", ".join(f"stage {k} {q:g}" for k, (q, _) in sorted(ref.stages(model=True).items()))
    return (f"Observed ({ref.citation}): first removal {ref.first_removal_lps:g}, stages {obs} l/s; "
            f"model ({ref.model_citation}): {mod} l/s. ")


def _q(v) -> str:
    return "-" if v is None or not np.isfinite(v) else f"{v:.2f}"


def _median_range(values) -> str:
    v = np.asarray([x for x in values if x is not None and np.isfinite(x)], float)
    if v.size == 0:
        return "none"
    return f"{np.median(v):.2f} ({v.min():.2f}-{v.max():.2f})"


def scene_row(name: str, scene, df) -> str:
    done = df[df["status"] == "completed"]
    n = len(done)
    first = done["first_removal_lps"].astype(float).to_numpy()
    stages = done["stages"].fillna(0).astype(int).to_numpy()
    s1 = done["stage1_lps"].astype(float).to_numpy()
    crest = done["crest_lowering_mm"].astype(float).to_numpy()
    rtf = done["wall_seconds"].astype(float).to_numpy() / done["simulated_seconds"].astype(float).to_numpy()
    return (f"| {stone_model(scene)} | {coupling(scene)} | {n} | {np.isfinite(first).sum()} | {_median_range(first)} | "
            f"{(stages >= 1).sum()} | {_median_range(s1)} | {(stages >= 2).sum()} | {(stages >= 3).sum()} | "
            f"{np.median(crest):.1f} ({crest.min():.1f}-{crest.max():.1f}) | {np.median(rtf):.2f} |")


def members_table(df) -> str:
    out = ["| seed | first removal [l/s] | stages (Q l/s: stones) | removed | crest lowering [mm] | status |",
           "|---|---|---|---|---|---|"]
    for _, r in df.sort_values("seed").iterrows():
        st = []
        for k in (1, 2, 3):
            q = r.get(f"stage{k}_lps")
            if q is not None and np.isfinite(float(q)):
                st.append(f"{float(q):.2f}: {int(r[f'stage{k}_stones'])}")
        more = int(r["stages"]) - len(st) if r["stages"] == r["stages"] else 0
        stages = ", ".join(st) + (f" (+{more} more)" if more > 0 else "") if st else "none"
        out.append(f"| {int(r['seed'])} | {_q(float(r['first_removal_lps']))} | {stages} | {r['removed']} of "
                   f"{r['stones']} | {float(r['crest_lowering_mm']):.1f} | {r['status']} |")
    return "\n".join(out)


def figure(results, path: Path) -> None:
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, ax = plt.subplots(figsize=(8.0, 0.55 * len(results) + 1.6))
    marks = {"first_removal_lps": ("o", "first removal"), "stage1_lps": ("s", "stage 1"),
             "stage2_lps": ("^", "stage 2"), "stage3_lps": ("D", "stage 3")}
    for row, (name, scene, df) in enumerate(results):
        done = df[df["status"] == "completed"]
        for k, (col, (m, label)) in enumerate(marks.items()):
            q = done[col].astype(float).to_numpy()
            q = q[np.isfinite(q)]
            y = row + 0.15 * (k - 1.5) + 0.03 * np.random.default_rng(k).standard_normal(q.size)
            ax.scatter(q, y, marker=m, s=18, color=f"C{k}", label=label if row == 0 else None, alpha=0.8)
        # members that lost no stone, at the discharge they stood to
        none = done[~np.isfinite(done["first_removal_lps"].astype(float))]
        q = none["last_discharge_lps"].astype(float).to_numpy()
        ax.scatter(q, row + 0.05 * np.arange(q.size) - 0.025 * q.size, marker="x", s=18, color="k",
                   label="no removal (stood to the end)" if row == 0 else None)
    observed, modelled = reference_lines(results[0][1].reference)
    for q, _ in observed:
        ax.axvline(q, color="k", lw=1.0, ls="-")
    for q in modelled:
        ax.axvline(q, color="0.5", lw=1.0, ls="--")
    ax.set_yticks(range(len(results)))
    ax.set_yticklabels([f"{stone_model(s)}\n{coupling(s)}" for _, s, _ in results], fontsize=8)
    ax.set_xlabel("discharge [l/s]\n(solid: observed " + " / ".join(f"{q:g}" for q, _ in observed)
                  + "; dashed: modelled " + " / ".join(f"{q:g}" for q in modelled) + "; the scenes' [reference])",
                  fontsize=9)
    ax.set_xlim(9.5, 25.5)
    ax.invert_yaxis()
    ax.legend(fontsize=7, loc="lower right", framealpha=0.9)
    ax.set_title("Maeno 2008 weir: each member's events, by stone model and coupling")
    fig.tight_layout()
    path.parent.mkdir(parents=True, exist_ok=True)
    fig.savefig(path, dpi=90)
    plt.close(fig)


def main(argv=None) -> Path:
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--scenes", nargs="+", default=list(SCENES), help="scene names in scenes/ (default: all six)")
    p.add_argument("--seeds", default="0-9")
    p.add_argument("--workers", type=int, default=None, help="local worker processes (default: one per core)")
    p.add_argument("--scheduler", default=None, help="an existing Dask cluster's address instead")
    p.add_argument("--quick", action="store_true", help="the scenes' quick variants (for a smoke test)")
    p.add_argument("--end-time", type=float, default=None, help="stop each member at this time [s] (smoke tests)")
    p.add_argument("--out", type=Path, default=ROOT / "out" / "stone_models")
    p.add_argument("--results", type=Path, default=ROOT / "studies" / "results")
    p.add_argument("--figures", type=Path, default=ROOT / "docs" / "figures")
    p.add_argument("--retry-failed", action="store_true", help="run the members that failed before again")
    args = p.parse_args(argv)
    seeds = parse_seeds(args.seeds)
    workers = args.workers if args.workers is not None else default_workers()
    results, t0 = [], time.perf_counter()
    for name in args.scenes:
        scene = load_scene(ROOT / "scenes" / f"{name}.toml")
        if args.quick:
            scene = scene.quick()
        if args.end_time is not None:
            scene = scene.replace(end_time=args.end_time)
        run_ensemble(scene, seeds, args.out / name, workers=workers, scheduler=args.scheduler, figures=False,
                     animation=False, retry_failed=args.retry_failed)
        results.append((name, scene, outcomes_frame(collect_outcomes(args.out / name))))
    wall = time.perf_counter() - t0
    variant = " (quick variants)" if args.quick else ""
    text = [f"# The Maeno 2008 weir by stone model and coupling, seeds {args.seeds}{variant}", "",
            f"Written by `studies/stone_models_weir.py --seeds {args.seeds}"
            f"{' --quick' if args.quick else ''}`; the last call took {wall / 60:.1f} min on "
            f"{workers or 1} worker process(es) ({os.cpu_count()} cores, load average {os.getloadavg()[0]:.1f} "
            f"at the end). Events as in `vofdem.analysis` (a stage: at least 2 removals with no pause over 3 s). "
            f"{reference_text(results[0][1].reference)}Real-time factor: wall time / simulated time per member, "
            f"on a shared machine.", "",
            "| stones | coupling | members | with a removal | first removal [l/s], median (range) | with a stage | "
            "stage 1 [l/s], median (range) | with 2+ stages | with 3+ stages | crest lowering [mm] | real-time factor |",
            "|---|---|---|---|---|---|---|---|---|---|---|"]
    text += [scene_row(name, scene, df) for name, scene, df in results]
    for name, scene, df in results:
        text += ["", f"## `{name}`: {stone_model(scene)}, {coupling(scene)} coupling", "", members_table(df)]
    args.results.mkdir(parents=True, exist_ok=True)
    md = args.results / "stone_models_weir.md"
    md.write_text("\n".join(text) + "\n", encoding="utf-8")
    figure(results, args.figures / "stone_models_weir.png")
    print(f"wrote {md} and {args.figures / 'stone_models_weir.png'}")
    return md


if __name__ == "__main__":
    main()
