"""Real clients read the output: ParaView's three XDMF readers (pvbatch, tests/paraview_dump.py) and
meshio, on a whole run of the quick scene (71 snapshots), on a run killed with SIGKILL and on a short
run of polygon stones. Each must find every (completed) time step, the field and stone array names, and
the values of run.h5; ParaView also draws the polygon stones, vertex for vertex as run.h5 has them."""
import shutil
import subprocess
from pathlib import Path

import h5py
import numpy as np
import pytest
from test_resume import _vofdem, kill_at_snapshot

from vofdem.io import FIELD_NAMES, completed_snapshots

# on several processes (pytest-xdist, --dist loadgroup) the module runs on one: the runs made once
pytestmark = pytest.mark.xdist_group("paraview")

ROOT = Path(__file__).resolve().parents[1]
READERS = ("XDMFReader", "Xdmf3ReaderS", "Xdmf3ReaderT")
QUICK = ["run", "maeno2008", "--quick", "--no-figures", "--no-animation", "--no-progress"]
# the polygon scene's quick variant to 8 s: 17 snapshots, the stones released at 5 s
POLYGONS = ["run", str(ROOT / "scenes" / "maeno2008_polygons.toml"), "--quick", "--end-time", "8", "--no-figures",
            "--no-animation", "--no-progress"]
VTK_POLYGON = 7
# point data of the stones in the XDMF and their datasets in run.h5
STONE_DATA = {"velocity": "stones/vel", "force_drag": "stones/force_drag", "force_pressure": "stones/force_pressure",
              "position": "stones/pos"}
PVBATCH = shutil.which("pvbatch")
needs_pvbatch = pytest.mark.skipif(PVBATCH is None, reason="pvbatch (Debian's paraview package) is not installed: "
                                   "the ParaView readers are not tested (scripts/install_deps.sh installs it)")


@pytest.fixture(scope="module")
def quick_run(tmp_path_factory):
    out = tmp_path_factory.mktemp("quick") / "run"
    p = _vofdem(*QUICK, "--out", str(out))
    assert p.wait(timeout=900) == 0, p.stderr.read()
    p.stderr.close()
    return out


@pytest.fixture(scope="module")
def polygon_run(tmp_path_factory):
    out = tmp_path_factory.mktemp("polygons") / "run"
    p = _vofdem(*POLYGONS, "--out", str(out))
    assert p.wait(timeout=900) == 0, p.stderr.read()
    p.stderr.close()
    return out


@pytest.fixture(scope="module")
def killed_run(tmp_path_factory):
    out = tmp_path_factory.mktemp("killed") / "run"
    # the XDMF files rewritten after every snapshot: the kill leaves them a snapshot behind at most
    kill_at_snapshot(out, int(np.random.default_rng().integers(20, 60)), QUICK + ["--xdmf-seconds", "0"])
    return out


def _expected(out):
    with h5py.File(out / "run.h5", "r") as f:  # plain h5py, default mode
        T = completed_snapshots(f["time"][()])
        h5 = {name: f[name][:T] for name in ["time", *STONE_DATA.values()] + [f"fields/{n}" for n in FIELD_NAMES]}
        h5["stones/diameter"] = f["stones/diameter"][()]
        return T, h5


def _compare(reader, z, T, h5):
    """A reader's arrays (paraview_dump.py) against run.h5."""
    times = z["times"]
    # all of a whole run's snapshots; a killed run's XDMF may lack the last completed one
    assert T - 1 <= times.size <= T and times.size >= 2, (reader, times.size, T)
    assert np.array_equal(times, h5["time"][:times.size]), reader
    assert {k.split("/")[-1] for k in z if k.startswith("fields/0/cell/")} == set(FIELD_NAMES)
    assert {k.split("/")[-1] for k in z if k.startswith("stones/0/point/")} == \
        set(STONE_DATA) | {"diameter", "fixed", "active"}
    for k in range(times.size):
        for name in FIELD_NAMES:
            assert np.array_equal(z[f"fields/{k}/cell/{name}"], h5[f"fields/{name}"][k].ravel()), (reader, k, name)
        for name, ds in STONE_DATA.items():
            assert np.array_equal(z[f"stones/{k}/point/{name}"][:, :2], h5[ds][k]), (reader, k, name)
        assert np.array_equal(z[f"stones/{k}/points"][:, :2], h5["stones/pos"][k]), (reader, k)
        assert np.array_equal(z[f"stones/{k}/point/diameter"], h5["stones/diameter"]), (reader, k)


def _compare_polygons(reader, z, T, f):
    """ParaView's polygon stones against run.h5 (h5py file f): one VTK polygon per stone, its vertices
    in run.h5's order, at the world positions of each snapshot, with the stones' cell data."""
    offset = f["stones/poly_offset"][()]
    n, m = offset.size - 1, int(offset[-1])
    assert T >= 2 and z["times"].size == T, (reader, z["times"].size, T)
    for k in range(T):
        b = f"stone_polygons/{k}"
        assert np.array_equal(z[f"{b}/cell_types"], np.full(n, VTK_POLYGON)), (reader, k)
        assert np.array_equal(z[f"{b}/offsets"], offset) and np.array_equal(z[f"{b}/connectivity"], np.arange(m))
        world = f["stones/poly_world"][k]
        assert np.array_equal(z[f"{b}/points"][:, :2], world) and not np.isnan(world).any(), (reader, k)
        for name, ds in (("angle", f["stones/angle"][k]), ("active", f["stones/active"][k]),
                         ("diameter", f["stones/diameter"][()]), ("fixed", f["stones/fixed"][()])):
            assert np.array_equal(z[f"{b}/cell/{name}"], ds), (reader, k, name)


