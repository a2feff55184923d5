"""Stone gradings: a sieve curve, the stones drawn from it by mass, and the packed weir's own curve.

**The curve.** A grading is the mass fraction F(d) of the stones passing a sieve of size d, given as
points (d_k [m], F_k) with F from 0 (the smallest stone) to 1 (the largest), interpolated linearly in
ln d between them (a straight line between two points of the usual semi-log sieve chart), or as
d15 / d50 / d85 (the sizes that 15, 50 and 85 % of the mass passes): the same interpolation through
those three points, continued beyond them with the slopes of the neighbouring segment down to F = 0
and up to F = 1, i.e. d0 = d15 (d15/d50)^(15/35) and d100 = d85 (d85/d50)^(15/35).

**Drawing by mass.** A sieve curve weighs stones: a stone of diameter d has the mass of the sphere of
that diameter, m ~ d^3 (the model's stones, dem_system.h). So the number of stones per size must go
as the curve's mass density over d^3: with F linear in ln d on a segment, dF/dd = c / d and the
number density n(d) ~ c / d^4, whose cumulative on [a, x] is c (a^-3 - x^-3) / 3. A diameter is drawn
by inverting that number cumulative at a uniform u. The u come in blocks of `BLOCK` (128) strata, (j + v_j)
/ BLOCK with v_j uniform, in a shuffled order, from numpy's default generator seeded with the scene's
seed: any run of draws reproduces the curve more closely than independent draws would (at most one
stone per stratum and block), and the sizes are not ordered in space.

**The packed weir's curve.** F_packed(d) = sum of d_i^3 over stones with d_i <= d, divided by the sum
over all (`mass_passing`), compared with the requested curve in `reports.grading_table` and `reports.fig_grading`.
"""
from __future__ import annotations

import math
from dataclasses import dataclass
from typing import List, Optional, Sequence

import numpy as np

BLOCK = 128  # strata per block of draws


@dataclass(frozen=True)
class Grading:
    """A sieve curve: diameters [m] (increasing) and mass fractions passing (0 first, 1 last, not decreasing)."""

    diameters: tuple
    passing: tuple

    @classmethod
    def from_points(cls, diameters: Sequence[float], passing: Sequence[float], name: str = "grading") -> "Grading":
        d, p = [float(v) for v in diameters], [float(v) for v in passing]
        check_points(d, p, name)
        return cls(tuple(d), tuple(p))

    @classmethod
    def from_d(cls, d15: float, d50: float, d85: float, name: str = "grading") -> "Grading":
        if not 0 < d15 < d50 < d85:
            raise ValueError(f"{name}: d15 = {d15:g} m, d50 = {d50:g} m, d85 = {d85:g} m must increase "
                             f"(0 < d15 < d50 < d85)")
        k = 15.0 / 35.0
        d0, d100 = d15 * (d15 / d50) ** k, d85 * (d85 / d50) ** k
        return cls((d0, d15, d50, d85, d100), (0.0, 0.15, 0.5, 0.85, 1.0))

    @property
    def d_min(self) -> float:
        return self.diameters[0]

    @property
    def d_max(self) -> float:
        return self.diameters[-1]

    def d(self, p: float) -> float:
        """The size [m] that a mass fraction p of the stones passes (d50 = d(0.5))."""
        lnd = np.log(self.diameters)
        return float(np.exp(np.interp(p, self.passing, lnd)))

    def passing_at(self, d) -> np.ndarray:
        """F(d): the mass fraction passing size d [m] (array)."""
        return np.interp(np.log(np.asarray(d, float)), np.log(self.diameters), self.passing)

    def _segments(self):
        """Per segment with mass: (a, b, c = dF / d ln d, number weight) and the number cumulative."""
        segs = []
        for a, b, fa, fb in zip(self.diameters, self.diameters[1:], self.passing, self.passing[1:]):
            if fb > fa:
                c = (fb - fa) / math.log(b / a)
                segs.append((a, b, c, c * (a ** -3 - b ** -3) / 3.0))
        w = np.array([s[3] for s in segs])
        return segs, np.concatenate([[0.0], np.cumsum(w) / w.sum()])

    def number_cdf(self, d) -> np.ndarray:
        """The share of stones (by number, drawn by mass) smaller than d [m]."""
        segs, cum = self._segments()
        total = sum(s[3] for s in segs)
        d = np.atleast_1d(np.asarray(d, float))
        out = np.zeros_like(d)
        for j, (a, b, c, w) in enumerate(segs):
            x = np.clip(d, a, b)
            out = np.where(d > a, cum[j] + c * (a ** -3 - x ** -3) / 3.0 / total, out)
        return np.clip(out, 0.0, 1.0)

    def inverse_number_cdf(self, u) -> np.ndarray:
        """Diameters [m] at number-cumulative levels u in [0, 1) (the draw by mass, module docstring)."""
        segs, cum = self._segments()
        u = np.atleast_1d(np.asarray(u, float))
        k = np.clip(np.searchsorted(cum, u, side="right") - 1, 0, len(segs) - 1)
        out = np.empty_like(u)
        total = sum(s[3] for s in segs)
        for j, (a, b, c, _) in enumerate(segs):
            sel = k == j
            if sel.any():
                inner = (u[sel] - cum[j]) * total  # number weight into the segment
                out[sel] = np.minimum((a ** -3 - 3.0 * inner / c) ** (-1.0 / 3.0), b)
        return out

    def mean_number_diameter(self) -> float:
        """Number-weighted mean diameter [m] of stones drawn by mass."""
        u = (np.arange(4096) + 0.5) / 4096
        return float(self.inverse_number_cdf(u).mean())


