#!/usr/bin/env python3
"""Why the 3D weir loses stones at the release: the stones lost when the held stones are let go at the end
of the spin-up, against the stones' friction angle (the dry heap's angle of repose), as a sensitivity of the
Maeno weir of 3D stones (scenes/maeno2008_spheres_rolling_consistent.toml), not a fit: the scene's own
values stay as they are.

Configurations: the scene's spheres at each rolling friction of --mu-r (stone-stone and stone-wall together,
the DEM step as calibration.with_rolling gives it) and clumps (stones.shape = 'clump', the default mix of
calibration_3d.ClumpMix) at each of --clump-mu-r, their DEM step that of the clump calibration
(calibration_3d.clump_params: 0.9 of the clumps' stable step at the scene's contact stiffness). Each
configuration is an ensemble over the same seeds (packings' seeds), run one member after the other in this
process (vofdem.ensemble.run_ensemble, workers=0; resumable), each member the settling, the spin-up with the
stones held, and --after seconds of the ramp after the release (scene.end_time), not the whole scenario.

Per member: the stones lost within --window seconds after the release (their removal times, vofdem.analysis),
whether a stage began in that window, the stones lost by the run's end (the outcome's 'removed'), and from
the last snapshot before the release (the stones still held): the water's load (drag + pressure-gradient
force, as studies/failure_mechanism.py) on the downstream slope's surface stones (calibration.
slope_surface_stones over the whole slope height, side walls included, of the stones initially on the
downstream slope or its shoulder) over each stone's submerged weight, and the friction angle a lone stone on the slope
would need against the mean load, slope + atan(f_x / (1 - f_z)) (sliding on a plane, no interlocking);
the weir's packed porosity (the packer's report, the prism across the flume). The heap angles come from
benchmarks/results/sphere_calibration.md and clump_calibration.md (not measured here). When --after reaches
the ramp's end, the page adds the verdict's tables of the members run (studies/maeno2008_verdict.py
config_md: each event's Kaplan-Meier median and band, the stage shares, the crest lowering, next to the
experiment and the paper's model).

    nice -n 5 env PYTHONPATH=python python3 studies/release_stability.py --seeds 0-3 \\
        --mu-r 0,0.2,0.4,0.8 --clump-mu-r 0

Writes studies/results/release_stability.md and docs/figures/release_stability.png; the ensembles go to
out/release_stability/<configuration>/ (each member's packing.json holds its packing's report). More packings
of a configuration on a page of their own, the earlier page's members of that configuration in its tables:

    nice -n 5 env PYTHONPATH=python python3 studies/release_stability.py --seeds 1-3 --mu-r '' \
        --clump-mu-r 0 --earlier studies/results/release_stability.md \
        --results studies/results/release_stability_clumps.md \
        --figure docs/figures/release_stability_clumps.png --out out/release_stability_clumps
"""

import argparse
import functools
import json
import math
import re
import sys
from dataclasses import dataclass
from pathlib import Path
from types import SimpleNamespace

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parent))
from vofdem import builder  # noqa: E402
from vofdem.analysis import REGIONS, classify_regions  # noqa: E402
from vofdem.calibration import PullSetup, slope_surface_stones, with_rolling  # noqa: E402
from vofdem.calibration_3d import ClumpMix, clump_params  # noqa: E402
from vofdem.ensemble import finished_outcomes, parse_seeds, run_ensemble  # noqa: E402
from vofdem.io import RunData  # noqa: E402
from vofdem.run import analyse_run  # noqa: E402
from vofdem.scene import load_scene  # noqa: E402
from vofdem.study import number_or_dash as _f, shown_path, sphere_volume, submerged_weight  # noqa: E402
from vofdem.study import parse_numbers  # noqa: E402
from maeno2008_verdict import config_md  # noqa: E402

ROOT = Path(__file__).resolve().parents[1]
PACKING_FILE = "packing.json"
NO_RUN_NOTE = (" With --no-run: the tables of the members finished there, which earlier calls of this script ran "
               "(a configuration or a set of seeds at a time); 'not run': a member no call ran.")
# the whole slope's surface: the pull's selection (calibration.PullSetup) from the bed to the crest
WHOLE_SLOPE = PullSetup(z_low=0.0, z_high=1.0)
# the downstream slope with its shoulder (vofdem.analysis regions of the stones' initial places)
SLOPE_REGIONS = ("shoulder", "downstream slope")
# a member's status on the page when its row comes from an earlier page (--earlier)
EARLIER = "completed, earlier page"
MEMBER_COLUMNS = 13  # the per-member table's


