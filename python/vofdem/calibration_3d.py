"""The calibration experiments of calibration.py for stones that move in 3D (models of dimensions 3).

* **Angle of repose** (`pour_cone`): stones leave a funnel on the heap's axis one every release_interval,
  each dropped a stated height above the heap's current top (higher if a stone still falling is in the way), onto a rough base (a disc of fixed stones of the scene's
  sizes on a triangular lattice on the bed). The side walls stand far away (beyond the widest cone the
  stones can build at 20 degrees), so the heap is a free cone. At rest, its surface stones are the
  highest of each square cell one mean diameter d wide in plan (stones that rolled off the disc onto the
  smooth bed are taken away, as stones falling off a table's edge, and counted); their tops z against their distance rho
  from the heap's axis (the plan centroid of the poured stones) are fitted by a straight line
  z = z0 - tan(theta) rho between stated fractions of the heap's height (not its rounded top, not its toe),
  and theta is the angle of repose. The two halves x < axis and x > axis are fitted apart too (their
  difference shows how round the cone is).
* **Pull-out test**: calibration.pull_test on the 3D-packed weir; the pulls act in the x-z plane (zero
  across the width), the stones pulled are surface stones of the downstream slope at least
  `SIDE_WALL_CLEARANCE` diameters from either side wall (`calibration.slope_surface_stones`).

Both take the stone model of the scene (spheres), or clumps of a mix of library shapes (`ClumpMix`, passed as
`clumps=`; a scene of `stones.shape = 'clump'` takes the default mix): the same heap and weir with each
stone a library clump of its nominal diameter drawn from the seed and turned at random (the weir from
pack_weir with `WeirSpec.shape = 'clump'`), the contact stiffness the scene's and the DEM step lowered to
the clumps' stable step (`clump_params`: more steps per contact at the same stiffness).

The drag of still water on the falling stones is neglected, as in the 2D heap.
"""
from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import List, Optional

import numpy as np

from . import _core, builder
from .scene import Scene


@dataclass
class ClumpMix:
    """Clump stones drawn from the library (clump.h quarried_stone): each stone one of `names` with equal
    chances, aspect ratios 1 : ratio_intermediate : ratio_short [-]; the default, the 2-, 3- and 4-sphere
    shapes, is pack_weir's (WeirSpec.clump_names)."""

    names: tuple = ("pair_2", "triangle_3", "tetra_4")
    ratio_intermediate: float = 0.8  # p [-], in [ratio_short, 1]
    ratio_short: float = 0.6         # q [-], in [0.55, 1]
    step_margin: float = 0.9         # the DEM step's fraction of the clumps' stable step [-], in (0, 1]

    def validate(self) -> "ClumpMix":
        if not 0.0 < self.step_margin <= 1.0:
            raise ValueError(f"step_margin = {self.step_margin} is outside the allowed range (0, 1]")
        self.unit_shapes()  # names and ratios checked by the library (ValueError naming the parameter)
        return self

    def unit_shapes(self) -> List[np.ndarray]:
        """The mix's shapes at d_eq = 1 (k, 4) rows (x, y, z, r), principal frames."""
        return [np.asarray(_core.quarried_stone(n, 1.0, self.ratio_intermediate, self.ratio_short))
                for n in self.names]

    def label(self) -> str:
        return "clumps " + "/".join(self.names)


def random_quaternions(rng, n: int) -> np.ndarray:
    """n unit quaternions (w, x, y, z) uniform over the rotations (Shoemake 1992), as clump_packing.cpp."""
    u1, u2, u3 = rng.random(n), rng.random(n), rng.random(n)
    a, b = np.sqrt(1.0 - u1), np.sqrt(u1)
    return np.c_[a * np.sin(2 * np.pi * u2), a * np.cos(2 * np.pi * u2), b * np.sin(2 * np.pi * u3),
                 b * np.cos(2 * np.pi * u3)]


