"""Polygon stones from Python: scene keys and their validation, the packed polygon weir, explicit
polygon stones, zero-copy views, and a short run of scenes/maeno2008_polygons.toml with its output."""
import gc
import math
from pathlib import Path

import numpy as np
import pytest

import vofdem
from vofdem.builder import build_stones, dem_params
from vofdem.io import RunData, check_xdmf
from vofdem.run import run_scene
from vofdem.scene import Scene, load_scene

ROOT = Path(__file__).resolve().parents[1]


def small_polygon_scene(seed=0):
    s = Scene.maeno2008().quick()
    s.weir.height, s.weir.crest_length = 0.12, 0.08
    s.stones.shape = "polygon"
    s.numerics.dem_dt, s.numerics.dem_contact_steps = 4e-5, 50.0
    s.seed = seed
    return s.validate()


def test_scene_keys_validate_and_round_trip():
    s = Scene.maeno2008()
    assert s.stones.shape == "disc" and s.numerics.dem_contact_steps == 20.0
    s.stones.shape = "polygon"
    s.stones.polygon_vertices_min, s.stones.polygon_vertices_max, s.stones.aspect_ratio = 6, 7, 1.2
    t = Scene.from_toml(s.validate().to_toml())
    assert t == s and isinstance(t.stones.polygon_vertices_min, int)
    bad = [("shape", "cube", "is not one of"), ("polygon_vertices_min", 2, "allowed range [3, 16]"),
           ("polygon_vertices_min", 5.5, "whole number"), ("polygon_vertices_max", 4, "allowed range [6, 16]"),
           ("aspect_ratio", 0.5, "allowed range [1.0, 3.0]")]
    for key, value, msg in bad:
        u = Scene.maeno2008()
        u.stones.shape = "polygon"
        u.stones.polygon_vertices_min = 6
        setattr(u.stones, key, value)
        with pytest.raises(ValueError, match=f"stones.{key}") as e:
            u.validate()
        assert msg in str(e.value)
    u = Scene.maeno2008()
    u.stones.shape = "polygon"
    u.numerics.porosity_method = "lookup"
    with pytest.raises(ValueError, match="porosity_method = 'lookup'.*disc"):
        u.validate()
    # the contact stiffness key reaches the DEM
    assert dem_params(small_polygon_scene()).contact_steps == 50.0


def test_polygons_refuse_the_discs_rolling_resistance():
    # a polygon resists rolling by its shape: the disc law's mu_r is refused naming both keys
    for key in ("rolling_friction", "rolling_friction_wall"):
        u = Scene.maeno2008()
        u.stones.shape = "polygon"
        setattr(u.stones, key, 0.4)
        with pytest.raises(ValueError, match=rf"stones.{key} = 0.4 is outside the allowed range \[0, 0\] with "
                                             r"stones.shape = 'polygon'"):
            u.validate()
        u.stones.shape = "disc"
        u.validate()
    # and in C++, whichever comes first
    p = vofdem.DEMParams()
    p.rolling_friction_stone = 0.4
    box = np.array([[-0.02, -0.01], [0.02, -0.01], [0.02, 0.01], [-0.02, 0.01]])
    with pytest.raises(ValueError, match="rolling_friction_stone"):
        vofdem.DEMSystem(p, np.zeros((1, 2)), [0.03], [2650.0]).set_polygons(box, [0, 4])


def test_scene_file_is_the_paper_scene_with_polygons():
    s = load_scene(ROOT / "scenes" / "maeno2008_polygons.toml")
    ref = Scene.maeno2008()
    ref.name = "maeno2008_polygons"
    ref.stones.shape = "polygon"
    ref.numerics.dem_dt, ref.numerics.dem_contact_steps = 4e-5, 50.0
    assert s == ref.validate()


def test_packed_polygon_weir_is_at_rest_inside_the_outline_and_reproducible():
    s = small_polygon_scene()
    a, rep = build_stones(s)
    b, _ = build_stones(s)
    assert a.shape == "polygon" and a.n == rep.n_stones > rep.n_fixed > 3
    assert np.array_equal(a.stone_pos, b.stone_pos) and np.array_equal(a.poly_vertex, b.poly_vertex)
    assert rep.max_speed < 1e-3 and rep.outline_error < s.stones.diameter
    d = np.array([a.nominal_diameter(i) for i in range(a.n)])
    assert np.all(np.abs(d / s.stones.diameter - 1) <= s.stones.diameter_spread + 1e-12)
    counts = np.diff(np.asarray(a.poly_offset))
    assert counts.min() >= 5 and counts.max() <= 8
    # the matching stone has the sphere's mass of its nominal diameter
    assert a.mass(0) == pytest.approx(s.stones.density * math.pi * d[0] ** 3 / 6, rel=1e-12)
    c, _ = build_stones(small_polygon_scene(seed=1))
    assert not np.array_equal(np.asarray(c.poly_vertex)[:5], np.asarray(a.poly_vertex)[:5])


def test_explicit_polygon_stones_and_views_tied_to_the_owner():
    s = Scene.maeno2008()
    s.stones.shape = "polygon"
    s.stones.positions = [[1.5, 0.03], [1.5, 0.09]]
    s.validate()
    st, rep = build_stones(s)
    assert rep is None and st.shape == "polygon"
    vertex = np.asarray(st.poly_vertex)
    low = 0.03 + vertex[st.poly_offset[0]:st.poly_offset[1], 1].min()
    assert np.asarray(st.stone_fixed).tolist() == [int(low <= 1e-9), 0]
    view = st.poly_vertex
    first = float(view[0, 0])
    del st
    gc.collect()
    assert view[0, 0] == first  # the view keeps its owner alive
    with pytest.raises(ValueError, match="stone 0"):
        vofdem.DEMSystem(vofdem.DEMParams(), np.zeros((1, 2)), [0.03], [2650.0]).set_polygons(
            np.array([[-1.0, -1.0], [-1.0, 1.0], [1.0, 1.0], [1.0, -1.0]]), [0, 4])


