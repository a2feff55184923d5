"""Hard cases of the coupled model (Coupler): stones in water, weirs in extreme flows, both couplings."""
import math

import numpy as np

from vofdem import _core
from vofdem.scene import Scene

from hc_harness import (D, RHO_W, assert_budget, budget_text, build, case, couple, dem_params, fields_bounded, fmt,
                        release_after, stones, stones_accounted, tank)


def small_weir(q_lps: float, duration: float, **sections) -> Scene:
    """A weir of 3 cm stones, 0.12 m high, in a 1.6 m flume on 2 cm x 1 cm cells, fed a constant q_lps
    [l/s] over a width of 0.5 m; sections: {'flume': {...}, ...} overrides."""
    d = {"name": "small_weir", "end_time": duration,
         "flume": {"length": 1.6, "height": 0.3},
         "weir": {"height": 0.12, "crest_length": 0.08, "toe_x": 0.4},
         "stones": {"diameter": 0.03},
         "hydrograph": {"kind": "table", "times": [0.0, duration], "discharge_lps": [q_lps, q_lps]},
         "grid": {"dx": 0.02, "dz": 0.01, "dz_bed": 0.005, "bed_layer_height": 0.005}}
    for sec, kv in sections.items():
        d.setdefault(sec, {}).update(kv)
    return Scene.from_dict(d)


def run_weir(scene: Scene, hold: float, duration: float, speed_limit: float, budget_tol: float = 1e-9):
    """Builds the scene, holds the stones for `hold` s, runs to `duration`; checks fields, the water
    budget and the stones; returns (sim, figures)."""
    sim = build(scene)
    v0 = sim.fluid.water_volume()
    if hold > 0:
        release_after(sim, hold)
    sim.advance(duration)
    out = fields_bounded(sim.fluid, speed_limit)
    err = assert_budget(sim.fluid, v0, budget_tol)
    L, H = scene.flume.length, scene.flume.height
    counts = stones_accounted(sim.stones, (-0.5 * L, L), (-0.5 * H, 4 * H), margin=scene.stones.max_diameter())
    return sim, {"max speed": f"{fmt(out['umax'])} m/s", "budget error": budget_text(err),
                 "stones removed": f"{counts['removed']} of {sim.stones.n}"}


def wet_tank_with_stone(z0, density, level=0.3, flags=None, x0=0.2):
    fluid = tank(0.4, 0.5, 0.01, level)
    dem = stones(dem_params(0.0, 0.4), [[x0, z0]], density=density)
    sim = couple(fluid, dem, flags)
    sim.update_porosity(keep_water_volume=False)
    return sim


def released_float(t_end=8.0):
    """A 500 kg/m3 stone released 0.2 m deep in a tank 0.3 m deep, run to t_end: (sim, largest and
    smallest height of its centre above the level and mean wet fraction from 3 s on, volume error)."""
    sim = wet_tank_with_stone(0.1, 500.0)
    v0 = sim.water_volume()
    sim.advance(3.0)
    dz, wets = [], []
    while sim.time < t_end - 1e-9:
        sim.advance(sim.time + 0.05)
        dz.append(float(sim.stones.stone_pos[0, 1]) - 0.3)
        wets.append(float(sim.stones.stone_wet[0]))
    return sim, max(dz), min(dz), float(np.mean(wets)), abs(sim.water_volume() - v0) / v0


@case("floating_stone_floats_at_the_surface", "coupled",
      "a stone lighter than water (500 kg/m3, 4.8 cm) released 0.2 m deep: it rises at 0.7 m/s, overshoots "
      "the surface, and its buoyancy and added mass change with its wet fraction as it bobs (it used to hang "
      "5 cm above the surface and bob 7 cm peak to peak)",
      "from 3 s to 8 s its centre stays within 1 cm of the level (never more than 0.6 d above it), its mean "
      "wet fraction is the density ratio 0.5 within 0.1, water volume to 1e-9")
