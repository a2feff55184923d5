"""The run loop against a pure-Python test double of the coupled simulation (tests/fake_sim.py)."""
import re

import numpy as np
import pytest
from fake_sim import FakeSimulation, short_scene

from vofdem.io import RunData, check_xdmf
from vofdem.run import SolverError, run_scene



def test_run_writes_output_and_finds_the_stages(tmp_path):
    s = short_scene()
    sim = FakeSimulation(s)
    res = run_scene(s, tmp_path, sim=sim, progress=False, figures=True, animation=True)
    d = RunData(tmp_path / "run.h5")
    assert d.attrs["status"] == "completed"
    assert d.times[0] == 0.0 and d.times[-1] == pytest.approx(32.0)
    assert 2.0 in d.times.tolist()  # the release of the held stones is a snapshot
    assert np.allclose(d.discharge, [s.hydrograph.discharge(t) for t in d.times])
    assert check_xdmf(tmp_path / "run.xmf") > 0
    # the double removes 2 stones at 15-15.2 l/s and 3 at 18-18.3 l/s: two stages
    a = res.analysis
    assert [st.n_stones for st in a.stages] == [2, 3]
    assert all(st.location in ("downstream slope", "shoulder") for st in a.stages)
    from vofdem.plots import stage_of_stones

    lab = stage_of_stones(a)  # the destruction figure's colours
    assert ((lab == 1).sum(), (lab == 2).sum(), (lab == -1).sum(), (lab == 0).sum()) == (2, 3, 0, lab.size - 5)
    assert 15.0 <= a.stages[0].discharge_lps <= 15.2 + 0.5 + 1e-9  # snapshot every 1 s = 0.5 l/s
    assert 18.0 <= a.stages[1].discharge_lps <= 18.5 + 1e-9
    for name in ("stage_table.md", "stage_table.csv", "crest_lowering.csv", "profile.md", "scene.toml",
                 "figures/timeline.png", "figures/destruction.png", "figures/porosity_initial.png",
                 "figures/stones_velocity_stage1.png",
                 "figures/pressure_gradient_stage2.png", "figures/drag_stage1.png", "figures/rating_curve.png",
                 "figures/velocity_distribution.png"):
        assert (tmp_path / name).stat().st_size > 0, name
    anim = [p for p in res.files if p.name.startswith("animation")]
    assert anim and anim[0].stat().st_size > 0 and anim[0].suffix in (".mp4", ".gif")
    assert "| fake_fluid |" in res.profile_table and "real-time factor" in res.profile_table
    # the upstream level follows the double's weir formula
    assert np.allclose(d.upstream_level[1:], s.weir.height + (d.discharge[1:] / (1.7 * s.flume.width)) ** (2 / 3),
                       atol=s.grid.dz)


def test_stones_are_held_during_the_spin_up(tmp_path):
    s = short_scene()
    s.hydrograph.spin_up_duration = 12.0  # the double would push stones off at 15 l/s only, but
    sim = FakeSimulation(s, thresholds_lps=[9.0, 9.0])  # these two go at once unless held
    run_scene(s, tmp_path, sim=sim, progress=False, figures=False, animation=False)
    d = RunData(tmp_path / "run.h5")
    moved = np.linalg.norm(d.pos - d.pos[0], axis=2).max(axis=1)
    assert moved[d.times <= 12.0].max() == 0.0 and moved[-1] > 0
    assert np.array_equal(sim.stones.stone_fixed, d.fixed) and not sim.stones.held  # held by DEMSystem.held, let go


def test_water_at_the_domain_top_is_reported_once(tmp_path):
    s = short_scene()
    # the double's level, 0.25 m + (Q / (1.7 B))^(2/3), passes 0.32 m (the top row's floor) at 15.8 l/s; at 16 l/s
    # (t = 14 s) it is 0.3208 m: F = (0.3208 - 0.33) / 0.02 + 0.5 = 0.0381
    s.flume.height = 0.34
    with pytest.warns(RuntimeWarning) as caught:
        run_scene(s.validate(), tmp_path, sim=FakeSimulation(s), progress=False, figures=False, animation=False)
    messages = [str(w.message) for w in caught]
    # before the run, the weir formula's level at 25 l/s (0.3451 m) above the top row's floor (0.32 m)
    assert sum(m.startswith("at the peak discharge 25 l/s the weir formula puts the water 0.3451 m") for m in messages) == 1
    reached = [m for m in messages if m.startswith("water reaches")]
    assert len(reached) == 1  # once, though it stays there
    assert re.match(r"water reaches the domain's top row at t = 14 s \(F = 0.0381 .* raise flume.height = 0.34 m",
                    reached[0])
    assert RunData(tmp_path / "run.h5").attrs["water_at_top_s"] == 14.0
    run_scene(short_scene(), tmp_path / "low", sim=FakeSimulation(short_scene()), progress=False, figures=False,
              animation=False)  # 0.38 m: the level stays below the top row, no warning (warnings are errors here)
    assert "water_at_top_s" not in RunData(tmp_path / "low" / "run.h5").attrs


