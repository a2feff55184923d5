"""Ensembles: one scene over several packings (seeds) and parameter values, each member a whole run.

A weir's failure depends on where each stone sits, and one packing is one sample: the stage
discharges of a single seed can differ by several l/s from another's (docs/scenario_diagnosis.md).
`run_ensemble` runs the scene once per member, a member being one seed and one combination of the
varied parameters (several `vary` keys make their product), as a task on Dask distributed (a
LocalCluster by default, see `cluster`). Each member is a complete run directory:

    out_dir/seed<N>/                     without varied parameters
    out_dir/<key>=<value>[,...]/seed<N>/ with them, e.g. stones.friction_stone=0.5/seed3/

and its `outcome.json` is written last, atomically: a member with one is finished and is not run
again by a later call on the same directory (unless it failed and `retry_failed` is set). A member
whose solver fails is recorded with the error as 'failed'; one whose worker died is recorded as
'lost' and run again by the next call. After every member the summary is rewritten
(``ensemble.csv``: one row per member; ``ensemble.md``); at the end the fragility of each event per
parameter combination (``fragility.csv``, ``fragility.png``, see `fragility`).
"""
from __future__ import annotations

import hashlib
import itertools
import json
import os
import socket
import time as _time
from dataclasses import dataclass
from pathlib import Path
from typing import Any, Callable, Dict, List, Optional, Sequence, Tuple

import numpy as np

from .scene import Scene, load_scene

OUTCOME_FILE = "outcome.json"
# the columns of an outcome, after the member's name, seed and parameters
OUTCOME_COLUMNS = ["status", "error", "first_removal_lps", "stage1_lps", "stage1_stones", "stage2_lps",
                   "stage2_stones", "stage3_lps", "stage3_stones", "stages", "removed", "stones",
                   "crest_lowering_mm", "first_discharge_lps", "last_discharge_lps", "simulated_seconds",
                   "wall_seconds", "cpu_seconds", "steps", "stones_hash"]


def parse_seeds(spec: str) -> List[int]:
    """'0-4' -> [0, 1, 2, 3, 4]; '0,3,7' and '0-2,5' likewise; ValueError naming the bad part."""
    seeds: List[int] = []
    for part in spec.split(","):
        part = part.strip()
        try:
            if "-" in part[1:]:
                lo, hi = (int(v) for v in part.split("-", 1))
                if hi < lo:
                    raise ValueError
                seeds += range(lo, hi + 1)
            else:
                seeds.append(int(part))
        except ValueError:
            raise ValueError(f"seeds: {part!r} in {spec!r} is not a seed or a range 'a-b' with a <= b "
                             f"(e.g. '0-4' or '0,3,7')") from None
    if any(s < 0 for s in seeds) or len(set(seeds)) != len(seeds):
        raise ValueError(f"seeds: {spec!r} must list distinct non-negative seeds")
    return seeds


def _read_value(text: str):
    """A value as TOML reads it ('0.5', 'true', '"bed"'), else the text itself ('bed', '4.8 cm')."""
    from .schema import _toml

    try:
        return _toml.loads(f"v = {text}")["v"]
    except _toml.TOMLDecodeError:
        return text


def parse_vary(spec: str) -> Tuple[str, List[Any]]:
    """'stones.friction_stone=0.5,0.577' -> ('stones.friction_stone', [0.5, 0.577])."""
    key, sep, values = spec.partition("=")
    items = [v.strip() for v in values.split(",")]
    if not sep or not key.strip() or not all(items):
        raise ValueError(f"vary: {spec!r} is not KEY=V1,V2,... (e.g. 'stones.friction_stone=0.5,0.577,0.65')")
    key = key.strip()
    if key == "seed":
        raise ValueError("vary: the seed is varied with --seeds (e.g. --seeds 0-29), not with --vary")
    vals = [_read_value(v) for v in items]
    if len(set(map(repr, vals))) != len(vals):
        raise ValueError(f"vary: {spec!r} lists a value twice")
    return key, vals


def with_settings(scene, items):
    """The scene with each 'KEY=VALUE' of items set (one value each, read as --vary reads them), validated."""
    for item in items:
        key, values = parse_vary(item)
        if len(values) != 1:
            raise ValueError(f"--set {item!r}: one value, not {len(values)}")
        scene = scene.with_value(key, values[0])
    return scene.validate()


