"""Coupler from Python: the names the run loop uses, zero-copy views, checkpoint/restart, guards."""
import gc
import threading
import time

import numpy as np
import pytest

import vofdem
from vofdem import _core
from vofdem.flow import tank_params


def scene(n_stones=3, flags=None):
    grid = vofdem.Grid2D.uniform(20, 40, 0.2, 0.4)
    fp = tank_params()
    if flags is None or flags & _core.COUPLE_POROSITY:
        fp.flags |= vofdem.FlowEffect.RELATIVE_VELOCITY  # two-way: resistance relative to the stones
    fluid = vofdem.VOFGrid(grid, fp)
    fluid.fill_water_below(0.2)
    fluid.set_hydrostatic_pressure()
    dp = vofdem.DEMParams()
    dp.submerged = True
    dp.add_flume(0.0, 0.2, 0.0)
    pos = np.array([[0.1 + 0.002 * j, 0.2 + 0.05 * j] for j in range(n_stones)])
    stones = vofdem.DEMSystem(dp, pos=pos, density=[2650.0], radius=np.full(n_stones, 0.024))
    cp = _core.CouplerParams()
    if flags is not None:
        cp.flags = flags
    return _core.Coupler(fluid, stones, cp)


def test_run_loop_names_and_zero_copy_views():
    sim = scene()
    assert sim.time == 0.0
    sim.set_inflow_table(np.array([0.0, 10.0]), np.array([0.0, 0.0]))
    sim.advance(0.05)
    assert sim.time == pytest.approx(0.05, abs=1e-12)
    assert sim.stone_force_drag.shape == (3, 2) and sim.stone_force_pressure.shape == (3, 2)
    assert sim.stones.stone_pos.shape == (3, 2)
    assert sim.fluid.cell_F.shape == (40, 20)
    assert list(sim.profile.names) == ["snapshot", "porosity", "fluid_forces", "dem", "fluid", "checks", "stable_dt"]
    calls = dict(zip(sim.profile.names, sim.profile.calls))
    # advance() takes the guard's snapshot every few steps only (CouplerParams.max_snapshot_interval)
    assert 1 <= calls.pop("snapshot") < sim.step_count
    assert all(c == sim.step_count for c in calls.values())
    # the views write through and keep their owners alive after the coupler is gone
    drag, F, pos = sim.stone_force_drag, sim.fluid.cell_F, sim.stones.stone_pos
    fluid = sim.fluid
    assert fluid is sim.fluid  # the same Python object every time
    del sim, fluid
    gc.collect()
    assert np.isfinite(drag).all() and F.sum() > 0 and pos.shape == (3, 2)


def test_the_stage_times_sum_to_about_the_step_time():
    # `profile` the wall clock, `cpu_profile` the process's CPU time: the same stages and calls, each summing
    # to about what advance() took by that clock (the stages are disjoint here: no kernel, no overflow load;
    # the step control between them is the rest)
    sim = scene()
    sim.set_inflow_table(np.array([0.0, 10.0]), np.array([0.0, 0.0]))
    wall0, cpu0 = time.perf_counter(), time.process_time()
    sim.advance(0.3)
    wall, cpu = time.perf_counter() - wall0, time.process_time() - cpu0
    assert list(sim.cpu_profile.names) == list(sim.profile.names)
    assert list(sim.cpu_profile.calls) == list(sim.profile.calls)
    for prof, took in ((sim.profile, wall), (sim.cpu_profile, cpu)):
        assert 0.8 * took < prof.total_seconds <= took
    sim.cpu_profile.reset()
    assert sim.cpu_profile.total_seconds == 0.0 and sim.profile.total_seconds > 0.0  # reset apart

def test_checkpoint_dict_restarts_bit_for_bit():
    a = scene()
    a.advance(0.1)
    state = {k: v.copy() for k, v in a.export_state().items()}
    a.advance(0.2)
    b = scene()
    b.import_state(state)
    b.advance(0.2)
    sa, sb = a.export_state(), b.export_state()
    assert sa.keys() == sb.keys()
    for k in sa:
        assert np.array_equal(sa[k], sb[k]), k
    with pytest.raises(ValueError, match="fluid/cell_F"):
        state["fluid/cell_F"] = state["fluid/cell_F"][:3]
        b.import_state(state)


