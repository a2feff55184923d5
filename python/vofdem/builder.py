"""From a scene to solver objects: the DEM of the stones (packed weir), the flow solver, the coupler.

Each function maps the scene's parameters (SI units, see scene.py) onto the parameter structs of the
C++ core; no physics lives here.
"""
from __future__ import annotations

from contextlib import contextmanager
from contextvars import ContextVar
from typing import Optional

import numpy as np

from . import _core
from .scene import Scene
from .stone_models import front

import math

# the core's water and gravity (Medium) are the one source of their values
WATER_DENSITY = _core.Medium().rho_water  # kg/m^3, 998.2 at 20 C
GRAVITY = -_core.Medium().gravity[1]  # m/s^2, 9.81


# each struct's effect bits, by the scene's condition that sets them (the bits always on are named in
# the struct's builder); one table per struct, so that a key's mapping is written once
_FLOW_EFFECTS = {
    "POROUS_RESISTANCE": lambda s: s.effects.porous_resistance,
    "TURBULENCE": lambda s: s.effects.turbulence,
    # resistance relative to the stones' velocity: the stones move the flow's porosity only two-way
    "RELATIVE_VELOCITY": lambda s: s.effects.relative_velocity_resistance and s.effects.two_way,
}
_DEM_EFFECTS = {
    "ROTATION": lambda s: s.effects.rotation,
    "FRICTION": lambda s: s.effects.friction,
    "ROLLING_RESISTANCE": lambda s: s.effects.rolling_resistance,
    "ADDED_MASS": lambda s: s.effects.added_mass,
    "BUOYANCY": lambda s: s.effects.buoyancy,
    "EXTERNAL_FORCE": lambda s: s.effects.drag or s.effects.pressure_gradient,
}
_COUPLER_EFFECTS = {
    "DEM": lambda s: s.effects.dem,
    "POROSITY": lambda s: s.effects.two_way,
    "DRAG": lambda s: s.effects.drag,
    "PRESSURE_GRADIENT": lambda s: s.effects.pressure_gradient,
    "WET_FRACTION": lambda s: s.effects.buoyancy or s.effects.added_mass,
    "LOOKUP_POROSITY": lambda s: s.numerics.porosity_method == "lookup",
    "OVERFLOW_LOAD": lambda s: s.numerics.overflow_load == "drag_lift",
}


def _flags(enum, always, effects, scene: Scene) -> int:
    """The bits of `enum` always on and those whose condition holds in the scene, as an int."""
    names = list(always) + [name for name, on in effects.items() if on(scene)]
    flags = 0
    for name in names:
        flags |= int(getattr(enum, name))
    return flags


def gravity(scene: Scene):
    """(g_x, g_z) [m/s^2] in flume coordinates: along and normal to a bed of slope S0 = sin(angle)."""
    s = scene.flume.bed_slope
    return GRAVITY * s, -GRAVITY * math.sqrt(1.0 - s * s)


def medium(scene: Scene):
    """The scene's Medium: the core's water and air, gravity along a sloping bed; the flow owns it and a
    Coupler hands it to the stones."""
    m = _core.Medium()
    m.gravity = list(gravity(scene))
    return m