def _format_value(v) -> str:
    if isinstance(v, bool):
        return "true" if v else "false"
    if isinstance(v, float):
        return repr(v)
    return str(v).replace("/", "_").replace(os.sep, "_")


@dataclass(frozen=True)
class Member:
    """One run of an ensemble: a seed and the varied parameters' values (dotted key, value)."""

    seed: int
    params: Tuple[Tuple[str, Any], ...] = ()

    @property
    def combination(self) -> str:
        """Directory of the parameter combination ('' without varied parameters)."""
        return ",".join(f"{k}={_format_value(v)}" for k, v in self.params)

    @property
    def name(self) -> str:
        """The member's directory relative to the ensemble's."""
        return f"{self.combination}/seed{self.seed}" if self.params else f"seed{self.seed}"

    def scene(self, base: Scene) -> Scene:
        s = base
        for k, v in self.params:
            s = s.with_value(k, v)
        return s.replace(seed=self.seed)


def plan_members(scene: Scene, seeds: Sequence[int], vary: Optional[Sequence] = None) -> List[Member]:
    """The members of an ensemble, every combination of `vary` (a mapping key -> values, or specs
    'KEY=V1,V2' or (key, values) pairs) over the seeds. Each value is validated on the scene before
    anything runs (ValueError naming it); values are kept as the scene holds them (SI)."""
    if not seeds:
        raise ValueError("seeds: an ensemble needs at least one seed")
    axes: List[Tuple[str, List[Any]]] = []
    items = vary.items() if isinstance(vary, dict) else (vary or [])
    for item in items:
        key, values = parse_vary(item) if isinstance(item, str) else item
        if key in [k for k, _ in axes]:
            raise ValueError(f"vary: {key} is given twice")
        canon = []
        for v in values:
            try:
                canon.append(scene.with_value(key, v).value_of(key))
            except ValueError as e:
                raise ValueError(f"vary: {e}") from None
        axes.append((key, canon))
    members = []
    for combo in itertools.product(*[[(k, v) for v in vals] for k, vals in axes]):
        for seed in seeds:
            m = Member(int(seed), tuple(combo))
            try:  # every combination must make a valid scene (e.g. a weir that fits the flume)
                m.scene(scene)
            except ValueError as e:
                raise ValueError(f"vary: {e} (in the combination {m.combination})") from None
            members.append(m)
    return members


def scene_digest(scene: Scene) -> str:
    """SHA-256 of the scene's TOML text: a member's scene, to tell whether a finished member ran the same one."""
    return hashlib.sha256(scene.to_toml().encode()).hexdigest()


def _write_atomic(path: Path, text: str) -> None:
    tmp = path.with_name(f".{path.name}.{os.getpid()}.tmp")
    tmp.write_text(text, encoding="utf-8")
    os.replace(tmp, path)


def _event_columns(analysis, scene: Scene) -> Dict[str, Any]:
    """Event discharges of a run, the first discharge at which it could see an event (the first
    snapshot after the stones' release) and the last (its end)."""
    a = analysis
    h = scene.hydrograph
    release = h.ramp_start if h.hold_stones_during_spin_up and h.ramp_start > a.times[0] else float(a.times[0])
    after = a.times[a.times > release + 1e-9]
    fr = a.first_removal
    row: Dict[str, Any] = {"first_removal_lps": None if fr is None else float(a.discharge_lps_at(fr))}
    for k in (1, 2, 3):
        st = a.stages[k - 1] if len(a.stages) >= k else None
        row[f"stage{k}_lps"] = None if st is None else float(st.discharge_lps)
        row[f"stage{k}_stones"] = None if st is None else int(st.n_stones)
    row.update(stages=len(a.stages), removed=int(np.isfinite(a.removal_time).sum()),
               stones=int(a.removal_time.size), crest_lowering_mm=1e3 * float(a.crest_lowering[-1]),
               first_discharge_lps=float(a.discharge_lps_at(float(after[0]))) if after.size else None,
               last_discharge_lps=float(a.discharge_lps_at(float(a.times[-1]))),
               simulated_seconds=float(a.times[-1]))
    return row


def _stones_hash(h5_path: Path) -> str:
    """First 16 hex digits of the SHA-256 of the last snapshot's stone positions (float64 bytes)."""
    from .io import RunData

    pos = np.ascontiguousarray(RunData(h5_path).pos[-1], dtype="<f8")
    return hashlib.sha256(pos.tobytes()).hexdigest()[:16]


