"""3D sphere stones across the flume from Python (sphere_model.h): the out-of-plane state as zero-copy views, a
settling that stays between the side walls, checkpoint and restart bit for bit, a coupled run that keeps the
water, and the refusals (a flume without width, a packing porosity inside 3D stones; scenes of spheres:
test_sphere_scenes.py)."""

import numpy as np
import pytest

import vofdem
from vofdem import _core
from vofdem.flow import tank_params
from dem_util import restarts_bit_for_bit


def heap(n=12, width=0.1, seed=0, submerged=False):
    """n spheres of 4.8 cm dropped in a 0.25 m long flume of the given width [m], the model set."""
    p = vofdem.DEMParams()
    p.submerged = submerged
    p.add_flume(0.0, 0.25, 0.0, 0.3)
    p.width = width
    p.stiffness_normal = 1e5
    p.restitution = 0.3
    g = np.random.default_rng(seed)
    pos = np.array([[0.03 + 0.05 * (k % 4) + 0.004 * g.random(), 0.03 + 0.05 * (k // 4)] for k in range(n)])
    s = vofdem.DEMSystem(p, pos=pos, density=[2650.0], radius=np.full(n, 0.024))
    s.set_model("sphere")
    s.stone_y[:] = 0.025 + (width - 0.05) * g.random(n)
    return s


def test_the_out_of_plane_state_is_seen_in_place():
    s = heap()
    assert s.shape == "sphere"
    assert s.stone_y.shape == (12,) and s.stone_quat.shape == (12, 4) and s.stone_omega_3d.shape == (12, 3)
    np.testing.assert_array_equal(s.stone_quat[:, 0], 1.0)  # unturned
    y = s.stone_y
    y[0] = 0.05
    s.stone_vel_y[0] = 0.1
    s.advance(1e-3)
    assert y[0] > 0.05  # the view is the C++ array: it moved with the stone
    # the plane's models have none
    assert vofdem.DEMSystem(vofdem.DEMParams(), 2).stone_y.shape == (0,)


def test_a_heap_settles_between_the_side_walls_and_restarts_bit_for_bit():
    s, _, checkpoint = restarts_bit_for_bit(heap, 0.2, 0.2)
    assert "stone_quat" in checkpoint and "sphere_wall_spring" in checkpoint
    # every stone stays between the walls, on or above the bed, and some turned about x or z
    radius = np.asarray(s.stone_radius)
    assert np.all(s.stone_y >= radius * 0.95) and np.all(s.stone_y <= 0.1 - radius * 0.95)
    assert np.all(s.stone_pos[:, 1] >= radius * 0.95)
    assert np.abs(s.stone_quat[:, [1, 3]]).max() > 1e-3
    assert s.wall_contact_count > 0


def test_a_heap_restarts_bit_for_bit_in_a_system_of_no_stones():
    """As a resumed run's stones (builder.checkpoint_stones): the checkpoint makes the spheres and their springs."""
    s, r, _ = restarts_bit_for_bit(heap, 0.2, 0.2, empty=True)
    assert r.shape == "sphere" and r.n == s.n and s.wall_contact_count > 0


def test_spheres_under_the_flow_keep_the_water():
    stones = heap(n=4, submerged=True)
    grid = vofdem.Grid2D.uniform(25, 30, 0.25, 0.3)
    fluid = vofdem.VOFGrid(grid, tank_params())
    fluid.fill_water_below(0.2)  # below the open top, which lets water out when it reaches it
    fluid.set_hydrostatic_pressure()
    cp = _core.CouplerParams()
    cp.n_exp = 0.0
    sim = _core.Coupler(fluid, stones, cp)
    sim.update_porosity(True)
    v0 = sim.water_volume()
    volume = sum(stones.volume(i) for i in range(stones.n))
    solid = float(np.sum(1.0 - np.asarray(fluid.cell_porosity))) * 0.01 * 0.01 * 0.1
    assert solid == pytest.approx(volume, rel=1e-9)  # the true solid fraction: their volume over the width
    sim.advance(0.2)
    assert sim.water_volume() == pytest.approx(v0, rel=1e-12)
    assert np.all(np.abs(sim.stone_force_pressure) < 10.0) and np.isfinite(np.asarray(stones.stone_pos)).all()


def test_what_spheres_cannot_do_yet_is_refused_with_the_key_named():
    p = vofdem.DEMParams()
    s = vofdem.DEMSystem(p, pos=np.array([[0.1, 0.1]]), density=[2650.0], radius=np.array([0.024]))
    with pytest.raises(ValueError, match="width"):
        s.set_model("sphere")
    assert s.shape == "disc"
    # coupled to the flow, their footprint is their volume: eq. (11)'s packing porosity must be 0
    stones = heap(n=2)
    grid = vofdem.Grid2D.uniform(10, 20, 0.25, 0.3)
    fluid = vofdem.VOFGrid(grid, tank_params())
    sim = _core.Coupler(fluid, stones, _core.CouplerParams())
    with pytest.raises(ValueError, match=r"n_exp = 0.41 is outside the allowed range \[0, 0\] with 3D stones"):
        sim.advance(0.01)
