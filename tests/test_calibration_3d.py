"""The calibration experiments on 3D stones (vofdem.calibration_3d) at tiny size: the cone fit on a hand-made
cone, a small 3D heap, a sphere pulled out of a pocket of three fixed spheres against the hand-computed
forces, and the choice of slope stones away from the side walls."""
import math

import numpy as np
import pytest

import vofdem
from vofdem import _core, builder, calibration as cal, calibration_3d as c3
from vofdem.scene import Scene


def spheres(mu_r=0.0):
    s = Scene.maeno2008().replace()
    s.stones.shape = "sphere"
    return cal.with_rolling(s.validate(), mu_r)


def test_cone_fit_recovers_a_hand_made_cone():
    # one stone top per plan cell on a 33-degree cone 0.3 m high above a base at z = 0.05 m
    d, base, h, t = 0.048, 0.05, 0.3, math.tan(math.radians(33.0))
    g = (np.arange(-20, 20) + 0.5) * d
    x, y = (a.ravel() for a in np.meshgrid(g, g))
    top = base + np.maximum(h - np.hypot(x, y) * t, 0.0)
    cone, left, right, axis, surf, height = c3.fit_cone(x, y, top, base, d, cal.ReposeSetup())
    assert axis == pytest.approx([0.0, 0.0], abs=1e-12)
    for f in (cone, left, right):
        assert f.angle == pytest.approx(33.0, abs=1e-9)
    assert height == pytest.approx(top.max() - base)
    assert ((cone.z - base) / height).min() >= 0.2 and ((cone.z - base) / height).max() <= 0.8
    # only the highest stone of a cell counts: a buried stone below each changes nothing
    cone2 = c3.fit_cone(np.r_[x, x], np.r_[y, y], np.r_[top, top - d], base, d, cal.ReposeSetup())[0]
    assert cone2.angle == pytest.approx(33.0, abs=1e-9)
    with pytest.raises(ValueError, match="too few to fit"):
        c3.fit_cone(x[:3], y[:3], top[:3] + 1.0, base, d, cal.ReposeSetup())


def test_small_3d_heap_is_a_cone_at_rest_with_a_finite_angle():
    r = cal.pour_heap(spheres(), 0, setup=cal.ReposeSetup(n_stones=150, release_interval=0.04,
                                                          settle_time_max=8.0))
    assert isinstance(r, c3.ConeResult) and r.settled
    # a few spheres may roll off the rough disc: taken away, the rest of the heap at rest
    assert r.lost < 0.05 * 150 and r.max_speed < 1e-3
    # frictional spheres without rolling resistance heap low but finitely (a heap of 150: ~10 deg; of
    # 500: ~20 deg, benchmarks/results/sphere_calibration.md)
    assert 5.0 < r.angle < 30.0
    assert abs(r.left.angle - r.right.angle) < 10.0
    # the heap stands on the axis of the funnel, far from the walls
    assert np.hypot(*r.axis - [0.0, r.pos[r.fixed, 1].mean()]) < 0.05
    assert r.pos.shape[1] == 3 and cal.fig_heap(r) is not None


def pocket(mu_r=0.0):
    """A sphere of d 4.8 cm resting on three fixed ones touching in a triangle, one of them downstream (+x)."""
    sc = spheres(mu_r)
    d = sc.stones.diameter
    R = 0.5 * d
    p = cal.repose_params(sc, False, 10.0 * d)
    p.flags = int(p.flags | _core.DEM_EXTERNAL_FORCE)
    p.width = 10.0 * d
    az = np.radians([0.0, 120.0, 240.0])
    rc = 2.0 * R / math.sqrt(3.0)
    beta = math.asin(rc / (2.0 * R))
    x = np.r_[rc * np.cos(az), 0.0]
    y = np.r_[rc * np.sin(az), 0.0] + 5.0 * d
    z = np.r_[[R] * 3, R + 2.0 * R * math.cos(beta)]
    sys_ = builder.stone_system(sc, p, np.c_[x, z], [d] * 4, [1, 1, 1, 0])
    sys_.stone_y[:] = y
    sys_.advance(0.5)  # settles on its three supports
    m = float(sys_.mass(3))
    return sys_, sys_.export_state(), m, beta