def make_clumps(system, mix: ClumpMix, seed: int) -> None:
    """Makes every stone of a 3D system a clump of the mix, of its nominal diameter 2 r, drawn and turned at
    random from seed (centres of mass and y kept)."""
    rng = np.random.default_rng([int(seed), 0xC1])
    units = mix.unit_shapes()
    d = 2.0 * np.asarray(system.stone_radius, float)
    y = np.array(system.stone_y, float)
    pick = rng.integers(len(units), size=len(d))
    spheres = np.vstack([units[k] * d[i] for i, k in enumerate(pick)])
    offset = np.r_[0, np.cumsum([len(units[k]) for k in pick])]
    system.set_clumps(spheres, offset.tolist())
    system.stone_y[:] = y
    system.stone_quat[:] = random_quaternions(rng, len(d))


def mix_stable_dt(params, mix: ClumpMix, d_mean: float, spread: float, density: float) -> float:
    """The stable DEM step [s] (DEMSystem.stable_dt) of the mix's shapes at d_mean (1 -+ spread) under params."""
    units = mix.unit_shapes()
    sizes = [d_mean * (1.0 - spread), d_mean * (1.0 + spread)]
    n = len(units) * len(sizes)
    pos = np.c_[np.arange(n) * 2.0 * d_mean, np.full(n, 1.0)]
    probe = _core.DEMSystem(params, pos, np.full(n, 0.5 * d_mean), np.full(n, density), [0] * n)
    shapes = [u * d for u in units for d in sizes]
    probe.set_clumps(np.vstack(shapes), np.r_[0, np.cumsum([len(u) for u in shapes])].tolist())
    return float(probe.stable_dt())


def clump_params(params, mix: ClumpMix, d_mean: float, spread: float, density: float):
    """params with the DEM step lowered to step_margin of the clumps' stable step (mix_stable_dt) and the
    steps per contact raised by the same factor, so that the contact stiffness stays the scene's; unchanged
    where the step is stable already."""
    stable = mix_stable_dt(params, mix, d_mean, spread, density)
    p = params
    if p.dt > mix.step_margin * stable:
        f = p.dt / (mix.step_margin * stable)
        p.dt /= f
        p.contact_steps *= f
    return p


def pack_clump_weir(scene: Scene, seed: int, mix: ClumpMix):
    """(DEMSystem, WeirPackingReport): the scene's weir packed dry by pack_weir as clumps of the mix from seed,
    with the scene's contact stiffness (clump_params); the system keeps the packing's DEMParams."""
    mix.validate()
    sc = scene.replace(seed=seed)
    spec = builder.weir_spec(sc)
    spec.shape = "clump"
    spec.clump_names = list(mix.names)
    spec.clump_ratio_intermediate, spec.clump_ratio_short = mix.ratio_intermediate, mix.ratio_short
    pack = builder.dem_params(sc, submerged=False)
    pack.flags = int(pack.flags & ~_core.DEMFlag.EXTERNAL_FORCE)
    pack = clump_params(pack, mix, spec.d_mean, spec.d_spread, spec.density)
    return _core.pack_weir(spec, pack)


def speeds_3d(system) -> np.ndarray:
    """Each stone's largest speed [m/s]: its centre's or omega r (3D stones)."""
    v = np.sqrt(np.sum(np.asarray(system.stone_vel) ** 2, axis=1) + np.asarray(system.stone_vel_y) ** 2)
    w = np.linalg.norm(np.asarray(system.stone_omega_3d), axis=1) * np.asarray(system.stone_radius)
    return np.maximum(v, w)


@dataclass
class ConeFit:
    """z = intercept - slope rho fitted to the surface stones' tops [m] against their distance from the axis."""

    slope: float      # -dz/drho [-]
    intercept: float  # z on the axis [m]
    rho: np.ndarray   # points used [m]
    z: np.ndarray

    @property
    def angle(self) -> float:
        """Angle of the flank to the horizontal [deg]."""
        return math.degrees(math.atan(max(self.slope, 0.0)))


