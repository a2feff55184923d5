"""A run killed with SIGKILL at a random snapshot: its file opens in plain h5py, `vofdem run --resume`
continues it from its checkpoint, and it ends bit for bit as a run that was never stopped; with disc
stones and with polygon stones (their shapes, orientations and per-point contact springs)."""
import json
import os
import signal
import subprocess
import sys
import time
from pathlib import Path

import h5py
import numpy as np
import pandas as pd
import pytest

import vofdem
from vofdem.checkpoint import load_checkpoint
from vofdem.io import completed_snapshots, snapshots_written

ENV = dict(os.environ, PYTHONPATH=str(Path(vofdem.__file__).resolve().parents[1]) + os.pathsep
           + os.environ.get("PYTHONPATH", ""))
ROOT = Path(__file__).resolve().parents[1]
# a scene's quick variant to 8 s: 17 snapshots, the stones held during the 5 s spin-up and released
# (a checkpoint after every snapshot: the kill then leaves one from the middle of the run)
OPTIONS = ["--quick", "--end-time", "8", "--no-figures", "--no-animation", "--no-progress", "--checkpoint-seconds", "0"]
RUN = ["run", "maeno2008", *OPTIONS]
SCENES = {"discs": "maeno2008", "polygons": str(ROOT / "scenes" / "maeno2008_polygons.toml")}
SNAPSHOTS = 17


def _vofdem(*args, **kw):
    return subprocess.Popen([sys.executable, "-m", "vofdem", *args], env=ENV, stdout=subprocess.DEVNULL,
                            stderr=subprocess.PIPE, text=True, **kw)


def kill_at_snapshot(out: Path, k: int, args=RUN, run_dir: str = ".") -> None:
    """Starts `vofdem *args` into `out` and SIGKILLs it once `k` snapshots of out/run_dir/run.h5 are
    complete."""
    p = _vofdem(*args, "--out", str(out))
    deadline = time.monotonic() + 300
    while snapshots_written(out / run_dir / "run.h5") < k and p.poll() is None and time.monotonic() < deadline:
        time.sleep(0.005)
    p.send_signal(signal.SIGKILL)
    p.wait(timeout=60)
    assert p.returncode == -signal.SIGKILL, f"the run ended before it was killed: {p.stderr.read()}"
    p.stderr.close()


def _datasets(path, prefix=""):
    out = {}
    with h5py.File(path, "r") as f:
        f.visititems(lambda n, o: out.__setitem__(n, o[()]) if isinstance(o, h5py.Dataset) and n.startswith(prefix)
                     else None)
    return out


@pytest.mark.slow
@pytest.mark.parametrize("stones", sorted(SCENES))
def test_killed_run_resumes_bit_for_bit(tmp_path, stones):
    run = ["run", SCENES[stones], *OPTIONS]
    ref = _vofdem(*run, "--out", str(tmp_path / "ref"))
    assert ref.wait(timeout=600) == 0, ref.stderr.read()
    ref.stderr.close()
    k = int(np.random.default_rng().integers(2, SNAPSHOTS - 2))
    out = tmp_path / "killed"
    kill_at_snapshot(out, k, run)
    # plain h5py, default mode: every completed snapshot equals the uninterrupted run's
    series = ["time", "fields/F", "fields/p", "stones/pos", "stones/force_pressure"]
    if stones == "polygons":
        series += ["stones/angle", "stones/poly_world"]
    with h5py.File(out / "run.h5", "r") as f, h5py.File(tmp_path / "ref" / "run.h5", "r") as g:
        assert f.attrs["status"] == "running"
        T = completed_snapshots(f["time"][()])
        assert k <= T < SNAPSHOTS, (k, T)
        for name in series:
            assert np.array_equal(f[name][:T], g[name][:T]), name
    r = _vofdem("run", "--resume", str(out))
    assert r.wait(timeout=600) == 0, r.stderr.read()
    r.stderr.close()
    # the same results bit for bit: every dataset of run.h5 but the cost, the stage tables, the final state
    a, b = _datasets(tmp_path / "ref" / "run.h5"), _datasets(out / "run.h5")
    assert a.keys() == b.keys()
    for name in a:
        if not name.startswith("profile/"):
            assert np.array_equal(a[name], b[name], equal_nan=True), name
    with h5py.File(out / "run.h5", "r") as f:
        assert f.attrs["status"] == "completed"
    for table in ("stage_table.md", "stage_table.csv", "crest_lowering.csv"):
        assert (out / table).read_text() == (tmp_path / "ref" / table).read_text(), table
    sa, sb = load_checkpoint(tmp_path / "ref" / "checkpoint.h5"), load_checkpoint(out / "checkpoint.h5")
    assert sa.state.keys() == sb.state.keys() and len(sa.state) > 30 and sa.snapshots == sb.snapshots == SNAPSHOTS
    # polygon runs carry the shapes and the contact points' springs (some of them loaded) in the state
    assert ("dem/poly_vertex" in sa.state) == (stones == "polygons")
    if stones == "polygons":
        assert "stones/poly_world" in a and np.count_nonzero(sa.state["dem/poly_contact_xi"]) > 0
    for name in sa.state:
        assert np.array_equal(sa.state[name], sb.state[name]), name
    # the stage profile adds up the killed part and the resumed part
    assert b["profile/calls"].sum() >= a["profile/calls"].sum()


