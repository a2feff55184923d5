#!/usr/bin/env python3
"""The weir's margin under its own seepage load: by how much the water's load at the release must be
multiplied before the stones move (a load factor, as a slope's factor of safety), per stone model and
rolling resistance.

Per scene and seed: the weir is packed and settled as a run does it, the stones held through the
spin-up at the first discharge (as the runs hold them), and the water's force on each stone at the
release read (the drag and the pressure-gradient force, DEMSystem.stone_force_ext and the linear drag's
pull). The flow is then frozen and the stones let go: the DEM alone steps with each stone's force set to
s times its force at the release, s raised in levels, each held for --hold seconds (buoyancy by the wet
fractions at the release). Per level: the free stones that moved more than half their diameter from where
they lay at the release (or left the domain). The same packing and loads are replayed for each rolling
resistance of --mu-r (stone-stone and stone-wall, set on the DEM's parameters), so the rolling
resistance alone changes between those rows.

What it cannot say: the load does not follow the stones (a moved stone keeps its force; the flow does
not redistribute), and a level lasts --hold seconds, so a slow creep may be missed. It measures the
packing's resistance against this load, the quantity the run's release tests at once.

    python3 studies/load_factor.py --scenes maeno2008_spheres_rolling_consistent --seeds 0-3 \
        --mu-r 0 0.2 0.4 0.8 --discharges 10 14 --tag spheres

Writes studies/results/load_factor_<tag>.md and docs/figures/load_factor_<tag>.png; keeps each finished
case in out/load_factor/load_factor_<tag>.jsonl, so that a second call runs only the cases not finished.
"""
from __future__ import annotations

import argparse
import json
import math
import time
from pathlib import Path

import numpy as np

from vofdem.calibration import rolling_step
from vofdem.ensemble import parse_seeds
from vofdem.run import build_simulation
from vofdem.scene import load_scene
from vofdem.study import number_or_dash as _f, submerged_weight

ROOT = Path(__file__).resolve().parents[1]
LEVELS = (0.0, 0.25, 0.5, 0.625, 0.75, 0.875, 1.0, 1.25, 1.5, 1.75, 2.0, 2.5, 3.0)
FAILED_SHARE = 0.05  # a slope failure: this share of the free stones moved


def spin_up(scene):
    """The simulation after the scene's packing, settling and spin-up with the stones held."""
    sim = build_simulation(scene)
    t_tab, q_tab = scene.hydrograph.table(scene.duration)
    sim.set_inflow_table(np.asarray(t_tab, float), np.asarray(q_tab, float))
    sim.stones.held = True
    sim.advance(scene.hydrograph.ramp_start)
    return sim


def release_loads(stones) -> np.ndarray:
    """Each stone's water force at rest [N] (n, 2): the external force plus the linear drag's pull c U."""
    return np.asarray(stones.stone_force_ext) + np.asarray(stones.stone_drag_coef)[:, None] * np.asarray(
        stones.stone_drag_vel)


def _positions(stones) -> np.ndarray:
    """(n, 3) positions: x, z and, for stones across the width, y (0 for stones in the plane)."""
    p = np.asarray(stones.stone_pos)
    y = np.asarray(stones.stone_y) if stones.shape in ("sphere", "clump") else np.zeros(len(p))
    return np.column_stack([p[:, 0], p[:, 1], y])


