"""Real-time factor of the Maeno 2008 scenario on one core, with the solver's per-stage breakdown.

Runs the scene (the full scenario by default: 20 s spin-up + 120 s ramp; `--end-time T` stops
earlier, `--quick` the coarse variant) without figures, and writes
benchmarks/results/maeno2008_realtime.md: wall time, simulated time, their ratio (wall / simulated;
below 1 is faster than the flume), and the stage table of the run.

    OMP_NUM_THREADS=1 PYTHONPATH=python python3 benchmarks/maeno2008_realtime.py [--end-time 30] [--quick]
    PYTHONPATH=python python3 benchmarks/maeno2008_realtime.py --from-run out/maeno2008   # a finished run
"""
import argparse
import os
import platform
import tempfile
from pathlib import Path

os.environ.setdefault("OMP_NUM_THREADS", "1")
ROOT = Path(__file__).resolve().parents[1]

from vofdem.run import run_scene  # noqa: E402
from vofdem.scene import Scene  # noqa: E402
from vofdem.study import write_page  # noqa: E402


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--end-time", type=float, default=None, help="stop at this simulated time [s]")
    ap.add_argument("--quick", action="store_true")
    ap.add_argument("--from-run", type=Path, default=None, help="report a finished run directory instead")
    ap.add_argument("--viscous-scheme", choices=["explicit", "implicit_vertical"], default=None,
                    help="override FlowParams.viscous_scheme (default: the library's)")
    ap.add_argument("--corner-viscosity", choices=["arithmetic", "harmonic"], default=None,
                    help="override FlowParams.corner_viscosity (default: the library's)")
    ap.add_argument("--out", type=Path, default=ROOT / "benchmarks" / "results" / "maeno2008_realtime.md")
    args = ap.parse_args()
    if args.from_run is not None:
        return report_run(args.from_run, args.out)
    if args.viscous_scheme or args.corner_viscosity:
        override_flow_params(args.viscous_scheme, args.corner_viscosity)
    scene = Scene.maeno2008()
    if args.quick:
        scene = scene.quick()
    if args.end_time is not None:
        scene = scene.replace(end_time=args.end_time)
    with tempfile.TemporaryDirectory() as tmp:
        res = run_scene(scene, tmp, progress=True, figures=False, animation=False)
        stages = res.analysis.stage_table_markdown()
    text = [f"# Real-time factor of the '{scene.name}' scenario", "",
            f"Machine: {platform.processor() or platform.machine()}, Python {platform.python_version()}, one core "
            f"(OMP_NUM_THREADS={os.environ['OMP_NUM_THREADS']}).",
            f"Grid {scene.grid.dx} m x {scene.grid.dz} m ({scene.grid.dz_bed} m at the bed) over "
            f"{scene.flume.length:.3f} m x {scene.flume.height} m; simulated {res.simulated_seconds:.1f} s.", "",
            f"**Real-time factor (wall / simulated): {res.real_time_factor:.3g}** "
            f"({res.wall_seconds:.1f} s wall for {res.simulated_seconds:.1f} s simulated).", "",
            "## Per-stage cost", "", res.profile_table, "## Stages found in this run", "", stages]
    write_page(args.out, text)


def override_flow_params(scheme, corner):
    """Wraps the builder's flow_params so that the run uses the given viscous options."""
    import vofdem
    from vofdem import builder

    base = builder.flow_params

    def flow_params(scene):
        p = base(scene)
        if scheme:
            p.viscous_scheme = getattr(vofdem.ViscousScheme, scheme.upper())
        if corner:
            p.corner_viscosity = getattr(vofdem.CornerViscosity, corner.upper())
        return p

    builder.flow_params = flow_params


def report_run(run_dir: Path, out: Path):
    """The same report from a finished run (its HDF5 attributes, profile and stage table)."""
    from types import SimpleNamespace

    from vofdem.io import RunData
    from vofdem.run import profile_table

    d = RunData(run_dir / "run.h5")
    scene = d.scene()
    wall, sim = float(d.attrs["wall_seconds"]), float(d.attrs["simulated_seconds"])
    names, seconds, calls = d.profile
    table = profile_table(SimpleNamespace(names=names, seconds=seconds, calls=calls), wall, sim)
    text = [f"# Real-time factor of the '{scene.name}' scenario (run in {run_dir.name}, with output)", "",
            f"Grid {scene.grid.dx} m x {scene.grid.dz} m ({scene.grid.dz_bed} m at the bed) over "
            f"{scene.flume.length:.3f} m x {scene.flume.height} m, {d.diameter.size} stones; simulated {sim:.1f} s; "
            f"one process, OMP_NUM_THREADS=1, on a 2-core machine shared with other jobs.", "",
            f"**Real-time factor (wall / simulated): {wall / sim:.3g}** ({wall:.0f} s wall for {sim:.1f} s simulated;"
            f" wall time includes writing the snapshots).", "",
            "## Per-stage cost", "", table, "## Stages found in this run", "",
            (run_dir / "stage_table.md").read_text(encoding="utf-8")]
    write_page(out, text)


if __name__ == "__main__":
    main()
