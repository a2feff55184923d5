"""Calibration experiments of the stones, done with the DEM alone in the manner of a laboratory.

* **Angle of repose** (`pour_heap`, `repose_test`): stones leave a funnel one by one, each dropped a
  stated height above the heap's current top, onto a rough base (a row of fixed stones on the bed, so
  that the heap does not spread on a smooth floor). At rest, the upper envelope of each flank (the
  highest stone top per bin one mean diameter wide) is fitted by a straight line between stated
  fractions of the heap's height; the angle of repose is the mean of the two flanks. Dry, or submerged:
  buoyancy and added mass of still water (fluid_density 1000 kg/m3, every stone wet). The drag of the
  still water on the falling stones is neglected (there is no flow solver here).
* **Pull-out test** (`pull_stone`, `pull_test`), the seed paper's Fig. 5 and Table 1 (dry; vertical
  2.81 N, normal to the 27-degree slope 3.04 N, horizontal 4.75 N, each the mean of ten pulls): a
  surface stone of the packed weir's downstream slope, neither at the toe nor at the shoulder, is
  pulled through a soft spring whose anchor moves at a constant slow speed (displacement control),
  vertically, normal to the slope (outwards) and horizontally downstream. The result of a pull is the
  peak spring force. The paper's stones are 3D; these are the scene's 2D stones.

Both take a Scene and use only its stone model: stones.* (shape, sizes, density, friction, rolling
friction, polygon shape parameters), the DEM's effect flags and numerics.dem_dt, through
builder.dem_params with builder.stone_system (the heap) or builder.build_stones (the weir). Any stone
model the scene can express is therefore measured the same way. Polygon stones are measured by their
vertices: a stone's top is its highest vertex, its size its nominal diameter, and the figures draw its
outline; their shapes and their orientations as they leave the funnel come from the heap's seed.
"""
from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import Dict, List, Optional, Sequence

import numpy as np

from . import _core
from . import builder
from .stone_models import front, front_of, stone_diameters
from .scene import Scene

# the seed paper's Table 1: mean pull-out force of a slope stone in each direction, dry [N]
PAPER_PULL_N = {"vertical": 2.81, "normal": 3.04, "horizontal": 4.75}
# quarried stone's angle of repose (Chow 1959; very angular 41, rounded 37-38) [deg]
REPOSE_TARGET_DEG = (37.0, 41.0)
WATER = 1000.0  # kg/m^3, the still water of the submerged heap


# ------------------------------------------------------------------------------------------------
# angle of repose

@dataclass
class ReposeSetup:
    """How the heap is poured and measured (lengths in mean stone diameters d)."""

    n_stones: int = 300            # stones poured
    release_interval: float = 0.15  # s between two stones leaving the funnel (slow: see docs/dem.md)
    drop_height: float = 1.0       # a stone is released this many d above the heap's current top
    funnel_jitter: float = 0.25    # release point scattered uniformly by +- this many d about x = 0
    rest_speed: float = 1e-3       # the heap is at rest when every stone is slower [m/s] (also omega r)
    settle_time_max: float = 15.0  # simulated time allowed after the last release [s]
    bin_width: float = 1.0         # envelope bins [d]
    fit_low: float = 0.2           # each flank's fit uses the envelope between these fractions of the
    fit_high: float = 0.8          # heap's height above the base (not its rounded top nor its toe)

    def validate(self) -> "ReposeSetup":
        if not (isinstance(self.n_stones, int) and 3 <= self.n_stones <= 100000):
            raise ValueError(f"n_stones = {self.n_stones!r} must be an integer in [3, 100000]")
        for name, lo, hi in (("release_interval", 1e-4, 10.0), ("drop_height", 0.0, 100.0),
                             ("funnel_jitter", 0.0, 10.0), ("rest_speed", 1e-6, 1.0),
                             ("settle_time_max", 0.0, 1e4), ("bin_width", 0.1, 10.0)):
            v = getattr(self, name)
            if not (isinstance(v, (int, float)) and lo <= v <= hi):
                raise ValueError(f"{name} = {v!r} is outside the allowed range [{lo}, {hi}]")
        if not 0.0 <= self.fit_low < self.fit_high <= 1.0:
            raise ValueError(f"fit_low = {self.fit_low!r}, fit_high = {self.fit_high!r}: need 0 <= fit_low < "
                             "fit_high <= 1")
        return self


