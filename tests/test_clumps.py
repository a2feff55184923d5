"""Clump stones from Python (clump_model.h): library shapes set on a DEMSystem, a heap that settles between
the side walls and restarts bit for bit, library clumps coupled to a VOFGrid through a Coupler, and the
refusals (bad shapes, a packing porosity in the coupling, a scene)."""
from pathlib import Path

import numpy as np
import pytest

import vofdem
from vofdem import _core
from vofdem.flow import tank_params
from dem_util import restarts_bit_for_bit


def heap(n=12, width=0.06, seed=0):
    """n library clumps of d_eq = 3 cm dropped in a 0.16 m long flume of the given width [m]."""
    p = vofdem.DEMParams()
    p.add_flume(0.0, 0.16, 0.0, 0.3)
    p.width = width
    p.stiffness_normal = 1e5
    p.restitution = 0.3
    p.dt = 1e-5
    g = np.random.default_rng(seed)
    pos = np.array([[0.025 + 0.037 * (k % 4) + 0.003 * g.random(), 0.03 + 0.045 * (k // 4)] for k in range(n)])
    s = vofdem.DEMSystem(p, pos=pos, density=[2650.0], radius=np.full(n, 0.02))
    names = _core.quarried_stone_names()
    shapes = [_core.quarried_stone(names[k % len(names)], 0.03) for k in range(n)]
    offset = np.concatenate([[0], np.cumsum([len(c) for c in shapes])]).astype(int)
    s.set_clumps(np.vstack(shapes), offset.tolist())
    q = g.normal(size=(n, 4))
    s.stone_quat[:] = q / np.linalg.norm(q, axis=1)[:, None]
    s.stone_y[:] = 0.5 * width + 0.004 * (g.random(n) - 0.5)
    return s


def test_library_clumps_have_the_volume_of_their_equivalent_sphere():
    assert _core.quarried_stone_names() == ["pair_2", "triangle_3", "tetra_4", "box_8"]
    s = heap(n=4)
    assert s.shape == "clump"
    for i in range(4):
        # the library scales each union to pi d^3 / 6 (to its quadrature's accuracy, clump.h)
        assert s.nominal_diameter(i) == pytest.approx(0.03, rel=1e-5)
        assert s.volume(i) == pytest.approx(np.pi * 0.03**3 / 6.0, rel=3e-5)
        assert s.stone_radius[i] > 0.015  # the bounding radius, beyond the equivalent sphere's
    assert [len(_core.quarried_stone(n, 0.03)) for n in _core.quarried_stone_names()] == [2, 3, 4, 8]


def test_a_clump_heap_settles_between_the_side_walls_and_restarts_bit_for_bit():
    s, r, checkpoint = restarts_bit_for_bit(heap, 0.15, 0.1)
    assert "clump_sphere" in checkpoint and "clump_wall_spring" in checkpoint
    assert s.contact_count > 0 and s.wall_contact_count > 0
    # settled into the flume: the centres above the bed and between the side walls, the speeds small
    assert np.all(s.stone_pos[:, 1] > 0.0) and np.all(s.stone_pos[:, 1] < 0.2)
    assert np.all((s.stone_y > 0.0) & (s.stone_y < 0.06))
    e = s.energy()
    assert e.dissipated > 0.0 and e.total == r.energy().total


def test_a_clump_heap_restarts_bit_for_bit_in_a_system_of_no_stones():
    """As a resumed run's stones (builder.checkpoint_stones): the checkpoint makes the clumps, their shapes
    and springs."""
    s, r, _ = restarts_bit_for_bit(heap, 0.15, 0.1, empty=True)
    assert r.shape == "clump" and r.n == s.n and s.contact_count > 0


def test_library_clumps_coupled_to_the_flow_fall_and_keep_the_water():
    stones = heap(n=4)
    grid = vofdem.Grid2D.uniform(16, 30, 0.16, 0.3)
    fluid = vofdem.VOFGrid(grid, tank_params())
    fluid.fill_water_below(0.2)
    fluid.set_hydrostatic_pressure()
    cp = _core.CouplerParams()
    cp.n_exp = 0.0
    sim = _core.Coupler(fluid, stones, cp)
    sim.update_porosity(True)
    v0 = sim.water_volume()
    z0 = np.array(stones.stone_pos[:, 1])
    volume = sum(stones.volume(i) for i in range(stones.n))
    solid = float(np.sum(1.0 - np.asarray(fluid.cell_porosity))) * 0.01 * 0.01 * 0.06
    assert solid == pytest.approx(volume, rel=1e-12)  # each clump's union volume over the width
    sim.advance(0.1)
    assert sim.water_volume() == pytest.approx(v0, rel=1e-9)
    assert np.all(np.asarray(stones.stone_wet) == 1.0)  # under water: buoyed by their whole volume
    assert np.all(stones.stone_pos[:, 1] < z0) and np.isfinite(np.asarray(stones.stone_pos)).all()
    assert np.all(np.abs(sim.stone_force_drag[:, 1]) > 0.0)  # the flow drags on each as it falls


def test_what_clumps_cannot_do_yet_is_refused_with_the_key_named():
    s = heap(n=2)
    with pytest.raises(ValueError, match=r"allowed range \[1, 8\]"):
        s.set_clumps(np.full((9, 4), 0.01), [0, 9, 9])
    with pytest.raises(ValueError, match=r"radius in \(0, inf\)"):
        s.set_clumps(np.zeros((2, 4)), [0, 1, 2])
    with pytest.raises(ValueError, match="d_eq"):
        _core.quarried_stone("pair_2", -1.0)
    grid = vofdem.Grid2D.uniform(10, 20, 0.16, 0.3)
    fluid = vofdem.VOFGrid(grid, tank_params())
    sim = _core.Coupler(fluid, s, _core.CouplerParams())  # n_exp = 0.41: their footprint is their volume
    with pytest.raises(ValueError, match=r"n_exp = 0.41 is outside the allowed range \[0, 0\] with 3D stones "
                                         r"\(stones.shape = 'clump'\)"):
        sim.advance(0.01)
    scene = vofdem.load_scene(Path(__file__).resolve().parents[1] / "scenes" / "maeno2008.toml")
    # a scene takes clumps packed, not placed: explicit stones would need shapes drawn for them
    stones = {**scene.to_dict()["stones"], "shape": "clump", "positions": [[0.55, 0.02]], "diameters": [0.048]}
    with pytest.raises(ValueError, match=r"stones.positions is not allowed with stones.shape = 'clump'"):
        vofdem.Scene.from_dict({**scene.to_dict(), "stones": stones})
