"""vofdem against peer codes on the same 2D dam break (Martin & Moyce 1952), in one run.

Runs interFoam, interIsoFoam (OpenFOAM v1912) and gerris2D through the peer drivers in
../shared/peers (or $VOFDEM_PEERS), and vofdem, at the same resolutions (N cells per a), CFL 0.5,
no-slip walls, t_end 0.2 s; compares times and surge-front errors against Martin & Moyce's
measurements (simulated T used as it is, no +0.175 shift; the shifted error is listed too). vofdem's
pressure solve stops at the relative tolerance the scenes use, 1e-5 (--pressure-tolerance; the front
at T = 3 is the same as at 1e-8 to 4 digits at N = 16 and 32, the water volume drifts 3e-9 and 4e-10
over the run); interFoam's p_rgh stops at 1e-7 (normalised), relTol 0.05 but in the last corrector.

Every code runs as a whole process, timed from start to exit on both sides: a peer's wrapper (case
set-up, mesh, solver, sampling) and vofdem's (Python start-up, import, set-up, stepping, sampling:
this script run with --vofdem-run). Wall time and the CPU time of the process tree (getrusage of the
children) are recorded; the codes alternate (every code once per round, --repeats rounds) and each
figure is the median over the rounds. The solver's own time (peers: the solver process; vofdem: the
stepping) is listed too.

Python's bytecode is cached for every code's process, as Python does by default: a machine that sets
PYTHONDONTWRITEBYTECODE (the machines this project runs its benchmarks on do) would otherwise compile vofdem's modules and the
peers' Python drivers at every start. The caches go to the run's temporary directory
(PYTHONPYCACHEPREFIX), written by an untimed first run of each code at the smallest size.

Writes benchmarks/results/peer_dambreak.md and benchmarks/results/peer_dambreak.png.

    PYTHONPATH=python python3 benchmarks/peer_dambreak.py --sizes 16 32 [--repeats 3]
"""
from __future__ import annotations

import argparse
import csv
import os
import platform
import re
import resource
import subprocess
import sys
import tempfile
import time

import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
# the cases and their measured data live with the validation cases
sys.path.insert(0, os.path.join(HERE, "..", "validation"))
import vof_cases as val  # noqa: E402

sys.path.insert(0, HERE)
from peers import peers_dir  # noqa: E402

PEERS = str(peers_dir())
WRAPPERS = {"interFoam": "run_interfoam.sh", "interIsoFoam": "run_interisofoam.sh", "gerris2D": "run_gerris.sh"}


def read_peer_csv(path):
    meta, rows = {}, []
    with open(path) as f:
        lines = f.read().splitlines()
    body = []
    for line in lines:
        if line.startswith("#"):
            k, _, v = line[1:].partition(":")
            meta[k.strip()] = v.strip()
        else:
            body.append(line)
    for r in csv.DictReader(body):
        rows.append((float(r["T"]), float(r["Z"])))
    T, Z = np.array(rows).T
    return T, Z, meta


def timed_process(cmd, env):
    """Runs cmd to its exit: (completed process, wall s, CPU s of the process tree)."""
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    t0 = time.perf_counter()
    res = subprocess.run(cmd, env=env, capture_output=True, text=True)
    wall = time.perf_counter() - t0
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    cpu = (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime)
    if res.returncode != 0:
        raise RuntimeError("%s failed:\n%s\n%s" % (cmd, res.stdout[-2000:], res.stderr[-2000:]))
    return res, wall, cpu


def process_env(work, **extra):
    """The environment of every code's process: the caller's, with Python's bytecode cached under work."""
    env = dict(os.environ, PYTHONPYCACHEPREFIX=os.path.join(work, "pycache"), **extra)
    env.pop("PYTHONDONTWRITEBYTECODE", None)
    return env