@dataclass(frozen=True)
class Config:
    """One configuration of the stones: the shape ('sphere' or 'clump') and the rolling friction mu_r [-]."""

    shape: str
    mu_r: float

    @property
    def name(self) -> str:
        return f"{self.shape}s_mu_r={self.mu_r:g}"

    @property
    def label(self) -> str:
        return f"{self.shape}s, mu_r = {self.mu_r:g}"

    def scene(self, base):
        """The base scene with this shape and rolling friction, at the DEM step the stones need."""
        s = base.with_value("stones.shape", self.shape) if base.stones.shape != self.shape else base
        s = with_rolling(s, self.mu_r)
        return with_clump_step(s) if self.shape == "clump" else s


def with_clump_step(scene):
    """The scene with the clump calibration's DEM step (calibration_3d.clump_params) at its contact stiffness."""
    st = scene.stones
    p = clump_params(builder.dem_params(scene), ClumpMix(), st.diameter, st.diameter_spread, st.density)
    s = scene.with_value("numerics.dem_dt", float(p.dt))
    return s.with_value("numerics.dem_contact_steps", float(p.contact_steps)).validate()


def build_recording(scene, out_dir: Path):
    """builder.build_simulation of a member, keeping its packing's report in out_dir/seed<N>/packing.json
    (run_ensemble's `build`: the members' directories are seed<N> without varied parameters)."""
    packing: dict = {}
    sim = builder.build_simulation(scene, packing)
    if "report" not in packing:  # a resumed member, built from its checkpoint: its first build wrote the file
        return sim
    rep = packing.get("report")
    rec = {"porosity": None if rep is None else float(rep.porosity),
           "stones": None if rep is None else int(rep.n_stones), "fixed": None if rep is None else int(rep.n_fixed)}
    member = Path(out_dir) / f"seed{scene.seed}"
    member.mkdir(parents=True, exist_ok=True)
    (member / PACKING_FILE).write_text(json.dumps(rec) + "\n", encoding="utf-8")
    return sim


def heap_angles() -> dict:
    """{(shape, mu_r): mean dry heap angle [deg]} from the calibrations' summary tables."""
    res = ROOT / "benchmarks" / "results"
    out = {}
    sph = res / "sphere_calibration.md"
    if sph.exists():
        for m in re.finditer(r"^\| ([0-9.]+) \| ([0-9.]+) \+- [0-9.]+ \(\d+\) \|", sph.read_text(), re.M):
            out[("sphere", float(m.group(1)))] = float(m.group(2))
    clu = res / "clump_calibration.md"
    if clu.exists():
        for m in re.finditer(r"^\| clumps, mu_r = ([0-9.]+) \| ([0-9.]+)", clu.read_text(), re.M):
            out[("clump", float(m.group(1)))] = float(m.group(2))
    return out


def release_index(data, release: float) -> int:
    """The last snapshot at or before the release (the stones still held)."""
    return max(int(np.searchsorted(data.times, release + 1e-9)) - 1, 0)


def surface_loads(data, scene, k: int) -> dict:
    """The water's load on the downstream slope's surface stones at snapshot k, over their submerged weight."""
    w = scene.weir
    snap = SimpleNamespace(shape="sphere", stone_pos=data.pos[k], stone_radius=0.5 * data.diameter,
                           stone_y=data.y[k] if data.y is not None else np.zeros(len(data.diameter)),
                           stone_active=data.active[k], stone_fixed=data.fixed.astype(int),
                           params=SimpleNamespace(width=data.width if data.width is not None else math.inf))
    surface = slope_surface_stones(snap, scene, WHOLE_SLOPE, wall_clearance=0.0 if data.y is not None else None)
    region = classify_regions(data.pos[0, :, 0], w, float(np.mean(data.diameter)))
    idx = np.array([i for i in surface if region[i] in SLOPE_REGIONS], int)
    if idx.size == 0:
        return {"surface": 0, "load_x": math.nan, "load_x_max": math.nan, "load_z": math.nan, "phi_needed": math.nan}
    load = (data.force_drag[k, idx] + data.force_pressure[k, idx]) / submerged_weight(
        sphere_volume(data.diameter[idx]), scene.stones.density)[:, None]
    fx, fz = float(np.mean(load[:, 0])), float(np.mean(load[:, 1]))
    return {"surface": int(idx.size), "load_x": fx, "load_x_max": float(np.max(load[:, 0])), "load_z": fz,
            "phi_needed": needed_angle(w.downstream_slope_deg, fx, fz)}


