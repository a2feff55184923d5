"""Closure laws of the seed paper with numpy broadcasting: porous resistance and stone drag."""
from __future__ import annotations

import numpy as np

from . import _core

# the core's water (Medium), the one source of its values
WATER_DENSITY = _core.Medium().rho_water  # kg/m^3, 998.2
WATER_VISCOSITY = _core.Medium().nu_water  # kinematic, m^2/s, 1.004e-6


def porous_resistance(u, w, n, d, nu=WATER_VISCOSITY, k1=_core.PAPER_K1, k2=_core.PAPER_K2):
    """Porous resistance per unit mass (Rx, Rz) [m/s^2] of seed eqs. (5)-(7), against the flow.

    u, w: superficial velocity [m/s]; n: porosity in (0, 1]; d: stone diameter [m];
    nu: kinematic viscosity [m^2/s]; k1, k2: the paper's (200, 2.8), Ergun's are (150, 1.75).
    Returns floats for scalar input and arrays for array input (numpy broadcasting).
    """
    rx = _core._porous_resistance_x(u, w, n, d, nu, k1, k2)
    rz = _core._porous_resistance_z(u, w, n, d, nu, k1, k2)
    return _unwrap(rx), _unwrap(rz)


def drag_force(u, w, up, wp, d, rho=WATER_DENSITY, nu=WATER_VISCOSITY, law=_core.DragLaw.PAPER):
    """Drag (Fx, Fz) [N] on a stone of diameter d [m] (seed eqs. 16-18).

    (u, w): pore velocity of the water U = u/n [m/s]; (up, wp): stone velocity [m/s];
    rho [kg/m^3], nu [m^2/s]; law: DragLaw.PAPER (0.4 + 24/Re) or DragLaw.SCHILLER_NAUMANN.
    """
    fx = _core._drag_force_x(u, w, up, wp, d, rho, nu, law)
    fz = _core._drag_force_z(u, w, up, wp, d, rho, nu, law)
    return _unwrap(fx), _unwrap(fz)


def _unwrap(a):
    a = np.asarray(a)
    return float(a) if a.ndim == 0 else a