def ramp(stones, state: dict, params, mu_r, levels, hold: float) -> list:
    """Rows (s, moved, removed, max speed [m/s]) of the DEM alone under s times the release's loads, from
    the released state and the scene's DEM parameters; mu_r: the rolling resistance set on them (None: the
    scene's). Stops two levels after the slope failed, not before s = 1."""
    stones.import_state(state)
    stones.held = False
    stones.params = params
    if mu_r is not None:
        p = stones.params
        p.rolling_friction_stone = p.rolling_friction_wall = float(mu_r)
        p.dt, p.contact_steps = rolling_step(p.dt, p.contact_steps, mu_r)  # as calibration.with_rolling
        stones.params = p
    f_ext, u_drag = np.array(stones.stone_force_ext), np.array(stones.stone_drag_vel)
    free = ~np.asarray(stones.stone_fixed).astype(bool)
    start, r = _positions(stones), np.asarray(stones.stone_radius)
    rows, after = [], None
    for s in levels:
        stones.stone_force_ext[:] = s * f_ext
        stones.stone_drag_vel[:] = s * u_drag  # the linear drag pulls towards s U (its pull at rest: s c U)
        stones.advance(hold)
        gone = free & ~np.asarray(stones.stone_active).astype(bool)
        moved = free & ((np.linalg.norm(_positions(stones) - start, axis=1) > r) | gone)
        rows.append((s, int(moved.sum()), int(gone.sum()), float(stones.max_speed())))
        if after is None and moved.sum() >= FAILED_SHARE * free.sum():
            after = 0
        elif after is not None:
            after += 1
            if after >= 2 and s >= 1.0:  # the count at the release's own load is always measured
                break
    return rows


def first_level(rows, count: float) -> float:
    """The first load factor at which at least `count` free stones moved (nan: none of the levels)."""
    return next((s for s, moved, _, _ in rows if moved >= count), math.nan)


def load_summary(stones) -> dict:
    """The free stones' downstream and upward loads at the release over their submerged weights."""
    free = ~np.asarray(stones.stone_fixed).astype(bool)
    weight = submerged_weight([stones.volume(i) for i in range(stones.n)], stones.stone_density)
    f = release_loads(stones)[free] / weight[free, None]
    return {"free": int(free.sum()), "fx_mean": float(f[:, 0].mean()), "fx_p95": float(np.percentile(f[:, 0], 95)),
            "fz_mean": float(f[:, 1].mean())}


def run_case(scene, mu_rs, levels, hold: float) -> dict:
    """The spin-up of one scene (seed, discharge), then the ramps for each rolling resistance."""
    t0 = time.process_time()
    sim = spin_up(scene)
    cpu_spin = time.process_time() - t0
    stones = sim.stones
    state, params, loads = stones.export_state(), stones.params, load_summary(stones)
    out = {"loads": loads, "cpu_spin_up": cpu_spin, "ramps": {}}
    for mu in mu_rs:
        t1 = time.process_time()
        rows = ramp(stones, state, params, mu, levels, hold)
        out["ramps"][mu] = {"rows": rows, "cpu": time.process_time() - t1,
                            "first": first_level(rows, 1), "failed": first_level(rows, FAILED_SHARE * loads["free"])}
    return out


def _band(a: np.ndarray, top: str) -> str:
    """'median [smallest - largest]' of load factors, a member whose stones never moved counted above the
    largest level (top)."""
    if not np.isfinite(a).any():
        return f"{top} [{top} - {top}]"
    b = np.where(np.isfinite(a), a, np.inf)
    med = float(np.median(b))
    return f"{_f(med) if np.isfinite(med) else top} [{_f(float(b.min()))} - {_f(float(b.max())) if np.isfinite(b.max()) else top}]"


