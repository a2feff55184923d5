"""The deterministic weir packing and the porosity demo built on it."""
import importlib.util
import math
import os

import numpy as np
import pytest

from vofdem.packing import trapezoid_weir_discs

ROOT = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..")


def test_packing_is_deterministic_inside_the_trapezoid_and_free_of_overlap():
    x, z, d = trapezoid_weir_discs(seed=3)
    x2, z2, d2 = trapezoid_weir_discs(seed=3)
    assert np.array_equal(x, x2) and np.array_equal(z, z2) and np.array_equal(d, d2)
    assert not np.array_equal(d, trapezoid_weir_discs(seed=4)[2])
    r = d / 2
    assert x.size > 40
    assert np.all((d >= 0.048 * 0.9) & (d <= 0.048 * 1.1))
    # inside: under the crest, above the bed, inside both 27 degree slopes
    cot, inset = 1 / math.tan(math.radians(27)), 1 / math.sin(math.radians(27))
    base = 0.20 + 2 * 0.25 * cot
    assert np.all(z + r <= 0.25 + 1e-12) and np.all(z - r >= -1e-12)
    assert np.all(x - z * cot >= r * inset - 1e-12) and np.all(base - z * cot - x >= r * inset - 1e-12)
    dist = np.hypot(x[:, None] - x[None], z[:, None] - z[None]) + np.eye(x.size)
    assert np.all(dist >= (r[:, None] + r[None]) - 1e-12)


def test_packing_refuses_bad_geometry():
    with pytest.raises(ValueError):
        trapezoid_weir_discs(slope_deg=95.0)


def test_porosity_demo_writes_its_figure_and_arrays(tmp_path, capsys):
    spec = importlib.util.spec_from_file_location("porosity_demo", os.path.join(ROOT, "examples", "porosity_demo.py"))
    demo = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(demo)
    demo.main(["--out", str(tmp_path), "--m", "4"])
    assert (tmp_path / "porosity_weir.png").stat().st_size > 10_000
    data = np.load(tmp_path / "porosity_weir.npz")
    assert data["cell_porosity_exact"].shape == (data["z_faces"].size - 1, data["x_faces"].size - 1)
    for key in ("cell_porosity_exact", "cell_porosity_lookup"):
        assert data[key].min() >= 0.41 and data[key].max() == 1.0
    # the discs do not overlap and lie inside the grid: the mapped stone area is their total area
    total = np.sum(np.pi * data["disc_d"] ** 2 / 4)
    assert data["cell_solid_area_exact"].sum() == pytest.approx(total, rel=1e-12)
    assert "wrote" in capsys.readouterr().out
