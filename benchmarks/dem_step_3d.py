#!/usr/bin/env python3
"""The 3D stones' DEM step as a measured knob: the answers the verdict depends on against their CPU at
several DEM steps per contact, the finest setting the reference; spheres, or with --shape clump the
clumps of the release study (calibration_3d.ClumpMix(), mu_r = 0; heaps of 300, weirs for the pulls
across B = 0.3 m, as benchmarks/clump_calibration.py; the parts heap, pull and member).

The knob is vofdem.study.setting(ref, "dem_steps", N): N steps per contact at the same contact stiffness
(dem_dt = 2e-3 s / N for the spheres' contact of 32 steps of 6.25e-5 s, so k_n = m*/2 (pi / (N dem_dt))^2
does not move); only the integration's step changes. Settings below the DEM's stable step
(DEMSystem.stable_dt: the rolling springs' mode under critical damping of the lightest stones) are
refused by the DEM and reported as refused with its message; the project's rule for rolling resistance
(calibration.with_rolling) asks for at least 32.

Answers, each on the stones' own scenes with mu_r = 0.2 stone-stone and stone-wall:

(a) the paper's pull-out test (calibration.pull_test's weir and pulls, as benchmarks/sphere_calibration.py:
    scenes/maeno2008_spheres.toml, spring 50 N/m, the stones beyond 3 d held) against 2.81 / 3.04 / 4.75 N;
(b) the dry heap's angle of repose (calibration.pour_heap, 500 spheres, as sphere_calibration.py);
(c) the stones lost at the release of a Maeno member (scenes/maeno2008_spheres_rolling_consistent.toml, as
    studies/release_stability.py runs it: the packing, the 20-s spin-up with the stones held, --after s
    after the release in the run's 0.5-s windows; lost: removed in vofdem.analysis's sense within 2 s
    after the release, and by the end), with the DEM substeps and the mobile spheres after the release, so
    the CPU per sphere-substep.

Each job (a part, a setting, a seed) is run once and kept as JSON in --out (resumable; --no-run only writes
the tables of the jobs kept). CPU: each job's process time on a shared machine.

    nice -n 5 env PYTHONPATH=python python3 benchmarks/dem_step_3d.py --steps 16,24,26,32,48,64 \\
        --parts member,heap,pull --seeds 0,1

    nice -n 5 env PYTHONPATH=python python3 benchmarks/dem_step_3d.py --shape clump --steps 32,35.33,48,85.1 \\
        --parts heap,pull --seeds 0,1,2,3

Writes benchmarks/results/dem_step_3d.md and docs/figures/dem_step_3d.png (with --shape clump,
dem_step_3d_clumps.md and .png).
"""
import argparse
import json
import math
import os
import platform
import time
from pathlib import Path

import numpy as np

os.environ.setdefault("OMP_NUM_THREADS", "1")  # one core per job: the CPU is one thread's
ROOT = Path(__file__).resolve().parents[1]
from vofdem import _core, builder  # noqa: E402  (after the thread count is set)
from vofdem import calibration as cal  # noqa: E402
from vofdem.calibration_3d import ClumpMix, mix_stable_dt  # noqa: E402
from vofdem.analysis import removal_times  # noqa: E402
from vofdem.scene import load_scene  # noqa: E402
from vofdem.study import parse_numbers, setting, shown_path  # noqa: E402

CALIBRATION_SCENE = ROOT / "scenes" / "maeno2008_spheres.toml"
MEMBER_SCENE = ROOT / "scenes" / "maeno2008_spheres_rolling_consistent.toml"
PARTS = ("member", "heap", "pull", "release")
WINDOW = 0.5          # s: the run's snapshot interval
RELEASE_WINDOW = 2.0  # s: "at the release" (studies/release_stability.py's --window)
PULL = dict(hold_beyond=3.0)  # sphere_calibration.py's pulls
DIRECTIONS = ("vertical", "normal", "horizontal")
# per stone shape: the rolling friction (the spheres' calibrated one, the clumps' release study's), the heap
# (sphere_calibration.py's, clump_calibration.py's), the pulled weirs' flume width [m] (None: the scene's)
# and the clumps' mix, its step margin 1 so that the knob's setting is the step run (a step above the
# stable one is reported refused, not lowered)
SHAPES = {
    "sphere": dict(mu_r=0.2, heap=dict(n_stones=500, release_interval=0.04, settle_time_max=10.0), width=None,
                   mix=None),
    "clump": dict(mu_r=0.0, heap=dict(n_stones=300, release_interval=0.04, settle_time_max=10.0), width=0.3,
                  mix=ClumpMix(step_margin=1.0)),
}
SHAPE = "sphere"  # the shape measured (main sets it from --shape)