@pytest.mark.slow
def test_a_killed_ensemble_member_resumes_from_its_checkpoint_bit_for_bit(tmp_path):
    """The same ensemble command run again continues a member whose process died from the member's
    checkpoint (written after its first snapshot, then every checkpoint interval), not from the start."""
    run = ["run", "maeno2008", "--quick", "--end-time", "8", "--seeds", "0", "--workers", "0", "--no-figures",
           "--no-animation", "--no-progress"]
    ref = _vofdem(*run, "--out", str(tmp_path / "ref"))
    assert ref.wait(timeout=600) == 0, ref.stderr.read()
    ref.stderr.close()
    out = tmp_path / "killed"
    kill_at_snapshot(out, SNAPSHOTS - 4, run, run_dir="seed0")
    killed = load_checkpoint(out / "seed0" / "checkpoint.h5")
    assert 1 <= killed.snapshots < SNAPSHOTS and killed.cpu_seconds > 0
    again = _vofdem(*run, "--out", str(out))
    assert again.wait(timeout=600) == 0, again.stderr.read()
    again.stderr.close()
    a, b = _datasets(tmp_path / "ref" / "seed0" / "run.h5"), _datasets(out / "seed0" / "run.h5")
    assert a.keys() == b.keys()
    for name in a:
        if not name.startswith("profile/"):
            assert np.array_equal(a[name], b[name], equal_nan=True), name
    outcome = json.loads((out / "seed0" / "outcome.json").read_text())
    assert outcome["resumed"] is True and outcome["status"] == "completed"
    # the process time counts the killed process's part: not less than the checkpoint's
    assert outcome["cpu_seconds"] > killed.cpu_seconds
    assert "resumed" not in json.loads((tmp_path / "ref" / "seed0" / "outcome.json").read_text())
    rows = [pd.read_csv(d / "ensemble.csv").drop(columns=["wall_seconds", "cpu_seconds"]) for d in (tmp_path / "ref", out)]
    pd.testing.assert_frame_equal(*rows, check_exact=True)


def test_resume_errors(tmp_path, capsys):
    from vofdem.cli import main

    assert main(["run", "--resume", str(tmp_path / "nothing")]) == 2
    assert "no scene.toml there, not a run directory" in capsys.readouterr().err
    assert main(["run", "maeno2008", "--resume", str(tmp_path)]) == 2
    assert "give no SCENE" in capsys.readouterr().err
    assert main(["run"]) == 2
    assert "give a SCENE" in capsys.readouterr().err
    assert main(["run", "--resume", str(tmp_path), "--seeds", "0-1"]) == 2
    assert "an ensemble (--seeds, --vary) resumes when the same command is run again" in capsys.readouterr().err
    from vofdem.scene import Scene

    (tmp_path / "scene.toml").write_text(Scene.maeno2008().quick().to_toml())
    assert main(["run", "--resume", str(tmp_path), "--no-progress"]) == 2
    assert "no checkpoint" in capsys.readouterr().err


