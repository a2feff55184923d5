"""The 3D settling benchmark against LAMMPS (benchmarks/dem_settle3d_peer.py) at its smallest size, without
LAMMPS: its case is the peer's lattice, and its two neighbour lists give the same bits with fewer pairs."""
import numpy as np

from script_loader import load_script

peer = load_script("benchmarks/dem_settle3d_peer.py")


def test_the_lattice_is_the_peers():
    xyz, diam = peer.lattice(250, 5, 12345)
    # 5 x 5 in x and y, then layers of pitch 0.055 m; diameters 4.8 cm +-10 %; jitter +-1 mm in x, y only
    assert xyz.shape == (250, 3) and np.all(np.abs(diam / 0.048 - 1.0) <= 0.1)
    np.testing.assert_allclose(xyz[:, 2], (np.arange(250) // 25 + 0.5) * 0.055)
    assert np.all(np.abs(xyz[:, 0] - (np.arange(250) % 5 + 0.5) * 0.055) <= 0.001)
    assert np.all(np.abs(xyz[:, 1] - (np.arange(250) // 5 % 5 + 0.5) * 0.055) <= 0.001)


def test_a_tiny_run_gives_the_same_bits_with_both_lists(tmp_path):
    out = tmp_path / "settle3d.md"
    r = peer.main(["--n", "100", "--steps", "1500", "--across", "5", "--no-lammps", "--out", str(out)])
    assert r["same_bits"]
    assert r["cells"]["contacts"] == r["plane"]["contacts"] > 50
    # 5 across: the plane's list holds several times the pairs of the 3D list
    assert r["plane"]["pairs"] > 2 * r["cells"]["pairs"]
    # the spheres fell: the mean centre is below the lattice's (0.11 m for 4 layers)
    assert r["cells"]["mean_z"] < 0.11
    text = out.read_text()
    assert "| vofdem | 3D cells |" in text and "the same bits" in text
