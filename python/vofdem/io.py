"""Run output: one HDF5 file written snapshot by snapshot, and an XDMF file beside it for ParaView.

Layout of ``run.h5`` (SI units; T snapshots, a grid of nx x nz cells, n stones):

    /                   attrs: scene_toml, vofdem_version, seed, created (UTC ISO date), status
    /grid/x_faces       (nx+1,)   [m]     cell edges along the flume
    /grid/z_faces       (nz+1,)   [m]     cell edges upwards (non-uniform)
    /time               (T,)      [s]     simulation time of each snapshot
    /discharge          (T,)      [m3/s]  inflow discharge
    /upstream_level     (T,)      [m]     water level at the upstream gauge
    /fields/F           (T,nz,nx)         water fraction
    /fields/p           (T,nz,nx) [Pa]    pressure
    /fields/porosity    (T,nz,nx)         porosity n
    /fields/u, /fields/w (T,nz,nx) [m/s]  superficial velocity at cell centres (mean of the two faces)
    /stones/diameter    (n,)      [m]
    /stones/fixed       (n,)      uint8
    /stones/pos, vel    (T,n,2)   [m], [m/s]
    /stones/active      (T,n)     uint8   0 once a stone has left the domain
    /stones/force_drag, force_pressure (T,n,2) [N]   fluid forces on each stone
    /stones/poly_*, /stones/angle        polygon stones only: see polygon_output.py
    /profile/names, seconds, calls        the solver's per-stage cost (written at the end)

The file is opened in HDF5's single-writer/multiple-reader mode and flushed after every snapshot, so a
crash (or a reader running alongside) sees every completed snapshot. The XDMF file is rewritten after
each snapshot so that it references exactly the snapshots present.
"""
from __future__ import annotations

import datetime as _dt
import os
import xml.etree.ElementTree as ET
from pathlib import Path
from typing import Dict, Optional, Sequence

import h5py
import numpy as np

from . import polygon_output

FIELD_NAMES = ("F", "p", "porosity", "u", "w")
STONE_VECTORS = ("pos", "vel", "force_drag", "force_pressure")


def cell_velocities(face_u: np.ndarray, face_w: np.ndarray, nx: int, nz: int):
    """(u, w) at cell centres (nz, nx) from MAC face arrays (face_u flat (nx+1)*nz, face_w nx*(nz+1))."""
    fu = np.asarray(face_u).reshape(nz, nx + 1)
    fw = np.asarray(face_w).reshape(nz + 1, nx)
    return 0.5 * (fu[:, :-1] + fu[:, 1:]), 0.5 * (fw[:-1, :] + fw[1:, :])


