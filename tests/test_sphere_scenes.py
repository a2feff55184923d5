"""Scenes of 3D spheres (stones.shape = 'sphere'): a small weir packed in 3D across a narrow flume by the
scene's route (pack_weir -> weir_packing_3d.h), coupled with the true void fraction (n_exp = 0), stepped a
short time with the water kept; and what a scene of spheres refuses (outlines, sieve curves), key named."""
from pathlib import Path

import numpy as np
import pytest

import vofdem
from vofdem.builder import build_simulation, dem_params

SCENES = Path(__file__).resolve().parents[1] / "scenes"


def small_sphere_scene():
    """A 10 cm weir of 3 cm spheres across a 10 cm flume: ~50 spheres, built in about a second."""
    d = vofdem.Scene.maeno2008().to_dict()
    d["stones"].update(shape="sphere", diameter=0.03)
    d["flume"].update(width=0.1, length=1.6, height=0.2)
    d["weir"].update(height=0.08, crest_length=0.06, toe_x=0.5)
    d["hydrograph"].update(discharge_start_lps=1.0, discharge_end_lps=2.0)
    d["grid"].update(dx=0.02)
    s = vofdem.Scene.from_dict(d)
    return s.validate()


def test_a_scene_of_spheres_builds_across_the_width_and_keeps_the_water():
    scene = small_sphere_scene()
    assert dem_params(scene).width == 0.1
    packing = {}
    sim = build_simulation(scene, packing)
    stones = sim.stones
    assert stones.shape == "sphere" and packing["report"].n_fixed >= 3 * 11
    assert sim.params.n_exp == 0.0  # their footprint is their volume: no porosity inside them
    r = np.asarray(stones.stone_radius)
    assert np.all(stones.stone_y >= 0.99 * r) and np.all(stones.stone_y <= 0.1 - 0.99 * r)
    # the mapped solid is the spheres' volume: sum (1 - n) dx dz B over the cells
    g = sim.fluid.grid
    dz = np.diff(np.asarray(g.z_faces))
    solid = float(np.sum((1.0 - np.asarray(sim.fluid.cell_porosity)).reshape(len(dz), -1) * dz[:, None])) * g.dx * 0.1
    volume = sum(stones.volume(i) for i in range(stones.n))
    assert solid == pytest.approx(volume, rel=1e-9)
    # a short coupled step: the water grows by what flowed in (1 l/s over 0.1 m: 0.01 m^2/s per unit
    # width; none flows out yet, the reach below the weir dry), the stones stay finite
    v0 = sim.water_volume()
    sim.advance(0.05)
    assert np.isfinite(np.asarray(stones.stone_pos)).all()
    # to the pressure solver's tolerance (a drift of ~1e-11 m^2 per step, docs/pressure_solver.md)
    assert sim.water_volume() - v0 == pytest.approx(0.01 * 0.05, abs=1e-8)


def test_the_scene_file_of_spheres_is_the_papers_scene_with_spheres():
    spheres = vofdem.load_scene(SCENES / "maeno2008_spheres.toml")
    paper = vofdem.load_scene(SCENES / "maeno2008.toml")
    assert spheres.stones.shape == "sphere"
    a, b = spheres.to_dict(), paper.to_dict()
    a["stones"].pop("shape"), b["stones"].pop("shape")
    a.pop("name"), b.pop("name")
    assert a == b


def test_the_scene_of_rolling_spheres_is_the_sphere_scene_with_the_pulls_mu_r_and_the_consistent_coupling():
    """scenes/maeno2008_spheres_rolling_consistent.toml: the sphere scene with the rolling resistance its
    header names (the calibration's route, calibration.with_rolling) and the bed drag, nothing else."""
    from vofdem.calibration import with_rolling

    rolling = vofdem.load_scene(SCENES / "maeno2008_spheres_rolling_consistent.toml")
    expected = with_rolling(vofdem.load_scene(SCENES / "maeno2008_spheres.toml"), 0.2)
    expected.stones.drag_model = "bed"
    expected.effects.rolling_resistance = True
    a, b = rolling.to_dict(), expected.to_dict()
    a.pop("name"), b.pop("name")
    assert a == b
    assert rolling.numerics.dem_dt == pytest.approx(1e-4 * 20.0 / 32.0, rel=1e-12)


def test_a_scene_of_spheres_refuses_what_its_packing_cannot_do_naming_the_key():
    d = small_sphere_scene().to_dict()
    for key in ("height", "crest_length", "upstream_slope_deg", "downstream_slope_deg", "toe_x"):
        d["weir"].pop(key)
    d["weir"]["outline"] = [[0.5, 0.0], [0.6, 0.06], [0.65, 0.08], [0.7, 0.06], [0.8, 0.0]]  # not a trapezoid
    with pytest.raises(ValueError, match=r"stones.shape = 'sphere' is outside the allowed values .* weir.outline"):
        vofdem.Scene.from_dict(d)
    d = small_sphere_scene().to_dict()
    d["numerics"]["porosity_method"] = "lookup"
    with pytest.raises(ValueError, match="stones.shape = 'sphere'.*lookup|lookup.*stones.shape = 'sphere'"):
        vofdem.Scene.from_dict(d)


def test_a_run_of_spheres_writes_them_in_3d(tmp_path):
    from vofdem.io import RunData, check_xdmf
    from vofdem.run import run_scene

    d = small_sphere_scene().to_dict()
    d["hydrograph"].update(spin_up_duration=0.5)
    scene = vofdem.Scene.from_dict(d).replace(end_time=1.0).validate()
    sim = build_simulation(scene)
    run_scene(scene, tmp_path, sim=sim, progress=False, figures=True, animation=False)
    data = RunData(tmp_path / "run.h5")
    assert data.width == 0.1 and data.y.shape == (data.times.size, data.diameter.size)
    assert np.all(data.y >= 0.0) and np.all(data.y <= 0.1) and np.abs(data.y[-1] - data.y[0]).max() > 0.0
    np.testing.assert_allclose(np.linalg.norm(data.quat[-1], axis=1), 1.0, rtol=1e-12)
    np.testing.assert_array_equal(data.y[-1], np.asarray(sim.stones.stone_y))  # the last snapshot is the end
    np.testing.assert_array_equal(data.quat[-1], np.asarray(sim.stones.stone_quat))
    assert check_xdmf(tmp_path / "run.xmf") > 0 and check_xdmf(tmp_path / "stones.xmf") > 0
    assert (tmp_path / "figures" / "plan_view.png").stat().st_size > 0
