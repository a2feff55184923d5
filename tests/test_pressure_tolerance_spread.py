"""studies/pressure_tolerance_spread.py, the source of docs/accuracy_cost.md's pressure-tolerance row: its
permutation test by hand, and the script at a tiny size."""
import re

import pytest
from script_loader import load_script


@pytest.fixture(scope="module")
def spread():
    return load_script("studies/pressure_tolerance_spread.py")


def test_the_permutation_p_value_by_hand(spread):
    # identical samples: every relabelling differs at least as much (0 >= 0)
    assert spread.permutation_p([3, 3, 3], [3, 3, 3], n=200) == 1.0
    # {0, 0} against {1, 1}: of the 6 ways to split {0, 0, 1, 1} in two pairs, 2 differ by 1 in the means
    assert spread.permutation_p([0, 0], [1, 1], n=20000) == pytest.approx(2 / 6, abs=0.01)
    # 5 zeros against 5 tens: only the 2 of 252 splits that keep the groups apart differ by 10
    assert spread.permutation_p([0] * 5, [10] * 5, n=20000) == pytest.approx(2 / 252, abs=0.003)


def test_the_script_at_a_tiny_size(spread, tmp_path):
    md = spread.main(["--quick", "--seeds", "0", "--end-time", "2", "--spin-up", "0.5", "--workers", "0",
                      "--scenes", "maeno2008", "--out", str(tmp_path / "ens"),
                      "--results", str(tmp_path / "spread.md"), "--figure", str(tmp_path / "paired.png")])
    text = md.read_text()
    assert "## maeno2008_quick" in text
    assert (tmp_path / "paired.png").stat().st_size > 0 and f"Figure: `{tmp_path / 'paired.png'}`" in text
    assert "| first removal of any stone | not reached | not reached | - | 100% |" in text  # 2 s: no stone moved
    assert "**numerics.pressure_tolerance=1e-05**: 1 completed members" in text
    assert "**numerics.pressure_tolerance=0.0001**: 1 completed members" in text
    assert "| stones removed: mean, median [members' 16-84 %] | 0.0, 0.0 [0.0-0.0] | 0.0, 0.0 [0.0-0.0] | 1.00 |" in text
    assert re.search(r"\| steps per member: mean, median \[members' 16-84 %\] \| ([\d,]+), \1 \[\1-\1\] \| "
                     r"[\d,]+, [\d,]+ \[[\d,]+-[\d,]+\] \| 1.00 \|", text)
    assert "two packings (seeds i and i + 1) at 1e-05: - (one seed)" in text
    assert "The flow alone (stones held, seed 0, t = 0.5 s)" in text
    assert len(list((tmp_path / "ens" / "tol_spread_maeno2008_quick").glob("*/seed0/outcome.json"))) == 2


def test_another_numerics_key_at_a_tiny_size(spread, tmp_path):
    with pytest.raises(ValueError, match="--values"):
        spread.main(["--key", "numerics.wet_fraction_tolerance", "--seeds", "0", "--workers", "0"])
    md = spread.main(["--key", "numerics.wet_fraction_tolerance", "--values", "0", "1e-6", "--quick", "--seeds", "0",
                      "--end-time", "2", "--spin-up", "0.5", "--workers", "0", "--scenes", "maeno2008",
                      "--out", str(tmp_path / "ens"), "--results", str(tmp_path / "spread.md")])
    text = md.read_text()
    assert text.startswith("# `numerics.wet_fraction_tolerance` 0 against 1e-06: the packings' spread")
    assert "**numerics.wet_fraction_tolerance=1e-06**: 1 completed members" in text
    assert "| measure | wet_fraction_tolerance 0 | wet_fraction_tolerance 1e-06 | means' difference: p |" in text
    assert len(list((tmp_path / "ens" / "wet_fraction_tolerance_spread_maeno2008_quick").glob("*/seed0/outcome.json"))) == 2