@dataclass
class ConeResult:
    """One 3D heap: the cone's fit and the fits of its halves x < axis (left) and x > axis (right)."""

    seed: int
    submerged: bool
    cone: ConeFit
    left: ConeFit
    right: ConeFit
    height: float          # heap height above the base's top [m]
    base_top: float        # z of the base's top [m]
    settled: bool
    lost: int              # stones that rolled off the rough disc onto the smooth bed (taken away, as
    #                        stones falling off a table's edge; the heap is at rest without them)
    max_speed: float       # [m/s]
    time: float            # simulated time [s]
    axis: np.ndarray = field(repr=False)      # (x, y) of the heap's axis [m]
    pos: np.ndarray = field(repr=False)       # stone centres (n, 3): x, y, z [m]
    radius: np.ndarray = field(repr=False)
    fixed: np.ndarray = field(repr=False)
    surface: np.ndarray = field(repr=False)   # (m, 2): rho, top of the surface stones [m]

    @property
    def angle(self) -> float:
        """Angle of repose: the whole cone's fit [deg]."""
        return self.cone.angle


def heaps_markdown(heaps, lost: bool = False) -> List[str]:
    """The dry heaps' section of a calibration's results file: one row per (mu_r, ConeResult, CPU [s]),
    with the stones lost off the base when lost is True (the clumps' heaps)."""
    head = "| mu_r | heap (seed) | angle [deg] | halves [deg] | height [m] |" + (" lost |" if lost else "")
    lines = ["## Angle of repose, dry", "", head + " at rest | CPU [s] |",
             "|---:|---:|---:|---|---:|" + ("---:|" if lost else "") + "---|---:|"]
    for m, r, c in heaps:
        lines.append(f"| {m:g} | {r.seed} | {r.angle:.1f} | {r.left.angle:.1f} / {r.right.angle:.1f} | "
                     f"{r.height:.3f} |" + (f" {r.lost} |" if lost else "") +
                     f" {'yes' if r.settled else 'no'} | {c:.0f} |")
    return lines


def _line(rho, z) -> ConeFit:
    slope, intercept = np.polyfit(rho, z, 1)
    return ConeFit(float(-slope), float(intercept), np.asarray(rho), np.asarray(z))


def fit_cone(x, y, top, base_top: float, d: float, setup):
    """(cone, left, right, axis, surface, height): straight lines fitted to the surface stones' tops against
    their distance from the heap's axis.

    x, y, top: the free stones' centres and tops [m]; d: mean diameter [m]; setup: a ReposeSetup (its
    bin_width, fit_low, fit_high). The surface is the highest top per plan cell of bin_width d; H is its
    maximum above base_top; the fits use the surface stones between fit_low H and fit_high H (at least 5
    per fit)."""
    x, y, top = (np.asarray(a, float) for a in (x, y, top))
    axis = np.array([x.mean(), y.mean()])
    w = setup.bin_width * d
    cell = np.floor(x / w).astype(np.int64) * 1_000_003 + np.floor(y / w).astype(np.int64)
    best = {}
    for k, c in enumerate(cell):
        if c not in best or top[k] > top[best[c]]:
            best[c] = k
    s = np.array(sorted(best.values()))
    rho = np.hypot(x[s] - axis[0], y[s] - axis[1])
    height = top[s].max() - base_top
    if not height > 0.0:
        raise ValueError(f"no heap: the stones' highest top is {height:.3g} m above the base")
    rel = (top[s] - base_top) / height
    band = (rel >= setup.fit_low) & (rel <= setup.fit_high)
    fits = []
    for sel in (band, band & (x[s] < axis[0]), band & (x[s] > axis[0])):
        if sel.sum() < 5:
            raise ValueError(f"the heap has {int(sel.sum())} surface stones between {setup.fit_low} and "
                             f"{setup.fit_high} of its height {height:.3f} m on a side: too few to fit "
                             "(pour more stones)")
        fits.append(_line(rho[sel], top[s][sel]))
    return fits[0], fits[1], fits[2], axis, np.c_[rho, top[s]], float(height)


