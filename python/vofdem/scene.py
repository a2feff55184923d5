"""Scenes: everything a run of a rubble mound weir needs, from Python or from a TOML file.

A scene is a tree of small dataclasses (flume, weir, stones, hydrograph, grid, numerics, effects,
output) plus a seed. Every number is SI unless its name says otherwise: angles end in ``_deg``,
discharges in ``_lps`` (litres per second). In a TOML file a number may also carry its unit as a
string, e.g. ``diameter = "4.8 cm"`` or ``discharge_start_lps = "0.01 m3/s"``; it is converted to the
unit of the field, and a unit of the wrong kind (a length for a discharge) is an error.

Coordinates: x along the flume from the inflow boundary (x = 0) to the outflow end (x = length),
z upwards from the bed (z = 0). The weir is a trapezoid standing on the bed whose upstream toe is at
``weir.toe_x``.

Validation raises ValueError with the parameter's dotted name, the value and the allowed range;
unknown keys in a file are refused with the closest valid key suggested.
"""
from __future__ import annotations

import copy
import dataclasses
import difflib
import math
import re
from dataclasses import dataclass, field
from typing import Any, Callable, Dict, List, Optional, Sequence, Tuple

try:  # Python >= 3.11
    import tomllib as _toml
except ModuleNotFoundError:  # pragma: no cover - Python 3.9/3.10
    import tomli as _toml  # type: ignore[no-redef]

# units a value given as a string may carry, by kind, as factors to the SI unit of that kind
_UNITS: Dict[str, Dict[str, float]] = {
    "length": {"m": 1.0, "cm": 1e-2, "mm": 1e-3, "km": 1e3},
    "angle": {"deg": 1.0, "degree": 1.0, "degrees": 1.0, "rad": 180.0 / math.pi},  # to degrees
    "discharge": {"l/s": 1.0, "lps": 1.0, "m3/s": 1e3, "m^3/s": 1e3},  # to l/s
    "time": {"s": 1.0, "ms": 1e-3, "min": 60.0, "h": 3600.0},
    "density": {"kg/m3": 1.0, "kg/m^3": 1.0, "g/cm3": 1e3, "g/cm^3": 1e3},
}
# the unit a field of each kind is stored in
_BASE_UNIT = {"length": "m", "angle": "deg", "discharge": "l/s", "time": "s", "density": "kg/m3"}


def _p(default, kind: Optional[str], lo: float, hi: float, doc: str, closed: str = "[]"):
    """A numeric parameter: unit kind, allowed range [lo, hi] (closed='()' etc. for open ends)."""
    return field(default=default, metadata=dict(kind=kind, lo=lo, hi=hi, closed=closed, doc=doc))


def _choice(default, choices: Sequence[str], doc: str):
    return field(default=default, metadata=dict(choices=tuple(choices), doc=doc))


def _flag(default: bool, doc: str):
    return field(default=default, metadata=dict(flag=True, doc=doc))


def _fmt(v: float) -> str:
    return repr(float(v)) if isinstance(v, float) else str(v)


def _range_text(md) -> str:
    lo, hi, c = md["lo"], md["hi"], md["closed"]
    unit = _BASE_UNIT.get(md["kind"], "")
    return f"{c[0]}{_fmt(lo)}, {_fmt(hi)}{c[1]}" + (f" {unit}" if unit else "")


def _check_number(name: str, value, md) -> float:
    if isinstance(value, bool) or not isinstance(value, (int, float)):
        raise ValueError(f"{name} = {value!r} must be a number in {_range_text(md)}")
    v = float(value)
    lo, hi, c = md["lo"], md["hi"], md["closed"]
    ok = math.isfinite(v) and (v >= lo if c[0] == "[" else v > lo) and (v <= hi if c[1] == "]" else v < hi)
    if not ok:
        hint = ""
        if md["kind"] == "discharge" and v > hi:
            hint = " (discharges ending in _lps are in l/s; write e.g. \"0.01 m3/s\" to give m3/s)"
        elif md["kind"] == "discharge" and 0 < v < 0.5:
            hint = " (looks like m3/s; this field is in l/s)"
        elif md["kind"] == "length" and v > hi:
            hint = " (lengths are in metres; write e.g. \"4.8 cm\" to give another unit)"
        elif md["kind"] == "angle" and 0 < v < 1.6 and lo > 1.6:
            hint = " (angles ending in _deg are in degrees; this looks like radians)"
        raise ValueError(f"{name} = {_fmt(value)} is outside the allowed range {_range_text(md)}{hint}")
    return v


def _check_list(name: str, value, md: Optional[dict] = None) -> None:
    """A list field: a list (a TOML array) whose entries are numbers, in md's range if given. Checked
    whatever the section's kind, so a key the kind ignores is still refused when it is malformed."""
    if not isinstance(value, (list, tuple)):
        raise ValueError(f"{name} = {value!r} must be a list of numbers")
    for j, v in enumerate(value):
        if md is None:
            if isinstance(v, bool) or not isinstance(v, (int, float)) or not math.isfinite(v):
                raise ValueError(f"{name}[{j}] = {v!r} must be a finite number")
        else:
            _check_number(f"{name}[{j}]", v, md)


