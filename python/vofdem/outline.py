"""The weir's body as an outline, and zones inside it.

**Outline.** The stone body is the region between the bed z = 0 and an upper boundary z = s(x), a
polyline through points (x_k, z_k) [m] with x strictly increasing, from the upstream toe (z = 0) to the
downstream toe (z = 0): any crest (flat, rounded, sloping), berms, several slopes. The trapezoid of
`scene.Weir` is the four-point case (toe, crest corners, toe). The crest is the part of the polyline at
its largest height (within 1 mm); a pointed top has a crest of zero length.

**Zones.** A zone is a part of the body with its own grading (scene.Zone): either a layer of a given
thickness under the upper boundary (an armour layer: the points of the body nearer than `thickness` to
the upper boundary, measured along the shortest distance), or the inside of a closed polygon. A point
belongs to the first zone of the scene's list that holds it, and to the core ([stones]) otherwise.
"""
from __future__ import annotations

import math
from typing import List, Optional, Sequence

import numpy as np

CREST_TOLERANCE = 1e-3  # [m] points this close to the top height belong to the crest


def check_outline(points, name: str = "weir.outline") -> None:
    """The rules of an outline's points, ValueError naming `name`."""
    if not isinstance(points, (list, tuple)) or len(points) < 3:
        raise ValueError(f"{name} must list three points [x m, z m] at least (toe, top, toe), got {points!r}")
    for j, p in enumerate(points):
        if (not isinstance(p, (list, tuple)) or len(p) != 2 or not all(
                isinstance(v, (int, float)) and not isinstance(v, bool) and math.isfinite(v) for v in p)):
            raise ValueError(f"{name}[{j}] = {p!r} must be a pair [x m, z m] of finite numbers")
    xs, zs = [float(p[0]) for p in points], [float(p[1]) for p in points]
    if any(b <= a for a, b in zip(xs, xs[1:])):
        j = next(k for k in range(1, len(xs)) if xs[k] <= xs[k - 1])
        raise ValueError(f"{name}[{j}] = {list(points[j])}: x must increase strictly from the upstream toe to the "
                         f"downstream toe (the stone body has no overhang)")
    if zs[0] != 0.0 or zs[-1] != 0.0:
        raise ValueError(f"{name}: the first and the last point are the toes, on the bed (z = 0); got z = "
                         f"{zs[0]:g} and {zs[-1]:g}")
    if xs[0] <= 0.0:
        raise ValueError(f"{name}[0] = {list(points[0])}: the upstream toe must lie inside the flume (x > 0)")
    bad = [j for j in range(1, len(zs) - 1) if not zs[j] > 0.0]
    if bad:
        raise ValueError(f"{name}[{bad[0]}] = {list(points[bad[0]])}: the points between the toes must lie "
                         f"above the bed (z > 0)")


def check_polygon(points, name: str) -> None:
    """A closed polygon of three points at least (the last joins the first), finite, with an area."""
    if not isinstance(points, (list, tuple)) or len(points) < 3:
        raise ValueError(f"{name} must list three points [x m, z m] at least, got {points!r}")
    for j, p in enumerate(points):
        if (not isinstance(p, (list, tuple)) or len(p) != 2 or not all(
                isinstance(v, (int, float)) and not isinstance(v, bool) and math.isfinite(v) for v in p)):
            raise ValueError(f"{name}[{j}] = {p!r} must be a pair [x m, z m] of finite numbers")
    if abs(polygon_area(np.asarray(points, float))) < 1e-12:
        raise ValueError(f"{name} encloses no area")


def polygon_area(p: np.ndarray) -> float:
    """Signed area of a closed polygon (n, 2) [m^2] (shoelace)."""
    x, z = p[:, 0], p[:, 1]
    return 0.5 * float(np.sum(x * np.roll(z, -1) - np.roll(x, -1) * z))


def inside_polygon(poly: np.ndarray, x, z) -> np.ndarray:
    """Whether points (x, z) lie inside the closed polygon (n, 2) (even-odd rule), vectorised."""
    x, z = np.asarray(x, float), np.asarray(z, float)
    inside = np.zeros(np.broadcast(x, z).shape, bool)
    px, pz = poly[:, 0], poly[:, 1]
    for k in range(len(poly)):
        x1, z1, x2, z2 = px[k - 1], pz[k - 1], px[k], pz[k]
        cross = (z1 > z) != (z2 > z)
        with np.errstate(divide="ignore", invalid="ignore"):
            xi = x1 + (z - z1) * (x2 - x1) / (z2 - z1)
        inside ^= cross & (x < xi)
    return inside


