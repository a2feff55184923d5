"""The run loop: advance a coupled simulation through a scene's hydrograph, write snapshots, analyse.

The loop talks to the coupled simulation only through these names:
``sim.time`` [s]; ``sim.advance(t_end)``; ``sim.set_inflow_table(times [s], Q [m3/s])``;
``sim.fluid`` with ``grid``, ``cell_F``, ``cell_p``, ``cell_porosity``, ``face_u``, ``face_w``;
``sim.stones`` with ``stone_pos`` (n, 2), ``stone_vel`` (n, 2), ``stone_radius``, ``stone_active``,
``stone_fixed``; ``sim.stone_force_drag``, ``sim.stone_force_pressure`` (n, 2) [N]; ``sim.profile`` with
``names``, ``seconds``, ``calls``; ``sim.export_state()`` / ``sim.import_state(dict)`` (checkpoints).

A solver failure (RuntimeError while stepping) closes the output with everything written so far,
marks it failed and raises ``SolverError`` with the solver's message. A failing write (disk full)
raises ``OutputError`` naming the file, with the snapshots written before it kept. The loop writes a
checkpoint after the first and the last snapshot and every ``checkpoint_seconds`` of wall time
(checkpoint.py); ``run_scene(..., resume=True)`` continues a killed run from the last one.
"""
from __future__ import annotations

import time as _time
import warnings
from dataclasses import dataclass, field
from pathlib import Path
from types import SimpleNamespace
from typing import Callable, Dict, List, Optional

import numpy as np

from . import _core
from .analysis import FailureAnalysis, analyse
from .checkpoint import CHECKPOINT_NAME, CHECKPOINT_SECONDS, Checkpoint, load_checkpoint, save_checkpoint
from .io import XDMF_SECONDS, OutputError, RunData, RunWriter, cell_velocities, check_writable
from .stone_models import front_of, stone_diameters
from .scene import Scene


TOP_ROW_WATER = 0.01  # [-] a water fraction in the domain's top row that counts as water reaching it


class SolverError(RuntimeError):
    """The solver failed while stepping; the output written so far is kept."""


_stop_requested = False


def request_stop() -> None:
    """Asks the running loop to stop at its next snapshot and close its output as 'interrupted'.
    A flag as well as the signal's KeyboardInterrupt: Python drops an exception raised inside a
    finaliser (h5py closes files from __del__), and the stop must not be lost with it."""
    global _stop_requested
    _stop_requested = True


@dataclass
class RunResult:
    """What a run returns: its output paths, the failure analysis, wall and simulated time [s], the cost per
    stage, the coupled steps and the steps each step limit bound."""

    out_dir: Path
    h5_path: Path
    xmf_path: Path
    analysis: Optional[FailureAnalysis]
    wall_seconds: float
    simulated_seconds: float
    profile_table: str
    files: List[Path] = field(default_factory=list)
    steps: int = 0  # the coupled steps of the whole run (a resumed run counts the killed run's too)
    # the steps each limit bound (Coupler.step_limits: this process's steps, a resumed run's from its resume)
    step_limits: Dict[str, int] = field(default_factory=dict)

    @property
    def real_time_factor(self) -> float:
        """Wall time per simulated time [-] (below 1: faster than the flume)."""
        return self.wall_seconds / self.simulated_seconds if self.simulated_seconds > 0 else float("nan")


def build_simulation(scene: Scene, packing: Optional[dict] = None, settle: Optional[bool] = None):
    """Builds the coupled simulation of a scene (see builder.build_simulation)."""
    from .builder import build_simulation as build

    return build(scene, packing, settle)


def grid_faces(grid):
    """(x_faces [m], z_faces [m]) of a Grid2D."""
    x = grid.x0 + grid.dx * np.arange(grid.nx + 1)
    return x, np.asarray(grid.z_faces, float)