def dem_params(scene: Scene, submerged: bool = True):
    """DEMParams of a scene: contact law, friction, added mass, walls, removal box, effect flags.
    submerged: in the medium's water (False: dry, as the packing)."""
    st = scene.stones
    p = _core.DEMParams()
    p.medium = medium(scene)
    p.submerged = submerged
    p.added_mass_coefficient = st.added_mass_coefficient
    p.dt = scene.numerics.dem_dt
    p.contact_steps = scene.numerics.dem_contact_steps
    p.friction_stone = st.friction_stone
    p.side_wall_friction = st.friction_wall  # the side walls of 3D stones, as the bed and the end wall
    p.rolling_friction_stone = st.rolling_friction
    p.rolling_friction_wall = st.rolling_friction_wall
    p.rolling_damping = st.rolling_damping
    # the bed and the upstream end wall; downstream the stones leave over the outflow end
    p.walls = [_core.DEMWall(point=[0.0, 0.0], normal=[0.0, 1.0], friction=st.friction_wall),
               _core.DEMWall(point=[0.0, 0.0], normal=[1.0, 0.0], friction=st.friction_wall)]
    # stones leaving the flume (past its end, or falling below the bed level there) are removed
    p.domain_min = [-0.5 * scene.flume.length, -0.5 * scene.flume.height]
    p.domain_max = [scene.flume.length, 4.0 * scene.flume.height]
    p.flags = _flags(_core.DEMFlag, ("GRAVITY", "DAMPING", "REMOVAL"), _DEM_EFFECTS, scene)
    # 3D stones lie across the flume between its side walls
    if front(st.shape).dimensions == 3:
        p.width = scene.flume.width
    if is_graded(scene):
        p.stiffness_normal, p.dt = graded_contact(scene, p)
    return p


def is_graded(scene: Scene) -> bool:
    """Whether the packed stones come from sieve curves (the core's or a zone's)."""
    return not scene.stones.positions and (scene.stones.grading() is not None or bool(scene.zones))


def _sources_sizes(scene: Scene):
    """(d50 [m], smallest d [m]) of each size source of a packed scene: the zones', then the core's."""
    out = [(zn.grading().d(0.5), zn.grading().d_min) for zn in scene.zones]
    g, st = scene.stones.grading(), scene.stones
    out.append((g.d(0.5), g.d_min) if g is not None else (st.diameter, st.diameter * (1.0 - st.diameter_spread)))
    return out


def graded_contact(scene: Scene, params):
    """(k_n [N/m], DEM step [s]) of a graded scene. The automatic stiffness (dem_contact.h) is tied to the
    mean stone, and a sieve curve's smallest stones are much lighter than its mean: at the scene's
    numerics.dem_dt their contacts would be refused as unstable (DEMSystem::stable_dt). So the stiffness is
    that of `dem_contact_steps` steps of `dem_dt` per contact of two stones of the finest d50 among the
    core and the zones, k_n = (m50 / 2) (pi / (steps dt))^2 (the paper's rule, on d50), and the DEM step is
    the scene's dem_dt, lowered where needed to 0.98 of the stable step of the smallest stone the
    gradings hold (computed by the DEMSystem itself)."""
    n = scene.numerics
    sizes = _sources_sizes(scene)
    d_ref, d_min = min(d50 for d50, _ in sizes), min(dm for _, dm in sizes)
    m_ref = scene.stones.density * math.pi * d_ref ** 3 / 6.0
    kn = 0.5 * m_ref * (math.pi / (n.dem_contact_steps * n.dem_dt)) ** 2
    params.stiffness_normal = kn
    x, z = 0.5 * scene.flume.length, 0.5 * scene.flume.height  # two stones apart, inside the flume
    two = _core.DEMSystem(params, np.array([[x, z], [x + 4.0 * d_min, z]]), np.full(2, 0.5 * d_min),
                          np.full(2, scene.stones.density), [0, 0])
    stable = float(two.stable_dt())
    return kn, min(n.dem_dt, 0.98 * stable)


def stone_shapes(scene: Scene, diameters, seed=None):
    """The shapes of stones of the scene's model with these nominal diameters [m], drawn from `seed`
    (default the scene's) with the scene's shape options (stone_models.py); None for stones without
    shapes of their own (discs)."""
    seed = scene.seed if seed is None else int(seed)
    return front(scene.stones.shape).draw_shapes(scene.stones, diameters, seed)


