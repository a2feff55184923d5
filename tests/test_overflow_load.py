"""The overflow load (numerics.overflow_load = 'drag_lift'; docs/coupler.md): off in the paper's scenes, a
scene with it on builds and steps with the flag and coefficients handed to the coupler, the loaded stones
protrude into the water, the reaction taken from the flow is minus the stones' load, bad keys are refused."""
import numpy as np
import pytest

from vofdem import _core
from vofdem.builder import build_simulation, coupler_params
from vofdem.scene import Scene


def _scene(**numerics):
    s = Scene.maeno2008().quick()
    for k, v in numerics.items():
        setattr(s.numerics, k, v)
    return s.validate()


def test_off_in_the_paper_scene():
    s = _scene()
    assert s.numerics.overflow_load == "off"
    assert not coupler_params(s).flags & int(_core.CouplerEffect.OVERFLOW_LOAD)


def test_a_scene_with_the_key_on_builds_and_steps():
    s = _scene(overflow_load="drag_lift", overflow_lift_coefficient=0.2)
    p = coupler_params(s)
    assert p.flags & int(_core.CouplerEffect.OVERFLOW_LOAD)
    assert p.overflow_drag_coefficient == 0.91 and p.overflow_lift_coefficient == 0.2 and p.overflow_band_height == 1.0
    sim = build_simulation(s)
    sim.stones.stone_fixed[:] = True
    sim.advance(1.0)
    f = np.asarray(sim.stone_force_overflow)
    share = np.asarray(sim.stone_exposed_share)
    assert np.isfinite(f).all()
    loaded = np.abs(f).sum(axis=1) > 0.0
    assert loaded.any(), "no stone of the weir takes the overflow"
    # only stones that stick out are loaded, each on a share of its area below 1
    assert (share[loaded] > 0.0).all() and (share <= 1.0).all()
    # Newton's third law: the reaction over the cells times the flume width is minus the stones' sum
    r = np.asarray(sim.cell_overflow_reaction).sum(axis=0) * s.flume.width
    assert r == pytest.approx(-f.sum(axis=0), rel=1e-12)
    prof = sim.profile
    assert prof.calls[list(prof.names).index("overflow_load")] >= sim.step_count


@pytest.mark.parametrize("key, bad", [("overflow_load", "lift"), ("overflow_drag_coefficient", 0.0),
                                      ("overflow_lift_coefficient", -0.1), ("overflow_band_height", 6.0)])
def test_bad_keys_are_refused_by_name(key, bad):
    s = Scene.maeno2008().quick()
    setattr(s.numerics, key, bad)
    with pytest.raises(ValueError, match=rf"numerics\.{key}"):
        s.validate()