class RunWriter:
    """Writes snapshots of a run incrementally to HDF5 (+ XDMF). Use as a context manager."""

    def __init__(self, path, x_faces: Sequence[float], z_faces: Sequence[float], diameters: Sequence[float],
                 fixed: Sequence[bool], scene_toml: str = "", seed: int = 0, version: str = "",
                 write_fields: bool = True, polygons=None):
        self.path = Path(path)
        self.xmf_path = self.path.with_suffix(".xmf")
        self.x_faces = np.asarray(x_faces, float)
        self.z_faces = np.asarray(z_faces, float)
        self.nx, self.nz = self.x_faces.size - 1, self.z_faces.size - 1
        self.n = len(diameters)
        self.write_fields = write_fields
        # polygon stones: (body-frame vertices (m, 2), offsets (n + 1)); None for discs
        self.polygons = None if polygons is None else (np.asarray(polygons[0], float).reshape(-1, 2),
                                                        np.asarray(polygons[1], np.int64))
        self.count = 0
        self._times = []
        self.path.parent.mkdir(parents=True, exist_ok=True)
        f = self.file = h5py.File(self.path, "w", libver="latest")
        f.attrs.update(scene_toml=scene_toml, vofdem_version=version, seed=int(seed), status="running",
                       created=_dt.datetime.now(_dt.timezone.utc).isoformat(timespec="seconds"))
        f["grid/x_faces"] = self.x_faces
        f["grid/z_faces"] = self.z_faces
        f["stones/diameter"] = np.asarray(diameters, float)
        f["stones/fixed"] = np.asarray(fixed, bool).astype(np.uint8)
        for name in ("time", "discharge", "upstream_level"):
            f.create_dataset(name, (0,), maxshape=(None,), dtype="f8", chunks=(256,))
        if write_fields:
            for name in FIELD_NAMES:
                f.create_dataset(f"fields/{name}", (0, self.nz, self.nx), maxshape=(None, self.nz, self.nx),
                                 dtype="f4", chunks=(1, self.nz, self.nx), compression="gzip", compression_opts=1)
        nc = max(1, self.n)
        for name in STONE_VECTORS:
            f.create_dataset(f"stones/{name}", (0, self.n, 2), maxshape=(None, self.n, 2), dtype="f8",
                             chunks=(16, nc, 2))
        f.create_dataset("stones/active", (0, self.n), maxshape=(None, self.n), dtype="u1", chunks=(16, nc))
        if self.polygons is not None:
            polygon_output.create_datasets(f, *self.polygons, self.n, nc)
        f.swmr_mode = True
        self.write_xdmf()

    def __enter__(self):
        return self

    def __exit__(self, *exc):
        self.close("failed" if exc[0] is not None else None)

    def write_snapshot(self, t: float, discharge: float, upstream_level: float, fields: Optional[Dict] = None,
                       stones: Optional[Dict] = None) -> None:
        """Appends one snapshot: fields {name: (nz, nx)}, stones {pos, vel, force_drag, force_pressure:
        (n, 2), active: (n,)}. Flushed at once."""
        f, k = self.file, self.count
        for name, value in (("time", t), ("discharge", discharge), ("upstream_level", upstream_level)):
            ds = f[name]
            ds.resize((k + 1,))
            ds[k] = value
        if self.write_fields:
            for name in FIELD_NAMES:
                arr = np.asarray(fields[name]).reshape(self.nz, self.nx)
                ds = f[f"fields/{name}"]
                ds.resize((k + 1, self.nz, self.nx))
                ds[k] = arr
        for name in STONE_VECTORS:
            ds = f[f"stones/{name}"]
            ds.resize((k + 1, self.n, 2))
            if self.n:
                ds[k] = np.asarray(stones[name]).reshape(self.n, 2)
        ds = f["stones/active"]
        ds.resize((k + 1, self.n))
        if self.n:
            ds[k] = np.asarray(stones["active"]).astype(np.uint8)
        if self.polygons is not None:
            polygon_output.write_snapshot(f, k, *self.polygons, stones["pos"], stones["angle"])
        f.flush()
        self.count += 1
        self._times.append(float(t))
        self.write_xdmf()

    def write_xdmf(self) -> None:
        """Rewrites the XDMF beside the HDF5 for the snapshots written so far (atomic replace)."""
        npv = 0 if self.polygons is None else len(self.polygons[0])
        text = xdmf_text(self.path.name, self.nx, self.nz, self.n, self._times, self.write_fields, npv)
        tmp = self.xmf_path.with_suffix(".xmf.tmp")
        tmp.write_text(text, encoding="utf-8")
        os.replace(tmp, self.xmf_path)

    def close(self, status: Optional[str] = None, profile=None, extra_attrs: Optional[Dict] = None) -> None:
        """Closes the file; then records status ('completed', 'failed: ...'), the profile and extras."""
        if self.file is None:
            return
        self.file.close()
        self.file = None
        with h5py.File(self.path, "a", libver="latest") as f:
            f.attrs["status"] = status or "completed"
            if profile is not None:
                names, seconds, calls = profile
                f["profile/names"] = np.array([str(s) for s in names], dtype=h5py.string_dtype())
                f["profile/seconds"] = np.asarray(seconds, float)
                f["profile/calls"] = np.asarray(calls, np.int64)
            for k, v in (extra_attrs or {}).items():
                f.attrs[k] = v