def shape_of() -> dict:
    return SHAPES[SHAPE]


def references():
    """(calibration scene, member scene) of the shape measured, at their own DEM steps."""
    o = shape_of()
    refs = []
    for path in (CALIBRATION_SCENE, MEMBER_SCENE):
        s = load_scene(path)
        s = s.with_value("stones.shape", SHAPE) if s.stones.shape != SHAPE else s
        refs.append(cal.with_rolling(s, o["mu_r"]))
    if o["width"] is not None:
        refs[0] = refs[0].with_value("flume.width", o["width"]).validate()
    return refs


def scenes(steps: float):
    """(calibration scene, member scene) at `steps` DEM steps per contact, the contact stiffness kept."""
    return tuple(setting(r, "dem_steps", steps).scene(r) for r in references())


def stable_step(scene, n: int = 21) -> dict:
    """The DEM step of the scene against the DEM's stable step for n spheres of diameters spread evenly over
    d (1 -+ spread), apart: the automatic stiffness from their mean stone as a packing's, the bound from
    the two lightest (the packed weir's own, measured in the jobs, differs by its draw of sizes); clumps:
    the mix's shapes at the smallest and largest size (mix_stable_dt)."""
    p = builder.dem_params(scene)
    st = scene.stones
    d = st.diameter * np.linspace(1.0 - st.diameter_spread, 1.0 + st.diameter_spread, n)
    pos = np.c_[0.1 + 2.0 * st.diameter * np.arange(n), np.full(n, 0.5 * scene.flume.height)]
    probe = _core.DEMSystem(p, pos, 0.5 * d, np.full(n, st.density), [0] * n)
    mix = shape_of()["mix"]
    stable = float(probe.stable_dt())  # (and the automatic stiffness made)
    if mix is not None:
        stable = mix_stable_dt(p, mix, st.diameter, st.diameter_spread, st.density)
    return {"dt": float(p.dt), "stable_dt": stable, "kn": float(probe.stiffness_normal)}


def heap_job(steps: float, seed: int) -> dict:
    sc, _ = scenes(steps)
    t = time.process_time()
    r = cal.pour_heap(sc, seed, setup=cal.ReposeSetup(**shape_of()["heap"]), clumps=shape_of()["mix"])
    return {"angle": r.angle, "left": r.left.angle, "right": r.right.angle, "settled": bool(r.settled),
            "simulated": float(r.time), "cpu": time.process_time() - t}


def _pull_substeps(r, setup, dt: float) -> int:
    """DEM substeps of one pull: one advance of setup.update per force sample but the last if it broke off."""
    steps = int(round(setup.max_travel / setup.speed / setup.update))
    advances = len(r.travel) - (1 if len(r.travel) < steps else 0)
    return advances * max(1, math.ceil(setup.update / dt - 1e-9))


def pull_job(steps: float, seed: int, per_seed: int = 2) -> dict:
    sc, _ = scenes(steps)
    setup = cal.PullSetup(**PULL).validate()
    dirs = cal.pull_directions(sc)
    t = time.process_time()
    sys_, state = cal.pull_weir(sc, seed, clumps=shape_of()["mix"])
    cpu_pack = time.process_time() - t
    pulls, substeps = [], 0
    t = time.process_time()
    for i in cal.pick_evenly(cal.surface_stones(sys_, sc, setup), per_seed):
        for name in DIRECTIONS:
            r = cal.pull_stone(sys_, state, i, dirs[name], setup, seed=seed, name=name)
            pulls.append({"stone": int(i), "direction": name, "peak": r.peak, "weight": r.weight})
            substeps += _pull_substeps(r, setup, float(sys_.params.dt))
    return {"pulls": pulls, "cpu_pack": cpu_pack, "cpu_pulls": time.process_time() - t, "substeps": substeps,
            "cpu": cpu_pack + time.process_time() - t + 0.0}