def stone_system(scene: Scene, params, pos, diameters, fixed, shapes=None):
    """A DEMSystem of the scene's stone model at centres pos (n, 2) [m] with (nominal) diameters [m] and
    fixed flags; the one place that turns positions and sizes into stones, so that every experiment on
    the stones (calibration.py) builds them the way the weir is built. Stones with shapes of their own
    take `shapes` (stone_shapes') or have them drawn from the scene's seed, unrotated."""
    pos = np.asarray(pos, float).reshape(-1, 2)
    d = np.asarray(diameters, float)
    sys_ = _core.DEMSystem(params, pos, 0.5 * d, np.full(len(d), scene.stones.density), [int(f) for f in fixed])
    front(scene.stones.shape).install(sys_, shapes if shapes is not None else stone_shapes(scene, d))
    return sys_


def _explicit_stones(scene: Scene):
    """DEMSystem of the scene's explicit stones (discs or polygons of those nominal diameters, unrotated);
    the fixed ones are those whose lowest point touches the bed."""
    st = scene.stones
    pos = np.asarray(st.positions, float)
    d = np.asarray(st.diameters if st.diameters else [st.diameter] * len(pos), float)
    shapes = stone_shapes(scene, d)
    low = front(st.shape).lowest(pos, d, shapes)
    fixed = (low <= 1e-9) if st.fix_bottom_layer else np.zeros(len(pos), bool)
    return stone_system(scene, dem_params(scene), pos, d, fixed, shapes)


def dem_step_hint(message: str) -> str:
    """A DEM step refused as unstable, said in the scene's terms (the C++ message names DEMParams)."""
    if "stable step" not in message:
        return message
    return (message + "; in the scene: lower numerics.dem_dt, or raise numerics.dem_contact_steps (softer "
            "contacts), or both with their product kept (the same stiffness in more steps)")


def packing_route(scene: Scene) -> str:
    """How the scene's weir is packed: 'explicit' stones, 'trapezoid' (pack_weir: a trapezoid, or an outline
    that is one, with sizes uniform in d +- spread and no zones) or 'outline' (outline_packing.py)."""
    from .outline import as_trapezoid

    st, w = scene.stones, scene.weir
    if st.positions:
        return "explicit"
    if is_graded(scene) or (w.outline and as_trapezoid(w.outline) is None):
        return "outline"
    return "trapezoid"


def _pack_outline(scene: Scene, params):
    """(DEMSystem, OutlinePackingReport) of the outline packer (outline_packing.py) for the scene."""
    from .outline_packing import grading_source, pack_outline, uniform_source

    rng = np.random.default_rng(scene.seed)
    st = scene.stones
    sources = [grading_source(zn.grading(), rng) for zn in scene.zones]
    g = st.grading()
    sources.append(grading_source(g, rng) if g is not None else uniform_source(st.diameter, st.diameter_spread, rng))
    return pack_outline(scene.weir.body(), scene.zones, sources, params, st.density)


def build_stones(scene: Scene):
    """(DEMSystem, report): the weir packed under gravity from the scene's seed (pack_weir for a trapezoid
    of uniform sizes, outline_packing.pack_outline for other outlines, sieve curves and zones), or the
    scene's explicit stones. `report` is the WeirPackingReport or OutlinePackingReport (None for
    explicit stones)."""
    st = scene.stones
    route = packing_route(scene)
    if route == "explicit":
        return _explicit_stones(scene), None
    # packed dry (the rest state does not depend on the fluid), then given the run's parameters
    pack = dem_params(scene, submerged=False)
    pack.flags = int(pack.flags & ~_core.DEMFlag.EXTERNAL_FORCE)
    try:
        if route == "outline":
            sys_, report = _pack_outline(scene, pack)
        else:
            sys_, report = _core.pack_weir(weir_spec(scene), pack)
    except ValueError as e:
        raise ValueError(dem_step_hint(str(e))) from None
    sys_.params = dem_params(scene)
    if not st.fix_bottom_layer:
        sys_.stone_fixed[:] = 0
    return sys_, report


