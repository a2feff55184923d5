"""The prediction study of the Maeno 2008 weir: at what discharge it fails and in how many stages, over
packings, and what the accuracy of that answer costs.

Two parts, every ensemble on Dask (run_ensemble; one client for all), each resumable: a second call
runs only the members not finished (one directory per ensemble under --out).

* **The verdict**: per configuration (a scene of scenes/: by default the discs with the calibrated
  rolling resistance, the paper's and the consistent coupling; polygon scenes by name when present)
  over the seeds, per event the Kaplan-Meier median and 16-84 % band of its discharge (members in
  which it never happened censored at the run's last discharge; vofdem.study) with the lognormal fit
  beside it, the shares of members with a removal and failing in 2+ / 3+ separate stages, and the crest
  lowering at the run's end (25 l/s), next to the scene's [reference] data (the experiment's and the
  paper's model's discharges). Then the width sweep: one configuration over flume widths (the
  ensemble's `vary` of flume.width; the scene's own width is its verdict ensemble), in a domain raised
  where a narrower flume's water would reach the top (`sweep_height`); for 3D stones with each width's
  packings (stones, stones across, porosity). With --width-base and --parts width alone, the scene's own
  width is read from an earlier study's _verdict.csv instead of run (its seeds, not paired with the sweep's).
  The stone-wall friction's sweep (--parts wall, not run by default) is the like over stones.friction_wall
  (the side walls', the bed's and the upstream end wall's Coulomb friction; the paper's 0.176) with
  --wall-frictions, --wall-seeds and --wall-base: a sensitivity over a plausible range, not a fit.
* **Accuracy against cost**: from a reference configuration, one knob at a time over the same seeds
  (vofdem.study.knob_settings: grid, ramp, CFL, porosity table, DEM steps per contact, spin-up, the
  kernel mapping's width, the overflow load); per setting the shift of each event's median from the reference's, with its paired bootstrap interval,
  against the CPU time per member (its ratio to the reference's members at the same seeds, run again
  just before the settings', so that a drift of the machine's speed between the verdict and this part
  does not enter) and the steps per member (the same on any machine); the packings' own spread (the
  reference's 16-84 % band) beside it.

Writes studies/results/maeno2008_verdict<suffix>.md (+ _verdict.csv, _width.csv, _wall.csv, _cost.csv) and
docs/figures/maeno2008_verdict<suffix>_cost.png, _fragility.png, _width.png and _wall.png; suffix '' (full),
'_small', '_tiny', then '_<tag>' with --tag (a study of other scenes kept beside the main one; only the parts
run are written).

    PYTHONPATH=python python3 studies/maeno2008_verdict.py            # the full study: 30 seeds (hours)
    PYTHONPATH=python python3 studies/maeno2008_verdict.py --small    # the small version (minutes)
    PYTHONPATH=python python3 studies/maeno2008_verdict.py --scheduler tcp://host:8786   # on a cluster
    PYTHONPATH=python python3 studies/maeno2008_verdict.py --scenes maeno2008_rolling maeno2008_polygons
    PYTHONPATH=python python3 studies/maeno2008_verdict.py --parts verdict --scenes \
        maeno2008_spheres_rolling_consistent --seeds 0-9 --tag spheres   # the 3D spheres' verdict
    PYTHONPATH=python python3 studies/maeno2008_verdict.py --parts width --scenes \
        maeno2008_spheres_rolling_consistent --widths 0.3 0.4 --width-seeds 0-3 --width-base \
        studies/results/maeno2008_verdict_spheres_verdict.csv --tag spheres_width --workers 1 \
        --out out/spheres_width   # their width sweep, B = 0.5 m from the verdict's rows
    PYTHONPATH=python python3 studies/maeno2008_verdict.py --parts wall --scenes \
        maeno2008_spheres_rolling_consistent --wall-frictions 0.1 0.35 --wall-seeds 0-3 --wall-base \
        studies/results/maeno2008_verdict_spheres_verdict.csv --tag spheres_wall --workers 1 \
        --out out/spheres_wall   # their stone-wall friction's sweep, 0.176 from the verdict's rows
    PYTHONPATH=python python3 studies/maeno2008_verdict.py --redraw-cost   # the cost figure from its CSV
"""
import argparse
import contextlib
import math
import os
import time
from dataclasses import dataclass
from pathlib import Path

import numpy as np
import pandas as pd

from vofdem.builder import build_stones, peak_discharge, upstream_level
from vofdem.cluster import default_workers, ensemble_client
from vofdem.ensemble import finished_outcomes, parse_seeds, run_ensemble
from vofdem.fragility import EVENTS, fig_fragility, figure_legend, fragility_of
from vofdem.scene import load_scene
from vofdem.fidelity import PRESETS
from vofdem.study import (KNOBS, coupling, event_summary, knob_settings, median_shift, preset_of, shown_path,
                          spread, stage_fractions, stone_model)

ROOT = Path(__file__).resolve().parents[1]
# the first is the width sweep's and the cost part's reference: the consistent coupling, chosen on physics (the
# stones take the momentum the porous resistance removes; the weir's mean porosity is the measured one)
SCENES = ("maeno2008_rolling_consistent", "maeno2008_rolling")
# per size: seeds, the scenes' quick variant, the end time [s] (None: the hydrograph's end), widths [m],
# stone-wall frictions [-] (about the paper's 0.176: glass or stone on stone, wet; assumed, not measured)
SIZES = {"full": dict(seeds="0-29", quick=False, end_time=None, widths=(0.3, 0.4, 0.5), wall_frictions=(0.1, 0.35)),
         "small": dict(seeds="0-5", quick=True, end_time=None, widths=(0.3, 0.4, 0.5), wall_frictions=(0.1, 0.35)),
         "tiny": dict(seeds="0-1", quick=True, end_time=3.0, widths=(0.4, 0.5), wall_frictions=(0.35,))}
SUFFIX = {"full": "", "small": "_small", "tiny": "_tiny"}
PARTS = ("verdict", "width", "cost")  # the default parts; the stone-wall friction's sweep runs when asked
PART_CHOICES = ("verdict", "width", "wall", "cost")
WALL_FRICTION_RANGE = (0.0, 2.0)  # stones.friction_wall's range in the scene


@dataclass(frozen=True)
class Sweep:
    """A part that runs one configuration over values of one scene key; the scene's own value is its
    verdict ensemble (or an earlier study's rows, --<part>-base)."""

    part: str  # the part's name and its options' prefix: --<part>-seeds, --<part>-base
    key: str  # the scene key varied
    values_arg: str  # the option of its values, and their SIZES entry
    noun: str  # the value in words
    column: str  # the values' column in the tables and the CSV
    header: str  # the tables' first column
    axis: str  # the figure's abscissa
    named: str  # one value in words, a format of the value
    title: str
    what: str  # the page's sentence on the values


