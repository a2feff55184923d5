"""Cost of the output that survives a SIGKILL, per snapshot, against the writer it replaced.

The paper's grid (147 x 46 cells) and weir (80 stones), the whole scenario's 281 snapshots. Measured
in one process, the two writers alternated snapshot by snapshot so that both see the same machine load:
- 'kill-safe': vofdem.io.RunWriter (the oldest HDF5 format, datasets made at full size, the file
  reopened once made, raw writes and two flushes per snapshot, the XDMF 3 files rewritten every
  XDMF_SECONDS of wall time: here, snapshots back to back, fewer rewrites than in a run);
- 'kill-safe, XDMF each snapshot': the same with xdmf_seconds = 0;
- 'SWMR': the earlier writer (libver 'latest', SWMR mode, chunked gzip datasets resized per snapshot,
  one flush, XDMF rewritten), which readers of HDF5 1.10 and plain h5py refuse after a kill.
Also: making the file (its virtual datasets), closing it (the copy that replaces it), and a checkpoint
(sim.export_state() and checkpoint.py's write, timed after every snapshot; runs write one every
30 s of wall time). The solver's own cost
per snapshot on this grid is the whole scenario's CPU in benchmarks/results/maeno2008_before_after.md
(35.2 s for 281).
Writes benchmarks/results/output_cost.md.

    PYTHONPATH=python python3 benchmarks/output_cost.py
"""
import os
import tempfile
import time
from pathlib import Path

import h5py
import numpy as np

from vofdem.builder import build_simulation
from vofdem.checkpoint import Checkpoint, save_checkpoint
from vofdem.io import FIELD_NAMES, STONE_VECTORS, RunWriter, cell_velocities, xdmf_document, xdmf_step
from vofdem.scene import Scene

OUT = Path(__file__).resolve().parent / "results" / "output_cost.md"
SOLVER_SECONDS_PER_SNAPSHOT = 35.2 / 281  # the whole scenario on one core (README)


class SwmrWriter:
    """The replaced design, kept here only to measure against."""

    def __init__(self, path, nx, nz, n):
        self.nx, self.nz, self.n, self.k = nx, nz, n, 0
        f = self.f = h5py.File(path, "w", libver="latest")
        f.create_dataset("time", (0,), maxshape=(None,), dtype="f8", chunks=(256,))
        for name in FIELD_NAMES:
            f.create_dataset(f"fields/{name}", (0, nz, nx), maxshape=(None, nz, nx), dtype="f4",
                             chunks=(1, nz, nx), compression="gzip", compression_opts=1)
        for name in STONE_VECTORS:
            f.create_dataset(f"stones/{name}", (0, n, 2), maxshape=(None, n, 2), dtype="f8", chunks=(16, n, 2))
        f.swmr_mode = True
        self.steps = []
        self.xmf = Path(path).with_suffix(".xmf")

    def write(self, t, fields, stones):
        f, k = self.f, self.k
        f["time"].resize((k + 1,))
        f["time"][k] = t
        for name in FIELD_NAMES:
            f[f"fields/{name}"].resize((k + 1, self.nz, self.nx))
            f[f"fields/{name}"][k] = fields[name]
        for name in STONE_VECTORS:
            f[f"stones/{name}"].resize((k + 1, self.n, 2))
            f[f"stones/{name}"][k] = stones[name]
        f.flush()
        self.k += 1
        self.steps.append(xdmf_step("run.h5", k, t, self.nx, self.nz, self.n))
        self.xmf.write_text(xdmf_document([("stones", [s for _, s in self.steps]),
                                           ("fields", [g for g, _ in self.steps])]))


def snapshot_values(sim, nx, nz):
    """The fields and stones of the simulation now, as the run loop records them."""
    fl, st = sim.fluid, sim.stones
    u, w = cell_velocities(fl.face_u, fl.face_w, nx, nz)
    fields = {"F": fl.cell_F, "p": fl.cell_p, "porosity": fl.cell_porosity, "u": u, "w": w}
    fields = {k: np.asarray(v).reshape(nz, nx) for k, v in fields.items()}
    stones = {"pos": st.stone_pos, "vel": st.stone_vel, "force_drag": sim.stone_force_drag,
              "force_pressure": sim.stone_force_pressure}
    stones = {k: np.asarray(v).reshape(-1, 2) for k, v in stones.items()}
    stones["active"] = np.asarray(st.stone_active).astype(bool)
    return fields, stones


