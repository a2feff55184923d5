"""What `make demo` costs once vofdem is installed: its runs timed on a fresh copy of the repository.

The commands are read from the Makefile's `demo` recipe (the `vofdem run` lines, with $(PY) this Python
and $(OUT) a folder of the copy), so that they are written once; the install step before them is left
out (it builds the C++ library once per machine). Each command runs in a child process; its CPU time is
the children's user + system time (resource.getrusage, the Dask workers included, as they are the
children's children waited for), its wall time time.perf_counter's. Also checks that the demo ends with
the fragility figure it announces. Writes benchmarks/results/demo_time.md.

    python3 benchmarks/demo_time.py [--copy DIR] [--out FILE]
"""
import argparse
import os
import platform
import resource
import shlex
import subprocess
import sys
import tempfile
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
RESULTS = Path(__file__).resolve().parent / "results" / "demo_time.md"


def demo_commands(makefile: Path, py: str, out: str):
    """The `$(PY) -m vofdem run ...` lines of the Makefile's demo recipe, as argument lists."""
    lines, inside = [], False
    for line in makefile.read_text(encoding="utf-8").splitlines():
        if line.startswith("demo:"):
            inside = True
            continue
        if inside and not line.startswith("\t"):
            break
        if inside and "-m vofdem run" in line:
            lines.append(shlex.split(line.strip().replace("$(PY)", py).replace("$(OUT)", out)))
    if not lines:
        raise ValueError(f"no 'vofdem run' line in the demo recipe of {makefile}")
    return lines


def children_cpu():
    r = resource.getrusage(resource.RUSAGE_CHILDREN)
    return r.ru_utime + r.ru_stime


def timed(cmd, cwd):
    """(CPU seconds, wall seconds) of one command run to its end in cwd; raises if it fails."""
    c0, w0 = children_cpu(), time.perf_counter()
    subprocess.run(cmd, cwd=cwd, check=True, stdout=subprocess.DEVNULL)
    return children_cpu() - c0, time.perf_counter() - w0


def table(rows, figure_ok, copy_note):
    out = ["# `make demo`: its time after the install", "",
           f"Written by benchmarks/demo_time.py on {platform.machine()}, {os.cpu_count()} cores (shared with other",
           "work while it ran: the wall time is this run's, not the machine's best), Python "
           f"{platform.python_version()}. {copy_note}", "",
           "| command | CPU s | wall s |", "|---|---|---|"]
    for cmd, cpu, wall in rows:
        shown = " ".join(cmd[1:]).replace("|", "/")
        out.append(f"| `python {shown}` | {cpu:.1f} | {wall:.1f} |")
    cpu_total, wall_total = sum(r[1] for r in rows), sum(r[2] for r in rows)
    out += [f"| total | {cpu_total:.1f} | {wall_total:.1f} |", "",
            f"The demo ends with the fragility figure: {'yes' if figure_ok else 'NO'} "
            "(fragility.png of the ensemble over packings).", ""]
    return "\n".join(out), cpu_total, wall_total


def main(argv=None):
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--copy", type=Path, default=None, help="where to clone the repository (default: a temporary folder)")
    p.add_argument("--out", type=Path, default=RESULTS)
    args = p.parse_args(argv)
    with tempfile.TemporaryDirectory() as tmp:
        copy = args.copy or Path(tmp) / "vofdem"
        subprocess.run(["git", "clone", "--quiet", str(ROOT), str(copy)], check=True)
        cmds = demo_commands(copy / "Makefile", sys.executable, "out")
        rows = [(cmd, *timed(cmd, copy)) for cmd in cmds]
        figure_ok = (copy / "out" / "maeno2008_quick_fragility" / "fragility.png").is_file()
        text, cpu, wall = table(rows, figure_ok, "The commands ran in a fresh clone of the repository.")
    args.out.write_text(text, encoding="utf-8")
    print(text)
    return 0 if figure_ok else 1


if __name__ == "__main__":
    sys.exit(main())