def needed_angle(slope_deg: float, fx: float, fz: float) -> float:
    """Friction angle [deg] that holds a lone stone on the slope under loads fx (downstream), fz (up) in
    units of its submerged weight: the resultant's tilt from the slope's normal."""
    return slope_deg + math.degrees(math.atan2(fx, 1.0 - fz))


def member_row(cfg: Config, out: dict, member_dir: Path, window: float) -> dict:
    """The release's figures of one finished member (its outcome `out`, its run.h5)."""
    row = {"config": cfg.label, "seed": int(out["seed"]), "status": out["status"],
           "cpu": float(out.get("cpu_seconds") or math.nan), "removed": out.get("removed")}
    pk = member_dir / PACKING_FILE
    row["porosity"] = json.loads(pk.read_text())["porosity"] if pk.exists() else None
    if out["status"] != "completed":
        return row
    data = RunData(member_dir / "run.h5")
    scene = data.scene()
    a = analyse_run(data, scene)
    release = scene.hydrograph.ramp_start
    t = a.removal_time
    lost = np.isfinite(t) & (t > release) & (t <= release + window)
    st = [s for s in a.stages if s.start_time <= release + window]
    # where the stones lost at the release lay at the start (vofdem.analysis regions, as the stage tables')
    region = classify_regions(data.pos[0, :, 0], scene.weir, float(np.mean(data.diameter)))
    row["lost_where"] = {r: int(np.sum(lost & (region == r))) for r in REGIONS}
    row.update(stones=int(t.size), lost_release=int(lost.sum()), lost_end=int(np.isfinite(t).sum()),
               stage_release=len(st) > 0, stage_stones=st[0].n_stones if st else 0,
               simulated=float(data.times[-1]), q_end=float(scene.hydrograph.discharge_lps_at(float(data.times[-1]))))
    k = release_index(data, release)
    row["t_loads"] = float(data.times[k])
    row.update(surface_loads(data, scene, k))
    return row


def earlier_rows(page: Path, configs, seeds) -> list:
    """The completed members of an earlier page of this script (its per-member table) of the configurations
    run here, at seeds not run here: packings another call ran, whose ensembles need not be at hand."""
    return earlier_rows_of(page.read_text(encoding="utf-8"), configs, seeds)


def earlier_rows_of(text: str, configs, seeds) -> list:
    """earlier_rows of a page's text."""
    labels = {c.label for c in configs}
    rows = []
    for line in text.split("## Per member", 1)[-1].splitlines():
        cells = [c.strip() for c in line.strip().strip("|").split("|")]
        if len(cells) == MEMBER_COLUMNS and cells[0] in labels and cells[2] == "completed" and \
                int(cells[1]) not in seeds:
            rows.append(parsed_member(cells))
    return rows


def parsed_member(c) -> dict:
    """A row of member_row from the cells of its line in a per-member table (results_md)."""
    num = lambda v: math.nan if v == "-" else float(v)  # noqa: E731
    stage = re.fullmatch(r"yes \((\d+)\)", c[4])
    load = re.fullmatch(r"(\S+) \((\S+)\)", c[7])
    return {"config": c[0], "seed": int(c[1]), "status": EARLIER, "lost_release": int(c[3]),
            "stage_release": stage is not None, "stage_stones": int(stage.group(1)) if stage else 0,
            "lost_end": int(c[5]), "removed": int(c[5]), "surface": int(c[6]), "load_x": num(load.group(1)),
            "load_x_max": num(load.group(2)), "load_z": num(c[8]), "phi_needed": num(c[9]),
            "porosity": None if c[10] == "-" else float(c[10]), "simulated": float(c[11]), "cpu": num(c[12])}


def _done(r) -> bool:
    return r["status"] in ("completed", EARLIER)


def _median(vals) -> float:
    v = [x for x in vals if x is not None and not (isinstance(x, float) and math.isnan(x))]
    return float(np.median(v)) if v else math.nan


