#!/usr/bin/env python3
"""2D DEM settling benchmark: vofdem.DEMSystem against LAMMPS (gran/hooke/history) in one run.

The set-up is that of ../shared/peers/dem_settle (run_lammps.py; the peers' folder is found relative
to the project root, or set VOFDEM_PEERS to it): N discs of diameter
0.048 m * U(0.9, 1.1) (same random stream, same seed), density 2650, at rest on a square lattice of
pitch 0.055 m with +-1 mm x-jitter, settling for 20,000 steps of 1e-4 s onto a floor between two side
walls; linear spring-dashpot normal force, tangential history spring kt = 2/7 kn with Coulomb friction
0.577 on stones and walls, normal restitution 0.5, tangential damping half the normal one.

vofdem gives its stones the mass of a sphere (LAMMPS: a disc of unit thickness), so its normal
stiffness is scaled by m_sphere / m_disc: both codes then have the same contact frequency, contact
duration (about 22 steps) and restitution, and the same trajectories up to the inertia of rotation
(vofdem is run with the disc's inertia factor 1/2, as LAMMPS's nve/sphere disc).

usage: PYTHONPATH=python python3 benchmarks/dem_settle.py [--sizes 1000 10000] [--steps 20000]
       [--no-lammps]
Writes benchmarks/results/dem_settle.md.
"""
import argparse
import math
import os
import random
import re
import shutil
import subprocess
import sys
import tempfile
import time

import numpy as np

import vofdem

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from peers import peers_dir  # noqa: E402

HERE = os.path.dirname(os.path.abspath(__file__))
PEER = str(peers_dir() / "dem_settle" / "run_lammps.sh")
D_MEAN, POLY, RHO, PITCH = 0.048, 0.10, 2650.0, 0.055


def lattice(n, seed):
    """Discs as run_lammps.py writes them (same random stream)."""
    rng = random.Random(seed)
    nx = int(math.ceil(math.sqrt(n)))
    pos, diam = [], []
    for k in range(n):
        i, j = k % nx, k // nx
        d = D_MEAN * rng.uniform(1.0 - POLY, 1.0 + POLY)
        x = (i + 0.5) * PITCH + rng.uniform(-0.001, 0.001)
        y = (j + 0.5) * PITCH
        pos.append((x, y))
        diam.append(d)
    return np.array(pos), np.array(diam), nx * PITCH


def run_vofdem(n, steps, dt=1e-4, kn_lammps=5e6, e=0.5, mu=0.577, seed=12345):
    pos, diam, width = lattice(n, seed)
    m_disc = RHO * math.pi * D_MEAN ** 2 / 4.0
    m_sphere = RHO * math.pi * D_MEAN ** 3 / 6.0
    p = vofdem.DEMParams()
    p.stiffness_normal = kn_lammps * m_sphere / m_disc
    p.restitution = e
    p.friction_stone = mu
    p.tangential_damping_factor = 0.5
    p.inertia_factor = 0.5
    p.dt = dt
    p.add_flume(0.0, width, 0.0, mu)
    s = vofdem.DEMSystem(p, pos=pos, radius=0.5 * diam, density=np.array([RHO]))
    assert dt <= s.stable_dt()
    t0, c0 = time.perf_counter(), time.process_time()
    s.advance(steps * dt)
    wall, cpu = time.perf_counter() - t0, time.process_time() - c0
    r = s.stone_radius
    zmax = float(np.max(s.stone_pos[:, 1]))
    vmax = float(np.max(np.hypot(s.stone_vel[:, 0], s.stone_vel[:, 1])))
    ov = [((r[i] + r[j]) - np.hypot(*(s.stone_pos[i] - s.stone_pos[j]))) / D_MEAN for i, j in s.overlapping_pairs()]
    prof = s.profile
    stages = {name: sec for name, sec in zip(prof.names, prof.seconds)}
    return {"wall": wall, "ns": wall / (n * steps) * 1e9, "ns_cpu": cpu / (n * steps) * 1e9, "zmax": zmax, "vmax": vmax,
            "ov_max": max(ov) if ov else 0.0, "contacts": len(ov), "stages": stages,
            "builds": s.neighbour_builds}