@dataclass
class FlankFit:
    """A straight line fitted to one flank of a heap's envelope (z = slope x + intercept, [m])."""

    slope: float      # dz/dx of the fitted line [-]
    intercept: float  # z at x = 0 [m]
    x: np.ndarray     # envelope points used [m]
    z: np.ndarray

    @property
    def angle(self) -> float:
        """Angle of the flank to the horizontal [deg]."""
        return math.degrees(math.atan(abs(self.slope)))


@dataclass
class ReposeResult:
    """One heap poured from a funnel: both flanks' fits, its height [m], whether it came to rest, and the
    stones at the end (positions and radii [m])."""

    seed: int
    submerged: bool
    left: FlankFit
    right: FlankFit
    height: float          # heap height above the base's top [m]
    base_top: float        # z of the base's top [m]
    settled: bool          # at rest before settle_time_max
    max_speed: float       # largest stone speed at the end [m/s]
    time: float            # simulated time [s]
    pos: np.ndarray = field(repr=False)      # stone centres at the end (n, 2) [m]
    radius: np.ndarray = field(repr=False)   # [m]
    fixed: np.ndarray = field(repr=False)
    envelope: np.ndarray = field(repr=False)  # (bins, 2): bin centre x, highest stone top [m]
    outlines: Optional[List[np.ndarray]] = field(default=None, repr=False)  # polygon stones' world outlines

    @property
    def angle(self) -> float:
        """Angle of repose: the mean of the two flanks [deg]."""
        return 0.5 * (self.left.angle + self.right.angle)


def stone_tops(system) -> np.ndarray:
    """Height of each stone's highest point [m]: a disc's centre + radius, a polygon's highest vertex."""
    return front_of(system).tops(system)


def stone_outlines(system) -> Optional[List[np.ndarray]]:
    """The world outline (v, 2) [m] of every stone with a shape of its own (polygons); None for discs."""
    return front_of(system).outlines(system)


def _speeds(system) -> np.ndarray:
    v = np.hypot(*np.asarray(system.stone_vel).T)
    return np.maximum(v, np.abs(np.asarray(system.stone_omega)) * np.asarray(system.stone_radius))


def fit_flanks(x, top, base_top: float, d: float, setup: ReposeSetup):
    """(left, right, envelope, height): straight lines fitted to the heap's upper envelope.

    x, top: the free stones' centre abscissae and top heights [m]; base_top: z of the base [m]; d: mean
    diameter [m]. The envelope is the highest top per bin of setup.bin_width d; the heap's height H is
    the envelope's maximum above base_top, its apex the bin holding it. Each flank uses the bins on its
    side of the apex whose envelope lies between fit_low H and fit_high H above the base (at least 3)."""
    x, top = np.asarray(x, float), np.asarray(top, float)
    w = setup.bin_width * d
    k = np.floor(x / w).astype(int)
    bins = np.unique(k)
    env = np.array([[(b + 0.5) * w, top[k == b].max()] for b in bins])
    height = env[:, 1].max() - base_top
    if not height > 0.0:
        raise ValueError(f"no heap: the stones' highest top is {height:.3g} m above the base")
    apex = env[np.argmax(env[:, 1]), 0]
    rel = (env[:, 1] - base_top) / height
    band = (rel >= setup.fit_low) & (rel <= setup.fit_high)
    fits = []
    for side in (env[:, 0] < apex, env[:, 0] > apex):
        sel = band & side
        if sel.sum() < 3:
            raise ValueError(f"a flank of the heap has {int(sel.sum())} envelope bins between {setup.fit_low} and "
                             f"{setup.fit_high} of its height {height:.3f} m: too few to fit (pour more stones)")
        slope, intercept = np.polyfit(env[sel, 0], env[sel, 1], 1)
        fits.append(FlankFit(float(slope), float(intercept), env[sel, 0], env[sel, 1]))
    return fits[0], fits[1], env, height


# DEM steps per contact of stones with rolling resistance: under critical damping the rolling springs'
# mode needs more than the paper's 20 (DEMSystem::stable_dt()); the stiffness is kept by scaling dem_dt
ROLLING_CONTACT_STEPS = 32.0


