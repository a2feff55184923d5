"""benchmarks/stage_timer_clock.py at a tiny size: the readings it counts are the coupler's stages' two each."""
import re

import pytest
from script_loader import load_script


def test_the_coupler_readings_are_two_a_stage(tmp_path):
    script = load_script("benchmarks/stage_timer_clock.py")
    out = script.main(["--scene", "maeno2008", "--from", "0.05", "--to", "0.15", "--reads", "1000",
                       "--out", str(tmp_path / "c.md")])
    text = out.read_text()
    steps = int(re.search(r"\(stones not held\), (\d+) coupled steps", text).group(1))
    assert steps > 0
    coupler = float(re.search(r"^\| coupler \| ([\d.]+) \|", text, re.M).group(1))
    every = float(re.search(r"^\| every timer \| ([\d.]+) \|", text, re.M).group(1))
    # porosity, fluid_forces, dem, fluid, checks and stable_dt once a step, the snapshot every few steps
    assert 12.0 <= coupler < 14.0
    assert every > coupler
    assert re.search(r"the CPU clock adds \d+ ns a reading", text)
    with pytest.raises(ValueError, match="from"):
        script.main(["--from", "2", "--to", "1"])
    with pytest.raises(ValueError, match="reads"):
        script.main(["--reads", "0"])