SWEEPS = {"width": Sweep("width", "flume.width", "widths", "width", "width_m", "B [m]", "flume width B [m]",
                         "B = {:g} m", "The width sweep",
                         "flume widths B (the discharge is divided by B; the paper does not give it)"),
          "wall": Sweep("wall", "stones.friction_wall", "wall_frictions", "stone-wall friction", "friction_wall",
                        "stone-wall friction [-]", "stone-wall friction [-]", "Stone-wall friction {:g}",
                        "The stone-wall friction's sweep",
                        "stone-wall frictions (stones.friction_wall: the side walls', the bed's and the upstream end "
                        "wall's Coulomb friction; the paper gives 0.176 for its model, no measurement; the bed's "
                        "lowest stones are fixed)")}


def _parser():
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    size = p.add_mutually_exclusive_group()
    size.add_argument("--small", action="store_true", help="the small version: 6 seeds of the quick scenes, "
                      "one setting per knob (minutes on 2 cores)")
    size.add_argument("--tiny", action="store_true", help="the test suite's size: 2 seeds, 3 s, two knobs")
    p.add_argument("--scenes", nargs="+", default=list(SCENES), help="configurations: scene names in scenes/")
    p.add_argument("--width-scene", default=None, help="the configuration of the width and the stone-wall "
                   "friction's sweeps (default the first)")
    p.add_argument("--cost-scene", default=None, help="the reference of accuracy against cost (default the first)")
    p.add_argument("--widths", type=float, nargs="+", default=None, help="flume widths [m] of the sweep")
    p.add_argument("--knobs", nargs="+", default=None, choices=KNOBS, help="knobs of the cost part (default all)")
    p.add_argument("--seeds", default=None, help="packings (default 0-29; --small 0-5; --tiny 0-1)")
    p.add_argument("--width-seeds", default=None, help="packings of the width sweep (default --seeds)")
    p.add_argument("--width-base", type=Path, default=None, help="with --parts width alone: the scene's own width "
                   "from the rows of an earlier study's _verdict.csv (its Kaplan-Meier medians and bands over that "
                   "study's seeds, not paired with the sweep's) instead of running its verdict ensemble")
    p.add_argument("--wall-frictions", type=float, nargs="+", default=None, help="stone-wall frictions [-] of "
                   "the stone-wall friction's sweep (--parts wall), each in [0, 2] (default 0.1 0.35; --tiny 0.35)")
    p.add_argument("--wall-seeds", default=None, help="packings of the stone-wall friction's sweep (default --seeds)")
    p.add_argument("--wall-base", type=Path, default=None, help="with --parts wall alone: the scene's own "
                   "stone-wall friction from the rows of an earlier study's _verdict.csv, as --width-base")
    p.add_argument("--knob-seeds", default=None, help="packings of the accuracy-against-cost part (default --seeds; "
                   "the reference's members at these seeds are paired with each setting's)")
    p.add_argument("--no-reference-rerun", action="store_true", help="measure the settings' CPU time against the "
                   "reference's verdict members instead of rerunning it at the knob seeds (cheaper; a drift of the "
                   "machine's speed between the two then enters the ratios)")
    p.add_argument("--no-run", action="store_true", help="run no member: the tables of the members finished so far "
                   "(an ensemble cut short says how many of its members it holds)")
    p.add_argument("--parts", nargs="+", default=list(PARTS), choices=PART_CHOICES,
                   help="parts to run (default verdict, width, cost; the verdict's ensembles always run, the others "
                        "are measured against them, unless --width-base or --wall-base gives the part's own value)")
    p.add_argument("--end-time", type=float, default=None, help="stop each member at this time [s]")
    p.add_argument("--workers", type=int, default=None, help="local worker processes (default one per core; 0: "
                   "in this process, no Dask)")
    p.add_argument("--scheduler", default=None, help="an existing Dask cluster's address instead")
    p.add_argument("--n-boot", type=int, default=1000, help="bootstrap resamples (default 1000)")
    p.add_argument("--out", type=Path, default=None,
                   help="ensembles' directory (default out/maeno2008_verdict<suffix>)")
    p.add_argument("--tag", default=None, help="a name appended to the results' and figures' names "
                   "(maeno2008_verdict<suffix>_<tag>), to keep a study of other scenes beside the main one")
    p.add_argument("--results", type=Path, default=ROOT / "studies" / "results")
    p.add_argument("--figures", type=Path, default=ROOT / "docs" / "figures")
    p.add_argument("--redraw-cost", action="store_true", help="run nothing: draw the cost figure again from the "
                   "_cost.csv in --results (of the size chosen)")
    return p


def sweep_height(scene, widths) -> float:
    """The domain's height [m] for the width sweep: the scene's, raised by as much as the narrowest flume's
    level at the run's peak discharge (builder.upstream_level) lies above the scene's own (rounded up to
    the cm), so that every width keeps the scene's headroom over the water. Narrower flumes carry more
    discharge per metre: in the 0.38 m domain a 0.3 m flume's water reached the top row (Maeno scenes at
    25 l/s: 0.3449 m at 0.5 m, 0.3837 m at 0.3 m -> 0.42 m)."""
    peak = peak_discharge(scene)
    own = upstream_level(scene, peak)
    rise = max([upstream_level(scene.with_value("flume.width", w), peak) - own for w in widths] + [0.0])
    return scene.flume.height if rise <= 0.0 else math.ceil(round((scene.flume.height + rise) * 100, 6)) / 100


def _scene(name: str, quick: bool, end_time):
    scene = load_scene(ROOT / "scenes" / f"{name}.toml")
    if quick:
        scene = scene.quick()
    return scene if end_time is None else scene.replace(end_time=end_time)


@contextlib.contextmanager
def _client(workers, scheduler):
    """One Dask client for every ensemble of the study (None: in this process)."""
    if workers == 0 and scheduler is None:
        yield None
        return
    with ensemble_client(None, scheduler, workers) as c:
        yield c


def _size(args) -> str:
    return "tiny" if args.tiny else "small" if args.small else "full"


def _suffix(args) -> str:
    """The results' suffix: the size's, then the tag's."""
    return SUFFIX[_size(args)] + (f"_{args.tag}" if args.tag else "")


