"""Scene -> solver objects: the packed weir of the Maeno 2008 scene and the DEM parameters."""
import numpy as np
import pytest

import vofdem
from vofdem.builder import build_stones, dem_params
from vofdem.scene import Scene


def test_packed_weir_fits_the_scene_and_is_reproducible():
    s = Scene.maeno2008()
    a, rep = build_stones(s)
    b, _ = build_stones(s)
    assert np.array_equal(a.stone_pos, b.stone_pos)  # same seed, same weir
    pos, r = np.asarray(a.stone_pos), np.asarray(a.stone_radius)
    # within one stone diameter of the requested trapezoid (the packing generator's own guarantee)
    assert rep.outline_error < s.stones.diameter
    assert np.all(pos[:, 1] + r <= s.weir.surface(pos[:, 0]) + s.stones.diameter)
    assert np.all(pos[:, 0] > s.weir.toe_x - s.stones.diameter) and np.all(pos[:, 0] < s.weir.x_toe_down + 0.05)
    # diameters within the scene's spread, bottom layer fixed on the bed
    d = 2 * r
    assert np.all(np.abs(d / s.stones.diameter - 1) <= s.stones.diameter_spread + 1e-12)
    fixed = np.asarray(a.stone_fixed).astype(bool)
    assert fixed.sum() == rep.n_fixed > 0 and np.allclose(pos[fixed, 1], r[fixed], atol=1e-9)
    c, _ = build_stones(s.replace(seed=1))
    assert not np.array_equal(np.asarray(c.stone_pos)[:10], pos[:10])


def test_explicit_stones_and_effect_flags():
    s = Scene.maeno2008()
    s.stones.positions = [[1.5, 0.024], [1.5, 0.072]]
    s.effects.rotation = False
    s.effects.added_mass = False
    s.validate()
    sys_, rep = build_stones(s)
    assert rep is None and np.asarray(sys_.stone_fixed).tolist() == [1, 0]
    flags = dem_params(s).flags
    assert not flags & vofdem.DEM_ROTATION and not flags & vofdem.DEM_ADDED_MASS
    assert flags & vofdem.DEM_FRICTION and flags & vofdem.DEM_EXTERNAL_FORCE
    p = dem_params(s)
    assert p.friction_stone == pytest.approx(0.577) and p.walls[0].friction == pytest.approx(0.176)
    assert p.dt == 1e-4 and p.added_mass_coefficient == 1.0