def with_rolling(scene: Scene, mu_r: float) -> Scene:
    """The scene with rolling friction mu_r [-] at stone-stone and stone-wall contacts; for mu_r > 0 with
    ROLLING_CONTACT_STEPS DEM steps per contact at the scene's contact stiffness (as the rolling scenes)."""
    s = scene.replace()
    s.stones.rolling_friction = s.stones.rolling_friction_wall = float(mu_r)
    n = s.numerics
    n.dem_dt, n.dem_contact_steps = rolling_step(n.dem_dt, n.dem_contact_steps, mu_r)
    return s.validate()


def rolling_step(dt: float, contact_steps: float, mu_r: float):
    """(dt [s], steps per contact [-]) of a DEM with rolling friction mu_r [-]: for mu_r > 0 at least
    ROLLING_CONTACT_STEPS steps per contact, dt scaled with them so that the contact stiffness is kept;
    else (or with as many steps already) dt and contact_steps as given."""
    if mu_r > 0.0 and contact_steps < ROLLING_CONTACT_STEPS:
        return dt * (contact_steps / ROLLING_CONTACT_STEPS), ROLLING_CONTACT_STEPS
    return dt, contact_steps


def repose_params(scene: Scene, submerged: bool, half_width: float):
    """DEMParams of the heap: the scene's stone model, vertical gravity, a flat bed between end walls at
    +-half_width [m], no removal; submerged: buoyancy and added mass of still water."""
    p = builder.dem_params(scene, submerged=submerged)
    if submerged:
        p.medium.rho_water = WATER
    p.medium.gravity = [0.0, -builder.GRAVITY]
    p.walls = []
    p.add_flume(-half_width, half_width, 0.0, scene.stones.friction_wall)
    p.domain_min, p.domain_max = [-1e30, -1e30], [1e30, 1e30]
    p.flags = int(p.flags & ~(_core.DEM_EXTERNAL_FORCE | _core.DEM_REMOVAL))
    return p


def _heap_half_width(n: int, d: float) -> float:
    # the base must outrun the flatter heaps: a triangle of the stones' area at 10 degrees, plus margin
    area = n * math.pi * d * d / 4.0 / 0.8
    return 1.2 * math.sqrt(area / math.tan(math.radians(10.0))) + 2.0 * d


def _free_spot(pos, radius, active, x, z, r) -> bool:
    on = active.astype(bool)
    gap = np.hypot(pos[on, 0] - x, pos[on, 1] - z) - radius[on] - r
    return bool(gap.size == 0 or gap.min() > 1e-4)


