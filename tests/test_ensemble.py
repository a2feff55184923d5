"""Ensembles: seeds and parameter sweeps, members as Dask tasks on a LocalCluster of 2 worker
processes (the same outcomes as serial runs, bit for bit, with the real solver), resumption, failing
and killed members, the summary and the CLI (the test double where the solver is not needed)."""
import json
import re
import os

import numpy as np
import pandas as pd
import psutil
import pytest
from fake_sim import FakeSimulation, short_scene
from script_loader import load_script

from vofdem.cli import main
from vofdem.ensemble import parse_seeds, parse_vary, plan_members, run_ensemble
from vofdem.io import RunData

# distributed times the creation of its scratch directories and warns past 1 s; on a loaded machine
# that is the disk's speed, not this code's: the one warning of Dask's ignored here
pytestmark = pytest.mark.filterwarnings(
    "ignore:Creating scratch directories is taking a surprisingly long time:UserWarning")

QUIET = dict(progress=False, figures=False, animation=False, dashboard=False, log=lambda *a: None)

# per seed, the discharges [l/s] at which the double's five downstream stones go
THRESHOLDS = {0: [15.0, 15.2, 18.0, 18.1, 18.3], 1: [12.0, 12.2, 21.0, 21.1, 21.2], 2: [40.0] * 5,
              3: [13.0, 13.1, 16.0, 16.1, 16.2]}


def _build(scene):
    return FakeSimulation(scene, thresholds_lps=THRESHOLDS[scene.seed])


def _build_failing(scene):
    """Seed 1's solver fails at 7.5 s; seed 2 kills the worker process running it."""
    if scene.seed == 2:
        os._exit(3)
    return FakeSimulation(scene, fail_at=7.5 if scene.seed == 1 else None, thresholds_lps=THRESHOLDS[scene.seed])


def _children():
    """Processes started by this one, but for multiprocessing's resource tracker (it lives as long as
    the process that started it, by design)."""
    kids = []
    for p in psutil.Process().children(recursive=True):
        try:
            if "resource_tracker" not in " ".join(p.cmdline()):
                kids.append(p)
        except psutil.NoSuchProcess:
            pass
    return kids


@pytest.fixture
def no_process_left():
    before = {p.pid for p in _children()}
    yield
    left = [p for p in _children() if p.pid not in before]
    gone, alive = psutil.wait_procs(left, timeout=10)
    assert not alive, f"processes left behind: {[p.cmdline() for p in alive]}"


def test_parse_seeds():
    assert parse_seeds("0-4") == [0, 1, 2, 3, 4]
    assert parse_seeds("0-2, 7") == [0, 1, 2, 7]
    assert parse_seeds("5") == [5]
    for bad in ("a", "3-1", "1,1", "-2", ""):
        with pytest.raises(ValueError, match="seeds"):
            parse_seeds(bad)


def test_vary_is_parsed_and_validated_like_the_scene_before_anything_runs(tmp_path):
    assert parse_vary("stones.friction_stone=0.5, 0.577") == ("stones.friction_stone", [0.5, 0.577])
    assert parse_vary("stones.drag_model=sphere,bed") == ("stones.drag_model", ["sphere", "bed"])
    assert parse_vary("effects.drag=true,false") == ("effects.drag", [True, False])
    for bad, msg in (("stones.friction_stone", "is not KEY=V1"), ("seed=1,2", "--seeds"),
                     ("stones.k1=200,200", "twice")):
        with pytest.raises(ValueError, match=msg):
            parse_vary(bad)
    s = short_scene()
    members = plan_members(s, [0, 1], ["stones.friction_stone=0.5,0.65", "stones.diameter=4.6 cm,0.05"])
    assert len(members) == 8
    # values as the scene holds them (SI), names by parameter and seed
    assert members[0].params == (("stones.friction_stone", 0.5), ("stones.diameter", 0.046))
    assert members[0].name == "stones.friction_stone=0.5,stones.diameter=0.046/seed0"
    assert members[-1].name == "stones.friction_stone=0.65,stones.diameter=0.05/seed1"
    assert members[3].scene(s).stones.diameter == 0.05 and members[3].scene(s).seed == 1
    with pytest.raises(ValueError, match=r"vary: stones.friction_stone = 5 is outside the allowed range \[0.0, 2.0\]"):
        run_ensemble(s, [0], tmp_path / "e", vary=["stones.friction_stone=0.5,5"], workers=0, **QUIET)
    unknown = r"unknown key 'stones.friction_ston' in \[stones\]; did you mean 'friction_stone'"
    with pytest.raises(ValueError, match=unknown):
        plan_members(s, [0], ["stones.friction_ston=0.5"])
    with pytest.raises(ValueError, match="vary: the weir does not fit the flume"):
        plan_members(s, [0], ["weir.height=0.2,0.5"])
    # each value fits alone, not every combination: a weir of 0.3 m in a domain 0.28 m high
    with pytest.raises(ValueError, match=r"vary: the weir does not fit the flume: weir.height = 0.3 m must be below"):
        plan_members(s, [0], ["weir.height=0.2,0.3", "flume.height=0.45,0.28"])
    assert not (tmp_path / "e").exists()  # nothing ran, nothing was written


