"""Hard cases of the stones alone (DEMSystem): impacts, overlaps, the step at its limit, escapes."""
import math

import numpy as np

import vofdem
from vofdem import _core

from hc_harness import D, G, case, dem_params, fmt, stones, stones_accounted

R = 0.5 * D
M = 2650.0 * math.pi * D**3 / 6.0


def wall_impact(e: float, gravity: bool, v0: float = 1.0, kn: float = 1e5, steps_per_contact: int = 400):
    """A stone hitting the bed z = 0 at v0 [m/s] (dry): its rebound speed [m/s]."""
    p = vofdem.DEMParams()
    if not gravity:
        p.flags &= ~vofdem.DEM_GRAVITY
    p.stiffness_normal = kn
    p.restitution = e
    p.walls = [vofdem.DEMWall(point=[0.0, 0.0], normal=[0.0, 1.0], friction=0.3)]
    s = stones(p, [[0.5, R + 1e-4]])
    s.stone_vel[0] = [0.0, -v0]
    tc = vofdem.contact_duration(kn, M, vofdem.damping_ratio_from_restitution(e))
    dt = tc / steps_per_contact
    touched = False
    for _ in range(10 * steps_per_contact):
        s.step(dt)
        if s.wall_contact_count > 0:
            touched = True
        elif touched:
            break
    return float(s.stone_vel[0, 1])


def rebound_with_gravity(e: float, v0: float, kn: float, m: float, g: float = G) -> float:
    """Rebound speed of a linear spring-dashpot contact under a constant body force m g pressing it on:
    overlap d'' + 2 zeta w d' + w^2 d = g, d(0) = 0, d'(0) = v0, solved in closed form; the contact ends
    at the next d = 0 (found by bisection)."""
    zeta = vofdem.damping_ratio_from_restitution(e)
    w = math.sqrt(kn / m)
    wd = w * math.sqrt(1.0 - zeta * zeta)
    ds = g / (w * w)
    a, b = -ds, (v0 - zeta * w * ds) / wd

    def d(t):
        return ds + math.exp(-zeta * w * t) * (a * math.cos(wd * t) + b * math.sin(wd * t))

    def v(t):
        ex = math.exp(-zeta * w * t)
        return ex * ((-zeta * w * a + wd * b) * math.cos(wd * t) + (-zeta * w * b - wd * a) * math.sin(wd * t))

    lo, hi = 0.5 * math.pi / wd, 1.5 * math.pi / wd  # d > 0 at lo, < 0 at hi (checked below)
    assert d(lo) > 0 > d(hi)
    for _ in range(200):
        mid = 0.5 * (lo + hi)
        lo, hi = (mid, hi) if d(mid) > 0 else (lo, mid)
    return -v(0.5 * (lo + hi))


@case("restitution_0.05_to_0.95", "stones",
      "a normal wall impact over the whole restitution range, down to e = 0.05 (zeta = 0.69, the dashpot "
      "pulls at the end of the contact), gravity off",
      "rebound speed / impact speed within 1 % of e: e = 0.2, 0.5, 0.95 at 400 steps per contact, e = 0.05 "
      "at 2000")
def restitution_range():
    out = {}
    for e, spc in ((0.05, 2000), (0.2, 400), (0.5, 400), (0.95, 400)):
        r = wall_impact(e, gravity=False, steps_per_contact=spc)
        assert abs(r / e - 1) < 0.01, f"e = {e}: rebound {r}"
        out[f"e {e}"] = f"{100 * (r / e - 1):+.2f} %"
    return out


@case("restitution_0.05_at_400_steps_per_contact", "stones",
      "the most damped contact of the range (e = 0.05) at 400 steps per contact",
      "rebound within 1 % of e",
      xfail="rebounds 2.3 % low (0.47 % at 2000 steps, 0.23 % at 4000: first order in dt): the dashpot acts on "
            "the half-step velocity of the velocity-Verlet step; it would need the predicted end-of-step "
            "velocity, which changes every DEM result, so it is left for a change of its own")
