"""Polygon stones in the run output: what the run loop reads from the stones, what run.h5 holds for them,
and their outlines for plots and ParaView.

A run of polygon stones (``stones.shape = 'polygon'``) writes, beside the stones' usual datasets
(``/stones/diameter`` is then the nominal diameter, the equal-area disc's):

    /stones/poly_vertex   (m, 2)     [m]     body-frame vertices of every stone (constant), counter-clockwise
    /stones/poly_offset   (n + 1,)           stone i owns poly_vertex[poly_offset[i]:poly_offset[i + 1]]
    /stones/poly_topology (2 n + m,)         XDMF mixed topology: 3 (polygon), vertex count, vertex indices
    /stones/angle         (T, n)     [rad]   orientation (body frame to world, counter-clockwise)
    /stones/poly_world    (T, m, 2)  [m]     world-frame vertices, for ParaView (drawn as polygons)
    /snapshots/<k>/angle, poly_world         snapshot k of the two series (virtual datasets, as io.py's)

The two series are made at full size with the file, like every series of io.py, so a killed run leaves
them readable. run.xmf gets a third temporal collection, ``stone_polygons``: a mixed topology of polygons
on the world vertices, with diameter, fixed, active and angle per stone (ParaView's three XDMF readers
draw it; meshio 5.3 reads no polygons in a mixed topology, so it has no file of its own). The functions
here know nothing of the file's layout beyond these names, so the writer (io.py) calls them at its own
creation, snapshot and read steps.
"""
from __future__ import annotations

from typing import List

import numpy as np

# XDMF's mixed-topology code of a polygon (followed by its vertex count)
XDMF_POLYGON = 3


def world_polygon_vertices(vertex, offset, pos, angle) -> np.ndarray:
    """World-frame vertices (m, 2) [m] of polygon stones: body vertices (m, 2), offsets (n + 1), centres
    (n, 2) [m], angles (n,) [rad] counter-clockwise."""
    vertex = np.asarray(vertex, float).reshape(-1, 2)
    counts = np.diff(np.asarray(offset))
    owner = np.repeat(np.arange(counts.size), counts)
    a = np.asarray(angle, float)[owner]
    c, s = np.cos(a), np.sin(a)
    p = np.asarray(pos, float).reshape(-1, 2)[owner]
    return np.stack([p[:, 0] + c * vertex[:, 0] - s * vertex[:, 1], p[:, 1] + s * vertex[:, 0] + c * vertex[:, 1]],
                    axis=1)


def outlines(vertex, offset, pos, angle) -> List[np.ndarray]:
    """The world outline (v, 2) [m] of every stone."""
    w = world_polygon_vertices(vertex, offset, pos, angle)
    return [w[a:b] for a, b in zip(offset[:-1], offset[1:])]


def topology(offset) -> np.ndarray:
    """XDMF mixed topology of the stones' polygons: per stone 3, its vertex count, its vertex indices."""
    offset = np.asarray(offset, np.int64)
    out = []
    for a, b in zip(offset[:-1], offset[1:]):
        out += [XDMF_POLYGON, int(b - a)] + list(range(int(a), int(b)))
    return np.asarray(out, np.int64)


def check_polygons(vertex, offset, n: int) -> None:
    """ValueError unless the offsets (n + 1) end at the vertex count."""
    if offset.size != n + 1 or offset[-1] != len(vertex):
        raise ValueError(f"polygons: {offset.size} offsets for {n} stones and {len(vertex)} vertices "
                         "(expected n + 1 offsets ending at the vertex count)")


def create_datasets(f, vertex, offset, n: int, series) -> None:
    """The polygon datasets of run.h5 (h5py file f), made with the file: the constant shapes, and the
    series at full size through the writer's `series(f, name, tail, dtype, fill)` (nothing is resized)."""
    check_polygons(vertex, offset, n)
    f["stones/poly_vertex"] = vertex
    f["stones/poly_offset"] = offset
    f["stones/poly_topology"] = topology(offset)
    series(f, "stones/angle", (n,), "f8", np.nan)
    series(f, "stones/poly_world", (len(vertex), 2), "f8", np.nan)


def write_snapshot(f, k: int, vertex, offset, pos, angle) -> None:
    """Writes snapshot k into the series made by create_datasets: the stones' angles and world vertices."""
    n = np.asarray(offset).size - 1
    angle = np.asarray(angle, float).reshape(n)
    f["stones/angle"][k] = angle
    f["stones/poly_world"][k] = world_polygon_vertices(vertex, offset, pos, angle)


def xdmf_grid(h5name: str, k: int, t: float, n: int, m: int, item, attribute) -> str:
    """XDMF 3 text of snapshot k's polygons: n stones of m vertices in all, a mixed topology of polygons
    on the world vertices, with the stones' constant and per-snapshot values as cell data. `item` and
    `attribute` are the writer's DataItem and Attribute makers."""
    snap = f"/snapshots/{k:06d}"
    parts = [f'<Grid Name="stone_polygons_{k}" GridType="Uniform">', f'<Time Value="{float(t)!r}"/>',
             f'<Topology TopologyType="Mixed" NumberOfElements="{n}">'
             + item([2 * n + m], "/stones/poly_topology", h5name, "Int", "8") + "</Topology>",
             '<Geometry GeometryType="XY">' + item([m, 2], f"{snap}/poly_world", h5name) + "</Geometry>",
             attribute("diameter", "Scalar", "Cell", item([n], "/stones/diameter", h5name)),
             attribute("fixed", "Scalar", "Cell", item([n], "/stones/fixed", h5name, "UChar", "1")),
             attribute("active", "Scalar", "Cell", item([n], f"{snap}/active", h5name, "UChar", "1")),
             attribute("angle", "Scalar", "Cell", item([n], f"{snap}/angle", h5name))]
    return "".join(parts) + "</Grid>"


def reopen(f):
    """(vertex, offset) of an existing run file's polygon stones, or None for discs."""
    if "stones/poly_vertex" not in f:
        return None
    return f["stones/poly_vertex"][()], f["stones/poly_offset"][()].astype(np.int64)


def read(f, count: int):
    """(vertex, offset, angle (count, n)) of a run's polygon stones, or (None, None, None) for discs."""
    if "stones/poly_vertex" not in f:
        return None, None, None
    return f["stones/poly_vertex"][()], f["stones/poly_offset"][()], f["stones/angle"][:count]
