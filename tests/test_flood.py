"""Measured floods (hydrograph.kind = 'csv', vofdem.flood): the file's units, its validation with errors
naming the file, line and column, the hydrograph it makes, and a run that follows it and plots it."""
from pathlib import Path

import numpy as np
import pytest
from fake_sim import FakeSimulation

from vofdem.flood import read_hydrograph_csv
from vofdem.run import run_scene
from vofdem.scene import Scene, load_scene

GOOD = "# gauge 7, flood of 12 May\n\ntime_min,discharge_m3s\n0,0.010\n0.5,0.013\n1.5,0.020\n2,0.016\n"


def _write(tmp_path, text, name="flood.csv"):
    p = tmp_path / name
    p.write_text(text, encoding="utf-8")
    return p


def test_units_of_the_header_and_times_from_the_first_row(tmp_path):
    t, q = read_hydrograph_csv(_write(tmp_path, GOOD))
    assert t == [0.0, 30.0, 90.0, 120.0] and q == pytest.approx([10.0, 13.0, 20.0, 16.0], rel=1e-12)
    t, q = read_hydrograph_csv(_write(tmp_path, "time_h,discharge_lps\n1,5\n1.5,7.5\n"))
    assert t == [0.0, 1800.0] and q == [5.0, 7.5]
    t, q = read_hydrograph_csv(_write(tmp_path, " Time_S , Discharge_LPS \n10, 3\n12.5, 0\n"))
    assert t == [0.0, 2.5] and q == [3.0, 0.0]


@pytest.mark.parametrize("text, where, what", [
    ("", "", "the file is empty"),
    ("# nothing\n", "", "the file is empty"),
    ("time,discharge_lps\n0,1\n1,2\n", "line 1, column 1 (time)", "unknown time column"),
    ("time_s,discharge_cfs\n0,1\n1,2\n", "line 1, column 2 (discharge_cfs)", "unknown discharge column"),
    ("time_s;discharge_lps\n0;1\n", "line 1", "the header must name two columns"),
    ("time_s,discharge_lps\n0,1\n", "line 2", "1 row(s) of readings"),
    ("time_s,discharge_lps\n0,1\n5,2\n5,3\n", "line 4, column 1 (time_s)", "does not come after"),
    ("time_s,discharge_lps\n0,1\n5,2\n4,3\n", "line 4, column 1 (time_s)", "increase strictly"),
    ("time_s,discharge_lps\n0,1\n5,-2\n", "line 3, column 2 (discharge_lps)", "is negative"),
    ("time_s,discharge_lps\n0,1\n5,nan\n", "line 3, column 2 (discharge_lps)", "not a finite number"),
    ("time_s,discharge_lps\n0,1\ninf,2\n", "line 3, column 1 (time_s)", "not a finite number"),
    ("time_s,discharge_lps\n0,1\n5,two\n", "line 3, column 2 (discharge_lps)", "'two' is not a number"),
    ("time_s,discharge_lps\n0,1\n5,2,7\n", "line 3", "two values"),
])
def test_bad_files_are_refused_naming_file_line_and_column(tmp_path, text, where, what):
    p = _write(tmp_path, text)
    with pytest.raises(ValueError) as e:
        read_hydrograph_csv(p)
    msg = str(e.value)
    assert str(p) in msg and where in msg and what in msg and "\n" not in msg


