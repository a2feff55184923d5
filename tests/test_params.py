"""Parameters from Python cannot change unchecked: `obj.params` is a copy, so editing it in place changes
nothing; every invalid value reaches the owner only through a checked path (the constructor or assigning
`obj.params`), which raises ValueError naming the field and leaves the owner as it was."""
import math

import numpy as np
import pytest

import vofdem
from vofdem import _core
from vofdem.flow import tank_params

NAN = math.nan


def grid():
    return vofdem.Grid2D.uniform(8, 6, 0.08, 0.06)


def fluid(params=None):
    return vofdem.VOFGrid(grid(), params if params is not None else tank_params())


def dem_params():
    p = vofdem.DEMParams()
    p.submerged = True
    p.add_flume(0.0, 0.08, 0.0)
    return p


def stones(params=None):
    p = params if params is not None else dem_params()
    return vofdem.DEMSystem(p, pos=np.array([[0.04, 0.03]]), density=[2650.0], radius=np.array([0.01]))


def coupler(params=None):
    return _core.Coupler(fluid(), stones(), params if params is not None else _core.CouplerParams())


def porosity_params():
    p = _core.PorosityParams()
    p.r_min, p.r_max = 0.01, 0.012
    return p


def mapper(params=None):
    return _core.PorosityMapper(grid(), params if params is not None else porosity_params())


# invalid values of every numeric field (NaN is refused everywhere); the name the error must give
FLOW_BAD = {
    "cfl": [0.0, 0.7, NAN],
    "max_dt": [0.0, NAN], "initial_dt": [-1e-3, NAN], "max_dt_growth": [0.9, 11.0, NAN], "min_dt": [0.0, NAN],
    "k1": [0.0, NAN], "k2": [-1.0, NAN], "flume_width": [0.0, NAN], "pressure_tol": [0.0, NAN],
    "tailwater_level": [math.inf, NAN], "flags": [1 << 8], "viscous_substeps": [0, 65],
    "turbulence_production_limit": [-1.0, NAN], "turbulence_pore_filter_length": [-1.0, NAN],
    "turbulence_bed_roughness": [-1e-3, NAN],
    "turbulence_wall_roughness": [-1e-3, NAN], "turbulence_inflow_intensity": [-0.1, NAN],
    "turbulence_cfl": [0.0, 1.5, NAN],
    "turbulence_inflow_length_scale": [0.0, NAN],
}
DEM_BAD = {
    "added_mass_coefficient": [-0.5, NAN], "dt": [0.0, NAN],
    "stiffness_normal": [-1.0, NAN], "contact_steps": [4.0, NAN], "stiffness_ratio": [-0.1, NAN],
    "restitution": [-0.1, 1.5, NAN], "tangential_damping_factor": [-0.5, NAN], "friction_stone": [-0.1, NAN],
    "inertia_factor": [0.0, 1.5, NAN], "rolling_friction_stone": [-0.1, NAN], "rolling_friction_wall": [-0.1, NAN],
    "rolling_damping": [-0.1, 1.5, NAN], "neighbour_skin": [-1e-3, NAN], "sleep_velocity": [-1e-3, NAN],
    "sleep_time": [-0.1, NAN], "wake_acceleration": [-0.1, NAN], "flags": [1 << 10],
    "width": [-0.1, NAN, math.inf], "side_wall_friction": [-0.1, NAN, math.inf],
}
# fields holding pairs: the bad pair and the element the error names
DEM_BAD_PAIRS = {
    "domain_min": [([NAN, 0.0], "domain_min[0]"), ([0.0, math.inf], "domain_min[1]")],
    "domain_max": [([-2e30, 0.0], "domain_max[0]"), ([1.0, NAN], "domain_max[1]")],
}
COUPLER_BAD = {
    "flags": [1 << 11], "n_exp": [-0.1, 1.1, NAN], "lookup_m": [1, 65], "lookup_dr": [0.0, NAN],
    "max_dt": [0.0, NAN], "stone_cfl": [0.0, 1.5, NAN], "drag_relaxation": [0.0, NAN], "min_dt": [-1.0, NAN], "wet_fraction_tolerance": [-1e-9, 0.6, NAN],
    "max_snapshot_interval": [0, 4097], "bandwidth": [-0.01, 1.5, NAN],
    "overflow_drag_coefficient": [0.0, 5.5, NAN], "overflow_lift_coefficient": [-0.1, 5.5, NAN],
    "overflow_band_height": [0.0, 5.5, NAN],
}
# the medium shared by flow and stones (FlowParams.medium, DEMParams.medium)
MEDIUM_BAD = {
    "rho_water": [0.0, -1.0, NAN], "rho_air": [0.0, NAN], "nu_water": [-1e-6, NAN], "nu_air": [-1e-6, NAN],
}
MEDIUM_BAD_PAIRS = {"gravity": [([NAN, -9.81], "gravity[0]"), ([0.0, math.inf], "gravity[1]")]}
# older names kept as aliases of the medium's fields: (alias, a bad value, the field the error names)
ALIASES = {
    "flow": [("rho_water", -1.0, "rho_water"), ("rho_air", NAN, "rho_air"), ("nu_water", -1e-6, "nu_water"),
             ("nu_air", NAN, "nu_air"), ("gravity_x", math.inf, "gravity[0]"), ("gravity_z", NAN, "gravity[1]")],
}
POROSITY_BAD = {
    "m": [0, 257], "n_exp": [-0.1, 1.1, NAN], "r_min": [0.0, NAN], "r_max": [0.005, NAN], "dr": [0.0, NAN],
    "max_discs": [-1],
}