def _parse_quantity(name: str, value, kind: Optional[str]):
    """Converts '4.8 cm' to the field's unit; numbers pass unchanged."""
    if not isinstance(value, str):
        return value
    m = re.fullmatch(r"\s*([-+0-9.eE]+)\s*([A-Za-z/^0-9]*)\s*", value)
    if m is None:
        raise ValueError(f"{name} = {value!r} is not a number or a number with a unit")
    number, unit = float(m.group(1)), m.group(2)
    if kind is None:
        if unit:
            raise ValueError(f"{name} = {value!r}: this parameter is dimensionless, it takes no unit")
        return number
    if unit == "":
        return number
    table = _UNITS[kind]
    if unit not in table:
        other = [k for k, t in _UNITS.items() if unit in t]
        what = f"'{unit}' is a unit of {other[0]}" if other else f"unknown unit '{unit}'"
        raise ValueError(f"{name} = {value!r}: {what}; {name.split('.')[-1]} is a {kind} "
                         f"(use one of {', '.join(table)})")
    return number * table[unit]


class _Section:
    """Field-by-field validation shared by the scene's sections."""

    def _validate_fields(self, prefix: str) -> None:
        for f in dataclasses.fields(self):
            md = f.metadata
            name = f"{prefix}.{f.name}"
            value = getattr(self, f.name)
            if "lo" in md:
                if value is None and f.default is None:
                    continue
                setattr(self, f.name, _check_number(name, value, md))
            elif "choices" in md:
                if value not in md["choices"]:
                    raise ValueError(f"{name} = {value!r} is not one of {', '.join(map(repr, md['choices']))}")
            elif "flag" in md:
                if not isinstance(value, bool):
                    raise ValueError(f"{name} = {value!r} must be true or false")


@dataclass
class Flume(_Section):
    """The computational flume: a 2D vertical slice of a flume of width B."""

    length: float = _p(3.681, "length", 0.2, 100.0, "domain length from inflow to outflow end [m]", "(]")
    width: float = _p(0.50, "length", 0.0, 10.0, "flume width B dividing the discharge [m]; usual 0.5", "(]")
    height: float = _p(0.45, "length", 0.05, 10.0, "domain height above the bed [m]", "(]")
    bed_slope: float = _p(0.0, None, -0.1, 0.1, "bed slope S0 = sin(angle) [-], positive falling downstream")
    outflow: str = _choice("free_overfall", ("free_overfall", "tailwater"),
                           "outflow at x = length: free overfall or a fixed tailwater level")
    tailwater_level: Optional[float] = _p(None, "length", 0.0, 10.0,
                                          "tailwater level above the bed [m] (outflow = 'tailwater')", "(]")

    def validate(self, prefix: str = "flume") -> None:
        self._validate_fields(prefix)
        if self.outflow == "tailwater":
            if self.tailwater_level is None:
                raise ValueError(f"{prefix}.tailwater_level is required when {prefix}.outflow = 'tailwater'")
            if self.tailwater_level >= self.height:
                raise ValueError(f"{prefix}.tailwater_level = {_fmt(self.tailwater_level)} is outside the "
                                 f"allowed range (0, {_fmt(self.height)}) m (below the domain top)")


@dataclass
class Weir(_Section):
    """A trapezoidal rubble mound weir standing on the bed.

    The paper gives the downstream slope (27 deg) only; height 0.25 m, crest 0.20 m and a 27 deg
    upstream slope are assumed defaults.
    """

    height: float = _p(0.25, "length", 0.0, 5.0, "weir height above the bed [m]; usual 0.25", "(]")
    crest_length: float = _p(0.20, "length", 0.0, 10.0, "horizontal crest length [m]; usual 0.20")
    upstream_slope_deg: float = _p(27.0, "angle", 5.0, 60.0, "upstream face angle to the bed [deg]")
    downstream_slope_deg: float = _p(27.0, "angle", 5.0, 60.0, "downstream face angle to the bed [deg]")
    toe_x: float = _p(1.0, "length", 0.0, 100.0, "x of the upstream toe [m]", "(]")

    def validate(self, prefix: str = "weir") -> None:
        self._validate_fields(prefix)

    @property
    def x_crest_up(self) -> float:
        """x of the upstream end of the crest [m]."""
        return self.toe_x + self.height / math.tan(math.radians(self.upstream_slope_deg))

    @property
    def x_crest_down(self) -> float:
        """x of the downstream end of the crest (the shoulder) [m]."""
        return self.x_crest_up + self.crest_length

    @property
    def x_toe_down(self) -> float:
        """x of the downstream toe [m]."""
        return self.x_crest_down + self.height / math.tan(math.radians(self.downstream_slope_deg))

    @property
    def base_length(self) -> float:
        return self.x_toe_down - self.toe_x

    def outline(self) -> Tuple[List[float], List[float]]:
        """The trapezoid's corners (x [m], z [m]) from the upstream toe to the downstream toe."""
        return ([self.toe_x, self.x_crest_up, self.x_crest_down, self.x_toe_down], [0.0, self.height, self.height, 0.0])

    def surface(self, x):
        """Height of the weir's surface above x [m] (0 outside the weir); x may be an array."""
        import numpy as np

        x = np.asarray(x, dtype=float)
        up = (x - self.toe_x) * math.tan(math.radians(self.upstream_slope_deg))
        down = (self.x_toe_down - x) * math.tan(math.radians(self.downstream_slope_deg))
        return np.clip(np.minimum(np.minimum(up, down), self.height), 0.0, None)


