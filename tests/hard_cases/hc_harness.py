"""The hard-case catalogue's registry, small scenes and the checks every case draws on.

A case is a function that builds a small scene, runs it, asserts what must hold and returns the
figures it measured (for the table in docs/hard_cases.md). It is registered with `@case(...)`, which
states in words what is hard and what must hold; `xfail` (a reason) marks a case that fails today and
cannot be fixed yet: it runs as a strict expected failure, so a fix shows up as an unexpected pass.
"""
from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Callable, Dict, List, Optional

import numpy as np

import vofdem
from vofdem import _core
from vofdem.flow import tank_params

RHO_W = tank_params().rho_water
G = 9.81
D = 0.048  # the paper's stone [m]


@dataclass
class Case:
    name: str  # says what is hard
    group: str  # flow, stones, coupled, errors
    hard: str  # why the case is hard, one line
    must_hold: str  # what the case asserts, with its tolerances
    run: Callable[[], Dict[str, str]]
    xfail: Optional[str] = None  # why it fails today (strict expected failure)


CASES: List[Case] = []


def case(name: str, group: str, hard: str, must_hold: str, xfail: Optional[str] = None):
    """Registers a hard case (the decorated function returns its measured figures as strings)."""

    def deco(fn):
        if any(c.name == name for c in CASES):
            raise ValueError(f"hard case {name!r} registered twice")
        CASES.append(Case(name, group, hard, must_hold, fn, xfail))
        return fn

    return deco


# ---------------------------------------------------------------------------------------- scenes
def flow_params(**kw):
    p = tank_params()
    for k, v in kw.items():
        setattr(p, k, v)
    return p


def tank(width: float, height: float, h: float, level: Optional[float], hz: Optional[float] = None, **params):
    """A VOFGrid of cells h x hz [m] (hz = h by default), water below `level` [m] at rest."""
    grid = vofdem.Grid2D.uniform(int(round(width / h)), int(round(height / (hz or h))), width, height)
    fluid = vofdem.VOFGrid(grid, flow_params(**params))
    fluid.cell_stone_diameter[...] = D
    if level is not None:
        fluid.fill_water_below(level)
    fluid.set_hydrostatic_pressure()
    return fluid


def dem_params(x0: float, x1: float, wet: bool = True, **kw):
    """DEMParams of a flume [x0, x1] (bed z = 0, both end walls), water density if wet."""
    p = vofdem.DEMParams()
    p.submerged = wet
    p.add_flume(x0, x1, 0.0)
    for k, v in kw.items():
        setattr(p, k, v)
    return p


def stones(params, pos, d=D, density=2650.0, fixed=None):
    pos = np.asarray(pos, float).reshape(-1, 2)
    n = len(pos)
    d = np.broadcast_to(np.asarray(d, float), (n,))
    dens = np.broadcast_to(np.asarray(density, float), (n,))
    return vofdem.DEMSystem(params, pos=pos, radius=0.5 * d, density=np.array(dens),
                            fixed=[int(f) for f in (fixed if fixed is not None else [0] * n)])


def couple(fluid, dem, flags=None, **kw):
    cp = _core.CouplerParams()
    if flags is not None:
        cp.flags = int(flags)
    for k, v in kw.items():
        setattr(cp, k, v)
    if fluid is not None and dem is not None and dem.n > 0 and cp.flags & _core.COUPLE_POROSITY:
        fp = fluid.params  # two-way: the flow resists relative to the stones (its own flag)
        fp.flags = int(fp.flags) | int(vofdem.FlowEffect.RELATIVE_VELOCITY)
        fluid.params = fp
    return _core.Coupler(fluid, dem, cp)


def weir_scene(**changes):
    """The quick variant of the Maeno 2008 scene (5 cm x 2 cm cells, 80 stones), with section fields
    changed as section__field=value (e.g. flume__height=1.0)."""
    from vofdem.scene import Scene

    s = Scene.maeno2008().quick()
    for key, value in changes.items():
        sec, name = key.split("__")
        setattr(getattr(s, sec), name, value)
    return s.validate()


def build(scene):
    from vofdem.builder import build_simulation

    return build_simulation(scene)


def release_after(sim, t_hold: float):
    """Holds every stone for t_hold [s] of flow (the run loop's spin-up), then releases the loose ones."""
    fixed0 = np.array(sim.stones.stone_fixed, copy=True)
    sim.stones.stone_fixed[:] = 1
    sim.advance(sim.time + t_hold)
    sim.stones.stone_fixed[:] = fixed0