def check_points(d: List[float], p: List[float], name: str) -> None:
    """The rules of a sieve curve's points, ValueError naming `name`."""
    if len(d) != len(p):
        raise ValueError(f"{name}_diameters has {len(d)} entries, {name}_passing has {len(p)}: they must match")
    if len(d) < 2:
        raise ValueError(f"{name}_diameters needs two points at least (the smallest and the largest stone)")
    if any(not (math.isfinite(v) and v > 0) for v in d) or any(b <= a for a, b in zip(d, d[1:])):
        raise ValueError(f"{name}_diameters = {d} must be positive sizes [m] that increase strictly")
    if any(not math.isfinite(v) for v in p) or any(b < a for a, b in zip(p, p[1:])):
        raise ValueError(f"{name}_passing = {p} must be mass fractions that do not decrease")
    if p[0] != 0.0 or p[-1] != 1.0:
        raise ValueError(f"{name}_passing = {p} must run from 0 (the smallest stone) to 1 (the largest): "
                         f"first {p[0]:g}, last {p[-1]:g}")


class Sampler:
    """Diameters drawn by mass from a grading in stratified, shuffled blocks (module docstring)."""

    def __init__(self, grading: Grading, rng: np.random.Generator):
        self.grading, self.rng = grading, rng
        self._queue: List[float] = []

    def draw(self) -> float:
        if not self._queue:
            u = (self.rng.permutation(BLOCK) + self.rng.random(BLOCK)) / BLOCK
            self._queue = list(self.grading.inverse_number_cdf(u)[::-1])
        return float(self._queue.pop())


def mass_passing(diameters, sizes) -> np.ndarray:
    """The mass fraction of stones of `diameters` [m] (masses ~ d^3) passing each of `sizes` [m]."""
    d = np.sort(np.asarray(diameters, float))
    m = np.cumsum(d ** 3)
    idx = np.searchsorted(d, np.asarray(sizes, float), side="right")
    return np.where(idx > 0, m[np.maximum(idx - 1, 0)], 0.0) / m[-1]


def grading_deviation(grading: Grading, diameters, n: int = 200) -> float:
    """Largest ``|F_packed - F_requested|`` over sizes from the grading's smallest to its largest stone."""
    sizes = np.exp(np.linspace(math.log(grading.d_min), math.log(grading.d_max), n))
    return float(np.max(np.abs(mass_passing(diameters, sizes) - grading.passing_at(sizes))))


def packed_d(diameters, p: float) -> float:
    """The size [m] that a mass fraction p of the stones passes (interpolated in ln d between stones)."""
    d = np.sort(np.asarray(diameters, float))
    f = np.cumsum(d ** 3) / np.sum(d ** 3)
    return float(np.exp(np.interp(p, f, np.log(d))))


def grading_of(section, prefix: str) -> Optional[Grading]:
    """The Grading a scene section gives (points or d15/d50/d85), None if it gives none; ValueError
    naming the key."""
    pts = bool(section.grading_diameters) or bool(section.grading_passing)
    ds = [section.d15, section.d50, section.d85]
    given = [v is not None for v in ds]
    if pts and any(given):
        raise ValueError(f"{prefix}.d50: give the grading either as points ({prefix}.grading_diameters and "
                         f"{prefix}.grading_passing) or as d15 / d50 / d85, not both")
    if pts:
        return Grading.from_points(section.grading_diameters, section.grading_passing, f"{prefix}.grading")
    if any(given):
        if not all(given):
            missing = next(n for n, g in zip(("d15", "d50", "d85"), given) if not g)
            raise ValueError(f"{prefix}.{missing} is required: a grading by sizes needs d15, d50 and d85")
        return Grading.from_d(*ds, name=prefix)
    return None
