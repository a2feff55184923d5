"""The design answer (vofdem run --until-failure): a slow rise stopped at the first destruction stage and
its critical discharge, total and per unit width, for one run and over an ensemble; the test double
(tests/fake_sim.py) for the loop, and one short run of the real solver."""
import pytest
from fake_sim import FakeSimulation, short_scene

from vofdem import cli
from vofdem.ensemble import run_ensemble
from vofdem.reports import critical_discharge
from vofdem.io import RunData
from vofdem.run import run_scene
from vofdem.scene import Scene

QUIET = dict(progress=False, figures=False, animation=False)


def test_the_until_failure_scene_rises_at_the_rate_from_the_start_to_the_maximum():
    s = Scene.maeno2008().until_failure()
    h = s.hydrograph
    assert s.name == "maeno2008_until_failure" and h.kind == "until_failure" and h.stops_at_first_stage
    assert (h.discharge_start_lps, h.discharge_end_lps, h.spin_up_duration) == (10.0, 25.0, 20.0)
    assert h.ramp_duration == pytest.approx(15.0 / 0.125) and s.duration == pytest.approx(140.0)
    assert h.discharge_lps_at(20.0 + 8.0) == pytest.approx(11.0)
    assert s.reference.model_stage_times == [] and s.reference.model_stage_lps == [17.1, 19.2]
    assert Scene.from_toml(s.to_toml()) == s
    s2 = Scene.maeno2008().with_value("hydrograph.until_failure_rate_lps_per_s", "90 l/s/min").until_failure()
    assert s2.duration == pytest.approx(30.0)
    q = Scene.maeno2008().quick().until_failure()  # quick: the rise four times faster, as its ramp
    assert q.hydrograph.until_failure_rate_lps_per_s == 0.5 and q.duration == pytest.approx(35.0)
    flat = Scene.maeno2008()
    flat.hydrograph.discharge_end_lps = 10.0
    with pytest.raises(ValueError, match="never rises above its start"):
        flat.until_failure()


def test_the_run_stops_at_the_first_stage_and_reports_the_critical_discharge(tmp_path):
    s = short_scene().until_failure()  # 10 l/s for 2 s, then +0.125 l/s per s up to 25 l/s (122 s)
    res = run_scene(s, tmp_path, sim=FakeSimulation(s), **QUIET)
    d = RunData(tmp_path / "run.h5")
    # the double's stones go at 15 l/s (t = 42 s) and 15.2 l/s (t = 44 s): a stage, confirmed at 44 s
    assert d.times[-1] == pytest.approx(44.0) and d.attrs["stopped"] == "at the first destruction stage"
    assert d.attrs["status"] == "completed"
    c = critical_discharge(res.analysis, s)
    assert c["status"] == "stage" and c["q_lps"] == pytest.approx(15.0) and c["stones"] == 2
    assert c["q_per_width_lps_m"] == pytest.approx(30.0) and c["q_per_width_m2s"] == pytest.approx(0.03)
    assert c["resolution_lps"] == pytest.approx(0.125)
    md = (tmp_path / "until_failure.md").read_text()
    assert "**Critical discharge: 15.00 l/s** in total, 30.00 l/s per m of width (0.03 m2/s; width 0.5 m)" in md


def test_no_stage_up_to_the_maximum_and_a_failure_at_the_release(tmp_path):
    s = short_scene().until_failure()
    res = run_scene(s, tmp_path / "a", sim=FakeSimulation(s, thresholds_lps=[40.0] * 5), **QUIET)
    assert res.simulated_seconds == pytest.approx(s.duration)
    c = critical_discharge(res.analysis, s)
    assert c["status"] == "none" and c["q_lps"] == pytest.approx(25.0)
    assert "**Critical discharge: above 25.00 l/s**" in (tmp_path / "a" / "until_failure.md").read_text()
    res = run_scene(s, tmp_path / "b", sim=FakeSimulation(s, thresholds_lps=[9.0, 9.0]), **QUIET)
    c = critical_discharge(res.analysis, s)  # loaded at 10 l/s when the held stones are released at 2 s
    assert c["status"] == "at release" and c["q_lps"] == pytest.approx(10.125)  # the first snapshot after it
    assert res.simulated_seconds == pytest.approx(3.0)
    assert "or below" in (tmp_path / "b" / "until_failure.md").read_text()


def _build(scene):
    return FakeSimulation(scene, thresholds_lps={0: [15.0, 15.2], 1: [12.0, 12.2], 2: [40.0, 40.0],
                                                 3: [18.0, 18.1]}[scene.seed])


def test_an_ensemble_reports_the_distribution_of_the_critical_discharge(tmp_path):
    s = short_scene().until_failure()
    df = run_ensemble(s, [0, 1, 2, 3], tmp_path, build=_build, workers=0, n_boot=100, dashboard=False,
                      log=lambda *a: None, **QUIET)
    assert df["stage1_lps"].tolist()[:2] == pytest.approx([15.0, 12.0]) and df["stage1_lps"].isna().tolist()[2]
    md = (tmp_path / "until_failure.md").read_text()
    assert "| all members | 4 | 3 (0) | 15.00 |" in md and "per unit width" in md
    # the median per unit width is the median over the width (0.5 m)
    row = next(line for line in md.splitlines() if line.startswith("| all members"))
    med, per = (float(c.split()[0]) for c in row.split("|")[5:7])
    assert per == pytest.approx(med / 0.5, abs=0.011)


def test_the_cli_prints_the_design_answer(tmp_path, capsys):
    code = cli.main(["run", "maeno2008", "--quick", "--until-failure", "--out", str(tmp_path), "--no-progress",
                     "--no-figures", "--no-animation"], build=lambda s: FakeSimulation(s))
    out = capsys.readouterr().out
    assert code == 0 and "# Until failure: maeno2008_quick_until_failure" in out and "**Critical discharge:" in out
    assert cli.main(["check", "maeno2008", "--until-failure"]) == 0
    assert 'kind = "until_failure"' in capsys.readouterr().out


def test_a_short_real_run_stops_at_its_first_stage_or_reaches_its_end(tmp_path):
    # the quick scene on the real solver, its rise cut short: either a stage stops it early and the report
    # gives that stage's discharge, or it reaches its end and says "above"
    s = Scene.maeno2008().quick().until_failure().replace(end_time=7.0)
    res = run_scene(s, tmp_path, **QUIET)
    a, c = res.analysis, critical_discharge(res.analysis, s)
    md = (tmp_path / "until_failure.md").read_text()
    if a.stages:
        assert c["q_lps"] == pytest.approx(a.stages[0].discharge_lps) and res.simulated_seconds <= 7.0
        assert a.stages[0].end_time == pytest.approx(a.times[-1])  # stopped at the snapshot that confirmed it
    else:
        assert res.simulated_seconds == pytest.approx(7.0) and c["status"] == "none" and "above" in md
