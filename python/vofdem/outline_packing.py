"""Packing generator of a weir given by an outline (outline.py), with zones of their own grading: the
stones are placed geometrically and settled under gravity by the DEM (dem_system.h), as the paper's
"free packing method due to gravity" and as `pack_weir` (weir_packing.h) does for the trapezoid.

Steps:

1. the bottom row: touching stones on the bed from toe to toe (fixed to the bed);
2. a mould: small fixed discs ("ghosts", a quarter of the smallest stone's diameter, overlapping, so
   nothing passes between them) along the upper boundary, half a local d50 outside it, so that the
   centres of the boundary stones end near the boundary (as pack_weir's temporary slope walls);
3. rounds of filling: stones are drawn zone by zone in turn, and each is laid at the lowest site of a
   fine triangular lattice (pitch a quarter of the smallest stone; sites in the body or up to half a
   local d50 outside it, under the mould) of its zone where it touches no other stone; a zone whose
   next stone finds no site stops, and that stone waits for the next round (no size is rejected);
   the stones settle; the gaps the compaction leaves are filled in the next round (up to six);
4. the mould removed (and stones whose centre lies more than a quarter of a local d50 outside the
   outline with it), the body settles on its own; hollows left at its surface are topped up (up to
   three rounds), then stones are laid by hand into the largest remaining gaps along the boundary;
   stones that rolled off the body (centre more than a local d50 outside it) are taken away;
5. the report: stones, porosity of the body (sampled every 2 mm), how far stones reach outside the
   outline and the largest gap along it, the zone of each stone (as placed).

Each stone's zone is that of the lattice site it was placed at (outline.zone_index); its diameter
comes from that zone's grading.Sampler (drawn by mass), or for a core without a grading from
d (1 + spread (2u - 1)) as pack_weir draws them. Random numbers: numpy's default generator seeded
with the scene's seed, so a seed gives the same weir.
"""
from __future__ import annotations

import math
import time as _time
from dataclasses import dataclass, field
from typing import Callable, List, Sequence

import numpy as np

from . import _core
from .outline import Outline, zone_index

REST_SPEED = 1e-3  # [m/s] the packing is at rest when every stone is slower
SETTLE_TIME_MAX = 6.0  # [s] simulated time allowed for each settling phase


@dataclass
class Source:
    """Where a zone's (or the core's) diameters come from: draw() -> d [m], and its typical sizes."""

    draw: Callable[[], float]
    d50: float
    d_min: float
    d_max: float


@dataclass
class OutlinePackingReport:
    """How a weir of an outline was packed: stone counts, its 2D porosity [-], the largest speed at the end
    [m/s], the settling time [s], the outline error [m], the wall time [s] and the zone of each stone."""

    n_stones: int = 0  # stones of the weir (fixed included; no ghosts)
    n_fixed: int = 0  # fixed bottom stones
    porosity: float = 0.0  # 2D porosity of the body: 1 - area covered by the stones / area [-]
    max_speed: float = 0.0  # largest stone speed at the end [m/s]
    settle_time: float = 0.0  # simulated time of the settling phases [s]
    outline_error: float = 0.0  # larger of how far a stone reaches outside and the largest gap [m]
    wall_seconds: float = 0.0
    left_over: int = 0  # drawn stones that found no place in the end (not in the weir)
    rolled_off: int = 0  # stones that rolled off the body while settling, taken away
    zone: np.ndarray = field(default_factory=lambda: np.zeros(0, int))  # zone of each stone, -1 the core