def pour_heap(scene: Scene, seed: int = 0, submerged: bool = False, setup: Optional[ReposeSetup] = None,
              log=None, clumps=None) -> ReposeResult:
    """Pours setup.n_stones of the scene's stones from a funnel onto a rough base and measures the heap
    (stones that move in 3D: a cone on a rough disc, calibration_3d.pour_cone). clumps: a
    calibration_3d.ClumpMix to pour clumps of it instead, with the scene's other stone options (its stones
    spheres)."""
    setup = (setup or ReposeSetup()).validate()
    if clumps is not None and front(scene.stones.shape).dimensions != 3:
        raise ValueError(f"clumps: the scene's stones.shape = {scene.stones.shape!r} does not move in 3D (allowed: "
                         "'sphere', whose options the clumps take)")
    if front(scene.stones.shape).dimensions == 3:
        from .calibration_3d import pour_cone
        return pour_cone(scene, seed, submerged, setup, lambda half: repose_params(scene, submerged, half), log,
                         clumps=clumps)
    st = scene.stones
    g = st.grading()  # a sieve curve: its d50 and stones drawn from it by mass (grading.py)
    d = st.diameter if g is None else g.d(0.5)
    rng = np.random.default_rng(seed)

    def sizes(n=None):
        if g is not None:
            return g.inverse_number_cdf(rng.random(1 if n is None else n))[0 if n is None else slice(None)]
        return d * (1.0 + st.diameter_spread * rng.uniform(-1.0, 1.0, n))

    half = _heap_half_width(setup.n_stones, d)
    # the rough base: a row of touching stones of the scene's sizes fixed on the bed (random sizes, so
    # that the heap does not grow as a lattice on a regular row)
    db = []
    while sum(db) < 2.0 * half:
        db.append(float(sizes()))
    db = np.array(db)
    xb = np.cumsum(db) - 0.5 * db - half
    nb = len(xb)
    diam = np.r_[db, sizes(setup.n_stones)]
    pos = np.zeros((nb + setup.n_stones, 2))
    pos[:nb, 0], pos[:nb, 1] = xb, 0.5 * db
    pos[nb:, 1] = 2.0 * d  # parked, inactive until released
    fixed = np.r_[np.ones(nb, bool), np.zeros(setup.n_stones, bool)]
    shapes = builder.stone_shapes(scene, diam, seed)
    sys_ = builder.stone_system(scene, repose_params(scene, submerged, xb[-1] + db[-1]), pos, diam, fixed, shapes)
    # stones whose orientation shows take a random one from the heap's seed; the base stones at once
    turn = front_of(sys_).turn_base(sys_, seed, nb)
    sys_.stone_active[nb:] = 0
    base_top = float(stone_tops(sys_)[:nb].max())
    dt_release = setup.release_interval
    for k in range(nb, nb + setup.n_stones):
        x = setup.funnel_jitter * d * rng.uniform(-1.0, 1.0)
        while True:
            P, R, A = np.asarray(sys_.stone_pos), np.asarray(sys_.stone_radius), np.asarray(sys_.stone_active)
            # the heap's top under the funnel: stones at rest there (not those still falling)
            near = A.astype(bool) & (np.abs(P[:, 0]) < 1.5 * d) & (_speeds(sys_) < 0.2)
            top = max(base_top, float(stone_tops(sys_)[near].max()) if near.any() else base_top)
            z = top + setup.drop_height * d + R[k]
            if _free_spot(P, R, A, x, z, R[k]):
                break
            sys_.advance(0.01)  # the previous stone is still in the way
        sys_.stone_pos[k] = (x, z)
        sys_.stone_vel[k] = (0.0, 0.0)
        sys_.stone_omega[k] = 0.0
        if turn is not None:
            sys_.stone_angle[k] = turn[k]
        sys_.stone_active[k] = 1
        sys_.advance(dt_release)
        if log and (k - nb + 1) % 100 == 0:
            log(f"  poured {k - nb + 1} stones, t = {sys_.time:.1f} s")
    settled, t_end = False, sys_.time + setup.settle_time_max
    while sys_.time < t_end - 1e-9:
        sys_.advance(0.1)
        if _speeds(sys_)[nb:].max() < setup.rest_speed:
            settled = True
            break
    free = ~fixed
    P = np.asarray(sys_.stone_pos)
    left, right, env, height = fit_flanks(P[free, 0], stone_tops(sys_)[free], base_top, d, setup)
    return ReposeResult(seed=seed, submerged=submerged, left=left, right=right, height=float(height),
                        base_top=base_top, settled=settled, max_speed=float(_speeds(sys_)[nb:].max()),
                        time=float(sys_.time), pos=P.copy(), radius=np.asarray(sys_.stone_radius).copy(),
                        fixed=fixed, envelope=env, outlines=stone_outlines(sys_))


def repose_test(scene: Scene, seeds: Sequence[int] = (0, 1, 2), submerged: bool = False,
                setup: Optional[ReposeSetup] = None, log=None) -> List[ReposeResult]:
    """One heap per seed."""
    out = []
    for s in seeds:
        r = pour_heap(scene, s, submerged, setup, log)
        if log:
            log(f"{'submerged' if submerged else 'dry'} heap, seed {s}: {r.left.angle:.1f} / {r.right.angle:.1f} deg "
                f"(height {r.height:.3f} m, at rest: {r.settled})")
        out.append(r)
    return out


def mean_spread(values) -> tuple:
    """(mean, sample standard deviation, n) of finite values (spread 0 for one value)."""
    v = np.asarray([x for x in values if x is not None and np.isfinite(x)], float)
    if v.size == 0:
        return float("nan"), float("nan"), 0
    return float(v.mean()), float(v.std(ddof=1)) if v.size > 1 else 0.0, int(v.size)