def test_serial_ensemble_summary_and_fragility(tmp_path):
    df = run_ensemble(short_scene(), [0, 1, 2, 3], tmp_path, build=_build, workers=0, n_boot=100, **QUIET)
    assert df["member"].tolist() == ["seed0", "seed1", "seed2", "seed3"] and (df["status"] == "completed").all()
    for seed in range(4):
        assert RunData(tmp_path / f"seed{seed}" / "run.h5").attrs["seed"] == seed
        assert json.loads((tmp_path / f"seed{seed}" / "outcome.json").read_text())["status"] == "completed"
    # snapshots every 1 s = every 0.5 l/s: a removal is seen at the first snapshot at or above its discharge
    assert df["stage1_lps"].tolist()[:2] == [15.0, 12.0]
    assert df["stage2_lps"].tolist()[:2] == [pytest.approx(18.0, abs=1e-12), 21.5]
    assert np.isnan(df.loc[2, "first_removal_lps"]) and df.loc[2, "removed"] == 0
    assert (df["last_discharge_lps"] == 25.0).all() and (df["first_discharge_lps"] == 10.5).all()
    assert df["stones_hash"].str.len().eq(16).all()
    # the coupled steps: each step calls the fluid stage once (the member's profile.md; the fake's stage)
    for seed in range(4):
        fluid = re.search(r"\| fake_fluid \| [\d.]+ \| [\d.]+ % \| (\d+) \|", (tmp_path / f"seed{seed}" / "profile.md").read_text())
        assert df.loc[seed, "steps"] == int(fluid.group(1)) > 0
        outcome = json.loads((tmp_path / f"seed{seed}" / "outcome.json").read_text())
        assert outcome["step_limits"] == {"fake_limit": int(fluid.group(1))}
    csv = pd.read_csv(tmp_path / "ensemble.csv")
    assert csv["member"].tolist() == df["member"].tolist()
    md = (tmp_path / "ensemble.md").read_text()
    assert "# Ensemble: 4 of 4 members finished (4 completed, 0 failed, 0 lost)" in md
    # stage 1 at 15, 12, 13 l/s and once never (censored at 25): Kaplan-Meier median 13
    assert "| stage 1 | 3 of 4 (0) | 13.00 |" in md and "| stage 3 | 0 of 4 (0) | not reached | no fit |" in md
    frag = pd.read_csv(tmp_path / "fragility.csv")
    assert frag["event"].tolist() == ["first_removal", "stage1", "stage2", "stage3"]
    assert frag.loc[1, "happened"] == 3 and frag.loc[1, "censored_at_lps"] == 25.0
    assert (tmp_path / "fragility.png").stat().st_size > 0
    # a member without its outcome file (interrupted) runs again, alone
    (tmp_path / "seed2" / "outcome.json").unlink()
    stamps = {s: os.stat(tmp_path / f"seed{s}" / "run.h5").st_mtime_ns for s in range(4)}
    again = run_ensemble(short_scene(), [0, 1, 2, 3], tmp_path, build=_build, workers=0, n_boot=100, **QUIET)
    changed = [s for s in range(4) if os.stat(tmp_path / f"seed{s}" / "run.h5").st_mtime_ns != stamps[s]]
    assert changed == [2] and (tmp_path / "seed2" / "outcome.json").exists()
    same = [c for c in df.columns if c not in ("wall_seconds", "cpu_seconds")]
    pd.testing.assert_frame_equal(again[same], df[same], check_exact=True)


