"""Measured floods: a hydrograph read from a CSV file, and the slow rise of ``--until-failure``.

**CSV file** (``hydrograph.kind = "csv"``, ``hydrograph.file`` relative to the scene file): two
comma-separated columns, a header naming each with its unit, then one row per reading:

    # gauge 4711, flood of 12 May (lines starting with '#' and blank lines are skipped)
    time_min,discharge_m3s
    0,0.010
    2.5,0.0135
    ...

Time columns: ``time_s``, ``time_min``, ``time_h``; discharge columns: ``discharge_lps`` (l/s),
``discharge_m3s`` (m3/s). Rules, each broken one a ValueError naming the file, the line and the
column: at least two rows, every value a finite number, times strictly increasing, discharges not
negative. The times are kept relative to the first row (the flood starts at the file's first reading).

In the run (scene.Hydrograph): the first discharge is held for ``spin_up_duration`` seconds (stones
held if ``hold_stones_during_spin_up``), then the file's readings follow, linearly interpolated, their
times multiplied by ``time_scale`` and their discharges by ``discharge_scale`` (1 and 1 by default:
the file as measured). The run lasts the spin-up plus the file's span (times ``time_scale``).

**Until failure** (``vofdem run SCENE --until-failure``, `until_failure_hydrograph`): the discharge
is held at the scene's first discharge of its rise for the spin-up, then raised linearly at
``hydrograph.until_failure_rate_lps_per_s`` up to the scene's largest discharge; the run stops at the
first destruction stage (analysis.py's definition), and its discharge is the weir's critical
discharge for this rate.
"""
from __future__ import annotations

import math
from pathlib import Path
from typing import List, Tuple

TIME_UNITS = {"time_s": 1.0, "time_min": 60.0, "time_h": 3600.0}  # to s
DISCHARGE_UNITS = {"discharge_lps": 1.0, "discharge_m3s": 1000.0}  # to l/s


def _fail(path: Path, line: int, column: int, name: str, what: str) -> ValueError:
    where = f"{path}, line {line}" + (f", column {column} ({name})" if column else "")
    return ValueError(f"hydrograph CSV {where}: {what}")


def _rows(path: Path):
    """(line number, cells) of the file's non-blank, non-comment lines."""
    try:
        text = path.read_text(encoding="utf-8")
    except OSError as e:
        raise ValueError(f"hydrograph.file: cannot read the hydrograph CSV {str(path)!r}: {e.strerror or e} (a scene "
                         f"of kind 'csv' reads its flood from the file unless hydrograph.times and "
                         f"hydrograph.discharge_lps hold it)") from None
    except UnicodeDecodeError:
        raise ValueError(f"hydrograph CSV {path}: not a text file (UTF-8)") from None
    for n, line in enumerate(text.splitlines(), start=1):
        s = line.strip()
        if s and not s.startswith("#"):
            yield n, [c.strip() for c in s.split(",")]


def _header(path: Path, n: int, cells: List[str]) -> Tuple[float, float, str, str]:
    if len(cells) != 2:
        raise _fail(path, n, 0, "", f"the header must name two columns, time and discharge with their units "
                                    f"(e.g. 'time_s,discharge_lps'), got {len(cells)}: {','.join(cells)!r}")
    t_name, q_name = (c.lower() for c in cells)
    if t_name not in TIME_UNITS:
        raise _fail(path, n, 1, cells[0], f"unknown time column; use one of {', '.join(TIME_UNITS)}")
    if q_name not in DISCHARGE_UNITS:
        raise _fail(path, n, 2, cells[1], f"unknown discharge column; use one of {', '.join(DISCHARGE_UNITS)}")
    return TIME_UNITS[t_name], DISCHARGE_UNITS[q_name], cells[0], cells[1]


def _number(path: Path, n: int, col: int, name: str, text: str) -> float:
    try:
        v = float(text)
    except ValueError:
        raise _fail(path, n, col, name, f"{text!r} is not a number") from None
    if not math.isfinite(v):
        raise _fail(path, n, col, name, f"{text!r} is not a finite number")
    return v