def main():
    scene = Scene.maeno2008()
    sim = build_simulation(scene)
    sim.advance(1.0)  # fields with flow in them (gzip compresses still water too well)
    g = sim.fluid.grid
    nx, nz, n = g.nx, g.nz, sim.stones.stone_pos.shape[0]
    T = 281
    x = g.x0 + g.dx * np.arange(nx + 1)
    fields, stones = snapshot_values(sim, nx, nz)
    with tempfile.TemporaryDirectory() as tmp:
        tmp = Path(tmp)
        t0 = time.perf_counter()
        new = RunWriter(tmp / "a" / "run.h5", x, np.asarray(g.z_faces), np.full(n, 0.048), np.zeros(n, bool),
                        capacity=T)
        make = time.perf_counter() - t0
        every = RunWriter(tmp / "c" / "run.h5", x, np.asarray(g.z_faces), np.full(n, 0.048), np.zeros(n, bool),
                          capacity=T, xdmf_seconds=0.0)
        (tmp / "b").mkdir()
        old = SwmrWriter(tmp / "b" / "run.h5", nx, nz, n)
        cost = {"kill-safe": [], "kill-safe, XDMF each snapshot": [], "SWMR": [], "checkpoint": []}
        for k in range(T):
            t0 = time.perf_counter()
            every.write_snapshot(0.5 * k, 0.01, 0.3, fields, stones)
            cost["kill-safe, XDMF each snapshot"].append(time.perf_counter() - t0)
            t0 = time.perf_counter()
            new.write_snapshot(0.5 * k, 0.01, 0.3, fields, stones)
            t1 = time.perf_counter()
            old.write(0.5 * k, fields, stones)
            t2 = time.perf_counter()
            state = dict(sim.export_state())  # as the run loop does: the state copied out, then written
            save_checkpoint(tmp / "a" / "checkpoint.h5", Checkpoint(state, k + 1, [0.5] * T, False, "", {}, 0.0))
            t3 = time.perf_counter()
            cost["kill-safe"].append(t1 - t0)
            cost["SWMR"].append(t2 - t1)
            cost["checkpoint"].append(t3 - t2)
        old.f.close()
        every.close("completed")
        t0 = time.perf_counter()
        new.close("completed")
        close = time.perf_counter() - t0
        size_new = os.path.getsize(tmp / "a" / "run.h5")
        size_old = os.path.getsize(tmp / "b" / "run.h5")
        size_ck = os.path.getsize(tmp / "a" / "checkpoint.h5")
    rows = [f"| per snapshot | mean ms | median ms | last 20 ms | share of the solver's "
            f"{1e3 * SOLVER_SECONDS_PER_SNAPSHOT:.0f} ms (quiet core) |",
            "|---|---|---|---|---|"]
    for name, c in cost.items():
        c = 1e3 * np.asarray(c)
        rows.append(f"| {name} | {c.mean():.2f} | {np.median(c):.2f} | {c[-20:].mean():.2f} | "
                    f"{c.mean() / (1e3 * SOLVER_SECONDS_PER_SNAPSHOT):.2%} |")
    text = (f"# Output cost per snapshot ({nx} x {nz} cells, {n} stones, {T} snapshots)\n\n"
            f"Written by `benchmarks/output_cost.py` (one process, the writers alternated).\n\n" + "\n".join(rows)
            + f"\n\nMaking the kill-safe file ({T} snapshots, {T * 10} virtual datasets): {1e3 * make:.0f} ms; "
            f"closing it (the copy that replaces it): {1e3 * close:.0f} ms.\n"
            f"File sizes: kill-safe {size_new / 1e6:.1f} MB (contiguous float32 fields), SWMR {size_old / 1e6:.1f} MB "
            f"(gzip level 1); one checkpoint {size_ck / 1e6:.2f} MB.\n"
            f"Kill-safe / SWMR per snapshot: {np.mean(cost['kill-safe']) / np.mean(cost['SWMR']):.2f}.\n")
    OUT.write_text(text, encoding="utf-8")
    print(text)


if __name__ == "__main__":
    main()