def xdmf_text(h5name: str, nx: int, nz: int, n: int, times: Sequence[float], fields: bool = True,
              n_poly_vertices: int = 0) -> str:
    """XDMF 2 text: a temporal collection of the fields on a 2D rectilinear mesh (cell-centred
    attributes, x_faces/z_faces as node coordinates), one of the stones as points and, for polygon
    stones (n_poly_vertices > 0), one of their outlines as polygons."""
    T = len(times)
    root = ET.Element("Xdmf", Version="2.0")
    dom = ET.SubElement(root, "Domain")

    def hdf(parent, path, dims, ntype="Float", prec="8"):
        e = ET.SubElement(parent, "DataItem", Dimensions=" ".join(map(str, dims)), NumberType=ntype,
                          Precision=prec, Format="HDF")
        e.text = f"{h5name}:{path}"
        return e

    def slab(parent, path, full, start, count, out_dims, ntype="Float", prec="8"):
        e = ET.SubElement(parent, "DataItem", ItemType="HyperSlab", Dimensions=" ".join(map(str, out_dims)),
                          Type="HyperSlab")
        sel = ET.SubElement(e, "DataItem", Dimensions=f"3 {len(full)}", Format="XML")
        sel.text = " ".join(map(str, list(start) + [1] * len(full) + list(count)))
        hdf(e, path, full, ntype, prec)
        return e

    if fields:
        coll = ET.SubElement(dom, "Grid", Name="fields", GridType="Collection", CollectionType="Temporal")
        for k, t in enumerate(times):
            g = ET.SubElement(coll, "Grid", Name=f"fields_{k}", GridType="Uniform")
            ET.SubElement(g, "Time", Value=repr(float(t)))
            ET.SubElement(g, "Topology", TopologyType="2DRectMesh", Dimensions=f"{nz + 1} {nx + 1}")
            geo = ET.SubElement(g, "Geometry", GeometryType="VXVY")
            hdf(geo, "/grid/x_faces", [nx + 1])
            hdf(geo, "/grid/z_faces", [nz + 1])
            for name in FIELD_NAMES:
                a = ET.SubElement(g, "Attribute", Name=name, AttributeType="Scalar", Center="Cell")
                slab(a, f"/fields/{name}", [T, nz, nx], [k, 0, 0], [1, nz, nx], [nz, nx], prec="4")
    if n:
        coll = ET.SubElement(dom, "Grid", Name="stones", GridType="Collection", CollectionType="Temporal")
        for k, t in enumerate(times):
            g = ET.SubElement(coll, "Grid", Name=f"stones_{k}", GridType="Uniform")
            ET.SubElement(g, "Time", Value=repr(float(t)))
            ET.SubElement(g, "Topology", TopologyType="Polyvertex", NumberOfElements=str(n), NodesPerElement="1")
            geo = ET.SubElement(g, "Geometry", GeometryType="XY")
            slab(geo, "/stones/pos", [T, n, 2], [k, 0, 0], [1, n, 2], [n, 2])
            a = ET.SubElement(g, "Attribute", Name="diameter", AttributeType="Scalar", Center="Node")
            hdf(a, "/stones/diameter", [n])
            a = ET.SubElement(g, "Attribute", Name="fixed", AttributeType="Scalar", Center="Node")
            hdf(a, "/stones/fixed", [n], "UChar", "1")
            a = ET.SubElement(g, "Attribute", Name="active", AttributeType="Scalar", Center="Node")
            slab(a, "/stones/active", [T, n], [k, 0], [1, n], [n], "UChar", "1")
            for name in ("vel", "force_drag", "force_pressure"):
                for c, comp in enumerate(("x", "z")):
                    a = ET.SubElement(g, "Attribute", Name=f"{name}_{comp}", AttributeType="Scalar", Center="Node")
                    slab(a, f"/stones/{name}", [T, n, 2], [k, 0, c], [1, n, 1], [n])
    if n and n_poly_vertices:
        m = n_poly_vertices
        coll = ET.SubElement(dom, "Grid", Name="stone_polygons", GridType="Collection", CollectionType="Temporal")
        for k, t in enumerate(times):
            g = ET.SubElement(coll, "Grid", Name=f"stone_polygons_{k}", GridType="Uniform")
            ET.SubElement(g, "Time", Value=repr(float(t)))
            topo = ET.SubElement(g, "Topology", TopologyType="Mixed", NumberOfElements=str(n))
            hdf(topo, "/stones/poly_topology", [2 * n + m], "Int", "8")
            geo = ET.SubElement(g, "Geometry", GeometryType="XY")
            slab(geo, "/stones/poly_world", [T, m, 2], [k, 0, 0], [1, m, 2], [m, 2])
            a = ET.SubElement(g, "Attribute", Name="active", AttributeType="Scalar", Center="Cell")
            slab(a, "/stones/active", [T, n], [k, 0], [1, n], [n], "UChar", "1")
            a = ET.SubElement(g, "Attribute", Name="fixed", AttributeType="Scalar", Center="Cell")
            hdf(a, "/stones/fixed", [n], "UChar", "1")
    ET.indent(root) if hasattr(ET, "indent") else None
    return '<?xml version="1.0" ?>\n<!DOCTYPE Xdmf SYSTEM "Xdmf.dtd" []>\n' + ET.tostring(root, encoding="unicode") + "\n"