@dataclass
class Stones(_Section):
    """The weir's stones: discs in the x-z plane with the mass and area of spheres (``shape = 'disc'``), or
    convex polygons of quarried-stone form with the mass, inertia and projected area of the matching 3D
    stone (``shape = 'polygon'``; polygon.h). A polygon's ``diameter`` is its nominal diameter, that of the
    disc of equal area (the matching stone has the mass of the sphere of that diameter)."""

    diameter: float = _p(0.048, "length", 0.001, 0.5, "mean stone diameter [m]; the paper's 0.048", "[]")
    diameter_spread: float = _p(0.1, None, 0.0, 0.5, "diameters uniform in d (1 +- spread) [-]; 0 = one size")
    density: float = _p(2650.0, "density", 1000.0, 20000.0, "stone density [kg/m3]; usual 2650", "(]")
    friction_stone: float = _p(0.577, None, 0.0, 2.0, "stone-stone Coulomb friction [-]; paper 0.577")
    friction_wall: float = _p(0.176, None, 0.0, 2.0, "stone-wall Coulomb friction [-]; paper 0.176")
    rolling_friction: float = _p(0.0, None, 0.0, 1.0, "stone-stone rolling friction mu_r [-]: the rolling moment "
                                 "is capped at mu_r R* f_n (Ai et al. 2011, type C); 0 = none, the paper's discs")
    rolling_friction_wall: float = _p(0.0, None, 0.0, 1.0, "stone-wall rolling friction mu_r [-]; 0 = none")
    rolling_damping: float = _p(0.3, None, 0.0, 1.0, "rolling damping ratio eta_r [-] below full mobilisation; "
                                "usual 0.3")
    n_exp: float = _p(0.41, None, 0.0, 1.0, "measured porosity of the packing, eq. (11) [-]; paper 0.41", "()")
    k1: float = _p(200.0, None, 0.0, 1e4, "porous resistance coefficient k1, eq. (7) [-]; paper 200", "(]")
    k2: float = _p(2.8, None, 0.0, 100.0, "porous resistance coefficient k2, eq. (7) [-]; paper 2.8", "(]")
    added_mass_coefficient: float = _p(1.0, None, 0.0, 5.0, "C_M of M' = rho C_M V [-]; the paper's run 1.0")
    drag_model: str = _choice("sphere", ("sphere", "bed"),
                              "drag on the stones: 'sphere' (eqs. 16-18, the paper's) or 'bed' (the reaction of the "
                              "porous resistance of eqs. 5-7 on the stones, rho n R per bulk volume)")
    porosity_mapping: str = _choice("paper", ("paper", "bulk"),
                                    "eq. (11) with n_exp inside each disc ('paper') or with the inner porosity "
                                    "1 - (1 - n_exp) / phi that makes the weir's mean porosity n_exp ('bulk'; phi: the "
                                    "packing's 2D solid fraction)")
    fix_bottom_layer: bool = _flag(True, "stones touching the bed are fixed to it (as in the paper)")
    shape: str = _choice("disc", ("disc", "polygon"),
                         "stone shape: 'disc' (the paper's) or 'polygon' (random convex polygons of quarried-stone "
                         "form, one per stone from the seed)")
    polygon_vertices_min: int = _p(5, None, 3, 16, "fewest vertices of a polygon stone [-]; usual 5")
    polygon_vertices_max: int = _p(8, None, 3, 16, "most vertices of a polygon stone [-]; usual 8")
    aspect_ratio: float = _p(1.5, None, 1.0, 3.0, "length / thickness of a polygon stone's section [-]; usual 1.5")
    polygon_radial_jitter: float = _p(0.2, None, 0.0, 0.5, "polygon vertex radii 1 +- jitter before the hull [-]; "
                                      "usual 0.2")
    positions: List[List[float]] = field(default_factory=list, metadata=dict(
        doc="explicit stone centres [[x m, z m], ...] instead of packing the weir; empty = pack"))
    diameters: List[float] = field(default_factory=list, metadata=dict(
        doc="diameters [m] of the explicit stones (same length as positions); empty = all `diameter`"))

    def validate(self, prefix: str = "stones") -> None:
        self._validate_fields(prefix)
        self._validate_polygon(prefix)
        size = {"lo": 0.001, "hi": 0.5, "closed": "[]", "kind": "length"}
        if not isinstance(self.positions, (list, tuple)):
            raise ValueError(f"{prefix}.positions = {self.positions!r} must be a list of pairs [x m, z m]")
        _check_list(f"{prefix}.diameters", self.diameters, size)
        for j, row in enumerate(self.positions):
            if not isinstance(row, (list, tuple)) or len(row) != 2 or not all(
                    isinstance(v, (int, float)) and not isinstance(v, bool) and math.isfinite(v) for v in row):
                raise ValueError(f"{prefix}.positions[{j}] = {row!r} must be a pair [x m, z m] of finite numbers")
        if self.diameters:
            if len(self.diameters) != len(self.positions):
                raise ValueError(f"{prefix}.diameters has {len(self.diameters)} entries, "
                                 f"{prefix}.positions has {len(self.positions)}: they must match")
            for j, d in enumerate(self.diameters):
                _check_number(f"{prefix}.diameters[{j}]", d, size)

    def _validate_polygon(self, prefix: str) -> None:
        for name in ("polygon_vertices_min", "polygon_vertices_max"):
            v = getattr(self, name)
            if v != int(v):
                raise ValueError(f"{prefix}.{name} = {_fmt(v)} must be a whole number in [3, 16]")
            setattr(self, name, int(v))
        if self.polygon_vertices_max < self.polygon_vertices_min:
            raise ValueError(f"{prefix}.polygon_vertices_max = {self.polygon_vertices_max} is outside the allowed "
                             f"range [{self.polygon_vertices_min}, 16] (at least {prefix}.polygon_vertices_min)")
        # a polygon resists rolling by its shape; the disc law on its bounding radius has no physical basis
        for name in ("rolling_friction", "rolling_friction_wall"):
            if self.shape == "polygon" and getattr(self, name) > 0.0:
                raise ValueError(f"{prefix}.{name} = {_fmt(getattr(self, name))} is outside the allowed range [0, 0] "
                                 f"with {prefix}.shape = 'polygon': the rolling resistance is a law for disc stones "
                                 "(polygon stones resist rolling by their shape)")

    def mean_diameter(self) -> float:
        """Number-weighted mean diameter [m] of the grading (or `diameter`)."""
        if self.diameters:
            return float(sum(self.diameters) / len(self.diameters))
        return self.diameter

    def max_diameter(self) -> float:
        if self.diameters:
            return float(max(self.diameters))
        return self.diameter * (1.0 + self.diameter_spread)