def floating_stone():
    sim, hi, lo, wet, err = released_float()
    assert err < 1e-9, f"water volume changed by {err:.2e}"
    assert hi < min(0.01, 0.6 * D) and lo > -0.01, f"centre between {lo:.4f} and {hi:.4f} m of the level"
    assert abs(wet - 0.5) < 0.1, f"mean wet fraction {wet}"
    return {"centre - level": f"{fmt(lo, 2)} to {fmt(hi, 2)} m", "mean wet fraction": fmt(wet, 3),
            "volume error": fmt(err, 2)}


@case("floating_stone_comes_to_rest", "coupled",
      "the same stone after 8 s: at rest only if the water it disturbed comes to rest too",
      "speed below 2 cm/s all through 8-9 s (sampled every 0.05 s: one instant can fall below it by chance)",
      xfail="it keeps moving with the water at 1.7-8.5 cm/s (median 5.4) over 8-12 s, the water at 0.09-0.19 m/s "
            "(faces with F > 0.5) under a +-4 mm seiche whose own orbital speed is ~0.04 m/s: the surface the stone "
            "broke keeps films of water in nearly empty cells (flow case `film_on_a_surface_at_a_cell_face`). "
            "Judged at the instant 8 s alone it passed once by chance (1.7 cm/s there)")
def floating_at_rest():
    sim, *_ = released_float()
    speeds = [float(np.hypot(*sim.stones.stone_vel[0]))]
    while sim.time < 9.0 - 1e-9:
        sim.advance(sim.time + 0.05)
        speeds.append(float(np.hypot(*sim.stones.stone_vel[0])))
    top = max(speeds)
    assert top < 0.02, f"speed up to {top:.3f} m/s over 8-9 s (at 8 s {speeds[0]:.3f} m/s)"
    return {"largest speed 8-9 s": f"{fmt(top, 2)} m/s"}


@case("stone_resting_across_the_free_surface", "coupled",
      "a stone on the bed in water 3 cm deep (its top 1.8 cm above the surface): a wet fraction between "
      "0 and 1, the free surface crossing its porous disc",
      "it stays where it is (moves < 0.5 mm in 3 s), its wet fraction is the disc's area below the "
      "level within 0.1, no spurious currents (< 5 cm/s), water volume to 1e-9",
      xfail="spurious currents of 0.3 m/s (5 cm/s in the water, a +-1 mm seiche) within 1 s. The stone settles "
            "6 um into the bed's spring at the start; the 1.7e-7 m^2 of water it displaces goes to the cell above "
            "the surface (F = 0.004), and a film that thin on a surface lying on a cell face is what drives the "
            "currents: the same film without any stone does the same (flow case "
            "`film_on_a_surface_at_a_cell_face`); with the stone pre-settled they stay below 1e-5 m/s")
def stone_across_surface():
    level = 0.03
    sim = wet_tank_with_stone(0.5 * D, 2650.0, level=level)
    v0 = sim.water_volume()
    sim.advance(3.0)
    st = sim.stones
    moved = float(np.hypot(*(np.asarray(st.stone_pos[0]) - [0.2, 0.5 * D])))
    s = (level - 0.5 * D) / (0.5 * D)
    geometric = (math.acos(-s) + s * math.sqrt(1 - s * s)) / math.pi
    wet = float(st.stone_wet[0])
    out = fields_bounded(sim.fluid, 0.05)
    err = abs(sim.water_volume() - v0) / v0
    assert moved < 5e-4, f"moved {moved} m"
    assert abs(wet - geometric) < 0.1, f"wet fraction {wet} against the geometric {geometric}"
    assert err < 1e-9, f"water volume changed by {err:.2e}"
    return {"moved": f"{fmt(moved, 2)} m", "wet fraction": f"{fmt(wet)} (geometric {fmt(geometric)})",
            "max speed": f"{fmt(out['umax'], 2)} m/s", "volume error": fmt(err, 2)}


