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
import math
from dataclasses import dataclass, field
from typing import Any, Dict, List, Optional, Tuple

from . import _core
from .flood import Hydrograph
from .reference import Reference, maeno2008_reference
from .stone_models import front, has_front as _has_front
from .schema import (_BASE_UNIT, _UNITS, _Section, _check_list, _check_number, _choice, _flag, _fmt,  # noqa: F401
                     _p, _parse_quantity, _range_text, _toml, _toml_value, _unknown, describe, parse_toml,
                     section_args, section_dict, toml_table)


@dataclass
class Flume(_Section):
    """The computational flume: a 2D vertical slice of a flume of width B."""

    length: float = _p(3.681, "length", 0.2, 100.0, "domain length from inflow to outflow end [m]", "(]")
    # the core's FlowParams.flume_width is the one source of the default
    width: float = _p(_core.FlowParams().flume_width, "length", 0.0, 10.0,
                      "flume width B dividing the discharge [m]; usual 0.5", "(]")
    height: float = _p(0.38, "length", 0.05, 10.0,
                       "domain height above the bed [m]; usual 0.38 (5.5 cm over the Maeno weir's highest surface)", "(]")
    bed_slope: float = _p(0.0, None, -0.1, 0.1, "bed slope S0 = sin(angle) [-], positive falling downstream")
    outflow: str = _choice("free_overfall", ("free_overfall", "tailwater"),
                           "outflow at x = length: free overfall or a fixed tailwater level")
    tailwater_level: Optional[float] = _p(None, "length", 0.0, 10.0,
                                          "tailwater level above the bed [m] (outflow = 'tailwater')", "(]")
    initial_water: str = _choice("rest", ("rest", "displaced"),
                                 "the water at the start: at rest to the weir-formula level in the pores, or "
                                 "'displaced' (filled before the stones, which push it up over the weir)")

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
    """The rubble mound weir standing on the bed: a trapezoid (height, crest, two slopes, toe), or any
    stone body given by `outline`, the points of its upper boundary from the upstream toe to the
    downstream toe (outline.py: any crest, berms, several slopes). With an outline, height, toe_x and
    crest_length are derived from it (and the slopes unused); a scene file gives one or the other.

    The paper gives the downstream slope (27 deg) only; height 0.25 m, crest 0.20 m and a 27 deg
    upstream slope are assumed defaults.
    """

    height: float = _p(0.25, "length", 0.0, 5.0, "weir height above the bed [m]; usual 0.25", "(]")
    crest_length: float = _p(0.20, "length", 0.0, 10.0, "horizontal crest length [m]; usual 0.20")
    upstream_slope_deg: float = _p(27.0, "angle", 5.0, 60.0, "upstream face angle to the bed [deg]")
    downstream_slope_deg: float = _p(27.0, "angle", 5.0, 60.0, "downstream face angle to the bed [deg]")
    toe_x: float = _p(1.0, "length", 0.0, 100.0, "x of the upstream toe [m]", "(]")
    outline: List[List[float]] = field(default_factory=list, metadata=dict(
        doc="the stone body's upper boundary [[x m, z m], ...] from toe (z = 0) to toe (z = 0), x increasing; "
            "empty: the trapezoid"))

    def validate(self, prefix: str = "weir") -> None:
        self._validate_fields(prefix)
        if not isinstance(self.outline, (list, tuple)):
            raise ValueError(f"{prefix}.outline = {self.outline!r} must be a list of points [x m, z m]")
        if self.outline:
            from .outline import check_outline

            check_outline(self.outline, f"{prefix}.outline")
            self.outline = [[float(x), float(z)] for x, z in self.outline]
            body = self.body()
            up, down = body.crest()
            self.height, self.toe_x, self.crest_length = body.height, body.x_toe_up, down - up
            _check_number(f"{prefix}.outline (its height)", self.height, {"lo": 0.0, "hi": 5.0, "closed": "(]",
                                                                           "kind": "length"})

    def body(self):
        """The stone body as an outline.Outline (the trapezoid's four points without an outline)."""
        from .outline import Outline, trapezoid_points

        if self.outline:
            return Outline(self.outline)
        return Outline(trapezoid_points(self.toe_x, self.height, self.crest_length, self.upstream_slope_deg,
                                        self.downstream_slope_deg))

    @property
    def x_crest_up(self) -> float:
        """x of the upstream end of the crest [m]."""
        if self.outline:
            return self.body().crest()[0]
        return self.toe_x + self.height / math.tan(math.radians(self.upstream_slope_deg))

    @property
    def x_crest_down(self) -> float:
        """x of the downstream end of the crest (the shoulder) [m]."""
        if self.outline:
            return self.body().crest()[1]
        return self.x_crest_up + self.crest_length

    @property
    def x_toe_down(self) -> float:
        """x of the downstream toe [m]."""
        if self.outline:
            return float(self.outline[-1][0])
        return self.x_crest_down + self.height / math.tan(math.radians(self.downstream_slope_deg))

    @property
    def base_length(self) -> float:
        return self.x_toe_down - self.toe_x

    def outline_xz(self) -> Tuple[List[float], List[float]]:
        """The upper boundary's points (x [m], z [m]) from the upstream toe to the downstream toe."""
        p = self.body().points
        return list(p[:, 0]), list(p[:, 1])

    def surface(self, x):
        """Height of the weir's surface above x [m] (0 outside the weir); x may be an array."""
        import numpy as np

        if self.outline:
            return self.body().surface(x)
        x = np.asarray(x, dtype=float)
        up = (x - self.toe_x) * math.tan(math.radians(self.upstream_slope_deg))
        down = (self.x_toe_down - x) * math.tan(math.radians(self.downstream_slope_deg))
        return np.clip(np.minimum(np.minimum(up, down), self.height), 0.0, None)