def repose_markdown(results: Sequence[ReposeResult]) -> str:
    """A table of the heaps: per seed, each flank and their mean; then mean and spread over the seeds."""
    lines = ["| heap | seed | left flank [deg] | right flank [deg] | angle [deg] | height [m] | at rest |",
             "|---|---|---|---|---|---|---|"]
    for r in results:
        lines.append(f"| {'submerged' if r.submerged else 'dry'} | {r.seed} | {r.left.angle:.1f} | "
                     f"{r.right.angle:.1f} | {r.angle:.1f} | {r.height:.3f} | {'yes' if r.settled else 'no'} |")
    for sub in (False, True):
        rs = [r for r in results if r.submerged == sub]
        if rs:
            m, s, n = mean_spread([r.angle for r in rs])
            lines.append(f"| {'submerged' if sub else 'dry'} | mean of {n} | | | **{m:.1f} +- {s:.1f}** | | |")
    return "\n".join(lines)


# ------------------------------------------------------------------------------------------------
# pull-out test

@dataclass
class PullSetup:
    """The pull: a linear spring of zero rest length from the stone's centre to an anchor that starts
    there and moves at `speed` along the pull direction."""

    spring: float = 50.0     # spring stiffness [N/m] (a spring balance reading 5 N at 10 cm)
    speed: float = 0.02      # anchor speed [m/s]
    max_travel: float = 0.3  # the pull stops after the anchor has travelled this far [m]
    pulled_out: float = 1.5  # ... or once the stone has moved this many of its diameters (out of its pocket)
    update: float = 1e-3     # the spring force is updated every `update` seconds [s]
    z_low: float = 0.2       # stones pulled: centres between z_low and z_high of the weir's height
    z_high: float = 0.8
    hold_beyond: float = 0.0  # > 0: stones whose centres lie farther than this many of the pulled stone's
    #                           diameters from it are held fixed during the pull (a packed weir at rest:
    #                           the far stones do not take part, and held stones cost nothing); 0: none

    def validate(self) -> "PullSetup":
        for name, lo, hi in (("spring", 1e-3, 1e6), ("speed", 1e-5, 10.0), ("max_travel", 1e-3, 10.0),
                             ("pulled_out", 0.01, 100.0), ("update", 1e-5, 0.1), ("hold_beyond", 0.0, 1e3)):
            v = getattr(self, name)
            if not (isinstance(v, (int, float)) and lo <= v <= hi):
                raise ValueError(f"{name} = {v!r} is outside the allowed range [{lo}, {hi}]")
        if not 0.0 <= self.z_low < self.z_high <= 1.0:
            raise ValueError(f"z_low = {self.z_low!r}, z_high = {self.z_high!r}: need 0 <= z_low < z_high <= 1")
        return self


def pull_directions(scene: Scene) -> Dict[str, np.ndarray]:
    """Unit vectors (x, z) of the three pulls: vertical, normal to the downstream slope (outwards),
    horizontal downstream."""
    a = math.radians(scene.weir.downstream_slope_deg)
    return {"vertical": np.array([0.0, 1.0]), "normal": np.array([math.sin(a), math.cos(a)]),
            "horizontal": np.array([1.0, 0.0])}


@dataclass
class PullResult:
    """One pull-out test of a slope stone: the peak spring force [N], the anchor's travel at it [m], the stone's
    weight [N], and the force [N] against the travel [m] over the pull."""

    seed: int
    stone: int
    direction: str
    peak: float               # peak spring force [N]
    travel_at_peak: float     # anchor travel at the peak [m]
    weight: float             # the stone's weight M g [N]
    travel: np.ndarray = field(repr=False)  # anchor travel [m] at each update
    force: np.ndarray = field(repr=False)   # spring force [N] at each update


# stones across a flume: the pulled stones' centres at least this many of their diameters from either side
# wall [-], so that the walls do not hold them
SIDE_WALL_CLEARANCE = 1.5


