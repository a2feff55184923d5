"""The packed weir settles under buoyancy in still water before the flow starts
(hydrograph.settle_in_still_water): the scene keys, the build (the stones at rest with their wet
fractions, the flow untouched, the same bits twice, the stage timed), and a run stopped after its first
checkpoint resumes without settling again, bit for bit."""
import numpy as np
import pytest

import vofdem.builder as builder
import vofdem.run as run
from vofdem.builder import build_simulation, build_stones
from vofdem.io import RunData
from vofdem.scene import Scene, load_scene


def _scene(settle=True, **kw):
    s = Scene.maeno2008().quick()
    s.hydrograph.settle_in_still_water = settle
    for k, v in kw.items():
        setattr(s.hydrograph, k, v)
    return s


def test_the_keys_default_on_in_the_paper_scene_and_refuse_bad_values(tmp_path):
    s = Scene.maeno2008()
    assert s.hydrograph.settle_in_still_water is True and s.hydrograph.settle_time_max == 5.0
    p = tmp_path / "s.toml"
    p.write_text(_scene(False, settle_time_max=2.5).to_toml(), encoding="utf-8")
    back = load_scene(p)
    assert back.hydrograph.settle_in_still_water is False and back.hydrograph.settle_time_max == 2.5
    for bad in (0.0, -1.0, 601.0, float("nan")):
        with pytest.raises(ValueError, match=r"hydrograph\.settle_time_max.*\(0\.0, 600\.0\]"):
            s.with_value("hydrograph.settle_time_max", bad)


def test_the_coupler_refuses_bad_settle_parameters_by_name():
    sim = build_simulation(_scene(False))
    for kw, name in (({"max_time": 0.0}, "max_time"), ({"rest_speed": -1.0}, "rest_speed"),
                     ({"hold": 11.0}, "hold"), ({"chunk": 0.0}, "chunk")):
        with pytest.raises(ValueError, match=name):
            sim.settle(**kw)


def test_the_built_weir_settles_to_rest_in_the_still_pool_and_the_flow_waits():
    packing = {}
    on = build_simulation(_scene(), packing)
    off = build_simulation(_scene(False))
    r = packing["settle"]
    assert r.rested and r.max_speed < 1e-3 and 0.2 <= r.time <= 5.0
    assert on.stones.max_speed() < 1e-3
    # the flow frozen: the pool as filled, the coupler's clock at 0
    np.testing.assert_array_equal(on.fluid.cell_F, off.fluid.cell_F)
    assert on.time == 0.0 and on.step_count == 0
    # the stones moved, under a millimetre (the packing was at rest dry), and the ones in the pool are
    # lighter: the upstream stones are wet, the downstream slope's dry
    d = np.abs(np.asarray(on.stones.stone_pos) - np.asarray(off.stones.stone_pos))
    assert 0.0 < d.max() < 1e-3
    wet = np.asarray(on.stones.stone_wet)
    assert wet.max() == 1.0 and wet.min() == 0.0
    assert "settle" in list(on.profile.names)
    # the same bits twice
    again = build_simulation(_scene())
    for key, v in on.export_state().items():
        np.testing.assert_array_equal(np.asarray(again.export_state()[key]), np.asarray(v), err_msg=key)


def test_without_the_key_the_build_is_the_former_one():
    a, b = build_simulation(_scene(False)), build_simulation(_scene(False), settle=False)
    st, _ = build_stones(_scene(False))
    np.testing.assert_array_equal(a.stones.stone_pos, st.stone_pos)
    np.testing.assert_array_equal(a.stones.stone_pos, b.stones.stone_pos)
    assert "settle" not in list(a.profile.names)


@pytest.mark.parametrize("stop_after", [3, 12])
def test_a_resumed_run_does_not_settle_again_and_ends_bit_for_bit(tmp_path, monkeypatch, stop_after):
    """Stopped during the hold (snapshot 3, t = 1 s) and after the release at 5 s (snapshot 12, t = 5.5 s:
    the resumed stones keep the accelerations their checkpoint carries)."""
    scene = _scene().replace(end_time=6.5)
    calls = []
    real = builder.settle_stones

    def counted(sim, sc):
        calls.append(1)
        return real(sim, sc)

    monkeypatch.setattr(builder, "settle_stones", counted)
    opts = dict(progress=False, figures=False, animation=False, checkpoint_seconds=0.0, log=lambda *a: None)
    ref = run.run_scene(scene, tmp_path / "ref", **opts)
    assert len(calls) == 1
    # stopped after a snapshot (a checkpoint after each), then resumed
    snap, seen = run._Loop.snapshot, []

    def stopping(self):
        snap(self)
        seen.append(1)
        if len(seen) == stop_after:
            run._stop_requested = True

    monkeypatch.setattr(run._Loop, "snapshot", stopping)
    with pytest.raises(KeyboardInterrupt):
        run.run_scene(scene, tmp_path / "cut", **opts)
    monkeypatch.setattr(run._Loop, "snapshot", snap)
    assert len(calls) == 2
    res = run.run_scene(scene, tmp_path / "cut", resume=True, **opts)
    assert len(calls) == 2  # no second settling
    a, b = RunData(ref.h5_path), RunData(res.h5_path)
    np.testing.assert_array_equal(a.times, b.times)
    np.testing.assert_array_equal(a.pos, b.pos)
    for k in range(len(a.times)):
        np.testing.assert_array_equal(a.fields(k)["F"], b.fields(k)["F"], err_msg=f"snapshot {k}")
    assert "settle" in (tmp_path / "cut" / "profile.md").read_text(encoding="utf-8")


def test_the_benchmark_pairs_the_settle_off_and_on_at_a_tiny_size(tmp_path):
    from script_loader import load_script

    bench = load_script("studies/settle_still_water.py")
    md = bench.main(["--quick", "--seeds", "0", "--end-time", "0.2", "--out", str(tmp_path / "ens"),
                     "--results", str(tmp_path / "settle.md")])
    text = md.read_text(encoding="utf-8")
    assert "1 members of both ensembles" in text and "| seed0 |" in text
    assert "The settling alone (process CPU time around `builder.settle_stones`, 1 packings)" in text
    assert "1 of 1 packings came to rest" in text