class _Pile:
    """Stones being packed: centres, radii, fixed flags, zones; ghosts are fixed stones of zone -2."""

    def __init__(self):
        self.pos = np.zeros((0, 2))
        self.r = np.zeros(0)
        self.fixed = np.zeros(0, bool)
        self.zone = np.zeros(0, int)

    def add(self, x: float, z: float, r: float, fixed: bool, zone: int) -> None:
        self.pos = np.vstack([self.pos, [[x, z]]])
        self.r = np.append(self.r, r)
        self.fixed = np.append(self.fixed, fixed)
        self.zone = np.append(self.zone, zone)

    def keep(self, mask) -> None:
        self.pos, self.r, self.fixed, self.zone = self.pos[mask], self.r[mask], self.fixed[mask], self.zone[mask]

    def fits(self, x: float, z: float, r: float, margin: float) -> bool:
        if z - r < margin:
            return False
        d = np.hypot(self.pos[:, 0] - x, self.pos[:, 1] - z) - self.r - r
        return bool(d.size == 0 or d.min() > margin)

    def system(self, params, density: float):
        return _core.DEMSystem(params, self.pos, self.r, np.full(self.r.size, density),
                               [int(f) for f in self.fixed])

    def take(self, sys_) -> None:
        """Positions of the settled system; stones that left the domain are dropped."""
        self.pos = np.asarray(sys_.stone_pos, float).reshape(-1, 2).copy()
        self.keep(np.asarray(sys_.stone_active, bool))


def max_speed(sys_) -> float:
    """The largest speed [m/s] of the moving stones of a DEMSystem, translation or rim speed of rotation."""
    moving = np.asarray(sys_.stone_active, bool) & ~np.asarray(sys_.stone_fixed, bool)
    if not moving.any():
        return 0.0
    v = np.asarray(sys_.stone_vel).reshape(-1, 2)[moving]
    w = np.abs(np.asarray(sys_.stone_omega)[moving] * np.asarray(sys_.stone_radius)[moving])
    return float(max(np.hypot(v[:, 0], v[:, 1]).max(), w.max()))


def settle(sys_, hold: float) -> float:
    """Runs until every stone has been slower than REST_SPEED for `hold` seconds (or SETTLE_TIME_MAX);
    returns the simulated time used [s]."""
    chunk, t, quiet = 0.01, 0.0, 0.0
    while t < SETTLE_TIME_MAX:
        sys_.advance(chunk)
        t += chunk
        quiet = quiet + chunk if max_speed(sys_) < REST_SPEED else 0.0
        if quiet >= hold - 1e-12:
            break
    return t


def _bottom_row(body: Outline, zones, sources: Sequence[Source], pile: _Pile) -> None:
    """Touching stones on the bed from toe to toe, each of the zone at its place."""
    x, x_end = body.x_toe_up, body.x_toe_down
    probe = 0.25 * sources[-1].d50
    while True:
        j = int(zone_index(x + probe, probe, body, zones))
        d = sources[j].draw()
        if x + d > x_end + 1e-12:
            return
        pile.add(x + 0.5 * d, 0.5 * d, 0.5 * d, True, j)
        x += d


def _ghosts(body: Outline, zones, sources: Sequence[Source], d_min: float):
    """Centres and radius of the mould's fixed discs along the upper boundary (module docstring)."""
    rg = 0.25 * d_min
    step = rg
    pts, normals = body.points, body.outward_normals()
    out = []

    def offset_at(p, n):
        j = int(zone_index(p[0] - 1e-3 * n[0], p[1] - 1e-3 * n[1], body, zones))
        return 0.5 * sources[j].d50 + rg

    nseg = len(pts) - 1
    for k in range(nseg):
        a, b, n = pts[k], pts[k + 1], normals[k]
        L = float(np.hypot(*(b - a)))
        lo, hi = (-3.0 * sources[-1].d_max / L if k == 0 else 0.0), (
            1.0 + 3.0 * sources[-1].d_max / L if k == nseg - 1 else 1.0)
        for t in np.arange(lo, hi + 1e-12, step / L):
            p = a + t * (b - a)
            out.append(p + offset_at(a + min(max(t, 0.0), 1.0) * (b - a), n) * n)
        if k + 1 < nseg:  # a convex corner: an arc of ghosts around it
            n2 = normals[k + 1]
            a1, a2 = math.atan2(n[1], n[0]), math.atan2(n2[1], n2[0])
            if a2 < a1:
                off = offset_at(b, n)
                m = max(2, int(math.ceil((a1 - a2) * off / step)))
                for ang in np.linspace(a1, a2, m + 1):
                    out.append(b + off * np.array([math.cos(ang), math.sin(ang)]))
    c = np.array(out)
    keep = (c[:, 1] >= rg) & ~body.inside(c[:, 0], c[:, 1]) & (body.depth(c[:, 0], c[:, 1]) > rg + 0.25 * d_min)
    return c[keep], rg


