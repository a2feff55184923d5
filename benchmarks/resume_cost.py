"""What resuming a killed ensemble member costs when it packs its weir again and when it takes its stones
from its checkpoint.

A member of a scene (an ensemble of one seed, members in the process: `vofdem run SCENE --seeds N --workers
0`) is killed (SIGKILL) once --kill-at snapshots of its run.h5 are complete; its directory is copied twice
and the same command resumes each copy in a child process (one core): 'checkpoint', as the checkpoint is
(the stones built from its state, builder.resumed_from), and 'packed', with the checkpoint's disc porosity
removed, as in a checkpoint written before it was kept: that resume builds the scene in full, packing the
weir, as every resume did before. Per resume: the child's CPU (process time, os.wait4) and wall time, and
whether the two resumed run.h5 hold the same datasets bit for bit (the stage profile aside). The machine may
be shared: CPU times are the children's own.

    OMP_NUM_THREADS=1 PYTHONPATH=python python3 benchmarks/resume_cost.py [--scene maeno2008] [--quick] \
        [--end-time 8] [--kill-at 9] [--seed 0] [--out FILE]

Writes benchmarks/results/resume_cost_<scene>[_quick].md.
"""
import argparse
import os
import platform
import shutil
import signal
import subprocess
import sys
import tempfile
import time
from pathlib import Path

os.environ.setdefault("OMP_NUM_THREADS", "1")
ROOT = Path(__file__).resolve().parents[1]

import h5py  # noqa: E402
import numpy as np  # noqa: E402

from vofdem.io import snapshots_written  # noqa: E402
from vofdem.study import shown_path, write_page  # noqa: E402


def command(args, out: Path) -> list:
    """The member's ensemble command (run again, it resumes the member)."""
    cmd = [sys.executable, "-m", "vofdem", "run", args.scene, "--seeds", str(args.seed), "--workers", "0",
           "--no-figures", "--no-animation", "--no-progress", "--out", str(out)]
    return cmd + (["--quick"] if args.quick else []) + (["--end-time", f"{args.end_time:g}"] if args.end_time else [])