@pytest.mark.usefixtures("no_process_left")
def test_an_existing_cluster_by_its_scheduler_address(tmp_path):
    from distributed import Client, LocalCluster

    with LocalCluster(n_workers=1, threads_per_worker=1, processes=True, dashboard_address=":0") as cluster:
        logs = []
        df = run_ensemble(short_scene(), [0, 3], tmp_path, build=_build, scheduler=cluster.scheduler_address,
                          n_boot=0, **{**QUIET, "log": logs.append})
        with Client(cluster) as client:  # the cluster is left running for its owner
            assert client.submit(sum, [1, 2]).result() == 3
    assert df["stage1_lps"].tolist() == [15.0, pytest.approx(13.0, abs=1e-12)]
    assert not any("no Dask dashboard" in m for m in logs)


def test_cli_sweep_and_analyse(tmp_path, capsys):
    code = main(["run", "maeno2008", "--quick", "--seeds", "0-1", "--vary", "stones.friction_stone=0.5,0.6",
                 "--end-time", "3", "--workers", "0", "--out", str(tmp_path), "--no-animation", "--no-figures",
                 "--no-progress"], build=_build)
    out = capsys.readouterr().out
    assert code == 0 and "**stones.friction_stone=0.5**: 2 completed members" in out
    for v in ("0.5", "0.6"):
        for seed in (0, 1):
            assert (tmp_path / f"stones.friction_stone={v}" / f"seed{seed}" / "run.h5").exists()
    assert main(["analyse", str(tmp_path)]) == 0
    assert "| first removal of any stone | 0 of 2 (0) |" in capsys.readouterr().out
    assert main(["run", "maeno2008", "--seeds", "2-1"]) == 2
    assert "seeds: '2-1'" in capsys.readouterr().err
    assert main(["run", "maeno2008", "--vary", "stones.friction_stone=9", "--out", str(tmp_path / "x")]) == 2
    assert "outside the allowed range" in capsys.readouterr().err and not (tmp_path / "x").exists()
    assert main(["run", "maeno2008", "--workers", "2"]) == 2
    assert "for ensembles" in capsys.readouterr().err


def _tiny_real_scene():
    """The short scene for 4 s (stones released at 2 s): a member costs about a second."""
    return short_scene().replace(end_time=4.0)


@pytest.mark.usefixtures("no_process_left")
def test_dask_members_equal_serial_runs_bit_for_bit_and_a_second_call_runs_nothing(tmp_path):
    scene, seeds = _tiny_real_scene(), [0, 1, 2]
    serial = run_ensemble(scene, seeds, tmp_path / "serial", workers=0, n_boot=50, **QUIET)
    logs = []
    dask = run_ensemble(scene, seeds, tmp_path / "dask", workers=2, n_boot=50,
                        **{**QUIET, "log": logs.append})
    assert (dask["status"] == "completed").all(), dask["error"].tolist()
    assert dask["removed"].sum() > 0  # something happens in these 4 s, so the comparison has teeth
    same = [c for c in dask.columns if c not in ("wall_seconds", "cpu_seconds")]
    pd.testing.assert_frame_equal(dask[same], serial[same], check_exact=True)
    # the final stone positions of every member agree to the last bit
    for seed in seeds:
        a = RunData(tmp_path / "dask" / f"seed{seed}" / "run.h5").pos
        b = RunData(tmp_path / "serial" / f"seed{seed}" / "run.h5").pos
        assert np.array_equal(a, b)
    # a second call finds every member finished: no cluster, no run, the same table
    stamps = {s: os.stat(tmp_path / "dask" / f"seed{s}" / "run.h5").st_mtime_ns for s in seeds}
    logs.clear()
    again = run_ensemble(scene, seeds, tmp_path / "dask", workers=2, n_boot=50, **{**QUIET, "log": logs.append})
    assert logs == [f"vofdem: ensemble of 3 members (3 already finished in {tmp_path / 'dask'})"]
    assert {s: os.stat(tmp_path / "dask" / f"seed{s}" / "run.h5").st_mtime_ns for s in seeds} == stamps
    pd.testing.assert_frame_equal(again, dask, check_exact=True)