def restitution_005_at_400():
    r = wall_impact(0.05, gravity=False)
    assert abs(r / 0.05 - 1) < 0.01, f"rebound {r} against 0.05 ({100 * (r / 0.05 - 1):+.2f} %)"
    return {"rebound / e": fmt(r / 0.05, 4)}


@case("restitution_0.2_dropped_under_gravity", "stones",
      "a stone dropped on the bed at 1 m/s with e = 0.2: gravity acts through the 4 ms contact and the "
      "rebound is 7 % below e v0, which is physics, not a bug (e(zeta) holds for a contact without body "
      "force); it explains a 6 % shortfall seen at e = 0.2 with gravity on, 0.2 % at e = 0.9",
      "rebound within 0.5 % of the closed-form spring-dashpot solution with gravity (d'' + 2 zeta w d' + "
      "w^2 d = g), for e = 0.2 and 0.9")
def restitution_under_gravity():
    out = {}
    for e in (0.2, 0.9):
        r = wall_impact(e, gravity=True)
        exact = rebound_with_gravity(e, 1.0, 1e5, M)
        assert abs(r / exact - 1) < 0.005, f"e = {e}: rebound {r}, closed form {exact}"
        out[f"e {e}: rebound / (e v0)"] = fmt(r / e, 4)
        out[f"e {e}: rebound / closed form"] = fmt(r / exact, 4)
    return out


@case("overlapping_stones_at_start", "stones",
      "20 stones placed overlapping by up to 40 % of a radius (a careless scene): the springs hold "
      "k delta^2 / 2 at t = 0",
      "no NaN, no stone lost; the fastest stone below the speed that all the stored spring energy would "
      "give it; after 2 s less than 5 % of that energy left as motion (discs without rolling resistance "
      "may keep rolling on the bed)")
def overlapping_start():
    rng = np.random.default_rng(7)
    # two rows at a centre distance of 1.6 r: each neighbour overlaps by 0.4 r
    i = np.arange(10)
    pos = np.vstack([np.c_[0.3 + 1.6 * R * i, np.full(10, R)],
                     np.c_[0.3 + 0.8 * R + 1.6 * R * i, np.full(10, R + 1.6 * R * math.sin(math.pi / 3))]])
    pos += 0.0005 * rng.standard_normal(pos.shape)
    p = dem_params(0.0, 1.0, wet=False)
    s = stones(p, pos)
    pairs = s.overlapping_pairs_reference()
    assert len(pairs) > 5
    s.advance(1e-4)  # one step: the springs are known
    e0 = s.energy()
    spring = e0.elastic + e0.kinetic
    vmax_bound = math.sqrt(2.0 * spring / M)
    vmax = 0.0
    for _ in range(200):
        s.advance(0.01)
        vmax = max(vmax, float(np.hypot(*np.asarray(s.stone_vel).T).max()))
    counts = stones_accounted(s, (0.0, 1.0), (0.0, 1.0))
    assert vmax <= vmax_bound, f"speed {vmax} above the energy bound {vmax_bound}"
    left = s.energy().kinetic / spring
    assert left < 0.05, f"{left:.3f} of the spring energy still kinetic after 2 s"
    return {"kinetic left": fmt(left, 2), "overlapping pairs": str(len(pairs)), "max speed": f"{fmt(vmax)} m/s (bound {fmt(vmax_bound)})",
            **{k: str(v) for k, v in counts.items()}}


def dry_weir(seed=0, **params):
    p = dem_params(0.0, 1.4, wet=False, **params)
    spec = _core.WeirSpec()
    spec.height, spec.crest, spec.slope_up_deg, spec.slope_down_deg = 0.15, 0.1, 27.0, 27.0
    spec.x_toe, spec.z_bed, spec.d_mean, spec.d_spread, spec.density, spec.seed = 0.4, 0.0, D, 0.1, 2650.0, seed
    s, rep = _core.pack_weir(spec, p)
    return s


