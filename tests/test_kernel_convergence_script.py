"""studies/kernel_convergence.py, the source of docs/coupler.md's convergence of the kernel mapping with the
grid: its grids and its fixed-bed columns by hand, and the script at a tiny size."""
import json
from types import SimpleNamespace

import numpy as np
import pytest
from script_loader import load_script


@pytest.fixture(scope="module")
def conv():
    return load_script("studies/kernel_convergence.py")


def test_the_grids_by_hand(conv):
    assert conv.grid_settings(1) == ["grid.dx=0.025", "grid.dz=0.01", "grid.dz_bed=0.005", "grid.bed_layer_height=0.005"]
    assert conv.grid_settings(4) == ["grid.dx=0.00625", "grid.dz=0.0025", "grid.dz_bed=0.00125",
                                     "grid.bed_layer_height=0.00125"]


def test_a_column_by_hand(conv):
    # two columns of rows 1, 2 and 2 cm: the second column full in its first row, half in the second, a
    # quarter of its third row's pores (porosity 0.5 there) wet
    grid = SimpleNamespace(x0=0.0, dx=0.1, z_faces=[0.0, 0.01, 0.03, 0.05])
    fluid = SimpleNamespace(grid=grid, cell_F=np.array([[0.0, 1.0], [0.0, 0.5], [0.0, 0.25]]),
                            cell_porosity=np.array([[1.0, 1.0], [1.0, 1.0], [1.0, 0.5]]),
                            cell_p=np.array([[7.0, 123.5], [0.0, 0.0], [0.0, 0.0]]))
    depth, p = conv.column_state(SimpleNamespace(fluid=fluid), 0.15)
    assert depth == pytest.approx(0.01 + 0.01 + 0.25 * 0.5 * 0.02, abs=1e-15)
    assert p == 123.5
    assert conv.column_state(SimpleNamespace(fluid=fluid), 0.05) == (0.0, 7.0)


def test_the_table_by_hand(conv):
    # one packing, the kernel on three grids; the finest grid run to the first time only
    rec = lambda r, loads: {"key": conv.key_of(0, "kernel", 1.0, r), "b": 0.048,
                            "rows": [{"t": t, "load": v} for t, v in zip((20.0, 30.0), loads)]}
    done = {conv.key_of(0, "kernel", 1.0, r): rec(r, v) for r, v in ((1, (8.0, 10.0)), (2, (8.4, 10.5)), (4, (8.4,)))}
    args = SimpleNamespace(seeds=[0], mappings=["cell", "kernel"], bandwidths=[1.0], grids=[4.0, 1.0, 2.0],
                           times=[20.0, 30.0])
    rows = conv.table_rows(args, done, "load", ".3f")
    assert rows == ["| 0 | 20 | kernel, 1 | 8.000 | 8.400 | 8.400 | +5.0 % | +0.0 % |",
                    "| 0 | 30 | kernel, 1 | 10.000 | 10.500 | - | +5.0 % | - |"]
    # the head over the crest: the approach depth less the weir's height, in mm
    args.weir_height, args.times = 0.25, [20.0]
    for r, h in ((1, 0.29), (2, 0.28), (4, 0.2795)):
        done[conv.key_of(0, "kernel", 1.0, r)]["rows"][0]["h_up"] = h
    assert conv.table_rows(args, done, "head", ".1f", 1e3) == ["| 0 | 20 | kernel, 1 | 40.0 | 30.0 | 29.5 | -25.0 % | -1.7 % |"]


def test_the_script_at_a_tiny_size(conv, tmp_path):
    out = conv.main(["--seeds", "0", "--times", "0.1", "0.2", "--grids", "0.5", "1", "--mappings", "cell", "kernel",
                     "--bandwidths", "1", "1.5", "--cache", str(tmp_path / "runs.jsonl"), "--out", str(tmp_path / "k.md")])
    text = out.read_text()
    assert "# The kernel mapping's convergence with the grid, held stones" in text
    for label in ("cell, -", "kernel, 1", "kernel, 1.5"):
        assert f"| 0 | 0.2 | {label} |" in text
    assert "## Fixed bed: the approach depth's head over the crest, h_up - H (H: the weir's height)" in text
    # the widths: 1.5 times the unset one, which is the packing's mean diameter (4.8 cm +- 10 %)
    runs = {rec["key"]: rec for rec in map(json.loads, (tmp_path / "runs.jsonl").read_text().splitlines())}
    assert len(runs) == 6
    b1 = runs["0|kernel|1|1"]["b"]
    assert 0.9 * 0.048 < b1 < 1.1 * 0.048
    assert runs["0|kernel|1.5|0.5"]["b"] == pytest.approx(1.5 * b1, rel=1e-12)
    assert runs["0|cell|1|1"]["b"] == 0.0
    # a second call runs nothing: every configuration is in the cache
    conv.main(["--seeds", "0", "--times", "0.1", "0.2", "--grids", "0.5", "1", "--mappings", "cell", "kernel",
               "--bandwidths", "1", "1.5", "--cache", str(tmp_path / "runs.jsonl"), "--out", str(tmp_path / "k.md")])
    assert len((tmp_path / "runs.jsonl").read_text().splitlines()) == 6
