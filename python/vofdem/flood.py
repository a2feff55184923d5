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
discharge for this rate (reports.py's `critical_discharge` and `until_failure_markdown`).
"""
from __future__ import annotations

import math
from dataclasses import dataclass, field
from pathlib import Path
from typing import Callable, List, Optional, Tuple

from .schema import _Section, _check_list, _choice, _flag, _fmt, _p

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


@dataclass
class Hydrograph(_Section):
    """Inflow discharge Q(t) at x = 0.

    kind 'ramp' (the paper's): a spin-up at `discharge_start_lps` for `spin_up_duration` seconds (the
    flow settles to a steady state over the weir, stones held in place if `hold_stones_during_spin_up`;
    before it, if `settle_in_still_water`, the packed stones settle in the still pool: builder.settle_stones),
    then a linear rise to `discharge_end_lps` over `ramp_duration`. The clock of the rise starts at the
    ramp: clock = simulation time - spin_up_duration (`ramp_start`).
    kind 'table': piecewise-linear through (`times` [s], `discharge_lps` [l/s]), spin-up included.
    kind 'csv': a measured flood read from the CSV file `file` (relative to the scene file; format in
    flood.py): its first discharge held for `spin_up_duration` (stones held as for a ramp), then its
    readings, times x `time_scale`, discharges x `discharge_scale`. The file's content is kept in
    `times` [s from its first row] and `discharge_lps` [l/s]; a scene written by vofdem (a run's
    scene.toml) carries it there, and the file is then not read again.
    kind 'until_failure' (made by `Scene.until_failure()`, ``vofdem run --until-failure``): a ramp from
    `discharge_start_lps` to `discharge_end_lps` at `until_failure_rate_lps_per_s`; the run stops at
    the first destruction stage.
    From Python, `function` (a callable t [s] -> Q [m3/s]) overrides all; it is sampled into a
    table every `table_interval` seconds for the solver.
    """

    kind: str = _choice("ramp", ("ramp", "table", "csv", "until_failure"),
                        "'ramp' (spin-up then linear rise), 'table', 'csv' (a measured flood from `file`) or "
                        "'until_failure' (a slow ramp stopped at the first stage)")
    discharge_start_lps: float = _p(10.0, "discharge", 0.1, 1000.0, "spin-up and ramp start discharge [l/s]")
    discharge_end_lps: float = _p(25.0, "discharge", 0.1, 1000.0, "discharge at the end of the ramp [l/s]")
    ramp_duration: float = _p(120.0, "time", 0.0, 1e5, "duration of the linear rise [s]; paper 120", "(]")
    spin_up_duration: float = _p(20.0, "time", 0.0, 1e4, "time at the start discharge before the ramp [s]")
    hold_stones_during_spin_up: bool = _flag(True, "stones do not move during the spin-up")
    settle_in_still_water: bool = _flag(True, "before the first flow step the packed stones settle in the still "
                                        "water (each buoyant by the water it sits in, the flow frozen) until "
                                        "at rest or settle_time_max")
    settle_time_max: float = _p(5.0, "time", 0.0, 600.0, "cap on the settling in still water [s] (simulated time "
                                "of the stones alone)", "(]")
    times: List[float] = field(default_factory=list, metadata=dict(doc="table times [s] (kind = 'table'; 'csv': "
                                                                       "the file's, from its first row)"))
    discharge_lps: List[float] = field(default_factory=list, metadata=dict(doc="table discharges [l/s]"))
    file: str = field(default="", metadata=dict(text=True, doc="the flood's CSV file (kind = 'csv'), relative to "
                                                               "the scene file; header e.g. time_s,discharge_lps"))
    time_scale: float = _p(1.0, None, 0.0, 1e3, "kind 'csv': the file's times are multiplied by this [-]", "(]")
    discharge_scale: float = _p(1.0, None, 0.0, 1e6, "kind 'csv': the file's discharges are multiplied by this "
                                "[-]", "(]")
    until_failure_rate_lps_per_s: float = _p(0.125, "discharge rate", 0.0, 100.0, "rise of --until-failure [l/s per s]; "
                                             "0.125 = the paper's 15 l/s in 120 s", "(]")
    table_interval: float = _p(0.5, "time", 0.0, 100.0, "sampling step of `function` into a table [s]", "(]")
    function: Optional[Callable[[float], float]] = field(default=None, compare=False, metadata=dict(
        doc="Python only: Q(t) in m3/s, overrides kind", python_only=True))
    base_dir: Optional[str] = field(default=None, compare=False, metadata=dict(
        doc="Python only: the directory `file` is relative to (the scene file's; default the working one)",
        python_only=True))

    def validate(self, prefix: str = "hydrograph") -> None:
        self._validate_fields(prefix)
        if not isinstance(self.file, str) or "\n" in self.file:
            raise ValueError(f"{prefix}.file = {self.file!r} must be a file name (text)")
        if self.kind == "csv" and self.function is None and not self.times:
            self._read_csv(prefix)
        # the table's lists are checked under any kind: a malformed key is an error even where it is ignored
        q_md = {"lo": 0.0, "hi": 1000.0 if self.kind != "csv" else 1e9, "closed": "[]", "kind": "discharge"}
        t_md = {"lo": 0.0, "hi": 1e6, "closed": "[]", "kind": "time"}
        _check_list(f"{prefix}.times", self.times, t_md)
        _check_list(f"{prefix}.discharge_lps", self.discharge_lps, q_md)
        if self.function is not None:
            if not callable(self.function):
                raise ValueError(f"{prefix}.function must be a callable t [s] -> Q [m3/s]")
            return
        if self.kind in ("table", "csv"):
            if len(self.times) < 2 or len(self.times) != len(self.discharge_lps):
                raise ValueError(f"{prefix}.times and {prefix}.discharge_lps must be lists of the same "
                                 f"length >= 2 (got {len(self.times)} and {len(self.discharge_lps)})")
            if any(b <= a for a, b in zip(self.times, self.times[1:])):
                raise ValueError(f"{prefix}.times must be strictly increasing")
        if self.kind == "csv":
            self._check_csv(prefix)
        if self.kind == "until_failure":
            self._check_until_failure(prefix)

    def _read_csv(self, prefix: str) -> None:
        if not self.file.strip():
            raise ValueError(f"{prefix}.file is required when {prefix}.kind = 'csv' (the flood's CSV file, "
                             f"relative to the scene file)")
        path = Path(self.base_dir or ".") / self.file
        self.times, self.discharge_lps = read_hydrograph_csv(path)

    def _check_csv(self, prefix: str) -> None:
        if self.times[0] != 0.0:
            raise ValueError(f"{prefix}.times[0] = {_fmt(self.times[0])}: a CSV flood's times start at 0 (its first row)")
        q_max = max(self.discharge_lps) * self.discharge_scale
        if q_max > 1000.0:
            raise ValueError(f"{prefix}.discharge_scale = {_fmt(self.discharge_scale)}: the flood of {self.file or 'the file'} "
                             f"peaks at {q_max:.6g} l/s, outside the allowed range [0, 1000] l/s (scale a field "
                             f"flood to the flume with discharge_scale)")
        span = self.times[-1] * self.time_scale
        if span > 1e6:
            raise ValueError(f"{prefix}.time_scale = {_fmt(self.time_scale)}: the flood lasts {span:.6g} s, outside "
                             f"the allowed range (0, 1e6] s")

    def _check_until_failure(self, prefix: str) -> None:
        rise = self.discharge_end_lps - self.discharge_start_lps
        if not rise > 0:
            raise ValueError(f"{prefix}.discharge_end_lps = {_fmt(self.discharge_end_lps)} must be above "
                             f"{prefix}.discharge_start_lps = {_fmt(self.discharge_start_lps)} for kind 'until_failure'")
        duration = rise / self.until_failure_rate_lps_per_s
        if duration > 1e5:
            raise ValueError(f"{prefix}.until_failure_rate_lps_per_s = {_fmt(self.until_failure_rate_lps_per_s)} "
                             f"makes the rise last {duration:.4g} s, outside the allowed range (0, 1e5] s")
        self.ramp_duration = duration

    @property
    def ramp_start(self) -> float:
        """Simulation time [s] at which the clock of the rise starts (end of the spin-up)."""
        if self.function is None and self.kind in ("ramp", "csv", "until_failure"):
            return self.spin_up_duration
        return 0.0

    @property
    def end_time(self) -> float:
        """Simulation time [s] at the end of the hydrograph."""
        if self.function is None and self.kind == "table":
            return float(self.times[-1])
        if self.function is None and self.kind == "csv":
            return self.spin_up_duration + float(self.times[-1]) * self.time_scale
        return self.spin_up_duration + self.ramp_duration

    @property
    def stops_at_first_stage(self) -> bool:
        """Whether the run ends at the first destruction stage (kind 'until_failure')."""
        return self.function is None and self.kind == "until_failure"

    def discharge(self, t):
        """Q [m3/s] at simulation time t [s] (scalar or array)."""
        import numpy as np

        if self.function is not None:
            return np.vectorize(lambda s: float(self.function(s)))(t) if np.ndim(t) else float(self.function(t))
        if self.kind == "table":
            q = np.interp(t, self.times, self.discharge_lps) * 1e-3
        elif self.kind == "csv":
            tc = (np.asarray(t, float) - self.spin_up_duration) / self.time_scale
            q = np.interp(tc, self.times, self.discharge_lps) * (1e-3 * self.discharge_scale)
        else:
            s = np.clip((np.asarray(t, float) - self.spin_up_duration) / self.ramp_duration, 0.0, 1.0)
            q = (self.discharge_start_lps + (self.discharge_end_lps - self.discharge_start_lps) * s) * 1e-3
        return float(q) if np.ndim(q) == 0 else q

    def discharge_lps_at(self, t):
        """Q [l/s] at simulation time t [s]."""
        return self.discharge(t) * 1e3

    def table(self, t_end: Optional[float] = None):
        """(times [s], Q [m3/s]) describing Q(t) exactly for a piecewise-linear solver input."""
        import numpy as np

        t_end = self.end_time if t_end is None else t_end
        if self.function is not None:
            n = max(2, int(math.ceil(t_end / self.table_interval)) + 1)
            t = np.linspace(0.0, t_end, n)
        elif self.kind == "table":
            t = np.asarray(self.times, float)
        elif self.kind == "csv":
            t = self.spin_up_duration + np.asarray(self.times, float) * self.time_scale
            if self.spin_up_duration > 0.0:
                t = np.concatenate([[0.0], t])
            if t_end > t[-1]:
                t = np.append(t, t_end)
        else:
            t = np.array([0.0, self.spin_up_duration, self.spin_up_duration + self.ramp_duration])
            if self.spin_up_duration == 0.0:
                t = t[1:]
            if t_end > t[-1]:
                t = np.append(t, t_end)
        return t, np.asarray(self.discharge(t), float)

    def source(self) -> str:
        """What the discharge follows, in words (for figures and reports)."""
        if self.function is not None:
            return "a Python function"
        if self.kind == "csv":
            scale = "" if self.time_scale == 1.0 and self.discharge_scale == 1.0 else (
                f", times x {self.time_scale:g}, discharges x {self.discharge_scale:g}")
            return f"measured flood {self.file or '(CSV)'}{scale}"
        if self.kind == "table":
            return "a table"
        rise = f"{self.discharge_start_lps:g} -> {self.discharge_end_lps:g} l/s"
        if self.kind == "until_failure":
            return f"until failure: {rise} at {self.until_failure_rate_lps_per_s:g} l/s per s"
        return f"ramp {rise} over {self.ramp_duration:g} s"


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
