"""Run output: one HDF5 file written snapshot by snapshot, and XDMF 3 files beside it for ParaView and meshio.

Layout of ``run.h5`` (SI units; a capacity of T snapshots, a grid of nx x nz cells, n stones)::

    /                   attrs: scene_toml, vofdem_version, seed, created (UTC ISO date), status, capacity
    /grid/x_faces       (nx+1,)   [m]     cell edges along the flume
    /grid/z_faces       (nz+1,)   [m]     cell edges upwards (non-uniform)
    /grid/nodes         ((nz+1)(nx+1), 2) [m]  mesh nodes (x, z), node i + (nx+1) k
    /grid/cells         (nz nx, 4) int32   quadrilaterals, counter-clockwise; cell i + nx k
    /time               (T,)      [s]     simulation time of each snapshot; NaN after the last completed one
    /discharge          (T,)      [m3/s]  inflow discharge
    /upstream_level     (T,)      [m]     water level at the upstream gauge
    /fields/F           (T,nz,nx)         water fraction
    /fields/p           (T,nz,nx) [Pa]    pressure
    /fields/porosity    (T,nz,nx)         porosity n
    /fields/u, /fields/w (T,nz,nx) [m/s]  superficial velocity at cell centres (mean of the two faces)
    /stones/diameter    (n,)      [m]
    /stones/fixed       (n,)      uint8
    /stones/index       (n, 1)    int32   0 .. n-1: the point cloud's vertices (XDMF Polyvertex)
    /stones/pos, vel    (T,n,2)   [m], [m/s]
    /stones/active      (T,n)     uint8   0 once a stone has left the domain
    /stones/force_drag, force_pressure (T,n,2) [N]   fluid forces on each stone
    /stones/poly_*, /stones/angle        polygon stones only: see polygon_output.py
    /stones/y, quat, point3              3D stones only (across the flume): see output_3d.py
    /snapshots/000042/<name>      snapshot 42 of each series above as a dataset of its own (an HDF5
                                  virtual dataset, no copy): for readers that take whole datasets only
    /profile/names, seconds, calls        the solver's per-stage cost (written at the end)

Readers: the file is written in the format ``HDF5_LIBVER``, which HDF5 1.10 and later read (ParaView 5.11
links HDF5 1.10.8). Every dataset is created at its full size when the file is made (contiguous, the
space allocated and filled with NaN at once); a snapshot then only writes raw values into space that
exists, and no HDF5 metadata changes until the end of the run. So a writer killed at any moment (even
SIGKILL) leaves a file that plain readers open (``h5py.File(p, "r")``, ParaView), with every completed
snapshot intact: the superblock of this format has no open-for-write flag, and its metadata on disk is
the one flushed when the file was made. A snapshot is complete when its time is written; the time is
written last, after the other values were flushed. The file is reopened once made, so that HDF5's
metadata cache holds only the series written and a flush walks those alone. The end of a run (status,
profile) is written into a copy that replaces the file atomically. The XDMF files (write, then rename)
list the completed snapshots: ``run.xmf`` (the fields on the quadrilateral mesh, cell-centred, the
stones as a point cloud and, for polygon stones, their outlines as polygons; open it in ParaView) and
``stones.xmf`` (the stones alone, for meshio, whose time-series reader takes one collection per file:
the last one, so the fields come last in ``run.xmf``). They are rewritten at the first snapshot, at the
first one ``XDMF_SECONDS`` of wall time after the last rewrite and at the end: a rewrite's cost grows
with the snapshots listed (a replacing rename writes the new file back at once), so rewriting after
every snapshot would cost a long run time quadratic in its snapshots. After a kill they may lack the
snapshots of the last ``XDMF_SECONDS``; ``RunWriter.reopen`` (a resumed run) lists every completed one
again.
"""
from __future__ import annotations

import datetime as _dt
import errno
import os
import re
import shutil
import time as _time
import xml.etree.ElementTree as ET
from pathlib import Path
from typing import Dict, List, Optional, Sequence

import h5py
import numpy as np

from . import output_3d, polygon_output

# the HDF5 format written: the oldest object versions ('earliest': superblock 0, which has no
# open-for-write flag), and nothing newer than HDF5 1.10 reads (virtual datasets need 1.10)
HDF5_LIBVER = ("earliest", "v110")
# wall time [s] between rewrites of the XDMF files during a run
XDMF_SECONDS = 2.0

