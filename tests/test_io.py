"""HDF5 + XDMF output: contents, the written format, incremental writing, an XDMF that matches the HDF5
file, and a file that plain readers open after the writer was killed at random moments."""
import os
import signal
import subprocess
import sys
import time
import xml.etree.ElementTree as ET
from pathlib import Path

import h5py
import numpy as np
import pytest

import vofdem
from vofdem.io import (HDF5_LIBVER, RunData, RunWriter, cell_velocities, check_xdmf, completed_snapshots, mesh_of,
                       open_run, snapshots_written)
from vofdem.scene import Scene

NX, NZ, N = 6, 4, 3
XF = np.linspace(0.0, 0.6, NX + 1)
ZF = np.array([0.0, 0.005, 0.015, 0.025, 0.035])
ENV = dict(os.environ, PYTHONPATH=str(Path(vofdem.__file__).resolve().parents[1]) + os.pathsep
           + os.environ.get("PYTHONPATH", ""))


def _snapshot(k):
    rng = np.random.default_rng(k)
    fields = {name: rng.random((NZ, NX)) for name in ("F", "p", "porosity", "u", "w")}
    stones = {name: rng.random((N, 2)) for name in ("pos", "vel", "force_drag", "force_pressure")}
    stones["active"] = np.array([True, k < 2, True])
    return fields, stones


def _write(path, count, close=True, capacity=None):
    s = Scene.maeno2008()
    w = RunWriter(path, XF, ZF, [0.04, 0.048, 0.05], [True, False, False], capacity=capacity or count,
                  scene_toml=s.to_toml(), seed=5, version="9.9.9")
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
    assert np.array_equal(d.fields(1)["p"], fields["p"].astype(np.float32))  # fields stored in float32
    assert np.array_equal(d.fields(-1)["u"], _snapshot(2)[0]["u"].astype(np.float32))
    assert np.array_equal(d.pos[1], stones["pos"]) and np.array_equal(d.force_drag[1], stones["force_drag"])
    assert d.active[:, 1].tolist() == [True, True, False]
    assert d.fixed.tolist() == [True, False, False]
    assert d.profile[0] == ["fluid", "dem"] and d.profile[2].tolist() == [10, 100]
    with pytest.raises(IndexError, match="snapshot 3 is out of range"):
        d.fields(3)


def test_the_file_is_in_the_old_format_and_made_at_full_size(tmp_path):
    w = _write(tmp_path / "run.h5", 2, close=False, capacity=5)
    assert HDF5_LIBVER == ("earliest", "v110")
    # superblock version 0 (byte 8 after the signature): no open-for-write flag that readers refuse
    raw = (tmp_path / "run.h5").read_bytes()
    assert raw[:8] == b"\x89HDF\r\n\x1a\n" and raw[8] == 0
    with open_run(tmp_path / "run.h5") as f:  # while the writer holds it open (plain h5py: the kill test)
        assert f["fields/F"].shape == (5, NZ, NX) and f["fields/F"].chunks is None  # contiguous
        assert f["fields/F"].id.get_space_status() == h5py.h5d.SPACE_STATUS_ALLOCATED
        times = f["time"][()]
        assert times[:2].tolist() == [0.0, 0.5] and np.isnan(times[2:]).all()
        assert completed_snapshots(times) == 2
        assert np.isnan(f["fields/p"][2:]).all()
        # snapshot 1 of each series as a dataset of its own (a virtual view, for meshio)
        assert f["snapshots/000001/p"].is_virtual
        assert np.array_equal(f["snapshots/000001/p"][()], f["fields/p"][1])
        assert np.array_equal(f["snapshots/000001/vel"][()], f["stones/vel"][1])
    assert snapshots_written(tmp_path / "run.h5") == 2  # while the writer holds it open
    assert snapshots_written(tmp_path / "not_yet.h5") == 0
    h5py.File(tmp_path / "empty.h5", "w").close()  # made, no /time yet
    assert snapshots_written(tmp_path / "empty.h5") == 0
    w.close("failed: test")
    assert RunData(tmp_path / "run.h5").attrs["status"] == "failed: test"
    assert not (tmp_path / "run.h5.tmp").exists()