@pytest.mark.usefixtures("no_process_left")
def test_a_failing_member_and_a_killed_worker_are_recorded_and_the_rest_finish(tmp_path):
    df = run_ensemble(short_scene(), [0, 1, 2, 3], tmp_path, build=_build_failing, workers=2, n_boot=50, **QUIET)
    status = dict(zip(df["seed"], df["status"]))
    assert status == {0: "completed", 1: "failed", 2: "lost", 3: "completed"}
    err = dict(zip(df["seed"], df["error"]))
    assert err[1].startswith("SolverError: solver failed at t = 7.5 s: fake stage 'pressure'")
    assert "KilledWorker" in err[2]
    assert df.loc[df["seed"] == 3, "stage1_lps"].item() == pytest.approx(13.0, abs=1e-12)
    # the failed member is finished (its outcome is on disk); the lost one is not, and runs again next time
    assert (tmp_path / "seed1" / "outcome.json").exists() and not (tmp_path / "seed2" / "outcome.json").exists()
    md = (tmp_path / "ensemble.md").read_text()
    assert "(2 completed, 1 failed, 1 lost)" in md and "| seed2 | lost: KilledWorker" in md
    assert "2 completed members (2 failed or lost members left out)" in md
    again = run_ensemble(short_scene(), [0, 1, 2, 3], tmp_path, build=_build, workers=0, n_boot=50, **QUIET)
    assert again["status"].tolist() == ["completed", "failed", "completed", "completed"]
    scene_file = tmp_path / "short.toml"
    scene_file.write_text(short_scene().to_toml())
    assert main(["run", str(scene_file), "--seeds", "0-3", "--workers", "0", "--retry-failed", "--out",
                 str(tmp_path), "--no-progress", "--no-figures", "--no-animation"], build=_build) == 0
    retried = pd.read_csv(tmp_path / "ensemble.csv")
    assert (retried["status"] == "completed").all()


class _Interrupted(FakeSimulation):
    """Interrupted (Ctrl-C) once past 10 s."""

    def advance(self, t_end):
        if t_end > 10.0:
            raise KeyboardInterrupt
        super().advance(t_end)


def test_an_interrupted_member_built_by_a_study_resumes_from_its_checkpoint(tmp_path):
    """A member built by a `build` (as the studies build theirs) continues from its checkpoint when the same
    ensemble is called again, and ends as a member never stopped."""
    settles = []  # whether each build was asked to settle the stones: not the resumed one (its checkpoint has)

    def build(scene):
        settles.append(scene.hydrograph.settle_in_still_water)
        return _build(scene)

    ref = run_ensemble(short_scene(), [0], tmp_path / "ref", build=build, workers=0, n_boot=0, **QUIET)
    with pytest.raises(KeyboardInterrupt):
        run_ensemble(short_scene(), [0], tmp_path / "cut", workers=0, n_boot=0, **QUIET,
                     build=lambda scene: _Interrupted(scene, thresholds_lps=THRESHOLDS[scene.seed]))
    assert RunData(tmp_path / "cut" / "seed0" / "run.h5").attrs["status"] == "interrupted"
    again = run_ensemble(short_scene(), [0], tmp_path / "cut", build=build, workers=0, n_boot=0, **QUIET)
    assert settles == [True, False]
    outcome = json.loads((tmp_path / "cut" / "seed0" / "outcome.json").read_text())
    assert outcome["resumed"] is True and "resumed" not in json.loads(
        (tmp_path / "ref" / "seed0" / "outcome.json").read_text())
    same = [c for c in ref.columns if c not in ("wall_seconds", "cpu_seconds")]
    pd.testing.assert_frame_equal(again[same], ref[same], check_exact=True)
    assert again["stage1_lps"].notna().all()  # the member got past the cut's 10 s to its stages