def run_lammps(n, steps):
    env = dict(os.environ, PEERS_NO_RECORD="1")
    work = tempfile.mkdtemp(prefix="vofdem_dem_settle_")
    out = subprocess.run([PEER, str(n), "--steps", str(steps), "--work", work], capture_output=True, text=True,
                         env=env)
    line = next((l for l in out.stdout.splitlines() if l.startswith("RESULT")), None)
    if line is None:
        return None
    kv = dict(re.findall(r"(\w[\w/]*)=([^\s(]+)", line))
    loop = float(kv["loop_s"])
    # LAMMPS reports the share of the loop it had the CPU ("% CPU use"): the CPU time of its loop
    log = open(os.path.join(work, "dem_settle_lammps_N%d" % n, "log.lammps")).read()
    m = re.search(r"([0-9.]+)% CPU use", log)
    cpu = loop * float(m.group(1)) / 100.0 if m else float("nan")
    shutil.rmtree(work, ignore_errors=True)
    return {"loop": loop, "ns": loop / (n * steps) * 1e9, "ns_cpu": cpu / (n * steps) * 1e9, "zmax": float(kv["ymax_end"]),
            "vmax": float(kv["vmax_end"]), "ov_max": float(kv["max"]), "contacts": int(kv["contacts"])}


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--sizes", type=int, nargs="+", default=[1000, 10000])
    ap.add_argument("--steps", type=int, default=20000)
    ap.add_argument("--no-lammps", action="store_true")
    args = ap.parse_args()
    have_lammps = not args.no_lammps and os.path.exists("/usr/bin/lmp") and os.path.exists(PEER)
    rows = []
    for n in args.sizes:
        ours = run_vofdem(n, args.steps)
        peer = run_lammps(n, args.steps) if have_lammps else None
        rows.append((n, ours, peer))
        print(f"N={n}: vofdem {ours['ns']:.1f} (cpu {ours['ns_cpu']:.1f}) ns/particle-step"
              + (f", LAMMPS {peer['ns']:.1f} (cpu {peer['ns_cpu']:.1f}) ns/particle-step, "
                 f"ratio {ours['ns'] / peer['ns']:.2f} (cpu {ours['ns_cpu'] / peer['ns_cpu']:.2f})" if peer else ""),
              flush=True)
    lines = ["# 2D DEM settling: cost per particle-step, vofdem vs LAMMPS (one run)", "",
             f"{args.steps} steps of 1e-4 s, discs 4.8 cm +-10 %, lattice start (../shared/peers/dem_settle), "
             "one core each. LAMMPS time is its own loop time; vofdem's is the wall time of "
             "`DEMSystem.advance`. Wall times depend on the machine's load; the CPU times (vofdem: process "
             "time; LAMMPS: loop time x its reported % CPU use) do less.", "",
             "| N | vofdem ns/particle-step wall (cpu) | LAMMPS ns/particle-step wall (cpu) | "
             "ratio vofdem/LAMMPS wall (cpu) | "
             "top z vofdem / LAMMPS [m] | max overlap/d vofdem / LAMMPS | contacts vofdem / LAMMPS |",
             "|---|---|---|---|---|---|---|"]
    for n, o, p in rows:
        if p:
            lines.append(f"| {n} | {o['ns']:.1f} ({o['ns_cpu']:.1f}) | {p['ns']:.1f} ({p['ns_cpu']:.1f}) | "
                         f"{o['ns'] / p['ns']:.2f} ({o['ns_cpu'] / p['ns_cpu']:.2f}) | "
                         f"{o['zmax']:.3f} / {p['zmax']:.3f} | {o['ov_max']:.4f} / {p['ov_max']:.4f} | "
                         f"{o['contacts']} / {p['contacts']} |")
        else:
            lines.append(f"| {n} | {o['ns']:.1f} ({o['ns_cpu']:.1f}) | n/a | n/a | {o['zmax']:.3f} / - | {o['ov_max']:.4f} / - | "
                         f"{o['contacts']} / - |")
    lines += ["", "vofdem stage times [s] (StageProfile):", ""]
    for n, o, _ in rows:
        st = ", ".join(f"{k} {v:.2f}" for k, v in o["stages"].items() if v > 0)
        lines.append(f"- N = {n}: {st}; neighbour-list builds {o['builds']}")
    os.makedirs(os.path.join(HERE, "results"), exist_ok=True)
    path = os.path.join(HERE, "results", "dem_settle.md")
    with open(path, "w") as f:
        f.write("\n".join(lines) + "\n")
    print("wrote", path)


if __name__ == "__main__":
    sys.exit(main())
