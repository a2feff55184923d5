"""Typed state copies: VOFGrid, DEMSystem and Coupler copy their whole state (copy_state) and return to
it (set_state), so a run can branch: copy mid-run, run on, restore, run again, and the two runs are the
same bit for bit. The checkpoint (export_state, a dict) is the same state as named arrays."""
import numpy as np
import pytest

import vofdem
from vofdem import _core
from vofdem.flow import tank_params


def scene(polygons=False):
    grid = vofdem.Grid2D.uniform(20, 40, 0.2, 0.4)
    fp = tank_params()
    fp.flags |= vofdem.FlowEffect.TURBULENCE | vofdem.FlowEffect.RELATIVE_VELOCITY
    fluid = vofdem.VOFGrid(grid, fp)
    fluid.fill_water_box(0.0, 0.12, 0.0, 0.25)  # a dam break over the stones: everything moves
    dp = vofdem.DEMParams()
    dp.submerged = True
    dp.add_flume(0.0, 0.2, 0.0)
    if polygons:
        dp.contact_steps = 40  # the polygons' stable step stays above the DEM step
    pos = np.array([[0.1 + 0.002 * j, 0.03 + 0.05 * j] for j in range(3)])
    stones = vofdem.DEMSystem(dp, pos=pos, density=[2650.0], radius=np.full(3, 0.024))
    if polygons:
        stones.set_polygons(*_core.random_polygons(np.full(3, 0.048), seed=2))
    return _core.Coupler(fluid, stones, _core.CouplerParams())


def same(a, b):
    assert a.keys() == b.keys()
    for k in a:
        assert np.array_equal(a[k], b[k], equal_nan=True), k


@pytest.mark.parametrize("polygons", [False, True], ids=["discs", "polygons"])
def test_a_coupled_run_branches_bit_for_bit(polygons):
    sim = scene(polygons)
    sim.advance(0.05)
    branch = sim.copy_state()
    at_branch = sim.export_state()
    sim.advance(0.12)
    first = sim.export_state()
    assert not np.array_equal(first["dem/stone_pos"], at_branch["dem/stone_pos"])
    sim.set_state(branch)
    same(sim.export_state(), at_branch)  # the typed copy is the checkpoint's state
    sim.advance(0.12)
    same(sim.export_state(), first)
    assert branch.time == pytest.approx(0.05)


def test_flow_and_stones_branch_alone():
    sim = scene()
    fluid, stones = sim.fluid, sim.stones
    del sim
    f0, s0 = fluid.copy_state(), stones.copy_state()
    fluid.advance(0.05)
    stones.advance(0.05)
    u, pos = np.array(fluid.face_u), np.array(stones.stone_pos)
    fluid.set_state(f0)
    stones.set_state(s0)
    assert fluid.time == 0.0 and stones.time == 0.0
    fluid.advance(0.05)
    stones.advance(0.05)
    assert np.array_equal(fluid.face_u, u) and np.array_equal(stones.stone_pos, pos)


def test_a_state_of_another_scene_is_refused_and_changes_nothing():
    sim = scene()
    sim.advance(0.02)
    before = sim.export_state()
    other = vofdem.VOFGrid(vofdem.Grid2D.uniform(10, 10, 0.1, 0.1), tank_params())
    with pytest.raises(ValueError, match="cell_p"):
        sim.fluid.set_state(other.copy_state())
    few = vofdem.DEMSystem(vofdem.DEMParams(), 2)
    with pytest.raises(ValueError, match="coupler/stone_force_drag"):
        c = _core.Coupler(None, few, _core.CouplerParams())
        sim.set_state(c.copy_state())
    same(sim.export_state(), before)