@case("neutrally_buoyant_stone_stays_put", "coupled",
      "a stone of the water's own density (998.2 kg/m3) in still water: weight and buoyancy cancel, "
      "anything left over is numerical",
      "it drifts < 1 mm in 2 s, no spurious currents (< 1 mm/s), water volume to 1e-9")
def neutral_stone():
    sim = wet_tank_with_stone(0.15, RHO_W)
    v0 = sim.water_volume()
    sim.advance(2.0)
    moved = float(np.hypot(*(np.asarray(sim.stones.stone_pos[0]) - [0.2, 0.15])))
    out = fields_bounded(sim.fluid, 1e-3)
    err = abs(sim.water_volume() - v0) / v0
    assert moved < 1e-3, f"drifted {moved} m"
    assert err < 1e-9
    return {"drift": f"{fmt(moved, 2)} m", "max speed": f"{fmt(out['umax'], 2)} m/s", "volume error": fmt(err, 2)}


@case("all_stones_washed_out", "coupled",
      "12 loose stones (3 cm) on a bed under a 0.1 m^2/s stream: every one leaves the domain, the porosity "
      "map and the forces must cope with none left",
      "all 12 removed and counted, all through the outflow end, within the 6 s run, which goes on after the "
      "last has left; water budget to 1e-9, speed < 5 m/s")
def washed_out():
    s = small_weir(50.0, 6.0, stones={"positions": [[0.3 + 0.04 * j, 0.016] for j in range(12)],
                                      "fix_bottom_layer": False})
    sim = build(s)
    v0 = sim.fluid.water_volume()
    t_all = None
    while sim.time < 6.0 - 1e-9:
        sim.advance(sim.time + 0.1)
        if t_all is None and sim.stones.removed_count == sim.stones.n:
            t_all = sim.time
    out = fields_bounded(sim.fluid, 5.0)
    err = assert_budget(sim.fluid, v0, 1e-9)
    stones_accounted(sim.stones, (0.0, 1.6), (0.0, 1.2))
    assert t_all is not None and t_all < 6.0, f"removed {sim.stones.removed_count} of 12 by 6 s"
    assert np.all(np.asarray(sim.stones.stone_pos)[:, 0] > 1.6), "a stone left elsewhere than the outflow end"
    return {"all out at": f"{fmt(t_all, 2)} s", "max speed": f"{fmt(out['umax'])} m/s",
            "budget error": budget_text(err)}


def one_stone_in_flow(pos, vel, duration):
    """A stone of 3 cm with velocity vel [m/s] in the small weir's flume (no weir stones), 10 l/s."""
    s = small_weir(10.0, duration, stones={"positions": [list(pos)], "fix_bottom_layer": False})
    sim = build(s)
    sim.stones.stone_vel[0] = vel
    v0 = sim.fluid.water_volume()
    sim.advance(duration)
    fields_bounded(sim.fluid, 5.0)
    err = assert_budget(sim.fluid, v0, 1e-9)
    counts = stones_accounted(sim.stones, (-0.8, 1.6), (-0.15, 1.2), margin=0.015)
    return sim, err, counts


@case("stone_leaves_through_the_outflow_end", "coupled",
      "a stone thrown at 5 m/s through the outflow end: half of it outside the fluid grid before it is "
      "removed (porosity and forces of cells that do not exist)",
      "removed and counted (removed_count 1), fields bounded, water budget to 1e-9")
def leaves_outflow():
    sim, err, counts = one_stone_in_flow((1.5, 0.1), (5.0, 0.0), 0.5)
    assert counts["removed"] == 1
    return {"removed": str(counts["removed"]), "budget error": budget_text(err)}


@case("stone_thrown_against_the_upstream_end_wall", "coupled",
      "a stone thrown at 10 m/s against the inlet end wall (x = 0), where the inflow enters",
      "it rebounds into the flume (never past x = 0 by more than a quarter radius), nothing removed, water "
      "budget to 1e-9")