def _cone_radius(n: int, d: float, angle_deg: float) -> float:
    # a cone of n stones' volume at a packing fraction 0.55 and this angle
    vol = n * math.pi * d ** 3 / 6.0 / 0.55
    return (3.0 * vol / (math.pi * math.tan(math.radians(angle_deg)))) ** (1.0 / 3.0)


def rough_base(radius: float, sizes, d: float, spread: float):
    """(x, y, diameters) of a disc of touching-free stones on a triangular lattice of pitch d (1 + spread)
    within `radius` [m] of the origin; sizes(n) draws n diameters [m]."""
    a = d * (1.0 + spread)
    m = int(math.ceil(radius / a)) + 1
    i, j = np.meshgrid(np.arange(-m, m + 1), np.arange(-m, m + 1), indexing="ij")
    x = (i + 0.5 * (j % 2)).ravel() * a
    y = j.ravel() * a * math.sqrt(3.0) / 2.0
    keep = np.hypot(x, y) <= radius
    x, y = x[keep], y[keep]
    return x, y, np.asarray(sizes(len(x)), float)


def pour_cone(scene: Scene, seed: int, submerged: bool, setup, heap_params, log=None,
              clumps: Optional[ClumpMix] = None) -> ConeResult:
    """Pours setup.n_stones of the scene's 3D stones (or clumps of the mix) from a funnel onto a rough disc of
    the same stones and fits the cone; heap_params(half_width) gives the heap's DEMParams
    (calibration.repose_params, dry or submerged)."""
    from .stone_models import front_of

    st = scene.stones
    d = st.diameter
    rng = np.random.default_rng(seed)

    def sizes(n):
        return d * (1.0 + st.diameter_spread * rng.uniform(-1.0, 1.0, n))

    r_base = _cone_radius(setup.n_stones, d, 20.0) + 2.0 * d
    xb, yb, db = rough_base(r_base, sizes, d, st.diameter_spread)
    nb = len(xb)
    half = r_base + 2.0 * d  # end walls and side walls beyond the base
    p = heap_params(half)
    p.width = 2.0 * half
    yc = half
    diam = np.r_[db, sizes(setup.n_stones)]
    pos = np.zeros((nb + setup.n_stones, 2))
    pos[:nb, 0], pos[:nb, 1] = xb, 0.5 * db
    pos[nb:, 1] = 2.0 * d
    fixed = np.r_[np.ones(nb, bool), np.zeros(setup.n_stones, bool)]
    if clumps is not None:
        p = clump_params(p, clumps.validate(), d, st.diameter_spread, st.density)
    sys_ = builder.stone_system(scene, p, pos, diam, fixed)
    if clumps is not None:
        make_clumps(sys_, clumps, seed)
    sys_.stone_y[:nb] = yb + yc
    sys_.stone_active[nb:] = 0
    tops = front_of(sys_).tops
    base_top = float(tops(sys_)[:nb].max())
    for k in range(nb, nb + setup.n_stones):
        r_j, a_j = setup.funnel_jitter * d * math.sqrt(rng.random()), 2.0 * math.pi * rng.random()
        x, y = r_j * math.cos(a_j), yc + r_j * math.sin(a_j)
        P, Y, R, A = (np.asarray(v) for v in (sys_.stone_pos, sys_.stone_y, sys_.stone_radius, sys_.stone_active))
        on = A.astype(bool)
        near = on & (np.hypot(P[:, 0], Y - yc) < 1.5 * d) & (speeds_3d(sys_) < 0.2)
        top = max(base_top, float(tops(sys_)[near].max()) if near.any() else base_top)
        z = top + setup.drop_height * d + R[k]
        # a stone still falling in the way: this one leaves the funnel just above it (a stream, not a
        # wait: the 3D heap's stones cost too much to pour one at a time)
        while True:
            gap = np.sqrt((P[on, 0] - x) ** 2 + (Y[on] - y) ** 2 + (P[on, 1] - z) ** 2) - R[on] - R[k]
            if gap.size == 0 or gap.min() > 1e-4:
                break
            z += 0.5 * d
        sys_.stone_pos[k] = (x, z)
        sys_.stone_y[k] = y
        sys_.stone_vel[k] = (0.0, 0.0)
        sys_.stone_vel_y[k] = 0.0
        sys_.stone_omega_3d[k] = (0.0, 0.0, 0.0)
        sys_.stone_active[k] = 1
        sys_.advance(setup.release_interval)
        _drop_off_the_base(sys_, nb, yc, r_base, base_top)
        if log and (k - nb + 1) % 100 == 0:
            log(f"  poured {k - nb + 1} stones, t = {sys_.time:.1f} s")
    settled, t_end = False, sys_.time + setup.settle_time_max
    while sys_.time < t_end - 1e-9:
        sys_.advance(0.1)
        _drop_off_the_base(sys_, nb, yc, r_base, base_top)
        on = np.asarray(sys_.stone_active)[nb:].astype(bool)
        if speeds_3d(sys_)[nb:][on].max() < setup.rest_speed:
            settled = True
            break
    lost = int(setup.n_stones - np.asarray(sys_.stone_active)[nb:].sum())
    fixed = fixed | ~np.asarray(sys_.stone_active).astype(bool)  # the lost stones drop out of the fit
    free = ~fixed
    P, Y = np.asarray(sys_.stone_pos), np.asarray(sys_.stone_y)
    top = tops(sys_)
    cone, left, right, axis, surf, height = fit_cone(P[free, 0], Y[free], top[free], base_top, d, setup)
    on = np.asarray(sys_.stone_active)[nb:].astype(bool)
    return ConeResult(seed=seed, submerged=submerged, cone=cone, left=left, right=right, height=height,
                      base_top=base_top, settled=settled, lost=lost, max_speed=float(speeds_3d(sys_)[nb:][on].max()),
                      time=float(sys_.time), axis=axis, pos=np.c_[P[:, 0], Y, P[:, 1]],
                      radius=np.asarray(sys_.stone_radius).copy(), fixed=fixed, surface=surf)