# the weir's keys that an outline replaces
TRAPEZOID_KEYS = ("height", "crest_length", "upstream_slope_deg", "downstream_slope_deg", "toe_x")


def _grading_field(name: str, whose: str):
    """A fresh field of the grading keys shared by [stones] and a zone (grading.py)."""
    if name == "grading_diameters":
        return field(default_factory=list, metadata=dict(doc=f"{whose} sieve curve: sizes [m], increasing (with "
                                                             f"grading_passing); empty: no sieve curve"))
    if name == "grading_passing":
        return field(default_factory=list, metadata=dict(doc=f"{whose} sieve curve: mass fraction passing each "
                                                             f"size [-], 0 first, 1 last"))
    return _p(None, "length", 0.001, 0.5, f"{whose} grading by sizes: {name} [m] (d15, d50, d85 together)", "[]")


def _validate_grading(sec, prefix: str) -> None:
    _check_list(f"{prefix}.grading_diameters", sec.grading_diameters,
                {"lo": 0.001, "hi": 0.5, "closed": "[]", "kind": "length"})
    _check_list(f"{prefix}.grading_passing", sec.grading_passing, {"lo": 0.0, "hi": 1.0, "closed": "[]", "kind": None})
    from .grading import grading_of

    grading_of(sec, prefix)


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
    compaction_friction: Optional[float] = _p(None, None, 0.0, 2.0, "3D stones' packing: the stone-stone friction of "
                                              "the pour's rounds [-], a compaction before friction_stone returns "
                                              "for a last settling; unset: the stone model's own (clumps 0.1, "
                                              "spheres none: friction_stone throughout)")
    fix_bottom_layer: bool = _flag(True, "stones touching the bed are fixed to it (as in the paper)")
    # the choices are the stone models' registry (stone_model.h), each name written once there
    shape: str = _choice("disc", tuple(_core.stone_model_names()),
                         "stone shape: 'disc' (the paper's) or 'polygon' (random convex polygons of quarried-stone "
                         "form, one per stone from the seed); 'sphere' (3D spheres across flume.width, packed in 3D); "
                         "'clump' (3D clumps of 2-4 spheres across flume.width, packed in 3D; their DEM step is "
                         "about 0.7 of the spheres', numerics.dem_dt)")
    polygon_vertices_min: int = _p(5, None, 3, 16, "fewest vertices of a polygon stone [-]; usual 5")
    polygon_vertices_max: int = _p(8, None, 3, 16, "most vertices of a polygon stone [-]; usual 8")
    aspect_ratio: float = _p(1.5, None, 1.0, 3.0, "length / thickness of a polygon stone's section [-]; usual 1.5")
    polygon_radial_jitter: float = _p(0.2, None, 0.0, 0.5, "polygon vertex radii 1 +- jitter before the hull [-]; "
                                      "usual 0.2")
    positions: List[List[float]] = field(default_factory=list, metadata=dict(
        doc="explicit stone centres [[x m, z m], ...] instead of packing the weir; empty = pack"))
    diameters: List[float] = field(default_factory=list, metadata=dict(
        doc="diameters [m] of the explicit stones (same length as positions); empty = all `diameter`"))
    grading_diameters: List[float] = _grading_field("grading_diameters", "the stones'")
    grading_passing: List[float] = _grading_field("grading_passing", "the stones'")
    d15: Optional[float] = _grading_field("d15", "the stones'")
    d50: Optional[float] = _grading_field("d50", "the stones'")
    d85: Optional[float] = _grading_field("d85", "the stones'")

    def validate(self, prefix: str = "stones") -> None:
        self._validate_fields(prefix)
        self._validate_polygon(prefix)
        _validate_grading(self, prefix)
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
            _make_whole(self, prefix, name, "[3, 16]")
        if self.polygon_vertices_max < self.polygon_vertices_min:
            raise ValueError(f"{prefix}.polygon_vertices_max = {self.polygon_vertices_max} is outside the allowed "
                             f"range [{self.polygon_vertices_min}, 16] (at least {prefix}.polygon_vertices_min)")
        # what the stone model cannot honour (stone_models.py)
        front(self.shape).check(self, prefix)
        if self.compaction_friction is not None and front(self.shape).dimensions != 3:
            raise ValueError(f"{prefix}.compaction_friction = {self.compaction_friction!r}: the plane's packing has "
                             f"no compaction ({prefix}.shape = '{self.shape}'); leave it unset or use a 3D shape "
                             "('sphere', 'clump')")

    def grading(self):
        """The sieve curve of the stones (grading.Grading) when one is given (grading_diameters and
        grading_passing, or d15 / d50 / d85; `diameter` and `diameter_spread` are then not used for the
        packing), else None (sizes uniform in diameter +- spread)."""
        from .grading import grading_of

        return grading_of(self, "stones")

    def mean_diameter(self) -> float:
        """Number-weighted mean diameter [m] of the explicit stones, the grading, or `diameter`."""
        if self.diameters:
            return float(sum(self.diameters) / len(self.diameters))
        g = self.grading()
        return g.mean_number_diameter() if g is not None else self.diameter

    def max_diameter(self) -> float:
        if self.diameters:
            return float(max(self.diameters))
        g = self.grading()
        return g.d_max if g is not None else self.diameter * (1.0 + self.diameter_spread)