def _lattice(body: Outline, pitch: float, beyond) -> np.ndarray:
    """Sites of a triangular lattice of `pitch` [m] in the body or up to beyond(x, z) [m] outside its upper
    boundary (the mould lies there), row by row from the bed up."""
    rows = []
    dz = pitch * math.sqrt(3.0) / 2.0
    for k, z in enumerate(np.arange(0.5 * pitch, body.height + 0.1, dz)):
        xs = np.arange(body.x_toe_up - 0.1 + (0.5 * pitch if k % 2 else 0.0), body.x_toe_down + 0.1, pitch)
        zs = np.full(xs.size, z)
        ok = body.inside(xs, zs) | ((xs > body.x_toe_up) & (xs < body.x_toe_down) & (body.depth(xs, zs) < beyond(xs, zs)))
        rows.append(np.column_stack([xs[ok], zs[ok]]))
    return np.vstack(rows) if rows else np.zeros((0, 2))


class _Sites:
    """The lattice sites with the largest stone radius each can take (its clearance to the bed and every
    stone), kept up to date as stones are placed; a stone goes to the lowest site of its zone that
    takes it."""

    def __init__(self, sites: np.ndarray, zone: np.ndarray, pile: _Pile, margin: float):
        self.xy, self.zone, self.margin = sites, zone, margin
        self.clear = sites[:, 1].copy()  # the bed
        for k in range(0, pile.r.size, 256):
            p, r = pile.pos[k:k + 256], pile.r[k:k + 256]
            d = np.hypot(sites[:, 0:1] - p[None, :, 0], sites[:, 1:2] - p[None, :, 1]) - r[None, :]
            self.clear = np.minimum(self.clear, d.min(axis=1))

    def place(self, zone: int, r: float):
        """(x, z) of the lowest site of `zone` that takes a stone of radius r [m], or None."""
        ok = np.flatnonzero((self.zone == zone) & (self.clear > r + self.margin))
        if ok.size == 0:
            return None
        k = ok[np.lexsort((self.xy[ok, 0], self.xy[ok, 1]))[0]]
        return float(self.xy[k, 0]), float(self.xy[k, 1])

    def occupy(self, x: float, z: float, r: float) -> None:
        self.clear = np.minimum(self.clear, np.hypot(self.xy[:, 0] - x, self.xy[:, 1] - z) - r)


MISSES = 8  # a zone stops filling while this many of its drawn stones wait for a site


def _fill(body: Outline, zones, sources: Sequence[Source], pile: _Pile, sites: np.ndarray, szone: np.ndarray,
          margin: float, waiting: dict) -> int:
    """Stones laid zone by zone in turn at the lowest site of their zone that takes them: first the stones
    waiting from before (largest first), else a new draw; a drawn stone that finds no site waits
    (`waiting`: zone -> diameters), and a zone stops when MISSES of them wait (so in the end a few per
    zone are left over, not a tail of the largest sizes). Returns how many."""
    free = _Sites(sites, szone, pile, margin)
    open_zones = sorted(set(int(j) for j in szone))
    added = 0
    while open_zones:
        for j in list(open_zones):
            queue = waiting.setdefault(j, [])
            spot = next(((d, at) for d in sorted(queue, reverse=True) if (at := free.place(j, 0.5 * d))), None)
            if spot is not None:
                queue.remove(spot[0])
            else:
                d = sources[j].draw()
                at = free.place(j, 0.5 * d)
                if at is None:
                    queue.append(d)
                    if len(queue) >= MISSES:
                        open_zones.remove(j)
                    continue
                spot = (d, at)
            d, (x, z) = spot
            pile.add(x, z, 0.5 * d, False, j)
            free.occupy(x, z, 0.5 * d)
            added += 1
    return added