def max_overlap(s) -> float:
    """Largest stone-stone overlap now, relative to the smaller radius."""
    pos, r = np.asarray(s.stone_pos), np.asarray(s.stone_radius)
    worst = 0.0
    for i, j in s.overlapping_pairs_reference():
        d = np.hypot(*(pos[i] - pos[j]))
        worst = max(worst, (r[i] + r[j] - d) / min(r[i], r[j]))
    return worst


@case("stone_thrown_at_10_m_per_s_into_the_weir", "stones",
      "a stone thrown at 10 m/s (200 times the weir stones' settling speeds) into a packed weir: "
      "overlaps of a quarter radius at the DEM's automatic stiffness, tunnelling through a stone",
      "no stone passes through another (largest overlap < 50 % of a radius at every 1 ms), no blow-up "
      "(total energy within 10 % of its start: the impacts last 20 steps, the automatic stiffness), no "
      "stone faster than the thrown one can fall (sqrt(10^2 + 2 g 0.1) m/s), every stone accounted for")
def thrown_stone():
    s = dry_weir()
    n0 = s.n
    pos = np.vstack([np.asarray(s.stone_pos), [[0.15, 0.1]]])
    rad = np.r_[np.asarray(s.stone_radius), R]
    fixed = list(np.asarray(s.stone_fixed)) + [0]
    p = s.params
    t = vofdem.DEMSystem(p, pos=pos, radius=rad, density=np.full(n0 + 1, 2650.0), fixed=[int(f) for f in fixed])
    t.stone_vel[n0] = [10.0, 0.0]
    t.advance(1e-4)
    e0 = t.energy().total
    worst, drift, vmax = 0.0, 0.0, 0.0
    for _ in range(300):
        t.advance(1e-3)
        worst = max(worst, max_overlap(t))
        drift = max(drift, abs(t.energy().total - e0) / abs(e0))
        vmax = max(vmax, float(np.hypot(*np.asarray(t.stone_vel).T).max()))
    assert worst < 0.5, f"overlap {worst:.2f} of a radius"
    assert drift < 0.1, f"energy changed by {drift:.2e} of its start"
    vfall = math.sqrt(10.0**2 + 2 * G * 0.1)  # thrown at 10 m/s from 0.1 m above the bed
    assert vmax <= vfall, f"a stone reached {vmax} m/s"
    counts = stones_accounted(t, (0.0, 1.4), (0.0, 10.0))
    return {"largest overlap": f"{fmt(worst, 2)} r", "largest energy error": fmt(drift, 2),
            **{k: str(v) for k, v in counts.items()}}


def energy_growth(s, dt, duration=1.0):
    """Relative growth of the total energy of a DEM stepped at dt [s] for duration [s]."""
    s.step(dt)
    e0 = s.energy().total
    for _ in range(int(duration / dt)):
        s.step(dt)
    return (s.energy().total - e0) / abs(e0)


@case("dem_step_at_the_scenes_step", "stones",
      "the packed weir at rest (critical damping, up to 4-5 contacts per stone) stepped at the scene's DEM "
      "step, 1e-4 s, and one step above stable_dt()",
      "energy never grows (total within 1e-9 of its start over 1 s); above stable_dt(): a ValueError "
      "naming stable_dt, the state untouched")
def dem_scene_step():
    s = dry_weir(seed=1)
    frac = s.params.dt / s.stable_dt()
    growth = energy_growth(s, s.params.dt)
    assert growth < 1e-9, f"energy grew by {growth:.2e}"
    before = np.array(s.stone_pos)
    try:
        s.step(1.01 * s.stable_dt())
        raise AssertionError("a step above stable_dt() was accepted")
    except ValueError as e:
        assert "stable" in str(e), str(e)
    assert np.array_equal(before, s.stone_pos)
    return {"dt / stable_dt": fmt(frac, 3), "energy change over 1 s": fmt(growth, 2)}


@case("dem_step_at_stable_dt", "stones",
      "six packed weirs at rest (critical damping) stepped at exactly stable_dt(), the step the DEM reports "
      "as stable (it used to be 1/10 of the pair's undamped contact period, at which the energy grew by "
      "up to 13 % in 1 s)",
      "energy never grows (total within 1e-9 of its start over 1 s), for packings of seeds 0-5")