def test_a_directory_of_another_scene_is_refused(tmp_path):
    run_ensemble(short_scene(), [0], tmp_path, build=_build, workers=0, n_boot=0, **QUIET)
    other = short_scene()
    other.stones.friction_stone = 0.6
    with pytest.raises(ValueError, match="holds a run of another scene"):
        run_ensemble(other.validate(), [0], tmp_path, build=_build, workers=0, **QUIET)


def test_a_member_of_an_older_version_without_new_default_keys_is_the_same_scene(tmp_path):
    """A version that added scene keys with their defaults writes another scene.toml for the same scene:
    the finished member is recognised by its scene read with the present defaults, and not run again."""
    import hashlib
    import json

    first = run_ensemble(short_scene(), [0], tmp_path, build=_build, workers=0, n_boot=0, **QUIET)
    member = tmp_path / "seed0"
    text = "".join(line for line in (member / "scene.toml").read_text().splitlines(keepends=True)
                   if not line.startswith(("aspect_ratio", "polygon_radial_jitter")))
    (member / "scene.toml").write_text(text)
    outcome = json.loads((member / "outcome.json").read_text())
    outcome["scene_sha256"] = hashlib.sha256(text.encode()).hexdigest()
    (member / "outcome.json").write_text(json.dumps(outcome))
    calls = []
    again = run_ensemble(short_scene(), [0], tmp_path, build=lambda sc: calls.append(sc) or _build(sc), workers=0,
                         n_boot=0, **QUIET)
    assert calls == [] and again["stones_hash"].tolist() == first["stones_hash"].tolist()


def test_the_maeno_fragility_script_at_a_tiny_size(tmp_path):
    """studies/maeno2008_fragility.py, which makes docs/results.md's 30-seed figure, on 1 seed of the quick
    variant for 2 s."""
    mod = load_script("studies/maeno2008_fragility.py")
    md = mod.main(["--quick", "--seeds", "0", "--end-time", "2", "--workers", "0", "--out", str(tmp_path / "ens"),
                   "--results", str(tmp_path), "--figures", str(tmp_path)])
    text = md.read_text()
    assert md.name == "maeno2008_quick_fragility.md" and "over 1 packings (seeds 0)" in text
    assert "in this process, one member after the other" in text
    assert "| first removal of any stone | 0 of 1 (0) |" in text
    assert (tmp_path / "maeno2008_quick_fragility.png").stat().st_size > 0


def test_the_dashboard_link_is_printed_only_where_a_dashboard_is_served(monkeypatch):
    from types import SimpleNamespace

    import vofdem.cluster as cluster

    served = SimpleNamespace(scheduler_info=lambda: {"services": {"dashboard": 8787}},
                             dashboard_link="http://127.0.0.1:8787/status")
    bare = SimpleNamespace(scheduler_info=lambda: {"services": {}}, dashboard_link="http://127.0.0.1:8787/status")
    monkeypatch.setattr(cluster, "has_bokeh", lambda: True)
    assert cluster.dashboard_link(served, local=True) == "http://127.0.0.1:8787/status"
    assert cluster.dashboard_link(bare, local=True) is None
    # without bokeh a local scheduler serves only a page saying so; a remote one may have bokeh
    monkeypatch.setattr(cluster, "has_bokeh", lambda: False)
    assert cluster.dashboard_link(served, local=True) is None
    assert cluster.dashboard_link(served, local=False) == "http://127.0.0.1:8787/status"


def test_the_stone_models_script_at_a_tiny_size(tmp_path):
    """studies/stone_models_weir.py (each stone model and coupling over packings) on 1 seed of two
    quick scenes for 2 s, in this process."""
    mod = load_script("studies/stone_models_weir.py")
    md = mod.main(["--quick", "--seeds", "0", "--end-time", "2", "--workers", "0", "--scenes", "maeno2008",
                   "maeno2008_rolling_consistent", "--out", str(tmp_path / "ens"), "--results", str(tmp_path),
                   "--figures", str(tmp_path)])
    text = md.read_text()
    assert "| discs | paper's | 1 | 0 | none | 0 | none | 0 | 0 |" in text
    assert "| discs, mu_r = 0.5 | consistent | 1 | 0 | none |" in text
    assert "## `maeno2008_rolling_consistent`: discs, mu_r = 0.5, consistent coupling" in text
    assert (tmp_path / "stone_models_weir.png").stat().st_size > 0