def results_md(args, cases, command: str) -> str:
    lines = [
        "# The weir's margin under its own seepage load: the load factor at which its stones move", "",
        "Generated by `studies/load_factor.py` (its docstring says what it measures and what it cannot). Per scene, "
        "seed and first discharge: the weir packed, settled and held through the scene's spin-up as a run does it; "
        "then, the flow frozen and the stones let go, the DEM alone under s times each stone's water force at the "
        f"release, s raised in levels of {args.hold:g} s each. Rolling resistance mu_r set on the same packing and "
        f"loads. First movement: a free stone moved more than half its diameter; slope failure: {FAILED_SHARE:.0%} "
        "of the free stones did. A factor below 1: the weir cannot carry the release's load; the run loses "
        "stones at the release.", "",
        f"Command: `{command}`", "",
        "## Load factor per configuration (median over the seeds [smallest - largest])", "",
        "| scene | discharge [l/s] | mu_r | seeds | first movement | slope failure | moved at s = 1 (median) |",
        "|---|---:|---:|---:|---|---|---:|"]
    top = f"> {max(args.levels):g}"
    keys = sorted({(c["scene"], c["q"], mu) for c in cases for mu in c["ramps"]}, key=str)
    for scene, q, mu in keys:
        sel = [c["ramps"][mu] for c in cases if c["scene"] == scene and c["q"] == q and mu in c["ramps"]]
        first = np.array([r["first"] for r in sel], float)
        fail = np.array([r["failed"] for r in sel], float)
        at1 = [next((m for s, m, _, _ in r["rows"] if s == 1.0), math.nan) for r in sel]
        at1 = np.array(at1, float)
        lines.append(f"| {scene} | {q:g} | {_f(mu, '{:g}')} | {len(sel)} | {_band(first, top)} | {_band(fail, top)} | "
                     f"{_f(float(np.median(at1)), '{:.0f}')} |")
    lines += ["", "## Per member", "",
              "| scene | discharge [l/s] | seed | free stones | downstream load / W' (mean, 95 %) | upward / W' (mean) | "
              "mu_r | stones moved per level s | first movement | slope failure | CPU spin-up / ramp [s] |",
              "|---|---:|---:|---:|---|---:|---:|---|---:|---:|---|"]
    for c in cases:
        ld = c["loads"]
        for mu, r in c["ramps"].items():
            moved = ", ".join(f"{s:g}: {m}" for s, m, _, _ in r["rows"])
            lines.append(f"| {c['scene']} | {c['q']:g} | {c['seed']} | {ld['free']} | {ld['fx_mean']:.3f}, "
                         f"{ld['fx_p95']:.3f} | {ld['fz_mean']:.3f} | {_f(mu, '{:g}')} | {moved} | {_f(r['first'])} | "
                         f"{_f(r['failed'])} | {c['cpu_spin_up']:.0f} / {r['cpu']:.0f} |")
    lines += ["", "W': each stone's submerged weight (rho_s - rho_w) g V. CPU: process time of one thread, on a "
              "machine shared with other jobs.", ""]
    return "\n".join(lines)


