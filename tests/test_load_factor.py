"""studies/load_factor.py: the weir's stones under multiples of the water's load at the release, the flow
frozen, on a small weir of 3D spheres (tests/test_sphere_scenes.py's): nothing moves without load, a load
large enough moves stones, a replay from the same state repeats itself, and the results file says it."""
import numpy as np
import pytest

from script_loader import load_script
from test_sphere_scenes import small_sphere_scene

lf = load_script("studies/load_factor.py")


def _spun_up():
    scene = small_sphere_scene()
    scene.hydrograph.spin_up_duration = 0.3
    return lf.spin_up(scene)


def test_no_load_moves_nothing_and_a_large_one_moves_stones_the_same_way_twice():
    sim = _spun_up()
    stones = sim.stones
    assert np.abs(lf.release_loads(stones)).sum() > 0.0  # the water pulls on the held stones
    state = stones.export_state()
    rows = lf.ramp(stones, state, stones.params, None, [0.0, 400.0], 0.1)
    assert rows[0][1] == 0  # the settled weir stands under buoyancy alone
    assert rows[-1][1] > 0  # 400 times the release's load moves stones
    assert lf.ramp(stones, state, stones.params, None, [0.0, 400.0], 0.1) == rows  # the replay starts from the same state
    assert lf.first_level(rows, 1) == 400.0 and np.isnan(lf.first_level(rows, 10 ** 6))


def test_the_rolling_resistance_is_set_for_the_replay():
    sim = _spun_up()
    stones = sim.stones
    params, state = stones.params, stones.export_state()
    lf.ramp(stones, state, params, 0.7, [0.0], 0.02)
    assert stones.params.rolling_friction_stone == 0.7 and stones.params.rolling_friction_wall == 0.7
    lf.ramp(stones, state, params, None, [0.0], 0.02)  # the next replay starts from the scene's parameters
    assert stones.params.rolling_friction_stone == params.rolling_friction_stone


def test_the_results_file_names_the_command_and_each_member(tmp_path):
    scene_file = tmp_path / "small.toml"
    scene_file.write_text(small_sphere_scene().to_toml(), encoding="utf-8")
    cases = lf.main(["--scenes", str(scene_file), "--seeds", "0", "--mu-r", "0", "0.5", "--levels", "0", "400",
                     "--hold", "0.05", "--spin-up", "0.3", "--tag", "t", "--results", str(tmp_path),
                     "--figures", str(tmp_path), "--out", str(tmp_path)])
    text = (tmp_path / "load_factor_t.md").read_text()
    assert "--mu-r 0 0.5 --levels 0 400 --hold 0.05 --spin-up 0.3 --tag t" in text
    assert len(cases) == 1 and set(cases[0]["ramps"]) == {0.0, 0.5}
    for mu, r in cases[0]["ramps"].items():
        moved = ", ".join(f"{s:g}: {m}" for s, m, _, _ in r["rows"])
        assert f"| {mu:g} | {moved} |" in text
    assert (tmp_path / "load_factor_t.png").stat().st_size > 0
    # a second call resumes: the finished case is read back, not run again, and the file is the same
    again = lf.main(["--scenes", str(scene_file), "--seeds", "0", "--mu-r", "0", "0.5", "--levels", "0", "400",
                     "--hold", "0.05", "--spin-up", "0.3", "--tag", "t", "--results", str(tmp_path),
                     "--figures", str(tmp_path), "--out", str(tmp_path)])
    assert again[0]["cpu_spin_up"] == cases[0]["cpu_spin_up"]
    assert (tmp_path / "load_factor_t.md").read_text() == text
    # --no-run: the tables of the finished cases only (seed 1 has not run), and none at all is an error
    only = lf.main(["--scenes", str(scene_file), "--seeds", "0-1", "--mu-r", "0", "0.5", "--levels", "0", "400",
                    "--hold", "0.05", "--spin-up", "0.3", "--tag", "t", "--results", str(tmp_path),
                    "--figures", str(tmp_path), "--out", str(tmp_path), "--no-run"])
    assert [c["seed"] for c in only] == [0]
    with pytest.raises(ValueError, match="no case"):
        lf.main(["--scenes", str(scene_file), "--seeds", "5", "--tag", "t", "--out", str(tmp_path), "--no-run",
                 "--results", str(tmp_path), "--figures", str(tmp_path)])