def _drop_off_the_base(system, nb: int, yc: float, r_base: float, base_top: float) -> None:
    """Takes away (deactivates) the poured stones that rolled off the rough disc onto the bed: on a smooth
    bed a sphere without rolling resistance rolls on for ever, and it has left the heap."""
    P, Y = np.asarray(system.stone_pos), np.asarray(system.stone_y)
    off = (np.hypot(P[:, 0], Y - yc) > r_base) & (P[:, 1] < base_top)
    off[:nb] = False
    system.stone_active[off] = 0


# ------------------------------------------------------------------------------------------------
# figures

def _circles(ax, cx, cz, radius, fixed):
    from matplotlib.collections import EllipseCollection

    from .plots import _MPL_36

    for sel, face in ((fixed, "0.55"), (~fixed, "tan")):
        dd = 2.0 * radius[sel]
        ax.add_collection(EllipseCollection(dd, dd, np.zeros(sel.sum()), units="xy",
                                            offsets=np.c_[cx[sel], cz[sel]], facecolors=face, edgecolors="0.25",
                                            linewidths=0.2, alpha=0.9,
                                            **{"offset_transform" if _MPL_36 else "transOffset": ax.transData}))


def fig_cone(result: ConeResult, title: str = ""):
    """The 3D heap seen from the side (x-z, stones drawn back to front) and its surface stones' tops against
    their distance from the axis with the fitted line."""
    from matplotlib.figure import Figure

    fig = Figure(figsize=(10.0, 3.6), layout="constrained")
    ax, bx = fig.subplots(1, 2, gridspec_kw={"width_ratios": [1.6, 1.0]})
    order = np.argsort(-result.pos[:, 1])  # far stones first (larger y drawn behind)
    pos, rad, fix = result.pos[order], result.radius[order], result.fixed[order]
    _circles(ax, pos[:, 0] - result.axis[0], pos[:, 2], rad, fix)
    c = result.cone
    for sgn in (-1.0, 1.0):
        rr = np.array([c.rho.min(), c.rho.max()])
        ax.plot(sgn * rr, c.intercept - c.slope * rr, color="tab:red", lw=1.4)
    span = np.abs(result.pos[~result.fixed, 0] - result.axis[0]).max() + 0.05
    ax.set_xlim(-span, span)
    ax.set_ylim(0.0, result.base_top + 1.2 * result.height)
    ax.set_aspect("equal")
    ax.set_xlabel("x - axis [m]")
    ax.set_ylabel("z [m]")
    ax.set_title(f"side view, {int((~result.fixed).sum())} spheres")
    bx.plot(result.surface[:, 0], result.surface[:, 1], ".", color="0.5", ms=3, label="surface stones' tops")
    bx.plot(c.rho, c.z, ".", color="tab:blue", ms=4, label="fitted band")
    rr = np.array([0.0, c.rho.max()])
    bx.plot(rr, c.intercept - c.slope * rr, color="tab:red", lw=1.4, label=f"fit: {c.angle:.1f}°")
    bx.set_xlabel("distance from the axis [m]")
    bx.set_ylabel("top [m]")
    bx.legend(fontsize=8)
    fig.suptitle(title or f"{'submerged' if result.submerged else 'dry'} 3D heap, seed {result.seed}: angle of "
                          f"repose {result.angle:.1f}° (halves {result.left.angle:.1f}° / {result.right.angle:.1f}°)")
    return fig


