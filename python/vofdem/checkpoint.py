"""Checkpoints of a run, so that ``vofdem run --resume DIR`` continues a killed run bit for bit.

A checkpoint is ``DIR/checkpoint.h5``: the coupled simulation's whole state (``sim.export_state()``: flow,
k-epsilon, stones, contact springs, coupler; its arrays of doubles end to end in /state/values, their names
and sizes in /state/keys and /state/sizes), the run loop's position (the snapshots written, the snapshot
times, whether the stones are still held), the cost so far (the stage profile, wall time) and the porosity
inside each stone the run was built with. It is written after the first and the last snapshot and after any
snapshot that comes at least ``CHECKPOINT_SECONDS`` of wall time after the last checkpoint
(``run_scene(checkpoint_seconds=...)``, ``vofdem run --checkpoint-seconds``; 0: after every snapshot), into
``checkpoint.h5.tmp`` that then replaces the old one (``os.replace``, atomic), so a kill at any moment leaves
one whole checkpoint. A resumed run rewrites the snapshots after the checkpoint's and ends with the same
``run.h5`` datasets as a run that was never stopped (the C++ state restarts bit for bit,
tests/test_resume.py).
"""
from __future__ import annotations

import os
from dataclasses import dataclass
from pathlib import Path
from typing import Dict, List, Optional, Tuple

import h5py
import numpy as np

from .io import HDF5_LIBVER, OutputError

CHECKPOINT_NAME = "checkpoint.h5"
# wall seconds between checkpoints: a kill loses at most this much of the run; after every snapshot the
# checkpoint cost 3 % of a weir run's CPU (4 ms per 0.5 s snapshot, benchmarks/output_cost.py)
CHECKPOINT_SECONDS = 30.0


@dataclass
class Checkpoint:
    """A run's state after `snapshots` snapshots: the solver's state, the snapshot times of the whole
    run (`targets`, after the first snapshot), whether the stones are held (`hold`), the scene (TOML),
    the profile so far {stage: (seconds, calls)}, the wall time so far [s], when water first reached
    the domain's top row [s] (None: not yet; the resumed run then warns no second time), the
    process (CPU) time so far [s] (None in checkpoints written before it was kept) and the porosity
    inside each stone of eq. (11) the run was built with [-] (the coupler's n_exp; with it a resumed run
    builds its stones from `state` instead of packing them, builder.resumed_from; None in checkpoints
    written before it was kept: the weir is packed again)."""

    state: Dict[str, np.ndarray]
    snapshots: int
    targets: List[float]
    hold: bool
    scene_toml: str
    profile: Dict[str, Tuple[float, int]]
    wall_seconds: float
    water_at_top_s: Optional[float] = None
    cpu_seconds: Optional[float] = None
    disc_porosity: Optional[float] = None


def save_checkpoint(path, ck: Checkpoint) -> None:
    """Writes `ck` to `path` atomically (write the .tmp, then rename); OutputError if that fails (the
    previous checkpoint is then kept)."""
    path = Path(path)
    tmp = path.with_name(path.name + ".tmp")
    try:
        with h5py.File(tmp, "w", libver=HDF5_LIBVER) as f:
            # one array of all the state's values (one dataset per key costs ten times as much)
            keys = sorted(ck.state)
            values = [np.asarray(ck.state[k], float).ravel() for k in keys]
            f["state/keys"] = np.array(keys, dtype=h5py.string_dtype())
            f["state/sizes"] = np.array([v.size for v in values], np.int64)
            f["state/values"] = np.concatenate(values) if values else np.zeros(0)
            f["targets"] = np.asarray(ck.targets, float)
            names = list(ck.profile)
            f["profile/names"] = np.array(names, dtype=h5py.string_dtype())
            f["profile/seconds"] = np.array([ck.profile[n][0] for n in names], float)
            f["profile/calls"] = np.array([ck.profile[n][1] for n in names], np.int64)
            f.attrs.update(snapshots=int(ck.snapshots), hold=bool(ck.hold), scene_toml=ck.scene_toml,
                           wall_seconds=float(ck.wall_seconds))
            for name in ("water_at_top_s", "cpu_seconds", "disc_porosity"):
                if getattr(ck, name) is not None:
                    f.attrs[name] = float(getattr(ck, name))
        os.replace(tmp, path)
    except OSError as e:
        tmp.unlink(missing_ok=True)
        raise OutputError(e.errno, f"writing the checkpoint '{path}' failed (the previous one is kept): {e}") from e


def _optional_float(v) -> Optional[float]:
    return None if v is None else float(v)


def load_checkpoint(path) -> Checkpoint:
    """Reads a checkpoint; ValueError naming the file if there is none or it cannot be read."""
    path = Path(path)
    if not path.is_file():
        raise ValueError(f"no checkpoint '{path}': the run cannot be resumed (was it started before "
                         f"checkpoints were written, or did it end?)")
    try:
        with h5py.File(path, "r") as f:
            keys = [k.decode() if isinstance(k, bytes) else str(k) for k in f["state/keys"][()]]
            parts = np.split(f["state/values"][()], np.cumsum(f["state/sizes"][()])[:-1]) if keys else []
            state: Dict[str, np.ndarray] = dict(zip(keys, parts))
            names = [s.decode() if isinstance(s, bytes) else str(s) for s in f["profile/names"][()]]
            profile = {n: (float(s), int(c)) for n, s, c in
                       zip(names, f["profile/seconds"][()], f["profile/calls"][()])}
            return Checkpoint(state, int(f.attrs["snapshots"]), f["targets"][()].tolist(), bool(f.attrs["hold"]),
                              str(f.attrs["scene_toml"]), profile, float(f.attrs["wall_seconds"]),
                              _optional_float(f.attrs.get("water_at_top_s")),
                              _optional_float(f.attrs.get("cpu_seconds")),
                              _optional_float(f.attrs.get("disc_porosity")))
    except (OSError, KeyError) as e:
        raise ValueError(f"checkpoint '{path}' cannot be read: {e}") from e