FIELD_NAMES = ("F", "p", "porosity", "u", "w")
STONE_VECTORS = ("pos", "vel", "force_drag", "force_pressure")
# XDMF names of the stones' point data (the datasets' names are kept in run.h5)
STONE_POINT_DATA = {"vel": "velocity", "force_drag": "force_drag", "force_pressure": "force_pressure",
                    "pos": "position"}


def cell_velocities(face_u: np.ndarray, face_w: np.ndarray, nx: int, nz: int):
    """(u, w) at cell centres (nz, nx) from MAC face arrays (face_u flat (nx+1)*nz, face_w nx*(nz+1))."""
    fu = np.asarray(face_u).reshape(nz, nx + 1)
    fw = np.asarray(face_w).reshape(nz + 1, nx)
    return 0.5 * (fu[:, :-1] + fu[:, 1:]), 0.5 * (fw[:-1, :] + fw[1:, :])


def mesh_of(x_faces: np.ndarray, z_faces: np.ndarray):
    """(nodes ((nz+1)(nx+1), 2) [m], cells (nz nx, 4) int32): the grid as quadrilaterals, cell i + nx k
    with its nodes counter-clockwise in (x, z)."""
    nx, nz = x_faces.size - 1, z_faces.size - 1
    X, Z = np.meshgrid(x_faces, z_faces)
    nodes = np.stack([X.ravel(), Z.ravel()], axis=1)
    i, k = np.meshgrid(np.arange(nx), np.arange(nz))
    n0 = (i + (nx + 1) * k).ravel()
    cells = np.stack([n0, n0 + 1, n0 + nx + 2, n0 + nx + 1], axis=1).astype(np.int32)
    return nodes, cells


def _open(path, mode: str) -> h5py.File:
    """h5py.File in the written format; the writer takes no HDF5 file lock, so that a reader (ParaView,
    h5py) can open the file while a run writes it (HDF5 before 1.12.1 has no switch: it locks)."""
    try:
        return h5py.File(path, mode, libver=HDF5_LIBVER, locking=False)
    except ValueError:
        return h5py.File(path, mode, libver=HDF5_LIBVER)


def open_run(path) -> h5py.File:
    """A run's HDF5 file opened for reading, also while this process writes it (the same file-lock
    setting as the writer's: HDF5 refuses a second open of a file with another one)."""
    return _open(path, "r")


class OutputError(OSError):
    """Writing the run's output failed (disk full, directory not writable); what was written is kept.
    `errno` is the failing call's (errno.ENOSPC for a full disk), the message names the file."""

    def __init__(self, errno_: Optional[int], message: str):
        super().__init__(message)
        self.errno = errno_


def check_writable(directory) -> Path:
    """Creates `directory` if needed and writes and removes a probe file in it; raises OutputError
    naming the directory and the reason if that fails (before a run starts)."""
    d = Path(directory)
    probe = d / ".vofdem_write_probe"
    try:
        d.mkdir(parents=True, exist_ok=True)
        with open(probe, "wb") as fh:
            fh.write(b"0" * 4096)
            fh.flush()
            os.fsync(fh.fileno())
        probe.unlink()
    except OSError as e:
        raise OutputError(e.errno, f"output directory '{d}' is not writable: {e.strerror or e}") from e
    return d


