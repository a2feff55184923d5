"""Command line: ``vofdem run SCENE [--quick] [--out DIR] [--seed N | --seeds 0-4]`` and helpers, among them
``vofdem calibrate repose|pull SCENE`` (the laboratory experiments on the stones, calibration.py).

SCENE is a TOML scene file or the name of a ready scene (``maeno2008``); ``vofdem run --resume DIR``
continues a killed run from its last checkpoint. Exit codes: 0 success, 2 a bad scene or bad
arguments, an unwritable output directory (one line on stderr), 1 a solver failure or a failing
write, e.g. a full disk (the output written so far is kept; a solver failure is marked in run.h5).
"""
from __future__ import annotations

import argparse
import signal
import sys
from pathlib import Path
from typing import Callable, Optional, Sequence

READY = {"maeno2008": "Scene.maeno2008()"}


def _parser() -> argparse.ArgumentParser:
    p = argparse.ArgumentParser(prog="vofdem", description="VOF-DEM model of a rubble mound weir's destruction")
    sub = p.add_subparsers(dest="command", required=True)
    r = sub.add_parser("run", help="run a scene and write HDF5/XDMF output, stage tables, figures, animation")
    r.add_argument("scene", nargs="?", help="TOML scene file, or a ready scene: " + ", ".join(READY))
    r.add_argument("--resume", type=Path, default=None, metavar="DIR",
                   help="continue the killed run in DIR from its last checkpoint (see --checkpoint-seconds)")
    r.add_argument("--checkpoint-seconds", type=float, default=None, metavar="S",
                   help="wall time between checkpoints (default 30 s; 0: after every snapshot): a killed run "
                        "resumes from the last one")
    r.add_argument("--xdmf-seconds", type=float, default=None, metavar="S",
                   help="wall time between rewrites of run.xmf and stones.xmf during the run (default 2 s; 0: "
                        "after every snapshot): what ParaView shows of a running or killed run")
    r.add_argument("--quick", action="store_true", help="shorter, coarser variant that runs in a few minutes: the "
                   "draft grid on a shortened flume under a hydrograph four times faster")
    _fidelity_argument(r)
    r.add_argument("--until-failure", action="store_true",
                   help="raise the discharge slowly (hydrograph.until_failure_rate_lps_per_s) from the scene's start "
                        "until the first destruction stage and report the critical discharge (with --seeds: its "
                        "distribution)")
    r.add_argument("--out", type=Path, default=None, help="output directory (default: out/<scene name>)")
    seed = r.add_mutually_exclusive_group()
    seed.add_argument("--seed", type=int, default=None, help="random seed of the packing (overrides the scene)")
    seed.add_argument("--seeds", default=None,
                      help="an ensemble over packings, e.g. '0-4' or '0,3,7': one run per seed in DIR/seed<N>/, "
                           "summary in DIR/ensemble.md, fragility curves in DIR/fragility.png")
    r.add_argument("--vary", action="append", default=None, metavar="KEY=V1,V2,...",
                   help="an ensemble over parameter values, e.g. 'stones.friction_stone=0.5,0.577,0.65' (any scene "
                        "key; several --vary make a product), each combination over the seeds")
    r.add_argument("--workers", type=int, default=None,
                   help="ensemble: worker processes of the local Dask cluster (default: one per core; 0: no Dask, "
                        "one member after the other in this process)")
    r.add_argument("--scheduler", default=None, metavar="ADDRESS",
                   help="ensemble: run on an existing Dask cluster (e.g. tcp://host:8786, or a scheduler file .json)")
    r.add_argument("--retry-failed", action="store_true",
                   help="ensemble: run again the members whose solver failed (finished members are kept)")
    r.add_argument("--threads", type=int, default=None, metavar="N",
                   help="threads of a single run (default: OMP_NUM_THREADS, else every core); the results are the "
                        "same bits for any N (docs/threads.md). An ensemble's members run one thread each")
    r.add_argument("--end-time", type=float, default=None, help="stop at this simulated time [s]")
    r.add_argument("--no-figures", action="store_true", help="skip the figures")
    r.add_argument("--no-animation", action="store_true", help="skip the animation")
    r.add_argument("--no-progress", action="store_true", help="no progress bar")
    c = sub.add_parser("check", help="validate a scene file and print it as resolved")
    c.add_argument("scene")
    c.add_argument("--quick", action="store_true")
    _fidelity_argument(c)
    c.add_argument("--until-failure", action="store_true")
    a = sub.add_parser("analyse", help="redo the stage tables and figures of a finished run directory")
    a.add_argument("out", type=Path)
    a.add_argument("--no-animation", action="store_true")
    sub.add_parser("params", help="print every scene parameter with its default and allowed range")
    _calibrate_parser(sub)
    return p