def _command(args, size: str) -> str:
    """The options of the call that are not the defaults, as a command line."""
    flag = {"full": "", "small": " --small", "tiny": " --tiny"}[size]
    if list(args.parts) != list(PARTS):
        flag += " --parts " + " ".join(args.parts)
    if list(args.scenes) != list(SCENES):
        flag += " --scenes " + " ".join(args.scenes)
    if args.width_scene:
        flag += f" --width-scene {args.width_scene}"
    for k in ("widths", "wall_frictions"):
        if getattr(args, k):
            flag += f" --{k.replace('_', '-')} " + " ".join(f"{v:g}" for v in getattr(args, k))
    flag += "".join(f" --{k.replace('_', '-')} {getattr(args, k)}" for k in ("seeds", "width_seeds", "wall_seeds",
                                                                            "knob_seeds", "tag") if getattr(args, k))
    for k in ("width_base", "wall_base"):
        if getattr(args, k):
            flag += f" --{k.replace('_', '-')} {shown_path(getattr(args, k), ROOT)}"
    if args.knobs:
        flag += " --knobs " + " ".join(args.knobs)
    return flag + (" --no-reference-rerun" if args.no_reference_rerun else "")


def run_study(args, build=None, log=print):
    """Runs (or resumes) every ensemble of the study; returns the outcome tables:
    {'verdict': {scene name: frame}, 'width': frame or None, 'cost': {setting name: frame}}, with
    the scenes, the width scene's name and the settings."""
    size = _size(args)
    d = SIZES[size]
    end_time = args.end_time if args.end_time is not None else d["end_time"]
    seeds = parse_seeds(args.seeds or d["seeds"])
    knob_seeds = parse_seeds(args.knob_seeds) if args.knob_seeds else seeds
    scenes = {n: _scene(n, d["quick"], end_time) for n in args.scenes}
    width_name, cost_name = args.width_scene or args.scenes[0], args.cost_scene or args.scenes[0]
    for n in (width_name, cost_name):
        if n not in scenes:
            raise ValueError(f"{n!r} is not one of the study's scenes ({', '.join(scenes)})")
    settings = knob_settings(scenes[cost_name], size, args.knobs) if "cost" in args.parts else []
    out = args.out or ROOT / "out" / f"maeno2008_verdict{SUFFIX[size]}"
    sweeps = {part: _sweep_plan(args, part, width_name, scenes[width_name], d, seeds)
              for part in SWEEPS if part in args.parts}
    height = sweep_height(scenes[width_name], sweeps["width"]["values"] if "width" in sweeps else [])
    res = {"size": size, "seeds": seeds, "knob_seeds": knob_seeds, "scenes": scenes,
           "width_scene": width_name, "cost_scene": cost_name, "sweeps": sweeps,
           "settings": settings, "sweep_height": height, "out": out, "found": _finished(out)}
    with _client(0 if args.no_run else args.workers, None if args.no_run else args.scheduler) as client:
        kw = dict(client=client, workers=args.workers, figures=False, animation=False, build=build,
                  progress=log is print, dashboard=False, n_boot=args.n_boot, log=log)
        ens = (lambda s, sd, d, vary=None: finished_outcomes(s, sd, d, vary)) if args.no_run else \
            (lambda s, sd, d, vary=None: run_ensemble(s, sd, d, vary=vary, **kw))
        # with --width-base (--wall-base) the scene's own value comes from an earlier study's rows: no verdict
        # member runs
        from_base = any(plan["base_rows"] is not None for plan in sweeps.values())
        res["verdict"] = {} if from_base else {n: ens(s, seeds, out / "verdict" / n) for n, s in scenes.items()}
        for part, plan in sweeps.items():
            plan["frame"] = (ens(scenes[width_name], plan["seeds"], out / part / width_name, _sweep_vary(res, part))
                             if plan["values"] else None)
        ref = scenes[cost_name]
        # the reference rerun at the knob seeds just before the settings: its CPU time is measured beside theirs
        rerun = settings and not args.no_reference_rerun
        res["cost_reference"] = ens(ref, knob_seeds, out / "cost" / "reference") if rerun else None
        res["cost"] = {st.name: ens(st.scene(ref), knob_seeds, out / "cost" / st.name) for st in settings}
    for part, plan in sweeps.items():
        plan["packing"] = (_packings(scenes[width_name], SWEEPS[part].key, [plan["own"], *plan["values"]],
                                     plan["seeds"]) if plan["values"] else {})
    return res


def _sweep_plan(args, part: str, name: str, scene, size: dict, seeds) -> dict:
    """What a sweep part runs: the scene's own value, the other values, the seeds, and the earlier study's
    rows for the own value where --<part>-base gives them."""
    sw = SWEEPS[part]
    own = float(scene.value_of(sw.key))
    given = getattr(args, sw.values_arg) or size[sw.values_arg]
    if part == "wall":
        _check_range(f"--{sw.values_arg.replace('_', '-')}", given, WALL_FRICTION_RANGE)
    own_seeds = getattr(args, f"{part}_seeds")
    base = getattr(args, f"{part}_base")
    return {"own": own, "values": [v for v in given if not math.isclose(v, own)],
            "seeds": parse_seeds(own_seeds) if own_seeds else seeds, "base_path": base,
            "base_rows": _sweep_base_rows(args, part, name, scene) if base else None}


def _check_range(option: str, values, bounds) -> None:
    lo, hi = bounds
    for v in values:
        if not lo <= v <= hi:
            raise ValueError(f"{option}: {v:g} is outside the allowed range [{lo:g}, {hi:g}]")


def _packings(scene, key: str, values, seeds) -> dict:
    """{value of key: [(stones, stones across, porosity) per seed]} of 3D stones' weirs packed as the members
    pack them (builder.build_stones: the seed's weir bit for bit; seconds each); {} for stones in the plane."""
    if scene.stones.shape not in ("sphere", "clump"):
        return {}
    out = {}
    for v in values:
        reports = [build_stones(scene.with_value(key, v).replace(seed=s))[1] for s in seeds]
        out[v] = [(r.n_stones, r.stones_across, r.porosity) for r in reports]
    return out


def _sweep_base_rows(args, part: str, name: str, scene) -> list:
    """The event rows of scene `name` in the earlier study's _verdict.csv given by --<part>-base (a verdict of
    the same scene: its own width and stone-wall friction)."""
    path, width = getattr(args, f"{part}_base"), scene.flume.width
    if list(args.parts) != [part]:
        raise ValueError(f"{part}_base: the scene's own {SWEEPS[part].noun} is read instead of run in the {part} "
                         f"part alone (--parts {part}), not with --parts {' '.join(args.parts)}")
    frame = pd.read_csv(path)
    rows = frame[frame["scene"] == name]
    if rows.empty or not np.allclose(rows["width_m"].astype(float), width):
        raise ValueError(f"{part}_base: {path.name} holds no rows of {name} at its width B = {width:g} m")
    return [{k: (None if isinstance(v, float) and math.isnan(v) else v) for k, v in r.items()}
            for r in rows.to_dict("records")]


