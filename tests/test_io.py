"""HDF5 + XDMF output: contents, incremental writing, and an XDMF that matches the HDF5 file."""
import xml.etree.ElementTree as ET

import h5py
import numpy as np
import pytest

from vofdem.io import RunData, RunWriter, cell_velocities, check_xdmf
from vofdem.scene import Scene

NX, NZ, N = 6, 4, 3
XF = np.linspace(0.0, 0.6, NX + 1)
ZF = np.array([0.0, 0.005, 0.015, 0.025, 0.035])


def _snapshot(k):
    rng = np.random.default_rng(k)
    fields = {name: rng.random((NZ, NX)) for name in ("F", "p", "porosity", "u", "w")}
    stones = {name: rng.random((N, 2)) for name in ("pos", "vel", "force_drag", "force_pressure")}
    stones["active"] = np.array([True, k < 2, True])
    return fields, stones


def _write(path, count, close=True):
    s = Scene.maeno2008()
    w = RunWriter(path, XF, ZF, [0.04, 0.048, 0.05], [True, False, False], scene_toml=s.to_toml(), seed=5,
                  version="9.9.9")
    for k in range(count):
        fields, stones = _snapshot(k)
        w.write_snapshot(0.5 * k, 0.01 + 1e-3 * k, 0.3, fields, stones)
    if close:
        w.close(profile=(["fluid", "dem"], [1.5, 0.5], [10, 100]))
    return w


def test_contents_round_trip(tmp_path):
    _write(tmp_path / "run.h5", 3)
    d = RunData(tmp_path / "run.h5")
    assert d.times.tolist() == [0.0, 0.5, 1.0]
    assert d.attrs["seed"] == 5 and d.attrs["vofdem_version"] == "9.9.9" and d.attrs["status"] == "completed"
    assert d.scene() == Scene.maeno2008()
    assert d.attrs["created"].endswith("+00:00")
    fields, stones = _snapshot(1)
    assert np.allclose(d.fields(1)["p"], fields["p"], rtol=1e-6)  # fields stored in float32
    assert np.array_equal(d.pos[1], stones["pos"]) and np.array_equal(d.force_drag[1], stones["force_drag"])
    assert d.active[:, 1].tolist() == [True, True, False]
    assert d.fixed.tolist() == [True, False, False]
    assert d.profile[0] == ["fluid", "dem"] and d.profile[2].tolist() == [10, 100]


def test_snapshots_survive_without_close(tmp_path):
    # a crash: the writer is never closed, yet what was flushed is readable (SWMR) and the XDMF matches
    w = _write(tmp_path / "run.h5", 2, close=False)
    d = RunData(tmp_path / "run.h5")
    assert d.times.tolist() == [0.0, 0.5] and d.attrs["status"] == "running"
    assert check_xdmf(tmp_path / "run.xmf") > 0
    w.close("failed: test")
    assert RunData(tmp_path / "run.h5").attrs["status"] == "failed: test"


def test_xdmf_is_well_formed_and_matches_the_hdf5(tmp_path):
    _write(tmp_path / "run.h5", 4)
    xmf = tmp_path / "run.xmf"
    root = ET.parse(xmf).getroot()
    colls = {g.get("Name"): g for g in root.find("Domain").findall("Grid")}
    assert set(colls) == {"fields", "stones"}
    with h5py.File(tmp_path / "run.h5", "r") as f:
        times = f["time"][()]
    for coll in colls.values():
        steps = coll.findall("Grid")
        assert [float(g.find("Time").get("Value")) for g in steps] == times.tolist()
    # cell attributes have one entry fewer than the mesh's nodes each way
    g0 = colls["fields"].find("Grid")
    assert g0.find("Topology").get("Dimensions") == f"{NZ + 1} {NX + 1}"
    for a in g0.findall("Attribute"):
        assert a.get("Center") == "Cell" and a.find("DataItem").get("Dimensions") == f"{NZ} {NX}"
    # 4 snapshots x (2 geometry + 5 fields) + 4 x (pos + diameter + fixed + active + 6 components)
    assert check_xdmf(xmf) == 4 * 7 + 4 * 10


def test_check_xdmf_catches_a_wrong_shape(tmp_path):
    _write(tmp_path / "run.h5", 2)
    xmf = tmp_path / "run.xmf"
    xmf.write_text(xmf.read_text().replace(f'Dimensions="{NX + 1}"', f'Dimensions="{NX + 2}"'))
    with pytest.raises(ValueError, match=r"/grid/x_faces has shape \(7,\), XDMF declares \(8,\)"):
        check_xdmf(xmf)
    xmf.write_text("<Xdmf><Domain>")
    with pytest.raises(ET.ParseError):
        check_xdmf(xmf)


def test_cell_velocities_average_the_faces():
    nx, nz = 3, 2
    face_u = np.arange((nx + 1) * nz, dtype=float)  # row k: k*4 + [0, 1, 2, 3]
    face_w = np.arange(nx * (nz + 1), dtype=float)
    u, w = cell_velocities(face_u, face_w, nx, nz)
    assert u.tolist() == [[0.5, 1.5, 2.5], [4.5, 5.5, 6.5]]
    assert w.tolist() == [[1.5, 2.5, 3.5], [4.5, 5.5, 6.5]]
