"""The calibration experiments (vofdem.calibration) at tiny size: the flank fit and the pull by hand, a small
heap, the choice of slope stones, the command line."""
import math

import numpy as np
import pytest

import vofdem
from vofdem import builder, calibration as cal, cli
from vofdem.scene import Scene


def scene(mu_r=0.0):
    return cal.with_rolling(Scene.maeno2008(), mu_r)


def test_flank_fit_recovers_a_hand_made_heap():
    # one stone top per bin on a symmetric 35-degree triangle 0.5 m high above a base at z = 0.05 m
    d, base, h, t = 0.048, 0.05, 0.5, math.tan(math.radians(35.0))
    x = (np.arange(-30, 30) + 0.5) * d
    top = base + np.maximum(h - np.abs(x) * t, 0.0)
    left, right, env, height = cal.fit_flanks(x, top, base, d, cal.ReposeSetup())
    assert left.angle == pytest.approx(35.0, abs=1e-9) and right.angle == pytest.approx(35.0, abs=1e-9)
    assert height == pytest.approx(top.max() - base)
    # only the envelope between 0.2 and 0.8 of the height is fitted
    assert ((left.z - base) / height).min() >= 0.2 and ((right.z - base) / height).max() <= 0.8
    with pytest.raises(ValueError, match="too few to fit"):
        cal.fit_flanks(x[25:30], top[25:30], base, d, cal.ReposeSetup())
    with pytest.raises(ValueError, match="no heap"):
        cal.fit_flanks(x[:3], top[:3], base, d, cal.ReposeSetup())


def test_setups_refuse_bad_values():
    with pytest.raises(ValueError, match="n_stones"):
        cal.ReposeSetup(n_stones=1).validate()
    with pytest.raises(ValueError, match="fit_low"):
        cal.ReposeSetup(fit_low=0.9, fit_high=0.5).validate()
    with pytest.raises(ValueError, match=r"spring = -1.0 is outside the allowed range"):
        cal.PullSetup(spring=-1.0).validate()


def test_small_heaps_at_rest_and_steeper_with_rolling_resistance():
    # 60 stones: a submerged heap with rolling resistance stands narrow and steep, and fewer give its
    # flanks too few envelope bins to fit
    setup = cal.ReposeSetup(n_stones=60)
    plain = cal.pour_heap(scene(0.0), 0, False, setup)
    rolled = cal.pour_heap(scene(0.5), 0, False, setup)
    wet = cal.pour_heap(scene(0.5), 0, True, setup)
    for r in (plain, rolled, wet):
        assert r.settled and r.max_speed < setup.rest_speed
        assert 5.0 < r.angle < 70.0
        assert len(r.pos) == len(r.fixed) and r.fixed.sum() > 0 and (~r.fixed).sum() == 60
    assert rolled.height > 1.15 * plain.height  # the same stones stand higher
    assert "| dry | 0 |" in cal.repose_markdown([plain]) and "submerged" in cal.repose_markdown([wet])


def lone_stone(mu_r, f=0.4):
    """One 4.8 cm stone at rest on the flat bed, with the scene's stone model and the pull's force input."""
    s = scene(mu_r)
    p = builder.dem_params(s, submerged=False)
    p.flags = int(p.flags | vofdem.DEM_EXTERNAL_FORCE)
    p.inertia_factor = f
    m = 2650.0 * math.pi * 0.048**3 / 6.0
    sys_ = builder.stone_system(s, p, [[0.5, 0.024]], [0.048], [0])
    sys_.advance(0.2)  # settle on the bed's spring
    return sys_, sys_.export_state(), m


def test_pull_of_a_lone_stone_on_the_bed_by_hand():
    setup = cal.PullSetup(spring=50.0, speed=0.02, max_travel=0.12)
    g, k, v = builder.GRAVITY, setup.spring, setup.speed
    # vertical: it lifts at F = M g, then lags the anchor by an oscillation of amplitude v / omega,
    # omega^2 = k / M: the peak is M g + v sqrt(k M)
    sys_, state, m = lone_stone(0.0)
    r = cal.pull_stone(sys_, state, 0, np.array([0.0, 1.0]), setup)
    assert r.weight == pytest.approx(m * g)
    assert r.peak == pytest.approx(m * g + v * math.sqrt(k * m), rel=0.01)
    # horizontal, rolling friction 0.1 on the bed (below its friction 0.176): it starts rolling at
    # F = mu_r M g and then lags by v / omega with omega^2 = k / (M (1 + f))
    sys_, state, m = lone_stone(0.1)
    r = cal.pull_stone(sys_, state, 0, np.array([1.0, 0.0]), setup)
    assert r.peak == pytest.approx(0.1 * m * g + v * math.sqrt(k * m * 1.4), rel=0.02)
    # without rolling resistance a disc pulled at its centre rolls away at once
    sys_, state, m = lone_stone(0.0)
    r = cal.pull_stone(sys_, state, 0, np.array([1.0, 0.0]), setup)
    assert r.peak == pytest.approx(v * math.sqrt(k * m * 1.4), rel=0.02)
    # the curve starts at zero force and rises at k v per second of pulling
    assert r.force[0] == 0.0 and r.travel[1] == pytest.approx(v * setup.update)