def config_rows(configs, rows, heaps) -> list:
    """One summary per configuration over its completed members."""
    out = []
    for cfg in configs:
        done = [r for r in rows if r["config"] == cfg.label and _done(r)]
        mine = [r for r in rows if r["config"] == cfg.label]
        lr, le = [r["lost_release"] for r in done], [r["lost_end"] for r in done]
        out.append({"config": cfg.label, "heap": heaps.get((cfg.shape, cfg.mu_r), math.nan),
                    "members": f"{len(done)} of {len(mine)}", "lost_release": lr, "lost_end": le,
                    "staged": sum(r["stage_release"] for r in done),
                    "load_x": _median([r["load_x"] for r in done]), "load_z": _median([r["load_z"] for r in done]),
                    "phi_needed": _median([r["phi_needed"] for r in done]),
                    "porosity": _median([r["porosity"] for r in mine]), "cpu": _median([r["cpu"] for r in mine])})
    return out


def _counts(v) -> str:
    return "-" if not v else f"{np.median(v):g} [{min(v)}-{max(v)}], sum {sum(v)}"


def results_md(args, base, configs, rows, summary, command) -> str:
    rel = base.hydrograph.ramp_start
    q = base.hydrograph.discharge_lps_at
    lines = ["# The release of the held stones against the stones' friction angle", "",
             f"Written by `{command}`: scene `{base.name}`, seeds {args.seeds}, each member the settling, the "
             f"{rel:g} s spin-up with the stones held and {args.after:g} s of the ramp after the release "
             f"({q(rel + 1e-6):.2f} to {q(rel + args.after):.2f} l/s), one member after the other in one process "
             "on a machine shared with other jobs (2 cores; CPU: each member's process time). Ensembles: `"
             f"{shown_path(args.out, ROOT)}/<configuration>/`." + NO_RUN_NOTE * args.no_run + _earlier_note(args, rows),
             "",
             f"Lost at the release: stones removed (moved more than their diameter) within {args.window:g} s after "
             "it; a stage at the release: a stage (vofdem.analysis) beginning in that window. Loads: the last "
             "snapshot before the release (stones held), drag + pressure-gradient force on the downstream slope's "
             "surface stones over each stone's submerged weight (x downstream, z up); the angle needed: slope + "
             "atan(f_x / (1 - f_z)) of the mean load, a lone stone sliding on the slope. Heap: the dry heap's "
             "angle of repose from the calibrations (`benchmarks/results/sphere_calibration.md`, "
             "`clump_calibration.md`; '-': not measured). Porosity: the packed prism's (the packer's report).", "",
             "## Per configuration", "",
             "| stones | heap angle [deg] | members | lost at the release, median [range], sum | lost by the end, "
             "median [range], sum | members with a stage at the release | load x / W' (median of members' means) | "
             "load z / W' | angle needed [deg] | porosity (prism) | CPU per member [s] |",
             "|---|---:|---|---|---|---:|---:|---:|---:|---:|---:|"]
    for s in summary:
        lines.append(f"| {s['config']} | {_f(s['heap'], '{:.1f}')} | {s['members']} | {_counts(s['lost_release'])} | "
                     f"{_counts(s['lost_end'])} | {s['staged']} | {_f(s['load_x'])} | {_f(s['load_z'])} | "
                     f"{_f(s['phi_needed'], '{:.1f}')} | {_f(s['porosity'], '{:.3f}')} | {_f(s['cpu'], '{:.0f}')} |")
    lines += ["", "## Per member", "",
              "| stones | seed | status | lost at the release | stage at the release (stones) | lost by the end | "
              "surface stones | load x / W', mean (max) | load z / W' | angle needed [deg] | porosity (prism) | "
              "simulated [s] | CPU [s] |", "|---|---:|---|---:|---|---:|---:|---|---:|---:|---:|---:|---:|"]
    for r in rows:
        if not _done(r):
            lines.append(f"| {r['config']} | {r['seed']} | {r['status']} | | | | | | | | {_f(r['porosity'], '{:.3f}')} "
                         f"| | {_f(r['cpu'], '{:.0f}')} |")
            continue
        stage = f"yes ({r['stage_stones']})" if r["stage_release"] else "no"
        lines.append(f"| {r['config']} | {r['seed']} | {r['status']} | {r['lost_release']} | {stage} | {r['lost_end']} | "
                     f"{r['surface']} | {_f(r['load_x'])} ({_f(r['load_x_max'])}) | {_f(r['load_z'])} | "
                     f"{_f(r['phi_needed'], '{:.1f}')} | {_f(r['porosity'], '{:.3f}')} | {r['simulated']:.1f} | "
                     f"{r['cpu']:.0f} |")
    lines += _where_md(rows)
    cpu = [r["cpu"] for r in rows if not math.isnan(r["cpu"])]
    n_earlier = sum(r["status"] == EARLIER for r in rows)
    from_earlier = f"; {n_earlier} of them from the earlier page" if n_earlier else ""
    lines += ["", f"CPU: {sum(cpu) / 60:.1f} min over {len(cpu)} members (each member's process time, packing "
              f"included; median {_median(cpu):.0f} s{from_earlier}).", "",
              f"Figure: `{shown_path(args.figure, ROOT)}`.", ""]
    return "\n".join(lines)