def _check_paraview(out, tmp_path, polygons=False):
    T, h5 = _expected(out)
    r = subprocess.run([PVBATCH, str(ROOT / "tests" / "paraview_dump.py"), str(out / "run.xmf"),
                        str(tmp_path / "pv_"), *READERS], capture_output=True, text=True, timeout=600)
    assert r.returncode == 0, r.stdout + r.stderr
    assert "HDF5-DIAG" not in r.stderr and "XDMF Error" not in r.stderr, r.stderr[:2000]
    for reader in READERS:
        with np.load(tmp_path / f"pv_{reader}.npz") as z:
            _compare(reader, dict(z), T, h5)
            assert any(k.startswith("stone_polygons/") for k in z) == polygons, reader
            if polygons:
                with h5py.File(out / "run.h5", "r") as f:
                    _compare_polygons(reader, dict(z), T, f)
    return T


def _check_meshio(out):
    import meshio

    T, h5 = _expected(out)
    with meshio.xdmf.TimeSeriesReader(out / "run.xmf") as r:
        points, cells = r.read_points_cells()
        assert T - 1 <= r.num_steps <= T and cells[0].type == "quad"
        assert len(cells[0].data) == h5["fields/F"].shape[1] * h5["fields/F"].shape[2]
        for k in range(r.num_steps):
            t, point_data, cell_data = r.read_data(k)
            assert t == h5["time"][k] and set(cell_data) == set(FIELD_NAMES)
            for name in FIELD_NAMES:
                assert np.array_equal(cell_data[name][0], h5[f"fields/{name}"][k]), (k, name)
    with meshio.xdmf.TimeSeriesReader(out / "stones.xmf") as r:
        points, cells = r.read_points_cells()
        assert cells[0].type == "vertex" and np.array_equal(points, h5["stones/pos"][0])
        for k in range(r.num_steps):
            t, point_data, _ = r.read_data(k)
            assert t == h5["time"][k]
            for name, ds in STONE_DATA.items():
                assert np.array_equal(point_data[name], h5[ds][k]), (k, name)
    return T


@pytest.mark.slow
@needs_pvbatch
def test_paraview_reads_every_snapshot_of_a_whole_run(quick_run, tmp_path):
    assert _check_paraview(quick_run, tmp_path) == 71
    with h5py.File(quick_run / "run.h5", "r") as f:  # several chunks' worth of snapshots of every series
        assert f.attrs["status"] == "completed" and f["fields/F"].shape[0] == 71


@pytest.mark.slow
def test_meshio_reads_every_snapshot_of_a_whole_run(quick_run):
    assert _check_meshio(quick_run) == 71


@pytest.mark.slow
@needs_pvbatch
def test_paraview_and_meshio_read_a_run_killed_with_sigkill(killed_run, tmp_path):
    with h5py.File(killed_run / "run.h5", "r") as f:
        assert f.attrs["status"] == "running"
    T = _check_paraview(killed_run, tmp_path)
    assert 20 <= T < 71
    assert _check_meshio(killed_run) == T



@pytest.mark.slow
@needs_pvbatch
def test_paraview_draws_the_polygon_stones_of_run_h5(polygon_run, tmp_path):
    # the polygon stones' grid of run.xmf: the three readers draw every stone of every snapshot as run.h5's
    # polygon; the fields and the stones' points read as in a disc run
    assert _check_paraview(polygon_run, tmp_path, polygons=True) == 17
    with h5py.File(polygon_run / "run.h5", "r") as f:
        moved = np.abs(f["stones/angle"][-1] - f["stones/angle"][0]).max()
    assert moved > 1e-3  # the stones turned after their release: the vertices are not the first snapshot's


@pytest.mark.slow
def test_meshio_reads_the_fields_and_stones_of_a_polygon_run(polygon_run):
    # meshio 5.3 reads no polygons in a mixed topology (its translate_mixed_cells knows no type 3), so it
    # is given no polygon grid; the polygon grid in run.xmf must not keep it from the fields and stones
    assert _check_meshio(polygon_run) == 17


@pytest.mark.slow
@needs_pvbatch
def test_the_paraview_example_builds_its_view(quick_run):
    # the pipeline of examples/paraview_view.py without rendering (rendering needs a display)
    r = subprocess.run([PVBATCH, str(ROOT / "examples" / "paraview_view.py"), str(quick_run), "--check"],
                       capture_output=True, text=True, timeout=600)
    assert r.returncode == 0, r.stdout + r.stderr
    # the quick grid: 52 x 19 cells (0.38 m: a 1 cm bed row, 2 cm rows, the top one 3 cm)
    assert "t = 35 s: cells 988, water cells" in r.stdout and "stones 80" in r.stdout
    assert "porosity" in r.stdout and "velocity" in r.stdout