def slope_surface_stones(system, scene: Scene, setup: Optional[PullSetup] = None,
                         wall_clearance: Optional[float] = None) -> List[int]:
    """Stones an experimenter would pull: free stones of the downstream slope beyond the crest's middle
    whose centres lie between z_low and z_high of the weir's height (not the toe, not the shoulder) with
    no stone lying outward of them (none whose centre is more than half a contact distance farther out
    along the slope's normal within 0.75 of a contact distance in the slope's plane); ordered from the
    toe up. wall_clearance [-] (stones across a flume, 3D): only centres at least this many of their
    diameters from both side walls, the neighbours' distance in the slope's plane taken along the slope
    and across the flume; None: stones in the plane (no walls, along the slope alone)."""
    setup = setup or PullSetup()
    w = scene.weir
    a = math.radians(w.downstream_slope_deg)
    n = np.array([math.sin(a), math.cos(a)])   # outward normal of the downstream slope
    t = np.array([-math.cos(a), math.sin(a)])  # up the slope
    P, R = np.asarray(system.stone_pos), 0.5 * stone_diameters(system)  # polygons: nominal radii
    across = wall_clearance is not None
    # in the plane every stone sits at y = 0: hypot(du, 0) is exactly abs(du)
    Y = np.asarray(system.stone_y) if across else np.zeros(len(P))
    width = float(system.params.width) if across else math.inf
    on = np.asarray(system.stone_active).astype(bool)
    free = on & (np.asarray(system.stone_fixed) == 0)
    s = (P - [w.x_toe_down, 0.0]) @ n
    u = (P - [w.x_toe_down, 0.0]) @ t
    x_mid = 0.5 * (w.x_crest_up + w.x_crest_down)
    cand = []
    for i in np.flatnonzero(free & (P[:, 0] > x_mid)):
        z = P[i, 1] / w.height
        if not setup.z_low <= z <= setup.z_high:
            continue
        if across and min(Y[i], width - Y[i]) < 2.0 * wall_clearance * R[i]:
            continue
        reach = R[i] + R
        outward = on & (s - s[i] > 0.5 * reach) & (np.hypot(u - u[i], Y - Y[i]) < 0.75 * reach)
        outward[i] = False
        if not outward.any():
            cand.append(int(i))
    return sorted(cand, key=lambda i: P[i, 1])


def surface_stones(system, scene: Scene, setup: Optional[PullSetup] = None) -> List[int]:
    """The stones an experimenter would pull: slope_surface_stones, for stones that move in 3D those
    SIDE_WALL_CLEARANCE diameters or more from the side walls."""
    setup = setup or PullSetup()
    if front_of(system).dimensions == 3:
        return slope_surface_stones(system, scene, setup, wall_clearance=SIDE_WALL_CLEARANCE)
    return slope_surface_stones(system, scene, setup)


def pick_evenly(candidates: Sequence[int], k: int) -> List[int]:
    """k of the candidates spread evenly along their order (all of them if there are no more than k)."""
    if len(candidates) <= k:
        return list(candidates)
    return [candidates[int((j + 0.5) * len(candidates) / k)] for j in range(k)]


def pull_weir(scene: Scene, seed: int, clumps=None):
    """(DEMSystem, packed-state checkpoint): the scene's weir packed dry from `seed`, ready to pull; clumps: a
    calibration_3d.ClumpMix to pack clumps of it instead (calibration_3d.pack_clump_weir)."""
    if clumps is not None:
        from .calibration_3d import pack_clump_weir
        sys_, _ = pack_clump_weir(scene, seed, clumps)
        p = sys_.params  # the packing's step, lowered for the clumps
    else:
        sys_, _ = builder.build_stones(scene.replace(seed=seed))
        p = builder.dem_params(scene, submerged=False)
    p.flags = int(p.flags | _core.DEM_EXTERNAL_FORCE)
    sys_.params = p
    sys_.stone_wet[:] = 0.0
    return sys_, sys_.export_state()


def _hold_far(system, stone: int, reach: float) -> None:
    """Fixes the stones whose centres lie farther than reach [m] from the stone's (in 3D for 3D stones);
    the checkpoint's import_state frees them again."""
    rel = np.asarray(system.stone_pos) - np.asarray(system.stone_pos)[stone]
    dist2 = np.sum(rel ** 2, axis=1)
    y = np.asarray(system.stone_y)
    if y.size:
        dist2 = dist2 + (y - y[stone]) ** 2
    far = dist2 > reach * reach
    system.stone_fixed[far] = 1