def read_hydrograph_csv(path) -> Tuple[List[float], List[float]]:
    """(times [s] from the first row, discharges [l/s]) of a hydrograph CSV file (see the module's
    docstring); ValueError naming the file, the line and the column of the first problem."""
    path = Path(path)
    rows = _rows(path)
    first = next(rows, None)
    if first is None:
        raise ValueError(f"hydrograph CSV {path}: the file is empty (it needs a header and two rows at least)")
    t_unit, q_unit, t_name, q_name = _header(path, *first)
    times: List[float] = []
    q: List[float] = []
    last_line = first[0]
    for n, cells in rows:
        last_line = n
        if len(cells) != 2:
            raise _fail(path, n, 0, "", f"a row must hold two values (time, discharge), got {len(cells)}")
        t = _number(path, n, 1, t_name, cells[0]) * t_unit
        v = _number(path, n, 2, q_name, cells[1])
        if v < 0:
            raise _fail(path, n, 2, q_name, f"discharge {cells[1]} is negative (allowed: >= 0)")
        if times and t <= times[-1]:
            raise _fail(path, n, 1, t_name, f"time {cells[0]} does not come after the previous row's "
                                            f"(times must increase strictly)")
        times.append(t)
        q.append(v * q_unit)
    if len(times) < 2:
        raise ValueError(f"hydrograph CSV {path}, line {last_line}: {len(times)} row(s) of readings; a hydrograph "
                         f"needs at least two")
    t0 = times[0]
    return [t - t0 for t in times], q


def until_failure_hydrograph(h):
    """The hydrograph of ``--until-failure`` for the scene's hydrograph h: the same spin-up at the first
    discharge of its rise, then a linear rise at h.until_failure_rate_lps_per_s up to its largest
    discharge. ValueError when the scene's discharge never rises above its start."""
    import copy

    import numpy as np

    t, q = h.table()
    q_start = float(h.discharge_lps_at(h.ramp_start))
    q_max = float(np.max(q)) * 1e3
    if not q_max > q_start * (1.0 + 1e-9):
        raise ValueError(f"--until-failure: the scene's discharge never rises above its start ({q_start:.4g} l/s), "
                         f"so there is nothing to raise it to; give the hydrograph a larger discharge")
    out = copy.deepcopy(h)
    out.kind = "until_failure"
    out.function = None
    out.discharge_start_lps, out.discharge_end_lps = q_start, q_max
    out.spin_up_duration = h.spin_up_duration if h.kind in ("ramp", "csv", "until_failure") else 0.0
    out.ramp_duration = (q_max - q_start) / h.until_failure_rate_lps_per_s
    return out


def critical_discharge(analysis, scene) -> dict:
    """The design answer of an until-failure run: the discharge of its first destruction stage.

    Returns dict(status, q_lps, q_per_width_lps_m, q_per_width_m2s, resolution_lps, first_lps, last_lps):
    status 'stage' (q_lps: the stage's discharge), 'at release' (the weir failed as soon as it was
    loaded: the critical discharge is q_lps = the first discharge or below), or 'none' (no stage up to
    the run's last discharge q_lps: the critical discharge is above it). resolution_lps: the rise
    between two snapshots, the uncertainty of q_lps from the snapshot interval."""
    a, h = analysis, scene.hydrograph
    release = h.ramp_start if h.hold_stones_during_spin_up and h.ramp_start > a.times[0] else float(a.times[0])
    after = a.times[a.times > release + 1e-9]
    first = float(a.discharge_lps_at(float(after[0]))) if after.size else float(a.discharge_lps_at(release))
    last = float(a.discharge_lps_at(float(a.times[-1])))
    if a.stages:
        st = a.stages[0]
        status = "at release" if after.size and st.start_time <= after[0] + 1e-9 else "stage"
        q = float(st.discharge_lps)
    else:
        status, q = "none", last
    rate = h.until_failure_rate_lps_per_s if h.kind == "until_failure" else float("nan")
    width = scene.flume.width
    return dict(status=status, q_lps=q, q_per_width_lps_m=q / width, q_per_width_m2s=q * 1e-3 / width,
                resolution_lps=rate * scene.output.snapshot_interval, first_lps=first, last_lps=last,
                stones=int(a.stages[0].n_stones) if a.stages else 0, width_m=width)