def _fidelity_argument(p) -> None:
    p.add_argument("--fidelity", default=None, metavar="PRESET",
                   help="numerical preset: draft (grid twice as coarse as the paper's), standard (the paper's grid), "
                        "fine (twice as fine); sets numerics.fidelity and its knobs (docs/verdict.md)")


def _calibrate_parser(sub) -> None:
    k = sub.add_parser("calibrate", help="laboratory experiments on the scene's stones: angle of repose, pull-out test")
    ks = k.add_subparsers(dest="experiment", required=True)
    r = ks.add_parser("repose", help="pour heaps from a funnel onto a rough base and fit their flanks")
    r.add_argument("scene", help="TOML scene file, or a ready scene: " + ", ".join(READY))
    r.add_argument("--seeds", default="0-2", help="one heap per seed, e.g. '0-2' (default)")
    r.add_argument("--stones", type=int, default=300, help="stones poured per heap (default 300)")
    r.add_argument("--submerged", action="store_true", help="also pour the heaps under still water")
    r.add_argument("--out", type=Path, default=None, help="output directory (default: out/calibration/<scene name>)")
    q = ks.add_parser("pull", help="the paper's pull-out test of slope stones of the packed weir (Fig. 5, Table 1)")
    q.add_argument("scene", help="TOML scene file, or a ready scene: " + ", ".join(READY))
    q.add_argument("--seeds", default="0-4", help="one packed weir per seed (default '0-4')")
    q.add_argument("--per-seed", type=int, default=2, help="slope stones pulled per weir (default 2)")
    q.add_argument("--spring", type=float, default=50.0, help="spring stiffness [N/m] (default 50)")
    q.add_argument("--speed", type=float, default=0.02, help="anchor speed [m/s] (default 0.02)")
    q.add_argument("--hold", type=float, default=0.0,
                   help="hold the stones farther than this many diameters from the pulled one fixed during its "
                        "pull [-] (default 0: none; docs/dem.md, 3D spheres)")
    q.add_argument("--out", type=Path, default=None, help="output directory (default: out/calibration/<scene name>)")


def _calibrate(args, scene) -> int:
    """Runs a calibration experiment, prints its table and writes it with a figure to the output directory."""
    from . import calibration as cal
    from .ensemble import parse_seeds

    seeds = parse_seeds(args.seeds)
    out = args.out or Path("out") / "calibration" / scene.name
    out.mkdir(parents=True, exist_ok=True)
    log = lambda msg: print(msg, file=sys.stderr)  # noqa: E731
    if args.experiment == "repose":
        setup = cal.ReposeSetup(n_stones=args.stones)
        res = cal.repose_test(scene, seeds, False, setup, log)
        if args.submerged:
            res += cal.repose_test(scene, seeds, True, setup, log)
        table, name = cal.repose_markdown(res), "repose"
        cal.fig_heap(res[0]).savefig(out / "heap.png", dpi=110)
    else:
        setup = cal.PullSetup(spring=args.spring, speed=args.speed, hold_beyond=args.hold)
        res = cal.pull_test(scene, seeds, args.per_seed, setup=setup, log=log)
        table, name = cal.pull_markdown(res), "pull"
        cal.fig_pull(res).savefig(out / "pull.png", dpi=110)
    (out / f"{name}.md").write_text(f"# {name} test of scene '{scene.name}'\n\n{table}\n", encoding="utf-8")
    print(table)
    print(f"output: {out}/ ({name}.md, {'heap' if name == 'repose' else 'pull'}.png)")
    return 0


def resolve_scene(name: str, quick: bool = False, seed: Optional[int] = None, end_time: Optional[float] = None,
                  until_failure: bool = False, fidelity: Optional[str] = None):
    """A scene from a file path or a ready scene's name, with the command's options (quick first, then
    the fidelity preset, then until failure); ValueError if neither."""
    from .scene import Scene, load_scene

    path = Path(name)
    if path.suffix == ".toml" or path.exists():
        scene = load_scene(path)
    elif name in READY:
        scene = getattr(Scene, name)()
    else:
        raise ValueError(f"scene {name!r} is neither a file nor a ready scene ({', '.join(READY)})")
    if quick:
        scene = scene.quick()
    if fidelity is not None:
        scene = scene.with_value("numerics.fidelity", fidelity)
    if until_failure:
        scene = scene.until_failure()
    if seed is not None:
        scene = scene.replace(seed=seed)
    if end_time is not None:
        scene = scene.replace(end_time=end_time)
    return scene


