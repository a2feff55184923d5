"""Helpers for the flow solver `VOFGrid`: discharge tables from callables, the paper's ramp, scenes.

Discharges are in m^3/s unless a name says l/s (``discharge_lps``). The table lives in C++ so that
``VOFGrid.advance`` runs without the GIL; a Python callable is sampled into it once.
"""
from __future__ import annotations

import numpy as np

from . import _core

__all__ = ["discharge_table", "linear_ramp", "paper_discharge_ramp", "set_discharge", "dam_break", "tank_params"]


def linear_ramp(q0: float, q1: float, t0: float, t1: float) -> _core.DischargeTable:
    """Discharge rising linearly from q0 to q1 [m^3/s] over [t0, t1] [s], constant outside."""
    return _core.DischargeTable.ramp(q0, q1, t0, t1)


def paper_discharge_ramp() -> _core.DischargeTable:
    """The seed paper's discharge: 10 -> 25 l/s linearly over 120 s."""
    return linear_ramp(0.010, 0.025, 0.0, 120.0)


def discharge_table(q, t_end: float | None = None, dt: float = 0.1, t_start: float = 0.0,
                    discharge_lps: bool = False) -> _core.DischargeTable:
    """A DischargeTable from a constant, a callable Q(t) or a table.

    q: a number, a callable of time [s], or a pair (times [s], discharges); sampled every dt [s] on
    [t_start, t_end] when callable. discharge_lps: the values are in l/s (else m^3/s).
    """
    scale = 1e-3 if discharge_lps else 1.0
    if isinstance(q, _core.DischargeTable):
        return q
    if callable(q):
        if t_end is None or not (dt > 0 and t_end > t_start):
            raise ValueError(f"need dt > 0 and t_end > t_start, got dt={dt}, t_start={t_start}, t_end={t_end}")
        n = int(np.ceil((t_end - t_start) / dt)) + 1
        times = np.linspace(t_start, t_end, n)
        values = np.array([float(q(t)) for t in times]) * scale
        return _core.DischargeTable(times.tolist(), values.tolist())
    if isinstance(q, tuple) and len(q) == 2:
        times, values = q
        return _core.DischargeTable(list(map(float, times)), [float(v) * scale for v in values])
    return _core.DischargeTable.constant(float(q) * scale)


def set_discharge(flow: _core.VOFGrid, q, t_end: float | None = None, dt: float = 0.1,
                  discharge_lps: bool = False) -> _core.DischargeTable:
    """Sets the inlet discharge of `flow` from a number, a callable Q(t), a (times, values) pair or a
    DischargeTable (see discharge_table); a callable is sampled every dt [s] from flow.time to t_end."""
    table = discharge_table(q, t_end=t_end, dt=dt, t_start=flow.time, discharge_lps=discharge_lps)
    flow.discharge = table
    return table


def tank_params() -> _core.FlowParams:
    """FlowParams of the classical flow cases in a closed tank (the dam break, the validation's and the
    cost studies' tanks): walls at both ends, laminar, CFL 0.4 and a pressure tolerance of 1e-8 (the
    cases measure the VOF and the projection themselves), k-epsilon point-implicit when switched on. A
    scene's flow takes the core's defaults instead (its options, docs/scenario.md)."""
    p = _core.FlowParams()
    p.cfl, p.pressure_tol = 0.4, 1e-8
    E = _core.FlowEffect
    p.flags = int(E.FREE_SURFACE | E.POROUS_RESISTANCE | E.VISCOSITY | E.GRAVITY | E.CONVECTION)
    p.outlet = _core.OutletBoundary.WALL
    p.turbulence_time_scheme = _core.KEpsilonTimeScheme.POINT_IMPLICIT
    return p


def dam_break(a: float = 0.05715, cells_per_a: int = 8, length_in_a: float = 5.0, height_in_a: float = 2.5,
              params: _core.FlowParams | None = None) -> _core.VOFGrid:
    """The Martin & Moyce (1952) dam break: a water column a wide and 2a high in a closed tank.

    a [m]: column width; cells_per_a: resolution; the tank is length_in_a * a long and
    height_in_a * a high (open top), in int(length_in_a * cells_per_a) by int(height_in_a * cells_per_a)
    cells. Returns a VOFGrid at rest with the column filled. params: default `tank_params()`. The one
    dam-break set-up (the validation's dam_break_front runs it).
    """
    nx = int(length_in_a * cells_per_a)
    nz = int(height_in_a * cells_per_a)
    grid = _core.Grid2D.uniform(nx, nz, length_in_a * a, height_in_a * a)
    flow = _core.VOFGrid(grid, params if params is not None else tank_params())
    flow.fill_water_box(0.0, a, 0.0, 2.0 * a)
    return flow