def water_level(F: np.ndarray, z_faces: np.ndarray, i: int) -> float:
    """Water level [m] above the bed in cell column i: the column's water volume per unit length."""
    dz = np.diff(z_faces)
    return float(np.sum(np.asarray(F)[:, i] * dz))


def profile_table(profile, wall_seconds: Optional[float] = None, simulated: Optional[float] = None) -> str:
    """Markdown table of a StageProfile: stage, seconds, share, calls, ms per call."""
    names, seconds, calls = list(profile.names), np.asarray(profile.seconds, float), np.asarray(profile.calls)
    total = float(seconds.sum())
    rows = ["| stage | seconds | share | calls | ms per call |", "|---|---|---|---|---|"]
    for name, s, c in sorted(zip(names, seconds, calls), key=lambda r: -r[1]):
        share = 100 * s / total if total > 0 else 0.0
        per = 1e3 * s / c if c else 0.0
        rows.append(f"| {name} | {s:.3f} | {share:.1f} % | {int(c)} | {per:.4f} |")
    rows.append(f"| total (stages) | {total:.3f} | 100 % | | |")
    if wall_seconds is not None and simulated:
        rows.append("")
        rows.append(f"Wall time {wall_seconds:.1f} s for {simulated:.1f} s simulated: real-time factor "
                    f"{wall_seconds / simulated:.3g} (wall / simulated).")
    return "\n".join(rows) + "\n"


class _Recorder:
    """Reads the simulation's views and appends one snapshot to the writer."""

    def __init__(self, sim, scene: Scene, writer: RunWriter, pos0: Optional[np.ndarray] = None,
                 fixed0: Optional[np.ndarray] = None):
        self.sim, self.scene, self.writer = sim, scene, writer
        g = sim.fluid.grid
        self.nx, self.nz = g.nx, g.nz
        self.x_faces, self.z_faces = grid_faces(g)
        self.gauge_i = int(np.clip(np.searchsorted(self.x_faces, scene.gauge_x) - 1, 0, self.nx - 1))
        start = sim.stones.stone_pos if pos0 is None else pos0
        self.pos0 = np.array(start, float).reshape(-1, 2).copy()
        self.diameter = stone_diameters(sim.stones)
        self.polygons = front_of(sim.stones).output_shapes(sim.stones) is not None
        self.three_d = front_of(sim.stones).dimensions == 3
        self.fixed0 = np.zeros(len(self.diameter), bool) if fixed0 is None else np.asarray(fixed0, bool)
        self.removal_t = np.full(len(self.diameter), np.nan)  # first snapshot of each removal (analysis.py)
        self.moved = 0
        self.top_water_t: Optional[float] = None  # when water first reached the domain's top row [s]

    def record(self) -> None:
        sim, fl, st = self.sim, self.sim.fluid, self.sim.stones
        shape = (self.nz, self.nx)
        F = np.asarray(fl.cell_F).reshape(shape)
        u, w = cell_velocities(fl.face_u, fl.face_w, self.nx, self.nz)
        fields = {"F": F, "p": np.asarray(fl.cell_p).reshape(shape),
                  "porosity": np.asarray(fl.cell_porosity).reshape(shape), "u": u, "w": w}
        pos = np.asarray(st.stone_pos, float).reshape(-1, 2)
        stones = {"pos": pos, "vel": np.asarray(st.stone_vel).reshape(-1, 2),
                  "force_drag": np.asarray(sim.stone_force_drag).reshape(-1, 2),
                  "force_pressure": np.asarray(sim.stone_force_pressure).reshape(-1, 2),
                  "active": np.asarray(st.stone_active).astype(bool)}
        if self.polygons:
            stones["angle"] = np.array(st.stone_angle, float)
        if self.three_d:
            stones["y"], stones["quat"] = np.array(st.stone_y, float), np.array(st.stone_quat, float)
        t = float(sim.time)
        self.check_top_row(F[-1], t)
        disp = np.linalg.norm(pos - self.pos0, axis=1)
        removed = (disp > self.diameter) | ~stones["active"]
        self.moved = int(np.sum(removed))
        self.removal_t[removed & ~self.fixed0 & np.isnan(self.removal_t)] = t
        self.writer.write_snapshot(t, self.scene.hydrograph.discharge(t), water_level(F, self.z_faces, self.gauge_i),
                                   fields if self.writer.write_fields else None, stones)

    def check_top_row(self, top: np.ndarray, t: float) -> None:
        """Warns once when water reaches the top row: through the open top it would leave the flume."""
        if self.top_water_t is not None or not top.max() > TOP_ROW_WATER:
            return
        self.top_water_t = t
        i = int(np.argmax(top))
        x = 0.5 * (self.x_faces[i] + self.x_faces[i + 1])
        warnings.warn(f"water reaches the domain's top row at t = {t:.4g} s (F = {top[i]:.3g} at x = {x:.4g} m) "
                      f"and can leave through the open top: raise flume.height = {self.z_faces[-1]:.4g} m",
                      RuntimeWarning, stacklevel=2)