def numeric_fields(p):
    """the int and float fields of a parameter struct (bools have no invalid value; enums are typed;
    aliases and read-only properties are checked through the field behind them)"""
    out = []
    for name in dir(type(p)):
        prop = getattr(type(p), name)
        if name.startswith("_") or not isinstance(prop, property) or prop.fset is None:
            continue
        if (prop.__doc__ or "").startswith("alias"):
            continue
        v = getattr(p, name)
        if isinstance(v, (int, float)) and not isinstance(v, bool):
            out.append(name)
    return out


def with_value(make, name, value):
    p = make()
    setattr(p, name, value)
    return p


CASES = [
    # (label, params factory, bad table, constructors, owner factory (None: no assignment path))
    ("flow", vofdem.FlowParams, FLOW_BAD, [fluid], fluid),
    ("dem", dem_params, DEM_BAD, [stones, lambda p: vofdem.DEMSystem(p, 2)], stones),
    ("coupler", _core.CouplerParams, COUPLER_BAD, [coupler], coupler),
    ("porosity", porosity_params, POROSITY_BAD, [mapper], None),
]


@pytest.mark.parametrize("label, make, bad, builders, owner", CASES, ids=[c[0] for c in CASES])
def test_every_numeric_field_has_invalid_values_listed(label, make, bad, builders, owner):
    # a field added later without an entry here fails this test
    assert sorted(numeric_fields(make())) == sorted(bad), label


@pytest.mark.parametrize("label, make, bad, builders, owner", CASES, ids=[c[0] for c in CASES])
def test_an_invalid_value_raises_through_every_path_and_changes_nothing(label, make, bad, builders, owner):
    obj = owner() if owner else None
    for name, values in bad.items():
        for value in values:
            p = with_value(make, name, value)
            pattern = name.replace("turbulence_", r"turbulence[._]") + " = "
            for build in builders:
                with pytest.raises(ValueError, match=pattern):
                    build(p)
            if obj is None:
                continue
            before = getattr(obj.params, name)
            with pytest.raises(ValueError, match=pattern):
                obj.params = p
            assert getattr(obj.params, name) == before, (label, name)


def test_invalid_pairs_and_walls_of_the_dem_raise_naming_the_element():
    s = stones()
    for name, cases in DEM_BAD_PAIRS.items():
        for value, named in cases:
            p = with_value(dem_params, name, value)
            with pytest.raises(ValueError, match=re_name(named)):
                stones(p)
            with pytest.raises(ValueError, match=re_name(named)):
                s.params = p
    p = dem_params()
    walls = p.walls
    walls[0].friction = -0.1
    p.walls = walls
    with pytest.raises(ValueError, match="wall friction = -0.1"):
        s.params = p
    assert s.params.walls[0].friction == pytest.approx(0.176)


def flow_with_medium(m):
    p = tank_params()
    p.medium = m
    return p