@dataclass
class Zone(_Section):
    """A part of the packed weir with its own grading (outline.py): a layer `thickness` [m] thick under
    the weir's upper boundary (an armour layer), or the inside of the closed polygon `outline`. A stone
    placed in the first zone holding its place takes that zone's grading; the rest (the core) [stones]'."""

    name: str = field(default="", metadata=dict(text=True, doc="the zone's name (e.g. 'armour')"))
    thickness: Optional[float] = _p(None, "length", 0.0, 5.0, "a layer this thick under the weir's surface [m]",
                                    "(]")
    outline: List[List[float]] = field(default_factory=list, metadata=dict(
        doc="or a closed polygon [[x m, z m], ...] (three points at least)"))
    grading_diameters: List[float] = _grading_field("grading_diameters", "the zone's")
    grading_passing: List[float] = _grading_field("grading_passing", "the zone's")
    d15: Optional[float] = _grading_field("d15", "the zone's")
    d50: Optional[float] = _grading_field("d50", "the zone's")
    d85: Optional[float] = _grading_field("d85", "the zone's")

    def validate(self, prefix: str = "zones[0]") -> None:
        self._validate_fields(prefix)
        if not isinstance(self.name, str) or not self.name.strip() or "\n" in self.name:
            raise ValueError(f"{prefix}.name = {self.name!r} must be a non-empty name of one line")
        if not isinstance(self.outline, (list, tuple)):
            raise ValueError(f"{prefix}.outline = {self.outline!r} must be a list of points [x m, z m]")
        if (self.thickness is None) == (not self.outline):
            raise ValueError(f"{prefix}.thickness: give a zone either a thickness (a layer under the surface) or an "
                             f"outline (a polygon), one of the two")
        if self.outline:
            from .outline import check_polygon

            check_polygon(self.outline, f"{prefix}.outline")
        _validate_grading(self, prefix)
        if self.grading() is None:
            raise ValueError(f"{prefix}.d50: a zone needs its grading (grading_diameters and grading_passing, or "
                             f"d15, d50 and d85)")

    def grading(self, prefix: str = "zone"):
        from .grading import grading_of

        return grading_of(self, prefix)


