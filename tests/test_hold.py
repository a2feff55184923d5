"""Stones held while the flow spins up keep their contacts (DEMSystem.held): a packed weir held for a
while and let go has the contact pairs and tangential springs of its packing, where fixing every stone
(the former hold) dropped the pairs of two fixed stones; the run loop holds this way and releases at
the ramp's start."""
import numpy as np

from vofdem.builder import build_stones
from vofdem.scene import Scene


def _packed():
    st, _ = build_stones(Scene.maeno2008().quick())
    return st


def test_a_held_weir_keeps_its_springs_and_places():
    st = _packed()
    before = st.export_state()
    assert np.count_nonzero(before["contact_xi"]) > 10  # the packing's friction
    st.held = True
    st.stone_force_ext[:] = 0.3  # a load that would move free stones
    st.advance(0.5)
    held = st.export_state()
    for key in ("contact_i", "contact_j", "contact_xi", "contact_mr", "stone_pos", "wall_xi"):
        np.testing.assert_array_equal(held[key], before[key], err_msg=key)
    assert not np.any(held["stone_vel"])
    st.held = False
    st.advance(0.01)
    assert not np.array_equal(st.stone_pos, before["stone_pos"])  # let go, the load moves them


def test_fixing_every_stone_drops_the_springs_the_hold_keeps():
    st = _packed()
    packed = np.abs(st.export_state()["contact_xi"])
    fixed0 = np.array(st.stone_fixed)
    st.stone_fixed[:] = True
    st.advance(0.01)
    st.stone_fixed[:] = fixed0
    st.advance(1e-4)  # one step after the release: the springs start again from zero
    after = np.abs(st.export_state()["contact_xi"])
    assert after.max() < 1e-6 * np.median(packed[packed > 0])