def run_member(base: Scene, member: Member, out_dir, figures: bool = False, animation: bool = False,
               build: Optional[Callable] = None, retry_failed: bool = False, threads: int = 1) -> Dict[str, Any]:
    """Runs one member into ``out_dir/member.name`` and writes its outcome.json last (atomically);
    returns the outcome. A failure inside the run is an outcome with status 'failed'. A member that
    finished already returns its outcome without running: Dask recomputes the tasks whose results
    were held by a worker that died, and a finished run must not be redone for that. `threads`: the
    member's threads (docs/threads.md), 1 so that the members fill the cores one each (and its
    cpu_seconds is one core's); the process's setting is restored afterwards."""
    from . import _core

    before = _core.threads()
    _core.set_threads(threads)
    try:
        return _run_member(base, member, out_dir, figures, animation, build, retry_failed)
    finally:
        _core.set_threads(before)


def _run_member(base: Scene, member: Member, out_dir, figures: bool, animation: bool, build: Optional[Callable],
                retry_failed: bool) -> Dict[str, Any]:
    from . import __version__
    from .run import run_scene

    scene = member.scene(base)
    mdir = Path(out_dir) / member.name
    old = read_outcome(mdir / OUTCOME_FILE)
    if old is not None and _same_scene(old, mdir, scene) and not (
            retry_failed and old.get("status") != "completed"):
        return old
    row: Dict[str, Any] = {"member": member.name, "seed": member.seed, "params": dict(member.params),
                           "status": "completed", "error": "", "scene_sha256": scene_digest(scene),
                           "vofdem_version": __version__, "host": socket.gethostname()}
    ck = _checkpoint_to_resume(mdir, scene)
    if ck is not None:
        row["resumed"] = True  # in the JSON only: continued from the checkpoint of a killed run
    cpu_before = 0.0 if ck is None else ck.cpu_seconds
    wall0, cpu0 = _time.perf_counter(), _time.process_time()
    try:
        res = run_scene(scene, mdir, progress=False, figures=figures, animation=animation, build=build,
                        log=lambda *a, **k: None, resume=ck is not None)
        row.update(_event_columns(res.analysis, scene))
        row["steps"], row["stones_hash"] = res.steps, _stones_hash(res.h5_path)
        row["step_limits"] = res.step_limits  # in the JSON only: which limit bound the member's steps
    except Exception as e:  # noqa: BLE001 - a failing member is an outcome; the others go on
        row.update(status="failed", error=f"{type(e).__name__}: {e}")
    # the CPU time of the member's process: the cost of a member on a loaded machine (one thread, run_member)
    row["wall_seconds"] = _time.perf_counter() - wall0 + (0.0 if ck is None else ck.wall_seconds)
    # a checkpoint written before it kept the process time: the killed runs' CPU is unknown
    row["cpu_seconds"] = None if cpu_before is None else _time.process_time() - cpu0 + cpu_before
    _write_atomic(mdir / OUTCOME_FILE, json.dumps(row, indent=1) + "\n")
    return row


def _checkpoint_to_resume(member_dir: Path, scene: Scene):
    """The checkpoint of a killed run of `scene` in `member_dir` (a member whose worker or machine died
    before it finished: its run.h5 still 'running', or 'interrupted'), or None: no checkpoint, one that
    cannot be read or is of another scene, or a run that ended (completed without its outcome written,
    or failed): that one runs again from the start."""
    from .checkpoint import CHECKPOINT_NAME, load_checkpoint
    from .io import RunData

    try:
        ck = load_checkpoint(member_dir / CHECKPOINT_NAME)
        status = RunData(member_dir / "run.h5").attrs.get("status")
    except (ValueError, OSError):
        return None
    return ck if ck.scene_toml == scene.to_toml() and status in ("running", "interrupted") else None


def read_outcome(path: Path) -> Optional[Dict[str, Any]]:
    """A member's outcome, or None if it has none (not finished) or it cannot be read."""
    try:
        return json.loads(Path(path).read_text(encoding="utf-8"))
    except (OSError, ValueError):
        return None


