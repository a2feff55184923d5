"""Command line: ``vofdem run SCENE [--quick] [--out DIR] [--seed N | --seeds 0-4]`` and helpers.

SCENE is a TOML scene file or the name of a ready scene (``maeno2008``). Exit codes: 0 success,
2 a bad scene or bad arguments (one line on stderr), 1 a solver failure (the output written so far
is kept and marked failed in run.h5).
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
    r.add_argument("scene", help="TOML scene file, or a ready scene: " + ", ".join(READY))
    r.add_argument("--quick", action="store_true", help="shorter, coarser variant that runs in a few minutes")
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
    r.add_argument("--end-time", type=float, default=None, help="stop at this simulated time [s]")
    r.add_argument("--no-figures", action="store_true", help="skip the figures")
    r.add_argument("--no-animation", action="store_true", help="skip the animation")
    r.add_argument("--no-progress", action="store_true", help="no progress bar")
    c = sub.add_parser("check", help="validate a scene file and print it as resolved")
    c.add_argument("scene")
    c.add_argument("--quick", action="store_true")
    a = sub.add_parser("analyse", help="redo the stage tables and figures of a finished run directory")
    a.add_argument("out", type=Path)
    a.add_argument("--no-animation", action="store_true")
    sub.add_parser("params", help="print every scene parameter with its default and allowed range")
    return p


def resolve_scene(name: str, quick: bool = False, seed: Optional[int] = None, end_time: Optional[float] = None):
    """A scene from a file path or a ready scene's name; ValueError if neither."""
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
    if seed is not None:
        scene = scene.replace(seed=seed)
    if end_time is not None:
        scene = scene.replace(end_time=end_time)
    return scene


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
        scene = resolve_scene(args.scene, args.quick, getattr(args, "seed", None), getattr(args, "end_time", None))
        from .ensemble import parse_seeds

        seeds = parse_seeds(args.seeds) if getattr(args, "seeds", None) else None
        if seeds is None and getattr(args, "vary", None):
            seeds = [scene.seed]
        if seeds is None and (getattr(args, "workers", None) is not None or getattr(args, "scheduler", None)):
            raise ValueError("--workers and --scheduler are for ensembles (--seeds or --vary)")
    except ValueError as e:
        print(f"vofdem: error: {e}", file=sys.stderr)
        return 2
    if args.command == "check":
        print(scene.to_toml(), end="")
        return 0
    from .ensemble import run_ensemble
    from .run import SolverError, run_scene

    out = args.out or Path("out") / scene.name
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
            print(f"output: {out}/ (ensemble.md/.csv, fragility.csv/.png, one run directory per member)")
            return 0
        res = run_scene(scene, out, **opts)
    except SolverError as e:
        print(f"vofdem: {e}", file=sys.stderr)
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
    print(f"output: {out}/ (run.h5 + run.xmf for ParaView, stage_table.md/.csv, figures/, animation)")
    return 0


if __name__ == "__main__":  # pragma: no cover
    sys.exit(main())