def thrown_upstream():
    sim, err, counts = one_stone_in_flow((0.1, 0.05), (-10.0, 0.0), 0.3)
    x = float(sim.stones.stone_pos[0, 0])
    assert counts["removed"] == 0 and x > 0.015, f"x = {x}"
    return {"x after": f"{fmt(x)} m", "budget error": budget_text(err)}


@case("stone_thrown_above_the_domain_top", "coupled",
      "a stone thrown upwards at 10 m/s out of the top of the fluid grid (0.3 m): it flies 5 m high, far "
      "above the cells, then falls back through the open top into the water",
      "above the removal box (4 x the domain height) it is removed and counted; nothing non-finite on the "
      "way; water budget to 1e-9")
def thrown_up():
    sim, err, counts = one_stone_in_flow((0.8, 0.2), (0.0, 10.0), 1.0)
    assert counts["removed"] == 1
    return {"removed": str(counts["removed"]), "budget error": budget_text(err)}


@case("stone_driven_into_the_bed", "coupled",
      "a stone driven down into the bed at 10 m/s under water (the bed is a DEM wall and the fluid's "
      "bottom)",
      "it does not pass the bed (centre never below a quarter radius above it), stays in the domain, water "
      "budget to 1e-9")
def into_bed():
    s = small_weir(10.0, 0.3, stones={"positions": [[0.8, 0.05]], "fix_bottom_layer": False})
    sim = build(s)
    sim.stones.stone_vel[0] = [0.0, -10.0]
    v0 = sim.fluid.water_volume()
    lowest = 1.0
    while sim.time < 0.3 - 1e-9:
        sim.advance(sim.time + 0.002)
        lowest = min(lowest, float(sim.stones.stone_pos[0, 1]))
    err = assert_budget(sim.fluid, v0, 1e-9)
    assert lowest > 0.25 * 0.015, f"centre reached z = {lowest}"
    assert sim.stones.removed_count == 0
    return {"lowest centre": f"{fmt(lowest)} m (r = 0.015)", "budget error": budget_text(err)}


@case("stones_of_5mm_on_the_papers_grid", "coupled",
      "a heap of 120 stones of 5 mm (a fifth of a cell, 1/10 the paper's) on the paper's 2.5 cm x 1 cm grid "
      "under 10 l/s: many stones per cell, a short drag relaxation time",
      "fields bounded (< 3 m/s), water budget to 1e-9, every stone accounted for")
