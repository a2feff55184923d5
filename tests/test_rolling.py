"""Rolling resistance through the binding and the scene (the C++ tests cover the law by hand)."""
import math

import numpy as np
import pytest

import vofdem
from vofdem import cli
from vofdem.builder import build_stones, dem_params
from vofdem.scene import Scene, Stones
from dem_util import state_hash

R = 0.024
M = 2650.0 * 4.0 / 3.0 * math.pi * R**3


def incline(theta, mu_r, f=0.4):
    """A stone at its static overlap on a bed, gravity tilted by theta: an incline."""
    p = vofdem.DEMParams()
    p.medium.gravity = [9.81 * math.sin(theta), -9.81 * math.cos(theta)]
    p.stiffness_normal = 1e5
    p.inertia_factor = f
    p.rolling_friction_wall = mu_r
    p.walls = [vofdem.DEMWall([0.0, 0.0], [0.0, 1.0], 0.577)]
    delta = M * 9.81 * math.cos(theta) / 1e5
    return vofdem.DEMSystem(p, pos=np.array([[0.0, R - delta]]), density=[2650.0], radius=np.array([R]))


def test_parameters_and_flag_are_bound():
    p = vofdem.DEMParams()
    assert p.rolling_friction_stone == 0.0 and p.rolling_friction_wall == 0.0 and p.rolling_damping == 0.3
    assert vofdem.DEM_ROLLING_RESISTANCE == 512 and p.flags & vofdem.DEM_ROLLING_RESISTANCE
    p.rolling_friction_stone = -0.2
    with pytest.raises(ValueError, match=r"rolling_friction_stone = -0.2"):
        vofdem.DEMSystem(p, 1)
    p.rolling_friction_stone, p.rolling_damping = 0.2, 1.5
    with pytest.raises(ValueError, match=r"rolling_damping = 1.5 is outside the allowed range \[0, 1\]"):
        vofdem.DEMSystem(p, 1)


def test_incline_holds_below_mu_r_and_rolls_above_at_the_hand_rate():
    mu_r = 0.25
    s = incline(math.atan(0.9 * mu_r), mu_r)
    s.advance(1.0)
    assert abs(s.stone_vel[0, 0]) < 1e-5 and abs(s.stone_pos[0, 0]) < 1e-4
    th = math.atan(1.6 * mu_r)
    s = incline(th, mu_r)
    s.advance(0.5)
    v0 = s.stone_vel[0, 0]
    s.advance(0.5)
    a = (s.stone_vel[0, 0] - v0) / 0.5
    assert a == pytest.approx(9.81 * (math.sin(th) - mu_r * math.cos(th)) / 1.4, rel=5e-3)
    # the flag off: the coefficient is ignored and the stone rolls at 5/7 g sin
    s = incline(th, mu_r)
    p = s.params
    p.flags = p.flags & ~vofdem.DEM_ROLLING_RESISTANCE
    s.params = p
    s.advance(0.5)
    v0 = s.stone_vel[0, 0]
    s.advance(0.5)
    assert (s.stone_vel[0, 0] - v0) / 0.5 == pytest.approx(5 / 7 * 9.81 * math.sin(th), rel=5e-3)


