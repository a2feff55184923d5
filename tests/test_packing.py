"""The porosity demo on the weir packed by the C++ packer (pack_weir; its own tests: test_dem_weir.py)."""
import numpy as np
import pytest
from script_loader import load_script


def test_porosity_demo_writes_its_figure_and_arrays(tmp_path, capsys):
    demo = load_script("examples/porosity_demo.py")
    demo.main(["--out", str(tmp_path), "--m", "4"])
    assert (tmp_path / "porosity_weir.png").stat().st_size > 10_000
    data = np.load(tmp_path / "porosity_weir.npz")
    assert data["cell_porosity_exact"].shape == (data["z_faces"].size - 1, data["x_faces"].size - 1)
    for key in ("cell_porosity_exact", "cell_porosity_lookup"):
        assert data[key].min() >= 0.41 and data[key].max() == 1.0
    # the discs lie inside the grid but for the bed stones' contact overlap (micrometres below z = 0):
    # the mapped stone area is their total area
    total = np.sum(np.pi * data["disc_d"] ** 2 / 4)
    assert data["cell_solid_area_exact"].sum() == pytest.approx(total, rel=1e-6)
    assert "wrote" in capsys.readouterr().out