def _snapshot(st):
    pos = np.asarray(st.stone_pos, float).copy()
    return pos, np.asarray(st.stone_active).astype(bool).copy()


def member_job(steps: float, seed: int, after: float, switch: bool = False) -> dict:
    """A release-study member: packing, spin-up held, `after` s after the release, as run.py steps it.
    switch: packed, settled and spun up at the scene's own step (32 per contact), the DEM step changed to
    the setting's at the release (the same weir let go; only the step differs)."""
    own, sc = scenes(steps)[1], load_scene(MEMBER_SCENE)
    sc = (sc if switch else own).replace(seed=seed)
    c0 = time.process_time()
    sim = builder.build_simulation(sc)
    cpu_build = time.process_time() - c0
    st = sim.stones
    release = sc.hydrograph.ramp_start
    times, pos, active = [float(sim.time)], *[[a] for a in _snapshot(st)]
    st.held = True
    c0 = time.process_time()
    t = float(sim.time)
    while t < release - 1e-9:
        t = min(release, t + WINDOW)
        sim.advance(t)
    cpu_spin = time.process_time() - c0
    if switch:  # the same stiffness (steps x dt kept), the setting's step
        p, q = st.params, builder.dem_params(own)
        p.dt, p.contact_steps = q.dt, q.contact_steps
        st.params = p
    st.held = False
    mobile = int(np.sum(np.asarray(st.stone_active).astype(bool) & ~np.asarray(st.stone_fixed).astype(bool)))
    sub0, c0 = int(st.steps), time.process_time()
    while t < release + after - 1e-9:
        t = min(release + after, t + WINDOW)
        sim.advance(t)
        times.append(float(sim.time))
        p_, a = _snapshot(st)
        pos.append(p_)
        active.append(a)
    cpu_after = time.process_time() - c0
    d = 2.0 * np.asarray(st.stone_radius, float)
    rem = removal_times(times, np.array(pos), d, np.array(active), np.asarray(st.stone_fixed).astype(bool))
    lost = np.isfinite(rem)
    at_release = lost & (rem <= release + RELEASE_WINDOW)
    return {"stones": int(d.size), "mobile": mobile, "lost_release": int(at_release.sum()), "lost_end": int(lost.sum()),
            "substeps": int(st.steps) - sub0, "flow_steps": int(sim.step_count),
            "after": after, "simulated": float(sim.time), "cpu_build": cpu_build, "cpu_spin_up": cpu_spin,
            "cpu_after": cpu_after, "cpu": cpu_build + cpu_spin + cpu_after, "dt": float(st.params.dt),
            "kn": float(st.stiffness_normal), "stable_dt": float(st.stable_dt())}


def run_job(part: str, steps: float, seed: int, args) -> dict:
    """The job's record; a step the DEM refuses as unstable is recorded as refused with its message (clumps:
    a step above the mix's stable step, which the calibration's clump_params would lower, is not run)."""
    if shape_of()["mix"] is not None:
        s = stable_step(scenes(steps)[0 if part in ("heap", "pull") else 1])
        if s["dt"] > s["stable_dt"]:
            return {"refused": f"dt = {s['dt']:.4g} s exceeds the clumps' stable step {s['stable_dt']:.4g} s"}
    try:
        if part == "heap":
            return heap_job(steps, seed)
        if part == "pull":
            return pull_job(steps, seed, args.per_seed)
        return member_job(steps, seed, args.after, switch=part == "release")
    except (ValueError, RuntimeError) as e:
        if "stable step" not in str(e):
            raise
        return {"refused": str(e)}


def job_path(out: Path, part: str, steps: float, seed: int) -> Path:
    return out / f"{part}_steps{steps:g}_seed{seed}.json"


def load(out: Path, part: str, steps: float, seed: int):
    p = job_path(out, part, steps, seed)
    return json.loads(p.read_text()) if p.exists() else None


# ------------------------------------------------------------------------------------------------
# tables


def _mean(v):
    v = [x for x in v if x is not None]
    return float(np.mean(v)) if v else math.nan


def _fmt(v, f="{:.2f}"):
    return "-" if v is None or (isinstance(v, float) and math.isnan(v)) else f.format(v)


def _ratio(cpu, ref):
    return _fmt(cpu / ref if ref and not math.isnan(ref) else math.nan, "x{:.2f}")


