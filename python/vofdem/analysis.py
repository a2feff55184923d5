"""Failure analysis of a rubble mound weir from its stones' trajectories.

Definitions (all from the recorded snapshots of stone positions):

* **Displacement** of stone i at time t: |x_i(t) - x_i(0)| [m].
* **Removal**: a stone counts as removed at the first snapshot where its displacement exceeds
  ``removal_factor`` (default 1) times its own diameter, or where the solver reports it inactive
  (it left the domain). Fixed stones are never removed. The time resolution is the snapshot interval.
* **Destruction stages** (the paper's "collapsing stage and stable stage alternately"): the removal
  times are sorted and split wherever two consecutive removals are more than ``gap`` seconds apart
  (default 3 s: a stable period is a pause longer than this). A group with at least ``min_stones``
  removals (default 2) is a stage; smaller groups are isolated removals (the paper's "only one
  particle washed away" between its second and third stages is not a stage). Each stage carries its
  start time (first removal), the discharge then, its number of stones and where they were on the
  weir at the start.
* **Location** on the weir, from a stone's initial x and the initial trapezoid: upstream slope
  (x < upstream crest corner), crest, shoulder (within ``shoulder_half_width``, default one mean
  diameter, of the downstream crest corner), downstream slope (beyond it).
* **Crest level**: the crest span is cut into bins one mean diameter wide; in each bin the top of the
  highest active stone above the bin's centre is taken; the crest level is their mean, and the crest
  lowering is its drop from the initial snapshot.

Stages are compared by order with the paper (Maeno & Tomita 2008): our stage k against its stage k.
Experiment (Maeno et al. 2002): first removals ~14 l/s, second stage 16.5 l/s, third 20.4 l/s. The
paper's model: no first-stage removal (stones vibrated above 15 l/s), second stage 17.1 l/s at
56.8 s of its clock, third 19.2 l/s 16 s later (72.8 s). Its clock starts at the ramp (10 l/s).
"""
from __future__ import annotations

import csv
import io
from dataclasses import dataclass, field
from typing import Callable, Dict, List, Optional

import numpy as np

REGIONS = ("upstream slope", "crest", "shoulder", "downstream slope")

# the paper's numbers, stage number -> (discharge [l/s], paper-clock time [s] or None)
PAPER_EXPERIMENT = {1: (14.0, None), 2: (16.5, None), 3: (20.4, None)}
PAPER_MODEL = {1: (None, None), 2: (17.1, 56.8), 3: (19.2, 72.8)}


@dataclass
class StageCriterion:
    """Parameters of the removal and burst definitions (see the module's docstring)."""

    removal_factor: float = 1.0  # removed once moved more than this many own diameters [-]
    gap: float = 3.0  # [s] a pause between removals longer than this separates two stages
    min_stones: int = 2  # a burst needs at least this many removals to count as a stage
    shoulder_half_width: Optional[float] = None  # [m]; default: one mean diameter


@dataclass
class Stage:
    number: int
    start_time: float  # simulation time of its first removal [s]
    end_time: float  # simulation time of its last removal [s]
    paper_time: float  # start on the paper's clock (since the ramp began) [s]
    discharge_lps: float  # discharge at the start [l/s]
    stones: List[int]  # indices of the stones removed in it
    region_counts: Dict[str, int]

    @property
    def n_stones(self) -> int:
        return len(self.stones)

    @property
    def location(self) -> str:
        """The region holding most of its stones (ties joined with '+')."""
        best = max(self.region_counts.values())
        return " + ".join(r for r in REGIONS if self.region_counts.get(r, 0) == best)