def test_capacity_and_reopen(tmp_path):
    w = _write(tmp_path / "run.h5", 3, close=False)
    with pytest.raises(ValueError, match="beyond the file's capacity of 3 snapshots"):
        w.write_snapshot(9.0, 0.0, 0.0, *_snapshot(3))
    w.close()
    with pytest.raises(ValueError, match=r"capacity = 0 snapshots is out of range \(allowed: >= 1\)"):
        RunWriter(tmp_path / "x.h5", XF, ZF, [], [], capacity=0)
    # a resumed run continues after its checkpoint's snapshot: the later ones are written again
    w = RunWriter.reopen(tmp_path / "run.h5", 2)
    assert w.count == 2 and RunData(tmp_path / "run.h5").times.tolist() == [0.0, 0.5]
    assert check_xdmf(tmp_path / "run.xmf") > 0
    fields, stones = _snapshot(7)
    w.write_snapshot(1.0, 0.0, 0.3, fields, stones)
    w.close()
    d = RunData(tmp_path / "run.h5")
    assert d.times.tolist() == [0.0, 0.5, 1.0] and np.array_equal(d.vel[2], stones["vel"])


def test_xdmf_is_version_3_cell_centred_and_matches_the_hdf5(tmp_path):
    _write(tmp_path / "run.h5", 4)
    xmf = tmp_path / "run.xmf"
    root = ET.parse(xmf).getroot()
    assert root.get("Version") == "3.0"
    colls = {g.get("Name"): g for g in root.find("Domain").findall("Grid")}
    assert list(colls) == ["stones", "fields"]  # the fields last: meshio reads the last collection
    with h5py.File(tmp_path / "run.h5", "r") as f:
        times = f["time"][()]
    for coll in colls.values():
        assert [float(g.find("Time").get("Value")) for g in coll.findall("Grid")] == times.tolist()
    g0 = colls["fields"].find("Grid")
    assert g0.find("Topology").get("TopologyType") == "Quadrilateral"
    assert g0.find("Topology").get("NumberOfElements") == str(NX * NZ)
    for a in g0.findall("Attribute"):
        assert a.get("Center") == "Cell" and a.find("DataItem").get("Dimensions") == f"{NZ} {NX}"
    names = [a.get("Name") for a in colls["stones"].find("Grid").findall("Attribute")]
    assert names == ["diameter", "fixed", "active", "velocity", "force_drag", "force_pressure", "position"]
    # 4 snapshots x (2 mesh + 5 fields) + 4 x (index + pos + 7 point data)
    assert check_xdmf(xmf) == 4 * 7 + 4 * 9
    assert check_xdmf(tmp_path / "stones.xmf") == 4 * 9


def _listed(xmf):
    return len(ET.parse(xmf).getroot().find("Domain").find("Grid").findall("Grid"))


def test_the_xdmf_files_list_the_first_snapshot_then_every_xdmf_seconds_and_all_at_the_end(tmp_path):
    with pytest.raises(ValueError, match=r"xdmf_seconds = -1.0 is out of range \(allowed: >= 0 s\)"):
        RunWriter(tmp_path / "x.h5", XF, ZF, [], [], capacity=1, xdmf_seconds=-1.0)
    w = RunWriter(tmp_path / "run.h5", XF, ZF, [0.04, 0.048, 0.05], [True, False, False], capacity=4,
                  xdmf_seconds=3600.0)
    for k in range(3):
        w.write_snapshot(0.5 * k, 0.0, 0.3, *_snapshot(k))
        with open_run(tmp_path / "run.h5") as f:  # the HDF5 file completes each snapshot at once
            assert completed_snapshots(f["time"][()]) == k + 1
    assert _listed(tmp_path / "run.xmf") == 1 and _listed(tmp_path / "stones.xmf") == 1
    w.close()
    assert _listed(tmp_path / "run.xmf") == 3 and check_xdmf(tmp_path / "stones.xmf") == 3 * 9
    w = RunWriter.reopen(tmp_path / "run.h5", 2, xdmf_seconds=3600.0)  # a resumed run lists its snapshots
    assert _listed(tmp_path / "run.xmf") == 2
    w.write_snapshot(1.0, 0.0, 0.3, *_snapshot(2))
    assert _listed(tmp_path / "run.xmf") == 2
    w.close("failed: test")
    assert _listed(tmp_path / "run.xmf") == 3