def check_headroom(scene: Scene, z_faces) -> None:
    """Warns before a run whose water the weir formula (builder.upstream_level) puts above the floor of
    the domain's top row at the hydrograph's peak: it would leave through the open top. The formula
    overestimates (the Maeno weir at 25 l/s, B = 0.5 m: 0.345 m against 0.325 m measured), so a run it
    passes can still warn when the water gets there (_Recorder.check_top_row)."""
    from .builder import peak_discharge, upstream_level

    peak = peak_discharge(scene)
    level, floor = upstream_level(scene, peak), float(z_faces[-2])
    if level > floor:
        warnings.warn(f"at the peak discharge {peak * 1e3:.4g} l/s the weir formula puts the water {level:.4g} m high "
                      f"(flume.width = {scene.flume.width:g} m), above the domain's top row from {floor:.4g} m: "
                      f"raise flume.height = {scene.flume.height:g} m", RuntimeWarning, stacklevel=2)


def run_scene(scene: Scene, out_dir, sim=None, progress: bool = True, figures: Optional[bool] = None,
              animation: Optional[bool] = None, build: Optional[Callable] = None, log=print,
              resume: bool = False, checkpoint_seconds: float = CHECKPOINT_SECONDS,
              xdmf_seconds: float = XDMF_SECONDS) -> RunResult:
    """Runs a scene to its end, writing ``out_dir``/run.h5 + run.xmf, the stage tables, the figures,
    the animation and the per-stage cost table. Returns a RunResult; raises SolverError on a solver
    failure (after closing the output), OutputError on a failing write, ValueError (before the run) if
    the output directory is not writable. resume: continue the killed run in ``out_dir`` from its
    checkpoint (the scene must be the run's own: ``out_dir``/scene.toml). checkpoint_seconds: wall time
    [s] between checkpoints (>= 0; 0: after every snapshot). xdmf_seconds: wall time [s] between rewrites
    of the XDMF files during the run (>= 0; 0: after every snapshot; io.py)."""
    from . import __version__

    global _stop_requested
    _stop_requested = False
    if not checkpoint_seconds >= 0.0:
        raise ValueError(f"checkpoint_seconds = {checkpoint_seconds} is out of range (allowed: >= 0 s)")
    if not xdmf_seconds >= 0.0:
        raise ValueError(f"xdmf_seconds = {xdmf_seconds} is out of range (allowed: >= 0 s)")
    scene.validate()
    out = Path(out_dir)
    ck = load_checkpoint(out / CHECKPOINT_NAME) if resume else None
    if ck is not None and ck.scene_toml != scene.to_toml():
        raise ValueError(f"the scene differs from the one of the run in '{out}' (resume with its own scene.toml)")
    if ck is not None and RunData(out / "run.h5").attrs.get("status") == "completed":
        raise ValueError(f"the run in '{out}' has completed: nothing to resume")
    try:
        check_writable(out)
    except OutputError as e:
        raise ValueError(str(e)) from e
    if ck is None:
        (out / "scene.toml").write_text(scene.to_toml(), encoding="utf-8")
    packing: dict = {}
    if ck is None:  # a grading report of an earlier run in this directory is not this one's
        (out / "grading.md").unlink(missing_ok=True)
    if sim is None:
        # a resumed run's stones settled before its checkpoint: they are not settled again (a study's build
        # too: it is given the scene without the settling, whose result the checkpoint's state replaces),
        # and they are built from the checkpoint's stones, not packed (builder.resumed_from)
        with _resumed(ck):
            if build is not None:
                sim = build(scene.with_value("hydrograph.settle_in_still_water", False) if ck else scene)
            else:
                sim = build_simulation(scene, packing, settle=False if ck else None)
    if ck is None and getattr(packing.get("report"), "zone", None) is not None:
        _write_grading(out, scene, sim.stones, packing["report"].zone, figures)
    t_tab, q_tab = scene.hydrograph.table(scene.duration)
    sim.set_inflow_table(np.asarray(t_tab, float), np.asarray(q_tab, float))
    loop = _Loop(sim, scene, out, __version__, ck, checkpoint_seconds, xdmf_seconds)
    if ck is None:
        check_headroom(scene, loop.rec.z_faces)
    duration = scene.duration
    bar = _progress_bar(duration, progress)
    try:
        if ck is None:
            loop.snapshot()
        for t_next in loop.remaining():
            if _stop_requested:
                raise KeyboardInterrupt
            if loop.first_stage_reached():
                break
            sim.advance(t_next)
            loop.after_advance()
            loop.snapshot()
            if bar is not None:
                bar.n = round(min(float(sim.time), duration), 3)
                bar.set_postfix_str(f"Q={scene.hydrograph.discharge_lps_at(float(sim.time)):.2f} l/s, "
                                    f"stones moved={loop.rec.moved}", refresh=False)
                bar.refresh()
    except RuntimeError as e:
        if bar is not None:
            bar.close()
        loop.close(f"failed: {e}")
        raise SolverError(f"solver failed at t = {float(sim.time):.4g} s: {e} (output so far kept in {out})") from e
    except OutputError:
        if bar is not None:
            bar.close()
        loop.close_quietly("failed: output could not be written")
        raise
    except BaseException:
        if bar is not None:
            bar.close()
        loop.close("interrupted")
        raise
    if bar is not None:
        bar.close()
    wall = loop.wall_seconds()
    simulated = float(sim.time) - loop.t_start
    table = profile_table(loop.profile(), wall, simulated)
    table += f"\nThreads: {_core.threads()} (docs/threads.md).\n"
    writer = loop.writer
    extra = {"wall_seconds": wall, "simulated_seconds": simulated, "threads": _core.threads()}
    if loop.first_stage_reached():
        extra["stopped"] = "at the first destruction stage"
    loop.close("completed", extra)
    (out / "profile.md").write_text(table, encoding="utf-8")
    result = RunResult(out, writer.path, writer.xmf_path, None, wall, simulated, table,
                       [writer.path, writer.xmf_path, out / "profile.md", out / "scene.toml"], int(sim.step_count),
                       {k: int(v) for k, v in dict(sim.step_limits()).items()})
    result.analysis = postprocess(out, scene, figures=scene.output.figures if figures is None else figures,
                                  animation=scene.output.animation if animation is None else animation,
                                  files=result.files)
    return result