@dataclass
class Hydrograph(_Section):
    """Inflow discharge Q(t) at x = 0.

    kind 'ramp' (the paper's): a spin-up at `discharge_start_lps` for `spin_up_duration` seconds (the
    flow settles to a steady state over the weir, stones held in place if `hold_stones_during_spin_up`),
    then a linear rise to `discharge_end_lps` over `ramp_duration`. The paper's clock starts at the
    ramp: paper time = simulation time - spin_up_duration.
    kind 'table': piecewise-linear through (`times` [s], `discharge_lps` [l/s]), spin-up included.
    From Python, `function` (a callable t [s] -> Q [m3/s]) overrides both; it is sampled into a
    table every `table_interval` seconds for the solver.
    """

    kind: str = _choice("ramp", ("ramp", "table"), "'ramp' (spin-up then linear rise) or 'table'")
    discharge_start_lps: float = _p(10.0, "discharge", 0.1, 1000.0, "spin-up and ramp start discharge [l/s]")
    discharge_end_lps: float = _p(25.0, "discharge", 0.1, 1000.0, "discharge at the end of the ramp [l/s]")
    ramp_duration: float = _p(120.0, "time", 0.0, 1e5, "duration of the linear rise [s]; paper 120", "(]")
    spin_up_duration: float = _p(20.0, "time", 0.0, 1e4, "time at the start discharge before the ramp [s]")
    hold_stones_during_spin_up: bool = _flag(True, "stones do not move during the spin-up")
    times: List[float] = field(default_factory=list, metadata=dict(doc="table times [s] (kind = 'table')"))
    discharge_lps: List[float] = field(default_factory=list, metadata=dict(doc="table discharges [l/s]"))
    table_interval: float = _p(0.5, "time", 0.0, 100.0, "sampling step of `function` into a table [s]", "(]")
    function: Optional[Callable[[float], float]] = field(default=None, metadata=dict(
        doc="Python only: Q(t) in m3/s, overrides kind", python_only=True))

    def validate(self, prefix: str = "hydrograph") -> None:
        self._validate_fields(prefix)
        # the table's lists are checked under any kind: a malformed key is an error even where it is ignored
        q_md = {"lo": 0.0, "hi": 1000.0, "closed": "[]", "kind": "discharge"}
        t_md = {"lo": 0.0, "hi": 1e6, "closed": "[]", "kind": "time"}
        _check_list(f"{prefix}.times", self.times, t_md)
        _check_list(f"{prefix}.discharge_lps", self.discharge_lps, q_md)
        if self.function is not None:
            if not callable(self.function):
                raise ValueError(f"{prefix}.function must be a callable t [s] -> Q [m3/s]")
            return
        if self.kind == "table":
            if len(self.times) < 2 or len(self.times) != len(self.discharge_lps):
                raise ValueError(f"{prefix}.times and {prefix}.discharge_lps must be lists of the same "
                                 f"length >= 2 (got {len(self.times)} and {len(self.discharge_lps)})")
            if any(b <= a for a, b in zip(self.times, self.times[1:])):
                raise ValueError(f"{prefix}.times must be strictly increasing")

    @property
    def ramp_start(self) -> float:
        """Simulation time [s] at which the paper's clock starts (end of the spin-up)."""
        return self.spin_up_duration if self.kind == "ramp" and self.function is None else 0.0

    @property
    def end_time(self) -> float:
        """Simulation time [s] at the end of the hydrograph."""
        if self.function is None and self.kind == "table":
            return float(self.times[-1])
        return self.spin_up_duration + self.ramp_duration

    def discharge(self, t):
        """Q [m3/s] at simulation time t [s] (scalar or array)."""
        import numpy as np

        if self.function is not None:
            return np.vectorize(lambda s: float(self.function(s)))(t) if np.ndim(t) else float(self.function(t))
        if self.kind == "table":
            q = np.interp(t, self.times, self.discharge_lps) * 1e-3
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
        else:
            t = np.array([0.0, self.spin_up_duration, self.spin_up_duration + self.ramp_duration])
            if self.spin_up_duration == 0.0:
                t = t[1:]
            if t_end > t[-1]:
                t = np.append(t, t_end)
        return t, np.asarray(self.discharge(t), float)