def flow_params(scene: Scene):
    """FlowParams of a scene: fluid, gravity along a sloping bed, CFL, porous law, boundaries, effects."""
    f, n, st = scene.flume, scene.numerics, scene.stones
    p = _core.FlowParams()
    p.medium = medium(scene)
    p.cfl = n.cfl
    p.max_dt = n.max_dt
    p.initial_dt = n.initial_dt
    p.max_dt_growth = n.max_dt_growth
    p.k1, p.k2 = st.k1, st.k2
    p.flume_width = f.width
    p.pressure_solver = {"multigrid_cg": _core.PressureSolverKind.MULTIGRID_CG,
                         "direct": _core.PressureSolverKind.EIGEN_DIRECT}[n.pressure_solver]
    p.pressure_tol = n.pressure_tolerance
    p.viscous_substeps = n.viscous_substeps
    p.viscous_scheme = {"implicit_vertical": _core.ViscousScheme.IMPLICIT_VERTICAL,
                        "implicit_vertical_from_start": _core.ViscousScheme.IMPLICIT_VERTICAL_FROM_START,
                        "explicit": _core.ViscousScheme.EXPLICIT,
                        "implicit": _core.ViscousScheme.IMPLICIT}[n.viscous_scheme]
    p.viscous_bound = {"energy": _core.ViscousBound.ENERGY, "row_sum": _core.ViscousBound.ROW_SUM}[n.viscous_bound]
    p.time_scheme = {"adams_bashforth2": _core.MomentumTimeScheme.ADAMS_BASHFORTH2,
                     "euler": _core.MomentumTimeScheme.EULER}[n.time_scheme]
    p.step_control = {"this_step": _core.StepControl.THIS_STEP, "two_steps": _core.StepControl.TWO_STEPS}[n.step_control]
    p.turbulence_time_scheme = {"vertical_lines": _core.KEpsilonTimeScheme.VERTICAL_LINES,
                                "point_implicit": _core.KEpsilonTimeScheme.POINT_IMPLICIT,
                                "alternating_lines": _core.KEpsilonTimeScheme.ALTERNATING_LINES}[n.turbulence_scheme]
    p.turbulence_limit_step = n.turbulence_step_limit
    p.turbulence_cfl = n.turbulence_cfl
    p.turbulence_production = {"strain": _core.KEpsilonProduction.STRAIN,
                               "kato_launder": _core.KEpsilonProduction.KATO_LAUNDER}[n.turbulence_production]
    p.turbulence_production_limit = n.turbulence_production_limit
    p.turbulence_pore_strain = {"neighbours": _core.KEpsilonPoreStrain.NEIGHBOURS,
                                "local": _core.KEpsilonPoreStrain.LOCAL,
                                "filtered": _core.KEpsilonPoreStrain.FILTERED}[n.turbulence_pore_strain]
    if n.turbulence_pore_strain == "filtered":
        p.turbulence_pore_filter_length = n.turbulence_pore_filter or stone_diameter(scene)
    p.inlet = _core.InletBoundary.DISCHARGE
    p.inlet_profile = {"equivalent_depth": _core.InletProfile.EQUIVALENT_DEPTH,
                       "water_fraction": _core.InletProfile.WATER_FRACTION}[n.inlet_profile]
    if f.outflow == "tailwater":
        p.outlet = _core.OutletBoundary.TAILWATER
        p.tailwater_level = f.tailwater_level
    else:
        p.outlet = _core.OutletBoundary.FREE_OVERFALL
    p.flags = _flags(_core.FlowEffect, ("FREE_SURFACE", "VISCOSITY", "GRAVITY", "CONVECTION"), _FLOW_EFFECTS, scene)
    return p


def build_grid(scene: Scene):
    """The scene's Grid2D: cells of about dx along the flume (a whole number over its length), dz_bed
    up to bed_layer_height, then dz."""
    g, f = scene.grid, scene.flume
    nx = max(4, int(round(f.length / g.dx)))
    top = g.bed_layer_height if g.bed_layer_height > 0 else 0.0
    return _core.Grid2D.graded(nx=nx, length_x=f.length, height_z=f.height, dz=g.dz, dz_bed=g.dz_bed, z_bed_top=top,
                               merge_fraction=g.merge_fraction)