def kill_at(cmd: list, member: Path, k: int) -> float:
    """Runs `cmd` and SIGKILLs it once k snapshots of the member's run.h5 are complete; its CPU [s]."""
    p = subprocess.Popen(cmd, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    while snapshots_written(member / "run.h5") < k and p.poll() is None:
        time.sleep(0.01)
    if p.poll() is not None:
        raise RuntimeError(f"the member ended before {k} snapshots: lower --kill-at")
    p.send_signal(signal.SIGKILL)
    cpu, p.returncode = waited(p.pid)  # reaped here: Popen must not wait for it again
    return cpu


def waited(pid: int) -> tuple:
    """(process time [s], user + system; exit code) of the child once it ended."""
    _, status, ru = os.wait4(pid, 0)
    return ru.ru_utime + ru.ru_stime, os.waitstatus_to_exitcode(status)


def resume(cmd: list, log: Path) -> tuple:
    """(CPU [s], wall [s]) of the member's command run again (it resumes the member); its stderr in `log`."""
    t0 = time.perf_counter()
    with open(log, "w") as err:
        p = subprocess.Popen(cmd, stdout=subprocess.DEVNULL, stderr=err)
        cpu, p.returncode = waited(p.pid)  # reaped here: Popen must not wait for it again
    if p.returncode != 0:
        raise RuntimeError(f"{' '.join(cmd)} exited with {p.returncode}: {log.read_text()}")
    return cpu, time.perf_counter() - t0


def datasets(path: Path) -> dict:
    out = {}
    with h5py.File(path, "r") as f:
        f.visititems(lambda n, o: out.__setitem__(n, o[()]) if isinstance(o, h5py.Dataset) else None)
    return out


def same_bits(a: Path, b: Path) -> bool:
    """Whether two run.h5 hold the same datasets bit for bit, the stage profile aside."""
    da, db = datasets(a), datasets(b)
    return da.keys() == db.keys() and all(np.array_equal(da[n], db[n], equal_nan=True)
                                          for n in da if not n.startswith("profile/"))


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--scene", default="maeno2008", help="a scene name or TOML file")
    ap.add_argument("--quick", action="store_true", help="the scene's quick variant")
    ap.add_argument("--end-time", type=float, default=8.0, help="the member's end [s] (0: the scene's)")
    ap.add_argument("--kill-at", type=int, default=9, help="kill the member after this many snapshots")
    ap.add_argument("--seed", type=int, default=0)
    ap.add_argument("--out", type=Path, default=None)
    args = ap.parse_args(argv)
    if args.kill_at < 2:
        raise ValueError(f"--kill-at = {args.kill_at} is out of range (allowed: >= 2 snapshots)")
    name = Path(args.scene).stem + ("_quick" if args.quick else "")
    out = args.out or ROOT / "benchmarks" / "results" / f"resume_cost_{name}.md"
    load0 = os.getloadavg()[0]
    rows = {}
    with tempfile.TemporaryDirectory() as tmp:
        killed = Path(tmp) / "killed"
        member = f"seed{args.seed}"
        cpu_killed = kill_at(command(args, killed), killed / member, args.kill_at)
        with h5py.File(killed / member / "checkpoint.h5", "r") as f:
            at = int(f.attrs["snapshots"])
        for label in ("packed", "checkpoint"):
            shutil.copytree(killed, Path(tmp) / label)
        with h5py.File(Path(tmp) / "packed" / member / "checkpoint.h5", "a") as f:
            del f.attrs["disc_porosity"]
        for label in ("packed", "checkpoint"):
            rows[label] = resume(command(args, Path(tmp) / label), Path(tmp) / f"{label}.err")
            print(f"{label}: {rows[label][0]:.1f} s CPU, {rows[label][1]:.1f} s wall", flush=True)
        with h5py.File(Path(tmp) / "checkpoint" / member / "run.h5", "r") as f:
            total = int(f["time"].shape[0])
        same = same_bits(Path(tmp) / "packed" / member / "run.h5", Path(tmp) / "checkpoint" / member / "run.h5")
    (cp, wp), (cc, wc) = rows["packed"], rows["checkpoint"]
    text = [f"# Resuming a killed member of `{shown_path(args.scene, ROOT)}`{' (quick)' if args.quick else ''}", "",
            f"`benchmarks/resume_cost.py --scene {shown_path(args.scene, ROOT)}{' --quick' if args.quick else ''} "
            f"--end-time {args.end_time:g} --kill-at {args.kill_at} --seed {args.seed}`, "
            f"{time.strftime('%Y-%m-%d %H:%M UTC', time.gmtime())}, {platform.processor() or platform.machine()}, "
            f"one core per child (OMP_NUM_THREADS=1), on a shared machine (load average {load0:.2f} at the start, "
            f"{os.getloadavg()[0]:.2f} at the end). CPU is the child's process time.", "",
            f"The member ran {cpu_killed:.1f} CPU-s before it was killed after {args.kill_at} snapshots; its "
            f"checkpoint holds {at} of its {total} snapshots. The same command then resumed two copies of it:", "",
            "| resume | stones | CPU [s] | wall [s] |", "|---|---|---|---|",
            f"| packed | the weir packed again (the build in full), then the checkpoint's state imported | {cp:.1f} | {wp:.1f} |",
            f"| checkpoint | built from the checkpoint's state (builder.resumed_from) | {cc:.1f} | {wc:.1f} |", "",
            f"Saved: {cp - cc:.1f} CPU-s ({100 * (cp - cc) / cp:.0f} % of the packed resume). The two resumed "
            f"run.h5 hold {'the same' if same else 'DIFFERENT'} datasets bit for bit (the stage profile aside).", ""]
    return write_page(out, text)


if __name__ == "__main__":
    main()