@dataclass
class GridSpec(_Section):
    """The VOF mesh: uniform in x, `dz` in z with a finer layer `dz_bed` next to the bed."""

    dx: float = _p(0.025, "length", 0.001, 0.5, "cell length along the flume [m]; paper 0.025", "(]")
    dz: float = _p(0.010, "length", 0.0005, 0.5, "cell height [m]; paper 0.010", "(]")
    dz_bed: float = _p(0.005, "length", 0.0005, 0.5, "cell height next to the bed [m]; paper 0.005", "(]")
    bed_layer_height: float = _p(0.005, "length", 0.0, 1.0, "thickness of the fine bed layer [m]")
    merge_fraction: float = _p(_core.GRADED_MERGE_FRACTION, None, 0.0, 1.0, "a last row of the bed layer or of the domain of at most this "
                               "fraction of its row height joins the row below [-]; 0: every remainder is a row "
                               "(a sliver row under the open top binds the step by the air through it)", "[)")

    def validate(self, prefix: str = "grid") -> None:
        self._validate_fields(prefix)


def _make_whole(section, prefix: str, name: str, allowed: str) -> None:
    """A key read as a number (TOML 8 or 8.0) made an int, refused unless whole."""
    v = getattr(section, name)
    if v != int(v):
        raise ValueError(f"{prefix}.{name} = {_fmt(v)} must be a whole number in {allowed}")
    setattr(section, name, int(v))