def upstream_level(scene: Scene, discharge: float) -> float:
    """Water level [m] upstream of the weir at `discharge` Q [m^3/s], from the critical-depth relation of
    a broad-crested weir, H = 1.5 (q^2 / g)^(1/3), q = Q / B: an estimate (the Maeno weir's highest
    surface at 25 l/s, B = 0.5 m: 0.325 m measured against 0.345 m)."""
    q = discharge / scene.flume.width
    return scene.weir.height + 1.5 * (q * q / GRAVITY) ** (1.0 / 3.0)


def peak_discharge(scene: Scene) -> float:
    """The largest discharge Q [m^3/s] of the scene's hydrograph over its run: a piecewise-linear table
    peaks at one of its times or at the run's end."""
    t, q = (np.asarray(v, float) for v in scene.hydrograph.table(scene.duration))
    at = np.append(t[t <= scene.duration], scene.duration)
    return float(np.max(np.interp(at, t, q)))


def initial_level(scene: Scene) -> float:
    """Water level [m] upstream of the weir at the start discharge (`upstream_level`): only a starting
    guess for the spin-up."""
    return upstream_level(scene, scene.hydrograph.discharge(0.0))


def stone_diameter(scene: Scene) -> float:
    """The stones' median diameter [m]: the grading's d50, else the stones' diameter."""
    g = scene.stones.grading()
    return g.d(0.5) if g is not None and not scene.stones.positions else scene.stones.diameter


def build_fluid(scene: Scene):
    """VOFGrid of a scene: grid, parameters, inflow hydrograph, water upstream of the crest up to
    `initial_level` (porosity is left to the coupler, which computes it from the stones: flume.initial_water)."""
    fluid = _core.VOFGrid(build_grid(scene), flow_params(scene))
    t, q = scene.hydrograph.table(scene.duration)
    fluid.discharge = _core.DischargeTable([float(v) for v in t], [float(v) for v in q])
    fluid.cell_stone_diameter[...] = stone_diameter(scene)
    fluid.fill_water_box(0.0, scene.weir.x_crest_down, 0.0, initial_level(scene))
    fluid.set_hydrostatic_pressure()
    return fluid


def _trapezoid(scene: Scene) -> dict:
    """The weir's trapezoid keys (toe_x, height, crest_length, both slopes): the scene's, or its outline's
    when the outline is a trapezoid."""
    from .outline import as_trapezoid

    w = scene.weir
    trap = dict(toe_x=w.toe_x, height=w.height, crest_length=w.crest_length, upstream_slope_deg=w.upstream_slope_deg,
                downstream_slope_deg=w.downstream_slope_deg)
    if w.outline:  # an outline that is a trapezoid: the same generator as the trapezoid's keys
        trap = as_trapezoid(w.outline) or trap
    return trap


def weir_spec(scene: Scene):
    """WeirSpec of the scene's weir: its trapezoid on the bed z = 0 (_trapezoid) and its stones (sizes,
    density, seed, shape), what pack_weir packs."""
    t, st = _trapezoid(scene), scene.stones
    spec = _core.WeirSpec()
    spec.height, spec.crest = t["height"], t["crest_length"]
    spec.slope_up_deg, spec.slope_down_deg = t["upstream_slope_deg"], t["downstream_slope_deg"]
    spec.x_toe, spec.z_bed = t["toe_x"], 0.0
    spec.d_mean, spec.d_spread, spec.density, spec.seed = st.diameter, st.diameter_spread, st.density, scene.seed
    spec.shape = st.shape
    spec.compaction_friction = -1.0 if st.compaction_friction is None else st.compaction_friction
    front(st.shape).spec_options(st, spec)
    return spec