def collect(out: Path, part: str, steps, seeds) -> dict:
    """{steps: [record per seed kept]}; a setting whose jobs the DEM refused holds the refusal."""
    got = {}
    for n in steps:
        recs = [dict(r, seed=s) for s, r in ((s, load(out, part, n, s)) for s in seeds) if r is not None]
        if recs:
            got[n] = recs
    return got


def same_seeds(ref_recs, recs):
    """The reference's records of the seeds in recs (deviations over the same packings)."""
    seeds = {r["seed"] for r in recs}
    return [r for r in ref_recs if r["seed"] in seeds]


def _sd(v):
    v = [x for x in v if x is not None]
    return float(np.std(v, ddof=1)) if len(v) > 1 else math.nan


def spread_line(what: str, values) -> list:
    """The reference's spread between packings (or heaps), the yardstick of the deviations."""
    return ["", f"The reference's spread: {what} {_fmt(_sd(values))} (sample standard deviation over "
            f"{len(values)})."]


def _seeds(recs) -> str:
    return ", ".join(str(r["seed"]) for r in recs)


def _each(recs, key: str, f: str = "{}") -> str:
    """The records' values of key side by side (the spread between packings)."""
    return " / ".join(_fmt(r[key], f) for r in recs)


def _ran(recs) -> list:
    """The records of the seeds the DEM ran (not refused)."""
    return [r for r in recs if "refused" not in r]


def _seeds_cell(recs) -> str:
    """'n (seeds)', with the seeds whose job the DEM refused (a lighter stone drawn: a shorter stable step)."""
    ok, no = _ran(recs), [r for r in recs if "refused" in r]
    return f"{len(ok)} ({_seeds(ok)})" + (f"; seed {_seeds(no)} refused" if no else "")


def setting_rows(head: list, got: dict, refs: list, cells) -> list:
    """A table: head (its title, a blank line, the header and the alignment row), then a row per setting in
    got's order (the steps, ascending): the steps, then cells(every, recs, refs) of its records (every), those
    the DEM ran (recs) and the reference's records the DEM ran (refs); 'refused' and empty cells where it ran
    none of its seeds."""
    width = head[-1].count("|") - 1
    rows = list(head)
    for n, every in got.items():
        recs = _ran(every)
        rest = " | ".join(cells(every, recs, refs)) + " |" if recs else "refused |" + " |" * (width - 2)
        rows.append(f"| {n:g} | {rest}")
    return rows


def _cost(recs, refs, cost):
    """The mean of cost(record) over recs, and its ratio to the reference's mean ('x0.00')."""
    c = _mean([cost(r) for r in recs])
    return c, _ratio(c, _mean([cost(r) for r in refs]))


def heap_table(got: dict, ref: float) -> list:
    def cells(every, recs, refs):
        m, (c, x) = _mean([r["angle"] for r in recs]), _cost(recs, refs, lambda r: r["cpu"])
        base = _mean([r["angle"] for r in same_seeds(refs, recs)])
        rest = " / ".join("yes" if r["settled"] else "no" for r in recs)
        return [_seeds_cell(every), _each(recs, "angle", "{:.1f}"), f"{m:.1f}", f"{m - base:+.1f}", rest,
                f"{c:.0f}", x]

    o = shape_of()
    head = [f"## (b) Dry angle of repose ({o['heap']['n_stones']} {SHAPE}s, mu_r = {o['mu_r']:g})", "",
            "| steps per contact | heaps (seeds) | angle per heap [deg] | mean [deg] | deviation of the mean from "
            "the reference [deg] | at rest | CPU per heap [s] | CPU ratio |", "|---:|---|---|---:|---:|---|---:|---:|"]
    refs = _ran(got.get(ref, []))
    return setting_rows(head, got, refs, cells) + spread_line("angle [deg]", [r["angle"] for r in refs])


def _pull_means(recs) -> dict:
    return {d: _mean([p["peak"] for r in recs for p in r["pulls"] if p["direction"] == d]) for d in DIRECTIONS}