def pull_stone(system, state, stone: int, direction: np.ndarray, setup: Optional[PullSetup] = None,
               seed: int = 0, name: str = "") -> PullResult:
    """Pulls one stone from the checkpoint `state` through the spring; returns the force history."""
    setup = (setup or PullSetup()).validate()
    system.import_state(state)
    e = np.asarray(direction, float) / np.linalg.norm(direction)
    x0 = np.array(system.stone_pos[stone])
    d = float(system.nominal_diameter(stone))
    if setup.hold_beyond > 0.0:
        _hold_far(system, stone, setup.hold_beyond * d)
    weight = float(system.mass(stone)) * builder.GRAVITY
    steps = int(round(setup.max_travel / setup.speed / setup.update))
    travel, force = np.zeros(steps), np.zeros(steps)
    k_end = steps
    h = setup.update
    for k in range(steps):
        # the force held over the next `update` is the spring's at its middle (anchor and stone moved on
        # by half of it): holding the force of its start would lag and pump energy into the stone
        x, v = np.asarray(system.stone_pos[stone]), np.asarray(system.stone_vel[stone])
        f = setup.spring * (x0 + e * setup.speed * h * (k + 0.5) - (x + 0.5 * h * v))
        system.stone_force_ext[stone] = f
        travel[k], force[k] = setup.speed * h * k, float(np.hypot(*(setup.spring * (x0 + e * setup.speed * h * k - x))))
        if float(np.hypot(*(x - x0))) > setup.pulled_out * d:
            k_end = k + 1
            break
        system.advance(setup.update)
    system.stone_force_ext[stone] = (0.0, 0.0)
    travel, force = travel[:k_end], force[:k_end]
    kp = int(np.argmax(force))
    return PullResult(seed=seed, stone=int(stone), direction=name, peak=float(force[kp]),
                      travel_at_peak=float(travel[kp]), weight=weight, travel=travel, force=force)


def pull_test(scene: Scene, seeds: Sequence[int] = (0, 1, 2, 3, 4), per_seed: int = 2,
              directions: Sequence[str] = ("vertical", "normal", "horizontal"), setup: Optional[PullSetup] = None,
              log=None, clumps=None) -> List[PullResult]:
    """Per seed, a weir is packed and `per_seed` slope stones (slope_surface_stones, pick_evenly) are
    each pulled in every direction from the same packed state; clumps: a calibration_3d.ClumpMix to pack
    and pull clumps of it (pull_weir)."""
    setup = (setup or PullSetup()).validate()
    dirs = pull_directions(scene)
    for name in directions:
        if name not in dirs:
            raise ValueError(f"direction {name!r} is not one of {', '.join(dirs)}")
    out = []
    for seed in seeds:
        sys_, state = pull_weir(scene, seed, clumps)
        stones = pick_evenly(surface_stones(sys_, scene, setup), per_seed)
        if not stones:
            raise ValueError(f"seed {seed}: no surface stone on the downstream slope between {setup.z_low} and "
                             f"{setup.z_high} of the weir's height")
        for i in stones:
            for name in directions:
                r = pull_stone(sys_, state, i, dirs[name], setup, seed=seed, name=name)
                if log:
                    log(f"seed {seed}, stone {i} (z = {state['stone_pos'][2 * i + 1]:.3f} m), {name}: "
                        f"peak {r.peak:.2f} N ({r.peak / r.weight:.2f} of its weight)")
                out.append(r)
    return out


def pull_markdown(results: Sequence[PullResult]) -> str:
    """Mean and spread of the peak forces per direction, next to the paper's Table 1."""
    lines = ["| direction | pulls | peak force [N], mean +- spread | min - max [N] | of the stone's weight | "
             "paper (Table 1) [N] | ratio to the paper |", "|---|---|---|---|---|---|---|"]
    for name, paper in PAPER_PULL_N.items():
        rs = [r for r in results if r.direction == name]
        if not rs:
            continue
        m, s, n = mean_spread([r.peak for r in rs])
        mw, _, _ = mean_spread([r.peak / r.weight for r in rs])
        lo, hi = min(r.peak for r in rs), max(r.peak for r in rs)
        lines.append(f"| {name} | {n} | {m:.2f} +- {s:.2f} | {lo:.2f} - {hi:.2f} | {mw:.2f} | {paper:.2f} | "
                     f"{m / paper:.2f} |")
    return "\n".join(lines)