def test_a_csv_scene_reads_its_file_relative_to_itself_and_stays_self_contained(tmp_path, monkeypatch):
    d = tmp_path / "weir"
    d.mkdir()
    _write(d, GOOD, "may.csv")
    (d / "s.toml").write_text('[hydrograph]\nkind = "csv"\nfile = "may.csv"\nspin_up_duration = 10\n')
    monkeypatch.chdir(tmp_path)  # not the scene's directory
    s = load_scene(d / "s.toml")
    h = s.hydrograph
    assert h.ramp_start == 10.0 and s.duration == 130.0
    assert h.discharge_lps_at(np.array([0.0, 10.0, 40.0, 70.0, 130.0, 200.0])) == pytest.approx(
        [10.0, 10.0, 13.0, 16.5, 16.0, 16.0])
    t, q = h.table()
    assert t.tolist() == [0.0, 10.0, 40.0, 100.0, 130.0] and q[-1] == pytest.approx(0.016)
    # the scene written by a run carries the flood: it loads without the file
    text = s.to_toml()
    (d / "may.csv").unlink()
    back = Scene.from_toml(text)
    assert back == s and back.hydrograph.source() == "measured flood may.csv"
    # scales (a Froude-scaled field flood) and the quick variant (four times faster)
    s2 = s.with_value("hydrograph.time_scale", 0.5).with_value("hydrograph.discharge_scale", 0.5)
    assert s2.duration == 70.0 and s2.hydrograph.discharge_lps_at(70.0) == pytest.approx(8.0)
    q4 = s.quick()
    assert q4.hydrograph.time_scale == 0.25 and q4.duration == pytest.approx(5.0 + 30.0)


def test_scene_errors_name_the_key_and_the_file(tmp_path):
    (tmp_path / "a.toml").write_text('[hydrograph]\nkind = "csv"\n')
    with pytest.raises(ValueError, match=r"hydrograph.file is required when hydrograph.kind = 'csv'"):
        load_scene(tmp_path / "a.toml")
    (tmp_path / "b.toml").write_text('[hydrograph]\nkind = "csv"\nfile = "missing.csv"\n')
    with pytest.raises(ValueError, match=r"hydrograph.file: cannot read the hydrograph CSV .*missing.csv"):
        load_scene(tmp_path / "b.toml")
    _write(tmp_path, "time_s,discharge_lps\n0,1\n5,-1\n", "bad.csv")
    (tmp_path / "c.toml").write_text('[hydrograph]\nkind = "csv"\nfile = "bad.csv"\n')
    with pytest.raises(ValueError, match=r"bad.csv, line 3, column 2 \(discharge_lps\): discharge -1 is negative"):
        load_scene(tmp_path / "c.toml")
    _write(tmp_path, "time_s,discharge_m3s\n0,1\n5,3\n", "river.csv")  # 3000 l/s: a river, not a flume
    (tmp_path / "d.toml").write_text('[hydrograph]\nkind = "csv"\nfile = "river.csv"\n')
    with pytest.raises(ValueError, match=r"hydrograph.discharge_scale = 1.0: the flood of river.csv peaks at 3000 l/s"):
        load_scene(tmp_path / "d.toml")


def test_a_run_follows_the_flood_and_plots_it_with_its_stages(tmp_path):
    from fake_sim import short_scene

    # a flood rising to 20 l/s and falling again: the double's stones go at 15-15.2 and 18-18.3 l/s
    _write(tmp_path, "time_s,discharge_lps\n0,10\n20,20\n30,12\n", "f.csv")
    s = short_scene()
    s.hydrograph.kind, s.hydrograph.file, s.hydrograph.base_dir = "csv", "f.csv", str(tmp_path)
    s.hydrograph.spin_up_duration = 2.0
    s.validate()
    res = run_scene(s, tmp_path / "out", sim=FakeSimulation(s), progress=False, figures=True, animation=False)
    a = res.analysis
    assert res.simulated_seconds == pytest.approx(32.0)
    assert [st.n_stones for st in a.stages] == [2, 3]
    assert a.stages[0].discharge_lps == pytest.approx(15.0) and a.stages[1].discharge_lps == pytest.approx(18.0)
    assert (tmp_path / "out" / "figures" / "hydrograph.png").stat().st_size > 0
    from vofdem.io import RunData
    from vofdem.plots import fig_hydrograph

    fig = fig_hydrograph(a, RunData(tmp_path / "out" / "run.h5"), s)
    texts = [t.get_text() for t in fig.findobj(lambda o: hasattr(o, "get_text"))]
    labels = fig.axes[0].get_legend_handles_labels()[1]
    assert any("measured flood f.csv" in t for t in texts)
    assert "stage 1: 15.00 l/s, 2 stones" in labels and "stage 2: 18.00 l/s, 3 stones" in labels
    assert Path(res.out_dir / "scene.toml").read_text().count('kind = "csv"') == 1
