"""Zero-copy views stay live for their owner's lifetime: a view held across set_params, building and
freeing a Coupler, stepping, a guard's restore and a checkpoint's import still points at the owner's
array (same data pointer, same shape) and shows what a fresh view shows. Only an explicit resize (and
DEMSystem.set_polygons for the poly_* arrays, a state of another stone count) may reallocate, as views.h
states. The typed state copies (copy_state / set_state) keep them too."""
import gc

import numpy as np
import pytest

import vofdem
from vofdem import _core
from vofdem.flow import tank_params

FLUID_VIEWS = {"face_u", "face_w", "cell_p", "cell_F", "cell_porosity", "face_x_porosity", "face_z_porosity",
               "cell_stone_diameter", "cell_nut", "cell_k", "cell_eps", "face_x_solid_u", "face_z_solid_w"}
STONE_VIEWS = {"stone_pos", "stone_vel", "stone_force_ext", "stone_drag_coef", "stone_drag_vel", "stone_force", "stone_acc",
               "stone_angle", "stone_omega", "stone_radius", "stone_density", "stone_fixed", "stone_active", "stone_wet",
               "stone_water_level", "stone_torque", "stone_alpha", "stone_asleep"}
POLYGON_VIEWS = STONE_VIEWS | {"poly_vertex", "poly_offset"}  # empty (no view) for disc stones
COUPLER_VIEWS = {"stone_force_drag", "stone_force_pressure", "cell_base_porosity", "cell_base_diameter"}


def views_of(obj):
    """every property of obj that is a numpy view of obj's memory"""
    out = {}
    for name in dir(type(obj)):
        if name.startswith("_") or not isinstance(getattr(type(obj), name), property):
            continue
        v = getattr(obj, name)
        if isinstance(v, np.ndarray) and v.base is obj:
            out[name] = v
    return out


def address(a):
    return a.__array_interface__["data"][0]


class Held:
    """views taken once and compared with fresh ones after each operation"""

    def __init__(self):
        self.owners = {}
        self.views = {}

    def hold(self, label, obj, expected):
        views = views_of(obj)
        assert expected <= set(views), sorted(expected - set(views))
        self.owners[label] = obj
        for name, v in views.items():
            self.views[(label, name)] = v

    def stale(self):
        """the held views that no longer show their owner's array"""
        bad = []
        for (label, name), held in self.views.items():
            fresh = getattr(self.owners[label], name)
            if address(held) != address(fresh) or held.shape != fresh.shape:
                bad.append(f"{label}.{name}: moved")  # its memory may be freed: not read
            elif not np.array_equal(held, fresh, equal_nan=held.dtype.kind == "f"):
                bad.append(f"{label}.{name}: differs")
        return bad


def flow():
    f = vofdem.VOFGrid(vofdem.Grid2D.uniform(20, 40, 0.2, 0.4), tank_params())
    f.fill_water_below(0.2)
    f.set_hydrostatic_pressure()
    return f


def stones(n=3):
    dp = vofdem.DEMParams()
    dp.submerged = True
    dp.add_flume(0.0, 0.2, 0.0)
    pos = np.array([[0.1 + 0.002 * j, 0.2 + 0.05 * j] for j in range(n)])
    return vofdem.DEMSystem(dp, pos=pos, density=[2650.0], radius=np.full(n, 0.024))


def test_views_stay_live_through_every_operation():
    fluid, dem = flow(), stones()
    held = Held()
    held.hold("fluid", fluid, FLUID_VIEWS)
    held.hold("stones", dem, STONE_VIEWS)
    steps = []

    def after(what):
        steps.extend(f"{what}: {s}" for s in held.stale())

    p = fluid.params
    p.flags |= vofdem.FlowEffect.TURBULENCE | vofdem.FlowEffect.RELATIVE_VELOCITY
    p.pressure_solver = _core.PressureSolverKind.EIGEN_DIRECT
    fluid.params = p  # rebuilds the pressure solver and the k-epsilon model
    after("fluid.params =")
    d = dem.params
    d.friction_stone = 0.5
    dem.params = d
    after("stones.params =")
    sim = _core.Coupler(fluid, dem, _core.CouplerParams())
    held.hold("coupler", sim, COUPLER_VIEWS)
    after("Coupler()")
    sim.advance(0.03)  # the stones' porosity is mapped onto the flow
    assert held.views[("fluid", "cell_porosity")].min() < 0.9
    after("coupler.advance")
    state = {k: v.copy() for k, v in sim.export_state().items()}
    sim.advance(0.06)
    sim.import_state(state)
    after("coupler.import_state")
    dem.import_state(dem.export_state())
    after("stones.import_state")
    branch = sim.copy_state()
    sim.advance(0.08)
    sim.set_state(branch)
    fluid.set_state(fluid.copy_state())
    dem.set_state(dem.copy_state())
    after("set_state")
    cp = sim.params
    cp.flags |= _core.COUPLE_LOOKUP_POROSITY  # a new porosity mapper
    sim.params = cp
    after("coupler.params =")
    fp = fluid.params
    fp.flags = int(fp.flags) & ~int(vofdem.FlowEffect.RELATIVE_VELOCITY)
    fluid.params = fp
    after("fluid.params = (relative velocity)")
    with pytest.raises(RuntimeError):
        fluid.step(10.0)  # a CFL breach: the flow restores the step's start
    after("fluid guard")
    del held.owners["coupler"]
    held.views = {k: v for k, v in held.views.items() if k[0] != "coupler"}
    del sim
    gc.collect()
    after("Coupler freed")
    fluid.advance(fluid.time + 0.01)
    dem.advance(0.01)
    after("stepping alone")
    assert not steps, "\n".join(steps)


def test_polygon_views_stay_live_through_stepping_and_checkpoints():
    dem = stones(2)
    d = dem.params
    d.contact_steps = 40  # softer contacts: the polygons' stable step stays above the DEM step
    dem.params = d
    vertex, offset = _core.random_polygons(np.full(2, 0.048), seed=1)
    dem.set_polygons(vertex, offset)  # documented to invalidate earlier poly_* views
    held = Held()
    held.hold("stones", dem, POLYGON_VIEWS)
    dem.advance(0.02)
    state = {k: v.copy() for k, v in dem.export_state().items()}
    dem.advance(0.02)
    dem.import_state(state)
    d = dem.params
    d.restitution = 0.2
    dem.params = d
    dem.advance(0.01)
    assert not held.stale()


def test_the_reallocating_calls_say_so():
    # the only calls that may move a view's memory: an explicit resize, new polygons, and a checkpoint
    # of another size; each says so in its docstring
    for method in (vofdem.DEMSystem.resize, vofdem.DEMSystem.set_polygons, vofdem.DEMSystem.import_state,
                   vofdem.DEMSystem.set_state):
        assert "invalidates" in method.__doc__.lower(), method.__name__
    dem = stones(2)
    dem.resize(5)
    assert dem.stone_pos.shape == (5, 2)