# ------------------------------------------------------------------------------------------------
# figures (matplotlib's object-oriented API, no pyplot state)

PULL_COLORS = {"vertical": "tab:blue", "normal": "tab:green", "horizontal": "tab:red"}


def _discs(ax, pos, radius, fixed, polygons=None):
    """The stones: discs of their radius, or the polygons' outlines; fixed ones grey."""
    from matplotlib.collections import EllipseCollection, PolyCollection

    from .plots import _MPL_36

    if polygons is not None:
        for sel, face in ((fixed, "0.55"), (~fixed, "tan")):
            ax.add_collection(PolyCollection([polygons[i] for i in np.flatnonzero(sel)], facecolors=face,
                                             edgecolors="0.25", linewidths=0.3))
        return
    for sel, face in ((fixed, "0.55"), (~fixed, "tan")):
        d = 2.0 * radius[sel]
        ax.add_collection(EllipseCollection(d, d, np.zeros(sel.sum()), units="xy", offsets=pos[sel],
                                            facecolors=face, edgecolors="0.25", linewidths=0.3,
                                            **{"offset_transform" if _MPL_36 else "transOffset": ax.transData}))


def fig_heap(result: ReposeResult, title: str = ""):
    """The heap at rest: stones, the upper envelope, the two fitted flanks and their angles (a 3D heap:
    calibration_3d.fig_cone)."""
    from matplotlib.figure import Figure

    if hasattr(result, "cone"):
        from .calibration_3d import fig_cone
        return fig_cone(result, title)

    fig = Figure(figsize=(8.0, 3.4), layout="constrained")
    ax = fig.add_subplot()
    _discs(ax, result.pos, result.radius, result.fixed, result.outlines)
    env = result.envelope
    ax.plot(env[:, 0], env[:, 1], ".", color="0.3", ms=3, label="envelope (highest top per bin)")
    for fit, side in ((result.left, "left"), (result.right, "right")):
        xs = np.array([fit.x.min(), fit.x.max()])
        ax.plot(xs, fit.slope * xs + fit.intercept, color="tab:red", lw=1.6)
        ax.annotate(f"{fit.angle:.1f}°", (xs.mean(), fit.slope * xs.mean() + fit.intercept), color="tab:red",
                    textcoords="offset points", xytext=(-38 if side == "left" else 8, 6))
    free = ~result.fixed
    x = result.pos[free, 0]
    span = max(abs(x.min()), abs(x.max())) + 0.1
    ax.set_xlim(-span, span)
    ax.set_ylim(0.0, result.base_top + result.height * 1.15)
    ax.set_aspect("equal")
    ax.set_xlabel("x [m]")
    ax.set_ylabel("z [m]")
    ax.set_title(title or f"{'submerged' if result.submerged else 'dry'} heap, seed {result.seed}: "
                          f"angle of repose {result.angle:.1f}°")
    ax.legend(loc="upper right", fontsize=8)
    return fig


def fig_pull(results: Sequence[PullResult], title: str = ""):
    """Spring force against anchor travel of every pull, one colour per direction, with the paper's means."""
    from matplotlib.figure import Figure

    fig = Figure(figsize=(7.0, 3.6), layout="constrained")
    ax = fig.add_subplot()
    for name, color in PULL_COLORS.items():
        rs = [r for r in results if r.direction == name]
        for k, r in enumerate(rs):
            ax.plot(r.travel * 100.0, r.force, color=color, lw=0.8, alpha=0.6,
                    label=f"{name} ({len(rs)} pulls)" if k == 0 else None)
        if rs:
            ax.axhline(PAPER_PULL_N[name], color=color, ls="--", lw=1.2)
    ax.plot([], [], "k--", lw=1.2, label="paper's means (Table 1)")
    ax.set_xlabel("anchor travel [cm]")
    ax.set_ylabel("spring force [N]")
    ax.set_title(title or "pull-out test of slope stones")
    ax.set_ylim(bottom=0.0)
    ax.legend(fontsize=8, loc="upper right")
    return fig
