"""benchmarks/step_flicker.py: the flicker measure and the response by hand, and a tiny run (the draft grid,
a few steps of each variant from one state) whose table holds what it says."""
import math

import pytest
from script_loader import load_script

flicker = load_script("benchmarks/step_flicker.py")


def test_a_two_step_cycle_by_hand():
    # limits 1, 1.2, 1, 1.2, ...: each change log 1.2 in size, each the opposite of the last
    rows = [dict(advective=1.2 if s % 2 else 1.0) for s in range(10)]
    med, corr = flicker.flicker(rows)
    assert med == pytest.approx(math.log(1.2))
    assert corr == pytest.approx(-1.0)
    # a steady fall: no flicker, the changes all alike
    med, corr = flicker.flicker([dict(advective=0.9 ** s) for s in range(10)])
    assert med == pytest.approx(-math.log(0.9))
    assert math.isnan(corr)  # no spread in the changes


def test_the_response_to_the_steps_length_by_hand():
    # the limit after a step inversely as its length: slope -1
    dts = [1.0, 2.0, 1.0, 2.0, 1.0]
    rows = [dict(dt=dt, advective=1.0) for dt in dts]
    for r, prev in zip(rows[1:], rows[:-1]):
        r["advective"] = 1.0 / prev["dt"]
    assert flicker.response(rows) == pytest.approx(-1.0)


def test_a_tiny_run(tmp_path):
    out = flicker.main(["--factor", "0.5", "--t0", "0.05", "--steps", "4", "--vary", "numerics.step_control=two_steps",
                        "--out", str(tmp_path / "f.md")])
    text = out.read_text()
    rows = [line for line in text.splitlines() if line.startswith("| as set") or line.startswith("| numerics.")]
    assert len(rows) == 4, text  # adaptive, fixed and alternating steps as set, adaptive of the other
    assert all(int(r.split("|")[2]) == 4 for r in rows), text
    with pytest.raises(ValueError, match="changes nothing"):
        flicker.main(["--factor", "0.5", "--t0", "0.05", "--steps", "4", "--vary", "numerics.step_control=this_step",
                      "--out", str(tmp_path / "g.md")])