@dataclass
class FailureAnalysis:
    times: np.ndarray  # (T,) snapshot times [s]
    displacement: np.ndarray  # (T, n) [m]
    removal_time: np.ndarray  # (n,) [s], nan = never removed
    region: np.ndarray  # (n,) region name of each stone's initial place
    stages: List[Stage]
    isolated: List[int]  # stones removed outside any stage
    crest_level: np.ndarray  # (T,) [m]
    criterion: StageCriterion
    ramp_start: float = 0.0
    discharge_lps_at: Optional[Callable] = None
    removed_count: np.ndarray = field(default=None)  # (T,) stones removed so far

    @property
    def crest_lowering(self) -> np.ndarray:
        """Drop of the crest level since the first snapshot [m] (positive = lower)."""
        return self.crest_level[0] - self.crest_level

    @property
    def first_removal(self) -> Optional[float]:
        t = self.removal_time[np.isfinite(self.removal_time)]
        return float(t.min()) if t.size else None

    # ------------------------------------------------------------------ tables
    def stage_rows(self) -> List[Dict[str, object]]:
        """One row per detected stage, with the paper's numbers for the stage of the same order."""
        rows = []
        for s in self.stages:
            exp_q = PAPER_EXPERIMENT.get(s.number, (None, None))[0]
            mod_q, mod_t = PAPER_MODEL.get(s.number, (None, None))
            rows.append({
                "stage": s.number, "start_s": round(s.start_time, 3), "paper_clock_s": round(s.paper_time, 3),
                "discharge_lps": round(s.discharge_lps, 3), "stones": s.n_stones, "location": s.location,
                "experiment_lps": exp_q, "paper_model_lps": mod_q, "paper_model_s": mod_t,
            })
        return rows

    def stage_table_csv(self) -> str:
        cols = ["stage", "start_s", "paper_clock_s", "discharge_lps", "stones", "location", "experiment_lps",
                "paper_model_lps", "paper_model_s"]
        buf = io.StringIO()
        w = csv.DictWriter(buf, fieldnames=cols, lineterminator="\n")
        w.writeheader()
        for r in self.stage_rows():
            w.writerow({k: ("" if v is None else v) for k, v in r.items()})
        return buf.getvalue()

    def stage_table_markdown(self) -> str:
        """Stages found, then a comparison with the paper's experiment and model."""
        c = self.criterion
        out = [f"Removal: moved more than {c.removal_factor:g} diameter(s); stage: >= {c.min_stones} removals "
               f"with pauses <= {c.gap:g} s. Paper clock = simulation time - {self.ramp_start:g} s.", "",
               "| stage | start [s] | paper clock [s] | Q [l/s] | stones | where |", "|---|---|---|---|---|---|"]
        for s in self.stages:
            out.append(f"| {s.number} | {s.start_time:.1f} | {s.paper_time:.1f} | {s.discharge_lps:.2f} | "
                       f"{s.n_stones} | {s.location} |")
        if not self.stages:
            out.append("| - | no stage | | | 0 | |")
        n_iso = len(self.isolated)
        fr = self.first_removal
        out += ["", f"Isolated removals (not in a stage): {n_iso}. "
                f"Stones removed in total: {int(np.isfinite(self.removal_time).sum())} of {self.removal_time.size}. "
                f"Final crest lowering: {1e3 * float(self.crest_lowering[-1]):.1f} mm.", ""]
        out += ["| event | this run: Q [l/s] (paper clock [s]) | experiment Q [l/s] | paper's model Q [l/s] (t [s]) |",
                "|---|---|---|---|"]
        q_first = f"{self._q(fr):.2f} ({fr - self.ramp_start:.1f})" if fr is not None else "none"
        out.append(f"| first removal of any stone | {q_first} | ~14 | none (vibration from 15) |")
        names = {1: "first stage (first removals)", 2: "second stage", 3: "third stage"}
        for k in (1, 2, 3):
            ours = next((s for s in self.stages if s.number == k), None)
            mine = f"{ours.discharge_lps:.2f} ({ours.paper_time:.1f})" if ours else "none"
            eq = PAPER_EXPERIMENT[k][0]
            mq, mt = PAPER_MODEL[k]
            model = "none" if mq is None else f"{mq} ({mt})"
            out.append(f"| {names[k]} | {mine} | {'~' if k == 1 else ''}{eq} | {model} |")
        return "\n".join(out) + "\n"

    def _q(self, t):
        return float(self.discharge_lps_at(t)) if self.discharge_lps_at is not None else float("nan")


def displacements(pos: np.ndarray) -> np.ndarray:
    """(T, n) distance [m] of each stone from its place in the first snapshot; pos is (T, n, 2)."""
    pos = np.asarray(pos, float)
    return np.linalg.norm(pos - pos[0:1], axis=2)


def removal_times(times, pos, diameters, active=None, fixed=None, factor: float = 1.0) -> np.ndarray:
    """(n,) first snapshot time [s] at which each stone counts as removed; nan if never."""
    times = np.asarray(times, float)
    disp = displacements(pos)
    removed = disp > factor * np.asarray(diameters, float)[None, :]
    if active is not None:
        removed |= ~np.asarray(active, bool)
    if fixed is not None:
        removed &= ~np.asarray(fixed, bool)[None, :]
    first = np.argmax(removed, axis=0)
    out = times[first].astype(float)
    out[~removed.any(axis=0)] = np.nan
    return out