class RunWriter:
    """Writes snapshots of a run into an HDF5 file made at its full size (see the module's doc), and the
    XDMF files beside it. Use as a context manager, or reopen a killed run's file with `reopen`.

    capacity: the number of snapshots the file holds (the run's snapshot times are known in advance);
    a snapshot beyond it raises ValueError. polygons: (body-frame vertices (m, 2) [m], offsets (n + 1))
    of polygon stones (polygon_output.py), None for discs; each snapshot then needs stones["angle"].
    width: the flume's width B [m] of 3D stones (output_3d.py), None for stones in the plane; each
    snapshot then needs stones["y"] (n,) [m] and stones["quat"] (n, 4).
    xdmf_seconds: wall time [s] between rewrites of the XDMF files (>= 0; 0: after every snapshot)."""

    def __init__(self, path, x_faces: Sequence[float], z_faces: Sequence[float], diameters: Sequence[float],
                 fixed: Sequence[bool], capacity: int, scene_toml: str = "", seed: int = 0, version: str = "",
                 write_fields: bool = True, polygons=None, xdmf_seconds: float = XDMF_SECONDS,
                 width: Optional[float] = None):
        if not int(capacity) >= 1:
            raise ValueError(f"capacity = {capacity} snapshots is out of range (allowed: >= 1)")
        if not xdmf_seconds >= 0.0:
            raise ValueError(f"xdmf_seconds = {xdmf_seconds} is out of range (allowed: >= 0 s)")
        self.path = Path(path)
        self.xdmf_seconds = float(xdmf_seconds)
        self._geometry(np.asarray(x_faces, float), np.asarray(z_faces, float), len(diameters), write_fields,
                       int(capacity), polygons, None if width is None else output_3d.check_width(width))
        self.path.parent.mkdir(parents=True, exist_ok=True)
        self.file = None
        try:
            f = self.file = _open(self.path, "w")
            self._make(f, np.asarray(diameters, float), np.asarray(fixed, bool), scene_toml, seed, version)
            f.close()
            self.file = _open(self.path, "r+")
        except (OSError, ValueError, RuntimeError) as e:
            failed = _system_errno(e)
            if failed is None:
                raise
            self._abandon()
            raise OutputError(failed, f"cannot make '{self.path}' ({self.capacity} snapshots): {e}") from e
        self.write_xdmf()

    @classmethod
    def reopen(cls, path, count: int, xdmf_seconds: float = XDMF_SECONDS) -> "RunWriter":
        """The writer of an existing run file, continuing after its first `count` snapshots (a resumed
        run): later snapshots are marked incomplete (time NaN) and will be written again."""
        self = cls.__new__(cls)
        self.path = Path(path)
        self.xdmf_seconds = float(xdmf_seconds)
        f = self.file = _open(self.path, "r+")
        T = int(f.attrs["capacity"])
        if not 0 < count <= T:
            f.close()
            raise ValueError(f"count = {count} snapshots is out of range for {self.path} (allowed: 1 .. {T})")
        self._geometry(f["grid/x_faces"][()], f["grid/z_faces"][()], f["stones/diameter"].shape[0],
                       "fields" in f, T, polygon_output.reopen(f), output_3d.width_of(f))
        f["time"][count:] = np.nan
        f.flush()
        self.count = count
        self._times = [float(t) for t in f["time"][:count]]
        self.write_xdmf()
        return self

    def _abandon(self) -> None:
        """Drops the file after a failed system call (its close may fail too: the disk is full)."""
        f, self.file = self.file, None
        try:
            if f is not None:
                f.close()
        except (OSError, ValueError, RuntimeError):
            pass

    def _geometry(self, x_faces, z_faces, n, write_fields, capacity, polygons=None, width=None):
        self.xmf_path = self.path.with_suffix(".xmf")
        self.stones_xmf_path = self.path.with_name("stones.xmf")
        # polygon stones: (body-frame vertices (m, 2), offsets (n + 1)); None for discs
        self.polygons = None if polygons is None or not n else (np.asarray(polygons[0], float).reshape(-1, 2),
                                                                 np.asarray(polygons[1], np.int64))
        self.width = width if n else None  # 3D stones: the flume's width [m]
        self.x_faces, self.z_faces = x_faces, z_faces
        self.nx, self.nz = x_faces.size - 1, z_faces.size - 1
        self.n = n
        self.write_fields = write_fields
        self.capacity = capacity
        self.count = 0
        self._xdmf_at = -np.inf  # wall time of the last XDMF rewrite
        self._times: List[float] = []
        self._xdmf_steps: Dict[str, List[str]] = {"fields": [], "stones": [], "stone_polygons": []}
        self._rows: Dict[str, tuple] = {}  # per series: dataset id, type, row shape, memory space
        self._snapshot_groups: list = []  # the ids of /snapshots/<k>, k < capacity (_series)

    def _series(self, f, name, tail, dtype, fill):
        """A time series (capacity, *tail), contiguous, allocated and filled at once, with a virtual
        dataset per snapshot under /snapshots."""
        T = self.capacity
        dcpl = h5py.h5p.create(h5py.h5p.DATASET_CREATE)
        dcpl.set_alloc_time(h5py.h5d.ALLOC_TIME_EARLY)
        f.create_dataset(name, (T,) + tail, dtype=dtype, fillvalue=fill, dcpl=dcpl, track_times=False)
        if not tail:
            return
        # h5py's low-level calls: 2.6x faster than its VirtualLayout (which copies the layout per dataset)
        h5type = h5py.h5t.py_create(np.dtype(dtype))
        src_space, space = h5py.h5s.create_simple((T,) + tail), h5py.h5s.create_simple(tail)
        fill_value = np.array(fill, dtype)
        leaf = name.split("/")[-1].encode()
        if len(self._snapshot_groups) != T:  # each snapshot's group looked up once for every series
            self._snapshot_groups = [f.require_group(f"snapshots/{k:06d}").id for k in range(T)]
        for k, group in enumerate(self._snapshot_groups):
            vcpl = h5py.h5p.create(h5py.h5p.DATASET_CREATE)
            vcpl.set_fill_value(fill_value)
            src_space.select_hyperslab((k,) + (0,) * len(tail), (1,) + tail)
            vcpl.set_virtual(space, b".", name.encode(), src_space)
            h5py.h5d.create(group, leaf, h5type, space, dcpl=vcpl)

    def _make(self, f, diameters, fixed, scene_toml, seed, version):
        f.attrs.update(scene_toml=scene_toml, vofdem_version=version, seed=int(seed), status="running",
                       capacity=self.capacity,
                       created=_dt.datetime.now(_dt.timezone.utc).isoformat(timespec="seconds"))
        f["grid/x_faces"] = self.x_faces
        f["grid/z_faces"] = self.z_faces
        nodes, cells = mesh_of(self.x_faces, self.z_faces)
        f["grid/nodes"] = nodes
        f["grid/cells"] = cells
        f["stones/diameter"] = diameters
        f["stones/fixed"] = fixed.astype(np.uint8)
        f["stones/index"] = np.arange(self.n, dtype=np.int32).reshape(-1, 1)
        for name in ("time", "discharge", "upstream_level"):
            self._series(f, name, (), "f8", np.nan)
        if self.write_fields:
            for name in FIELD_NAMES:
                self._series(f, f"fields/{name}", (self.nz, self.nx), "f4", np.nan)
        if self.n:
            for name in STONE_VECTORS:
                self._series(f, f"stones/{name}", (self.n, 2), "f8", np.nan)
            self._series(f, "stones/active", (self.n,), "u1", 0)
        if self.polygons is not None:
            polygon_output.create_datasets(f, *self.polygons, self.n, self._series)
        if self.width is not None:
            output_3d.create_datasets(f, self.n, self.width, self._series)

    def __enter__(self):
        return self

    def __exit__(self, *exc):
        self.close("failed" if exc[0] is not None else None)

    def write_snapshot(self, t: float, discharge: float, upstream_level: float, fields: Optional[Dict] = None,
                       stones: Optional[Dict] = None) -> None:
        """Appends one snapshot: fields {name: (nz, nx)}, stones {pos, vel, force_drag, force_pressure:
        (n, 2), active: (n,)} (and the polygons' angle, the 3D stones' y and quat). The values are
        flushed, then the time (the mark of a completed snapshot), then the XDMF files are rewritten if
        xdmf_seconds have passed since their last rewrite. Raises OutputError if a write fails (earlier
        snapshots kept)."""
        f, k, put = self.file, self.count, self._put
        if k >= self.capacity:
            raise ValueError(f"snapshot {k + 1} is beyond the file's capacity of {self.capacity} snapshots")
        try:
            put("discharge", k, discharge)
            put("upstream_level", k, upstream_level)
            if self.write_fields:
                for name in FIELD_NAMES:
                    put(f"fields/{name}", k, fields[name])
            if self.n:
                for name in STONE_VECTORS:
                    put(f"stones/{name}", k, stones[name])
                put("stones/active", k, stones["active"])
            if self.polygons is not None:
                polygon_output.write_snapshot(f, k, *self.polygons, stones["pos"], stones["angle"])
            if self.width is not None:
                output_3d.write_snapshot(self._put, k, self.width, stones["pos"], stones["y"], stones["quat"])
            f.flush()
            put("time", k, t)
            f.flush()
        except (OSError, ValueError, RuntimeError) as e:
            failed = _system_errno(e)
            if failed is None:
                raise
            raise OutputError(failed, f"writing snapshot {k} (t = {t:.6g} s) to '{self.path}' failed: {e}") from e
        self.count += 1
        self._times.append(float(t))
        if not self._xdmf_steps["fields"] or _time.perf_counter() - self._xdmf_at >= self.xdmf_seconds:
            self.write_xdmf()

    def _put(self, name: str, k: int, values) -> None:
        """Writes `values` as row k of the series `name` (converted to its type; h5py's low-level write,
        the series looked up once: the high-level item assignment took 2.6 times as long)."""
        if name not in self._rows:
            d = self.file[name]
            row = (1,) + d.shape[1:]
            self._rows[name] = (d.id, d.dtype, row, h5py.h5s.create_simple(row))
        dsid, dtype, row, mspace = self._rows[name]
        fspace = dsid.get_space()
        fspace.select_hyperslab((k,) + (0,) * (len(row) - 1), row)
        dsid.write(mspace, fspace, np.ascontiguousarray(values, dtype).reshape(row))

    def write_xdmf(self) -> None:
        """Rewrites the XDMF files for the snapshots written so far (write, then rename: atomic)."""
        steps = self._xdmf_steps
        for k in range(len(steps["fields"]), self.count):
            fields, stones = xdmf_step(self.path.name, k, self._times[k], self.nx, self.nz, self.n,
                                       self.write_fields, self.width is not None)
            steps["fields"].append(fields)
            steps["stones"].append(stones)
            if self.polygons is not None:
                steps["stone_polygons"].append(polygon_output.xdmf_grid(
                    self.path.name, k, self._times[k], self.n, len(self.polygons[0]), _item, _attribute))
        # meshio reads the last collection of a file: the fields
        polygons = [("stone_polygons", steps["stone_polygons"])] if self.polygons is not None else []
        both = ([("stones", steps["stones"])] if self.n else []) + polygons + (
            [("fields", steps["fields"])] if self.write_fields else [])
        _replace_text(self.xmf_path, xdmf_document(both))
        if self.n:
            _replace_text(self.stones_xmf_path, xdmf_document([("stones", steps["stones"])]))
        self._xdmf_at = _time.perf_counter()

    def close(self, status: Optional[str] = None, profile=None, extra_attrs: Optional[Dict] = None) -> None:
        """Closes the file; then records status ('completed', 'failed: ...'), the profile and extras in a
        copy of it that replaces it (so that a kill meanwhile leaves the file as it was), and lists every
        snapshot in the XDMF files. Raises OutputError if that fails (disk full): the file is then kept
        as it was, status 'running' (or, if only the XDMF files failed, with its status)."""
        if self.file is None:
            return
        self.file.close()
        self.file = None
        tmp = self.path.with_name(self.path.name + ".tmp")
        try:
            shutil.copyfile(self.path, tmp)
            with _open(tmp, "r+") as f:
                f.attrs["status"] = status or "completed"
                if profile is not None:
                    if "profile" in f:  # a resumed run's file, closed once before (interrupted)
                        del f["profile"]
                    names, seconds, calls = profile
                    f["profile/names"] = np.array([str(s) for s in names], dtype=h5py.string_dtype())
                    f["profile/seconds"] = np.asarray(seconds, float)
                    f["profile/calls"] = np.asarray(calls, np.int64)
                for key, v in (extra_attrs or {}).items():
                    f.attrs[key] = v
            os.replace(tmp, self.path)
        except OSError as e:
            tmp.unlink(missing_ok=True)
            raise OutputError(e.errno, f"closing '{self.path}' failed (its snapshots are kept): {e}") from e
        self.write_xdmf()