def pile(mu_r):
    p = vofdem.DEMParams()
    p.rolling_friction_stone = p.rolling_friction_wall = mu_r
    p.contact_steps = 32.0  # the rolling springs' mode under critical damping (DEMSystem::stable_dt)
    p.add_flume(0.0, 0.5, 0.0)
    rng = np.random.default_rng(2)
    pos = np.array([[0.04 + 0.055 * (k % 8) + 0.002 * rng.random(), 0.03 + 0.055 * (k // 8)] for k in range(40)])
    return vofdem.DEMSystem(p, pos=pos, density=[2650.0], radius=R * (0.9 + 0.2 * rng.random(40)))


def test_rolling_springs_are_checkpointed_and_restart_bit_for_bit():
    a = pile(0.3)
    a.advance(0.3)
    chk = {k: v.copy() for k, v in a.export_state().items()}
    assert np.any(chk["contact_mr"] != 0.0) and np.any(chk["wall_mr"] != 0.0)
    a.advance(0.2)
    b = vofdem.DEMSystem(vofdem.DEMParams(), 0)
    b.params = a.params
    b.import_state(chk)
    b.advance(0.2)
    assert state_hash(a) == state_hash(b)


def test_energy_bookkeeping_includes_the_rolling_springs():
    # 60 stones falling into a box (restitution 0.3): the balance K + P + elastic + dissipated closes to
    # first order in dt, 3.0 % of the dissipated energy at stable_dt / 2 (1.5 % at stable_dt / 4)
    rng = np.random.default_rng(5)
    p = vofdem.DEMParams()
    p.add_flume(0.0, 0.45, 0.0, 0.3)
    p.stiffness_normal, p.restitution = 2e5, 0.3
    p.rolling_friction_stone = p.rolling_friction_wall = 0.3
    pos = np.array([[0.03 + 0.055 * (k % 8) + 0.002 * rng.random(), 0.03 + 0.055 * (k // 8)] for k in range(60)])
    s = vofdem.DEMSystem(p, pos=pos, density=[2650.0], radius=R * (0.9 + 0.2 * rng.random(60)))
    p.dt = 0.5 * s.stable_dt()
    s.params = p
    e0 = s.energy().total
    s.advance(0.5)
    e = s.energy()
    assert e.dissipated > 0 and abs(e.total - e0) < 0.04 * e.dissipated


def test_scene_keys_are_range_checked_and_mapped_to_the_dem():
    s = Scene.maeno2008()
    assert s.stones.rolling_friction == 0.0 and s.effects.rolling_resistance
    with pytest.raises(ValueError, match=r"stones.rolling_friction = 1.5 is outside the allowed range \[0.0, 1.0\]"):
        Scene(stones=Stones(rolling_friction=1.5))
    with pytest.raises(ValueError, match="stones.rolling_damping"):
        Scene.from_toml("[stones]\nrolling_damping = -1\n")
    t = Scene.from_toml("[stones]\nrolling_friction = 0.4\nrolling_friction_wall = 0.2\nrolling_damping = 0.5\n")
    p = dem_params(t)
    assert (p.rolling_friction_stone, p.rolling_friction_wall, p.rolling_damping) == (0.4, 0.2, 0.5)
    assert p.flags & vofdem.DEM_ROLLING_RESISTANCE
    assert Scene.from_toml(t.to_toml()) == t
    t.effects.rolling_resistance = False
    assert not dem_params(t).flags & vofdem.DEM_ROLLING_RESISTANCE


def test_the_weir_is_packed_with_the_rolling_resistance():
    from vofdem.calibration import with_rolling

    s = Scene.maeno2008()
    plain, _ = build_stones(s)
    rolled, _ = build_stones(with_rolling(s, 0.4))
    assert rolled.params.rolling_friction_stone == 0.4
    # the same seed packs differently: the packer used the rolling resistance
    n = min(plain.n, rolled.n)
    assert not np.allclose(np.asarray(plain.stone_pos)[:n], np.asarray(rolled.stone_pos)[:n])


def test_params_command_lists_the_rolling_keys(capsys):
    assert cli.main(["params"]) == 0
    out = capsys.readouterr().out
    for key in ("stones.rolling_friction ", "stones.rolling_friction_wall", "stones.rolling_damping",
                "effects.rolling_resistance"):
        assert key in out


def test_rolling_scenes_are_the_base_scenes_with_the_calibrated_stones():
    from pathlib import Path

    from vofdem.scene import load_scene

    root = Path(__file__).resolve().parents[1] / "scenes"
    for name, base in (("maeno2008_rolling", "maeno2008"), ("maeno2008_rolling_consistent", "maeno2008_consistent")):
        s, b = load_scene(root / f"{name}.toml"), load_scene(root / f"{base}.toml")
        assert s.name == name and s.effects.rolling_resistance
        assert (s.stones.rolling_friction, s.stones.rolling_friction_wall, s.stones.rolling_damping) == (0.5, 0.5, 0.3)
        # the same contact stiffness in more, shorter DEM steps (the rolling springs' stable step)
        assert s.numerics.dem_contact_steps * s.numerics.dem_dt == pytest.approx(
            b.numerics.dem_contact_steps * b.numerics.dem_dt, rel=1e-12)
        s.name = b.name
        s.stones.rolling_friction = s.stones.rolling_friction_wall = 0.0
        s.numerics.dem_dt, s.numerics.dem_contact_steps = b.numerics.dem_dt, b.numerics.dem_contact_steps
        assert s == b