def pull_table(got: dict, ref: float) -> list:
    def cells(every, recs, refs):
        m, base = _pull_means(recs), _pull_means(same_seeds(refs, recs))
        peaks = {d: [p["peak"] for r in recs for p in r["pulls"] if p["direction"] == d] for d in DIRECTIONS}
        npulls = len(peaks[DIRECTIONS[0]])
        dev = " / ".join(f"{100 * (m[d] / base[d] - 1):+.0f}" for d in DIRECTIONS)
        c, x = _cost(recs, refs, lambda r: r["cpu"])
        us, xus = _cost(recs, refs, lambda r: 1e6 * r["cpu_pulls"] / r["substeps"])
        return ([f"{_seeds_cell(every)}, {npulls} pulls"] +
                [f"{m[d]:.2f} ({' / '.join(f'{v:.2f}' for v in peaks[d])})" for d in DIRECTIONS] +
                [dev, f"{c:.0f}", x, f"{us:.1f} ({xus})"])

    head = ["## (a) Pull-out forces (the paper: 2.81 / 3.04 / 4.75 N)", "",
            "| steps per contact | weirs (seeds), pulls per direction | vertical [N] | normal [N] | horizontal [N] | "
            "deviation of the means from the reference [%] | CPU per weir (packing + pulls) [s] | CPU ratio | "
            "CPU per pull substep [us] (ratio) |", "|---:|---|---|---|---|---|---:|---:|---|"]
    refs = _ran(got.get(ref, []))
    pulls = [p for r in refs for p in r["pulls"]]
    sds = " / ".join(_fmt(_sd([p["peak"] for p in pulls if p["direction"] == d])) for d in DIRECTIONS)
    return setting_rows(head, got, refs, cells) + [
        "", f"The reference's spread between the pulled stones (sample standard deviation, vertical / normal / "
            f"horizontal): {sds} N."]


MEMBER_TITLES = {
    "member": "## (c) Stones lost at the release of a Maeno member ({shape}s, mu_r = {mu_r:g}, consistent coupling)",
    "release": "## (c') The same weir let go at each step: packed, settled and spun up at 32 steps per contact, "
               "the DEM step changed at the release",
}


def member_table(got: dict, ref: float, part: str = "member") -> list:
    def cells(every, recs, refs):
        m, (c, x) = _mean([r["lost_release"] for r in recs]), _cost(recs, refs, lambda r: r["cpu"])
        lost0 = _mean([r["lost_release"] for r in same_seeds(refs, recs)])
        ca, xa = _cost(recs, refs, lambda r: r["cpu_after"])
        ns, xns = _cost(recs, refs, lambda r: 1e9 * r["cpu_after"] / (r["mobile"] * r["substeps"]))
        return [_seeds_cell(every), _each(recs, "lost_release"), f"{m:.1f}", _fmt(m - lost0, "{:+.1f}"),
                _each(recs, "lost_end"), f"{c:.0f} ({x})", f"{ca / recs[0]['after']:.2f} ({xa})", f"{ns:.0f} ({xns})",
                f"{_mean([r['substeps'] / r['after'] for r in recs]):.0f}"]

    head = [MEMBER_TITLES[part].format(shape=SHAPE, mu_r=shape_of()["mu_r"]), "",
            "| steps per contact | members (seeds) | lost within 2 s of the release, per member | mean | deviation "
            "of the mean from the reference | lost by the end, per member | CPU per member [s] (ratio) | CPU per "
            f"simulated s after the release [s] (ratio) | ns per {SHAPE}-substep after the release (ratio) | DEM "
            "substeps per simulated s |", "|---:|---|---|---:|---:|---|---|---|---|---:|"]
    refs = _ran(got.get(ref, []))
    return setting_rows(head, got, refs, cells) + spread_line("stones lost within 2 s",
                                                              [r["lost_release"] for r in refs])


def settings_table(steps) -> list:
    probe = "the mix at its sizes" if shape_of()["mix"] else "two lightest spheres"
    lines = ["## The settings", "",
             f"| steps per contact | DEM step [s] | stable step of {probe} [s] | step / stable | "
             "k_n [N/m] | the DEM |", "|---:|---:|---:|---:|---:|---|"]
    for n in steps:
        s = stable_step(scenes(n)[1])
        ok = "accepts" if s["dt"] <= s["stable_dt"] else "refuses (step above stable_dt())"
        lines.append(f"| {n:g} | {s['dt']:.4g} | {s['stable_dt']:.4g} | {s['dt'] / s['stable_dt']:.2f} | "
                     f"{s['kn']:.4g} | {ok} |")
    return lines


# ------------------------------------------------------------------------------------------------
# figure: each answer against the CPU of its job, relative to the reference