def hydrograph_md(whole) -> str:
    """The verdict's tables (studies/maeno2008_verdict.py) of configurations whose members ran the whole
    ramp: their runs here, not an earlier page's."""
    if not whole:
        return ""
    lines = ["", "## Through the hydrograph", "",
             "The members ran the whole ramp: per event the Kaplan-Meier median and 16-84 % band of its "
             "discharge over the members run here (members in which it never happened censored at their last "
             "discharge), as the verdict's tables (`studies/maeno2008_verdict.py`), next to the experiment's and "
             "the paper's model's discharges.", ""]
    for label, scene, frame in whole:
        lines += config_md(label, scene, frame)
    return "\n".join(lines)


def _where_md(rows) -> list:
    """Where the stones lost at the release lay at the start, per member run here that lost any."""
    lost = [r for r in rows if r["status"] == "completed" and r["lost_release"] > 0]
    if not lost:
        return ["", "Where the stones lost at the release lay: no member run here lost any."]
    lines = ["", "## Where the stones lost at the release lay", "",
             "Their initial places (vofdem.analysis regions, as the stage tables'), per member run here that lost "
             "any:", "", "| stones | seed | " + " | ".join(REGIONS) + " |", "|---|---:|" + "---:|" * len(REGIONS)]
    for r in lost:
        lines.append(f"| {r['config']} | {r['seed']} | " + " | ".join(str(r["lost_where"][g]) for g in REGIONS) + " |")
    return lines


def _earlier_note(args, rows) -> str:
    earlier = [r for r in rows if r["status"] == EARLIER]
    if not earlier:
        return ""
    seeds = ", ".join(f"{c} seed {', '.join(str(r['seed']) for r in earlier if r['config'] == c)}"
                      for c in dict.fromkeys(r["config"] for r in earlier))
    return (f" With --earlier: the members '{EARLIER}' are the rows of `{shown_path(args.earlier, ROOT)}` (an earlier "
            f"call of this script; not run here): {seeds}.")