class RunData:
    """Read access to a run's HDF5 file (arrays loaded on use; fields one snapshot at a time)."""

    def __init__(self, path):
        self.path = Path(path)
        with h5py.File(self.path, "r", libver="latest", swmr=True) as f:
            self.attrs = dict(f.attrs)
            self.x_faces = f["grid/x_faces"][()]
            self.z_faces = f["grid/z_faces"][()]
            self.times = f["time"][()]
            self.discharge = f["discharge"][()]
            self.upstream_level = f["upstream_level"][()]
            self.diameter = f["stones/diameter"][()]
            self.fixed = f["stones/fixed"][()].astype(bool)
            T = self.times.size
            self.pos = f["stones/pos"][:T]
            self.vel = f["stones/vel"][:T]
            self.force_drag = f["stones/force_drag"][:T]
            self.force_pressure = f["stones/force_pressure"][:T]
            self.active = f["stones/active"][:T].astype(bool)
            self.poly_vertex, self.poly_offset, self.angle = polygon_output.read(f, T)  # None for discs
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
        """All fields (nz, nx) of snapshot k (negative k counts from the end)."""
        with h5py.File(self.path, "r", libver="latest", swmr=True) as f:
            return {name: f[f"fields/{name}"][k].astype(float) for name in FIELD_NAMES}

    def stone_outlines(self, k: int):
        """Polygon stones: the world outline (v, 2) [m] of every stone at snapshot k; None for discs."""
        if self.poly_vertex is None:
            return None
        return polygon_output.outlines(self.poly_vertex, self.poly_offset, self.pos[k], self.angle[k])

    def index_at(self, t: float) -> int:
        """Snapshot nearest to time t [s]."""
        return int(np.argmin(np.abs(self.times - t)))


def check_xdmf(xmf_path) -> int:
    """Checks that an XDMF file is well-formed and that every HDF dataset it references exists with the
    declared shape, hyperslabs inside it; returns the number of references checked, raises ValueError."""
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
                files[fname] = h5py.File(xmf_path.parent / fname, "r", libver="latest", swmr=True)
            f = files[fname]
            if dpath not in f:
                raise ValueError(f"{xmf_path.name}: dataset {dpath} missing from {fname}")
            dims = tuple(int(x) for x in item.get("Dimensions").split())
            if f[dpath].shape != dims:
                raise ValueError(f"{xmf_path.name}: {dpath} has shape {f[dpath].shape}, XDMF declares {dims}")
            checked += 1
        for slab in root.iter("DataItem"):
            if slab.get("ItemType") != "HyperSlab":
                continue
            sel, data = list(slab)
            full = [int(x) for x in data.get("Dimensions").split()]
            nums = [int(x) for x in sel.text.split()]
            r = len(full)
            start, stride, count = nums[:r], nums[r:2 * r], nums[2 * r:]
            for s, st, c, d in zip(start, stride, count, full):
                if s < 0 or st < 1 or c < 1 or s + (c - 1) * st >= d:
                    raise ValueError(f"{xmf_path.name}: hyperslab {nums} outside {full} of {data.text.strip()}")
            out = [int(x) for x in slab.get("Dimensions").split()]
            if int(np.prod(out)) != int(np.prod(count)):
                raise ValueError(f"{xmf_path.name}: hyperslab count {count} does not give {out}")
    finally:
        for f in files.values():
            f.close()
    return checked
