"""benchmarks/stone_model_cost.py: its table by hand, its hash of a state, and the script at a tiny size."""
import numpy as np
import pytest

from script_loader import load_script

smc = load_script("benchmarks/stone_model_cost.py")


def test_the_table_gives_medians_ratios_and_whether_the_bits_agree():
    def build(ns, ms, h):
        return {"dem/disc": {"ns_per_particle_step": ns, "hash": h}, "coupled/disc": {"ms_per_step": ms, "hash": "c"}}

    rounds = [[build(30.0, 2.0, "a"), build(33.0, 1.0, "a")], [build(40.0, 4.0, "a"), build(31.0, 3.0, "b")],
              [build(20.0, 3.0, "a"), build(32.0, 2.0, "a")]]
    rows = smc.table(["x", "y"], rounds).splitlines()
    # medians 30 / 32 ns and 3 / 2 ms; the DEM's bits differ in one round of build y
    assert rows[2] == "| dem/disc (ns per particle-step) | 30 | 32 | 1.067 | NO: a, b |"
    assert rows[3] == "| coupled/disc (ms CPU per coupled step) | 3 | 2 | 0.667 | yes |"


def test_the_hash_sees_one_bit():
    a = {"x": np.array([1.0, 2.0]), "y": np.array([3.0])}
    b = {"x": np.array([1.0, np.nextafter(2.0, 3.0)]), "y": np.array([3.0])}
    assert smc.state_hash(a) == smc.state_hash(dict(a)) != smc.state_hash(b)


def test_the_script_at_a_tiny_size(tmp_path):
    smc.main(["--rounds", "1", "--dem-time", "0.002", "--end-time", "0.01", "--label", "this build",
              "--out", str(tmp_path / "c.md")])
    text = (tmp_path / "c.md").read_text()
    assert "- build 0: this build" in text
    for case in ("dem/disc", "coupled/disc", "dem/polygon", "coupled/polygon"):
        assert f"| {case} (" in text and text.split(f"| {case} (")[1].splitlines()[0].endswith("| 1.000 | yes |")
    with pytest.raises(SystemExit, match="give one each"):
        smc.main(["--label", "a", "b", "--out", str(tmp_path / "x.md")])