def _system_errno(e: BaseException) -> Optional[int]:
    """The errno of a failed system call behind an exception (h5py reports HDF5's as ValueError or
    RuntimeError with 'errno = N' in the message); None for other errors (a wrong argument)."""
    if isinstance(e, OSError) and e.errno is not None:
        return e.errno
    m = re.search(r"errno = (\d+)", str(e))
    return int(m.group(1)) if m else (errno.EIO if isinstance(e, OSError) else None)


def _replace_text(path: Path, text: str) -> None:
    tmp = path.with_name(path.name + ".tmp")
    try:
        tmp.write_text(text, encoding="utf-8")
        os.replace(tmp, path)
    except OSError as e:
        tmp.unlink(missing_ok=True)
        raise OutputError(e.errno, f"writing '{path}' failed: {e}") from e


def _item(dims, path, h5name, ntype="Float", prec="8") -> str:
    return (f'<DataItem Dimensions="{" ".join(map(str, dims))}" NumberType="{ntype}" Precision="{prec}" '
            f'Format="HDF">{h5name}:{path}</DataItem>')


def _attribute(name, kind, center, item) -> str:
    return f'<Attribute Name="{name}" AttributeType="{kind}" Center="{center}">{item}</Attribute>'


def xdmf_step(h5name: str, k: int, t: float, nx: int, nz: int, n: int, fields: bool = True, three_d: bool = False):
    """(fields grid, stones grid): the XDMF 3 text of snapshot k at time t [s]. Each attribute is a
    whole dataset (/snapshots/<k>/...), which every reader takes (meshio reads no hyperslabs). three_d:
    the stones at their 3D points (output_3d.py) instead of (x, z)."""
    snap = f"/snapshots/{k:06d}"
    time = f'<Time Value="{float(t)!r}"/>'
    fgrid = ""
    if fields:
        nc, nn = nx * nz, (nx + 1) * (nz + 1)
        parts = [f'<Grid Name="fields_{k}" GridType="Uniform">', time,
                 f'<Topology TopologyType="Quadrilateral" NumberOfElements="{nc}">'
                 + _item([nc, 4], "/grid/cells", h5name, "Int", "4") + "</Topology>",
                 '<Geometry GeometryType="XY">' + _item([nn, 2], "/grid/nodes", h5name) + "</Geometry>"]
        for name in FIELD_NAMES:
            parts.append(_attribute(name, "Scalar", "Cell", _item([nz, nx], f"{snap}/{name}", h5name, prec="4")))
        fgrid = "".join(parts) + "</Grid>"
    sgrid = ""
    if n:
        parts = [f'<Grid Name="stones_{k}" GridType="Uniform">', time,
                 f'<Topology TopologyType="Polyvertex" NumberOfElements="{n}" NodesPerElement="1">'
                 + _item([n, 1], "/stones/index", h5name, "Int", "4") + "</Topology>",
                 output_3d.xdmf_geometry(h5name, k, n, _item) if three_d else
                 '<Geometry GeometryType="XY">' + _item([n, 2], f"{snap}/pos", h5name) + "</Geometry>",
                 _attribute("diameter", "Scalar", "Node", _item([n], "/stones/diameter", h5name)),
                 _attribute("fixed", "Scalar", "Node", _item([n], "/stones/fixed", h5name, "UChar", "1")),
                 _attribute("active", "Scalar", "Node", _item([n], f"{snap}/active", h5name, "UChar", "1"))]
        for name in ("vel", "force_drag", "force_pressure", "pos"):
            parts.append(_attribute(STONE_POINT_DATA[name], "Vector", "Node", _item([n, 2], f"{snap}/{name}", h5name)))
        if three_d:
            parts.append(output_3d.xdmf_attributes(h5name, k, n, _item, _attribute))
        sgrid = "".join(parts) + "</Grid>"
    return fgrid, sgrid