def _scene_of(args):
    """The scene of `vofdem run`/`check`: SCENE with its options, or a resumed run's own scene.toml."""
    resume = getattr(args, "resume", None)
    if resume is None:
        if args.scene is None:
            raise ValueError("give a SCENE (a scene file or a ready scene) or --resume DIR")
        return resolve_scene(args.scene, args.quick, getattr(args, "seed", None), getattr(args, "end_time", None),
                             args.until_failure, args.fidelity)
    if getattr(args, "seeds", None) or getattr(args, "vary", None):
        raise ValueError("--resume DIR continues one run; an ensemble (--seeds, --vary) resumes when the same "
                         "command is run again on its output directory")
    if (args.scene is not None or args.quick or args.seed is not None or args.end_time is not None or args.until_failure
            or args.fidelity is not None):
        raise ValueError("--resume DIR continues the run with its own scene (DIR/scene.toml): give no SCENE, "
                         "--quick, --fidelity, --until-failure, --seed or --end-time with it")
    from .scene import load_scene

    if not (resume / "scene.toml").is_file():
        raise ValueError(f"--resume {resume}: no scene.toml there, not a run directory")
    return load_scene(resume / "scene.toml")


def _terminate(signum, frame):
    from .run import request_stop

    request_stop()
    raise KeyboardInterrupt


def main(argv: Optional[Sequence[str]] = None, build: Optional[Callable] = None) -> int:
    """Entry point; `build` (scene -> simulation) replaces the solver builder, for tests."""
    args = _parser().parse_args(argv)
    if args.command == "params":
        from .scene import describe_parameters

        print(describe_parameters())
        return 0
    if args.command == "calibrate":
        try:
            return _calibrate(args, resolve_scene(args.scene))
        except ValueError as e:
            print(f"vofdem: error: {e}", file=sys.stderr)
            return 2
    try:
        if args.command == "analyse" and not (args.out / "run.h5").exists() and (args.out / "ensemble.csv").exists():
            from .ensemble import summarise

            print(summarise(args.out))
            return 0
        if args.command == "analyse":
            from .run import postprocess

            a = postprocess(args.out, animation=not args.no_animation)
            print(a.stage_table_markdown())
            return 0
        scene = _scene_of(args)
        from .ensemble import parse_seeds

        seeds = parse_seeds(args.seeds) if getattr(args, "seeds", None) else None
        if seeds is None and getattr(args, "vary", None):
            seeds = [scene.seed]
        if seeds is None and (getattr(args, "workers", None) is not None or getattr(args, "scheduler", None)):
            raise ValueError("--workers and --scheduler are for ensembles (--seeds or --vary)")
        for opt in ("checkpoint_seconds", "xdmf_seconds"):
            if seeds is not None and getattr(args, opt, None) is not None:
                raise ValueError(f"--{opt.replace('_', '-')} is for single runs (an ensemble's members use the "
                                 "default interval)")
        if getattr(args, "threads", None) is not None:
            if seeds is not None:
                raise ValueError("--threads is for single runs (an ensemble's members run one thread each, one "
                                 "member per core)")
            from . import _core

            _core.set_threads(args.threads)
    except ValueError as e:
        print(f"vofdem: error: {e}", file=sys.stderr)
        return 2
    if args.command == "check":
        print(scene.to_toml(), end="")
        return 0
    from .ensemble import run_ensemble
    from .io import OutputError
    from .run import SolverError, run_scene

    out = args.resume or args.out or Path("out") / scene.name
    # a terminated run closes its output as 'interrupted' (with the profile) once the solver returns
    signal.signal(signal.SIGTERM, _terminate)
    opts = dict(progress=not args.no_progress, figures=not args.no_figures, animation=not args.no_animation,
                build=build)
    try:
        if seeds is not None:
            run_ensemble(scene, seeds, out, vary=args.vary, workers=args.workers, scheduler=args.scheduler,
                         retry_failed=args.retry_failed, **opts)
            print()
            print((out / "ensemble.md").read_text(encoding="utf-8").split("\n| member |")[0])
            if scene.hydrograph.stops_at_first_stage:
                print((out / "until_failure.md").read_text(encoding="utf-8"))
            print(f"output: {out}/ (ensemble.md/.csv, fragility.csv/.png, one run directory per member)")
            return 0
        every = {k: getattr(args, k) for k in ("checkpoint_seconds", "xdmf_seconds") if getattr(args, k) is not None}
        res = run_scene(scene, out, resume=args.resume is not None, **every, **opts)
    except SolverError as e:
        print(f"vofdem: {e}", file=sys.stderr)
        return 1
    except OutputError as e:
        print(f"vofdem: output error: {e}", file=sys.stderr)
        return 1
    except ValueError as e:  # e.g. the solver refusing a parameter of the scene
        print(f"vofdem: error: {e}", file=sys.stderr)
        return 2
    except KeyboardInterrupt:
        print(f"vofdem: interrupted; the output written so far is kept in {out}", file=sys.stderr)
        return 130
    print()
    print(res.profile_table)
    print(res.analysis.stage_table_markdown())
    if scene.hydrograph.stops_at_first_stage:
        print((out / "until_failure.md").read_text(encoding="utf-8"))
    print(f"output: {out}/ (run.h5 + run.xmf for ParaView, stones.xmf, stage_table.md/.csv, figures/, animation)")
    return 0


if __name__ == "__main__":  # pragma: no cover
    sys.exit(main())