def _sweep_vary(res, part: str) -> dict:
    """A sweep's `vary`: its values; the width's with the raised domain's height where it is raised."""
    return _width_vary(res, res["sweeps"][part]["values"]) if part == "width" else \
        {SWEEPS[part].key: res["sweeps"][part]["values"]}


def _width_vary(res, widths) -> dict:
    """The width sweep's `vary`: the widths, and the raised domain's height where it is raised."""
    vary = {"flume.width": widths}
    if _raised(res):
        vary["flume.height"] = [res["sweep_height"]]
    return vary


def _raised(res) -> bool:
    """Whether the width sweep's narrower flumes run in a domain higher than the scene's own."""
    return res["sweep_height"] > res["scenes"][res["width_scene"]].flume.height


def _seed_range(seeds) -> str:
    return f"{seeds[0]}-{seeds[-1]}" if list(seeds) == list(range(seeds[0], seeds[-1] + 1)) else \
        ", ".join(map(str, seeds))


def _finished(out: Path) -> int:
    """Members finished in the study's directory (an outcome file each)."""
    return len(list(Path(out).glob("**/outcome.json"))) if Path(out).exists() else 0


# ---------------------------------------------------------------------------- tables
def _q(v, fmt="{:.2f}") -> str:
    return "-" if v is None or (isinstance(v, float) and not math.isfinite(v)) else fmt.format(v)


def _band(lo, med, hi, censored=None) -> str:
    """'16.20 [14.10-18.00]'; a quantile not reached is '> Q' (above the runs' last discharge)."""
    nr = f"> {_q(censored)}" if censored is not None else "not reached"
    return f"{nr if med is None else _q(med)} [{nr if lo is None else _q(lo)} to {nr if hi is None else _q(hi)}]"


def verdict_rows(name, scene, df):
    """CSV rows of one configuration: one per event."""
    ref = scene.reference
    rows = []
    for ev in EVENTS:
        s = event_summary(df, ev)
        obs, mod = ref.event_lps(ev) if ref.given else (None, None)
        rows.append({"scene": name, "stones": stone_model(scene), "coupling": coupling(scene),
                     "width_m": scene.flume.width, **s, "observed_lps": obs, "model_lps": mod})
    return rows


def config_md(name, scene, df) -> list:
    done = df[df["status"] == "completed"]
    fr = stage_fractions(df)
    crest = spread(done["crest_lowering_mm"].astype(float))
    q_end = spread(done["last_discharge_lps"].astype(float))[1]
    cpu = spread(done["cpu_seconds"].astype(float))[1]
    lines = [f"**{name}** ({stone_model(scene)}, {coupling(scene)} coupling, B = {scene.flume.width:g} m): "
             f"{len(done)} of {len(df)} members completed; with a removal {fr['with_removal']:.0%}, failing in "
             f"2+ separate stages {fr['stages_2plus']:.0%}, 3+ {fr['stages_3plus']:.0%}; crest lowering at "
             f"{_q(q_end)} l/s (the run's end) {_band(*[None if v is None else v for v in crest])} mm "
             f"(median [16-84 %]); CPU {_q(cpu, '{:.1f}')} s per member.", "",
             "| event | happened in (at the first discharge) | Kaplan-Meier median [16-84 %] [l/s] | lognormal "
             "median [16-84 %] [l/s] | observed [l/s] | paper's model [l/s] |", "|---|---|---|---|---|---|"]
    for r in verdict_rows(name, scene, df):
        cens = r["censored_at_lps"]
        fit = ("no fit" if r["fit_median_lps"] is None
               else _band(r["fit_q16_lps"], r["fit_median_lps"], r["fit_q84_lps"]))
        lines.append(f"| {EVENTS[r['event']][1]} | {r['happened']} of {r['members']} ({r['at_first_discharge']}) | "
                     f"{_band(r['km_q16_lps'], r['km_median_lps'], r['km_q84_lps'], cens)} | {fit} | "
                     f"{_q(r['observed_lps'], '{:g}')} | {_q(r['model_lps'], '{:g}')} |")
    return lines + [""]


def sweep_frames(res, part: str):
    """{value: outcome frame} of a sweep, the scene's own value from its verdict ensemble (its members at the
    sweep's seeds)."""
    plan = res["sweeps"][part]
    base = res["verdict"].get(res["width_scene"])
    out = {} if base is None else {plan["own"]: base[base["seed"].isin(plan["seeds"])]}
    if plan["frame"] is not None:
        for v, g in plan["frame"].groupby(SWEEPS[part].key):
            out[float(v)] = g
    return dict(sorted(out.items()))


def sweep_rows(res, part: str):
    """One row per value and event; the scene's own value from --<part>-base's rows where given."""
    col, plan = SWEEPS[part].column, res["sweeps"][part]
    rows = _base_sweep_rows(res, part) if plan["base_rows"] is not None else []
    for v, df in sweep_frames(res, part).items():
        fr = stage_fractions(df)
        done = df[df["status"] == "completed"]
        for ev in EVENTS:
            rows.append({col: v, **event_summary(df, ev), "stages_2plus": fr["stages_2plus"],
                         "crest_lowering_mm_median": spread(done["crest_lowering_mm"].astype(float))[1],
                         "stages_3plus": fr["stages_3plus"], "stones_median": spread(done["stones"].astype(float))[1],
                         "cpu_s_median": spread(done["cpu_seconds"].astype(float))[1],
                         "seeds": _seed_range(sorted(done["seed"])) if len(done) else "", "source": "run"})
    for r in rows:
        packed = _near(plan.get("packing", {}), r[col])
        r.update({k: (float(np.mean([p[i] for p in packed])) if packed else None)
                  for i, k in enumerate(("packed_stones_mean", "stones_across_mean", "packed_porosity_mean"))})
    return sorted(rows, key=lambda r: r[col])


def _near(by_value: dict, v: float):
    return next((x for k, x in by_value.items() if math.isclose(k, v)), None)


