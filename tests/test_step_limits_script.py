"""benchmarks/maeno2008_step_limits.py at a tiny size: its windows add up to the run's steps."""
import re

import pytest
from script_loader import load_script


def test_the_windows_add_up(tmp_path):
    script = load_script("benchmarks/maeno2008_step_limits.py")
    out = script.main(["--scene", "maeno2008", "--seed", "1", "--set", "grid.merge_fraction=0", "--end-time", "0.2",
                       "--window", "0.1", "--out", str(tmp_path / "limits.md")])
    text = out.read_text()
    assert text.startswith("# Step limits of maeno2008 window by window (grid.merge_fraction=0)")
    assert "seed 1, stones not held through the spin-up" in text
    total = int(re.search(r"; (\d+) steps in all", text).group(1))
    rows = re.findall(r"^\| (0\.[12]) \| (\d+) \| ([^|]*) \|", text, re.M)
    assert [r[0] for r in rows] == ["0.1", "0.2"]
    assert sum(int(r[1]) for r in rows) == total > 0
    # each window's steps are those its limits bound
    for _, n, bound in rows:
        assert sum(int(v) for v in re.findall(r"\w+ (\d+)", bound)) == int(n)
    with pytest.raises(ValueError, match="one value"):
        script.main(["--set", "grid.merge_fraction=0,0.5"])