@dataclass
class GridSpec(_Section):
    """The VOF mesh: uniform in x, `dz` in z with a finer layer `dz_bed` next to the bed."""

    dx: float = _p(0.025, "length", 0.001, 0.5, "cell length along the flume [m]; paper 0.025", "(]")
    dz: float = _p(0.010, "length", 0.0005, 0.5, "cell height [m]; paper 0.010", "(]")
    dz_bed: float = _p(0.005, "length", 0.0005, 0.5, "cell height next to the bed [m]; paper 0.005", "(]")
    bed_layer_height: float = _p(0.005, "length", 0.0, 1.0, "thickness of the fine bed layer [m]")

    def validate(self, prefix: str = "grid") -> None:
        self._validate_fields(prefix)


@dataclass
class Numerics(_Section):
    cfl: float = _p(0.3, None, 0.0, 1.0, "Courant number of the fluid step [-]; usual 0.3", "(]")
    dem_dt: float = _p(1e-4, "time", 0.0, 1e-2, "DEM time step [s]; paper 1e-4", "(]")
    dem_contact_steps: float = _p(20.0, None, 5.0, 1e6, "automatic contact stiffness: DEM steps of dem_dt per "
                                  "contact of two mean stones [-]; 20 (polygons: 50 at dem_dt 4e-5 s, the same "
                                  "stiffness)")
    max_dt: float = _p(0.01, "time", 0.0, 1.0, "largest fluid time step [s]", "(]")
    initial_dt: float = _p(1e-3, "time", 0.0, 1.0, "first fluid time step from rest [s]; usual 1e-3", "(]")
    max_dt_growth: float = _p(1.2, None, 1.0, 10.0, "growth limit of the fluid step, dt <= factor x last dt [-]; "
                              "usual 1.2", "[]")
    porosity_method: str = _choice("exact", ("exact", "lookup"),
                                   "disc-cell overlap: exact areas or the paper's lookup table")
    pressure_solver: str = _choice("multigrid_cg", ("multigrid_cg", "direct"),
                                   "multigrid-preconditioned CG (fast) or Eigen's direct solver (reference)")
    pressure_tolerance: float = _p(1e-8, None, 0.0, 1e-2, "relative residual of the pressure solve [-]", "(]")

    def validate(self, prefix: str = "numerics") -> None:
        self._validate_fields(prefix)


@dataclass
class Effects(_Section):
    """Physical effects, each switchable (a switched-off effect costs nothing)."""

    turbulence: bool = _flag(True, "standard k-epsilon turbulence (laminar when off)")
    porous_resistance: bool = _flag(True, "porous resistance of eqs. (5)-(7)")
    dem: bool = _flag(True, "stones move (DEM); off = a rigid porous weir")
    two_way: bool = _flag(True, "porosity follows the stones (feedback on the flow)")
    added_mass: bool = _flag(True, "added mass M' = rho C_M V")
    rotation: bool = _flag(True, "stone rotation, eq. (10)")
    rolling_resistance: bool = _flag(True, "rolling resistance at contacts (stones.rolling_friction*; "
                                     "nothing while those are 0)")
    friction: bool = _flag(True, "Coulomb friction at contacts")
    buoyancy: bool = _flag(True, "buoyancy (M - rho_w V) g")
    drag: bool = _flag(True, "drag of the flow on stones, eqs. (16)-(18)")
    pressure_gradient: bool = _flag(True, "pressure-gradient force F_S on stones")
    relative_velocity_resistance: bool = _flag(False, "porous resistance uses the water-stone relative velocity")

    def validate(self, prefix: str = "effects") -> None:
        self._validate_fields(prefix)


@dataclass
class Output(_Section):
    snapshot_interval: float = _p(0.5, "time", 0.0, 1e4, "simulated time between snapshots [s]", "(]")
    gauge_x: Optional[float] = _p(None, "length", 0.0, 100.0,
                                  "x of the upstream water-level gauge [m]; default halfway to the weir", "(]")
    figures: bool = _flag(True, "write the figures at the end of the run")
    animation: bool = _flag(True, "write an animation of the run (mp4 with ffmpeg, gif otherwise)")
    animation_fps: float = _p(10.0, None, 0.0, 120.0, "frames per second of the animation", "(]")

    def validate(self, prefix: str = "output") -> None:
        self._validate_fields(prefix)