def solid_fraction(scene: Scene, stones) -> float:
    """phi [-]: the 2D area fraction of the weir's outline covered by the stones (discs or polygons), 1 minus the
    packing porosity that pack_weir reports (weir_porosity, sampled every 2 mm; for an outline that is
    not a trapezoid, outline_packing.body_porosity, the same sampling, of discs; the models the outline
    packer cannot place come with a trapezoid only, scene.py)."""
    if scene.weir.outline and front(scene.stones.shape).outline_packer:
        from .outline_packing import body_porosity

        act = np.asarray(stones.stone_active, bool)
        pos = np.asarray(stones.stone_pos, float).reshape(-1, 2)[act]
        return 1.0 - body_porosity(scene.weir.body(), pos, np.asarray(stones.stone_radius, float)[act])
    return 1.0 - float(_core.weir_porosity(stones, weir_spec(scene)))


def disc_porosity(scene: Scene, stones):
    """(n_s, phi): the porosity inside each disc used in eq. (11), and the packing's solid fraction phi
    (None for the paper's mapping, which does not need it).

    'paper': n_s = n_exp. Eq. (11) then maps a mean porosity 1 - phi (1 - n_exp) over the weir: the
    voids between the discs (1 - phi, ~0.2 for 2D discs) and n_exp again inside them.
    'bulk': n_s = 1 - (1 - n_exp) / phi, so that the weir's mean mapped porosity is the measured n_exp;
    phi from the packed stones, computed once at build.
    3D stones (spheres): n_s = 0 whatever the mapping, their volume mapped exactly (CouplerParams.n_exp = 0)."""
    st = scene.stones
    # 3D stones map their volume: the porosity is the true void fraction, with no porosity inside them
    if front(st.shape).dimensions == 3:
        return 0.0, None
    if st.porosity_mapping == "paper":
        return st.n_exp, None
    phi = solid_fraction(scene, stones)
    if not phi >= 1.0 - st.n_exp or phi <= 0.0:
        n_s = 1.0 - (1.0 - st.n_exp) / phi if phi > 0.0 else float("-inf")
        raise ValueError(f"stones.porosity_mapping = 'bulk': the stones cover phi = {phi:.4f} of the weir's outline, "
                         f"below 1 - stones.n_exp = {1.0 - st.n_exp:.4f}, so the discs' inner porosity "
                         f"n_s = 1 - (1 - n_exp) / phi = {n_s:.4f} would be negative (allowed: phi >= 1 - n_exp); "
                         f"use porosity_mapping = 'paper' or a larger n_exp")
    return 1.0 - (1.0 - st.n_exp) / phi, phi


_STONE_DRAG = {"sphere": "SPHERE", "bed": "BED"}


def coupler_params(scene: Scene, n_exp: float | None = None):
    """CouplerParams of a scene: which couplings run, the drag model, n_exp, porosity method. n_exp:
    the porosity inside each disc of eq. (11) (disc_porosity; default the scene's n_exp)."""
    p = _core.CouplerParams()
    p.n_exp = scene.stones.n_exp if n_exp is None else float(n_exp)
    p.stone_drag = getattr(_core.StoneDragModel, _STONE_DRAG[scene.stones.drag_model])
    p.max_dt = scene.numerics.max_dt
    p.implicit_drag = scene.numerics.drag_exchange == "implicit"
    p.lookup_m = scene.numerics.lookup_m
    p.wet_fraction_tolerance = scene.numerics.wet_fraction_tolerance
    p.mapping = {"cell": _core.CouplingMapping.CELL, "kernel": _core.CouplingMapping.KERNEL}[scene.numerics.coupling_mapping]
    # unset: 0, the coupler's own default (the stones' mean nominal diameter)
    p.bandwidth = scene.numerics.coupling_bandwidth or 0.0
    p.overflow_drag_coefficient = scene.numerics.overflow_drag_coefficient
    p.overflow_lift_coefficient = scene.numerics.overflow_lift_coefficient
    p.overflow_band_height = scene.numerics.overflow_band_height
    p.flags = _flags(_core.CouplerEffect, ("FLUID", "CHECKS"), _COUPLER_EFFECTS, scene)
    return p