def figure(rows, configs, heaps, path: Path) -> None:
    """Stones lost at the release against the heap angle, one marker per member."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, ax = plt.subplots(figsize=(6.4, 4.2))
    markers = {"sphere": "o", "clump": "s"}
    for j, cfg in enumerate(configs):
        done = [r for r in rows if r["config"] == cfg.label and _done(r)]
        heap = heaps.get((cfg.shape, cfg.mu_r), math.nan)
        if not done or math.isnan(heap):
            continue
        x = heap + 0.25 * (np.arange(len(done)) - 0.5 * (len(done) - 1))  # members side by side
        ax.plot(x, [r["lost_release"] for r in done], markers[cfg.shape], color=f"C{j}", label=cfg.label,
                mfc="none" if cfg.shape == "clump" else None, ms=7)
    ax.set_xlabel("dry heap angle of repose [deg] (calibration)")
    ax.set_ylabel("stones lost at the release")
    ax.set_yscale("symlog", linthresh=10.0)  # a few stones and a collapse of hundreds on one axis
    ax.axvspan(37.0, 41.0, color="0.9", zorder=0, label="quarried stone 37-41 deg")
    ax.set_ylim(bottom=0.0)
    ticks = [0, 1, 2, 5, 10, 20, 50, 100, 200, 500]
    ax.set_yticks(ticks, [str(t) for t in ticks])
    ax.legend(fontsize=8)
    fig.tight_layout()
    path.parent.mkdir(parents=True, exist_ok=True)
    fig.savefig(path, dpi=110)
    plt.close(fig)


def parse_mu(spec: str, name: str) -> list:
    """'0,0.2' -> [0.0, 0.2]; '' -> []; ValueError naming the option and the range [0, 2]."""
    return parse_numbers(spec, name, 0.0, 2.0, what="a rolling friction", allow_empty=True)


def _paths_shown(parser, args) -> str:
    """The options of the earlier page and of the files written that are not the defaults, as a command line."""
    out = f" --earlier {shown_path(args.earlier, ROOT)}" if args.earlier is not None else ""
    for name in ("results", "figure", "out"):
        if getattr(args, name).resolve() != parser.get_default(name).resolve():
            out += f" --{name} {shown_path(getattr(args, name), ROOT)}"
    return out


def main(argv=None) -> Path:
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--scene", type=Path, default=ROOT / "scenes" / "maeno2008_spheres_rolling_consistent.toml")
    p.add_argument("--quick", action="store_true", help="the scene's quick variant")
    p.add_argument("--seeds", default="0-3")
    p.add_argument("--mu-r", default="0,0.2,0.4,0.8", help="the spheres' rolling frictions [-], each in [0, 2]")
    p.add_argument("--clump-mu-r", default="0", help="the clumps' rolling frictions [-], each in [0, 2]; '' none")
    p.add_argument("--after", type=float, default=10.0, help="seconds of the ramp run after the release [s], > 0")
    p.add_argument("--window", type=float, default=2.0, help="'at the release': this long after it [s], > 0")
    p.add_argument("--no-run", action="store_true", help="tables of the members finished so far, running none")
    p.add_argument("--out", type=Path, default=ROOT / "out" / "release_stability")
    p.add_argument("--results", type=Path, default=ROOT / "studies" / "results" / "release_stability.md")
    p.add_argument("--figure", type=Path, default=ROOT / "docs" / "figures" / "release_stability.png")
    p.add_argument("--earlier", type=Path, default=None, help="an earlier page of this script: its completed members "
                   "of the configurations run here, at seeds not run here, join the tables")
    args = p.parse_args(argv)
    if args.earlier is not None and not args.earlier.is_file():
        raise ValueError(f"--earlier: {shown_path(args.earlier, ROOT)} is not a page of this script (no such file)")
    for name in ("after", "window"):
        if not getattr(args, name) > 0.0:
            raise ValueError(f"--{name} = {getattr(args, name)} s is outside the allowed range (0, ...)")
    base = load_scene(args.scene)
    base = base.quick() if args.quick else base
    base = base.replace(end_time=base.hydrograph.ramp_start + args.after)
    seeds = parse_seeds(args.seeds)
    configs = [Config("sphere", m) for m in parse_mu(args.mu_r, "--mu-r")] + \
              [Config("clump", m) for m in parse_mu(args.clump_mu_r, "--clump-mu-r")]
    rows, whole = [], []
    for cfg in configs:
        scene, d = cfg.scene(base), args.out / cfg.name
        if args.no_run:
            frame = finished_outcomes(scene, seeds, d)
        else:
            frame = run_ensemble(scene, seeds, d, workers=0, figures=False, animation=False, progress=False,
                                 build=functools.partial(build_recording, out_dir=d.resolve()))
        for rec in frame.to_dict("records"):
            out = {"seed": rec["seed"], "status": rec["status"], "cpu_seconds": rec.get("cpu_seconds"),
                   "removed": rec.get("removed")}
            rows.append(member_row(cfg, out, d / f"seed{rec['seed']}", args.window))
        if base.end_time >= base.hydrograph.ramp_start + base.hydrograph.ramp_duration - 1e-9:
            whole.append((cfg.label, scene, frame))
    if args.earlier is not None:
        order = [c.label for c in configs]
        rows = sorted(rows + earlier_rows(args.earlier, configs, seeds),
                      key=lambda r: (order.index(r["config"]), r["seed"]))
    heaps = heap_angles()
    summary = config_rows(configs, rows, heaps)
    command = ("PYTHONPATH=python python3 studies/release_stability.py" + (f" --scene {shown_path(args.scene, ROOT)}"
               if args.scene.resolve() != p.get_default("scene").resolve() else "") + (" --quick" if args.quick else "")
               + f" --seeds {args.seeds} --mu-r '{args.mu_r}' --clump-mu-r '{args.clump_mu_r}' --after {args.after:g}"
               f" --window {args.window:g}" + (" --no-run" if args.no_run else "") + _paths_shown(p, args))
    figure(rows, configs, heaps, args.figure)
    args.results.parent.mkdir(parents=True, exist_ok=True)
    args.results.write_text(results_md(args, base, configs, rows, summary, command) + hydrograph_md(whole),
                            encoding="utf-8")
    print(args.results)
    return args.results


if __name__ == "__main__":
    main()
