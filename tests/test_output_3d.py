"""3D stones in run.h5 and its XDMF files (output_3d.py): a settling heap of spheres written snapshot by
snapshot is read back as it was (y, quaternions, ParaView's points (x, z, B/2 - y) computed by hand), the
XDMF files reference datasets that exist, ParaView's three XDMF readers and meshio place every stone at
its 3D point, the plan view draws, and a writer refuses a width that is not one."""
import shutil
import subprocess
from pathlib import Path

import meshio
import numpy as np
import pytest
from test_spheres import heap

from vofdem import io, plots
from vofdem.scene import Scene

# on several processes (pytest-xdist, --dist loadgroup) the module runs on one: the 3D heap's run made once
pytestmark = pytest.mark.xdist_group("output_3d")

HERE = Path(__file__).resolve().parent
PVBATCH = shutil.which("pvbatch")
READERS = ("XDMFReader", "Xdmf3ReaderS", "Xdmf3ReaderT")
WIDTH = 0.1


def _write_heap(path, snapshots=4, dt=0.05):
    """A heap of 12 spheres settling in a 0.1 m wide flume, written at `snapshots` times: the run's file
    and the states written (y, quat, pos per snapshot)."""
    s = heap(width=WIDTH)
    x_faces, z_faces = np.linspace(0.0, 0.25, 6), np.linspace(0.0, 0.3, 7)
    d = 2.0 * np.asarray(s.stone_radius)
    written = []
    with io.RunWriter(path, x_faces, z_faces, d, np.zeros(d.size, bool), capacity=snapshots, width=WIDTH,
                      write_fields=False, xdmf_seconds=0.0) as w:
        for k in range(snapshots):
            if k:
                s.advance(dt)
            pos = np.array(s.stone_pos, float)
            stones = {"pos": pos, "vel": np.array(s.stone_vel), "force_drag": np.zeros_like(pos),
                      "force_pressure": np.zeros_like(pos), "active": np.ones(d.size, bool),
                      "y": np.array(s.stone_y), "quat": np.array(s.stone_quat)}
            w.write_snapshot(0.05 * k, 0.0, 0.0, None, stones)
            written.append({key: stones[key] for key in ("pos", "y", "quat")})
    return written


@pytest.fixture(scope="module")
def heap_run(tmp_path_factory):
    path = tmp_path_factory.mktemp("heap3d") / "run.h5"
    return path, _write_heap(path)


def test_the_3d_series_read_back_as_written(heap_run):
    path, written = heap_run
    data = io.RunData(path)
    assert data.width == WIDTH and data.y.shape == (4, 12) and data.quat.shape == (4, 12, 4)
    for k, st in enumerate(written):
        np.testing.assert_array_equal(data.y[k], st["y"])
        np.testing.assert_array_equal(data.quat[k], st["quat"])
        np.testing.assert_array_equal(data.pos[k], st["pos"])
    # the heap moved across the flume and turned, so the series are not copies of the start
    assert np.abs(data.y[-1] - data.y[0]).max() > 1e-4 and np.abs(data.quat[-1] - data.quat[0]).max() > 1e-4
    import h5py

    with h5py.File(path, "r") as f:
        p3 = f["stones/point3"][2]
    st = written[2]
    for i in (0, 5, 11):  # by hand: (x, z, B/2 - y)
        assert tuple(p3[i]) == (st["pos"][i, 0], st["pos"][i, 1], 0.05 - st["y"][i])


def test_the_xdmf_files_reference_the_3d_points(heap_run):
    path, _ = heap_run
    assert io.check_xdmf(path.with_suffix(".xmf")) > 0
    assert io.check_xdmf(path.with_name("stones.xmf")) > 0
    text = path.with_name("stones.xmf").read_text()
    assert text.count('GeometryType="XYZ"') == 4 and "/point3" in text and 'Name="y"' in text


def test_meshio_reads_the_stones_at_their_3d_points(heap_run):
    path, written = heap_run
    with meshio.xdmf.TimeSeriesReader(path.with_name("stones.xmf")) as r:
        points, _ = r.read_points_cells()
        for k in range(r.num_steps):
            t, point_data, _ = r.read_data(k)
            if points.shape[1] == 3 and k == 0:
                np.testing.assert_array_equal(points[:, 2], 0.5 * WIDTH - written[0]["y"])
            np.testing.assert_array_equal(point_data["y"], written[k]["y"])


@pytest.mark.skipif(PVBATCH is None, reason="pvbatch (Debian's paraview package) is not installed")
def test_paraview_draws_the_stones_at_their_3d_points(heap_run, tmp_path):
    path, written = heap_run
    subprocess.run([PVBATCH, str(HERE / "paraview_dump.py"), str(path.with_name("stones.xmf")), str(tmp_path / "pv_"),
                    *READERS], check=True, capture_output=True, timeout=300)
    for reader in READERS:
        z = np.load(tmp_path / f"pv_{reader}.npz")
        assert z["times"].size == len(written), reader
        for k, st in enumerate(written):
            expected = np.column_stack([st["pos"], 0.5 * WIDTH - st["y"]])
            np.testing.assert_array_equal(z[f"stones/{k}/points"], expected, err_msg=f"{reader} {k}")
            np.testing.assert_array_equal(z[f"stones/{k}/point/y"], st["y"], err_msg=f"{reader} {k}")


def test_the_plan_view_draws_3d_stones_and_refuses_plane_ones(heap_run, tmp_path):
    path, _ = heap_run
    data = io.RunData(path)
    scene = Scene()
    scene.weir.toe_x, scene.weir.height = 0.02, 0.1  # a weir's toes inside the 0.25 m heap's flume
    fig = plots.fig_plan_view(data, scene)
    ax = fig.axes[1]
    assert len(ax.collections) == 1 and len(ax.collections[0].get_offsets()) == 12
    order = np.argsort(data.pos[-1, :, 1])  # the lowest first
    np.testing.assert_array_equal(ax.collections[0].get_offsets(), np.column_stack([data.pos[-1, order, 0],
                                                                                    data.y[-1, order]]))
    fig.savefig(tmp_path / "plan.png")
    data.y = None
    with pytest.raises(ValueError, match="3D stones"):
        plots.fig_plan_view(data, scene)


def test_a_writer_refuses_a_width_that_is_not_one(tmp_path):
    for bad in (0.0, -0.1, float("nan"), float("inf")):
        with pytest.raises(ValueError, match="width = .* out of range"):
            io.RunWriter(tmp_path / "r.h5", [0.0, 1.0], [0.0, 1.0], [0.05], [False], capacity=1, width=bad)
    assert not (tmp_path / "r.h5").exists()
