"""benchmarks/dem_step_3d.py: the knob keeps the stiffness, the stable step refuses the coarse settings, the
tables by hand from canned jobs, the refusals of its options (a job packs the Maeno weir of 3D spheres: 30
CPU-s and more, too long for the suite)."""
import json
import types

import pytest

from script_loader import load_script

ds = load_script("benchmarks/dem_step_3d.py")


def test_the_knob_changes_the_step_not_the_stiffness():
    # 2e-3 s per contact: 32 x 6.25e-5 s, 64 x 3.125e-5 s
    for n in (26.0, 64.0):
        for sc in ds.scenes(n):
            assert sc.numerics.dem_contact_steps == n
            assert sc.numerics.dem_contact_steps * sc.numerics.dem_dt == pytest.approx(2e-3, rel=1e-12)
    s26, s64 = ds.stable_step(ds.scenes(26.0)[1]), ds.stable_step(ds.scenes(64.0)[1])
    assert s26["kn"] == pytest.approx(s64["kn"], rel=1e-12)
    assert s26["stable_dt"] == pytest.approx(s64["stable_dt"], rel=1e-12)


def test_the_settings_table_says_which_steps_the_dem_refuses():
    rows = ds.settings_table([24.0, 26.0])
    # 8.33e-5 s against the stable step of about 7.9e-5 s (the rolling springs' mode, critical damping)
    assert rows[-2].startswith("| 24 | 8.333e-05 |") and rows[-2].endswith("| refuses (step above stable_dt()) |")
    assert rows[-1].startswith("| 26 | 7.692e-05 |") and rows[-1].endswith("| accepts |")


def test_a_refused_step_is_recorded_and_other_errors_are_not(monkeypatch):
    args = types.SimpleNamespace(per_seed=2, after=1.0)

    def unstable(steps, seed):
        raise ValueError("dt = 1 s exceeds the DEM contact's stable step: allowed range (0, 0.5]")

    monkeypatch.setattr(ds, "heap_job", unstable)
    assert ds.run_job("heap", 16.0, 0, args) == {"refused": "dt = 1 s exceeds the DEM contact's stable step: "
                                                            "allowed range (0, 0.5]"}

    def broken(steps, seed):
        raise ValueError("something else")

    monkeypatch.setattr(ds, "heap_job", broken)
    with pytest.raises(ValueError, match="something else"):
        ds.run_job("heap", 16.0, 0, args)


def test_the_pull_substeps_count_the_advances():
    setup = ds.cal.PullSetup()  # 0.3 m at 0.02 m/s in 1e-3 s updates: 15000 samples
    full = types.SimpleNamespace(travel=[0.0] * 15000)
    broke = types.SimpleNamespace(travel=[0.0] * 101)  # broke off at the 101st sample: 100 advances
    assert ds._pull_substeps(full, setup, 2.5e-4) == 15000 * 4
    assert ds._pull_substeps(broke, setup, 3e-4) == 100 * 4  # ceil(1e-3 / 3e-4)


def _member(seed, lost, cpu, after_cpu, substeps=1000, mobile=10):
    return dict(seed=seed, lost_release=lost, lost_end=lost + 1, cpu=cpu, cpu_after=after_cpu, after=10.0,
                substeps=substeps, mobile=mobile)


def test_the_member_table_by_hand():
    got = {24.0: [{"seed": 0, "refused": "x"}],
           32.0: [_member(0, 10, 50.0, 20.0), _member(1, 14, 60.0, 20.0)],
           64.0: [_member(0, 12, 100.0, 40.0, 2000), _member(1, 20, 100.0, 40.0, 2000)]}
    rows = ds.member_table(got, 64.0)
    assert rows[4] == "| 24 | refused | | | | | | | | |"
    # mean 12 against 16: -4; CPU 55 of 100; after the release 2.0 s per simulated s, x0.50; 1e9 x 20 / (10 x
    # 1000) = 2e6 ns, the same as the reference's 1e9 x 40 / (10 x 2000)
    assert rows[5] == ("| 32 | 2 (0, 1) | 10 / 14 | 12.0 | -4.0 | 11 / 15 | 55 (x0.55) | 2.00 (x0.50) | "
                       "2000000 (x1.00) | 100 |")
    assert rows[-1] == "The reference's spread: stones lost within 2 s 5.66 (sample standard deviation over 2)."
    # a setting run at fewer seeds is compared with the reference's same seeds
    rows = ds.member_table({32.0: [_member(1, 14, 60.0, 20.0)], 64.0: got[64.0]}, 64.0)
    assert "| 14 | 14.0 | -6.0 |" in rows[4]