def lost_outcome(member: Member, error: BaseException) -> Dict[str, Any]:
    """The outcome of a member whose task did not return (its worker died): kept in the summary, not
    on disk, so the next call runs it again."""
    return {"member": member.name, "seed": member.seed, "params": dict(member.params), "status": "lost",
            "error": f"{type(error).__name__}: {error}"}


def outcomes_frame(rows: Sequence[Dict[str, Any]], param_keys: Sequence[str] = ()):
    """A pandas DataFrame of outcomes: member, seed, the parameters, then OUTCOME_COLUMNS."""
    import pandas as pd

    keys = list(param_keys) or sorted({k for r in rows for k in r.get("params", {})})
    recs = [{"member": r["member"], "seed": r["seed"], **{k: r.get("params", {}).get(k) for k in keys},
             **{c: r.get(c) for c in OUTCOME_COLUMNS}} for r in rows]
    df = pd.DataFrame.from_records(recs, columns=["member", "seed", *keys, *OUTCOME_COLUMNS])
    floats = [c for c in OUTCOME_COLUMNS if c.endswith(("_lps", "_mm", "_seconds"))]
    df[floats] = df[floats].astype(float)
    for c in ("stage1_stones", "stage2_stones", "stage3_stones", "stages", "removed", "stones", "steps"):
        df[c] = df[c].astype("Int64")
    df["error"] = df["error"].fillna("").astype(str)
    return df


def finished_outcomes(scene: Scene, seeds: Sequence[int], out_dir, vary=None):
    """The outcome table (as run_ensemble's) of an ensemble as far as it ran in `out_dir`, running none:
    a member not finished there is a row of status 'not run'."""
    members = plan_members(scene, seeds, vary)
    _, done = _check_existing(scene, members, Path(out_dir).resolve(), False)
    rows = [done.get(m.name) or {"member": m.name, "seed": m.seed, "params": dict(m.params), "status": "not run"}
            for m in members]
    return outcomes_frame(rows, [k for k, _ in members[0].params])


def collect_outcomes(out_dir) -> List[Dict[str, Any]]:
    """Every finished member's outcome found under `out_dir`, by parameter combination and seed."""
    rows = [read_outcome(p) for p in Path(out_dir).glob(f"**/{OUTCOME_FILE}")]
    return sorted((r for r in rows if r is not None), key=lambda r: (r["member"].rpartition("/")[0], r["seed"]))


def _same_scene(row: Dict[str, Any], member_dir: Path, scene: Scene) -> bool:
    """Whether the member in `member_dir` ran `scene`: the same digest, or, when the digest differs, its
    scene.toml read with this version's defaults equals `scene` (a version that added keys with their
    defaults writes a different file for the same scene)."""
    if row.get("scene_sha256") == scene_digest(scene):
        return True
    path = member_dir / "scene.toml"
    if not path.exists():
        return False
    try:
        return scene_digest(load_scene(path)) == scene_digest(scene)
    except ValueError:
        return False


def _check_existing(base: Scene, members: Sequence[Member], out: Path, retry_failed: bool):
    """(members to run, outcomes already there). A member directory holding a run of another scene
    is an error: its results are kept, not overwritten."""
    todo, done = [], {}
    for m in members:
        row = read_outcome(out / m.name / OUTCOME_FILE)
        if row is not None and not _same_scene(row, out / m.name, m.scene(base)):
            raise ValueError(f"{out / m.name} holds a run of another scene (its scene differs from this "
                             f"ensemble's); choose another output directory or remove it")
        if row is None or (retry_failed and row.get("status") != "completed"):
            todo.append(m)
        else:
            done[m.name] = row
    return todo, done