def test_checkpoint_round_trip_is_exact(tmp_path):
    from vofdem.checkpoint import Checkpoint, save_checkpoint

    state = {"fluid/face_u": np.array([0.1, -2.5e-300, np.pi]), "coupler/time": np.array([7.25]),
             "dem/contact_i": np.zeros(0)}
    ck = Checkpoint(state, 3, [0.5, 1.0], True, "name = 'x'\n", {"fluid": (1.5, 7)}, 2.0)
    save_checkpoint(tmp_path / "c.h5", ck)
    back = load_checkpoint(tmp_path / "c.h5")
    assert back.state.keys() == state.keys() and all(np.array_equal(back.state[k], v) for k, v in state.items())
    assert (back.snapshots, back.targets, back.hold, back.scene_toml, back.profile, back.wall_seconds) == \
        (3, [0.5, 1.0], True, "name = 'x'\n", {"fluid": (1.5, 7)}, 2.0)
    assert not (tmp_path / "c.h5.tmp").exists()
    assert back.water_at_top_s is None
    ck.water_at_top_s = 14.5
    save_checkpoint(tmp_path / "c.h5", ck)
    assert load_checkpoint(tmp_path / "c.h5").water_at_top_s == 14.5


def _run_h5_equal(ref: Path, out: Path) -> None:
    a, b = _datasets(ref / "run.h5"), _datasets(out / "run.h5")
    assert a.keys() == b.keys()
    for name in a:
        if not name.startswith("profile/"):
            assert np.array_equal(a[name], b[name], equal_nan=True), name


@pytest.mark.slow
@pytest.mark.parametrize("name", ["maeno2008", str(ROOT / "scenes" / "maeno2008_consistent.toml")],
                         ids=["paper", "bulk"])
def test_a_resumed_run_takes_its_stones_from_the_checkpoint_without_packing_the_weir(tmp_path, monkeypatch, name):
    """A run stopped mid-way and resumed builds its stones from the checkpoint (builder.checkpoint_stones):
    the weir is not packed again (builder.build_stones is not called), and run.h5 ends as the uninterrupted
    run's; with the paper's porosity mapping and with the bulk one, whose porosity inside the discs comes
    from the packing (the checkpoint keeps it). A checkpoint written before it kept that porosity packs the
    weir again, to the same end."""
    import shutil

    from vofdem import builder, run
    from vofdem.cli import resolve_scene
    from vofdem.io import RunData

    scene = resolve_scene(name, quick=True, end_time=8.0)
    kw = dict(progress=False, figures=False, animation=False, checkpoint_seconds=0.0)
    packed = []
    pack = builder.build_stones
    monkeypatch.setattr(builder, "build_stones", lambda s: packed.append(s.seed) or pack(s))
    run.run_scene(scene, tmp_path / "ref", **kw)
    after_advance = run._Loop.after_advance

    def stop_after_the_ninth_snapshot(loop):  # as Ctrl-C does: the loop closes the run as 'interrupted'
        after_advance(loop)
        if loop.writer.count >= 9:
            run.request_stop()

    with monkeypatch.context() as m, pytest.raises(KeyboardInterrupt):
        m.setattr(run._Loop, "after_advance", stop_after_the_ninth_snapshot)
        run.run_scene(scene, tmp_path / "cut", **kw)
    assert packed == [scene.seed, scene.seed]
    old = tmp_path / "old"  # the same checkpoint as one written before the disc porosity was kept (below)
    shutil.copytree(tmp_path / "cut", old)
    run.run_scene(scene, tmp_path / "cut", resume=True, **kw)
    assert packed == [scene.seed, scene.seed]
    _run_h5_equal(tmp_path / "ref", tmp_path / "cut")
    ck = load_checkpoint(old / "checkpoint.h5")
    n_s = RunData(tmp_path / "ref" / "run.h5").attrs["disc_porosity"]
    assert ck.snapshots == 10 < SNAPSHOTS and ck.disc_porosity == n_s
    assert (n_s == scene.stones.n_exp) == (scene.stones.porosity_mapping == "paper")
    with h5py.File(old / "checkpoint.h5", "a") as f:
        del f.attrs["disc_porosity"]
    run.run_scene(scene, old, resume=True, **kw)
    assert packed == [scene.seed] * 3
    _run_h5_equal(tmp_path / "ref", old)
