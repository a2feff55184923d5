"""Porosity of the cells from stone discs (seed paper section 2.4, eq. 11), Python front.

The work is done by ``PorosityMapper`` in the C++ core; this module builds it from plain arguments.
"""
from __future__ import annotations

import numpy as np

from . import _core

N_EXP = 0.41  # packing porosity of the paper's stones [-]

_METHODS = {"exact": _core.PorosityMethod.EXACT, "lookup": _core.PorosityMethod.LOOKUP}


def make_porosity_mapper(grid, r_min, r_max, method="exact", m=8, n_exp=N_EXP, dr=1e-3, max_discs=1024):
    """A ``PorosityMapper`` for ``grid`` and radii in [r_min, r_max] [m].

    method: "exact" (closed-form areas) or "lookup" (the paper's table, m x m sub-areas per cell);
    n_exp: packing porosity [-]; dr: radius node spacing of the lookup tables [m];
    max_discs: the largest number of discs one call maps.
    """
    if method not in _METHODS:
        raise ValueError(f"method = {method!r} is outside the allowed values {sorted(_METHODS)}")
    p = _core.PorosityParams()
    p.method = _METHODS[method]
    p.m = int(m)
    p.n_exp = float(n_exp)
    p.r_min = float(r_min)
    p.r_max = float(r_max)
    p.dr = float(dr)
    p.max_discs = int(max_discs)
    return _core.PorosityMapper(grid, p)


def porosity_from_discs(grid, disc_x, disc_z, disc_d, method="exact", m=8, n_exp=N_EXP):
    """Cell porosity (nz, nx) [-] of eq. (11) for discs of centres (disc_x, disc_z) [m], diameters disc_d [m]."""
    x = np.ascontiguousarray(disc_x, dtype=float).ravel()
    z = np.ascontiguousarray(disc_z, dtype=float).ravel()
    r = 0.5 * np.ascontiguousarray(disc_d, dtype=float).ravel()
    if not (x.size == z.size == r.size):
        raise ValueError("disc_x, disc_z and disc_d must have the same length")
    if r.size == 0:
        return np.ones((grid.nz, grid.nx))
    if not np.all(np.isfinite(r) & (r > 0)):
        bad = float(r[~(np.isfinite(r) & (r > 0))][0])
        raise ValueError(f"disc_d = {2 * bad!r} is outside the allowed range (0, inf)")
    mapper = make_porosity_mapper(grid, r.min(), r.max(), method=method, m=m, n_exp=n_exp, max_discs=r.size)
    mapper.map(x, z, r)
    return np.array(mapper.cell_porosity)
