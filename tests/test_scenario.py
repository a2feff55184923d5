"""The Maeno 2008 scenario with the real coupled solver, at a small size: the quick variant for the
spin-up and the first seconds of the ramp. Checks the output files against each other and the stage
table against the stones' displacements (what the physics gives is not asserted here)."""
import csv

import numpy as np
import pytest

from vofdem.io import RunData, check_xdmf
from vofdem.run import run_scene
from vofdem.scene import Scene

# on several processes (pytest-xdist, --dist loadgroup) the module runs on one: the quick run made once
pytestmark = pytest.mark.xdist_group("scenario")

END_TIME = 7.0  # s: 5 s spin-up at 10 l/s + 2 s of the ramp


@pytest.fixture(scope="module")
def run(tmp_path_factory):
    out = tmp_path_factory.mktemp("maeno2008_small")
    scene = Scene.maeno2008().quick().replace(end_time=END_TIME)
    res = run_scene(scene, out, progress=False, figures=True, animation=True)
    return scene, out, res


def test_output_files_exist_and_agree(run):
    scene, out, res = run
    d = RunData(out / "run.h5")
    assert d.attrs["status"] == "completed" and d.attrs["seed"] == scene.seed
    assert d.scene() == scene
    n_snap = int(round(END_TIME / scene.output.snapshot_interval)) + 1
    assert d.times.size == n_snap and d.times[-1] == pytest.approx(END_TIME)
    assert check_xdmf(out / "run.xmf") == n_snap * 7 + n_snap * 9  # mesh + 5 fields; index, pos, 7 point data
    f = d.fields(-1)
    assert set(f) == {"F", "p", "porosity", "u", "w"}
    assert 0.0 <= f["F"].min() and f["F"].max() <= 1.0 + 1e-6
    # the porosity inside the weir comes from the stones (eq. 11 with n_exp = 0.41): between 0 and 1,
    # and open water outside
    assert f["porosity"].min() < 0.6 and f["porosity"][-1].min() == pytest.approx(1.0)
    assert np.all(np.isfinite(d.force_drag)) and np.all(np.isfinite(d.force_pressure))
    # water over the weir: the upstream gauge stands above the crest
    assert np.all(d.upstream_level[1:] > scene.weir.height)
    for name in ("stage_table.md", "stage_table.csv", "crest_lowering.csv", "profile.md", "figures/timeline.png",
                 "figures/porosity_initial.png", "figures/velocity_distribution.png", "figures/rating_curve.png"):
        assert (out / name).stat().st_size > 0, name
    assert any(p.name.startswith("animation") and p.stat().st_size > 0 for p in res.files)
    names = d.profile[0]
    assert {"porosity", "fluid_forces", "dem", "fluid"} <= set(names)
    assert res.real_time_factor > 0


def test_stones_held_in_the_spin_up(run):
    scene, out, _ = run
    d = RunData(out / "run.h5")
    spin = d.times <= scene.hydrograph.spin_up_duration + 1e-9
    assert np.abs(d.pos[spin] - d.pos[0]).max() == 0.0


def test_stage_table_agrees_with_the_displacements(run):
    scene, out, res = run
    d = RunData(out / "run.h5")
    a = res.analysis
    disp = np.linalg.norm(d.pos - d.pos[0], axis=2)
    removed = (disp > d.diameter) | ~d.active
    removed &= ~d.fixed
    assert a.removed_count.tolist() == [int(np.any(removed[: k + 1], axis=0).sum()) for k in range(d.times.size)]
    rows = list(csv.DictReader((out / "stage_table.csv").read_text().splitlines()))
    assert len(rows) == len(a.stages)
    for row, s in zip(rows, a.stages):
        assert float(row["discharge_lps"]) == pytest.approx(scene.hydrograph.discharge_lps_at(s.start_time), abs=1e-3)
        k = d.index_at(s.start_time)
        assert removed[k, s.stones].any() and not removed[k - 1, s.stones].all()
    assert np.allclose(np.loadtxt(out / "crest_lowering.csv", delimiter=",", skiprows=1)[:, 3], a.crest_lowering,
                       atol=1e-6)