def run_ensemble(scene: Scene, seeds: Sequence[int], out_dir, client=None, vary=None, workers: Optional[int] = None,
                 scheduler: Optional[str] = None, figures: bool = False, animation: bool = False,
                 build: Optional[Callable] = None, progress: bool = True, retry_failed: bool = False,
                 dashboard: bool = True, n_boot: int = 1000, boot_seed: int = 0, log=print):
    """Runs the ensemble of `scene` over `seeds` and the `vary` combinations (see `plan_members`) and
    returns a pandas DataFrame of outcomes, one row per member (see OUTCOME_COLUMNS).

    Where: `client` (a distributed.Client), else `scheduler` (an address or scheduler file), else a
    LocalCluster of `workers` single-threaded processes (default one per core); ``workers=0`` runs the
    members one after the other in this process, without Dask. `build` (scene -> simulation, for
    tests) must be importable by the workers. Finished members in `out_dir` are not run again."""
    from .cluster import dashboard_link, ensemble_client
    from .fragility import write_fragility

    if workers is not None and (not isinstance(workers, int) or isinstance(workers, bool) or workers < 0):
        raise ValueError(f"workers = {workers!r} is outside the allowed range [0, ...] (0: no Dask)")
    members = plan_members(scene, seeds, vary)
    keys = [k for k, _ in members[0].params]
    out = Path(out_dir).resolve()
    out.mkdir(parents=True, exist_ok=True)
    todo, done = _check_existing(scene, members, out, retry_failed)
    rows: Dict[str, Dict[str, Any]] = dict(done)
    summary = _Summary(out, members, keys, rows)
    summary.write()
    log(f"vofdem: ensemble of {len(members)} members ({len(done)} already finished in {out})")
    opts = dict(figures=figures, animation=animation, build=build, retry_failed=retry_failed)
    bar = _Progress(len(members), len(done), progress)
    local = client is None and scheduler is None
    try:
        if todo and local and workers == 0:
            for m in todo:
                bar.update(running=1)
                summary.add(run_member(scene, m, out, **opts), bar)
        elif todo:
            with ensemble_client(client, scheduler, workers, dashboard) as c:
                link = dashboard_link(c, local=local)
                if link:
                    log(f"vofdem: Dask dashboard at {link}")
                elif dashboard and local:
                    log("vofdem: no Dask dashboard (it needs bokeh: pip install bokeh)")
                _run_on_dask(c, scene, todo, out, opts, summary, bar)
    finally:
        bar.close()
        summary.write()
    frame = summary.frame()
    frag_md = write_fragility(out, frame, keys, n_boot=n_boot, seed=boot_seed, reference=scene.reference)
    _write_atomic(out / "ensemble.md", members_markdown(frame, len(members), frag_md))
    if scene.hydrograph.stops_at_first_stage and (frame["status"] == "completed").any():
        from .reports import ensemble_until_failure_markdown

        widths = {m.combination: m.scene(scene).flume.width for m in members}
        _write_atomic(out / "until_failure.md", ensemble_until_failure_markdown(frame, widths, n_boot, boot_seed))
    return frame


def summarise(out_dir, n_boot: int = 1000, boot_seed: int = 0) -> str:
    """Rewrites the summary and the fragility of an ensemble directory from its members' outcome
    files (e.g. of an interrupted ensemble); returns the markdown of the fragility tables."""
    from .fragility import write_fragility

    out = Path(out_dir)
    rows = collect_outcomes(out)
    if not rows:
        raise ValueError(f"{out} holds no finished member ({OUTCOME_FILE} files)")
    keys = list(dict.fromkeys(k for r in rows for k in r.get("params", {})))
    frame = outcomes_frame(rows, keys)
    _write_atomic(out / "ensemble.csv", frame.to_csv(index=False, lineterminator="\n"))
    frag_md = write_fragility(out, frame, keys, n_boot=n_boot, seed=boot_seed, reference=_member_reference(out, rows))
    _write_atomic(out / "ensemble.md", members_markdown(frame, None, frag_md))
    return frag_md


def _member_reference(out: Path, rows):
    """The reference data of an ensemble's scene, read from its first member's scene.toml (None if none)."""
    for r in rows:
        path = out / r["member"] / "scene.toml"
        if path.is_file():
            return load_scene(path).reference
    return None


def _run_on_dask(client, scene: Scene, todo: Sequence[Member], out: Path, opts, summary, bar) -> None:
    """Submits every member and records each as it ends; cancels what is left if interrupted."""
    from .cluster import running_count

    futures = {client.submit(run_member, scene, m, str(out), **opts, pure=False,
                             key=f"vofdem-member-{i}-{os.urandom(4).hex()}"): m for i, m in enumerate(todo)}
    keys = {f.key for f in futures}
    polled = 0.0
    try:
        while futures:
            ended = [(f, row) for f in list(futures) if (row := _ended(f, futures[f], out)) is not None]
            for f, row in ended:
                del futures[f]
                f.release()  # a result left on a worker would be recomputed if that worker died
                summary.add(row, bar)
            if _time.monotonic() - polled > 1.0:
                bar.update(running=running_count(client, keys))
                polled = _time.monotonic()
            if not ended:
                _time.sleep(0.2)
    finally:
        if futures:
            client.cancel(list(futures))