def _resumed(ck: Optional[Checkpoint]):
    """The context of a run's build: a resumed run's stones from its checkpoint (builder.resumed_from) when the
    checkpoint keeps the disc porosity the run was built with; else a build as any (the weir packed)."""
    from contextlib import nullcontext

    from .builder import resumed_from

    if ck is None or ck.disc_porosity is None:
        return nullcontext()
    return resumed_from(ck.state, ck.disc_porosity)


class _Loop:
    """The run loop's state: the writer, the snapshot times, the held stones, the checkpoints and the
    cost so far (a resumed run adds the killed run's profile and wall time to its own)."""

    def __init__(self, sim, scene: Scene, out: Path, version: str, ck: Optional[Checkpoint],
                 checkpoint_seconds: float = CHECKPOINT_SECONDS, xdmf_seconds: float = XDMF_SECONDS):
        self.sim, self.scene, self.out = sim, scene, out
        st = sim.stones
        self.wall0, self.cpu0 = _time.perf_counter(), _time.process_time()
        self.checkpoint_seconds, self.last_checkpoint = checkpoint_seconds, None
        if ck is None:
            self.fixed0 = np.asarray(st.stone_fixed).astype(bool).copy()
            ramp = scene.hydrograph.ramp_start
            self.hold = scene.hydrograph.hold_stones_during_spin_up and ramp > float(sim.time) and len(self.fixed0) > 0
            self.t_start = float(sim.time)
            self.targets = _targets(self.t_start, scene.duration, scene.output.snapshot_interval,
                                    ramp if self.hold else None)
            x_faces, z_faces = grid_faces(sim.fluid.grid)
            self.writer = RunWriter(out / "run.h5", x_faces, z_faces, stone_diameters(st), self.fixed0,
                                    capacity=1 + len(self.targets), scene_toml=scene.to_toml(), seed=scene.seed,
                                    version=version, polygons=front_of(st).output_shapes(st), xdmf_seconds=xdmf_seconds,
                                    width=st.params.width if front_of(st).dimensions == 3 else None)
            if self.hold:
                st.held = True  # kept in place with their contacts' springs (DEMSystem.held)
            self.base_profile, self.base_wall, self.base_cpu, pos0 = {}, 0.0, 0.0, None
        else:
            sim.import_state(ck.state)
            self.targets, self.hold = ck.targets, ck.hold
            self.writer = RunWriter.reopen(out / "run.h5", ck.snapshots, xdmf_seconds)
            data = RunData(self.writer.path)
            self.fixed0, pos0 = data.fixed, data.pos[0]
            if self.hold:  # a checkpoint that held by fixing every stone (before DEMSystem.held) is let go as well
                st.stone_fixed[:] = self.fixed0
            # only a held run holds: letting go of stones that are not held would drop the accelerations the
            # checkpoint carries (DEMSystem.held = False recomputes them), and the resumed steps would differ
            if self.hold:
                st.held = True
            self.t_start = float(data.times[0])
            self.base_profile, self.base_wall, self.base_cpu = ck.profile, ck.wall_seconds, ck.cpu_seconds
        self.rec = _Recorder(sim, scene, self.writer, pos0, self.fixed0)
        if ck is not None:
            self.rec.top_water_t = ck.water_at_top_s
        if ck is not None and scene.hydrograph.stops_at_first_stage:  # the removals before the kill
            from .analysis import removal_times

            self.rec.removal_t = removal_times(data.times, data.pos, data.diameter, data.active, data.fixed)

    def first_stage_reached(self) -> bool:
        """Whether the run stops here: a scene that stops at the first stage (until failure) once the
        snapshots so far hold a destruction stage (analysis.find_bursts, its default criterion)."""
        if not self.scene.hydrograph.stops_at_first_stage:
            return False
        from .analysis import StageCriterion, find_bursts

        c = StageCriterion()
        return bool(find_bursts(self.rec.removal_t, c.gap, c.min_stones)[0])

    def remaining(self):
        """The snapshot times still to run."""
        return self.targets[self.writer.count - 1:]

    def after_advance(self) -> None:
        """Releases the held stones once the ramp starts."""
        if self.hold and float(self.sim.time) >= self.scene.hydrograph.ramp_start - 1e-9:
            self.sim.stones.held = False
            self.hold = False

    def snapshot(self) -> None:
        """Records a snapshot, then the checkpoint: after this loop's first snapshot, the run's last one,
        and any that comes checkpoint_seconds of wall time after the last checkpoint."""
        self.rec.record()
        now = _time.perf_counter()
        if (self.last_checkpoint is None or self.writer.count == 1 + len(self.targets)
                or now - self.last_checkpoint >= self.checkpoint_seconds):
            self.last_checkpoint = now
            names, seconds, calls = self.profile_tuple()
            save_checkpoint(self.out / CHECKPOINT_NAME, Checkpoint(
                dict(self.sim.export_state()), self.writer.count, self.targets, self.hold, self.scene.to_toml(),
                {n: (s, c) for n, s, c in zip(names, seconds, calls)}, self.wall_seconds(), self.rec.top_water_t,
                self.cpu_seconds(), float(self.sim.params.n_exp)))

    def wall_seconds(self) -> float:
        return self.base_wall + _time.perf_counter() - self.wall0

    def cpu_seconds(self) -> Optional[float]:
        """The process time of the run so far [s], the killed runs' included; None if a checkpoint it
        resumed from did not keep its own."""
        return None if self.base_cpu is None else self.base_cpu + _time.process_time() - self.cpu0

    def profile_tuple(self):
        """(names, seconds, calls) of the solver's profile plus the killed run's (resumed runs)."""
        own = _profile_tuple(self.sim)
        if own is None:
            return None
        names, seconds, calls = own
        base = self.base_profile
        # stages the killed run had and this one has not (the settling before its checkpoint) are kept
        extra = [n for n in base if n not in names]
        return (names + extra, [s + base.get(n, (0.0, 0))[0] for n, s in zip(names, seconds)] +
                [base[n][0] for n in extra], [c + base.get(n, (0.0, 0))[1] for n, c in zip(names, calls)] +
                [base[n][1] for n in extra])

    def profile(self):
        names, seconds, calls = self.profile_tuple()
        return SimpleNamespace(names=names, seconds=seconds, calls=calls)

    def close(self, status: str, extra: Optional[dict] = None) -> None:
        top = {} if self.rec.top_water_t is None else {"water_at_top_s": self.rec.top_water_t}
        self.writer.close(status, profile=self.profile_tuple(),
                          extra_attrs={**(extra or {}), **top, **_model_attrs(self.sim, self.scene)})

    def close_quietly(self, status: str) -> None:
        """Closes after a failed write: a second failure (the disk still full) must not hide the first."""
        try:
            self.close(status)
        except OutputError:
            pass


