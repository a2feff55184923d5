"""A scene over several packings: the same flume, weir outline and hydrograph, one run per seed.

A weir's failure depends on where each stone sits, and one packing is one sample: the stage
discharges of a single seed can differ by several l/s from another's (docs/scenario_diagnosis.md).
`run_ensemble` runs the scene once per seed into ``out_dir/seed<N>/`` (each a complete run directory)
and writes ``ensemble.md`` and ``ensemble.csv``: each seed's first removal and stages, then per event
the number of seeds that reached it and the median and range of its discharge.
"""
from __future__ import annotations

import csv
import io
from dataclasses import dataclass
from pathlib import Path
from typing import Callable, List, Optional, Sequence

import numpy as np

from .analysis import PAPER_EXPERIMENT, PAPER_MODEL
from .scene import Scene


def parse_seeds(spec: str) -> List[int]:
    """'0-4' -> [0, 1, 2, 3, 4]; '0,3,7' and '0-2,5' likewise; ValueError naming the bad part."""
    seeds: List[int] = []
    for part in spec.split(","):
        part = part.strip()
        try:
            if "-" in part[1:]:
                lo, hi = (int(v) for v in part.split("-", 1))
                if hi < lo:
                    raise ValueError
                seeds += range(lo, hi + 1)
            else:
                seeds.append(int(part))
        except ValueError:
            raise ValueError(f"seeds: {part!r} in {spec!r} is not a seed or a range 'a-b' with a <= b "
                             f"(e.g. '0-4' or '0,3,7')") from None
    if any(s < 0 for s in seeds) or len(set(seeds)) != len(seeds):
        raise ValueError(f"seeds: {spec!r} must list distinct non-negative seeds")
    return seeds


@dataclass
class SeedOutcome:
    seed: int
    first_removal_lps: Optional[float]
    stages: List[tuple]  # (discharge [l/s], stones) per stage
    removed: int
    stones: int
    crest_lowering_mm: float


def outcome_of(seed: int, analysis) -> SeedOutcome:
    a = analysis
    fr = a.first_removal
    return SeedOutcome(seed, None if fr is None else float(a.discharge_lps_at(fr)),
                       [(s.discharge_lps, s.n_stones) for s in a.stages],
                       int(np.isfinite(a.removal_time).sum()), int(a.removal_time.size),
                       1e3 * float(a.crest_lowering[-1]))


def _summary(values: Sequence[Optional[float]], n: int) -> str:
    v = [x for x in values if x is not None]
    if not v:
        return f"0 of {n} seeds"
    return f"{len(v)} of {n} seeds: median {np.median(v):.2f}, range {min(v):.2f}-{max(v):.2f}"


def ensemble_markdown(outcomes: List[SeedOutcome]) -> str:
    n = len(outcomes)
    out = ["| seed | first removal [l/s] | stages (Q l/s: stones) | removed | crest lowering [mm] |",
           "|---|---|---|---|---|"]
    for o in outcomes:
        fr = "none" if o.first_removal_lps is None else f"{o.first_removal_lps:.2f}"
        st = ", ".join(f"{q:.2f}: {k}" for q, k in o.stages) or "none"
        out.append(f"| {o.seed} | {fr} | {st} | {o.removed} of {o.stones} | {o.crest_lowering_mm:.1f} |")
    out += ["", "| event | this scene over the seeds: Q [l/s] | experiment Q [l/s] | paper's model Q [l/s] |",
            "|---|---|---|---|",
            f"| first removal of any stone | {_summary([o.first_removal_lps for o in outcomes], n)} | ~14 | none |"]
    for k in (1, 2, 3):
        q = [o.stages[k - 1][0] if len(o.stages) >= k else None for o in outcomes]
        model = PAPER_MODEL[k][0]
        out.append(f"| stage {k} | {_summary(q, n)} | {PAPER_EXPERIMENT[k][0]} | {'none' if model is None else model} |")
    return "\n".join(out) + "\n"


def ensemble_csv(outcomes: List[SeedOutcome]) -> str:
    buf = io.StringIO()
    w = csv.writer(buf, lineterminator="\n")
    w.writerow(["seed", "first_removal_lps", "stage1_lps", "stage1_stones", "stage2_lps", "stage2_stones",
                "stage3_lps", "stage3_stones", "removed", "stones", "crest_lowering_mm"])
    for o in outcomes:
        st = [x for k in range(3) for x in (o.stages[k] if len(o.stages) > k else ("", ""))]
        w.writerow([o.seed, "" if o.first_removal_lps is None else o.first_removal_lps, *st, o.removed,
                    o.stones, o.crest_lowering_mm])
    return buf.getvalue()


def run_ensemble(scene: Scene, seeds: Sequence[int], out_dir, build: Optional[Callable] = None, log=print,
                 **run_kwargs) -> List[SeedOutcome]:
    """Runs `scene` once per seed (keyword arguments go to `run_scene`); writes ensemble.md and
    ensemble.csv after every run, so an interrupted ensemble keeps the seeds it finished."""
    from .run import run_scene

    out = Path(out_dir)
    out.mkdir(parents=True, exist_ok=True)
    outcomes: List[SeedOutcome] = []
    for i, seed in enumerate(seeds):
        log(f"vofdem: seed {seed} ({i + 1} of {len(seeds)})")
        res = run_scene(scene.replace(seed=seed), out / f"seed{seed}", build=build, **run_kwargs)
        outcomes.append(outcome_of(seed, res.analysis))
        (out / "ensemble.md").write_text(ensemble_markdown(outcomes), encoding="utf-8")
        (out / "ensemble.csv").write_text(ensemble_csv(outcomes), encoding="utf-8")
    return outcomes
