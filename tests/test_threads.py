"""Threads for one run (docs/threads.md): the option's range from Python and the CLI, the same bits on
one and two threads, the GIL released while the threads step, ensemble members on one thread."""
import multiprocessing
import threading

import numpy as np
import pytest
from fake_sim import FakeSimulation, short_scene

import vofdem
from vofdem import _core
from vofdem.cli import main
from vofdem.ensemble import run_ensemble
from vofdem.flow import tank_params

needs_two = pytest.mark.skipif(not _core.built_with_openmp(), reason="built without OpenMP: one thread only")


@pytest.fixture
def restore_threads():
    before = _core.threads(), _core.thread_min_cells()
    yield
    _core.set_threads(before[0])
    _core.set_thread_min_cells(before[1])


def flume(turbulence=True, scheme=None):
    """Water fed through the inlet over a porous block into a free overfall, stones dropped on it
    (scheme: the k-epsilon transport's KEpsilonTimeScheme, None: the default)."""
    fp = tank_params()
    if scheme is not None:
        fp.turbulence_time_scheme = scheme
    fp.inlet = _core.InletBoundary.DISCHARGE
    fp.outlet = _core.OutletBoundary.FREE_OVERFALL
    fp.flume_width = 0.5
    fp.flags |= vofdem.FlowEffect.RELATIVE_VELOCITY
    if turbulence:
        fp.flags |= vofdem.FlowEffect.TURBULENCE
    fluid = vofdem.VOFGrid(vofdem.Grid2D.uniform(30, 15, 0.6, 0.3), fp)
    fluid.set_porosity_box(0.25, 0.4, 0.0, 0.12, 0.4, 0.04)
    fluid.fill_water_below(0.1)
    fluid.set_hydrostatic_pressure()
    dp = vofdem.DEMParams()
    dp.submerged = True
    dp.add_flume(0.0, 0.6, 0.0)
    pos = np.array([[0.3 + 0.03 * j, 0.2 + 0.03 * j] for j in range(3)])
    stones = vofdem.DEMSystem(dp, pos=pos, density=[2650.0], radius=np.full(3, 0.012))
    sim = _core.Coupler(fluid, stones, _core.CouplerParams())
    sim.set_inflow_table(np.array([0.0, 10.0]), np.array([0.01, 0.01]))
    return sim


def state_after(threads, seconds=0.15, scheme=None):
    _core.set_threads(threads)
    _core.set_thread_min_cells(1)  # every loop split, on this small grid too
    sim = flume(scheme=scheme)
    sim.advance(seconds)
    return {k: np.array(v, copy=True) for k, v in sim.export_state().items()}


@pytest.mark.parametrize("bad", [0, -3, 257])
def test_set_threads_refuses_values_outside_its_range(bad, restore_threads):
    before = _core.threads()
    with pytest.raises(ValueError, match=rf"threads = {bad} is outside the allowed range \[1, 256\]"):
        _core.set_threads(bad)
    assert _core.threads() == before
    with pytest.raises(ValueError, match=r"thread_min_cells = 0 is outside the allowed range \[1, 1000000000\]"):
        _core.set_thread_min_cells(0)


@needs_two
def test_a_coupled_flume_is_the_same_bits_on_one_and_two_threads(restore_threads):
    one, two = state_after(1), state_after(2)
    assert one.keys() == two.keys()
    for k in one:
        assert one[k].tobytes() == two[k].tobytes(), k
    start = np.asarray(flume().export_state()["dem/stone_pos"])
    assert start.shape == one["dem/stone_pos"].shape and not np.array_equal(one["dem/stone_pos"], start)  # they moved


@needs_two
def test_the_alternating_lines_are_the_same_bits_on_one_and_two_threads(restore_threads):
    # the k-epsilon transport's row systems, then its column systems, on the threads
    scheme = _core.KEpsilonTimeScheme.ALTERNATING_LINES
    one, two = state_after(1, scheme=scheme), state_after(2, scheme=scheme)
    for k in one:
        assert one[k].tobytes() == two[k].tobytes(), k
    default = state_after(1)
    assert any(one[k].tobytes() != default[k].tobytes() for k in one)  # the scheme is in play


@needs_two
def test_two_threads_step_with_the_gil_released(restore_threads):
    _core.set_threads(2)
    _core.set_thread_min_cells(1)
    sim = flume()
    t = threading.Thread(target=sim.advance, args=(0.1,))
    count = 0
    t.start()
    while t.is_alive():
        count += 1
    t.join()
    assert sim.time == pytest.approx(0.1)
    assert count > 1000


def _flume_hash_in_child(_):
    sim = flume()
    sim.advance(0.05)
    return _core.threads(), {k: np.array(v).tobytes() for k, v in sim.export_state().items()}


@needs_two
def test_a_forked_child_steps_on_one_thread_after_the_parent_ran_two(restore_threads):
    # GNU OpenMP hangs in a forked child's first parallel region once the parent has run one: the
    # library sets a forked child to one thread
    _core.set_threads(2)
    _core.set_thread_min_cells(1)
    parent = flume()
    parent.advance(0.05)
    with multiprocessing.get_context("fork").Pool(1) as pool:
        threads, state = pool.apply_async(_flume_hash_in_child, (0,)).get(timeout=120)
    assert threads == 1
    assert state == {k: np.array(v).tobytes() for k, v in parent.export_state().items()}


def test_cli_threads_option(tmp_path, restore_threads, capsys):
    scene = short_scene().replace(end_time=1.0)
    path = tmp_path / "scene.toml"
    path.write_text(scene.to_toml(), encoding="utf-8")
    assert main(["run", str(path), "--threads", "0", "--out", str(tmp_path / "a"), "--no-progress"]) == 2
    assert "threads = 0 is outside the allowed range [1, 256]" in capsys.readouterr().err
    assert main(["run", str(path), "--seeds", "0-1", "--threads", "2", "--out", str(tmp_path / "b")]) == 2
    assert "--threads is for single runs" in capsys.readouterr().err
    seen = []

    def build(s):
        seen.append(_core.threads())
        return FakeSimulation(s)

    assert main(["run", str(path), "--threads", "1", "--out", str(tmp_path / "c"), "--no-progress",
                 "--no-figures", "--no-animation"], build=build) == 0
    assert seen == [1]
    assert "Threads: 1" in (tmp_path / "c" / "profile.md").read_text(encoding="utf-8")


def _build_recording_threads(scene):
    _build_recording_threads.seen.append(_core.threads())
    return FakeSimulation(scene)


_build_recording_threads.seen = []


def test_ensemble_members_run_on_one_thread(tmp_path, restore_threads):
    _core.set_threads(_core.max_threads() if _core.built_with_openmp() else 1)
    before = _core.threads()
    _build_recording_threads.seen.clear()
    run_ensemble(short_scene(), [0, 1], tmp_path, build=_build_recording_threads, workers=0, n_boot=0,
                 progress=False, figures=False, animation=False, dashboard=False, log=lambda *a: None)
    assert _build_recording_threads.seen == [1, 1]
    assert _core.threads() == before  # the process's setting is back