def _model_attrs(sim, scene: Scene) -> dict:
    """The model options of the run: the drag model, the porosity mapping and the porosity n_s inside
    each disc that eq. (11) used (n_exp, or the bulk-consistent value computed at build)."""
    out = {"drag_model": scene.stones.drag_model, "porosity_mapping": scene.stones.porosity_mapping,
           "stone_shape": scene.stones.shape}
    out["disc_porosity"] = float(sim.params.n_exp)
    return out


def analyse_run(data: RunData, scene: Scene) -> FailureAnalysis:
    """Failure analysis of a written run."""
    return analyse(data.times, data.pos, data.diameter, scene.weir, scene.hydrograph.discharge_lps_at,
                   active=data.active, fixed=data.fixed, ramp_start=scene.hydrograph.ramp_start,
                   reference=scene.reference)


def postprocess(out_dir, scene: Optional[Scene] = None, figures: bool = True, animation: bool = True,
                files: Optional[list] = None) -> FailureAnalysis:
    """Stage tables (markdown + CSV), crest lowering (CSV), figures and animation of a written run."""
    out = Path(out_dir)
    data = RunData(out / "run.h5")
    scene = scene or data.scene()
    a = analyse_run(data, scene)
    files = files if files is not None else []
    (out / "stage_table.md").write_text(a.stage_table_markdown(), encoding="utf-8")
    (out / "stage_table.csv").write_text(a.stage_table_csv(), encoding="utf-8")
    np.savetxt(out / "crest_lowering.csv",
               np.column_stack([a.times, data.discharge * 1e3, a.crest_level, a.crest_lowering, a.removed_count]),
               delimiter=",", header="time_s,discharge_lps,crest_level_m,crest_lowering_m,stones_removed",
               comments="", fmt="%.6g")
    files += [out / "stage_table.md", out / "stage_table.csv", out / "crest_lowering.csv"]
    files += _grading_files(out, scene, data, figures)
    if scene.hydrograph.stops_at_first_stage:
        from .reports import until_failure_markdown

        (out / "until_failure.md").write_text(until_failure_markdown(a, scene), encoding="utf-8")
        files.append(out / "until_failure.md")
    if figures or animation:
        from . import plots

        if figures:
            files += plots.make_figures(data, a, scene, out / "figures")
        if animation and data.has_fields and data.times.size > 1:
            files.append(plots.animate(data, scene, out / "animation", analysis=a))
    return a