def test_a_choice_key_at_a_tiny_size(spread, tmp_path):
    # choices are compared as they are (no %g), under the members' names the ensemble gives them
    md = spread.main(["--key", "numerics.viscous_scheme", "--values", "implicit_vertical_from_start",
                      "implicit_vertical", "--quick", "--seeds", "0", "--end-time", "1", "--spin-up", "0.5",
                      "--workers", "0", "--scenes", "maeno2008", "--out", str(tmp_path / "ens"),
                      "--results", str(tmp_path / "spread.md")])
    text = md.read_text()
    assert text.startswith("# `numerics.viscous_scheme` implicit_vertical_from_start against implicit_vertical")
    assert "**numerics.viscous_scheme=implicit_vertical**: 1 completed members" in text
    assert ("| measure | viscous_scheme implicit_vertical_from_start | viscous_scheme implicit_vertical | "
            "means' difference: p |") in text
    assert "| stones removed: mean, median [members' 16-84 %] | 0.0, 0.0 [0.0-0.0] | 0.0, 0.0 [0.0-0.0] | 1.00 |" in text


def test_a_switch_over_a_base_setting_at_a_tiny_size(spread, tmp_path):
    # a switch given as a scene file writes it, every member with the --base setting (read in the
    # members' scene files)
    md = spread.main(["--key", "numerics.turbulence_step_limit", "--values", "true", "false",
                      "--base", "numerics.viscous_scheme=implicit", "--quick", "--seeds", "0", "--end-time", "1",
                      "--spin-up", "0.5", "--workers", "0", "--scenes", "maeno2008", "--out", str(tmp_path / "ens"),
                      "--results", str(tmp_path / "spread.md")])
    text = md.read_text()
    assert text.startswith("# `numerics.turbulence_step_limit` true against false")
    assert "**numerics.turbulence_step_limit=false**: 1 completed members" in text
    assert "Every member with numerics.viscous_scheme=implicit." in text
    scenes = sorted((tmp_path / "ens").glob("*/*/seed0/scene.toml"))
    assert len(scenes) == 2
    for s in scenes:
        assert 'viscous_scheme = "implicit"' in s.read_text()
    assert "turbulence_step_limit = false" in scenes[0].read_text()


def test_the_flow_alone_across_two_grids(spread):
    # a key that changes the grid (the fidelity preset): the second value's depths are read at the first
    # value's columns, so the difference is over the paper grid's columns
    from vofdem.scene import load_scene
    from script_loader import ROOT
    scene = load_scene(ROOT / "scenes" / "maeno2008_rolling_consistent.toml")
    text = spread.flow_alone(scene, ["standard", "fine"], 0.1, "numerics.fidelity")
    most, mean = map(float, re.search(r"differs by at most ([\d.]+) mm over the flume between the values \(mean "
                                      r"([\d.]+) mm\)", text).groups())
    assert 0.0 < mean < most


def test_the_median_shifts_by_hand(spread):
    import pandas as pd

    def members(first, stage1):
        n = len(first)
        return pd.DataFrame({"status": ["completed"] * n, "seed": range(n), "first_removal_lps": first,
                             "stage1_lps": stage1, "stage2_lps": [float("nan")] * n,
                             "stage3_lps": [float("nan")] * n, "last_discharge_lps": [25.0] * n})

    nan = float("nan")
    # three seeds: first removals 10, 12, 14 against 11, 13, 15 (every resample shifts by +1); stage 1 at
    # 14, 16, never against never: not reached at the second value
    lines = spread.median_shifts(members([10.0, 12.0, 14.0], [14.0, 16.0, nan]),
                                 members([11.0, 13.0, 15.0], [nan, nan, nan]), "standard", "fine", n_boot=200)
    assert lines[0].startswith("| event | median at standard [l/s] | median at fine [l/s] |")
    assert lines[2] == "| first removal of any stone | 12.00 | 13.00 | +1.00 [+1.00 to +1.00] | 0% |"
    assert lines[3] == "| stage 1 | 16.00 | not reached | - | 100% |"
    assert lines[5] == "| stage 3 | not reached | not reached | - | 100% |"
    assert lines[-1].startswith("Over the 3 seeds both values completed")
