"""Each option is written once: every scene key that feeds a field of the core's parameter structs
(builder.py) has the core's default as its own, so that the C++ and Python users of the solvers and the
scenes start from the same model. Each key is also moved to another allowed value to show that it is the
key feeding that field (a table entry that feeds nothing fails)."""
import dataclasses
import math

import pytest

from vofdem import _core, builder
from vofdem.scene import Scene, _SECTIONS

# scene key -> (struct, field, bit): the field of FlowParams ('flow'), DEMParams ('dem'), CouplerParams
# ('coupler') or WeirSpec ('weir') it feeds; a flag key feeds one bit of the struct's flags
FLOW, DEM, COUPLER, WEIR = "flow", "dem", "coupler", "weir"
FEEDS = {
    "flume.width": (FLOW, "flume_width", None),
    "flume.outflow": (FLOW, "outlet", None),
    "stones.k1": (FLOW, "k1", None),
    "stones.k2": (FLOW, "k2", None),
    "numerics.cfl": (FLOW, "cfl", None),
    "numerics.initial_dt": (FLOW, "initial_dt", None),
    "numerics.max_dt_growth": (FLOW, "max_dt_growth", None),
    "numerics.pressure_solver": (FLOW, "pressure_solver", None),
    "numerics.pressure_tolerance": (FLOW, "pressure_tol", None),
    "numerics.time_scheme": (FLOW, "time_scheme", None),
    "numerics.step_control": (FLOW, "step_control", None),
    "numerics.turbulence_scheme": (FLOW, "turbulence_time_scheme", None),
    "numerics.turbulence_cfl": (FLOW, "turbulence_cfl", None),
    "numerics.turbulence_production": (FLOW, "turbulence_production", None),
    "numerics.turbulence_pore_strain": (FLOW, "turbulence_pore_strain", None),
    "numerics.turbulence_production_limit": (FLOW, "turbulence_production_limit", None),
    "numerics.turbulence_step_limit": (FLOW, "turbulence_limit_step", None),
    "numerics.viscous_scheme": (FLOW, "viscous_scheme", None),
    "numerics.viscous_bound": (FLOW, "viscous_bound", None),
    "numerics.viscous_substeps": (FLOW, "viscous_substeps", None),
    "numerics.inlet_profile": (FLOW, "inlet_profile", None),
    "effects.turbulence": (FLOW, "flags", "FlowEffect.TURBULENCE"),
    "effects.porous_resistance": (FLOW, "flags", "FlowEffect.POROUS_RESISTANCE"),
    "stones.added_mass_coefficient": (DEM, "added_mass_coefficient", None),
    "stones.friction_stone": (DEM, "friction_stone", None),
    "stones.friction_wall": (DEM, "side_wall_friction", None),
    "stones.rolling_friction": (DEM, "rolling_friction_stone", None),
    "stones.rolling_friction_wall": (DEM, "rolling_friction_wall", None),
    "stones.rolling_damping": (DEM, "rolling_damping", None),
    "numerics.dem_dt": (DEM, "dt", None),
    "numerics.dem_contact_steps": (DEM, "contact_steps", None),
    "effects.rotation": (DEM, "flags", "DEMFlag.ROTATION"),
    "effects.friction": (DEM, "flags", "DEMFlag.FRICTION"),
    "effects.rolling_resistance": (DEM, "flags", "DEMFlag.ROLLING_RESISTANCE"),
    "effects.added_mass": (DEM, "flags", "DEMFlag.ADDED_MASS"),
    "effects.buoyancy": (DEM, "flags", "DEMFlag.BUOYANCY"),
    "stones.n_exp": (COUPLER, "n_exp", None),
    "stones.drag_model": (COUPLER, "stone_drag", None),
    "numerics.max_dt": (COUPLER, "max_dt", None),
    "numerics.lookup_m": (COUPLER, "lookup_m", None),
    "numerics.drag_exchange": (COUPLER, "implicit_drag", None),
    "numerics.wet_fraction_tolerance": (COUPLER, "wet_fraction_tolerance", None),
    "numerics.coupling_mapping": (COUPLER, "mapping", None),
    "numerics.coupling_bandwidth": (COUPLER, "bandwidth", None),
    "numerics.overflow_load": (COUPLER, "flags", "CouplerEffect.OVERFLOW_LOAD"),
    "numerics.overflow_drag_coefficient": (COUPLER, "overflow_drag_coefficient", None),
    "numerics.overflow_lift_coefficient": (COUPLER, "overflow_lift_coefficient", None),
    "numerics.overflow_band_height": (COUPLER, "overflow_band_height", None),
    "numerics.porosity_method": (COUPLER, "flags", "CouplerEffect.LOOKUP_POROSITY"),
    "effects.dem": (COUPLER, "flags", "CouplerEffect.DEM"),
    "effects.two_way": (COUPLER, "flags", "CouplerEffect.POROSITY"),
    "effects.drag": (COUPLER, "flags", "CouplerEffect.DRAG"),
    "effects.pressure_gradient": (COUPLER, "flags", "CouplerEffect.PRESSURE_GRADIENT"),
    "weir.height": (WEIR, "height", None),
    "weir.crest_length": (WEIR, "crest", None),
    "weir.upstream_slope_deg": (WEIR, "slope_up_deg", None),
    "weir.downstream_slope_deg": (WEIR, "slope_down_deg", None),
    "weir.toe_x": (WEIR, "x_toe", None),
    "stones.diameter": (WEIR, "d_mean", None),
    "stones.diameter_spread": (WEIR, "d_spread", None),
    "stones.density": (WEIR, "density", None),
    "stones.shape": (WEIR, "shape", None),
    "stones.compaction_friction": (WEIR, "compaction_friction", None),
}
# the fields the core leaves unset (0, refused by its check with the key named): the stones' material has
# no default in the core and comes from the scene alone
REQUIRED_BY_THE_CORE = {WEIR: {"d_mean", "density"}}
# keys another key must be given with before they can move
GIVEN_WITH = {"flume.outflow": {"flume.tailwater_level": 0.2},
              "stones.compaction_friction": {"stones.shape": "clump"}}  # the plane's packing has no compaction