def test_pull_of_a_sphere_out_of_a_pocket_by_hand():
    g = builder.GRAVITY
    sys_, state, m, beta = pocket()
    assert float(np.abs(sys_.stone_vel[3]).max()) < 1e-3
    setup = cal.PullSetup(spring=50.0, speed=0.002, max_travel=0.03)
    k, v = setup.spring, setup.speed
    # vertical: it lifts at M g, then lags the anchor: the peak is M g + v sqrt(k M)
    r = cal.pull_stone(sys_, state, 3, np.array([0.0, 1.0]), setup)
    assert r.peak == pytest.approx(m * g + v * math.sqrt(k * m), rel=0.01)
    # horizontal towards the downstream support: the contact force turns along the normal, so the sphere
    # rolls over it at F = M g tan(beta), sin(beta) = 1 / sqrt(3) (0.707 M g), friction or not
    r = cal.pull_stone(sys_, state, 3, np.array([1.0, 0.0]), setup)
    assert math.tan(beta) == pytest.approx(1.0 / math.sqrt(2.0))
    assert r.peak == pytest.approx(m * g * math.tan(beta), rel=0.03)
    # the pull stays in x-z: the sphere does not leave its plane y
    assert float(sys_.stone_y[3]) == pytest.approx(float(state["stone_y"][3]), abs=1e-6)


def test_3d_slope_stones_keep_away_from_the_side_walls():
    sc = spheres()
    sc.flume.width = 0.2
    sys_, _ = cal.pull_weir(sc, 0)
    stones = cal.surface_stones(sys_, sc)
    assert stones
    Y, R = np.asarray(sys_.stone_y), np.asarray(sys_.stone_radius)
    for i in stones:
        assert min(Y[i], 0.2 - Y[i]) >= 3.0 * R[i]
        assert sys_.stone_pos[i][0] > 0.5 * (sc.weir.x_crest_up + sc.weir.x_crest_down)


def test_pull_setup_refuses_a_negative_hold_distance():
    with pytest.raises(ValueError, match=r"hold_beyond = -1.0 is outside the allowed range"):
        cal.PullSetup(hold_beyond=-1.0).validate()


def test_stones_beyond_the_hold_distance_are_held_and_freed_by_the_checkpoint():
    sys_, state, m, beta = pocket()
    d = float(sys_.nominal_diameter(3))
    # seen from a support, the sphere in the pocket lies 1 d away (in 3D): held beyond 0.9 d, not beyond 1.1 d
    cal._hold_far(sys_, 0, 1.1 * d)
    assert list(sys_.stone_fixed) == [1, 1, 1, 0]
    cal._hold_far(sys_, 0, 0.9 * d)
    assert list(sys_.stone_fixed) == [1, 1, 1, 1]
    sys_.import_state(state)
    assert list(sys_.stone_fixed) == [1, 1, 1, 0]
    # a pull with nothing within reach held but the supports gives the same bits as without
    setup = cal.PullSetup(spring=50.0, speed=0.002, max_travel=0.01)
    free = cal.pull_stone(sys_, state, 3, np.array([1.0, 0.0]), setup)
    held = cal.pull_stone(sys_, state, 3, np.array([1.0, 0.0]), cal.PullSetup(**{**setup.__dict__, "hold_beyond": 0.5}))
    assert np.array_equal(held.force, free.force)


def test_the_heaps_table_of_both_calibration_scripts():
    # one writer for the spheres' and the clumps' results files (benchmarks/*_calibration.py): the rows as
    # those files hold them, the clumps' with the stones lost off the base
    from types import SimpleNamespace as NS
    heap = NS(seed=0, angle=20.54, left=NS(angle=20.31), right=NS(angle=20.66), height=0.2083, lost=3, settled=True)
    assert c3.heaps_markdown([(0.0, heap, 18.4)]) == [
        "## Angle of repose, dry", "", "| mu_r | heap (seed) | angle [deg] | halves [deg] | height [m] | at rest | CPU [s] |",
        "|---:|---:|---:|---|---:|---|---:|", "| 0 | 0 | 20.5 | 20.3 / 20.7 | 0.208 | yes | 18 |"]
    lines = c3.heaps_markdown([(0.2, heap, 93.0)], lost=True)
    assert lines[2] == "| mu_r | heap (seed) | angle [deg] | halves [deg] | height [m] | lost | at rest | CPU [s] |"
    assert lines[3] == "|---:|---:|---:|---|---:|---:|---|---:|"
    assert lines[4] == "| 0.2 | 0 | 20.5 | 20.3 / 20.7 | 0.208 | 3 | yes | 93 |"