def until_failure_markdown(analysis, scene) -> str:
    """The critical discharge of an until-failure run in words and numbers (until_failure.md)."""
    c = critical_discharge(analysis, scene)
    h = scene.hydrograph
    per = f"{c['q_per_width_lps_m']:.2f} l/s per m of width ({c['q_per_width_m2s']:.4g} m2/s; width {c['width_m']:g} m)"
    if c["status"] == "stage":
        answer = (f"**Critical discharge: {c['q_lps']:.2f} l/s** in total, {per}: the first destruction stage "
                  f"({c['stones']} stones when the run stopped) began there.")
    elif c["status"] == "at release":
        answer = (f"**Critical discharge: {c['q_lps']:.2f} l/s or below** ({per}): the weir lost a stage "
                  f"({c['stones']} stones) as soon as it was loaded, at the first discharge of the rise; a start "
                  f"at a lower discharge (hydrograph) would say how far below.")
    else:
        cut = "" if c["last_lps"] >= h.discharge_end_lps - 1e-9 else (
            f" (the run ended before the largest discharge, {h.discharge_end_lps:g} l/s)")
        answer = (f"**Critical discharge: above {c['q_lps']:.2f} l/s** ({per}): no destruction stage up to the "
                  f"run's last discharge{cut}.")
    return "\n".join([
        f"# Until failure: {scene.name}", "",
        f"The discharge rose from {h.discharge_start_lps:g} l/s at {h.until_failure_rate_lps_per_s:g} l/s per s "
        f"(after a {h.spin_up_duration:g} s spin-up) up to {h.discharge_end_lps:g} l/s at most; the run stops at the "
        f"first destruction stage (at least two stones removed, pauses under 3 s).", "", answer, "",
        f"Resolution: a snapshot every {scene.output.snapshot_interval:g} s, so {c['resolution_lps']:.3g} l/s of "
        f"rise between two; the answer belongs to this rate (a slower rise gives the stones more time) and to "
        f"this packing (seed {scene.seed}; an ensemble over seeds gives its spread).", ""])


def ensemble_until_failure_markdown(members, widths: dict, n_boot: int = 1000, seed: int = 0) -> str:
    """The critical discharge's distribution over an until-failure ensemble (until_failure.md of the
    ensemble): per parameter combination, the fragility of the first stage (fragility.py: censored
    empirical median, lognormal median and 16-84 % band), in total and per unit width. widths:
    {combination: flume width [m]}."""
    from .fragility import fragility_by_combination

    out = ["# Until failure: the critical discharge over the ensemble", "",
           "The critical discharge of a member is the discharge of its first destruction stage. Members "
           "without a stage are censored at their last discharge; members that failed as soon as they were "
           "loaded count at the first discharge or below (fragility.md's rules).", "",
           "| combination | members | with a stage (at the first discharge) | empirical median [l/s] | "
           "lognormal median [16-84 %] [l/s] | per unit width: median [16-84 %] [l/s per m] |",
           "|---|---|---|---|---|---|"]
    for combo, evs in fragility_by_combination(members, n_boot, seed).items():
        e = next(x for x in evs if x.event == "stage1")
        r, w = e.row(), widths.get(combo, float("nan"))
        emp = r["empirical_median_lps"]
        if e.fit is None:
            fit = per = "no fit"
        else:
            fit = f"{r['fit_median_lps']:.2f} [{r['fit_q16_lps']:.2f}-{r['fit_q84_lps']:.2f}]"
            per = f"{r['fit_median_lps'] / w:.2f} [{r['fit_q16_lps'] / w:.2f}-{r['fit_q84_lps'] / w:.2f}]"
        out.append(f"| {combo or 'all members'} | {r['members']} | {r['happened']} ({r['at_first_discharge']}) | "
                   f"{'not reached' if emp is None else f'{emp:.2f}'} | {fit} | {per} |")
    return "\n".join(out) + "\n"
