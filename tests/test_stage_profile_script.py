"""benchmarks/stage_profile.py at a tiny size: its timers nest as the solver's stages do."""
import re

import pytest
from script_loader import load_script


def test_the_stages_nest(tmp_path):
    script = load_script("benchmarks/stage_profile.py")
    out = script.main(["--scene", "maeno2008", "--from", "0.05", "--to", "0.15", "--out", str(tmp_path / "p.md")])
    text = out.read_text()
    steps = int(re.search(r"\(stones not held\), (\d+) coupled steps", text).group(1))
    assert steps > 0
    rows = {(t, s): (float(ms), float(calls)) for t, s, ms, calls in
            re.findall(r"^\| ([\w-]+) \| ([\w -]+) \| ([\d.]+) \| ([\d.]+) \|", text, re.M)}
    for stage in ("porosity", "dem", "fluid", "stable_dt"):
        assert rows[("coupler", stage)][1] == 1.0  # once per coupled step
    part = lambda timer: sum(ms for (t, _), (ms, _) in rows.items() if t == timer)  # noqa: E731
    # a nested timer's stages add up to no more than the stage that holds them (4-digit rounding aside)
    assert 0.0 < part("flow") <= rows[("coupler", "fluid")][0] + 1e-3
    assert 0.0 < part("k-epsilon") <= rows[("flow", "turbulence")][0] + 1e-3
    assert 0.0 < part("stones") <= rows[("coupler", "dem")][0] + 1e-3
    assert rows[("stones", "contacts")][1] > 1.0  # the stones' substeps
    assert re.search(r"\| flow \| pressure \| [\d.]+ \| 1\.00 \| [\d.]+ per cell \|", text)
    with pytest.raises(ValueError, match="from"):
        script.main(["--from", "2", "--to", "1"])
    with pytest.raises(ValueError, match="one value"):
        script.main(["--set", "flume.height=0.4,0.45"])


def test_a_set_value_changes_the_scene(tmp_path):
    script = load_script("benchmarks/stage_profile.py")
    out = script.main(["--scene", "maeno2008", "--from", "0", "--to", "0.02", "--set", "flume.height=0.45",
                       "--out", str(tmp_path / "p.md")])
    text = out.read_text()
    assert text.startswith("# Where a step of maeno2008 goes (flume.height=0.45)")
    assert "147 x 45 cells" in text  # the default 0.38 m gives 147 x 38
