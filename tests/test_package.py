"""The installed package: version, bindings present, errors mapped to Python exceptions."""
import re

import pytest

import vofdem


def test_version_is_the_cmake_project_version():
    assert re.fullmatch(r"\d+\.\d+\.\d+", vofdem.__version__)


def test_grid_views_and_errors():
    g = vofdem.Grid2D.graded(nx=40, length_x=1.0, height_z=0.3, dz=0.01, dz_bed=0.005, z_bed_top=0.02)
    assert (g.nx, g.nz) == (40, 32)
    assert g.z_faces[4] == pytest.approx(0.02)
    with pytest.raises(ValueError, match=r"dx = -0.1 is outside the allowed range \(0, inf\)"):
        vofdem.Grid2D(nx=2, dx=-0.1, z_faces=[0.0, 1.0])