def segment_distance(x, z, a, b) -> np.ndarray:
    """Distance [m] of points (x, z) to the segment a-b."""
    x, z = np.asarray(x, float), np.asarray(z, float)
    ex, ez = b[0] - a[0], b[1] - a[1]
    L2 = ex * ex + ez * ez
    t = np.clip(((x - a[0]) * ex + (z - a[1]) * ez) / L2, 0.0, 1.0) if L2 > 0 else np.zeros_like(x)
    return np.hypot(x - a[0] - t * ex, z - a[1] - t * ez)


class Outline:
    """The stone body under the polyline `points` (upper boundary) and over the bed z = 0."""

    def __init__(self, points: Sequence[Sequence[float]]):
        self.points = np.asarray(points, float).reshape(-1, 2)

    @property
    def x_toe_up(self) -> float:
        return float(self.points[0, 0])

    @property
    def x_toe_down(self) -> float:
        return float(self.points[-1, 0])

    @property
    def height(self) -> float:
        return float(self.points[:, 1].max())

    def crest(self):
        """(x of its upstream end, x of its downstream end) [m]: where the boundary is at its top height."""
        top = self.points[:, 1] >= self.height - CREST_TOLERANCE
        xs = self.points[top, 0]
        return float(xs.min()), float(xs.max())

    def surface(self, x) -> np.ndarray:
        """Height of the upper boundary above x [m] (0 outside the body)."""
        x = np.asarray(x, float)
        return np.where((x >= self.x_toe_up) & (x <= self.x_toe_down),
                        np.interp(x, self.points[:, 0], self.points[:, 1]), 0.0)

    def inside(self, x, z) -> np.ndarray:
        x, z = np.asarray(x, float), np.asarray(z, float)
        return (x > self.x_toe_up) & (x < self.x_toe_down) & (z >= 0.0) & (z < self.surface(x))

    def depth(self, x, z) -> np.ndarray:
        """Shortest distance [m] of points (x, z) to the upper boundary."""
        p = self.points
        return np.min([segment_distance(x, z, p[k], p[k + 1]) for k in range(len(p) - 1)], axis=0)

    def area(self) -> float:
        x, z = self.points[:, 0], self.points[:, 1]
        return float(np.sum(0.5 * (z[1:] + z[:-1]) * np.diff(x)))

    def polygon(self) -> np.ndarray:
        """The closed outline (the boundary's points; the bed joins the last to the first)."""
        return self.points.copy()

    def outward_normals(self) -> np.ndarray:
        """Unit normals of the boundary's segments pointing out of the body (up and away)."""
        d = np.diff(self.points, axis=0)
        n = np.stack([-d[:, 1], d[:, 0]], axis=1)
        return n / np.linalg.norm(n, axis=1)[:, None]


def zone_index(x, z, outline: Outline, zones) -> np.ndarray:
    """Index of the zone holding each point (the first of `zones` that does), -1 for the core."""
    x, z = np.asarray(x, float), np.asarray(z, float)
    out = np.full(np.broadcast(x, z).shape, -1, int)
    for j in range(len(zones) - 1, -1, -1):  # the first zone listed wins: assign in reverse
        zn = zones[j]
        if zn.outline:
            hit = inside_polygon(np.asarray(zn.outline, float), x, z)
        else:
            hit = outline.depth(x, z) < zn.thickness
        out[hit] = j
    return out


def trapezoid_points(toe_x: float, height: float, crest: float, up_deg: float, down_deg: float) -> List[List[float]]:
    """The outline's points of a trapezoidal weir (the one-line case)."""
    x1 = toe_x + height / math.tan(math.radians(up_deg))
    x2 = x1 + crest
    x3 = x2 + height / math.tan(math.radians(down_deg))
    return [[toe_x, 0.0], [x1, height], [x2, height], [x3, 0.0]]


def as_trapezoid(points) -> Optional[dict]:
    """The trapezoid keys (toe_x, height, crest_length, slopes) when the outline is one (four points: two
    toes on the bed and a flat crest), else None."""
    if len(points) != 4:
        return None
    (x0, z0), (x1, z1), (x2, z2), (x3, z3) = [(float(a), float(b)) for a, b in points]
    if not (z1 == z2 and z1 > 0 and x2 > x1):
        return None
    return dict(toe_x=x0, height=z1, crest_length=x2 - x1,
                upstream_slope_deg=math.degrees(math.atan2(z1, x1 - x0)),
                downstream_slope_deg=math.degrees(math.atan2(z2, x3 - x2)))