def dem_with_medium(m):
    p = dem_params()
    p.medium = m
    return p


def test_an_invalid_medium_raises_through_the_flow_and_the_stones():
    f, s = fluid(), stones()
    cases = [(name, v, name) for name, values in MEDIUM_BAD.items() for v in values]
    cases += [(name, v, named) for name, pairs in MEDIUM_BAD_PAIRS.items() for v, named in pairs]
    for name, value, named in cases:
        m = with_value(_core.Medium, name, value)
        with pytest.raises(ValueError, match=re_name(named)):
            m.validate()
        for build, owner, params in ((fluid, f, flow_with_medium(m)), (stones, s, dem_with_medium(m))):
            with pytest.raises(ValueError, match=re_name(named)):
                build(params)
            before = owner.params.medium
            with pytest.raises(ValueError, match=re_name(named)):
                owner.params = params
            assert owner.params.medium == before
    # every numeric field of the medium is listed
    listed = set(MEDIUM_BAD) | set(MEDIUM_BAD_PAIRS)
    assert {n for n in dir(_core.Medium) if not n.startswith("_") and isinstance(getattr(_core.Medium, n), property)} \
        == listed


def test_the_older_names_reach_the_medium_and_are_checked():
    # FlowParams' older names of the medium's fields (docs/vof_grid.md); DEMParams has none left
    for alias, value, named in ALIASES["flow"]:
        p = with_value(vofdem.FlowParams, alias, value)
        with pytest.raises(ValueError, match=re_name(named)):
            fluid(p)
    p = vofdem.FlowParams()
    p.rho_water, p.gravity_x = 1025.0, 0.5
    assert (p.medium.rho_water, p.medium.gravity[0]) == (1025.0, 0.5)
    assert not hasattr(vofdem.DEMParams(), "fluid_density") and not hasattr(vofdem.DEMParams(), "gravity")


def re_name(name):
    return name.replace("[", r"\[").replace("]", r"\]") + " = "


@pytest.mark.parametrize("label, make, bad, builders, owner", CASES, ids=[c[0] for c in CASES])
def test_editing_params_in_place_changes_nothing(label, make, bad, builders, owner):
    obj = (owner or builders[0])()
    for name in bad:
        before = getattr(obj.params, name)
        changed = before + 1 if isinstance(before, int) else (before * 0.5 if before else 0.25)
        setattr(obj.params, name, changed)  # on a copy
        assert getattr(obj.params, name) == before, (label, name)
    # the copy is a copy: assigned back, a valid edit takes effect
    if owner is not None:
        p = obj.params
        name = {"flow": "cfl", "dem": "friction_stone", "coupler": "stone_cfl"}[label]
        setattr(p, name, 0.3)
        obj.params = p
        assert getattr(obj.params, name) == 0.3


def test_an_in_place_cfl_does_not_reach_the_step():
    f = fluid()
    f.fill_water_below(0.03)
    f.params.cfl = 0.5  # a copy: the step keeps 0.4
    f.advance(0.01)
    assert f.params.cfl == 0.4
    p = f.params
    p.cfl = 7.0
    with pytest.raises(ValueError, match=r"cfl = 7 must lie in \(0, 0.5\]"):
        f.params = p


def test_assigned_params_rebuild_what_depends_on_them():
    f = fluid()
    f.fill_water_box(0.0, 0.03, 0.0, 0.05)  # a dam break: every solve has work to do
    f.advance(0.005)
    assert f.last_pressure_stats.iterations > 0  # multigrid-CG
    f.params.pressure_solver = _core.PressureSolverKind.EIGEN_DIRECT  # a copy: nothing changes
    f.advance(0.01)
    assert f.last_pressure_stats.iterations > 0
    p = f.params
    p.pressure_solver = _core.PressureSolverKind.EIGEN_DIRECT
    f.params = p
    f.advance(0.015)
    assert f.last_pressure_stats.iterations == 0  # the direct solver
    # one owner per flag: the coupler's parameters never rewrite the flow's flags
    c = coupler()
    flags = c.fluid.params.flags
    assert not flags & vofdem.FlowEffect.RELATIVE_VELOCITY
    cp = c.params
    cp.flags = _core.COUPLE_ONE_WAY
    c.params = cp
    assert c.fluid.params.flags == flags