def dem_stable_dt():
    worst = -1.0
    for seed in range(6):
        s = dry_weir(seed=seed)
        growth = energy_growth(s, s.stable_dt())
        assert growth < 1e-9, f"seed {seed}: energy grew by {growth:.2e} in 1 s"
        worst = max(worst, growth)
    return {"largest energy change over 1 s": fmt(worst, 2)}


def spheres(width: float, pos, **params):
    """3D spheres of the paper's size at (x, z) pairs in a dry flume 1 m long of the given width [m]."""
    p = vofdem.DEMParams()
    p.add_flume(0.0, 1.0, 0.0, 0.3)
    p.width = width
    p.stiffness_normal = 1e5
    for key, value in params.items():
        setattr(p, key, value)
    s = stones(p, pos)
    s.set_model("sphere")
    return s


@case("sphere_into_a_side_wall_at_10_m_s", "stones",
      "a 3D sphere thrown across the flume at 10 m/s (ten times a stone's speed in the overflow) into the glass "
      "side wall, obliquely and spinning, at the DEM's default step",
      "it rebounds no faster than it came (e = 0.5 by the law: 0.45-0.55 of the normal speed), does not pass the "
      "wall: its overlap stays below the undamped spring's v sqrt(m / k_n) (12.4 mm at k_n = 1e5 N/m, half the "
      "radius), and its energy account closes within 2 % (first order in dt: the dashpot's and the Coulomb slip's "
      "energies are taken on the step's half-step velocities; 1.4 % for the same impact head-on)")
def sphere_side_wall():
    s = spheres(0.3, [[0.5, 0.5]], restitution=0.5)
    s.stone_y[0] = 0.15
    s.stone_vel_y[0] = -10.0
    s.stone_vel[0] = [2.0, 0.0]
    s.stone_omega_3d[0] = [0.0, 0.0, 50.0]
    e0 = s.energy().total
    y_min = 1.0
    for _ in range(400):
        s.advance(1e-4)
        y_min = min(y_min, float(s.stone_y[0]))
    ratio = float(s.stone_vel_y[0]) / 10.0
    assert 0.45 < ratio < 0.55, f"rebound ratio {ratio}"
    assert R - y_min < 10.0 * math.sqrt(M / 1e5), f"overlap {R - y_min} m"
    drift = abs(s.energy().total - e0) / abs(e0)
    assert drift < 0.02, f"energy account off by {drift}"
    return {"rebound / impact": fmt(ratio), "largest overlap / r": fmt((R - y_min) / R), "energy drift": fmt(drift)}


@case("sphere_heap_poured_between_close_walls", "stones",
      "120 3D spheres poured into a flume barely two stones wide (0.1 m), frictional, with rolling resistance, at "
      "the DEM's default step: dense, jammed against both side walls",
      "no stone leaves the walls, the bed or the flume, every value stays finite, and the heap comes to rest "
      "(kinetic energy below 1e-4 J after 1.5 s)")
def sphere_heap_close_walls():
    g = np.random.default_rng(5)
    pos = [[0.05 + 0.05 * (k % 18) + 0.005 * g.random(), 0.05 + 0.05 * (k // 18)] for k in range(120)]
    s = spheres(0.1, pos, restitution=0.3, rolling_friction_stone=0.3, rolling_friction_wall=0.3)
    s.stone_y[:] = 0.025 + 0.05 * g.random(120)
    s.advance(1.5)
    y = np.asarray(s.stone_y)
    assert np.isfinite(y).all() and np.isfinite(np.asarray(s.stone_omega_3d)).all()
    assert y.min() > 0.75 * R and y.max() < 0.1 - 0.75 * R, f"y in [{y.min()}, {y.max()}]"
    counts = stones_accounted(s, (0.0, 1.0), (0.0, 10.0))
    kinetic = s.energy().kinetic
    assert kinetic < 1e-4, f"kinetic energy {kinetic} J"
    return {"kinetic energy [J]": fmt(kinetic), "contacts": s.contact_count, **counts}