def test_slope_stones_are_surface_stones_of_the_downstream_slope():
    s = scene(0.4)
    sys_, state = cal.pull_weir(s, 0)
    cand = cal.slope_surface_stones(sys_, s)
    assert len(cand) >= 3
    w = s.weir
    a = math.radians(w.downstream_slope_deg)
    n = np.array([math.sin(a), math.cos(a)])
    P, R = np.asarray(sys_.stone_pos), np.asarray(sys_.stone_radius)
    for i in cand:
        assert 0.2 * w.height <= P[i, 1] <= 0.8 * w.height and P[i, 0] > w.x_crest_up
        assert not sys_.stone_fixed[i]
        # nothing lies farther out along the slope's normal right above it
        out = (P - P[i]) @ n
        along = np.abs((P - P[i]) @ np.array([-n[1], n[0]]))
        assert not np.any((out > 0.5 * (R + R[i])) & (along < 0.75 * (R + R[i])))
    assert cal.pick_evenly(cand, 2) == [cand[len(cand) // 4], cand[3 * len(cand) // 4]]
    assert cal.pick_evenly([4, 5], 3) == [4, 5]


def test_pull_test_on_a_packed_weir():
    res = cal.pull_test(scene(0.4), seeds=[0], per_seed=1, directions=("vertical", "horizontal"))
    assert [r.direction for r in res] == ["vertical", "horizontal"]
    for r in res:
        assert r.peak > 0.8 * r.weight and r.travel_at_peak > 0.0
    table = cal.pull_markdown(res)
    assert "| vertical | 1 |" in table and "2.81" in table and "normal" not in table
    with pytest.raises(ValueError, match="direction 'up'"):
        cal.pull_test(scene(), seeds=[0], directions=("up",))
    fig = cal.fig_pull(res)
    assert len(fig.axes[0].lines) >= 3


def test_calibrate_command(tmp_path, capsys):
    out = tmp_path / "cal"
    assert cli.main(["calibrate", "repose", "maeno2008", "--seeds", "0", "--stones", "40", "--out", str(out)]) == 0
    assert "| dry | 0 |" in capsys.readouterr().out
    assert (out / "repose.md").exists() and (out / "heap.png").stat().st_size > 10000
    assert cli.main(["calibrate", "pull", "maeno2008", "--seeds", "0", "--per-seed", "1", "--out", str(out)]) == 0
    assert "| horizontal | 1 |" in capsys.readouterr().out
    assert (out / "pull.md").exists() and (out / "pull.png").exists()
    assert cli.main(["calibrate", "repose", "maeno2008", "--seeds", "2-1"]) == 2
    assert "seeds" in capsys.readouterr().err


def polygon_scene():
    s = Scene.maeno2008()
    s.stones.shape = "polygon"
    s.numerics.dem_dt, s.numerics.dem_contact_steps = 4e-5, 50.0
    return s.validate()


def test_polygon_stones_are_measured_by_their_vertices():
    # a 6 x 2 cm box: its top is its highest vertex, whatever its bounding disc
    s = polygon_scene()
    box = (np.array([[-0.03, -0.01], [0.03, -0.01], [0.03, 0.01], [-0.03, 0.01]]), np.array([0, 4]))
    sys_ = builder.stone_system(s, builder.dem_params(s, 0.0), [[0.5, 0.2]], [0.04], [0], shapes=box)
    assert sys_.shape == "polygon" and sys_.stone_radius[0] == pytest.approx(math.hypot(0.03, 0.01))
    assert cal.stone_tops(sys_)[0] == pytest.approx(0.21, abs=1e-15)
    sys_.stone_angle[0] = math.pi / 2
    assert cal.stone_tops(sys_)[0] == pytest.approx(0.23, abs=1e-15)
    assert np.allclose(cal.stone_outlines(sys_)[0], [[0.51, 0.17], [0.51, 0.23], [0.49, 0.23], [0.49, 0.17]])


def test_small_heap_of_polygons():
    setup = cal.ReposeSetup(n_stones=30)
    r = cal.pour_heap(polygon_scene(), 0, False, setup)
    assert r.settled and r.max_speed < setup.rest_speed and 5.0 < r.angle < 70.0
    assert len(r.outlines) == len(r.pos) and (~r.fixed).sum() == 30
    # the base: fixed polygons standing on the bed by their lowest vertex, in random orientations; the
    # envelope is made of the polygons' highest vertices
    base = [w for w, f in zip(r.outlines, r.fixed) if f]
    assert max(abs(w[:, 1].min()) for w in base) < 1e-12
    assert r.base_top == pytest.approx(max(w[:, 1].max() for w in base), abs=1e-15)
    tops = np.array([w[:, 1].max() for w in r.outlines])
    assert r.envelope[:, 1].max() == pytest.approx(tops[~r.fixed].max(), abs=1e-15)
    again = cal.pour_heap(polygon_scene(), 0, False, setup)
    assert again.angle == r.angle and np.array_equal(again.pos, r.pos)
    fig = cal.fig_heap(r)
    assert len(fig.axes[0].collections) == 2  # fixed and free polygons


def test_pull_of_a_lone_polygon_on_the_bed_by_hand():
    # a box lying on the bed pulled up at its centre: it lifts at M g, then lags the anchor by v / omega
    s = polygon_scene()
    setup = cal.PullSetup(spring=50.0, speed=0.02, max_travel=0.12)
    g, k, v = builder.GRAVITY, setup.spring, setup.speed
    p = builder.dem_params(s, submerged=False)
    p.flags = int(p.flags | vofdem.DEM_EXTERNAL_FORCE)
    box = (np.array([[-0.03, -0.015], [0.03, -0.015], [0.03, 0.015], [-0.03, 0.015]]), np.array([0, 4]))
    sys_ = builder.stone_system(s, p, [[0.5, 0.015]], [0.048], [0], shapes=box)
    sys_.advance(0.2)
    m = sys_.mass(0)
    r = cal.pull_stone(sys_, sys_.export_state(), 0, np.array([0.0, 1.0]), setup)
    assert r.weight == pytest.approx(m * g)
    assert r.peak == pytest.approx(m * g + v * math.sqrt(k * m), rel=0.01)
