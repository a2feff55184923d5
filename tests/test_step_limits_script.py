"""benchmarks/maeno2008_step_limits.py at a tiny size: its windows add up to the run's steps."""
import importlib.util
import re
from pathlib import Path

import pytest

PATH = Path(__file__).resolve().parents[1] / "benchmarks" / "maeno2008_step_limits.py"


@pytest.fixture(scope="module")
def script():
    spec = importlib.util.spec_from_file_location("maeno2008_step_limits", PATH)
    mod = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(mod)
    return mod


def test_the_windows_add_up(script, tmp_path):
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