_SECTIONS = {"flume": Flume, "weir": Weir, "stones": Stones, "hydrograph": Hydrograph, "grid": GridSpec,
             "numerics": Numerics, "effects": Effects, "output": Output}
_TOP_KEYS = ("name", "seed", "end_time")


@dataclass
class Scene:
    """A complete run: flume, weir, stones, hydrograph, grid, numerics, effects, output and seed."""

    name: str = "scene"
    flume: Flume = field(default_factory=Flume)
    weir: Weir = field(default_factory=Weir)
    stones: Stones = field(default_factory=Stones)
    hydrograph: Hydrograph = field(default_factory=Hydrograph)
    grid: GridSpec = field(default_factory=GridSpec)
    numerics: Numerics = field(default_factory=Numerics)
    effects: Effects = field(default_factory=Effects)
    output: Output = field(default_factory=Output)
    seed: int = 0
    end_time: Optional[float] = None  # [s]; default: the hydrograph's end

    def __post_init__(self):
        self.validate()

    # ---------------------------------------------------------------- ready scenes
    @classmethod
    def maeno2008(cls) -> "Scene":
        """The rubble mound weir of Maeno & Tomita (2008), ICHE 2008.

        From the paper: natural stones of mean diameter 4.8 cm, downstream slope 27 deg, bottom layer
        fixed, rest packed freely under gravity; mesh 2.5 cm x 1.0 cm with 0.5 cm at the bed; DEM step
        1e-4 s; friction 0.577 stone-stone and 0.176 stone-wall; n_exp = 0.41; (k1, k2) = (200, 2.8);
        added mass C_M = 1.0 (the run's value; the text says 0.5); discharge raised linearly from 10 to
        25 l/s over 120 s.

        Not given by the paper, assumed here (each a parameter): flume width 0.50 m; weir height
        0.25 m, crest 0.20 m, upstream slope 27 deg; stone density 2650 kg/m3; diameters spread
        uniformly over 4.8 cm +- 10 % (natural stones; the paper gives the mean only); a free overfall 1.5 m downstream of the weir's toe; 1.0 m
        of flume upstream of the weir; a spin-up of 20 s at 10 l/s before the ramp; a domain 0.45 m
        high; the fluid's CFL 0.3.
        """
        weir = Weir()
        flume = Flume(length=round(weir.x_toe_down + 1.5, 6))
        return cls(name="maeno2008", flume=flume, weir=weir)

    def quick(self) -> "Scene":
        """A shorter, coarser copy that runs in a few minutes on one core.

        Same weir and stones; the grid is twice as coarse (5 cm x 2 cm, 1 cm at the bed), the flume's
        reaches are shortened to 0.6 m upstream and 0.8 m downstream, the spin-up lasts 5 s and the
        ramp 10 -> 25 l/s lasts 30 s (four times faster than the paper's), snapshots every 0.5 s.
        Stage discharges of a quick run are not comparable with the paper: the discharge rises four
        times faster than the stones' response time allows for.
        """
        s = copy.deepcopy(self)
        s.name = self.name + "_quick"
        shift = s.weir.toe_x - 0.6
        s.weir.toe_x = 0.6
        if s.stones.positions:
            s.stones.positions = [[x - shift, z] for x, z in s.stones.positions]
        s.flume.length = round(s.weir.x_toe_down + 0.8, 6)
        s.grid = GridSpec(dx=0.05, dz=0.02, dz_bed=0.01, bed_layer_height=0.01)
        if s.hydrograph.kind == "ramp" and s.hydrograph.function is None:
            s.hydrograph.spin_up_duration = 5.0
            s.hydrograph.ramp_duration = 30.0
        s.end_time = None
        s.output.snapshot_interval = 0.5
        s.validate()
        return s

    # ---------------------------------------------------------------- validation
    @property
    def duration(self) -> float:
        """Simulated time of the run [s]."""
        return self.hydrograph.end_time if self.end_time is None else self.end_time

    @property
    def gauge_x(self) -> float:
        """x of the upstream water-level gauge [m]."""
        return 0.5 * self.weir.toe_x if self.output.gauge_x is None else self.output.gauge_x

    def validate(self) -> "Scene":
        """Checks every parameter and the geometry; raises ValueError naming the first problem."""
        for key, cls in _SECTIONS.items():
            sec = getattr(self, key)
            if not isinstance(sec, cls):
                raise ValueError(f"{key} must be a {cls.__name__}, got {type(sec).__name__}")
            sec.validate(key)
        if not isinstance(self.name, str) or not self.name.strip():
            raise ValueError(f"name = {self.name!r} must be a non-empty string")
        if not isinstance(self.seed, int) or isinstance(self.seed, bool) or not 0 <= self.seed < 2**63:
            raise ValueError(f"seed = {self.seed!r} must be an integer in [0, 2^63)")
        if self.end_time is not None:
            _check_number("end_time", self.end_time, {"lo": 0.0, "hi": 1e6, "closed": "(]", "kind": "time"})
        self._validate_geometry()
        return self

    def _validate_geometry(self) -> None:
        f, w, s, g = self.flume, self.weir, self.stones, self.grid
        if w.x_toe_down >= f.length:
            raise ValueError(f"the weir does not fit the flume: its downstream toe is at x = {w.x_toe_down:.4g} m "
                             f"(weir.toe_x = {w.toe_x:.4g} m + base {w.base_length:.4g} m), beyond "
                             f"flume.length = {f.length:.4g} m")
        if w.height >= f.height:
            raise ValueError(f"the weir does not fit the flume: weir.height = {w.height:.4g} m must be below "
                             f"flume.height = {f.height:.4g} m (the domain top), with room for the overflow")
        if w.toe_x < 2 * g.dx:
            raise ValueError(f"weir.toe_x = {w.toe_x:.4g} m leaves less than two cells (grid.dx = {g.dx:.4g} m) "
                             f"of flume upstream of the weir for the inflow")
        if s.max_diameter() >= w.height and not s.positions:
            raise ValueError(f"stones.diameter = {s.max_diameter():.4g} m must be smaller than "
                             f"weir.height = {w.height:.4g} m to build the weir")
        if g.dx >= f.length / 4 or g.dz >= f.height / 4:
            raise ValueError(f"grid.dx = {g.dx:.4g} m / grid.dz = {g.dz:.4g} m is too coarse: the flume needs at "
                             f"least 4 cells each way (length {f.length:.4g} m, height {f.height:.4g} m)")
        if s.shape == "polygon" and self.numerics.porosity_method == "lookup":
            raise ValueError("numerics.porosity_method = 'lookup' (the paper's table of disc areas) is for disc "
                             "stones; stones.shape = 'polygon' needs porosity_method = 'exact'")
        if g.bed_layer_height >= f.height / 2:
            raise ValueError(f"grid.bed_layer_height = {g.bed_layer_height:.4g} m is outside the allowed range "
                             f"[0, {f.height / 2:.4g}) m (half the domain height)")
        if self.output.gauge_x is not None and self.output.gauge_x >= w.toe_x:
            raise ValueError(f"output.gauge_x = {self.output.gauge_x:.4g} m must lie upstream of the weir "
                             f"(below weir.toe_x = {w.toe_x:.4g} m)")
        diam = s.diameters or [s.diameter] * len(s.positions)
        for j, ((x, z), d) in enumerate(zip(s.positions, diam)):
            r = 0.5 * d
            if x - r < 0 or x + r > f.length or z - r < -1e-12 or z + r > f.height:
                raise ValueError(f"stones.positions[{j}] = [{x:.4g}, {z:.4g}] (diameter {d:.4g} m) lies outside "
                                 f"the domain [0, {f.length:.4g}] x [0, {f.height:.4g}] m")

    # ---------------------------------------------------------------- dict / TOML
    def to_dict(self) -> Dict[str, Any]:
        """Plain dict (TOML-ready); a Python `hydrograph.function` is sampled into a table."""
        out: Dict[str, Any] = {"name": self.name, "seed": self.seed}
        if self.end_time is not None:
            out["end_time"] = self.end_time
        for key in _SECTIONS:
            sec = getattr(self, key)
            d = {}
            for f in dataclasses.fields(sec):
                v = getattr(sec, f.name)
                if f.metadata.get("python_only") or v is None:
                    continue
                d[f.name] = copy.deepcopy(v)
            out[key] = d
        h = self.hydrograph
        if h.function is not None:
            t, q = h.table(self.duration)
            out["hydrograph"].update(kind="table", times=[float(x) for x in t],
                                     discharge_lps=[float(x) * 1e3 for x in q])
        return out

    @classmethod
    def from_dict(cls, data: Dict[str, Any], source: str = "scene") -> "Scene":
        """Builds and validates a scene from a (TOML-like) dict; ValueError on any problem."""
        if not isinstance(data, dict):
            raise ValueError(f"{source}: a scene must be a table of sections")
        valid_top = set(_TOP_KEYS) | set(_SECTIONS)
        for key in data:
            if key not in valid_top:
                raise ValueError(_unknown(key, valid_top, "top level"))
        kwargs: Dict[str, Any] = {k: data[k] for k in _TOP_KEYS if k in data}
        if "end_time" in kwargs:
            kwargs["end_time"] = _parse_quantity("end_time", kwargs["end_time"], "time")
        for key, sec_cls in _SECTIONS.items():
            if key not in data:
                continue
            table = data[key]
            if not isinstance(table, dict):
                raise ValueError(f"[{key}] must be a table of parameters, got {table!r}")
            fields = {f.name: f for f in dataclasses.fields(sec_cls) if not f.metadata.get("python_only")}
            args = {}
            for k, v in table.items():
                if k not in fields:
                    raise ValueError(_unknown(k, fields, f"[{key}]", prefix=key))
                md = fields[k].metadata
                args[k] = _parse_quantity(f"{key}.{k}", v, md.get("kind")) if "lo" in md else v
            for k in ("positions", "discharge_lps", "times", "diameters"):
                if k in args and isinstance(args[k], list):
                    kind = {"times": "time", "discharge_lps": "discharge", "diameters": "length"}.get(k)
                    args[k] = [_parse_quantity(f"{key}.{k}[{j}]", v, kind) if not isinstance(v, list) else v
                               for j, v in enumerate(args[k])]
            kwargs[key] = sec_cls(**args)
        return cls(**kwargs)

    def to_toml(self) -> str:
        """The scene as TOML text (what `load_scene` reads back to an equal scene)."""
        d = self.to_dict()
        lines = [f"# vofdem scene '{self.name}' (SI units; angles *_deg in degrees, discharges *_lps in l/s)"]
        for k in _TOP_KEYS:
            if k in d:
                lines.append(f"{k} = {_toml_value(d[k])}")
        for key in _SECTIONS:
            lines.append("")
            lines.append(f"[{key}]")
            for k, v in d[key].items():
                lines.append(f"{k} = {_toml_value(v)}")
        return "\n".join(lines) + "\n"

    @classmethod
    def from_toml(cls, text: str, source: str = "scene") -> "Scene":
        try:
            data = _toml.loads(text)
        except _toml.TOMLDecodeError as e:
            raise ValueError(f"{source}: not valid TOML: {e}") from None
        if not data:
            raise ValueError(f"{source}: the scene is empty (no keys, no sections); write at least the sections "
                             f"that differ from the defaults, e.g. [flume], or run the ready scene 'maeno2008'")
        return cls.from_dict(data, source)

    def replace(self, **changes) -> "Scene":
        """A validated copy with top-level fields replaced (e.g. seed=3)."""
        s = copy.deepcopy(self)
        for k, v in changes.items():
            if not hasattr(s, k):
                raise ValueError(_unknown(k, [f.name for f in dataclasses.fields(Scene)], "Scene"))
            setattr(s, k, v)
        return s.validate()

    def with_value(self, key: str, value) -> "Scene":
        """A validated copy with one parameter set by its dotted name ('stones.friction_stone', or a
        top-level 'end_time'), the value read as in a scene file (numbers may carry a unit, '4.8 cm')."""
        s = copy.deepcopy(self)
        section, _, name = key.rpartition(".")
        if not section:
            if key not in ("end_time", "name"):
                raise ValueError(_unknown(key, [*_SECTIONS, "end_time", "name"], "top level"))
            setattr(s, key, _parse_quantity(key, value, "time") if key == "end_time" else value)
            return s.validate()
        if section not in _SECTIONS:
            raise ValueError(_unknown(section, list(_SECTIONS), "top level"))
        fields = {f.name: f for f in dataclasses.fields(_SECTIONS[section]) if not f.metadata.get("python_only")}
        if name not in fields:
            raise ValueError(_unknown(name, fields, f"[{section}]", prefix=section))
        md = fields[name].metadata
        setattr(getattr(s, section), name, _parse_quantity(key, value, md.get("kind")) if "lo" in md else value)
        return s.validate()

    def value_of(self, key: str):
        """The value of a parameter by its dotted name (see `with_value`)."""
        section, _, name = key.rpartition(".")
        return getattr(getattr(self, section), name) if section else getattr(self, key)


