"""Failure analysis of a rubble mound weir from its stones' trajectories.

Definitions (all from the recorded snapshots of stone positions):

* **Displacement** of stone i at time t: ``|x_i(t) - x_i(0)|`` [m].
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

Stages are compared by order with the scene's reference data (`reference.Reference`), when it has
any: our stage k against its stage k. The clock of the rise (simulation time minus the spin-up) is
shown only when the reference gives times on it.
"""
from __future__ import annotations

import csv
import io
from dataclasses import dataclass, field
from typing import Callable, Dict, List, Optional

import numpy as np

from .reference import Reference, format_lps

REGIONS = ("upstream slope", "crest", "shoulder", "downstream slope")
STAGE_NAMES = {1: "first stage", 2: "second stage", 3: "third stage"}


@dataclass
class StageCriterion:
    """Parameters of the removal and burst definitions (see the module's docstring)."""

    removal_factor: float = 1.0  # removed once moved more than this many own diameters [-]
    gap: float = 3.0  # [s] a pause between removals longer than this separates two stages
    min_stones: int = 2  # a burst needs at least this many removals to count as a stage
    shoulder_half_width: Optional[float] = None  # [m]; default: one mean diameter


@dataclass
class Stage:
    """A destruction stage: stones removed together, with pauses no longer than the criterion's (times [s],
    discharge [l/s])."""

    number: int
    start_time: float  # simulation time of its first removal [s]
    end_time: float  # simulation time of its last removal [s]
    clock_time: float  # start on the clock of the rise (simulation time - spin-up) [s]
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
    """What a run's stones did: their displacements [m] and removal times [s] over the snapshots, the stages,
    the isolated removals and the crest level [m] (made by `analyse`)."""

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
    reference: Optional[Reference] = None  # the scene's reference data; None or empty: no comparison

    @property
    def crest_lowering(self) -> np.ndarray:
        """Drop of the crest level since the first snapshot [m] (positive = lower)."""
        return self.crest_level[0] - self.crest_level

    @property
    def first_removal(self) -> Optional[float]:
        t = self.removal_time[np.isfinite(self.removal_time)]
        return float(t.min()) if t.size else None

    # ------------------------------------------------------------------ tables
    @property
    def _ref(self) -> Optional[Reference]:
        return self.reference if self.reference is not None and self.reference.given else None

    def stage_rows(self) -> List[Dict[str, object]]:
        """One row per detected stage, with the reference's values for the stage of the same order (only
        the columns the reference has)."""
        ref = self._ref
        rows = []
        for s in self.stages:
            row: Dict[str, object] = {"stage": s.number, "start_s": round(s.start_time, 3)}
            if ref is not None and ref.has_times:
                row["clock_s"] = round(s.clock_time, 3)
            row.update(discharge_lps=round(s.discharge_lps, 3), stones=s.n_stones, location=s.location)
            for who, model in (("observed", False), ("model", True)):
                if ref is None or not (ref.has_model if model else ref.has_observed):
                    continue
                q, t = ref.stages(model).get(s.number, (None, None))
                row[f"{who}_lps"] = q
                if ref.has_times:
                    row[f"{who}_clock_s"] = t
            rows.append(row)
        return rows

    def stage_table_csv(self) -> str:
        ref = self._ref
        cols = ["stage", "start_s"] + (["clock_s"] if ref is not None and ref.has_times else []) + [
            "discharge_lps", "stones", "location"]
        for who, has in (("observed", ref is not None and ref.has_observed), ("model", ref is not None and ref.has_model)):
            if has:
                cols += [f"{who}_lps"] + ([f"{who}_clock_s"] if ref.has_times else [])
        buf = io.StringIO()
        w = csv.DictWriter(buf, fieldnames=cols, lineterminator="\n")
        w.writeheader()
        for r in self.stage_rows():
            w.writerow({k: ("" if v is None else v) for k, v in r.items()})
        return buf.getvalue()

    def stage_table_markdown(self) -> str:
        """Stages found, then (when the scene has reference data) a comparison with it."""
        c, ref = self.criterion, self._ref
        clock = ref is not None and ref.has_times
        head = (f"Removal: moved more than {c.removal_factor:g} diameter(s); stage: >= {c.min_stones} removals "
                f"with pauses <= {c.gap:g} s.")
        if clock:
            head += f" Clock of the rise = simulation time - {self.ramp_start:g} s."
        out = [head, "", "| stage | start [s] | " + ("clock [s] | " if clock else "") + "Q [l/s] | stones | where |",
               "|---|---|" + ("---|" if clock else "") + "---|---|---|"]
        for s in self.stages:
            out.append(f"| {s.number} | {s.start_time:.1f} | " + (f"{s.clock_time:.1f} | " if clock else "")
                       + f"{s.discharge_lps:.2f} | {s.n_stones} | {s.location} |")
        if not self.stages:
            out.append("| - | no stage | " + ("| " if clock else "") + "| 0 | |")
        out += ["", f"Isolated removals (not in a stage): {len(self.isolated)}. "
                f"Stones removed in total: {int(np.isfinite(self.removal_time).sum())} of {self.removal_time.size}. "
                f"Final crest lowering: {1e3 * float(self.crest_lowering[-1]):.1f} mm.", ""]
        if ref is not None:
            out += self._comparison_markdown(ref) + [""]
        return "\n".join(out) + "\n"

    def _comparison_markdown(self, ref: Reference) -> List[str]:
        """The events of this run next to the reference's observed and modelled ones."""
        clock = ref.has_times
        sources = [(False, "observed")] if ref.has_observed else []
        sources += [(True, "model")] if ref.has_model else []
        unit = "Q [l/s] (clock [s])" if clock else "Q [l/s]"
        out = ["Compared with " + "; ".join(f"{w}: {ref.model_citation if m else ref.citation}" for m, w in sources)
               + ".", "", f"| event | this run: {unit} | " + " | ".join(f"{w}: {unit}" for _, w in sources) + " |",
               "|---|---|" + "---|" * len(sources)]
        fr = self.first_removal
        mine = "none" if fr is None else (f"{self._q(fr):.2f}" + (f" ({fr - self.ramp_start:.1f})" if clock else ""))
        refs = [format_lps(ref.model_first_removal_lps if m else ref.first_removal_lps) for m, _ in sources]
        out.append(f"| first removal of any stone | {mine} | " + " | ".join(refs) + " |")
        numbers = [k for m, _ in sources for k in ref.stages(m)]
        for k in range(1, max(numbers + [len(self.stages), 1]) + 1):
            ours = next((s for s in self.stages if s.number == k), None)
            mine = "none" if ours is None else (f"{ours.discharge_lps:.2f}" + (f" ({ours.clock_time:.1f})" if clock
                                                                              else ""))
            cells = [format_lps(*ref.stages(m).get(k, (None, None))) for m, _ in sources]
            out.append(f"| {STAGE_NAMES.get(k, f'stage {k}')} | {mine} | " + " | ".join(cells) + " |")
        for m, w in sources:
            note = ref.model_note if m else ref.note
            if note:
                out += ["", f"{w.capitalize()}: {note}."]
        return out

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
            ramp_start: float = 0.0, criterion: Optional[StageCriterion] = None,
            reference: Optional[Reference] = None) -> FailureAnalysis:
    """Failure analysis of recorded stone trajectories.

    times (T,) [s]; pos (T, n, 2) [m]; diameters (n,) [m]; weir: the initial `scene.Weir`;
    discharge_lps_at: t [s] -> Q [l/s]; active (T, n) bool; fixed (n,) bool; ramp_start [s] is
    where the clock of the rise starts; reference: the scene's reference data (compared in the tables).
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
        stages.append(Stage(number=k, start_time=t0, end_time=float(t_rem[g[-1]]), clock_time=t0 - ramp_start,
                            discharge_lps=float(discharge_lps_at(t0)), stones=list(g), region_counts=counts))
    crest = crest_level(pos, 0.5 * diameters, weir, float(diameters.mean()), active)
    removed_count = np.array([(t_rem <= t).sum() for t in times])
    return FailureAnalysis(times=times, displacement=disp, removal_time=t_rem, region=region, stages=stages,
                           isolated=isolated, crest_level=crest, criterion=c, ramp_start=ramp_start,
                           discharge_lps_at=discharge_lps_at, removed_count=removed_count, reference=reference)