def xdmf_document(collections) -> str:
    """An XDMF 3 document of temporal collections [(name, [grid text per snapshot])]."""
    body = "".join(f'<Grid Name="{name}" GridType="Collection" CollectionType="Temporal">\n' + "\n".join(steps)
                   + "\n</Grid>\n" for name, steps in collections)
    return f'<?xml version="1.0" ?>\n<Xdmf Version="3.0">\n<Domain>\n{body}</Domain>\n</Xdmf>\n'


class RunData:
    """Read access to a run's HDF5 file (arrays loaded on use; fields one snapshot at a time). Only the
    completed snapshots are read: those with a time (a killed run's file has NaN after them)."""

    def __init__(self, path):
        self.path = Path(path)
        with open_run(self.path) as f:
            self.attrs = dict(f.attrs)
            self.x_faces = f["grid/x_faces"][()]
            self.z_faces = f["grid/z_faces"][()]
            times = f["time"][()]
            T = completed_snapshots(times)
            self.times = times[:T]
            self.discharge = f["discharge"][:T]
            self.upstream_level = f["upstream_level"][:T]
            self.diameter = f["stones/diameter"][()]
            self.fixed = f["stones/fixed"][()].astype(bool)
            n = self.diameter.size
            for name in STONE_VECTORS:
                setattr(self, name, f[f"stones/{name}"][:T] if n else np.zeros((T, 0, 2)))
            self.active = f["stones/active"][:T].astype(bool) if n else np.zeros((T, 0), bool)
            self.poly_vertex, self.poly_offset, self.angle = polygon_output.read(f, T)  # None for discs
            self.width, self.y, self.quat = output_3d.read(f, T)  # None for stones in the plane
            self.has_fields = "fields" in f
            self.profile = None
            if "profile" in f:
                self.profile = ([s.decode() if isinstance(s, bytes) else str(s) for s in f["profile/names"][()]],
                                f["profile/seconds"][()], f["profile/calls"][()])

    @property
    def scene_toml(self) -> str:
        return str(self.attrs.get("scene_toml", ""))

    def scene(self):
        from .scene import Scene

        return Scene.from_toml(self.scene_toml)

    @property
    def x_centers(self):
        return 0.5 * (self.x_faces[1:] + self.x_faces[:-1])

    @property
    def z_centers(self):
        return 0.5 * (self.z_faces[1:] + self.z_faces[:-1])

    def fields(self, k: int) -> Dict[str, np.ndarray]:
        """All fields (nz, nx) of snapshot k (negative k counts from the last completed snapshot)."""
        T = self.times.size
        if not -T <= k < T:
            raise IndexError(f"snapshot {k} is out of range (the run has {T} completed snapshots)")
        with open_run(self.path) as f:
            return {name: f[f"fields/{name}"][k % T].astype(float) for name in FIELD_NAMES}

    def stone_outlines(self, k: int):
        """Polygon stones: the world outline (v, 2) [m] of every stone at snapshot k; None for discs."""
        if self.poly_vertex is None:
            return None
        return polygon_output.outlines(self.poly_vertex, self.poly_offset, self.pos[k], self.angle[k])

    def index_at(self, t: float) -> int:
        """Snapshot nearest to time t [s]."""
        return int(np.argmin(np.abs(self.times - t)))