@dataclass
class Numerics(_Section):
    """The scene's [numerics] section: time steps [s], Courant numbers, solvers and schemes of the flow, the
    stones and the coupling (`vofdem params` lists every field with its unit and range)."""

    cfl: float = _p(0.5, None, 0.0, 0.5, "Courant number of the fluid step [-]; usual 0.5 with adams_bashforth2 "
                    "(0.3 with euler); above 0.5 the VOF advection is not bounded", "(]")
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
    lookup_m: int = _p(8, None, 2, 64, "sub-areas per side of a cell in the paper's lookup table (porosity_method "
                       "= 'lookup') [-]; 8")
    pressure_solver: str = _choice("multigrid_cg", ("multigrid_cg", "direct"),
                                   "multigrid-preconditioned CG (fast) or Eigen's direct solver (reference)")
    pressure_tolerance: float = _p(1e-5, None, 0.0, 1e-2, "relative residual of the pressure solve [-]; 1e-5 "
                                   "(water volume drift about 1e-11 per step)", "(]")
    time_scheme: str = _choice("adams_bashforth2", ("adams_bashforth2", "euler"),
                               "momentum convection: Adams-Bashforth 2 (second order) or forward Euler")
    step_control: str = _choice("this_step", ("this_step", "two_steps"),
                                "the advective limit a flow step is taken under: its start's, or the smaller of "
                                "its start's and the last step's (a two-step flicker of the limit is not chased)")
    turbulence_scheme: str = _choice("vertical_lines", ("vertical_lines", "point_implicit", "alternating_lines"),
                                     "k-epsilon transport: columns implicit (step bounded by the horizontal "
                                     "faces), point-implicit (bounded by all faces), or rows then columns "
                                     "implicit (bounded by the horizontal advection alone: no diffusion limit)")
    turbulence_cfl: float = _p(0.5, None, 0.0, 1.0, "k-epsilon: the safety factor of its step limit [-]; 0.5 (1: "
                               "the explicit faces' positivity limit itself)", "(]")
    turbulence_production: str = _choice("strain", ("strain", "kato_launder"),
                                         "k-epsilon production of k: the standard P = nu_t S^2 (the paper's) or "
                                         "Kato-Launder's P = nu_t S Omega (none where the strain is irrotational)")
    turbulence_pore_strain: str = _choice("neighbours", ("neighbours", "local", "filtered"),
                                          "k-epsilon strain in porous cells: cross derivatives from each "
                                          "neighbour's own pore velocity (across the porosity's jumps), from the "
                                          "superficial velocities over the cell's own porosity, or from the pore "
                                          "velocities over the porosity averaged over a box of side "
                                          "turbulence_pore_filter")
    turbulence_pore_filter: float = _p(0.0, "length", 0.0, 1.0, "k-epsilon, turbulence_pore_strain = 'filtered': "
                                       "the averaging box's side [m]; 0 = the stones' median diameter", "[]")
    turbulence_production_limit: float = _p(0.0, None, 0.0, 1e3, "k-epsilon: P <= this x eps, 0 = off [-]; Menter "
                                            "(1994): 10")
    turbulence_step_limit: bool = _flag(True, "k-epsilon vertical_lines and alternating_lines: the explicit part's "
                                        "limit (the horizontal faces', or the horizontal advection's) bounds the fluid "
                                        "step (true), or not (false: k and eps stay positive, but in the weir nu_t "
                                        "runs to its cap and the upstream level rises)")
    viscous_scheme: str = _choice("implicit_vertical", ("implicit_vertical", "implicit_vertical_from_start",
                                                        "explicit", "implicit"),
                                  "viscous stresses: vertical diffusion by column solves after the explicit "
                                  "rest, the former splitting from the step's start (unstable above about 0.7 "
                                  "of the limit; to reproduce earlier runs), all explicit (the reference), or "
                                  "rows and columns implicit with the cross terms explicit (no step bound)")
    viscous_bound: str = _choice("energy", ("energy", "row_sum"),
                                 "the viscous step's bound for viscous_scheme 'implicit_vertical': the energy "
                                 "bound (no cross terms, proven) or the former Gershgorin row sums (cross terms "
                                 "in; a shorter step). The other schemes always take row_sum")
    viscous_substeps: int = _p(8, None, 1, 64, "the explicit viscous stresses in up to this many substeps of a "
                               "fluid step longer than their limit [-]; 8 (1: one step, the limit binds)")
    inlet_profile: str = _choice("equivalent_depth", ("equivalent_depth", "water_fraction"),
                                 "the discharge over the inlet rows: those below the inlet's level sum(F dz), or "
                                 "every row by its water fraction (the former profile, whose traces of water above "
                                 "the level take inflow and grow)")
    drag_exchange: str = _choice("implicit", ("implicit", "held"),
                                 "stone drag: linearised in the stone's velocity, implicit in the DEM, or held "
                                 "over the step (bounded by its relaxation time)")
    wet_fraction_tolerance: float = _p(1e-6, None, 0.0, 0.5, "a stone measured this close to wet (dry) is taken "
                                       "as under water (in the air) [-]; 1e-6 (the VOF's traces of air under "
                                       "water); 0: every measured wet fraction is followed", "[]")
    coupling_mapping: str = _choice("cell", ("cell", "kernel"),
                                    "what the stones and the flow exchange: each stone's footprint over the raw "
                                    "cells ('cell', the paper's) or footprints and flow smoothed by a Gaussian "
                                    "exp(-r^2/b^2) of the physical width coupling_bandwidth ('kernel'; docs/coupler.md)")
    coupling_bandwidth: Optional[float] = _p(None, "length", 0.0, 1.0, "coupling_mapping = 'kernel': the Gaussian's "
                                             "width b [m] (sigma = b / sqrt 2); unset: 1.0 x the stones' mean diameter",
                                             "(]")
    overflow_load: str = _choice("off", ("off", "drag_lift"),
                                 "the overflow's drag and lift on the stones that stick out of the stone surface, "
                                 "loaded on their exposed share by the water above their tops, the reaction taken "
                                 "from the flow ('drag_lift'), or none ('off', the paper's; docs/coupler.md)")
    overflow_drag_coefficient: float = _p(0.91, None, 0.0, 5.0, "overflow_load = 'drag_lift': drag coefficient C_D "
                                          "of a stone's exposed part [-]; 0.91, natural particles near a bed "
                                          "(Schmeeckle et al. 2007)", "(]")
    overflow_lift_coefficient: float = _p(0.178, None, 0.0, 5.0, "overflow_load = 'drag_lift': lift coefficient C_L "
                                          "[-]; 0.178 (Einstein and El-Samni 1949)", "[]")
    overflow_band_height: float = _p(1.0, None, 0.0, 5.0, "overflow_load = 'drag_lift': the approach velocity's "
                                     "band above a stone's top, in stone diameters [-]; 1", "(]")
    fidelity: Optional[str] = _choice(None, ("draft", "standard", "fine"),
                                      "a preset of the grid, CFL and porosity method (fidelity.py; the scene must "
                                      "hold its values); unset: the scene's own values")

    def validate(self, prefix: str = "numerics") -> None:
        self._validate_fields(prefix)
        _make_whole(self, prefix, "lookup_m", "[2, 64]")
        _make_whole(self, prefix, "viscous_substeps", "[1, 64]")


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
    """The scene's [output] section: the snapshot interval [s], the upstream gauge's x [m], figures and the
    animation."""

    snapshot_interval: float = _p(0.5, "time", 0.0, 1e4, "simulated time between snapshots [s]", "(]")
    gauge_x: Optional[float] = _p(None, "length", 0.0, 100.0,
                                  "x of the upstream water-level gauge [m]; default halfway to the weir", "(]")
    figures: bool = _flag(True, "write the figures at the end of the run")
    animation: bool = _flag(True, "write an animation of the run (mp4 with ffmpeg, gif otherwise)")
    animation_fps: float = _p(10.0, None, 0.0, 120.0, "frames per second of the animation", "(]")

    def validate(self, prefix: str = "output") -> None:
        self._validate_fields(prefix)