def test_check_xdmf_catches_a_wrong_shape_and_a_wrong_time_count(tmp_path):
    _write(tmp_path / "run.h5", 2)
    xmf = tmp_path / "run.xmf"
    good = xmf.read_text()
    xmf.write_text(good.replace(f'Dimensions="{NZ} {NX}"', f'Dimensions="{NZ} {NX + 1}"'))
    with pytest.raises(ValueError, match=r"/snapshots/000000/F has shape \(4, 6\), XDMF declares \(4, 7\)"):
        check_xdmf(xmf)
    xmf.write_text(good.replace('<Time Value="0.5"/>', '<Time Value="0.75"/>'))
    with pytest.raises(ValueError, match="collection 'stones' lists 2 times"):
        check_xdmf(xmf)
    xmf.write_text("<Xdmf><Domain>")
    with pytest.raises(ET.ParseError):
        check_xdmf(xmf)


def test_mesh_of_numbers_cells_like_the_grid():
    nodes, cells = mesh_of(np.array([0.0, 1.0, 3.0]), np.array([0.0, 0.5]))
    assert nodes.tolist() == [[0, 0], [1, 0], [3, 0], [0, 0.5], [1, 0.5], [3, 0.5]]
    assert cells.tolist() == [[0, 1, 4, 3], [1, 2, 5, 4]] and cells.dtype == np.int32


def test_cell_velocities_average_the_faces():
    nx, nz = 3, 2
    face_u = np.arange((nx + 1) * nz, dtype=float)  # row k: k*4 + [0, 1, 2, 3]
    face_w = np.arange(nx * (nz + 1), dtype=float)
    u, w = cell_velocities(face_u, face_w, nx, nz)
    assert u.tolist() == [[0.5, 1.5, 2.5], [4.5, 5.5, 6.5]]
    assert w.tolist() == [[1.5, 2.5, 3.5], [4.5, 5.5, 6.5]]


# a writer that writes snapshots as fast as it can (the file is in the middle of a write nearly all the
# time), each snapshot's values a function of its index k; the XDMF files rewritten every argv[2] s
WRITER = """
import sys, numpy as np
from vofdem.io import RunWriter
nx, nz, n, T = 30, 20, 40, 400
w = RunWriter(sys.argv[1], np.linspace(0, 1, nx + 1), np.linspace(0, 1, nz + 1), np.full(n, 0.05), np.zeros(n, bool),
              capacity=T, xdmf_seconds=float(sys.argv[2]))
print("ready", flush=True)
for k in range(T):
    f = {name: np.full((nz, nx), k + i, np.float32) for i, name in enumerate(("F", "p", "porosity", "u", "w"))}
    s = {name: np.full((n, 2), k + 0.5 * i) for i, name in enumerate(("pos", "vel", "force_drag", "force_pressure"))}
    s["active"] = np.ones(n, bool)
    w.write_snapshot(0.1 * k, 1e-3 * k, 0.2, f, s)
"""


def test_a_writer_killed_at_random_moments_leaves_a_file_plain_readers_open(tmp_path):
    rng = np.random.default_rng(20261124)
    counts = []
    for trial in range(8):
        path = tmp_path / f"kill{trial}" / "run.h5"
        path.parent.mkdir()
        xdmf_seconds = 0.0 if trial % 2 else 0.02  # after every snapshot, or every few dozen
        p = subprocess.Popen([sys.executable, "-c", WRITER, str(path), str(xdmf_seconds)], env=ENV,
                             stdout=subprocess.PIPE, text=True)
        assert p.stdout.readline().strip() == "ready"
        time.sleep(rng.uniform(0.01, 0.3))
        p.send_signal(signal.SIGKILL)
        p.wait(timeout=30)
        p.stdout.close()
        with h5py.File(path, "r") as f:  # plain h5py, default mode
            times = f["time"][()]
            T = completed_snapshots(times)
            assert np.array_equal(times[:T], 0.1 * np.arange(T)) and np.isnan(times[T:]).all()
            # on a loaded machine the kill may come before the first snapshot (T = 0)
            for k in sorted({0, T // 2, T - 1}) if T else ():
                assert (f["fields/porosity"][k] == k + 2).all() and (f["snapshots/%06d/u" % k][()] == k + 3).all()
                assert (f["stones/force_pressure"][k] == k + 1.5).all()
        counts.append(T)
        listed = _listed(path.with_suffix(".xmf"))
        # the XDMF is renamed in after the snapshot's time is written; the first snapshot at once
        assert (T - 1 if xdmf_seconds == 0.0 else min(T, 1)) <= listed <= T, (xdmf_seconds, listed, T)
        assert RunData(path).times.size == T
    assert max(counts) >= 1 and len(set(counts)) > 1, counts  # killed at different snapshots
