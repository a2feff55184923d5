"""Scenes: the paper's defaults, TOML round trip, and validation errors that name the problem."""
import math
from pathlib import Path

import numpy as np
import pytest

from vofdem.scene import Scene, Stones, Weir, describe_parameters, load_scene

ROOT = Path(__file__).resolve().parents[1]


def test_maeno2008_defaults_are_the_papers_numbers():
    s = Scene.maeno2008()
    assert s.stones.diameter == 0.048 and s.weir.downstream_slope_deg == 27.0
    assert (s.grid.dx, s.grid.dz, s.grid.dz_bed) == (0.025, 0.010, 0.005)
    assert (s.stones.friction_stone, s.stones.friction_wall, s.stones.n_exp) == (0.577, 0.176, 0.41)
    assert (s.stones.k1, s.stones.k2, s.stones.added_mass_coefficient) == (200.0, 2.8, 1.0)
    assert s.numerics.dem_dt == 1e-4
    # free overfall 1.5 m downstream of the weir's downstream toe
    assert s.flume.length - s.weir.x_toe_down == pytest.approx(1.5, abs=1e-6)
    # base of a 0.25 m weir with 0.20 m crest and 27 deg faces: 0.2 + 2 * 0.25 / tan(27 deg)
    assert s.weir.base_length == pytest.approx(0.2 + 0.5 / math.tan(math.radians(27)), rel=1e-12)


def test_paper_clock_matches_the_papers_stage_times():
    h = Scene.maeno2008().hydrograph
    # the paper's second stage: 17.1 l/s at 56.8 s after the ramp started; third 16 s later at ~19.2 l/s
    assert h.discharge_lps_at(h.ramp_start + 56.8) == pytest.approx(17.1, abs=0.01)
    assert h.discharge_lps_at(h.ramp_start + 72.8) == pytest.approx(19.1, abs=0.01)
    assert h.discharge_lps_at(0.0) == pytest.approx(10.0)
    assert h.discharge_lps_at(h.end_time + 50) == pytest.approx(25.0)
    t, q = h.table()
    assert np.allclose(np.interp([5.0, 80.0], t, q), h.discharge(np.array([5.0, 80.0])))


def test_callable_and_table_hydrographs():
    s = Scene.maeno2008()
    s.hydrograph.function = lambda t: 0.01 + 1e-4 * t
    t, q = s.hydrograph.table()
    assert q[0] == pytest.approx(0.01) and q[-1] == pytest.approx(0.01 + 1e-4 * t[-1])
    # a callable is written to TOML as its sampled table
    back = Scene.from_toml(s.to_toml())
    assert back.hydrograph.kind == "table"
    assert back.hydrograph.discharge_lps_at(70.0) == pytest.approx(17.0, rel=1e-9)
    tab = Scene.from_toml('[hydrograph]\nkind = "table"\ntimes = [0, 10]\ndischarge_lps = ["10 l/s", "0.02 m3/s"]')
    assert tab.hydrograph.discharge_lps_at(5.0) == pytest.approx(15.0)
    assert tab.duration == 10.0


def test_toml_file_equals_python_scene_and_round_trips():
    assert load_scene(ROOT / "scenes" / "maeno2008.toml") == Scene.maeno2008()
    # the consistent variant differs from the paper's scene in its name and the two coupling options only
    c = load_scene(ROOT / "scenes" / "maeno2008_consistent.toml")
    assert (c.stones.drag_model, c.stones.porosity_mapping) == ("bed", "bulk")
    c.name, c.stones.drag_model, c.stones.porosity_mapping = "maeno2008", "sphere", "paper"
    assert c == Scene.maeno2008()
    s = Scene.maeno2008().quick().replace(seed=7)
    assert Scene.from_toml(s.to_toml()) == s


def test_quick_is_coarser_and_shorter():
    s, q = Scene.maeno2008(), Scene.maeno2008().quick()
    assert q.duration < s.duration / 3 and q.grid.dx > s.grid.dx and q.flume.length < s.flume.length
    assert q.weir.x_toe_down < q.flume.length


def test_units_in_strings_are_converted():
    s = Scene.from_toml('[stones]\ndiameter = "4.8 cm"\n[weir]\nheight = "250 mm"\n'
                        'downstream_slope_deg = "0.5 rad"\n[hydrograph]\ndischarge_end_lps = "0.03 m3/s"')
    assert s.stones.diameter == pytest.approx(0.048)
    assert s.weir.height == pytest.approx(0.25)
    assert s.weir.downstream_slope_deg == pytest.approx(math.degrees(0.5))
    assert s.hydrograph.discharge_end_lps == pytest.approx(30.0)