def test_a_resumed_run_keeps_when_water_reached_the_top(tmp_path):
    from vofdem.run import request_stop

    s = short_scene()
    s.flume.height = 0.34  # the level reaches the top row at t = 14 s (above) and stays there

    class StopsAtSixteen(FakeSimulation):
        def advance(self, t_end):
            super().advance(t_end)
            if t_end == 16.0:
                request_stop()

    with pytest.warns(RuntimeWarning) as caught, pytest.raises(KeyboardInterrupt):
        run_scene(s.validate(), tmp_path, sim=StopsAtSixteen(s), progress=False, figures=False, animation=False,
                  checkpoint_seconds=0.0)
    assert any("top row at t = 14 s" in str(w.message) for w in caught)
    # the resumed run warns no second time, neither before nor during the run (warnings are errors here),
    # and records the first time
    run_scene(s, tmp_path, sim=FakeSimulation(s), progress=False, figures=False, animation=False, resume=True)
    d = RunData(tmp_path / "run.h5")
    assert d.attrs["status"] == "completed" and d.attrs["water_at_top_s"] == 14.0


def test_solver_failure_keeps_the_output(tmp_path):
    s = short_scene()
    with pytest.raises(SolverError, match=r"solver failed at t = 7.5 s: fake stage 'pressure': no convergence"):
        run_scene(s, tmp_path, sim=FakeSimulation(s, fail_at=7.5), progress=False)
    d = RunData(tmp_path / "run.h5")
    assert d.times.tolist() == [0.0, 1.0, 2.0, 3.0, 4.0, 5.0, 6.0, 7.0]
    assert d.attrs["status"].startswith("failed: fake stage 'pressure'")
    assert check_xdmf(tmp_path / "run.xmf") > 0


def test_a_stop_request_survives_a_swallowed_interrupt(tmp_path):
    """A SIGTERM's KeyboardInterrupt raised inside a finaliser is dropped by Python; the stop flag set
    by the same handler still ends the run at the next snapshot, with the output closed as interrupted."""
    from vofdem.run import request_stop

    s = short_scene()

    class StopsAtThree(FakeSimulation):
        def advance(self, t_end):
            super().advance(t_end)
            if t_end == 3.0:
                request_stop()

    with pytest.raises(KeyboardInterrupt):
        run_scene(s, tmp_path, sim=StopsAtThree(s), progress=False)
    d = RunData(tmp_path / "run.h5")
    assert d.times.tolist() == [0.0, 1.0, 2.0, 3.0]
    assert d.attrs["status"] == "interrupted"
    run_scene(s, tmp_path / "again", sim=FakeSimulation(s), progress=False, figures=False, animation=False)
    assert RunData(tmp_path / "again" / "run.h5").attrs["status"] == "completed"


def test_checkpoints_come_after_the_first_and_last_snapshot_and_every_interval(tmp_path, monkeypatch):
    import vofdem.run as run_mod

    clock = [0.0]  # a wall clock that advances 5 s at each reading
    saved = []
    real = run_mod.save_checkpoint

    def save(path, ck):
        saved.append(ck.snapshots)
        real(path, ck)

    def perf_counter():
        clock[0] += 5.0
        return clock[0]

    monkeypatch.setattr(run_mod, "save_checkpoint", save)
    monkeypatch.setattr(run_mod._time, "perf_counter", perf_counter)
    s = short_scene()
    run_scene(s, tmp_path / "a", sim=FakeSimulation(s), progress=False, figures=False, animation=False,
              checkpoint_seconds=25.0)
    n = RunData(tmp_path / "a" / "run.h5").times.size
    assert saved[0] == 1 and saved[-1] == n and 2 < len(saved) < n
    # the clock advances by the same readings per snapshot: checkpoints evenly spaced, more than one apart
    assert len({b - a for a, b in zip(saved, saved[1:-1])}) == 1 and saved[1] - saved[0] > 1
    saved.clear()
    run_scene(s, tmp_path / "b", sim=FakeSimulation(s), progress=False, figures=False, animation=False,
              checkpoint_seconds=0.0)
    assert saved == list(range(1, n + 1))
    with pytest.raises(ValueError, match=r"checkpoint_seconds = -1.0 is out of range \(allowed: >= 0 s\)"):
        run_scene(s, tmp_path / "c", sim=FakeSimulation(s), progress=False, checkpoint_seconds=-1.0)


def test_a_run_whose_peak_water_the_weir_formula_puts_in_the_top_row_is_warned_before_it_starts():
    from vofdem.builder import build_grid
    from vofdem.run import check_headroom
    from vofdem.scene import Scene

    s = Scene.maeno2008()
    z = np.asarray(build_grid(s).z_faces)  # the top row from 0.365 m to 0.38 m
    check_headroom(s, z)  # 25 l/s through 0.5 m: 0.25 + 1.5 (0.05^2 / g)^(1/3) = 0.3449 m, no warning
    s.flume.width = 0.3  # 0.0833 m^2/s: 0.3837 m
    with pytest.warns(RuntimeWarning, match=r"at the peak discharge 25 l/s the weir formula puts the water 0.3837 m "
                      r"high \(flume.width = 0.3 m\), above the domain's top row from 0.365 m: raise flume.height = 0.38 m"):
        check_headroom(s, z)