def _base_sweep_rows(res, part: str) -> list:
    """The scene's own value from an earlier study's verdict rows: its events as they are; its stage
    shares from the members in which stage 2 (3) happened; no crest lowering, stones or CPU time there."""
    plan = res["sweeps"][part]
    by = {r["event"]: r for r in plan["base_rows"]}
    n = max(int(by["stage2"]["members"]), 1)
    keys = ("event", "members", "happened", "at_first_discharge", "censored_at_lps", "km_median_lps", "km_q16_lps",
            "km_q84_lps", "fit_median_lps", "fit_q16_lps", "fit_q84_lps")
    return [{SWEEPS[part].column: plan["own"], **{k: by[ev][k] for k in keys},
             "stages_2plus": by["stage2"]["happened"] / n, "crest_lowering_mm_median": None,
             "stages_3plus": by["stage3"]["happened"] / n, "stones_median": None, "cpu_s_median": None,
             "seeds": "", "source": "earlier study"} for ev in EVENTS]


def _height_note(res) -> str:
    if not _raised(res):
        return ""
    own = res["scenes"][res["width_scene"]].flume.height
    return (f"; the narrower flumes in a domain {res['sweep_height']:g} m high (`sweep_height`: raised by the rise of "
            f"the weir formula's level at the peak discharge), the scene's own width in its {own:g} m")


def _sweep_md(res, part: str) -> list:
    sw, plan = SWEEPS[part], res["sweeps"][part]
    lines = [f"| {sw.header} | " + " | ".join(f"{EVENTS[e][1]}: KM median [16-84 %] [l/s]" for e in EVENTS)
             + " | 2+ stages | crest lowering [mm] | 3+ stages | stones | stones across | porosity | "
             "CPU s per member | members (seeds) |", "|---|" + "---|" * (len(EVENTS) + 8)]
    rows = sweep_rows(res, part)
    for v in dict.fromkeys(r[sw.column] for r in rows):
        rs = [r for r in rows if r[sw.column] == v]
        cells = [_band(r["km_q16_lps"], r["km_median_lps"], r["km_q84_lps"], r["censored_at_lps"]) for r in rs]
        r0 = rs[0]
        seeds = f"{r0['members']} ({r0['seeds']})" if r0["source"] == "run" else \
            f"{r0['members']} (earlier study: `{shown_path(plan['base_path'], ROOT)}`)"
        lines.append(f"| {v:g} | " + " | ".join(cells) + f" | {r0['stages_2plus']:.0%} | "
                     f"{_q(r0['crest_lowering_mm_median'], '{:.2f}')} | {r0['stages_3plus']:.0%} | "
                     f"{_q(r0['packed_stones_mean'], '{:.0f}')} | {_q(r0['stones_across_mean'], '{:.2f}')} | "
                     f"{_q(r0['packed_porosity_mean'], '{:.3f}')} | {_q(r0['cpu_s_median'], '{:.1f}')} | {seeds} |")
    notes = ["Crest lowering and CPU time: medians over the members; stones, stones across (the mean number a line "
             "across the flume through the trapezoid crosses) and the porosity of the trapezoid's prism: means over "
             f"the weirs packed as the members pack them at seeds {_seed_range(plan['seeds'])} (3D stones only)."]
    if plan["base_rows"] is not None:
        notes.append(f"{sw.named.format(plan['own'])}: the events and stage shares are the rows of the earlier study "
                     "named, over its own seeds (not paired with the sweep's; its crest lowering and CPU time are "
                     "in its own page).")
    return lines + [""] + [x for n in notes for x in (n, "")] + _sweep_members_md(res, part)


def _sweep_members_md(res, part: str) -> list:
    """The members run, one row each: a few seeds are read member by member, not by their medians."""
    lines = [f"| {SWEEPS[part].header} | seed | stones | first removal [l/s] | stage 1 [l/s] (stones) | stage 2 | "
             "stage 3 | stages | removed | crest lowering [mm] | CPU [s] |",
             "|---|---|---|---|---|---|---|---|---|---|---|"]
    stage = lambda r, k: "-" if pd.isna(r[f"stage{k}_lps"]) else f"{r[f'stage{k}_lps']:.2f} ({r[f'stage{k}_stones']})"  # noqa: E731
    for v, df in sweep_frames(res, part).items():
        for _, r in df[df["status"] == "completed"].sort_values("seed").iterrows():
            lines.append(f"| {v:g} | {r['seed']} | {r['stones']} | {_q(r['first_removal_lps'])} | {stage(r, 1)} | "
                         f"{stage(r, 2)} | {stage(r, 3)} | {r['stages']} | {r['removed']} | "
                         f"{_q(r['crest_lowering_mm'])} | {_q(r['cpu_seconds'], '{:.1f}')} |")
    return ["The members (stones: those of the run's analysis):", ""] + lines + [""]


def fig_sweep(rows, path: Path, sw: Sweep = SWEEPS["width"]):
    """Each event's Kaplan-Meier median and 16-84 % band against the sweep's value (a band's end not reached
    drawn to the runs' last discharge, open); hollow: the values taken from an earlier study; saved and
    returned."""
    from matplotlib.backends.backend_agg import FigureCanvasAgg
    from matplotlib.figure import Figure

    fig = Figure(figsize=(6.4, 4.2), layout="constrained")
    FigureCanvasAgg(fig)
    ax = fig.subplots()
    values = sorted({r[sw.column] for r in rows})
    dx = 0.08 * (min(np.diff(values)) if len(values) > 1 else 0.1)  # events side by side at each value
    for k, ev in enumerate(EVENTS):
        for r in (r for r in rows if r["event"] == ev and r["km_median_lps"] is not None):
            top = r["km_q84_lps"] if r["km_q84_lps"] is not None else r["censored_at_lps"]
            lo = r["km_q16_lps"] if r["km_q16_lps"] is not None else r["km_median_lps"]
            x, m = r[sw.column] + (k - 1.5) * dx, r["km_median_lps"]
            ax.errorbar([x], [m], yerr=[[m - lo], [top - m]], fmt="o", color=f"C{k}", capsize=3,
                        mfc="none" if r["source"] != "run" else f"C{k}", label=EVENTS[ev][1])
    ax.set_xticks(values)
    ax.set_xlabel(sw.axis)
    ax.set_ylabel("discharge Q [l/s]")
    ax.grid(alpha=0.3)
    figure_legend(fig, [ax], 2)
    path.parent.mkdir(parents=True, exist_ok=True)
    fig.savefig(path, dpi=90)
    return fig