@pytest.mark.parametrize("text, message", [
    ("[stones]\ndiamter = 0.05", r"unknown key 'stones.diamter' in \[stones\]; did you mean 'diameter'\?"),
    ("[weirs]\nheight = 0.2", r"unknown key 'weirs' in top level; did you mean 'weir'\?"),
    ('[stones]\ndiameter = "5 l/s"', r"stones.diameter = '5 l/s': 'l/s' is a unit of discharge; diameter is a length"),
    ("[stones]\ndiameter = 48", r"stones.diameter = 48 is outside the allowed range \[0.001, 0.5\] m \(lengths are in metres"),
    ("[hydrograph]\ndischarge_start_lps = 0.01", r"discharge_start_lps = 0.01 is outside the allowed range \[0.1, 1000.0\] l/s \(looks like m3/s"),
    ("[weir]\ndownstream_slope_deg = 0.47", r"downstream_slope_deg = 0.47 .*looks like radians"),
    ("[stones]\nn_exp = 1.2", r"stones.n_exp = 1.2 is outside the allowed range \(0.0, 1.0\)"),
    ("[stones]\ndensity = 900", r"stones.density = 900 is outside the allowed range \(1000.0, 20000.0\] kg/m3"),
    ('[numerics]\nporosity_method = "fast"', r"numerics.porosity_method = 'fast' is not one of 'exact', 'lookup'"),
    ("[effects]\ndrag = 1", r"effects.drag = 1 must be true or false"),
    ("[numerics]\nlookup_m = 1", r"numerics.lookup_m = 1 is outside the allowed range \[2, 64\]"),
    ("[numerics]\nlookup_m = 8.5", r"numerics.lookup_m = 8.5 must be a whole number in \[2, 64\]"),
    ("[numerics]\nviscous_substeps = 0", r"numerics.viscous_substeps = 0 is outside the allowed range \[1, 64\]"),
    ("[numerics]\nviscous_substeps = 2.5", r"numerics.viscous_substeps = 2.5 must be a whole number in \[1, 64\]"),
    ("[weir]\ntoe_x = 3.0", r"the weir does not fit the flume: its downstream toe is at x = 4.181 m"),
    ("[weir]\nheight = 0.5", r"the weir does not fit the flume: weir.height = 0.5 m must be below flume.height = 0.38 m"),
    ("[stones]\npositions = [[1.5, 0.1], [0.01, 0.1]]", r"stones.positions\[1\] = \[0.01, 0.1\] \(diameter 0.048 m\) lies outside the domain"),
    ("[stones]\npositions = [[1.5, 0.44]]", r"stones.positions\[0\] .* lies outside the domain"),
    ("[stones]\npositions = [[1.5, 0.1]]\ndiameters = [0.05, 0.05]", r"stones.diameters has 2 entries, stones.positions has 1"),
    ("[stones]\ndiameter_spread = 0.7", r"stones.diameter_spread = 0.7 is outside the allowed range \[0.0, 0.5\]"),
    ('[flume]\noutflow = "tailwater"', r"flume.tailwater_level is required"),
    ("[hydrograph]\nkind = 'table'\ntimes = [0, 0]\ndischarge_lps = [10, 20]", r"hydrograph.times must be strictly increasing"),
    ("seed = -1", r"seed = -1 must be an integer"),
    ("[flume\nwidth = 1", r"not valid TOML"),
    # keys the chosen kind ignores are still checked
    ('[hydrograph]\nkind = "ramp"\ntimes = "abc"', r"hydrograph.times = 'abc' must be a list of numbers"),
    ("[hydrograph]\ndischarge_lps = [10, nan]", r"hydrograph.discharge_lps\[1\] = nan is outside the allowed range"),
    ("[stones]\npositions = 5", r"stones.positions = 5 must be a list of pairs"),
    ("[stones]\ndiameters = 0.05", r"stones.diameters = 0.05 must be a list of numbers"),
    ("name = 3", r"name = 3 must be a non-empty string"),
    ("", r"the scene is empty"),
    ("# nothing but a comment\n", r"the scene is empty"),
])
def test_validation_errors_name_the_problem(text, message):
    with pytest.raises(ValueError, match=message):
        Scene.from_toml(text)


def test_python_api_validates_too():
    with pytest.raises(ValueError, match=r"weir.height = -0.1 is outside the allowed range \(0.0, 5.0\] m"):
        Scene(weir=Weir(height=-0.1))
    with pytest.raises(ValueError, match="stones.friction_stone"):
        Scene(stones=Stones(friction_stone=3.0))


def test_load_scene_names_the_file(tmp_path):
    p = tmp_path / "bad.toml"
    p.write_text("[stones]\nfriction = 0.5\n")
    with pytest.raises(ValueError, match=r"bad.toml: unknown key 'stones.friction' in \[stones\]; did you mean"):
        load_scene(p)
    with pytest.raises(ValueError, match="does not exist"):
        load_scene(tmp_path / "missing.toml")


def test_weir_geometry():
    w = Weir()
    assert w.surface(w.toe_x) == 0.0 and w.surface(w.x_toe_down) == pytest.approx(0.0, abs=1e-12)
    assert w.surface(0.5 * (w.x_crest_up + w.x_crest_down)) == 0.25
    assert w.surface(w.toe_x + 0.1) == pytest.approx(0.1 * math.tan(math.radians(27)))


def test_parameter_table_lists_every_section():
    table = describe_parameters()
    for name in ("flume.width", "weir.crest_length", "stones.n_exp", "hydrograph.discharge_start_lps", "grid.dz_bed",
                 "numerics.dem_dt", "effects.two_way", "output.snapshot_interval"):
        assert f"| {name} |" in table