def _write_grading(out: Path, scene: Scene, stones, zone, figures: bool) -> None:
    """grading.md (and figures/grading.png) of a weir the outline packer built: each stone in the zone it
    was drawn for (reports.packed_report)."""
    from .reports import packed_report

    pos = np.asarray(stones.stone_pos, float).reshape(-1, 2)
    md, fig = packed_report(scene, pos, 2.0 * np.asarray(stones.stone_radius, float), zone)
    if md is None:
        return
    (out / "grading.md").write_text(md, encoding="utf-8")
    if figures is not False and scene.output.figures:
        (out / "figures").mkdir(parents=True, exist_ok=True)
        fig.savefig(out / "figures" / "grading.png", dpi=110)


def _grading_files(out: Path, scene: Scene, data: RunData, figures: bool) -> list:
    """grading.md (and figures/grading.png) of a graded scene: the packed weir's grading against the
    requested one (reports.packed_report). Written when the weir was built (the stones' zones as
    drawn); a weir from elsewhere (a test double) counts each stone in the zone of its first place."""
    from .reports import packed_report

    if (out / "grading.md").exists():
        return [out / "grading.md"] + ([out / "figures" / "grading.png"] if (out / "figures" / "grading.png").exists()
                                       else [])
    md, fig = packed_report(scene, data.pos[0], data.diameter)
    if md is None:
        return []
    (out / "grading.md").write_text(md, encoding="utf-8")
    files = [out / "grading.md"]
    if figures:
        (out / "figures").mkdir(parents=True, exist_ok=True)
        fig.savefig(out / "figures" / "grading.png", dpi=110)
        files.append(out / "figures" / "grading.png")
    return files


def _targets(t0: float, duration: float, dt: float, release: Optional[float]):
    """Snapshot times after t0 up to duration (every dt), plus the release time of held stones."""
    n = int(np.ceil((duration - t0) / dt - 1e-9))
    ts = [min(t0 + k * dt, duration) for k in range(1, n + 1)]
    if release is not None and t0 < release < duration:
        ts.append(release)
    return sorted({round(t, 12) for t in ts})


def _profile_tuple(sim):
    try:
        p = sim.profile
        return list(p.names), list(p.seconds), list(p.calls)
    except Exception:  # noqa: BLE001 - a broken profile must not hide the solver's own error
        return None


def _progress_bar(duration: float, enabled: bool):
    if not enabled:
        return None
    from tqdm.auto import tqdm

    return tqdm(total=round(duration, 3), unit="s", unit_scale=False, dynamic_ncols=True,
                bar_format="{l_bar}{bar}| t={n:.1f}/{total:.1f} s sim [{elapsed}<{remaining}]{postfix}")