def cost_rows(res, n_boot: int):
    """One row per setting and event: the shift of the median, its interval, the CPU per member."""
    ref_df = res["verdict"][res["cost_scene"]]
    cpu_df = _cpu_reference(res)
    entries = [("reference", "-", "the reference", ref_df)]
    entries += [(st.name, st.knob, st.label, res["cost"][st.name]) for st in res["settings"]]
    rows = []
    for name, knob, label, df in entries:
        cpu = _median(cpu_df if name == "reference" else df, "cpu_seconds")
        # the ratio is paired: the reference's members at the seeds this setting completed
        done = df.loc[df["status"] == "completed", "seed"] if "seed" in df else []
        ref_cpu = _median(cpu_df[cpu_df["seed"].isin(done)], "cpu_seconds") if len(done) else math.nan
        # steps do not depend on the machine's speed: a cost measure where the CPU times drift
        steps, ref_steps = _median(df, "steps"), _median(ref_df[ref_df["seed"].isin(done)], "steps")
        for ev in EVENTS:
            sh = median_shift(ref_df, df, ev, n_boot=n_boot)
            s = event_summary(ref_df, ev)
            rows.append({"setting": name, "knob": knob, "label": label, "event": ev,
                         "completed": int((df["status"] == "completed").sum()), "members": len(df),
                         "cpu_s_per_member": cpu, "wall_s_per_member": _median(df, "wall_seconds"),
                         "cost_ratio": cpu / ref_cpu if ref_cpu > 0 else math.nan, "steps_per_member": steps,
                         "steps_ratio": steps / ref_steps if ref_steps > 0 else math.nan, "median_lps": sh.setting,
                         "reference_median_lps": sh.reference, "shift_lps": sh.shift, "shift_lo_lps": sh.lo,
                         "shift_hi_lps": sh.hi, "boot_left_out": sh.left_out, "seeds": sh.seeds,
                         "spread_lo_lps": _minus(s["km_q16_lps"], s["km_median_lps"]),
                         "spread_hi_lps": _minus(s["km_q84_lps"], s["km_median_lps"])})
    return rows


def _rerun(res):
    """The reference's rerun at the knob seeds when any of its members completed, else None."""
    rerun = res.get("cost_reference")
    return rerun if rerun is not None and (rerun["status"] == "completed").any() else None


def _cpu_reference(res):
    """The reference's members whose CPU time the settings are measured against: its rerun at the knob
    seeds when it ran (the same machine state as the settings'), else its verdict members."""
    rerun = _rerun(res)
    return res["verdict"][res["cost_scene"]] if rerun is None else rerun


def _rerun_md(res) -> list:
    """Whether the reference's rerun removed the same stones as its verdict members of the same seeds."""
    rerun = _rerun(res)
    if rerun is None:
        return ["The CPU ratios are against the reference's verdict members (no rerun at the knob seeds).", ""]
    ref = res["verdict"][res["cost_scene"]].set_index("seed")
    done = rerun[rerun["status"] == "completed"]
    same = sum(int(s in ref.index and ref.at[s, "stones_hash"] == h) for s, h in zip(done["seed"], done["stones_hash"]))
    return [f"The CPU ratios are against the reference rerun at the knob seeds just before the settings "
            f"(`cost/reference`; CPU {_median(done, 'cpu_seconds'):.1f} s per member, its verdict members of the same "
            f"seeds {_median(ref[ref.index.isin(done['seed'])].reset_index(), 'cpu_seconds'):.1f} s). The rerun "
            f"removed the same stones as the verdict's members in {same} of {len(done)} seeds.", ""]


def _median(df, col) -> float:
    v = df.loc[df["status"] == "completed", col].astype(float).to_numpy() if col in df else np.array([])
    v = v[np.isfinite(v)]
    return float(np.median(v)) if v.size else math.nan


def _minus(a, b):
    return None if a is None or b is None else a - b


def _shift_cell(r) -> str:
    if r["completed"] == 0:
        return "not run"
    if r["shift_lps"] is None:
        return "median not reached" if r["median_lps"] is None or r["reference_median_lps"] is None else "-"
    band = "" if math.isnan(r["shift_lo_lps"]) else f" [{r['shift_lo_lps']:+.2f} to {r['shift_hi_lps']:+.2f}]"
    return f"{r['shift_lps']:+.2f}{band}"


def _ref_cell(r) -> str:
    m = r["reference_median_lps"]
    return "median not reached" if m is None else f"median {m:.2f}"


def _cost_md(rows) -> list:
    lines = ["| setting | members | CPU s per member (x reference) | steps per member (x reference) | " + " | ".join(
        f"{EVENTS[e][1]}: shift [l/s]" for e in EVENTS) + " |", "|---|---|---|---|" + "---|" * len(EVENTS)]
    for name in dict.fromkeys(r["setting"] for r in rows):
        rs = [r for r in rows if r["setting"] == name]
        r0 = rs[0]
        cell = _ref_cell if name == "reference" else _shift_cell
        lines.append(f"| {name if name == 'reference' else r0['knob'] + ': ' + r0['label']} | {r0['completed']} of "
                     f"{r0['members']} | {_q(r0['cpu_s_per_member'], '{:.1f}')} (x{_q(r0['cost_ratio'], '{:.2f}')}) | "
                     f"{_q(r0['steps_per_member'], '{:.0f}')} (x{_q(r0['steps_ratio'], '{:.2f}')}) | "
                     + " | ".join(cell(r) for r in rs) + " |")
    ref = [r for r in rows if r["setting"] == "reference"]
    nr = "not reached"
    lines += ["", "The packings' own spread (the reference's Kaplan-Meier 16-84 % band about its median): "
              + "; ".join(f"{EVENTS[r['event']][1]} " + (nr if r["spread_lo_lps"] is None else
                          f"{r['spread_lo_lps']:+.2f}") + " to " + (nr if r["spread_hi_lps"] is None else
                          f"{r['spread_hi_lps']:+.2f} l/s") for r in ref) + ".", ""]
    return lines


def _presets_md(res, rows) -> list:
    """The fidelity presets among the reference and the settings: their cost and shifts."""
    ref = res["scenes"][res["cost_scene"]]
    scenes = {"reference": ref, **{st.name: st.scene(ref) for st in res["settings"]}}
    found = {}
    for n, s in scenes.items():  # the first that holds a preset's values: the reference before the settings
        if preset_of(s) is not None:
            found.setdefault(preset_of(s), n)
    lines = ["| preset | run as | CPU s per member (x reference) | " + " | ".join(
        f"{EVENTS[e][1]}: shift [l/s]" for e in EVENTS) + " |", "|---|---|---|" + "---|" * len(EVENTS)]
    for name in PRESETS:
        if name not in found:
            lines.append(f"| {name} | not in this study's settings | - |" + " - |" * len(EVENTS))
            continue
        rs = [r for r in rows if r["setting"] == found[name]]
        cell = _ref_cell if found[name] == "reference" else _shift_cell
        lines.append(f"| {name} | {found[name]} | {_q(rs[0]['cpu_s_per_member'], '{:.1f}')} "
                     f"(x{_q(rs[0]['cost_ratio'], '{:.2f}')}) | " + " | ".join(cell(r) for r in rs) + " |")
    return lines + [""]


