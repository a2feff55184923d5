"""benchmarks/k_production_budget.py at a tiny size, and its strain against hand values."""
import numpy as np
from script_loader import load_script


def test_strain_of_a_porosity_jump_and_of_a_shear():
    kb = load_script("benchmarks/k_production_budget.py")
    dx, dz = 0.1, np.full(3, 0.1)
    zc = np.array([0.05, 0.15, 0.25])
    # the same superficial u = 1 in three rows of porosity 0.5, 1, 0.25: the middle cell's pore dU/dz is
    # (1/0.25 - 1/0.5) / 0.2 = 10, its superficial one 0
    u, w = np.ones((3, 2)), np.zeros((4, 1))
    n = np.array([[0.5], [1.0], [0.25]])
    s2, dudz = kb.strain2(u, w, n, dx, dz, zc)
    assert dudz[1, 0] == 10.0 and s2[1, 0] == 100.0
    s2_sup, _ = kb.strain2(u, w, np.ones_like(n), dx, dz, zc)
    assert s2_sup[1, 0] == 0.0
    # a simple shear u = 3 z: S^2 = 9
    s2, _ = kb.strain2(3.0 * zc[:, None] * np.ones((3, 2)), w, np.ones_like(n), dx, dz, zc)
    assert abs(s2[1, 0] - 9.0) < 1e-12


def test_the_table_at_a_tiny_size(tmp_path):
    kb = load_script("benchmarks/k_production_budget.py")
    text = kb.main(["--times", "0.05", "--out", str(tmp_path / "kb.md")]).read_text()
    assert "stones held, seed 0;" in text and text.count("| 0.05 | ") == 6  # the row and five sources
