"""Deterministic packings of stone discs: a trapezoidal rubble mound weir.

The packing drops discs layer by layer: each disc, at its x position, falls until it rests on the
bed or on a disc already placed (no overlap), and is kept only if it lies inside the trapezoid.
Diameters are drawn uniformly from d_mean (1 +- spread) with a seeded generator, so the same
arguments always give the same packing. It is a geometric initial state (like the paper's Fig. 2
before the free packing under gravity), not a mechanical equilibrium.
"""
from __future__ import annotations

import math

import numpy as np


def trapezoid_weir_discs(height=0.25, crest=0.20, slope_deg=27.0, d_mean=0.048, spread=0.10, x_toe=0.0, seed=0,
                         gap=5e-4):
    """Disc centres (x, z) [m] and diameters d [m] of a trapezoidal weir on the bed z = 0.

    height [m] (0.25 in the paper's experiment), crest width [m] (0.20), slope_deg: both slopes [deg]
    (27), d_mean: mean stone diameter [m] (0.048), spread: relative half-range of the diameters (0.10),
    x_toe: x of the upstream toe [m], seed: random seed, gap: horizontal clearance between discs [m].
    Returns three arrays (x, z, d) sorted by layer then x.
    """
    if not (height > 0 and crest >= 0 and 0 < slope_deg < 90 and d_mean > 0 and 0 <= spread < 1):
        raise ValueError("height > 0, crest >= 0, slope_deg in (0, 90), d_mean > 0, spread in [0, 1) required")
    rng = np.random.default_rng(seed)
    cot = 1.0 / math.tan(math.radians(slope_deg))
    base = crest + 2.0 * height * cot
    inset = 1.0 / math.sin(math.radians(slope_deg))  # horizontal distance to a slope per unit normal distance

    def inside(x, z, r):
        # the whole disc under the crest and between the slopes
        return z + r <= height + 1e-12 and x - x_toe - z * cot >= r * inset and x_toe + base - z * cot - x >= r * inset

    xs, zs, rs = [], [], []
    layer = 0
    while True:
        placed = 0
        x = x_toe + (0.5 * d_mean if layer % 2 else 0.0)
        while x < x_toe + base:
            r = 0.5 * d_mean * (1.0 + spread * rng.uniform(-1.0, 1.0))
            cx = x + r
            z = _drop_height(cx, r, xs, zs, rs)
            if inside(cx, z, r):
                xs.append(cx)
                zs.append(z)
                rs.append(r)
                placed += 1
            x = cx + r + gap
        if placed == 0:
            break
        layer += 1
    return np.array(xs), np.array(zs), 2.0 * np.array(rs)


def _drop_height(x, r, xs, zs, rs):
    """Lowest centre height of a disc at abscissa x resting on the bed or on the discs placed."""
    z = r
    for xj, zj, rj in zip(xs, zs, rs):
        dx = abs(x - xj)
        reach = r + rj
        if dx < reach:
            z = max(z, zj + math.sqrt(reach * reach - dx * dx))
    return z