def test_the_pull_and_heap_tables_by_hand():
    def weir(seed, v, h, cpu):
        return dict(seed=seed, cpu=cpu, cpu_pulls=cpu / 2, substeps=1000,
                    pulls=[dict(direction=d, peak=p) for d, p in zip(ds.DIRECTIONS, (v, 3.0, h))])

    rows = ds.pull_table({32.0: [weir(0, 2.0, 4.0, 50.0)], 64.0: [weir(0, 2.5, 5.0, 100.0)]}, 64.0)
    assert rows[4] == ("| 32 | 1 (0), 1 pulls | 2.00 (2.00) | 3.00 (3.00) | 4.00 (4.00) | -20 / +0 / -20 | 50 | "
                       "x0.50 | 25000.0 (x0.50) |")
    heaps = {32.0: [dict(seed=0, angle=30.0, settled=True, cpu=30.0), dict(seed=1, angle=29.0, settled=False,
                                                                           cpu=34.0)],
             64.0: [dict(seed=0, angle=30.5, settled=True, cpu=64.0), dict(seed=1, angle=29.5, settled=True,
                                                                           cpu=64.0)]}
    rows = ds.heap_table(heaps, 64.0)
    assert rows[4] == "| 32 | 2 (0, 1) | 30.0 / 29.0 | 29.5 | -0.5 | yes / no | 32 | x0.50 |"
    # a seed the DEM refused (its lighter stones' shorter stable step) is named; the others are compared
    heaps[32.0][0] = dict(seed=0, refused="x")
    rows = ds.heap_table(heaps, 64.0)
    assert rows[4] == "| 32 | 1 (1); seed 0 refused | 29.0 | 29.0 | -0.5 | no | 34 | x0.53 |"


def test_the_report_from_kept_jobs(tmp_path):
    out = tmp_path / "jobs"
    out.mkdir()
    for n, lost in ((32.0, 10), (64.0, 12)):
        for seed in (0, 1):
            rec = _member(seed, lost + seed, 50.0 * n / 32, 20.0 * n / 32)
            rec.pop("seed")
            ds.job_path(out, "member", n, seed).write_text(json.dumps(rec))
    res, fig = tmp_path / "r.md", tmp_path / "f.png"
    ds.main(["--steps", "32,64", "--parts", "member", "--no-run", "--out", str(out), "--results", str(res),
             "--figure", str(fig)])
    text = res.read_text()
    assert "| 32 | 2 (0, 1) | 10 / 11 | 10.5 | -2.0 |" in text and fig.exists()
    assert "/tmp" not in text and str(tmp_path) not in text


@pytest.mark.parametrize("argv, match", [(["--steps", "4"], "--steps"), (["--steps", ""], "--steps"),
                                         (["--seeds", "x"], "--seeds"), (["--parts", "heap,x"], "--parts"),
                                         (["--per-seed", "0"], "--per-seed"), (["--after", "0"], "--after")])
def test_refusals_name_the_option(tmp_path, argv, match):
    with pytest.raises(ValueError, match=match):
        ds.main(argv + ["--no-run", "--out", str(tmp_path), "--results", str(tmp_path / "r.md"),
                        "--figure", str(tmp_path / "f.png")])


def test_the_clumps_knob_keeps_their_stiffness_and_refuses_steps_above_their_stable_one(monkeypatch):
    monkeypatch.setattr(ds, "SHAPE", "clump")
    for sc in ds.scenes(32.0):
        assert sc.stones.shape == "clump" and sc.stones.rolling_friction == 0.0
        assert sc.numerics.dem_contact_steps * sc.numerics.dem_dt == pytest.approx(2e-3, rel=1e-12)
    assert ds.scenes(32.0)[0].flume.width == 0.3  # the pulled weirs' (clump_calibration.py's)
    # the mix's stable step at this stiffness: ~6.29e-5 s (clump_model.h), between 28 and 32 steps per contact
    rows = ds.settings_table([28.0, 32.0])
    assert rows[-2].startswith("| 28 | 7.143e-05 |") and rows[-2].endswith("| refuses (step above stable_dt()) |")
    assert rows[-1].startswith("| 32 | 6.25e-05 |") and rows[-1].endswith("| accepts |")

    def ran(steps, seed):
        raise AssertionError("a step above the clumps' stable step was run")

    monkeypatch.setattr(ds, "heap_job", ran)
    rec = ds.run_job("heap", 28.0, 0, types.SimpleNamespace(per_seed=2, after=1.0))
    assert rec["refused"].startswith("dt = 7.143e-05 s exceeds the clumps' stable step")


def test_the_clumps_have_no_release_part(tmp_path):
    with pytest.raises(ValueError, match="'release'.*sphere only"):
        ds.main(["--shape", "clump", "--parts", "release", "--no-run", "--out", str(tmp_path), "--results",
                 str(tmp_path / "r.md"), "--figure", str(tmp_path / "f.png")])
    assert ds.SHAPE == "clump"
    ds.main(["--steps", "32,64", "--parts", "member", "--no-run", "--out", str(tmp_path), "--results",
             str(tmp_path / "r.md"), "--figure", str(tmp_path / "f.png")])
    assert ds.SHAPE == "sphere"  # each call sets it