def _boundary_gap(body: Outline, pile: _Pile, h: float = 0.002):
    """(largest gap [m] between the upper boundary and the stones, its point)."""
    pts = body.points
    worst, where = 0.0, (float(pts[0, 0]), 0.0)
    stones = pile.zone >= -1
    for a, b in zip(pts[:-1], pts[1:]):
        m = max(2, int(np.hypot(*(b - a)) / h))
        for t in np.linspace(0.0, 1.0, m + 1):
            p = a + t * (b - a)
            g = np.hypot(pile.pos[stones, 0] - p[0], pile.pos[stones, 1] - p[1]) - pile.r[stones]
            gap = max(float(g.min()), 0.0) if g.size else math.inf
            if gap > worst:
                worst, where = gap, (float(p[0]), float(p[1]))
    return worst, where


def _lay_by_hand(body, zones, sources, pile: _Pile, params, density: float) -> float:
    """Stones laid into the largest gaps along the boundary (at most 12); returns the settling time."""
    t = 0.0
    for _ in range(12):
        gap, (px, pz) = _boundary_gap(body, pile)
        j = int(zone_index(px, max(pz - 1e-3, 0.0), body, zones))
        if gap < 0.5 * sources[j].d50:
            break
        r = 0.5 * sources[j].draw()
        lift = next((s for s in np.arange(0.0, 2.0 * r + 1e-12, 0.05 * r) if pile.fits(px, pz + s, r, 1e-4)), None)
        if lift is None:
            break
        pile.add(px, pz + lift, r, False, j)
        sys_ = pile.system(params, density)
        t += settle(sys_, 0.3)
        pile.take(sys_)
    return t


def body_porosity(body: Outline, pos, radius, h: float = 0.002) -> float:
    """2D porosity of the body: 1 - the share of points (every h [m]) inside it covered by a stone."""
    xs = np.arange(body.x_toe_up + 0.5 * h, body.x_toe_down, h)
    zs = np.arange(0.5 * h, body.height, h)
    X, Z = np.meshgrid(xs, zs)
    ins = body.inside(X, Z)
    px, pz = X[ins], Z[ins]
    covered = np.zeros(px.size, bool)
    for (x, z), r in zip(pos, radius):
        near = np.abs(px - x) < r
        covered[near] |= (px[near] - x) ** 2 + (pz[near] - z) ** 2 < r * r
    return 1.0 - float(covered.mean()) if px.size else 1.0


def reach_outside(body: Outline, pos, radius) -> np.ndarray:
    """How far each stone reaches outside the body's upper boundary [m] (negative: inside by that much)."""
    pos = np.asarray(pos, float).reshape(-1, 2)
    depth = body.depth(pos[:, 0], pos[:, 1])
    inside = body.inside(pos[:, 0], pos[:, 1]) | (pos[:, 1] <= body.surface(pos[:, 0]))
    return np.where(inside, -depth, depth) + np.asarray(radius, float)