def fig(cases, path: Path) -> None:
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    groups = sorted({(c["scene"], c["q"]) for c in cases}, key=str)
    fig_, axes = plt.subplots(1, len(groups), figsize=(5.2 * len(groups), 4.0), squeeze=False)
    for ax, (scene, q) in zip(axes[0], groups):
        mus = sorted({mu for c in cases if (c["scene"], c["q"]) == (scene, q) for mu in c["ramps"]}, key=str)
        for k, mu in enumerate(mus):
            for j, c in enumerate(x for x in cases if (x["scene"], x["q"]) == (scene, q)):
                rows = c["ramps"][mu]["rows"]
                ax.plot([s for s, *_ in rows], [100.0 * m / c["loads"]["free"] for _, m, _, _ in rows], "o-",
                        color=f"C{k}", ms=3, lw=1, label=f"mu_r = {_f(mu, '{:g}')}" if j == 0 else None)
        ax.axvline(1.0, color="k", lw=0.8, ls="--")
        ax.axhline(100 * FAILED_SHARE, color="0.5", lw=0.8, ls=":")
        ax.set(xlabel="load factor s (times the water's load at the release)", ylabel="free stones moved [%]",
               title=f"{scene}, {q:g} l/s", ylim=(0, 30))
        ax.legend(fontsize=8)
    fig_.tight_layout()
    path.parent.mkdir(parents=True, exist_ok=True)
    fig_.savefig(path, dpi=110)
    plt.close(fig_)


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--scenes", nargs="+", default=["maeno2008_spheres_rolling_consistent"],
                    help="scene names in scenes/ (or paths to scene files)")
    ap.add_argument("--seeds", default="0-3", help="packings, e.g. 0-3 (default 0-3)")
    ap.add_argument("--mu-r", nargs="+", type=float, default=None,
                    help="rolling resistances to replay (default: the scene's own only)")
    ap.add_argument("--discharges", nargs="+", type=float, default=None,
                    help="first discharges [l/s] of the spin-up (default: the scene's)")
    ap.add_argument("--levels", nargs="+", type=float, default=list(LEVELS), help="load factors, rising")
    ap.add_argument("--hold", type=float, default=0.5, help="time at each level [s] (default 0.5)")
    ap.add_argument("--spin-up", type=float, default=None, help="spin-up duration [s] (default: the scene's)")
    ap.add_argument("--tag", default="spheres", help="name of the results and figure")
    ap.add_argument("--results", type=Path, default=ROOT / "studies" / "results")
    ap.add_argument("--figures", type=Path, default=ROOT / "docs" / "figures")
    ap.add_argument("--no-run", action="store_true",
                    help="run nothing: the tables of the cases finished so far (in --out)")
    ap.add_argument("--out", type=Path, default=ROOT / "out" / "load_factor",
                    help="where the finished cases are kept (a second call resumes; default out/load_factor)")
    args = ap.parse_args(argv)
    if not (0.0 < args.hold <= 10.0):
        raise ValueError(f"--hold = {args.hold} is out of range (allowed: 0 < hold <= 10 s)")
    if list(args.levels) != sorted(args.levels) or min(args.levels) < 0.0:
        raise ValueError(f"--levels = {args.levels}: load factors must be >= 0 and rising")
    cache = args.out / f"load_factor_{args.tag}.jsonl"  # one line per finished case: a rerun resumes
    cache.parent.mkdir(parents=True, exist_ok=True)
    done = {}
    if cache.exists():
        for line in cache.read_text(encoding="utf-8").splitlines():
            c = json.loads(line)
            c["ramps"] = {None if k == "null" else float(k): v for k, v in c["ramps"].items()}
            done[(c["scene"], c["q"], c["seed"])] = c
    cases = []
    for name in args.scenes:
        path = Path(name) if name.endswith(".toml") else ROOT / "scenes" / f"{name}.toml"
        base = load_scene(path)
        for q in args.discharges or [base.hydrograph.discharge_start_lps]:
            for seed in parse_seeds(args.seeds):
                if (base.name, float(q), seed) in done:
                    cases.append(done[(base.name, float(q), seed)])
                    continue
                if args.no_run:
                    continue
                scene = base.replace(seed=seed)
                scene.hydrograph.discharge_start_lps = float(q)
                if args.spin_up is not None:
                    scene.hydrograph.spin_up_duration = float(args.spin_up)
                scene.validate()
                case = run_case(scene, args.mu_r or [None], args.levels, args.hold)
                cases.append({"scene": base.name, "q": float(q), "seed": seed, **case})
                with cache.open("a", encoding="utf-8") as fh:
                    fh.write(json.dumps({**cases[-1], "ramps": {"null" if k is None else k: v
                                                                 for k, v in case["ramps"].items()}}) + "\n")
                print(f"{base.name} {q:g} l/s seed {seed}: " + ", ".join(
                    f"mu_r {_f(mu, '{:g}')}: first {_f(r['first'])} failed {_f(r['failed'])}"
                    for mu, r in case["ramps"].items()), flush=True)
    parts = ["python3 studies/load_factor.py", "--scenes", *args.scenes, "--seeds", args.seeds]
    if args.mu_r:
        parts += ["--mu-r", *[f"{m:g}" for m in args.mu_r]]
    if args.discharges:
        parts += ["--discharges", *[f"{q:g}" for q in args.discharges]]
    if list(args.levels) != list(LEVELS):
        parts += ["--levels", *[f"{s:g}" for s in args.levels]]
    if args.hold != 0.5:
        parts += ["--hold", f"{args.hold:g}"]
    if args.spin_up is not None:
        parts += ["--spin-up", f"{args.spin_up:g}"]
    parts += ["--tag", args.tag]
    if not cases:
        raise ValueError(f"no case of these scenes, discharges and seeds has finished in '{args.out}'")
    args.results.mkdir(parents=True, exist_ok=True)
    out = args.results / f"load_factor_{args.tag}.md"
    out.write_text(results_md(args, cases, " ".join(parts)), encoding="utf-8")
    fig(cases, args.figures / f"load_factor_{args.tag}.png")
    print(f"wrote {out}")
    return cases


if __name__ == "__main__":
    main()