def test_short_run_of_the_polygon_scene_writes_polygons(tmp_path):
    scene = load_scene(ROOT / "scenes" / "maeno2008_polygons.toml").quick().replace(end_time=5.5)
    res = run_scene(scene, tmp_path, progress=False, figures=True, animation=False)
    d = RunData(res.h5_path)
    assert d.attrs["status"] == "completed" and d.attrs["stone_shape"] == "polygon"
    n, T = d.diameter.size, d.times.size
    assert d.poly_offset.size == n + 1 and d.poly_vertex.shape == (d.poly_offset[-1], 2)
    assert d.angle.shape == (T, n)
    # the outlines of the last snapshot: polygons of the nominal diameter's area around each centre
    outlines = d.stone_outlines(T - 1)
    for i in (0, n // 2, n - 1):
        w = outlines[i]
        area = 0.5 * np.sum(w[:, 0] * np.roll(w[:, 1], -1) - np.roll(w[:, 0], -1) * w[:, 1])
        assert area == pytest.approx(math.pi * d.diameter[i] ** 2 / 4, rel=1e-12)
        assert np.allclose(w.mean(axis=0), d.pos[T - 1, i], atol=0.6 * d.diameter[i])
    # the XDMF also references the polygons: per snapshot, topology, world vertices and four cell data
    # (diameter, fixed, active, angle) beside the fields' 7 and the points' 9
    assert check_xdmf(res.xmf_path) == T * 7 + T * 9 + T * 6
    assert (tmp_path / "figures" / "porosity_initial.png").is_file()


def test_polygon_output_helpers_by_hand():
    from vofdem import polygon_output as po

    vertex = np.array([[-1.0, -0.5], [1.0, -0.5], [1.0, 0.5], [-1.0, 0.5], [0.0, -1.0], [1.0, 1.0], [-1.0, 0.0]])
    offset = np.array([0, 4, 7])
    w = po.world_polygon_vertices(vertex, offset, [[10.0, 0.0], [0.0, 5.0]], [math.pi / 2, 0.0])
    # the rectangle turned a quarter counter-clockwise about (10, 0); the triangle moved up by 5
    assert np.allclose(w[:4], [[10.5, -1.0], [10.5, 1.0], [9.5, 1.0], [9.5, -1.0]])
    assert np.allclose(w[4:], vertex[4:] + [0.0, 5.0])
    assert po.topology(offset).tolist() == [3, 4, 0, 1, 2, 3, 3, 3, 4, 5, 6]
    with pytest.raises(ValueError, match="offsets"):
        po.check_polygons(vertex, np.array([0, 4]), 2)


def test_the_outline_packer_refuses_polygons_naming_the_key():
    # outline_packing.py places discs only: zones, sieve curves and outlines other than a trapezoid are refused
    own = load_scene(ROOT / "scenes" / "own_weir.toml")
    own.stones.rolling_friction = own.stones.rolling_friction_wall = 0.0
    own.stones.shape = "polygon"
    graded = load_scene(ROOT / "scenes" / "maeno2008_polygons.toml")
    graded.stones.d15, graded.stones.d50, graded.stones.d85 = 0.04, 0.048, 0.056
    berm = load_scene(ROOT / "scenes" / "maeno2008_polygons.toml")
    berm.weir.outline = [[1.0, 0.0], [1.3, 0.2], [1.5, 0.2], [1.7, 0.1], [1.9, 0.0]]
    for scene, key in ((own, "zones"), (graded, "d15/d50/d85"), (berm, "weir.outline")):
        with pytest.raises(ValueError, match=r"stones.shape = 'polygon' is outside the allowed values \['disc'\]") as e:
            scene.validate()
        assert key in str(e.value)
    # an outline that is a trapezoid packs the polygons as the trapezoid's keys do
    from vofdem.outline import trapezoid_points
    s = small_polygon_scene()
    w = s.weir
    t = s.replace()
    t.weir.outline = [list(p) for p in trapezoid_points(w.toe_x, w.height, w.crest_length, w.upstream_slope_deg,
                                                        w.downstream_slope_deg)]
    a, _ = build_stones(s)
    b, _ = build_stones(t.validate())
    assert np.array_equal(a.stone_pos, b.stone_pos) and np.array_equal(a.poly_vertex, b.poly_vertex)


def test_packed_polygon_weir_at_rest_keeps_its_energy_at_the_stable_step():
    # the discs' stable step is bounded by the explicit dashpots of a packed stone (critical damping);
    # the polygons' bound (the trace of a two-point face contact) holds there without it
    p = vofdem.DEMParams()
    p.add_flume(0.0, 1.4, 0.0)
    p.dt, p.contact_steps = 4e-5, 50.0
    spec = vofdem.WeirSpec()  # the Maeno weir's slopes; its stones (4.8 cm +- 10 %, 2650 kg/m^3) set here
    spec.d_mean, spec.density = 0.048, 2650.0
    spec.shape, spec.height, spec.crest, spec.x_toe, spec.seed = "polygon", 0.15, 0.1, 0.4, 1
    s, _ = vofdem.pack_weir(spec, p)
    dt = s.stable_dt()
    s.step(dt)
    e0 = s.energy().total
    for _ in range(int(0.5 / dt)):
        s.step(dt)
    assert (s.energy().total - e0) / abs(e0) < 1e-9