def build_simulation(scene: Scene, packing: Optional[dict] = None, settle: Optional[bool] = None):
    """The coupled simulation of a scene: the flow (build_fluid), the packed weir (build_stones) and the
    Coupler owning both, with the inflow hydrograph set and the porosity mapped from the stones.
    packing: a dict that receives the packing's report under 'report' (None for explicit stones), and the
    settling's (settle_stones) under 'settle'. settle: the stones settle in the still water
    (settle_stones); None: as the scene says (hydrograph.settle_in_still_water); a resumed run passes False.
    Within `resumed_from`, the stones are a checkpoint's (checkpoint_stones) and the weir is not packed."""
    fluid = build_fluid(scene)
    resumed = _RESUMED.get()
    if resumed is None:
        stones, report = build_stones(scene)
        if packing is not None:
            packing["report"] = report
        n_s, _ = disc_porosity(scene, stones)
    else:  # no packing report: the run's first build wrote what it reports
        stones, n_s = checkpoint_stones(scene, resumed[0]), resumed[1]
    sim = _core.Coupler(fluid, stones, coupler_params(scene, n_s))
    t, q = scene.hydrograph.table(scene.duration)
    sim.set_inflow_table([float(v) for v in t], [float(v) for v in q])
    # 'rest': the pores below the level hold water; keeping the box's volume instead piles the water the
    # stones displace over the weir, up to the domain's top (0.385 m in the Maeno scene)
    sim.update_porosity(keep_water_volume=scene.flume.initial_water == "displaced")
    if scene.hydrograph.settle_in_still_water if settle is None else settle:
        report = settle_stones(sim, scene)
        if packing is not None:
            packing["settle"] = report
    return sim


# a resumed run's (checkpoint state, disc porosity n_s [-]) while it builds (resumed_from)
_RESUMED: ContextVar = ContextVar("vofdem_resumed", default=None)


@contextmanager
def resumed_from(state: dict, n_s: float):
    """Within it, build_simulation takes the stones from a checkpoint's state (checkpoint_stones) and eq. (11)'s
    porosity inside each stone n_s [-] (the coupler's n_exp the run was built with) instead of packing the weir
    (10 CPU-min for a clump weir at B = 0.5 m): a resumed run imports that state over whatever the build made,
    and the packing is only the run's initial state. A study's `build` that calls build_simulation gets the same."""
    token = _RESUMED.set((state, float(n_s)))
    try:
        yield
    finally:
        _RESUMED.reset(token)


def checkpoint_stones(scene: Scene, state: dict):
    """DEMSystem with the scene's parameters (dem_params) holding the stones of a coupled simulation's state
    (its 'dem/' arrays, sim.export_state()): their count, model, shapes, positions and contact springs, as
    DEMSystem.import_state makes them."""
    sys_ = _core.DEMSystem(dem_params(scene), 0)
    sys_.import_state({k[len("dem/"):]: v for k, v in state.items() if k.startswith("dem/")})
    return sys_


def settle_stones(sim, scene: Scene):
    """The packed stones settle in the still pool before the first flow step (Coupler.settle): the DEM
    alone, each stone lighter by the water it sits in (rho_w V w g, w its share under the still level),
    the flow frozen, until every free stone has been slower than the packing's rest speed (1e-3 m/s) for
    0.2 s or for hydrograph.settle_time_max; the porosity is then mapped from the settled stones as at
    the build. Returns the SettleReport (time [s], max_speed [m/s], rested)."""
    report = sim.settle(max_time=scene.hydrograph.settle_time_max)
    sim.update_porosity(keep_water_volume=scene.flume.initial_water == "displaced")
    return report
