"""benchmarks/fine_grid_nut.py: the largest eddy viscosity over the water by hand, and a tiny run whose
table holds what it says."""
from types import SimpleNamespace

import numpy as np
import pytest
from script_loader import load_script

fine_grid_nut = load_script("benchmarks/fine_grid_nut.py")


def test_nut_max_is_over_the_water_alone():
    # 3 x 2 cells of 0.1 x 0.05 m from x0 = 1 m; the largest nu_t sits in an air cell (F < 0.5): left out
    grid = SimpleNamespace(nx=3, dx=0.1, x0=1.0, z_faces=[0.0, 0.05, 0.1])
    fluid = SimpleNamespace(grid=grid, cell_F=np.array([1.0, 1.0, 0.5, 0.2, 1.0, 0.0]),
                            cell_nut=np.array([1e-4, 2e-4, 3e-4, 9e-2, 5e-4, 8e-2]))
    top, where = fine_grid_nut.nut_max(SimpleNamespace(fluid=fluid))
    assert top == 5e-4
    assert where == pytest.approx((1.15, 0.075))  # cell (i = 1, k = 1)


def test_a_tiny_run(tmp_path):
    out = fine_grid_nut.main(["--small", "--factors", "1", "2", "--seconds", "0.04", "--every", "0.02",
                              "--candidate", "filtered", "numerics.turbulence_pore_strain=filtered",
                              "--out", str(tmp_path / "n.md")])
    text = out.read_text()
    rows = [line for line in text.splitlines() if line.startswith("| filtered |")]
    assert len(rows) == 2, text
    assert [r.split("|")[2].strip() for r in rows] == ["5", "2.5"]  # the draft grid and the paper's
    cells = rows[1].split("|")
    assert all(float(v) >= 0.0 for v in cells[3:5])  # nu_t max at 0.02 and 0.04 s
    assert int(cells[8]) > 0 and float(cells[10]) > 0.0  # steps, CPU ratio
    with pytest.raises(ValueError, match="must be > 0"):
        fine_grid_nut.main(["--small", "--seconds", "0"])
