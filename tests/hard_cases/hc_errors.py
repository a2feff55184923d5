"""Hard cases that must end in a clear error, never in NaN: bad state, bad steps, bad input."""
import numpy as np
import pytest

import vofdem
from vofdem import _core

from hc_harness import D, RHO_W, case, couple, dem_params, stones, tank
from vofdem.flow import tank_params


def coupled_tank():
    fluid = tank(0.2, 0.3, 0.01, 0.2)
    dem = stones(dem_params(0.0, 0.2), [[0.1, 0.15], [0.1, 0.05]])
    sim = couple(fluid, dem)
    sim.advance(0.05)
    return sim


def state_of(sim):
    return {k: np.array(v, copy=True) for k, v in sim.export_state().items()}


def same_state(a, b) -> bool:
    return a.keys() == b.keys() and all(np.array_equal(a[k], b[k], equal_nan=True) for k in a)


@case("nan_in_a_stone_velocity", "errors",
      "a non-finite stone velocity written through the zero-copy view between steps",
      "RuntimeError naming the stage ('fluid_forces'), the stone and the time; time and every other array "
      "as before the step")
def nan_stone():
    sim = coupled_tank()
    sim.stones.stone_vel[1, 0] = np.nan
    before = state_of(sim)
    with pytest.raises(RuntimeError, match=r"fluid_forces.*stone 1.*t = ") as e:
        sim.step(1e-3)
    assert same_state(before, state_of(sim))
    return {"message": str(e.value).split(";")[0][:90]}


@case("nan_in_the_water_fraction", "errors",
      "a NaN written into one cell's water fraction",
      "RuntimeError naming the stage, the cell (i, k) and the time (here through the force on the stone that "
      "covers the cell); the state restored")
def nan_water():
    sim = coupled_tank()
    sim.fluid.cell_F[5, 7] = np.nan
    before = state_of(sim)
    with pytest.raises(RuntimeError, match=r"cell \(i=7, k=5\).*= nan") as e:
        sim.step(1e-3)
    assert same_state(before, state_of(sim))
    msg = str(e.value)
    return {"message": msg[:msg.index(" (drag")] + " ..." + msg[msg.index("; the flow"):msg.index("; coupled")]}


@case("fluid_step_above_the_cfl_limit", "errors",
      "a fluid step forced 50 times longer than stable_dt() in a falling column",
      "RuntimeError naming the CFL number, the face and the time; state restored bit for bit")
def step_above_cfl():
    fluid = tank(0.4, 0.3, 0.01, None)
    fluid.fill_water_box(0.0, 0.1, 0.0, 0.25)
    fluid.set_hydrostatic_pressure()
    fluid.advance(0.2)
    before = (np.array(fluid.cell_F), np.array(fluid.face_u), fluid.time)
    with pytest.raises(RuntimeError, match=r"CFL|Courant") as e:
        fluid.step(50 * fluid.stable_dt())
    assert np.array_equal(before[0], fluid.cell_F) and np.array_equal(before[1], fluid.face_u)
    assert fluid.time == before[2]
    return {"message": str(e.value)[:90]}


@case("porosity_out_of_range", "errors",
      "a cell porosity of 1.5, of -0.1 and of NaN written through the view",
      "ValueError naming cell_porosity, the cell and the allowed range [0, 1], for each")
def bad_porosity():
    out = {}
    for bad in (1.5, -0.1, np.nan):
        fluid = tank(0.2, 0.2, 0.01, 0.1)
        fluid.cell_porosity[3, 4] = bad
        with pytest.raises(ValueError, match=r"cell_porosity.*\[0, 1\]") as e:
            fluid.update_face_porosity()
        out[repr(bad)] = "ValueError"
    out["message"] = str(e.value)[:80]
    return out


@case("stone_far_outside_the_domain_at_start", "errors",
      "a stone placed 2 m below the bed and one 10 m beyond the outflow end when the simulation starts",
      "both removed and counted at the first step (removed_count 2), the others untouched, no NaN")
def stone_outside():
    fluid = tank(0.4, 0.3, 0.01, 0.2)
    p = dem_params(0.0, 0.4)
    p.domain_min, p.domain_max = [-0.2, -0.15], [0.4, 1.2]
    p.flags = int(p.flags) | int(vofdem.DEM_REMOVAL)
    dem = stones(p, [[0.2, -2.0], [10.4, 0.1], [0.2, 0.1]])
    sim = couple(fluid, dem)
    sim.advance(0.05)
    assert dem.removed_count == 2 and list(dem.stone_active) == [0, 0, 1]
    assert np.isfinite(np.asarray(sim.fluid.cell_F)).all()
    return {"removed": str(dem.removed_count)}


@case("dem_and_flow_disagree_on_the_water", "errors",
      "stones told the water is 1025 kg/m3 (sea water) while the flow holds 998.2 kg/m3",
      "the coupler hands the stones the flow's medium (water and gravity): one value, no disagreement")
def density_mismatch():
    fluid = tank(0.2, 0.2, 0.01, 0.1)
    p = dem_params(0.0, 0.2)
    p.medium.rho_water = 1025.0
    dem = stones(p, [[0.1, 0.05]])
    couple(fluid, dem)
    assert dem.params.medium == fluid.params.medium and dem.params.water_density == RHO_W
    return {"stones' water": f"{dem.params.water_density:g} kg/m3"}


@case("bad_parameters_of_every_solver", "errors",
      "a negative CFL, a zero DEM step, a restitution of 2, a stone radius of 0 and a stone_cfl of 5",
      "a ValueError naming the parameter and its allowed range for each, before anything runs")
def bad_parameters():
    checks = 0
    fp = tank_params()
    fp.cfl = -0.3
    with pytest.raises(ValueError, match=r"cfl = -0.3"):
        fp.validate()
    checks += 1
    dp = dem_params(0.0, 0.2)
    dp.dt = 0.0
    with pytest.raises(ValueError, match=r"dt"):
        stones(dp, [[0.1, 0.05]]).advance(0.01)
    checks += 1
    dp = dem_params(0.0, 0.2)
    dp.restitution = 2.0
    with pytest.raises(ValueError, match=r"restitution = 2 .*\[0, 1\]"):
        stones(dp, [[0.1, 0.05]])
    checks += 1
    with pytest.raises(ValueError, match="stone_radius"):
        vofdem.DEMSystem(dem_params(0.0, 0.2), pos=np.array([[0.1, 0.05]]), density=[2650.0], radius=np.array([0.0]))
    checks += 1
    cp = _core.CouplerParams()
    cp.stone_cfl = 5.0
    with pytest.raises(ValueError, match="stone_cfl"):
        cp.validate()
    checks += 1
    return {"clear errors": f"{checks} of 5"}


@case("no_water_at_all", "errors",
      "a coupled scene whose flume holds no water and gets no inflow: forces, wet fractions and the time "
      "step with nothing to act on",
      "stones fall and rest on the bed dry (wet fraction 0), time step max_dt, no NaN")
def no_water():
    fluid = tank(0.3, 0.2, 0.01, None)
    dem = stones(dem_params(0.0, 0.3), [[0.15, 0.1]])
    sim = couple(fluid, dem)
    sim.advance(1.0)
    z = float(dem.stone_pos[0, 1])
    assert abs(z - 0.5 * D) < 1e-3 and float(dem.stone_wet[0]) == 0.0
    assert np.isfinite(np.asarray(sim.stone_force_pressure)).all()
    return {"rest height - r": f"{z - 0.5 * D:.1e} m", "steps": str(sim.step_count)}