def test_fluid_of_the_scene():
    from vofdem.builder import build_fluid, initial_level, upstream_level

    s = Scene.maeno2008()
    s.effects.turbulence = False
    s.flume.outflow = "tailwater"
    s.flume.tailwater_level = 0.1
    s.numerics.pressure_solver = "direct"
    f = build_fluid(s.validate())
    g = f.grid
    # 3.681 m / 0.025 m; one 0.5 cm row, then 1 cm rows, the last 0.5 cm to 0.38 m joined to the row below
    assert (g.nx, g.nz) == (147, 1 + 37)
    assert g.z_faces[1] == pytest.approx(0.005) and g.z_faces[2] == pytest.approx(0.015)
    assert np.diff(g.z_faces)[-1] == pytest.approx(0.015) and g.z_faces[-1] == pytest.approx(0.38)
    # grid.merge_fraction 0: the remainder is a row of its own
    thin = build_fluid(s.with_value("grid.merge_fraction", 0.0).validate()).grid
    assert thin.nz == 1 + 37 + 1 and np.diff(thin.z_faces)[-1] == pytest.approx(0.005)
    with pytest.raises(ValueError, match=r"grid.merge_fraction = 1.0 is outside the allowed range \[0.0, 1.0\)"):
        s.with_value("grid.merge_fraction", 1.0).validate()
    p = f.params
    assert (p.cfl, p.k1, p.k2, p.flume_width) == (0.5, 200.0, 2.8, 0.5)
    assert p.outlet == vofdem.OutletBoundary.TAILWATER and p.tailwater_level == 0.1
    assert p.inlet == vofdem.InletBoundary.DISCHARGE
    assert p.pressure_solver == vofdem.PressureSolverKind.EIGEN_DIRECT
    assert not p.flags & int(vofdem.FlowEffect.TURBULENCE)
    assert p.flags & int(vofdem.FlowEffect.POROUS_FORCHHEIMER)
    # the numerics of the step count: second-order convection, column-implicit k-epsilon
    assert p.time_scheme == vofdem.MomentumTimeScheme.ADAMS_BASHFORTH2
    assert p.step_control == vofdem.StepControl.THIS_STEP
    assert p.turbulence_time_scheme == vofdem.KEpsilonTimeScheme.VERTICAL_LINES
    assert p.viscous_scheme == vofdem.ViscousScheme.IMPLICIT_VERTICAL
    assert p.viscous_bound == vofdem.ViscousBound.ENERGY
    s.numerics.time_scheme, s.numerics.turbulence_scheme = "euler", "point_implicit"
    s.numerics.step_control = "two_steps"
    s.numerics.viscous_scheme, s.numerics.viscous_bound = "implicit_vertical_from_start", "row_sum"
    p = build_fluid(s.validate()).params
    assert p.time_scheme == vofdem.MomentumTimeScheme.EULER
    assert p.step_control == vofdem.StepControl.TWO_STEPS
    assert p.turbulence_time_scheme == vofdem.KEpsilonTimeScheme.POINT_IMPLICIT
    assert p.viscous_scheme == vofdem.ViscousScheme.IMPLICIT_VERTICAL_FROM_START
    assert p.viscous_bound == vofdem.ViscousBound.ROW_SUM
    # the k-epsilon step limit: on at a safety factor of 0.5 unless the scene says otherwise
    assert (p.turbulence_limit_step, p.turbulence_cfl) == (True, 0.5)
    s.numerics.turbulence_scheme, s.numerics.viscous_scheme = "vertical_lines", "implicit"
    s.numerics.turbulence_step_limit, s.numerics.turbulence_cfl = False, 1.0
    p = build_fluid(s.validate()).params
    assert p.viscous_scheme == vofdem.ViscousScheme.IMPLICIT
    assert (p.turbulence_limit_step, p.turbulence_cfl) == (False, 1.0)
    # the production of k: the standard term, unlimited, unless the scene says otherwise
    assert (s.numerics.turbulence_production, s.numerics.turbulence_production_limit) == ("strain", 0.0)
    assert (p.turbulence_production, p.turbulence_production_limit) == (vofdem.KEpsilonProduction.STRAIN, 0.0)
    assert p.turbulence_pore_strain == vofdem.KEpsilonPoreStrain.NEIGHBOURS
    s.numerics.turbulence_production, s.numerics.turbulence_production_limit = "kato_launder", 10.0
    s.numerics.turbulence_pore_strain = "local"
    p = build_fluid(s.validate()).params
    assert (p.turbulence_production, p.turbulence_production_limit) == (vofdem.KEpsilonProduction.KATO_LAUNDER, 10.0)
    assert p.turbulence_pore_strain == vofdem.KEpsilonPoreStrain.LOCAL
    # the filtered pore strain's box: the stones' median diameter unless the scene gives it
    s.numerics.turbulence_pore_strain = "filtered"
    p = build_fluid(s.validate()).params
    assert p.turbulence_pore_strain == vofdem.KEpsilonPoreStrain.FILTERED
    assert p.turbulence_pore_filter_length == pytest.approx(s.stones.diameter)
    s.numerics.turbulence_pore_filter = 0.1
    assert build_fluid(s.validate()).params.turbulence_pore_filter_length == 0.1
    s.numerics.viscous_bound = "gershgorin"
    with pytest.raises(ValueError, match="numerics.viscous_bound"):
        s.validate()
    assert f.discharge.at(0.0) == pytest.approx(0.010) and f.discharge.at(140.0) == pytest.approx(0.025)
    # water at rest upstream of the crest up to the critical-depth estimate for 10 l/s over 0.5 m
    assert initial_level(s) == pytest.approx(0.25 + 1.5 * (0.02 ** 2 / 9.81) ** (1 / 3))
    # 25 l/s through 0.3 m: q = 0.0833 m^2/s, critical depth 0.0891 m, H = 0.134 m over the 0.25 m weir
    narrow = Scene.maeno2008()
    narrow.flume.width = 0.3
    assert upstream_level(narrow, 0.025) == pytest.approx(0.3837, abs=1e-4)
    F = np.asarray(f.cell_F)
    assert F[:, 0].sum() * 0.01 == pytest.approx(initial_level(s), abs=0.01)
    assert F[:, -1].sum() == 0.0


def test_the_start_water_rests_in_the_pores_or_is_displaced_over_the_weir():
    from vofdem.builder import build_fluid, build_simulation, initial_level

    s = Scene.maeno2008().validate()
    box = build_fluid(s)  # the water filled before the stones: F = 1 up to the level, upstream of the crest
    g = box.grid
    top_of_level_row = np.asarray(g.z_faces)[np.searchsorted(g.z_faces, initial_level(s))]  # 0.305 m
    rest = build_simulation(s).fluid
    # 'rest' (default): the stones take the place of the water they cover; every fraction stays the box's
    assert np.array_equal(np.asarray(rest.cell_F), np.asarray(box.cell_F))
    assert rest.water_volume() < box.water_volume()  # the stones' volume below the level holds no water
    displaced = build_simulation(s.with_value("flume.initial_water", "displaced").validate()).fluid
    # 'displaced': the box's volume kept, the water the stones take piled over the weir up to the top row
    assert displaced.water_volume() == pytest.approx(box.water_volume(), rel=1e-12)
    F = np.asarray(displaced.cell_F).reshape(g.nz, g.nx)
    z_c = 0.5 * (np.asarray(g.z_faces)[1:] + np.asarray(g.z_faces)[:-1])
    assert F[z_c > top_of_level_row].max() > 0.5 and F[-1].max() > 0.5
    with pytest.raises(ValueError, match=r"flume.initial_water = 'still' is not one of 'rest', 'displaced'"):
        s.with_value("flume.initial_water", "still").validate()