def small_stones():
    d = 0.005 * (1 + 0.02 * np.random.default_rng(5).random(120))
    pos = [[0.5 + 0.0052 * (j % 30) + 0.0026 * ((j // 30) % 2), 0.5 * d[j] + 0.0045 * (j // 30)] for j in range(120)]
    s = small_weir(10.0, 1.5, stones={"positions": pos, "diameters": [float(v) for v in d],
                                      "fix_bottom_layer": True},
                   grid={"dx": 0.025, "dz": 0.01, "dz_bed": 0.005, "bed_layer_height": 0.005})
    sim, out = run_weir(s, 0.5, 1.5, 3.0)
    out["steps"] = str(sim.step_count)
    return out


@case("stones_of_20cm_on_the_papers_grid", "coupled",
      "three stones of 20 cm (8 x 20 cells each, most cells fully covered: n = n_exp inside) as a weir under "
      "25 l/s",
      "fields bounded (< 3 m/s), water budget to 1e-9, every stone accounted for",
      xfail="the pressure solve's residual divergence makes 1.52e-6 of the water volume over the case, 0.152 x its "
            "tolerance 1e-5 (the harness allows 0.1 x; the rest holds: speeds bounded, budget 7e-16), since the "
            "start water rests in the pores (flume.initial_water = 'rest'); with the former start, whose water "
            "the stones had piled over them, 0.066 x: there an early positive residual (+2.9e-8 m^2) cancelled "
            "part of the later negative one; after the release both make -1.2e-7 to -1.3e-7 m^2 of water, on "
            "a start volume 20 % smaller now. The residual's water has a sign and adds up over the steps")
def large_stones():
    s = small_weir(25.0, 2.0, flume={"height": 0.5},
                   stones={"positions": [[0.5, 0.1], [0.72, 0.1], [0.61, 0.28]], "diameters": [0.2, 0.2, 0.2],
                           "fix_bottom_layer": True},
                   grid={"dx": 0.025, "dz": 0.01, "dz_bed": 0.005, "bed_layer_height": 0.005})
    sim, out = run_weir(s, 0.5, 2.0, 3.0)
    out["top stone moved"] = f"{fmt(float(np.hypot(*(sim.stones.stone_pos[2] - [0.61, 0.28]))), 2)} m"
    return out


@case("ten_times_the_peak_discharge", "coupled",
      "the quick Maeno weir (80 stones) under 250 l/s, ten times the scenario's peak: 0.3 m over the crest, "
      "4-5 m/s down the slope, the stones swept away",
      "fields bounded (< 10 m/s), water budget to 1e-9, every stone accounted for (removed ones counted)")
def ten_times_peak():
    from hc_harness import weir_scene
    s = weir_scene(flume__height=1.0, hydrograph__kind="table", hydrograph__times=[0.0, 4.0],
                   hydrograph__discharge_lps=[250.0, 250.0])
    s.end_time = 4.0
    sim, out = run_weir(s, 1.0, 4.0, 10.0)
    return out


def coupling_case(drag, mapping):
    from hc_harness import weir_scene
    s = weir_scene(stones__drag_model=drag, stones__porosity_mapping=mapping, hydrograph__spin_up_duration=3.0)
    s.end_time = 6.0
    sim, out = run_weir(s, 3.0, 6.0, 3.0)
    return out


@case("papers_coupling_on_the_weir", "coupled",
      "the quick Maeno weir at 10 l/s with the paper's coupling (sphere drag, eq. 11 with n_exp in each disc), "
      "released after a 3 s spin-up",
      "fields bounded (< 3 m/s), water budget to 1e-9, every stone accounted for")
def papers_coupling():
    return coupling_case("sphere", "paper")


@case("consistent_coupling_on_the_weir", "coupled",
      "the same with the consistent coupling (bed drag: the porous resistance's reaction, 10x the sphere "
      "drag; bulk mapping): the slope fails at the release",
      "fields bounded (< 3 m/s), water budget to 1e-9, every stone accounted for")
def consistent_coupling():
    return coupling_case("bed", "bulk")


@case("dam_break_onto_the_weir", "coupled",
      "a 0.25 m column of water released onto the small weir of 3 cm stones (dry until then): the bore "
      "hits the slope and fills the weir's pores, trapping air",
      "fields bounded (< 4 m/s), water budget to 1e-9, every stone accounted for")
def dam_break_weir():
    s = small_weir(0.1, 2.0)
    sim = build(s)
    pos0 = np.array(sim.stones.stone_pos)
    sim.fluid.cell_F[...] = 0.0
    sim.fluid.fill_water_box(0.0, 0.25, 0.0, 0.25)
    sim.fluid.set_hydrostatic_pressure()
    v0 = sim.fluid.water_volume()
    sim.advance(2.0)
    out = fields_bounded(sim.fluid, 4.0)
    err = assert_budget(sim.fluid, v0, 1e-9)
    counts = stones_accounted(sim.stones, (-0.8, 1.6), (-0.15, 1.2), margin=0.03)
    moved = float(np.hypot(*(np.asarray(sim.stones.stone_pos) - pos0).T).max())
    return {"max speed": f"{fmt(out['umax'])} m/s", "budget error": budget_text(err),
            "largest stone move": f"{fmt(moved)} m", "removed": str(counts["removed"])}


@case("tailwater_outlet_over_a_whole_weir_run", "coupled",
      "the quick Maeno weir with a tailwater outlet (level 6 cm, below the crest) through a 30 s ramp "
      "10 -> 25 l/s: water enters and leaves through the same end face",
      "the run completes: fields bounded (< 3 m/s), water budget to 1e-9, every stone accounted for")
def tailwater_run():
    from hc_harness import weir_scene
    s = weir_scene(flume__outflow="tailwater", flume__tailwater_level=0.06)
    sim, out = run_weir(s, s.hydrograph.spin_up_duration, s.duration, 3.0)
    return out


@case("displaced_water_drives_the_flow", "coupled",
      "the option COUPLE_DISPLACE_FLOW: a falling column of stones changes the porosity and the change "
      "drives the flow (dn/dt + div u = 0) instead of moving water by volume",
      "water volume to 1e-9",
      xfail="loses 1.6e-3 of the water here (6.2e-4 with forward-Euler convection and the held drag, which "
            "change how the stones fall; 7.5e-4 on the coupler's column-of-stones test): the source dn/dt "
            "acts on the mixture's volume, so a cell with partial F gives away water it does not hold; the "
            "default volume redistribution keeps it to 1e-12, so the option stays off by default")
def displace_flow():
    fluid = tank(0.2, 0.4, 0.01, 0.2)
    dem = stones(dem_params(0.0, 0.2), [[0.1, 0.1 + 0.05 * j] for j in range(4)])
    sim = couple(fluid, dem, int(_core.COUPLE_TWO_WAY) | int(_core.COUPLE_DISPLACE_FLOW))
    sim.update_porosity(keep_water_volume=False)
    v0 = sim.water_volume()
    sim.advance(1.0)
    err = abs(sim.water_volume() - v0) / v0
    assert err < 1e-9, f"water volume changed by {err:.2e}"
    return {"volume error": fmt(err, 2)}


@case("discharge_jump_onto_a_dry_flume", "coupled",
      "the quick Maeno weir in a dry flume (no water at all) hit by 25 l/s from t = 0: a bore over a dry "
      "bed, the first step from rest, the stones wetted all at once",
      "fields bounded (< 4 m/s), water budget to 1e-9, every stone accounted for")
def discharge_jump():
    from hc_harness import weir_scene
    s = weir_scene(hydrograph__kind="table", hydrograph__times=[0.0, 4.0], hydrograph__discharge_lps=[25.0, 25.0])
    s.end_time = 4.0
    sim = build(s)
    sim.fluid.cell_F[...] = 0.0
    sim.fluid.set_hydrostatic_pressure()
    release_after(sim, 1.0)
    sim.advance(4.0)
    out = fields_bounded(sim.fluid, 4.0)
    err = assert_budget(sim.fluid, 0.0, 1e-9)  # no water at the start: relative to the water that came in
    counts = stones_accounted(sim.stones, (-1.3, 2.6), (-0.25, 1.8), margin=0.06)
    return {"max speed": f"{fmt(out['umax'])} m/s", "budget error": budget_text(err),
            "stones removed": f"{counts['removed']} of {sim.stones.n}"}


@case("steepest_bed_slope_at_peak_discharge", "coupled",
      "the quick Maeno weir on the steepest bed the scene allows (slope 0.1: gravity has 0.98 m/s^2 along "
      "the flume, on the water and the stones) at the scenario's peak 25 l/s",
      "fields bounded (< 4 m/s), water budget to 1e-9, every stone accounted for")
def steep_bed():
    from hc_harness import weir_scene
    s = weir_scene(flume__bed_slope=0.1, hydrograph__kind="table", hydrograph__times=[0.0, 5.0],
                   hydrograph__discharge_lps=[25.0, 25.0])
    s.end_time = 5.0
    sim, out = run_weir(s, 2.0, 5.0, 4.0)
    return out