_SECTIONS = {"flume": Flume, "weir": Weir, "stones": Stones, "hydrograph": Hydrograph, "grid": GridSpec,
             "numerics": Numerics, "effects": Effects, "output": Output, "reference": Reference}
# sections written to a scene file only when they differ from their defaults
_OPTIONAL_SECTIONS = ("reference",)
# list keys whose entries may carry a unit, and the kind of that unit
_LIST_KINDS = {"positions": None, "grading_diameters": "length", "grading_passing": None, "times": "time", "discharge_lps": "discharge", "diameters": "length",
               "stage_lps": "discharge", "stage_times": "time", "model_stage_lps": "discharge",
               "model_stage_times": "time"}
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
    reference: Reference = field(default_factory=Reference)
    zones: List[Zone] = field(default_factory=list)
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
        of flume upstream of the weir; a spin-up of 20 s at 10 l/s before the ramp; a domain 0.38 m
        high (the water's highest surface at 25 l/s is 0.30-0.325 m, docs/scenario.md); the fluid's CFL 0.5.
        """
        weir = Weir()
        flume = Flume(length=round(weir.x_toe_down + 1.5, 6))
        return cls(name="maeno2008", flume=flume, weir=weir, reference=maeno2008_reference())

    def quick(self) -> "Scene":
        """A shorter, coarser copy that runs in a few minutes on one core.

        Same weir and stones; the grid is twice as coarse (5 cm x 2 cm, 1 cm at the bed: the draft
        preset's grid, fidelity.py; a scene at a preset becomes 'draft'), the flume's
        reaches are shortened to 0.6 m upstream and 0.8 m downstream, the spin-up lasts 5 s and the
        ramp 10 -> 25 l/s lasts 30 s (four times faster than the paper's), snapshots every 0.5 s.
        Stage discharges of a quick run are not comparable with the paper: the discharge rises four
        times faster than the stones' response time allows for. The reference's stage times are
        dropped (another clock); its discharges are kept for orientation. A measured (CSV) flood runs
        four times faster as well (time_scale x 0.25, spin-up at most 5 s), and --until-failure's rate is
        four times the scene's.
        """
        s = copy.deepcopy(self)
        s.name = self.name + "_quick"
        shift = s.weir.toe_x - 0.6
        s.weir.toe_x = 0.6
        if s.weir.outline:
            s.weir.outline = [[x - shift, z] for x, z in s.weir.outline]
        for zn in s.zones:
            zn.outline = [[x - shift, z] for x, z in zn.outline]
        if s.stones.positions:
            s.stones.positions = [[x - shift, z] for x, z in s.stones.positions]
        s.flume.length = round(s.weir.x_toe_down + 0.8, 6)
        s.grid = GridSpec(dx=0.05, dz=0.02, dz_bed=0.01, bed_layer_height=0.01)
        if s.numerics.fidelity is not None:  # the grid is the draft preset's
            s.numerics.fidelity = "draft"
        h = s.hydrograph
        if h.function is None and h.kind in ("ramp", "csv", "until_failure"):
            h.spin_up_duration = min(h.spin_up_duration, 5.0)
        if h.kind == "ramp" and h.function is None:
            h.ramp_duration = 30.0
        elif h.kind == "csv":  # the measured flood four times faster, as the ramp
            h.time_scale *= 0.25
        h.until_failure_rate_lps_per_s *= 4.0
        s.end_time = None
        s.output.snapshot_interval = 0.5
        s.reference = s.reference.without_times()
        s.validate()
        return s

    def until_failure(self) -> "Scene":
        """A copy whose discharge rises slowly until the weir fails (``vofdem run --until-failure``):
        held at the first discharge of the scene's rise for its spin-up, then raised linearly at
        `hydrograph.until_failure_rate_lps_per_s` up to the scene's largest discharge; the run stops at
        the first destruction stage (flood.py). The reference's stage times are dropped (another clock)."""
        from .flood import until_failure_hydrograph

        s = copy.deepcopy(self)
        s.name = self.name + "_until_failure"
        s.hydrograph = until_failure_hydrograph(self.hydrograph)
        s.end_time = None
        s.reference = s.reference.without_times()
        return s.validate()

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
        self._validate_zones()
        self._validate_geometry()
        self._validate_model_packing()
        from .fidelity import check

        check(self)
        return self

    def _validate_model_packing(self) -> None:
        # stones the outline packer (outline_packing.py) cannot place are packed by pack_weir (a trapezoid
        # of uniform sizes) or given explicitly
        s, w = self.stones, self.weir
        if front(s.shape).outline_packer or s.positions:
            return
        from .outline import as_trapezoid

        why = ("zones (zones[0])" if self.zones else
               "a sieve curve (stones.grading_diameters/grading_passing or d15/d50/d85)" if s.grading() is not None else
               f"weir.outline = {w.outline!r}, not a trapezoid" if w.outline and as_trapezoid(w.outline) is None else "")
        if why:
            placed = [k for k in _core.stone_model_names() if _has_front(k) and front(k).outline_packer]
            raise ValueError(f"stones.shape = {s.shape!r} is outside the allowed values {placed} with {why}: the outline "
                             f"packer cannot place {s.shape} stones; they need a trapezoid weir of sizes uniform in "
                             "stones.diameter +- diameter_spread, or explicit stones.positions")

    def _validate_zones(self) -> None:
        if not isinstance(self.zones, (list, tuple)):
            raise ValueError(f"zones = {self.zones!r} must be a list of zones ([[zones]] tables)")
        names = []
        for j, zn in enumerate(self.zones):
            if not isinstance(zn, Zone):
                raise ValueError(f"zones[{j}] must be a Zone, got {type(zn).__name__}")
            zn.validate(f"zones[{j}]")
            if zn.name in names:
                raise ValueError(f"zones[{j}].name = {zn.name!r} is taken by zones[{names.index(zn.name)}]")
            names.append(zn.name)
        if self.zones and self.stones.positions:
            raise ValueError("zones: zones are packed by the generator; they cannot be used with explicit "
                             "stones.positions")

    def largest_diameter(self) -> float:
        """The largest stone the scene can hold [m]: explicit, of the core's grading or of a zone's."""
        d = [self.stones.max_diameter()] + [zn.grading().d_max for zn in self.zones]
        return max(d)

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
        if self.largest_diameter() >= w.height and not s.positions:
            raise ValueError(f"stones.diameter = {self.largest_diameter():.4g} m (the largest stone) must be smaller than "
                             f"weir.height = {w.height:.4g} m to build the weir")
        if g.dx >= f.length / 4 or g.dz >= f.height / 4:
            raise ValueError(f"grid.dx = {g.dx:.4g} m / grid.dz = {g.dz:.4g} m is too coarse: the flume needs at "
                             f"least 4 cells each way (length {f.length:.4g} m, height {f.height:.4g} m)")
        if not front(s.shape).lookup_table and self.numerics.porosity_method == "lookup":
            raise ValueError("numerics.porosity_method = 'lookup' (the paper's table of disc areas) is for disc "
                             f"stones; stones.shape = {s.shape!r} needs porosity_method = 'exact'")
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
            if key in _OPTIONAL_SECTIONS and sec == type(sec)():
                continue
            out[key] = section_dict(sec)
            if key == "weir" and sec.outline:  # the outline replaces the trapezoid's keys
                for k in TRAPEZOID_KEYS:
                    out[key].pop(k)
        if self.zones:
            out["zones"] = [section_dict(zn) for zn in self.zones]
        h = self.hydrograph
        if h.function is not None:
            t, q = h.table(self.duration)
            out["hydrograph"].update(kind="table", times=[float(x) for x in t],
                                     discharge_lps=[float(x) * 1e3 for x in q])
        return out

    @classmethod
    def from_dict(cls, data: Dict[str, Any], source: str = "scene", base_dir: Optional[str] = None) -> "Scene":
        """Builds and validates a scene from a (TOML-like) dict; ValueError on any problem. base_dir: the
        directory files named in the scene (a CSV flood) are relative to (default the working one)."""
        if not isinstance(data, dict):
            raise ValueError(f"{source}: a scene must be a table of sections")
        from .fidelity import fill_table

        data = copy.deepcopy(data)
        fill_table(data)  # a preset's values where the file does not give them
        valid_top = set(_TOP_KEYS) | set(_SECTIONS) | {"zones"}
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
            args = section_args(sec_cls, table, key, _LIST_KINDS)
            if key == "hydrograph":
                args["base_dir"] = base_dir
            if key == "weir" and args.get("outline"):
                both = [k for k in TRAPEZOID_KEYS if k in table]
                if both:
                    raise ValueError(f"weir.{both[0]}: the weir is given by weir.outline; its height, crest, slopes "
                                     f"and toe come from the outline (give one or the other)")
            kwargs[key] = sec_cls(**args)
        if "zones" in data:
            zones = data["zones"]
            if not isinstance(zones, list) or not all(isinstance(z, dict) for z in zones):
                raise ValueError(f"zones = {zones!r} must be a list of tables ([[zones]] in a scene file)")
            kwargs["zones"] = [Zone(**section_args(Zone, z, f"zones[{j}]", _LIST_KINDS)) for j, z in enumerate(zones)]
        return cls(**kwargs)

    def to_toml(self) -> str:
        """The scene as TOML text (what `load_scene` reads back to an equal scene)."""
        d = self.to_dict()
        lines = [f"# vofdem scene '{self.name}' (SI units; angles *_deg in degrees, discharges *_lps in l/s)"]
        lines += toml_table(None, {k: d[k] for k in _TOP_KEYS if k in d})
        for key in _SECTIONS:
            if key in d:
                lines += [""] + toml_table(f"[{key}]", d[key])
        for zone in d.get("zones", []):
            lines += [""] + toml_table("[[zones]]", zone)
        return "\n".join(lines) + "\n"

    @classmethod
    def from_toml(cls, text: str, source: str = "scene", base_dir: Optional[str] = None) -> "Scene":
        data = parse_toml(text, source)
        if not data:
            raise ValueError(f"{source}: the scene is empty (no keys, no sections); write at least the sections "
                             f"that differ from the defaults, e.g. [flume], or run the ready scene 'maeno2008'")
        return cls.from_dict(data, source, base_dir)

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
        if section == "weir" and name in TRAPEZOID_KEYS and s.weir.outline:
            raise ValueError(f"{key}: the weir is given by weir.outline; its {name} comes from the outline")
        setattr(getattr(s, section), name, _parse_quantity(key, value, md.get("kind")) if "lo" in md else value)
        if key == "hydrograph.file":  # another flood: read it
            s.hydrograph.times, s.hydrograph.discharge_lps = [], []
        if key == "numerics.fidelity":  # a preset sets its knobs
            from .fidelity import apply

            apply(s, value)
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
        return Scene.from_toml(p.read_text(encoding="utf-8"), source=str(p), base_dir=str(p.parent))
    except ValueError as e:
        msg = str(e)
        raise ValueError(msg if msg.startswith(str(p)) else f"{p}: {msg}") from None


def describe_parameters() -> str:
    """A markdown table of every scene parameter: section, name, default, range, meaning."""
    return describe([*_SECTIONS.items(), ("zones[]", Zone)])
