"""The kernel mapping of the coupling (numerics.coupling_mapping = 'kernel', numerics.coupling_bandwidth):
a scene runs a few coupled steps with it, the flow sees the stones' whole solid volume, the width's
default and range; the default 'cell' mapping builds no kernel."""
import math

import numpy as np
import pytest

from vofdem import _core
from vofdem.builder import build_simulation, coupler_params
from vofdem.scene import GridSpec, Scene


def _scene(**numerics):
    s = Scene.maeno2008().quick()
    s.grid = GridSpec(dx=0.025, dz=0.01, dz_bed=0.005, bed_layer_height=0.005)  # the paper's grid
    s.stones.drag_model = "bed"
    for k, v in numerics.items():
        setattr(s.numerics, k, v)
    return s.validate()


def _seen_solid_area(sim):
    """sum (1 - n) A over the cells [m^2 per unit width]."""
    g = sim.fluid.grid
    n = np.asarray(sim.fluid.cell_porosity, float).reshape(g.nz, g.nx)
    dz = np.diff(np.asarray(g.z_faces, float))
    return float(((1.0 - n) * dz[:, None]).sum() * g.dx)


def test_the_default_is_the_cell_mapping_without_a_kernel():
    s = _scene()
    p = coupler_params(s)
    assert p.mapping == _core.CouplingMapping.CELL and p.bandwidth == 0.0
    sim = build_simulation(s)
    sim.step(1e-3)
    assert sim.kernel_bandwidth == 0.0 and "kernel" not in sim.profile.names


def test_a_kernel_scene_runs_coupled_steps_and_the_flow_sees_every_stone():
    s = _scene(coupling_mapping="kernel")
    sim = build_simulation(s)
    st = sim.stones
    d = 2.0 * np.asarray(st.stone_radius, float)
    # unset: the stones' mean diameter
    assert sim.kernel_bandwidth == pytest.approx(d.mean(), rel=1e-12)
    assert sim.floored_solid_area == 0.0
    # the stones' areas inside the domain (a bed stone pressed into the bed by its contact loses a sliver)
    g = sim.fluid.grid
    zf = np.asarray(g.z_faces, float)
    pos = np.asarray(st.stone_pos, float)
    inside = _core.stone_cell_area(pos[:, 0], pos[:, 1], d / 2.0, 0.0, g.nx * g.dx, zf[0], zf[-1])
    assert inside.sum() == pytest.approx(float((math.pi * d ** 2 / 4.0).sum()), rel=1e-6)
    stones = (1.0 - sim.params.n_exp) * float(inside.sum())
    assert _seen_solid_area(sim) == pytest.approx(stones, rel=1e-10)
    t0 = sim.time
    sim.advance(t0 + 0.05)
    assert sim.time == pytest.approx(t0 + 0.05)
    names = list(sim.profile.names)
    assert sim.profile.calls[names.index("kernel")] >= 2 * sim.step_count - 2
    for f in (sim.stone_force_drag, sim.stone_force_pressure):
        assert np.isfinite(np.asarray(f)).all()
    # the weir's stones in the overflow feel a drag downstream
    assert float(np.asarray(sim.stone_force_drag)[:, 0].sum()) > 0.0


def test_an_explicit_bandwidth_is_used():
    sim = build_simulation(_scene(coupling_mapping="kernel", coupling_bandwidth=0.036))
    assert sim.kernel_bandwidth == 0.036
    assert coupler_params(_scene(coupling_mapping="kernel", coupling_bandwidth=0.036)).bandwidth == 0.036


@pytest.mark.parametrize("bad", [0.0, -0.01, 1.5, float("nan")])
def test_bad_bandwidths_are_refused_naming_the_key(bad):
    s = Scene.maeno2008().quick()
    s.numerics.coupling_mapping = "kernel"
    s.numerics.coupling_bandwidth = bad
    with pytest.raises(ValueError, match=r"numerics\.coupling_bandwidth.*\(0\.0, 1\.0\] m"):
        s.validate()


def test_a_bad_mapping_is_refused_and_the_core_checks_its_own_range():
    s = Scene.maeno2008().quick()
    s.numerics.coupling_mapping = "gauss"
    with pytest.raises(ValueError, match=r"numerics\.coupling_mapping.*'cell', 'kernel'"):
        s.validate()
    p = _core.CouplerParams()
    p.bandwidth = 2.0
    with pytest.raises(ValueError, match=r"bandwidth = 2 m is outside the allowed range \(0, 1\] m"):
        p.validate()
