"""Scenes of 3D clumps (stones.shape = 'clump'): a small weir of library clumps packed in 3D across a narrow
flume by the scene's route (pack_weir -> clump_packing.cpp), coupled with the true void fraction (n_exp = 0),
run a second with the water kept and the stones bounded, the same bits twice from a seed; and what a scene
of clumps refuses (a DEM step too long for them, explicit stones), key named."""
import numpy as np
import pytest

import vofdem
from vofdem.builder import build_simulation, dem_params

WIDTH = 0.1  # [m]


def small_clump_scene(**numerics):
    """A 8 cm weir of 3 cm clumps across a 10 cm flume (the spheres' test scene, test_sphere_scenes.py), with
    the DEM step of 2.5e-5 s in 80 steps per contact: the scene's stiffness (1e-4 s in 20), at a step the
    clumps' turning allowed under the former bound of their stable step (~0.3 of the spheres' at a stiffness;
    ~0.7 under clump_model.h's)."""
    d = vofdem.Scene.maeno2008().to_dict()
    d["stones"].update(shape="clump", diameter=0.03)
    d["flume"].update(width=WIDTH, length=1.6, height=0.2)
    d["weir"].update(height=0.08, crest_length=0.06, toe_x=0.5)
    d["hydrograph"].update(discharge_start_lps=1.0, discharge_end_lps=2.0)
    d["grid"].update(dx=0.02)
    d["numerics"].update({"dem_dt": 2.5e-5, "dem_contact_steps": 80.0, **numerics})
    return vofdem.Scene.from_dict(d).validate()


def world_spheres(stones):
    """World centres (m, 3) [m] and radii [m] of every clump's sub-spheres."""
    sph, off = np.asarray(stones.clump_sphere), np.asarray(stones.clump_offset)
    st = np.repeat(np.arange(stones.n), np.diff(off))
    w, x, y, z = (np.asarray(stones.stone_quat)[st, k] for k in range(4))
    rot = np.stack([np.c_[1 - 2 * (y * y + z * z), 2 * (x * y - w * z), 2 * (x * z + w * y)],
                    np.c_[2 * (x * y + w * z), 1 - 2 * (x * x + z * z), 2 * (y * z - w * x)],
                    np.c_[2 * (x * z - w * y), 2 * (y * z + w * x), 1 - 2 * (x * x + y * y)]], axis=1)
    c = np.einsum("nij,nj->ni", rot, sph[:, :3])
    p = np.asarray(stones.stone_pos)
    return np.c_[p[st, 0] + c[:, 0], np.asarray(stones.stone_y)[st] + c[:, 1], p[st, 1] + c[:, 2]], sph[:, 3]


def run_one_second(scene):
    sim = build_simulation(scene)
    v0 = sim.water_volume()
    sim.advance(1.0)
    return sim, v0


def test_a_scene_of_clumps_packs_runs_a_second_keeps_the_water_and_repeats_its_bits():
    scene = small_clump_scene()
    assert dem_params(scene).width == WIDTH
    packing = {}
    sim = build_simulation(scene, packing)
    stones = sim.stones
    assert stones.shape == "clump" and sim.params.n_exp == 0.0
    assert packing["report"].n_stones > packing["report"].n_fixed + 10
    # the mapped solid, sum (1 - n) dx dz B over the cells, is the clumps' union volume less what their
    # sub-spheres, pressed by their contacts (overlaps ~ load / k_n), reach past the side walls and the bed,
    # outside the flume's slabs: at most those caps (each scaled by V_union / sum V_k <= 1 in the mapping)
    g = sim.fluid.grid
    dz = np.diff(np.asarray(g.z_faces))
    solid = float(np.sum((1.0 - np.asarray(sim.fluid.cell_porosity)).reshape(len(dz), -1) * dz[:, None])) * g.dx * WIDTH
    volume = sum(stones.volume(i) for i in range(stones.n))
    c, r = world_spheres(stones)
    past = np.concatenate([r - c[:, 1], c[:, 1] + r - WIDTH, r - c[:, 2]])
    rr = np.tile(r, 3)
    caps = float(np.sum(np.where(past > 0.0, np.pi * past**2 * (3.0 * rr - past) / 3.0, 0.0)))
    assert caps < 1e-6 * volume
    assert volume - caps - 1e-12 * volume <= solid <= volume * (1.0 + 1e-12)
    # a second of the coupled run: the water grows by what flowed in (1 l/s over 0.1 m: 0.01 m^2/s per unit
    # width; none flows out yet, the reach below the weir dry), within the pressure solver's drift (~1e-11
    # m^2 per step, docs/pressure_solver.md)
    a, v0 = run_one_second(scene)
    assert np.isfinite(np.asarray(a.stones.stone_pos)).all()
    assert a.water_volume() - v0 == pytest.approx(0.01 * 1.0, abs=1e-7)
    # bounded: every sub-sphere between the side walls and above the bed within 2 % of its radius (the
    # contacts' overlaps, as test_clump_packing.cpp asks), no stone lost
    c, r = world_spheres(a.stones)
    assert np.all(c[:, 1] - r >= -0.02 * r) and np.all(c[:, 1] + r <= WIDTH + 0.02 * r)
    assert np.all(c[:, 2] - r >= -0.02 * r)
    assert np.asarray(a.stones.stone_active).all()
    # the same bits from the same seed
    b, _ = run_one_second(small_clump_scene())
    np.testing.assert_array_equal(np.asarray(a.stones.stone_pos), np.asarray(b.stones.stone_pos))
    np.testing.assert_array_equal(np.asarray(a.stones.stone_quat), np.asarray(b.stones.stone_quat))
    np.testing.assert_array_equal(np.asarray(a.fluid.cell_F), np.asarray(b.fluid.cell_F))


def test_a_scene_of_clumps_refuses_a_step_too_long_and_explicit_stones_naming_the_key():
    with pytest.raises(ValueError, match="numerics.dem_dt"):
        build_simulation(small_clump_scene(dem_dt=1e-4, dem_contact_steps=20.0))
    d = small_clump_scene().to_dict()
    d["stones"].update(positions=[[0.55, 0.02]], diameters=[0.03])
    with pytest.raises(ValueError, match=r"stones.positions.*'clump'|'clump'.*stones.positions"):
        vofdem.Scene.from_dict(d).validate()


def test_a_compaction_friction_out_of_range_or_for_plane_stones_is_refused_naming_the_key():
    d = small_clump_scene().to_dict()
    for bad in (-0.1, 2.5, float("nan")):
        d["stones"].update(compaction_friction=bad)
        with pytest.raises(ValueError, match="stones.compaction_friction"):
            vofdem.Scene.from_dict(d).validate()
    d["stones"].update(compaction_friction=0.3, shape="disc")
    with pytest.raises(ValueError, match="stones.compaction_friction"):
        vofdem.Scene.from_dict(d).validate()
    d["stones"].update(shape="clump")
    assert vofdem.Scene.from_dict(d).validate().stones.compaction_friction == 0.3