def run_peer(peer, n, work, cfl):
    out = os.path.join(work, "%s_n%d.csv" % (peer, n))
    cmd = ["bash", os.path.join(PEERS, "dambreak", WRAPPERS[peer]), str(n), "--out", out,
           "--work", os.path.join(work, "cases"), "--cfl", str(cfl)]
    res, total, cpu = timed_process(cmd, process_env(work, PEERS_NO_RECORD="1"))
    line = [l for l in res.stdout.splitlines() if l.startswith("RESULT")][-1]
    wall = float(re.search(r"wall_solver_s=([0-9.]+)", line).group(1))
    steps = int(re.search(r"steps=([0-9]+)", line).group(1))
    T, Z, _ = read_peer_csv(out)
    return dict(code=peer, n=n, wall=wall, total=total, cpu=cpu, steps=steps, cells=8 * n * (5 * n // 2), T=T, Z=Z)


def run_vofdem(n, cfl, work, tol):
    """vofdem's whole process: this script with --vofdem-run (start-up, import, run, CSV)."""
    out = os.path.join(work, "vofdem_n%d_cfl%g.csv" % (n, cfl))
    cmd = [sys.executable, os.path.abspath(__file__), "--vofdem-run", str(n), str(cfl), out, str(tol)]
    res, total, cpu = timed_process(cmd, process_env(work, OMP_NUM_THREADS="1"))
    line = [l for l in res.stdout.splitlines() if l.startswith("RESULT")][-1]
    wall = float(re.search(r"wall_solver_s=([0-9.]+)", line).group(1))
    steps = int(re.search(r"steps=([0-9]+)", line).group(1))
    T, Z = np.loadtxt(out, delimiter=",", skiprows=1, unpack=True)
    return dict(code="vofdem (CFL %.1f)" % cfl, n=n, wall=wall, total=total, cpu=cpu, steps=steps,
                cells=8 * n * (5 * n // 2), T=T, Z=Z)


def vofdem_run(n, cfl, out, tol):
    """The vofdem side as one process: the dam break, its front as CSV, a RESULT line."""
    r = val.dam_break_front(n=int(n), cfl=float(cfl), pressure_tol=float(tol))
    np.savetxt(out, np.column_stack([r.T, r.Z]), delimiter=",", header="T,Z", comments="")
    print("RESULT vofdem n=%s wall_solver_s=%.4f steps=%d volume_drift=%.2e" % (n, r.wall_s, r.steps, r.volume_drift))


def median_run(rs):
    """The round whose whole-process wall time is the median, with the medians of the times."""
    by = sorted(rs, key=lambda r: r["total"])
    r = dict(by[len(by) // 2])
    for k in ("total", "cpu", "wall"):
        r[k] = float(np.median([x[k] for x in rs]))
    r["rounds"] = len(rs)
    return r


LOAD0 = os.getloadavg()[0]


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--sizes", type=int, nargs="+", default=[16])
    ap.add_argument("--peers", nargs="+", default=list(WRAPPERS))
    ap.add_argument("--cfl", type=float, default=0.5, help="CFL of every code (peers' default 0.5)")
    ap.add_argument("--extra-cfl", type=float, nargs="*", default=[0.2],
                    help="extra vofdem runs at these CFL numbers")
    ap.add_argument("--repeats", type=int, default=3, help="rounds; every code runs once per round")
    ap.add_argument("--out", default=os.path.join(HERE, "results", "peer_dambreak"))
    ap.add_argument("--pressure-tolerance", type=float, default=1e-5,
                    help="vofdem's relative pressure tolerance (default 1e-5, the scenes')")
    ap.add_argument("--vofdem-run", nargs=4, metavar=("N", "CFL", "CSV", "TOL"), help=argparse.SUPPRESS)
    args = ap.parse_args()
    if args.vofdem_run:
        return vofdem_run(*args.vofdem_run)

    runs = []
    with tempfile.TemporaryDirectory(prefix="vofdem_peers_") as work:
        # untimed: writes the bytecode caches of each code's Python modules
        for p in args.peers:
            run_peer(p, min(args.sizes), work, args.cfl)
        run_vofdem(min(args.sizes), args.cfl, work, args.pressure_tolerance)
        for n in args.sizes:
            jobs = [("peer", p) for p in args.peers] + [("vofdem", c) for c in [args.cfl] + list(args.extra_cfl)]
            results = {j: [] for j in jobs}
            for rnd in range(args.repeats):
                for kind, what in jobs:
                    print("round %d: %s N=%d ..." % (rnd + 1, what, n), flush=True)
                    r = (run_peer(what, n, work, args.cfl) if kind == "peer"
                         else run_vofdem(n, what, work, args.pressure_tolerance))
                    results[(kind, what)].append(r)
                    print("  process %.2f s wall, %.2f s CPU; solver %.2f s; %d steps" % (
                        r["total"], r["cpu"], r["wall"], r["steps"]), flush=True)
            runs += [median_run(results[j]) for j in jobs]

    for r in runs:
        r["err"] = val.front_error(r["T"], r["Z"])
        r["err_shift"] = val.front_error(r["T"], r["Z"], shift=val.MM_TIME_SHIFT)
        r["z3"] = float(np.interp(3.0, r["T"], r["Z"]))
        r["us_cell_step"] = r["cpu"] / (r["steps"] * r["cells"]) * 1e6

    os.makedirs(os.path.dirname(args.out), exist_ok=True)
    lines = [
        "# vofdem against peer codes: 2D dam break (Martin & Moyce 1952)",
        "",
        "Generated by `benchmarks/peer_dambreak.py` on %s (%s, %s), all codes serial on one core, in one run." % (
            time.strftime("%Y-%m-%d %H:%M UTC", time.gmtime()), platform.node(), platform.processor() or "cpu"),
        "Case: column a = 0.05715 m wide, 2a high, tank 8a x 2.5a, no-slip walls, open top, water/air "
        "(1000/1 kg/m^3), t_end = 0.2 s, CFL %.1f in every code unless stated; peers via their drivers in "
        "peers/dambreak (PEERS_NO_RECORD=1). Front: 0.5 crossing of the water fraction on the bottom row "
        "(the peers' definition); vofdem's pressure tolerance %g (relative). Times: the whole process of each code, start to exit (wall, and the CPU "
        "time of its process tree), median of %d alternating rounds after an untimed one (Python's bytecode cached); `solver s` is the solver alone "
        "(peers: the solver process; vofdem: the stepping); us/cell-step from the process CPU time. Load "
        "average at the start / end: %.1f / %.1f (2 cores, shared)." % (args.cfl, args.pressure_tolerance, args.repeats,
                                                               LOAD0, os.getloadavg()[0]),
        "Error: |Z_sim - Z_exp| at Martin & Moyce's 15 points (T = 0.41 ... 3.33), simulated T used as it "
        "is (no shift); the last column adds +0.175 to the simulated T.",
        "",
        "| N | code | cells | steps | process wall s | process CPU s | solver s | us/cell-step | Z(T=3) | RMS err | max err | mean (lead) | RMS err, +0.175 |",
        "|---|---|---|---|---|---|---|---|---|---|---|---|---|",
    ]
    for r in runs:
        lines.append("| %d | %s | %d | %d | %.2f | %.2f | %.2f | %.2f | %.3f | %.3f | %.3f | %+.3f | %.3f |" % (
            r["n"], r["code"], r["cells"], r["steps"], r["total"], r["cpu"], r["wall"], r["us_cell_step"], r["z3"],
            r["err"]["rms"], r["err"]["max"], r["err"]["mean"], r["err_shift"]["rms"]))
    lines += ["", "Ratios (peer / vofdem at the same CFL %.1f and N): whole-process wall and CPU time, and RMS "
              "front error vofdem / peer (below 1: vofdem closer to the measurements)." % args.cfl, "",
              "| N | peer | wall ratio peer/vofdem | CPU ratio peer/vofdem | error ratio vofdem/peer (no shift) | (+0.175) |",
              "|---|---|---|---|---|---|"]
    for n in args.sizes:
        v = [r for r in runs if r["n"] == n and r["code"] == "vofdem (CFL %.1f)" % args.cfl][0]
        for r in runs:
            if r["n"] == n and not r["code"].startswith("vofdem"):
                lines.append("| %d | %s | %.1f | %.1f | %.2f | %.2f |" % (
                    n, r["code"], r["total"] / v["total"], r["cpu"] / v["cpu"], v["err"]["rms"] / r["err"]["rms"],
                    v["err_shift"]["rms"] / r["err_shift"]["rms"]))
    with open(args.out + ".md", "w") as f:
        f.write("\n".join(lines) + "\n")
    print("\n".join(lines))

    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, axes = plt.subplots(1, len(args.sizes), figsize=(6 * len(args.sizes), 4.5), squeeze=False)
    for ax, n in zip(axes[0], args.sizes):
        for r in runs:
            if r["n"] == n:
                ax.plot(r["T"], r["Z"], "-" if not r["code"].startswith("vofdem") else "--", lw=1.6,
                        label="%s (%.1f s CPU)" % (r["code"], r["cpu"]))
        ax.plot(val.MM_T, val.MM_Z, "ko", label="Martin & Moyce (1952)")
        ax.set_xlim(0, 3.8)
        ax.set_ylim(1, 5)
        ax.set_xlabel("T = t sqrt(2g/a)  (no shift)")
        ax.set_ylabel("Z = x_front / a")
        ax.set_title("dam break, N = %d cells per a" % n)
        ax.grid(alpha=0.3)
        ax.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(args.out + ".png", dpi=110)


if __name__ == "__main__":
    main()