def _ended(future, member: Member, out: Path) -> Optional[Dict[str, Any]]:
    """The outcome of a member's task if it has ended, else None. A result lost with its worker is
    computed again by Dask unless the member's outcome file already says how it ended."""
    status = future.status
    if status == "finished":
        return future.result()
    if status in ("error", "cancelled"):
        return lost_outcome(member, future.exception() if status == "error" else RuntimeError("cancelled"))
    if status == "lost":
        return read_outcome(out / member.name / OUTCOME_FILE)
    return None


class _Summary:
    """ensemble.csv and ensemble.md, rewritten (atomically) after every member."""

    def __init__(self, out: Path, members: Sequence[Member], keys: Sequence[str], rows: Dict[str, Dict]):
        self.out, self.members, self.keys, self.rows = out, members, list(keys), rows

    def add(self, row: Dict[str, Any], bar) -> None:
        self.rows[row["member"]] = row
        bar.finished(row["status"])
        self.write()

    def frame(self):
        return outcomes_frame([self.rows[m.name] for m in self.members if m.name in self.rows], self.keys)

    def write(self) -> None:
        df = self.frame()
        _write_atomic(self.out / "ensemble.csv", df.to_csv(index=False, lineterminator="\n"))
        _write_atomic(self.out / "ensemble.md", members_markdown(df, len(self.members)))


def _cell(v, fmt: str = "{:.2f}") -> str:
    return "-" if _missing(v) else fmt.format(v)


def members_markdown(df, n_planned: Optional[int] = None, fragility_md: str = "") -> str:
    """The ensemble's summary: counts, the fragility tables when given, one row per member."""
    n = len(df)
    counts = df["status"].value_counts().to_dict()
    head = [f"# Ensemble: {n} of {n_planned if n_planned is not None else n} members finished "
            f"({counts.get('completed', 0)} completed, {counts.get('failed', 0)} failed, "
            f"{counts.get('lost', 0)} lost)", ""]
    if fragility_md:
        head += [fragility_md, ""]
    rows = ["| member | status | first removal [l/s] | stage 1 [l/s]: stones | stage 2 | stage 3 | removed | "
            "crest lowering [mm] | wall [s] |", "|---|---|---|---|---|---|---|---|---|"]
    for r in df.itertuples(index=False):
        st = [f"{_cell(getattr(r, f'stage{k}_lps'))}: {_cell(getattr(r, f'stage{k}_stones'), '{}')}"
              if not _missing(getattr(r, f"stage{k}_lps")) else "-" for k in (1, 2, 3)]
        status = r.status if not r.error else f"{r.status}: {r.error}".replace("|", "/").replace("\n", " ")
        rows.append(f"| {r.member} | {status} | {_cell(r.first_removal_lps)} | {' | '.join(st)} | "
                    f"{_cell(r.removed, '{}')} of {_cell(r.stones, '{}')} | {_cell(r.crest_lowering_mm, '{:.1f}')} | "
                    f"{_cell(r.wall_seconds, '{:.1f}')} |")
    return "\n".join(head + rows) + "\n"


def _missing(v) -> bool:
    import pandas as pd

    return v is None or bool(pd.isna(v))


class _Progress:
    """One bar over members: finished of all, with running and failed counts and the time left."""

    def __init__(self, total: int, already: int, enabled: bool):
        self.counts = {"running": 0, "failed": 0, "lost": 0}
        self.text = ""
        self.bar = None
        if enabled:
            from tqdm.auto import tqdm

            self.bar = tqdm(total=total, initial=already, unit="member", dynamic_ncols=True,
                            desc="ensemble", smoothing=0.1)

    def finished(self, status: str) -> None:
        if status in self.counts:
            self.counts[status] += 1
        if self.bar is not None:
            self.bar.update(1)
        self.update()

    def update(self, running: Optional[int] = None) -> None:
        if running is not None:
            self.counts["running"] = running
        c = self.counts
        text = f"running {c['running']}, failed {c['failed'] + c['lost']}"
        if self.bar is not None and text != self.text:  # redraw on a change only (logs stay short)
            self.text = text
            self.bar.set_postfix_str(text, refresh=True)

    def close(self) -> None:
        if self.bar is not None:
            self.bar.close()