def completed_snapshots(times: np.ndarray) -> int:
    """The number of completed snapshots: the leading finite entries of /time."""
    bad = ~np.isfinite(np.asarray(times, float))
    return int(np.argmax(bad)) if bad.any() else int(bad.size)


def snapshots_written(path) -> int:
    """The completed snapshots of the run file at `path` (a run.h5); 0 while the file is not made yet or
    cannot be read (a run still creating it). For watching a run, from this process or another."""
    try:
        with open_run(path) as f:
            return completed_snapshots(f["time"][()])
    except (OSError, KeyError):
        return 0


def check_xdmf(xmf_path) -> int:
    """Checks that an XDMF file is well-formed, that every HDF dataset it references exists with the
    declared shape and that each temporal collection lists the completed snapshots' times (a killed
    run's may lack the last one); returns the
    number of references checked, raises ValueError."""
    xmf_path = Path(xmf_path)
    root = ET.parse(xmf_path).getroot()  # raises ParseError if malformed
    checked = 0
    files: Dict[str, h5py.File] = {}
    try:
        for item in root.iter("DataItem"):
            if item.get("Format") != "HDF":
                continue
            fname, dpath = item.text.strip().split(":", 1)
            if fname not in files:
                files[fname] = open_run(xmf_path.parent / fname)
            f = files[fname]
            if dpath not in f:
                raise ValueError(f"{xmf_path.name}: dataset {dpath} missing from {fname}")
            dims = tuple(int(x) for x in item.get("Dimensions").split())
            if f[dpath].shape != dims:
                raise ValueError(f"{xmf_path.name}: {dpath} has shape {f[dpath].shape}, XDMF declares {dims}")
            checked += 1
        for fname, f in files.items():
            times = f["time"][:completed_snapshots(f["time"][()])].tolist()
            for coll in root.iter("Grid"):
                if coll.get("CollectionType") != "Temporal":
                    continue
                listed = [float(g.find("Time").get("Value")) for g in coll.findall("Grid")]
                # a killed run's XDMF may lack its last snapshot (renamed in after the time is written)
                if listed != times[:len(listed)] or len(listed) < len(times) - (f.attrs["status"] == "running"):
                    raise ValueError(f"{xmf_path.name}: collection '{coll.get('Name')}' lists {len(listed)} times, "
                                     f"{fname} has {len(times)} completed snapshots")
    finally:
        for f in files.values():
            f.close()
    return checked