def test_advance_releases_the_gil():
    # while a worker thread advances, this thread keeps running Python code (a held GIL would block it)
    sim = scene()
    t = threading.Thread(target=sim.advance, args=(0.3,))
    count = 0
    t.start()
    while t.is_alive():
        count += 1
    t.join()
    assert sim.time == pytest.approx(0.3)
    assert count > 1000


def test_guards_and_bad_input():
    sim = scene()
    sim.advance(0.02)
    t = sim.time
    sim.stones.stone_vel[0, 1] = np.nan
    with pytest.raises(RuntimeError, match="fluid_forces.*stone 0"):
        sim.step(1e-3)
    assert sim.time == t
    p = _core.CouplerParams()
    p.stone_cfl = 5.0
    with pytest.raises(ValueError, match="stone_cfl"):
        p.validate()
    p = _core.CouplerParams()
    p.flags |= 1 << 5  # the former relative-velocity coupling: the flow's own flag now
    with pytest.raises(ValueError, match="FlowEffect|kFlowRelativeVelocity"):
        p.validate()


def test_the_stones_take_the_flows_medium():
    fp = tank_params()
    fp.medium.rho_water = 1025.0  # sea water
    fp.medium.gravity = [0.3, -9.8]
    fluid = vofdem.VOFGrid(vofdem.Grid2D.uniform(4, 4, 0.2, 0.2), fp)
    dry = vofdem.DEMSystem(vofdem.DEMParams(), pos=np.array([[0.1, 0.1]]), density=[2650.0], radius=np.array([0.024]))
    _core.Coupler(fluid, dry)
    assert dry.params.submerged and dry.params.medium == fp.medium
    assert dry.params.water_density == 1025.0
    assert fluid.params.flags == fp.flags  # the coupler sets no flag of the flow


def test_scenes_with_one_module():
    dp = vofdem.DEMParams()
    dp.add_flume(0.0, 0.3, 0.0)
    stones = vofdem.DEMSystem(dp, pos=np.array([[0.1, 0.1]]), density=[2650.0], radius=np.array([0.024]))
    sim = _core.Coupler(None, stones)
    assert sim.fluid is None
    sim.advance(0.2)
    assert stones.stone_pos[0, 1] == pytest.approx(0.024, abs=1e-3)  # landed on the bed
    fluid = vofdem.VOFGrid(vofdem.Grid2D.uniform(8, 8, 0.2, 0.2), tank_params())
    fluid.fill_water_below(0.1)
    sim = _core.Coupler(fluid, None)
    sim.advance(0.05)
    assert sim.stones is None and fluid.time == sim.time


def test_initial_mapping_can_keep_the_water_fraction():
    # stones placed into a filled scene: keep F (pores full of water) or keep the volume (water displaced up)
    for keep, expect_same_F in ((False, True), (True, False)):
        sim = scene(flags=_core.COUPLE_TWO_WAY)
        sim.stones.stone_pos[:] = [[0.05, 0.05], [0.1, 0.05], [0.15, 0.05]]
        F0 = np.array(sim.fluid.cell_F)
        v0 = sim.water_volume()
        sim.update_porosity(keep_water_volume=keep)
        assert np.array_equal(F0, np.asarray(sim.fluid.cell_F)) == expect_same_F
        if keep:
            assert sim.water_volume() == pytest.approx(v0, rel=1e-12)
        else:
            assert sim.water_volume() < v0


def test_drag_exchange_option_and_step_limits():
    from vofdem.builder import build_simulation, coupler_params
    from vofdem.scene import Scene

    s = Scene.maeno2008().quick()
    assert coupler_params(s.validate()).implicit_drag
    s.numerics.drag_exchange = "held"
    assert not coupler_params(s.validate()).implicit_drag
    # every step of advance() is counted under the limit that bound it, and where
    sim = build_simulation(Scene.maeno2008().quick())
    n = sim.advance(0.05)
    limits = sim.step_limits()
    assert sum(limits.values()) == n and n > 0
    cells = sim.step_limit_cells()
    for term, counts in cells.items():
        assert counts.shape == (sim.fluid.grid.ncell,) and counts.sum() <= limits[term]
    sim.clear_step_limits()
    assert sim.step_limits() == {}