def fig_cost(rows, path: Path):
    """Shift of each event's median against the CPU time per member, one point per setting, the
    packings' spread (the reference's 16-84 % band about its median) as a grey band; saved to path and
    returned."""
    from matplotlib.backends.backend_agg import FigureCanvasAgg
    from matplotlib.figure import Figure

    fig = Figure(figsize=(9.0, 6.4), layout="constrained")
    FigureCanvasAgg(fig)  # a renderer to measure the labels with
    axes = fig.subplots(2, 2, sharex=True).ravel()
    knobs = list(dict.fromkeys(r["knob"] for r in rows))
    labels = {}
    for ax, ev in zip(axes, EVENTS):
        rs = [r for r in rows if r["event"] == ev]
        shown = [r for r in rs if r["shift_lps"] is not None and math.isfinite(r["cpu_s_per_member"])]
        labels[ax] = []
        for r in shown:
            lo, hi = r["shift_lo_lps"], r["shift_hi_lps"]
            err = None if math.isnan(lo) else [[r["shift_lps"] - lo], [hi - r["shift_lps"]]]
            if r["setting"] == "reference":
                # a marker of its own on top, named by the legend: a text label was placed by the
                # separation among the knobs' labels, where it could read as a knob's
                ax.plot([r["cpu_s_per_member"]], [r["shift_lps"]], "k*", ms=11, zorder=5, label="reference")
                continue
            c = f"C{knobs.index(r['knob']) % 10}"
            ax.errorbar([r["cpu_s_per_member"]], [r["shift_lps"]], yerr=err, fmt="o", color=c, capsize=3,
                        label=r["knob"])
            labels[ax].append(ax.annotate(r["setting"], (r["cpu_s_per_member"], r["shift_lps"]),
                                          textcoords="offset points", xytext=(4, 4), fontsize=7,
                                          arrowprops=dict(arrowstyle="-", color="0.6", lw=0.5, shrinkA=0, shrinkB=3)))
        ax.axhline(0.0, color="0.5", lw=0.8)
        _spread_band(ax, next(r for r in rs if r["setting"] == "reference"))
        _not_reached(ax, rs, shown)
        ax.set_title(EVENTS[ev][1])
        ax.grid(alpha=0.3)
    cpu = [r["cpu_s_per_member"] for r in rows if math.isfinite(r["cpu_s_per_member"]) and r["cpu_s_per_member"] > 0]
    if cpu and max(cpu) > 4 * min(cpu):
        axes[0].set_xscale("log")  # shared: the coarse and the fine grid lie an order of magnitude apart
    for ax in axes[2:]:
        ax.set_xlabel("CPU time per member [s]")
    for ax in axes[::2]:
        ax.set_ylabel("shift of the median [l/s]")
    figure_legend(fig, axes, 4)
    fig.canvas.draw()  # the layout first: the labels are separated where they will be drawn
    for texts in labels.values():
        separate_labels(fig, texts)
    path.parent.mkdir(parents=True, exist_ok=True)
    fig.savefig(path, dpi=90)
    return fig


# the cost rows' values that are None where an event is not reached (an empty cell in the CSV)
_NONE_WHEN_EMPTY = ("median_lps", "reference_median_lps", "shift_lps", "spread_lo_lps", "spread_hi_lps")


def cost_rows_from_csv(path: Path):
    """The rows of cost_rows (as fig_cost takes them) from the _cost.csv that write_results wrote."""
    frame = pd.read_csv(path, dtype={"setting": str, "knob": str, "label": str, "event": str})
    rows = frame.to_dict("records")
    for r in rows:
        for k in _NONE_WHEN_EMPTY:
            if math.isnan(r[k]):
                r[k] = None
    return rows


def _not_reached(ax, rows, shown) -> None:
    """Names the settings without a shift: their median (or the reference's) lies beyond the runs' end."""
    if not shown:
        ax.text(0.5, 0.5, "the reference's median is not reached\n(beyond the runs' end): no shift",
                transform=ax.transAxes, ha="center", va="center", fontsize=8)
        ax.set_yticks([])
        return
    text = []
    for label, names in (("median not reached", [r["setting"] for r in rows if r not in shown and r["completed"]]),
                         ("not run", [r["setting"] for r in rows if not r["completed"]])):
        if names:
            text.append(f"{label}: " + "\n".join(", ".join(names[i:i + 3]) for i in range(0, len(names), 3)))
    if text:
        ax.text(0.02, 0.02, "; ".join(text), transform=ax.transAxes, fontsize=7, va="bottom")