def fig_pull_3d(system, state, stone: int, scene: Scene, direction: np.ndarray, title: str = ""):
    """A pull seen from downstream of the slope: the packed weir's stones within 3 d of the pulled one in
    y, side view (x-z), the pulled stone and the pull's direction."""
    from matplotlib.figure import Figure

    system.import_state(state)
    P, Y, R = np.asarray(system.stone_pos), np.asarray(system.stone_y), np.asarray(system.stone_radius)
    fixed = np.asarray(system.stone_fixed).astype(bool)
    sel = np.abs(Y - Y[stone]) < 3.0 * 2.0 * R[stone]
    order = np.flatnonzero(sel)[np.argsort(-np.abs(Y[sel] - Y[stone]))]
    fig = Figure(figsize=(7.5, 3.2), layout="constrained")
    ax = fig.add_subplot()
    _circles(ax, P[order, 0], P[order, 1], R[order], fixed[order])
    ax.add_patch(__import__("matplotlib.patches", fromlist=["Circle"]).Circle(
        tuple(P[stone]), R[stone], facecolor="tab:orange", edgecolor="k", lw=0.8))
    e = np.asarray(direction, float)
    ax.annotate("", xy=tuple(P[stone] + 3.0 * R[stone] * e), xytext=tuple(P[stone]),
                arrowprops={"arrowstyle": "->", "color": "tab:red", "lw": 1.6})
    ax.set_aspect("equal")
    ax.set_xlim(P[sel, 0].min() - 0.05, P[sel, 0].max() + 0.05)
    ax.set_ylim(0.0, P[sel, 1].max() + 0.08)
    ax.set_xlabel("x [m]")
    ax.set_ylabel("z [m]")
    ax.set_title(title or f"pull of stone {stone} (y = {Y[stone]:.3f} m), stones within 3 d across the width")
    return fig
