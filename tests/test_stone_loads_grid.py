"""studies/stone_loads_grid.py, the source of docs/accuracy_cost.md's loads on the held stones on two grids: its
per-stone comparison by hand, and the script at a tiny size."""

import numpy as np
import pytest
from script_loader import load_script

from vofdem.scene import load_scene


@pytest.fixture(scope="module")
def loads():
    return load_script("studies/stone_loads_grid.py")


@pytest.fixture(scope="module")
def maeno():
    return load_scene("scenes/maeno2008_rolling_consistent.toml")


def test_the_comparison_by_hand(loads, maeno):
    # three stones: one on each slope and one on the crest; the second value doubles the downstream one
    x = np.array([1.2, 1.6, 2.0])
    a = (20.0, 100, x, np.array([0.1, 0.2, 0.4]), (np.array([1.0, 2.0, 4.0]), np.array([0.5, 0.0, -1.0])))
    b = (20.0, 300, x.copy(), np.array([0.1, 0.1, 0.8]), (np.array([1.0, 1.0, 8.0]), np.array([0.5, 0.25, -2.0])))
    rows = loads.compare(maeno, a, b, ("standard", "fine"))
    assert rows[0] == "| 20 | 10.00 | upstream slope | 1 | +0.100 | +0.100 | 1.00 / 1.00 | 0 / 0 | 0.100 / 0.100 | +1.000 / +1.000 | +0.500 / +0.500 |"
    assert rows[1] == "| 20 | 10.00 | crest | 1 | +0.200 | +0.100 | 0.50 / 0.50 | 0 / 0 | 0.200 / 0.100 | +2.000 / +1.000 | +0.000 / +0.250 |"
    assert rows[2] == "| 20 | 10.00 | downstream slope | 1 | +0.400 | +0.800 | 2.00 / 2.00 | 1 / 1 | 0.400 / 0.800 | +4.000 / +8.000 | -1.000 / -2.000 |"
    assert rows[3].endswith("| standard 100, fine 300 | | |")
    moved = (20.0, 300, x + np.array([0.0, 0.0, 0.01]), b[3], b[4])
    with pytest.raises(ValueError, match="placed the stones differently"):
        loads.compare(maeno, a, moved, ("standard", "fine"))


def test_the_script_at_a_tiny_size(loads, tmp_path):
    out = loads.main(["--values", "standard", "draft", "--seeds", "0", "--times", "0.3", "--out",
                      str(tmp_path / "loads.md")])
    text = out.read_text()
    assert "# The water's loads on the held stones: `numerics.fidelity` standard against draft" in text
    for region in ("upstream slope", "crest", "downstream slope"):
        assert f"| 0.3 | 10.00 | {region} |" in text
