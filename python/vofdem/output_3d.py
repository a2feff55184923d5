"""3D stones in the run output: what run.h5 holds of stones that move across the flume (the sphere model,
``stones.shape = 'sphere'``), and the points ParaView draws them at.

A run of 3D stones writes, beside the stones' usual datasets (``/stones/pos`` keeps x and z, the plane
of the width-averaged flow; ``/stones/diameter`` the stones' diameters):

    /stones/y        (T, n)     [m]  centre across the flume, 0 (side wall y = 0) .. B (the other wall)
    /stones/quat     (T, n, 4)       orientation, the unit quaternion (w, x, y, z) from body to world
    /stones/point3   (T, n, 3)  [m]  ParaView's points of the stones: (x, z, B / 2 - y)
    /stones          attrs: width  B [m], the flume's width
    /snapshots/<k>/y, quat, point3   snapshot k of the three series (virtual datasets, as io.py's)

ParaView's frame (X, Y, Z) = (x, z, B / 2 - y) is the flume turned a quarter about its axis (a proper
rotation, not a mirror): X along the flume, Y up, and the fields' x-z mesh (io.py, at Z = 0) cuts the
stones at mid-width, so the default 2D view of ParaView is the side view seen from the wall y = 0.
Draw the stones with a Glyph filter (sphere, scale array ``diameter``, scale factor 1). The stones'
collection of run.xmf and stones.xmf then has XYZ points and the point data ``y``; the orientation is
kept in run.h5 only (XDMF has no attribute of four components). The series are made at full size with
the file, like every series of io.py, so a killed run leaves them readable. The functions here know
nothing of the file's layout beyond these names; the writer (io.py) calls them at its own creation,
snapshot and read steps.
"""
from __future__ import annotations

from typing import Optional

import numpy as np


def check_width(width: float) -> float:
    """The flume's width [m] of 3D stones; ValueError unless finite and > 0."""
    width = float(width)
    if not (np.isfinite(width) and width > 0.0):
        raise ValueError(f"width = {width} m is out of range for 3D stones (allowed: finite, > 0 m)")
    return width


def paraview_points(pos, y, width: float) -> np.ndarray:
    """ParaView's points (n, 3) [m] of stones at (x, z) = pos (n, 2) and y (n,) in a flume of the width."""
    pos = np.asarray(pos, float).reshape(-1, 2)
    return np.column_stack([pos[:, 0], pos[:, 1], 0.5 * width - np.asarray(y, float).reshape(-1)])


def create_datasets(f, n: int, width: float, series) -> None:
    """The 3D datasets of run.h5 (h5py file f), made with the file, at full size through the writer's
    `series(f, name, tail, dtype, fill)` (nothing is resized later)."""
    f["stones"].attrs["width"] = check_width(width)
    series(f, "stones/y", (n,), "f8", np.nan)
    series(f, "stones/quat", (n, 4), "f8", np.nan)
    series(f, "stones/point3", (n, 3), "f8", np.nan)


def write_snapshot(put, k: int, width: float, pos, y, quat) -> None:
    """Writes snapshot k of the 3D series through the writer's `put(name, k, values)`."""
    n = np.asarray(pos).reshape(-1, 2).shape[0]
    y = np.asarray(y, float)
    quat = np.asarray(quat, float)
    if y.size != n or quat.size != 4 * n:
        raise ValueError(f"3D stones: {y.size} values of y and {quat.size} of quat for {n} stones "
                         "(expected n and 4 n)")
    put("stones/y", k, y)
    put("stones/quat", k, quat.reshape(n, 4))
    put("stones/point3", k, paraview_points(pos, y, width))


def xdmf_geometry(h5name: str, k: int, n: int, item) -> str:
    """The stones' XYZ geometry of snapshot k (`item`: the writer's DataItem maker)."""
    return '<Geometry GeometryType="XYZ">' + item([n, 3], f"/snapshots/{k:06d}/point3", h5name) + "</Geometry>"


def xdmf_attributes(h5name: str, k: int, n: int, item, attribute) -> str:
    """The stones' point data of snapshot k that only 3D stones have: y [m]."""
    return attribute("y", "Scalar", "Node", item([n], f"/snapshots/{k:06d}/y", h5name))


def width_of(f) -> Optional[float]:
    """The flume's width [m] of an existing run file's 3D stones, or None for stones in the plane."""
    if "stones/y" not in f:
        return None
    return float(f["stones"].attrs["width"])


def read(f, count: int):
    """(width, y (count, n), quat (count, n, 4)) of a run's 3D stones, or (None, None, None) in the plane."""
    width = width_of(f)
    if width is None:
        return None, None, None
    return width, f["stones/y"][:count], f["stones/quat"][:count]