def find_bursts(removal_t: np.ndarray, gap: float, min_stones: int):
    """(stages, isolated): lists of index lists, split where sorted removal times jump by > gap."""
    idx = np.flatnonzero(np.isfinite(removal_t))
    idx = idx[np.argsort(removal_t[idx], kind="stable")]
    groups: List[List[int]] = []
    for i in idx:
        if groups and removal_t[i] - removal_t[groups[-1][-1]] <= gap:
            groups[-1].append(int(i))
        else:
            groups.append([int(i)])
    stages = [g for g in groups if len(g) >= min_stones]
    isolated = [i for g in groups if len(g) < min_stones for i in g]
    return stages, isolated


def classify_regions(x0: np.ndarray, weir, half_width: float) -> np.ndarray:
    """Region of each initial x [m] on the weir: upstream slope, crest, shoulder, downstream slope."""
    x0 = np.asarray(x0, float)
    out = np.full(x0.shape, "crest", dtype=object)
    out[x0 < weir.x_crest_up] = "upstream slope"
    out[np.abs(x0 - weir.x_crest_down) <= half_width] = "shoulder"
    out[x0 > weir.x_crest_down + half_width] = "downstream slope"
    return out


def surface_profile(pos: np.ndarray, radius: np.ndarray, x_bins: np.ndarray, active=None) -> np.ndarray:
    """Top [m] of the highest stone above each x in x_bins; pos (T, n, 2) -> (T, nb); nan = no stone."""
    pos = np.asarray(pos, float)
    r = np.asarray(radius, float)[None, :, None]
    dx = x_bins[None, None, :] - pos[:, :, 0:1]
    h2 = r * r - dx * dx
    top = np.where(h2 > 0, pos[:, :, 1:2] + np.sqrt(np.clip(h2, 0, None)), -np.inf)
    if active is not None:
        top = np.where(np.asarray(active, bool)[:, :, None], top, -np.inf)
    best = top.max(axis=1)
    best[~np.isfinite(best)] = np.nan
    return best


def crest_level(pos, radius, weir, bin_width: float, active=None) -> np.ndarray:
    """(T,) mean over the crest span of the stones' top [m] (see the module's docstring)."""
    nb = max(1, int(round((weir.x_crest_down - weir.x_crest_up) / bin_width)))
    edges = np.linspace(weir.x_crest_up, weir.x_crest_down, nb + 1)
    prof = surface_profile(pos, radius, 0.5 * (edges[1:] + edges[:-1]), active)
    prof = np.where(np.isnan(prof), 0.0, prof)  # an empty bin has dropped to the bed
    return prof.mean(axis=1)


def analyse(times, pos, diameters, weir, discharge_lps_at: Callable, active=None, fixed=None,
            ramp_start: float = 0.0, criterion: Optional[StageCriterion] = None) -> FailureAnalysis:
    """Failure analysis of recorded stone trajectories.

    times (T,) [s]; pos (T, n, 2) [m]; diameters (n,) [m]; weir: the initial `scene.Weir`;
    discharge_lps_at: t [s] -> Q [l/s]; active (T, n) bool; fixed (n,) bool; ramp_start [s] is
    where the paper's clock starts.
    """
    c = criterion or StageCriterion()
    times = np.asarray(times, float)
    pos = np.asarray(pos, float)
    diameters = np.asarray(diameters, float)
    if pos.ndim != 3 or pos.shape[0] != times.size or pos.shape[1] != diameters.size or pos.shape[2] != 2:
        raise ValueError(f"pos has shape {pos.shape}, expected ({times.size}, {diameters.size}, 2)")
    disp = displacements(pos)
    t_rem = removal_times(times, pos, diameters, active, fixed, c.removal_factor)
    half = c.shoulder_half_width if c.shoulder_half_width is not None else float(diameters.mean())
    region = classify_regions(pos[0, :, 0], weir, half)
    groups, isolated = find_bursts(t_rem, c.gap, c.min_stones)
    stages = []
    for k, g in enumerate(groups, start=1):
        t0 = float(t_rem[g[0]])
        counts = {r: int(np.sum(region[g] == r)) for r in REGIONS if np.any(region[g] == r)}
        stages.append(Stage(number=k, start_time=t0, end_time=float(t_rem[g[-1]]), paper_time=t0 - ramp_start,
                            discharge_lps=float(discharge_lps_at(t0)), stones=list(g), region_counts=counts))
    crest = crest_level(pos, 0.5 * diameters, weir, float(diameters.mean()), active)
    removed_count = np.array([(t_rem <= t).sum() for t in times])
    return FailureAnalysis(times=times, displacement=disp, removal_time=t_rem, region=region, stages=stages,
                           isolated=isolated, crest_level=crest, criterion=c, ramp_start=ramp_start,
                           discharge_lps_at=discharge_lps_at, removed_count=removed_count)