PANELS = (  # (title of the y axis, [(part, CPU key, values of a setting's records)])
    ("pull-out force, mean [N]", [("pull", "cpu", _pull_means)]),
    ("dry angle of repose [deg]", [("heap", "cpu", lambda rs: {"heap": _mean([r["angle"] for r in rs])})]),
    ("stones lost within 2 s of the release, mean",
     [("member", "cpu", lambda rs: {"member (packed at the step)": _mean([r["lost_release"] for r in rs])}),
      ("release", "cpu_after", lambda rs: {"same weir, step changed at the release": _mean([r["lost_release"]
                                                                                            for r in rs])})]),
)


def _series(got: dict, ref: float, key: str, value) -> dict:
    """{name: [(CPU / the reference's, value, steps, [the value of each seed's job])]} of one part's settings."""
    cpu0 = _mean([r[key] for r in got[ref]])
    out = {}
    for n, rs in got.items():
        each = [value([r]) for r in rs]
        for name, v in value(rs).items():
            out.setdefault(name, []).append((_mean([r[key] for r in rs]) / cpu0, v, n, [e[name] for e in each]))
    return out


def figure(data: dict, ref: float, path: Path) -> None:
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, axes = plt.subplots(1, 3, figsize=(12.5, 4.0))
    k = 0
    for ax, (label, parts) in zip(axes, PANELS):
        for part, key, value in parts:
            got = {n: _ran(rs) for n, rs in data.get(part, {}).items() if _ran(rs)}
            if ref not in got:
                continue
            for name, pts in _series(got, ref, key, value).items():
                pts.sort()
                color = f"C{k}"
                k += 1
                ax.plot([q[0] for q in pts], [q[1] for q in pts], "o-", color=color, label=name)
                for x, y, n, each in pts:  # each seed's job: the spread between packings
                    ax.plot([x] * len(each), each, "_", color=color, ms=9)
                    ax.annotate(f"{n:g}", (x, y), textcoords="offset points", xytext=(3, 3), fontsize=7)
        ax.set_xlabel("CPU / the reference's")
        ax.set_ylabel(label)
        if ax.lines:
            ax.legend(fontsize=7)
    fig.suptitle(f"3D {SHAPE}s: mean (dots) and each packing or heap (dashes) against the CPU; labels: DEM steps "
                 f"per contact (reference {ref:g}" + ("; the same weir: the CPU after the release" if SHAPE == "sphere"
                                                   else "") + ")", fontsize=9)
    fig.tight_layout()
    path.parent.mkdir(parents=True, exist_ok=True)
    fig.savefig(path, dpi=110)
    plt.close(fig)


def main(argv=None) -> Path:
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--shape", default="sphere", choices=tuple(SHAPES), help="the stones measured")
    p.add_argument("--steps", default="16,24,26,32,48,64",
                   help="DEM steps per contact [-], each in [5, 1000]; the largest is the reference")
    p.add_argument("--parts", default="member,heap,pull", help=f"of {', '.join(PARTS)}, run in this order")
    p.add_argument("--seeds", default="0,1", help="packings' and heaps' seeds, each in [0, 10000]")
    p.add_argument("--per-seed", type=int, default=2, help="stones pulled per weir, in [1, 10]")
    p.add_argument("--after", type=float, default=10.0, help="member: seconds run after the release [s], in (0, 120]")
    p.add_argument("--no-run", action="store_true", help="only the tables of the jobs kept in --out")
    p.add_argument("--out", type=Path, help="the jobs kept (default out/dem_step_3d, with clumps ..._clumps)")
    p.add_argument("--results", type=Path, help="default benchmarks/results/dem_step_3d.md (clumps: _clumps.md)")
    p.add_argument("--figure", type=Path, help="default docs/figures/dem_step_3d.png (clumps: _clumps.png)")
    args = p.parse_args(argv)
    global SHAPE
    SHAPE = args.shape
    tail = "" if SHAPE == "sphere" else f"_{SHAPE}s"
    args.out = args.out or ROOT / "out" / f"dem_step_3d{tail}"
    args.results = args.results or ROOT / "benchmarks" / "results" / f"dem_step_3d{tail}.md"
    args.figure = args.figure or ROOT / "docs" / "figures" / f"dem_step_3d{tail}.png"
    steps = sorted(parse_numbers(args.steps, "--steps", 5.0, 1000.0))
    seeds = parse_numbers(args.seeds, "--seeds", 0, 10000, int)
    parts = [s.strip() for s in args.parts.split(",") if s.strip()]
    for part in parts:
        if part not in PARTS:
            raise ValueError(f"--parts: {part!r} is not one of {', '.join(PARTS)}")
    if "release" in parts and SHAPE != "sphere":
        raise ValueError("--parts: 'release' (the spheres' own weir let go at each step) is for --shape sphere only")
    if not 1 <= args.per_seed <= 10:
        raise ValueError(f"--per-seed = {args.per_seed} is outside the allowed range [1, 10]")
    if not 0.0 < args.after <= 120.0:
        raise ValueError(f"--after = {args.after} s is outside the allowed range (0, 120]")
    args.out.mkdir(parents=True, exist_ok=True)
    _core.set_threads(1)
    ref = steps[-1]
    # the reference first, then from the cheapest: an interrupted run holds the reference and the cheap end
    order = [ref] + steps[:-1]
    for part in [] if args.no_run else parts:
        for n in order:
            for s in seeds:
                path = job_path(args.out, part, n, s)
                if path.exists():
                    continue
                rec = dict(run_job(part, n, s, args), load=os.getloadavg()[0])
                path.write_text(json.dumps(rec) + "\n")
                print(f"{part} steps {n:g} seed {s}: " + ", ".join(f"{k} {v}" for k, v in rec.items() if k != "pulls"),
                      flush=True)
    data = {part: collect(args.out, part, steps, seeds) for part in PARTS}
    write(args, steps, seeds, ref, data)
    figure(data, ref, args.figure)
    print(args.results)
    return args.results