def separate_labels(fig, texts, step_pt: float = 9.0, tries: int = 12, pad_px: float = 4.0) -> None:
    """Moves labels (annotations placed in offset points) apart, from the cheapest point on: each takes
    the first offset of 0, -1, +1, -2, ... steps of `step_pt` points at which it comes no nearer than
    `pad_px` pixels to a label placed before it (its own place when none is free within `tries` steps)."""
    from matplotlib.text import Text

    renderer = fig.canvas.get_renderer()
    box = lambda t: Text.get_window_extent(t, renderer).padded(pad_px)  # noqa: E731 (the text's, not its line's)
    placed = []
    for t in sorted(texts, key=lambda t: t.xy[0]):
        x0, y0 = t.xyann
        for k in range(2 * tries + 1):
            t.xyann = (x0, y0 + step_pt * ((k + 1) // 2) * (-1 if k % 2 else 1))
            if not any(box(t).overlaps(p) for p in placed):
                break
        else:
            t.xyann = (x0, y0)
        placed.append(box(t))


def _spread_band(ax, ref) -> None:
    """The reference's 16-84 % band about its median, open-ended where a quantile is not reached."""
    lo, hi = ref["spread_lo_lps"], ref["spread_hi_lps"]
    if lo is None and hi is None:
        return
    y0, y1 = ax.get_ylim()
    span = max(y1 - y0, 1.0)
    ax.axhspan(y0 - 10 * span if lo is None else lo, y1 + 10 * span if hi is None else hi, color="0.85", zorder=0,
               label="packings' spread (16-84 %; open where not reached)")
    ax.set_ylim(min(y0, lo if lo is not None else y0) - 0.1 * span, max(y1, hi if hi is not None else y1) + 0.1 * span)


def write_results(res, args, wall: float) -> Path:
    """The tables (markdown and CSV) and the two figures."""
    size, sfx = res["size"], _suffix(args)
    args.results.mkdir(parents=True, exist_ok=True)
    args.figures.mkdir(parents=True, exist_ok=True)
    base = args.results / f"maeno2008_verdict{sfx}"
    ran_verdict = bool(res["verdict"])  # not with --width-base
    if ran_verdict:
        vrows = [r for n, s in res["scenes"].items() for r in verdict_rows(n, s, res["verdict"][n])]
        pd.DataFrame(vrows).to_csv(f"{base}_verdict.csv", index=False, lineterminator="\n")
    sweep_png = {part: args.figures / f"maeno2008_verdict{sfx}_{part}.png" for part in SWEEPS}
    for part in res["sweeps"]:
        srows = sweep_rows(res, part)
        pd.DataFrame(srows).to_csv(f"{base}_{part}.csv", index=False, lineterminator="\n")
        fig_sweep(srows, sweep_png[part], SWEEPS[part])
    # the bootstrap of every setting's shifts is the costly table: only when the cost part ran
    crows = cost_rows(res, args.n_boot) if "cost" in args.parts else []
    cost_png, frag_png = (args.figures / f"maeno2008_verdict{sfx}_{k}.png" for k in ("cost", "fragility"))
    if "cost" in args.parts:
        pd.DataFrame(crows).to_csv(f"{base}_cost.csv", index=False, lineterminator="\n")
        fig_cost(crows, cost_png)
    if ran_verdict:
        by = {n: fragility_of(df[df["status"] == "completed"], n_boot=0) for n, df in res["verdict"].items()}
        fig_fragility(by, next(iter(res["scenes"].values())).reference).savefig(frag_png, dpi=90)
    frames = [*res["verdict"].values(), *res["cost"].values()] + [
        df for df in (*(plan["frame"] for plan in res["sweeps"].values()), res.get("cost_reference"))
        if df is not None]
    n_members = sum(len(df) for df in frames)
    cpu = sum(float(df.loc[df["status"] == "completed", "cpu_seconds"].astype(float).sum()) for df in frames)
    ran = _finished(res["out"]) - res["found"]
    where = (f"on the cluster at {args.scheduler}" if args.scheduler else "in this process" if args.workers == 0
             else f"on {args.workers or default_workers()} local worker process(es)")
    flag = _command(args, size)
    if args.no_run:
        where = "(--no-run: tables of the members finished so far)"
    scene0 = next(iter(res["scenes"].values()))
    seeds = res["seeds"] if ran_verdict or not res["sweeps"] else next(iter(res["sweeps"].values()))["seeds"]
    text = [f"# The Maeno 2008 weir: the verdict and what its accuracy costs ({size} version)", "",
            f"Written by `PYTHONPATH=python python3 studies/maeno2008_verdict.py{flag}`: {len(seeds)} "
            f"seeds ({_seed_range(seeds)}), {n_members} members, "
            f"{'the quick variants of ' if size != 'full' else ''}scenes {', '.join(res['scenes'])}, "
            f"{scene0.duration:g} s simulated per member, {cpu / 60:.1f} CPU-minutes in all. The last call ran {ran} "
            f"members (found {res['found']} finished) in {wall / 60:.1f} min {where} ({os.cpu_count()} cores, load "
            f"average {os.getloadavg()[0]:.1f} at the end). Ensembles in "
            f"`{shown_path(res['out'], ROOT, tail=1)}/` (resumable). Figures: "
            + ", ".join(f"`docs/figures/{p.name}`" for p in (cost_png, frag_png, *sweep_png.values()) if p.exists())
            + ".", ""]
    if ran_verdict:
        text += ["## The verdict", "",
                 "Per event: members in which it happened (in brackets those in which it happened at the first "
                 "discharge a run could see it, when the stones were released), the Kaplan-Meier median and 16-84 % "
                 "band (members in which it never happened are censored at their last discharge; '> Q': not reached "
                 "by the runs' end), the lognormal fit, and the scene's reference data.", ""]
        for n, s in res["scenes"].items():
            text += config_md(n, s, res["verdict"][n])
    for part, plan in res["sweeps"].items():
        text += [f"## {SWEEPS[part].title}", "", f"`{res['width_scene']}` over {SWEEPS[part].what}, seeds "
                 f"{_seed_range(plan['seeds'])}" + (_height_note(res) if part == "width" else "") + ".", ""]
        text += _sweep_md(res, part)
    if "cost" in args.parts:
        text += _cost_sections(res, crows)
    md = Path(f"{base}.md")
    md.write_text("\n".join(text), encoding="utf-8")
    return md


def _cost_sections(res, crows) -> list:
    """Accuracy against cost and the presets."""
    ref_scene = res["scenes"][res["cost_scene"]]
    text = ["## Accuracy against cost", "",
             f"Reference: `{res['cost_scene']}` (grid {ref_scene.grid.dx * 100:g} x {ref_scene.grid.dz * 100:g} cm, "
             f"CFL {ref_scene.numerics.cfl:g}, porosity {ref_scene.numerics.porosity_method}, "
             f"{ref_scene.numerics.dem_contact_steps:g} DEM steps per contact, ramp "
             f"{ref_scene.hydrograph.ramp_duration:g} s, spin-up {ref_scene.hydrograph.spin_up_duration:g} s). "
             f"One knob at a time over the same seeds ({_seed_range(res['knob_seeds'])}): the shift of each event's "
             "Kaplan-Meier median from the "
             "reference's [l/s], with its paired bootstrap 16-84 % interval over the seeds, and the median CPU time "
             "per member (its ratio to the reference's median over the same seeds).", ""] + _rerun_md(res) + _cost_md(crows)
    text += ["## The fidelity presets", "", "The presets (`vofdem run SCENE --fidelity draft|standard|fine`, "
             "vofdem/fidelity.py) that the reference or a setting of this study ran, with their measured cost and "
             "shift from the reference:", ""] + _presets_md(res, crows)
    return text


def main(argv=None, build=None, log=print) -> Path:
    args = _parser().parse_args(argv)
    if args.redraw_cost:
        sfx = _suffix(args)
        png = args.figures / f"maeno2008_verdict{sfx}_cost.png"
        fig_cost(cost_rows_from_csv(args.results / f"maeno2008_verdict{sfx}_cost.csv"), png)
        log(f"wrote {png}")
        return png
    t0 = time.perf_counter()
    res = run_study(args, build=build, log=log)
    md = write_results(res, args, time.perf_counter() - t0)
    log(f"wrote {md}")
    return md


if __name__ == "__main__":
    main()