# ---------------------------------------------------------------------------------------- checks
def fields_bounded(fluid, speed_limit: float) -> Dict[str, float]:
    """Asserts finite fields, F and n in [0, 1] and superficial speeds below speed_limit [m/s];
    returns the largest speed and the largest excursion of F."""
    F = np.asarray(fluid.cell_F)
    for name in ("cell_F", "cell_p", "face_u", "face_w", "cell_porosity"):
        a = np.asarray(getattr(fluid, name))
        assert np.isfinite(a).all(), f"{name} holds non-finite values"
    assert F.min() >= -1e-9 and F.max() <= 1 + 1e-9, f"F outside [0, 1]: {F.min()} .. {F.max()}"
    n = np.asarray(fluid.cell_porosity)
    assert n.min() >= 0.0 and n.max() <= 1.0
    umax = max(np.abs(np.asarray(fluid.face_u)).max(), np.abs(np.asarray(fluid.face_w)).max())
    assert umax < speed_limit, f"speed {umax:.3g} m/s above the bound {speed_limit} m/s"
    return {"umax": float(umax), "F_excess": float(max(-F.min(), F.max() - 1.0, 0.0))}


def _budget_scale(fluid, v0: float) -> float:
    return max(v0, fluid.inlet_volume, abs(fluid.net_inflow_volume))


def budget_error(fluid, v0: float) -> float:
    """Relative error of the water budget: stored water against start + net boundary inflow + the water the
    advection's divergence correction made where the pressure solve left a residual divergence, relative
    to the larger of the start volume and the water that came in."""
    expected = v0 + fluid.net_inflow_volume + fluid.dilatation_volume
    return abs(fluid.water_volume() - expected) / _budget_scale(fluid, v0)


# the water the pressure solve's residual divergence may make over a case, as a share of the volume per
# unit of its relative tolerance: measured at most 0.06 over the catalogue at 1e-5 (the scenes'), 0.02-0.03
# at 1e-6 to 1e-8, scaling with the tolerance there; above 1e-5 it grows faster than the tolerance (at
# 1e-4 one case makes 0.12: docs/pressure_solver.md)
RESIDUAL_WATER_PER_TOLERANCE = 0.1


class Budget(float):
    """A budget error that also carries the residual divergence's share of the water (`dilatation`)."""
    dilatation: float = 0.0


def assert_budget(fluid, v0: float, tol: float) -> Budget:
    """Asserts the water budget closed to tol, and the water made by the pressure solve's residual
    divergence below RESIDUAL_WATER_PER_TOLERANCE x its relative tolerance."""
    err = Budget(budget_error(fluid, v0))
    assert err <= tol, f"water budget off by {err:.3g} of the water volume (allowed {tol:g})"
    err.dilatation = abs(fluid.dilatation_volume) / _budget_scale(fluid, v0)
    bound = RESIDUAL_WATER_PER_TOLERANCE * fluid.params.pressure_tol
    assert err.dilatation <= bound, (f"the pressure solve's residual divergence made {err.dilatation:.3g} of the "
                                     f"water volume (allowed {bound:g}, tolerance {fluid.params.pressure_tol:g})")
    return err


def budget_text(err: Budget) -> str:
    """The budget error for the table, with the residual divergence's water."""
    return f"{fmt(err, 2)} (residual divergence's water {fmt(err.dilatation, 2)})"


def stones_accounted(dem, x_range, z_range, margin: float = 0.0) -> Dict[str, int]:
    """Every stone is active and inside the box (with margin [m]) or deactivated and counted."""
    pos = np.asarray(dem.stone_pos)
    active = np.asarray(dem.stone_active).astype(bool)
    assert np.isfinite(pos).all(), "a stone position is not finite"
    assert int((~active).sum()) == dem.removed_count, \
        f"{int((~active).sum())} stones inactive but removed_count = {dem.removed_count}"
    x, z = pos[active].T
    r = np.asarray(dem.stone_radius)[active]
    inside = (x >= x_range[0] - margin) & (x <= x_range[1] + margin) & (z >= z_range[0] - margin) \
        & (z <= z_range[1] + margin)
    assert inside.all(), f"active stones outside the domain: {np.flatnonzero(~inside).tolist()}"
    below = z - r < z_range[0] - 0.5 * r
    assert not below.any(), f"stones sunk through the bed: {np.flatnonzero(below).tolist()}"
    return {"active": int(active.sum()), "removed": int(dem.removed_count)}


def fmt(v: float, digits: int = 3) -> str:
    """A number for the table: 3 significant digits."""
    if v == 0 or not math.isfinite(v):
        return str(v)
    return f"{v:.{digits}g}"