def _loads(data) -> str:
    """The one-minute load averages the jobs recorded at their ends."""
    v = [r["load"] for part in data.values() for recs in part.values() for r in recs if "load" in r]
    return f"load average {min(v):.1f}-{max(v):.1f} at the ends of {len(v)} jobs" if v else "load not recorded"


def write(args, steps, seeds, ref, data) -> None:
    shape = "" if SHAPE == "sphere" else f"--shape {SHAPE} "
    command = (f"nice -n 5 env PYTHONPATH=python python3 benchmarks/dem_step_3d.py {shape}--steps {args.steps} "
               f"--parts {args.parts} --seeds {args.seeds} --per-seed {args.per_seed} --after {args.after:g}"
               + (" --no-run" if args.no_run else ""))
    lines = [f"# The 3D {SHAPE}s' DEM step: the answers against the cost", "",
             f"`{command}`, {time.strftime('%Y-%m-%d %H:%M UTC', time.gmtime())}, {platform.machine()}, one core, "
             f"one job after the other on a machine shared with other jobs (2 cores; {_loads(data)}); CPU is each "
             "job's process time. Jobs kept in `" + shown_path(args.out, ROOT) + "` (run by calls of this script "
             "with subsets of --parts, --steps and --seeds; each job once).", "",
             f"The knob: N DEM steps per contact at the same contact stiffness (`vofdem.study.setting(ref, "
             f"'dem_steps', N)`: dem_dt = 2e-3 s / N), mu_r = {shape_of()['mu_r']:g}; the reference is the finest "
             f"setting, N = {ref:g}. Deviations are from the reference's mean over the same seeds; the spread between the "
             "packings is the per-seed values side by side. A '-' or a missing row: not run.", ""]
    lines += settings_table(steps) + [""]
    lines += pull_table(data["pull"], ref) + [""]
    lines += heap_table(data["heap"], ref) + [""]
    lines += member_table(data["member"], ref) + [""]
    if data["release"]:
        lines += member_table(data["release"], ref, "release") + [""]
    refusals = {}
    for part in data.values():
        for n, recs in part.items():
            r = next((r for r in recs if "refused" in r), None)
            if r is not None and n not in refusals:
                refusals[n] = f"Refused at {n:g} steps per contact (seed {r['seed']}): {r['refused']}"
    lines += [refusals[n] for n in sorted(refusals)]
    lines += ["", f"Figure: `{shown_path(args.figure, ROOT)}`.", ""]
    args.results.parent.mkdir(parents=True, exist_ok=True)
    args.results.write_text("\n".join(lines), encoding="utf-8")


if __name__ == "__main__":
    main()