# the fields a scene sets from its geometry or the run (no option of their own), which may differ from
# the core's defaults: the medium's gravity along the bed, the end walls and removal box of the stones,
# the inlet (a scene always feeds its discharge there), the stones in the water, the packing's seed
SET_BY_THE_SCENE = {
    FLOW: {"medium", "gravity_x", "gravity_z", "inlet"},
    DEM: {"medium", "gravity", "walls", "domain_min", "domain_max", "submerged", "water_density", "fluid_density"},
    COUPLER: set(),
    WEIR: {"seed", "polygon"},
}


def _structs(scene):
    return {FLOW: builder.flow_params(scene), DEM: builder.dem_params(scene), COUPLER: builder.coupler_params(scene),
            WEIR: builder.weir_spec(scene)}


def _defaults():
    return {FLOW: _core.FlowParams(), DEM: _core.DEMParams(), COUPLER: _core.CouplerParams(), WEIR: _core.WeirSpec()}


def _bit(name):
    cls, member = name.split(".")
    return int(getattr(getattr(_core, cls), member))


def _read(struct, field, bit):
    v = getattr(struct, field)
    return bool(int(v) & _bit(bit)) if bit else v


def _fields(struct):
    return [k for k in dir(struct) if not k.startswith("_") and not callable(getattr(struct, k))]


def _same(a, b):
    if isinstance(a, float) or isinstance(b, float):
        return math.isclose(float(a), float(b), rel_tol=0.0, abs_tol=0.0)
    return a == b


def _other_value(key):
    """Another allowed value of a key (its dataclass field's metadata), for the feeding check."""
    section, name = key.split(".")
    f = {f.name: f for f in dataclasses.fields(_SECTIONS[section])}[name]
    md, default = f.metadata, getattr(Scene(), section).__getattribute__(name)
    if "choices" in md:
        return next(c for c in md["choices"] if c != default)
    if "flag" in md:
        return not default
    if default is None:  # an optional length left unset (the core's own choice)
        return 0.05
    lo, hi = md["lo"], md["hi"]
    v = 0.9 * default if default > 0 else lo + 0.1 * (min(hi, lo + 1.0) - lo)
    v = v if v > lo else 0.5 * (lo + min(hi, 2.0 * default + 1.0))
    return int(round(v)) if isinstance(default, int) and v != int(v) and int(round(v)) != default else v


@pytest.mark.parametrize("key", sorted(FEEDS))
def test_scene_default_equals_the_core_default(key):
    what, field, bit = FEEDS[key]
    fed = _read(_structs(Scene())[what], field, bit)
    core = _read(_defaults()[what], field, bit)
    if field in REQUIRED_BY_THE_CORE.get(what, ()):
        assert core == 0.0 and fed > 0.0, f"{key}: the core's {field} = {core!r} (must be unset), the scene's {fed!r}"
        return
    assert _same(fed, core), (f"{key}: the scene's default gives {what} {field}{'/' + bit if bit else ''} = {fed!r}, "
                              f"the core's default is {core!r}")


@pytest.mark.parametrize("key", sorted(FEEDS))
def test_key_feeds_its_field(key):
    what, field, bit = FEEDS[key]
    moved = Scene()
    for k, v in GIVEN_WITH.get(key, {}).items():
        moved = moved.with_value(k, v)
    moved = moved.with_value(key, _other_value(key))
    before = _read(_structs(Scene())[what], field, bit)
    after = _read(_structs(moved)[what], field, bit)
    assert not _same(before, after), f"{key} moved to {_other_value(key)!r} leaves {what} {field} at {after!r}"


@pytest.mark.parametrize("field", sorted(REQUIRED_BY_THE_CORE[WEIR]))
def test_the_core_refuses_an_unset_stone_field_naming_it(field):
    spec = builder.weir_spec(Scene())
    setattr(spec, field, getattr(_core.WeirSpec(), field))
    with pytest.raises(ValueError, match=field):
        _core.pack_weir(spec)


@pytest.mark.parametrize("what", [FLOW, DEM, COUPLER, WEIR])
def test_no_other_field_differs_from_the_core(what):
    """A field the default scene sets to another value than the core's default is fed by a key of FEEDS
    (and then equal, above) or is one the scene sets from its geometry: nothing is left out of the table."""
    fed, core = _structs(Scene())[what], _defaults()[what]
    listed = {f for w, f, bit in FEEDS.values() if w == what and bit is None}
    differ = [k for k in _fields(core) if k not in SET_BY_THE_SCENE[what] and k not in listed and k != "flags"
              and not _same(getattr(fed, k), getattr(core, k))]
    assert not differ, f"{what}: fields the default scene sets away from the core's defaults: {differ}"
    if hasattr(core, "flags"):
        bits = 0
        for w, f, bit in FEEDS.values():
            bits |= _bit(bit) if w == what and bit else 0
        other = (int(fed.flags) ^ int(core.flags)) & ~bits
        assert other == 0, f"{what}: flags bits {other:#x} differ from the core's defaults with no scene key"