def load_scene(path) -> Scene:
    """Reads and validates a TOML scene file; ValueError names the file and the problem."""
    from pathlib import Path

    p = Path(path)
    if not p.is_file():
        raise ValueError(f"scene file {str(p)!r} does not exist")
    try:
        return Scene.from_toml(p.read_text(encoding="utf-8"), source=str(p))
    except ValueError as e:
        msg = str(e)
        raise ValueError(msg if msg.startswith(str(p)) else f"{p}: {msg}") from None


def _unknown(key: str, valid, where: str, prefix: Optional[str] = None) -> str:
    close = difflib.get_close_matches(key, list(valid), n=1, cutoff=0.5)
    name = f"{prefix}.{key}" if prefix else key
    hint = f"; did you mean '{close[0]}'?" if close else f"; valid keys: {', '.join(sorted(valid))}"
    return f"unknown key '{name}' in {where}{hint}"


def _toml_value(v) -> str:
    if isinstance(v, bool):
        return "true" if v else "false"
    if isinstance(v, int):
        return str(v)
    if isinstance(v, float):
        return repr(v) if math.isfinite(v) else ("inf" if v > 0 else "-inf" if v < 0 else "nan")
    if isinstance(v, str):
        return '"' + v.replace("\\", "\\\\").replace('"', '\\"') + '"'
    if isinstance(v, (list, tuple)):
        return "[" + ", ".join(_toml_value(x) for x in v) + "]"
    raise TypeError(f"cannot write {type(v).__name__} to TOML")


def describe_parameters() -> str:
    """A markdown table of every scene parameter: section, name, default, range, meaning."""
    rows = ["| parameter | default | allowed | meaning |", "|---|---|---|---|"]
    for key, cls in _SECTIONS.items():
        for f in dataclasses.fields(cls):
            md = f.metadata
            if md.get("python_only"):
                continue
            default = f.default if f.default is not dataclasses.MISSING else f.default_factory()
            allowed = _range_text(md) if "lo" in md else (" / ".join(md["choices"]) if "choices" in md
                                                            else ("true / false" if "flag" in md else "list"))
            rows.append(f"| {key}.{f.name} | {default!r} | {allowed} | {md.get('doc', '')} |")
    return "\n".join(rows)