def pack_outline(body: Outline, zones, sources: Sequence[Source], params, density: float):
    """(DEMSystem at rest, OutlinePackingReport) of the body packed with stones of `sources` (one per zone,
    then the core's last); `params` the DEM parameters of the packing (dry, no fluid forces)."""
    wall0 = _time.perf_counter()
    d_min = min(s.d_min for s in sources)
    pile = _Pile()
    _bottom_row(body, zones, sources, pile)
    n_fixed = pile.r.size
    ghosts, rg = _ghosts(body, zones, sources, d_min)
    for c in ghosts:
        pile.add(c[0], c[1], rg, True, -2)
    def beyond(x, z):  # how far outside the boundary a stone's centre may lie: half a local d50
        return np.array([0.5 * sources[j].d50 for j in zone_index(x, z, body, zones)])

    sites = _lattice(body, 0.25 * d_min, beyond)
    szone = zone_index(sites[:, 0], sites[:, 1], body, zones)
    margin = 0.02 * sources[-1].d50
    pending: dict = {}  # zone -> drawn stones still to be laid
    t_total = 0.0
    for _ in range(6):  # (3) rounds of filling inside the mould
        if _fill(body, zones, sources, pile, sites, szone, margin, pending) == 0:
            break
        sys_ = pile.system(params, density)
        t_total += settle(sys_, 0.2)
        pile.take(sys_)
    pile.keep(pile.zone >= -1)  # (4) the mould removed
    out = reach_outside(body, pile.pos, np.zeros(pile.r.size))
    pile.keep(pile.fixed | (out <= 0.25 * np.array([sources[j].d50 for j in pile.zone])))
    sys_ = pile.system(params, density)
    t_total += settle(sys_, 0.5)
    pile.take(sys_)
    for _ in range(3):
        if _fill(body, zones, sources, pile, sites, szone, margin, pending) == 0:
            break
        sys_ = pile.system(params, density)
        t_total += settle(sys_, 0.5)
        pile.take(sys_)
    t_total += _lay_by_hand(body, zones, sources, pile, params, density)
    # stones that rolled off the body (centre more than a local d50 out, e.g. along the bed) are taken away
    d50 = np.array([sources[j].d50 for j in pile.zone])
    off = ~pile.fixed & (reach_outside(body, pile.pos, np.zeros(pile.r.size)) > d50)
    rolled = int(off.sum())
    pile.keep(~off)
    sys_ = pile.system(params, density)
    if rolled:
        t_total += settle(sys_, 0.3)
        pile.take(sys_)
    gap, _ = _boundary_gap(body, pile)
    rep = OutlinePackingReport(
        n_stones=int(pile.r.size), n_fixed=int(np.sum(pile.fixed)) if n_fixed else 0,
        porosity=body_porosity(body, pile.pos, pile.r), max_speed=max_speed(sys_), settle_time=t_total,
        outline_error=max(float(reach_outside(body, pile.pos, pile.r).max()), gap),
        wall_seconds=_time.perf_counter() - wall0, zone=pile.zone.copy(),
        left_over=sum(len(v) for v in pending.values()), rolled_off=rolled)
    return sys_, rep


def uniform_source(d_mean: float, spread: float, rng: np.random.Generator) -> Source:
    """Diameters uniform in d_mean (1 +- spread), as pack_weir draws them."""
    return Source(lambda: float(d_mean * (1.0 + spread * (2.0 * rng.random() - 1.0))), d_mean,
                  d_mean * (1.0 - spread), d_mean * (1.0 + spread))


def grading_source(grading, rng: np.random.Generator) -> Source:
    """A Source of stone diameters [m] drawn by mass from a Grading, with its d50 and its smallest and largest
    diameters [m]."""
    from .grading import Sampler

    s = Sampler(grading, rng)
    return Source(s.draw, grading.d(0.5), grading.d_min, grading.d_max)


def zone_stats(body: Outline, zones, pos, zone) -> List[dict]:
    """Per zone (and the core, -1): stones, and the share whose final centre lies in their zone."""
    pos = np.asarray(pos, float).reshape(-1, 2)
    now = zone_index(pos[:, 0], pos[:, 1], body, zones)
    out = []
    for j in list(range(len(zones))) + [-1]:
        sel = np.asarray(zone) == j
        out.append(dict(zone=j, stones=int(sel.sum()), inside=float(np.mean(now[sel] == j)) if sel.any() else 1.0))
    return out


