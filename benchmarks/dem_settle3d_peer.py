#!/usr/bin/env python3
"""3D DEM settling: vofdem's sphere stones against LAMMPS 3D granular (gran/hooke/history) in one run.

The case is that of ../shared/peers/dem_settle3d (run_lammps.py; the peers' folder is found relative to
the project root, or set VOFDEM_PEERS to it): N spheres of diameter 0.048 m * U(0.9, 1.1) (the same random
stream and seed), density 2650 kg/m^3, at rest on a cubic lattice of pitch 0.055 m, `across` in y and as
many along x, then layers (+-1 mm jitter in x and y), settling for `steps` steps of 1e-4 s onto a floor
(friction 0.577) between two end walls x = 0, across * 0.055 m and the flume's side walls y = 0,
across * 0.055 m (friction 0.176). Contacts: linear spring k_n = 2e5 N/m, tangential spring 2/7 k_n with
Coulomb friction 0.577, tangential damping half the normal one, normal restitution 0.5. All walls are
planes in both codes.

One difference of law: LAMMPS damps every pair with gamma_n m_eff (gamma_n set for e = 0.5 between two
mean spheres, and the same gamma_n with m_eff = m on the walls); vofdem sets each contact's dashpot for
e = 0.5 with its own masses. The restitution of a mean pair is the same; that of other pairs and of the
walls differs a little, so the beds settle alike, not to the same bits.

Cost is CPU time per particle-step: vofdem's process time over `DEMSystem.advance` (one thread:
OMP_NUM_THREADS=1 is set before the library loads), LAMMPS's loop time times its reported "% CPU use"
(serial, one MPI rank). vofdem runs twice, with the plane's neighbour list (every pair within reach in x-z,
whatever y) and with the 3D list (cells in x, y and z); both give the same bits, which the script checks.

usage: python3 benchmarks/dem_settle3d_peer.py [--n 1000] [--steps 20000] [--across 10]
       [--no-lammps] [--out benchmarks/results/dem_settle3d_peer.md]
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

if __name__ == "__main__":
    os.environ.setdefault("OMP_NUM_THREADS", "1")  # one core, as LAMMPS (before the library loads)

import numpy as np  # noqa: E402

import vofdem  # noqa: E402

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from peers import peers_dir  # noqa: E402

HERE = os.path.dirname(os.path.abspath(__file__))
D_MEAN, POLY, RHO, PITCH = 0.048, 0.10, 2650.0, 0.055
KN, E, MU, MU_WALL, DT = 2e5, 0.5, 0.577, 0.176, 1e-4
# the beds settle alike when their mean centre height and their top (highest centre) agree within this
SETTLE_TOL = 0.03


def lattice(n, across, seed):
    """Spheres as run_lammps.py writes them (same random stream): centres (x, y, z) and diameters [m]."""
    rng = random.Random(seed)
    xyz, diam = [], []
    for k in range(n):
        i, j, l = k % across, (k // across) % across, k // (across * across)
        d = D_MEAN * rng.uniform(1.0 - POLY, 1.0 + POLY)
        x = (i + 0.5) * PITCH + rng.uniform(-0.001, 0.001)
        y = (j + 0.5) * PITCH + rng.uniform(-0.001, 0.001)
        xyz.append((x, y, (l + 0.5) * PITCH))
        diam.append(d)
    return np.array(xyz), np.array(diam)


def spheres(n, across, plane_list, seed=12345):
    """The case as a vofdem.DEMSystem of sphere stones."""
    xyz, diam = lattice(n, across, seed)
    box = across * PITCH
    p = vofdem.DEMParams()
    p.stiffness_normal = KN
    p.stiffness_ratio = 2.0 / 7.0
    p.restitution = E
    p.friction_stone = MU
    p.tangential_damping_factor = 0.5
    p.inertia_factor = 0.4
    p.dt = DT
    p.neighbour_skin = 0.006  # LAMMPS's `neighbor 0.006 bin`
    p.walls = [vofdem.DEMWall([0.0, 0.0], [0.0, 1.0], MU), vofdem.DEMWall([0.0, 0.0], [1.0, 0.0], MU_WALL),
               vofdem.DEMWall([box, 0.0], [-1.0, 0.0], MU_WALL)]
    p.width = box
    p.side_wall_friction = MU_WALL
    p.plane_neighbour_list = plane_list
    s = vofdem.DEMSystem(p, pos=xyz[:, [0, 2]], radius=0.5 * diam, density=np.array([RHO]))
    s.set_model("sphere")
    s.stone_y[:] = xyz[:, 1]
    assert DT <= s.stable_dt()
    return s


def run_vofdem(n, steps, across, plane_list):
    s = spheres(n, across, plane_list)
    c0 = time.process_time()
    s.advance(steps * DT)
    cpu = time.process_time() - c0
    z = np.asarray(s.stone_pos[:, 1])
    e = s.energy()
    prof = s.profile
    total = sum(prof.seconds)
    stages = {name: sec / total for name, sec in zip(prof.names, prof.seconds) if sec > 0.0}
    return {"ns_cpu": cpu / (n * steps) * 1e9, "cpu": cpu, "mean_z": float(z.mean()), "zmax": float(z.max()),
            "ke": e.kinetic, "pairs": len(s.neighbour_pairs()), "contacts": s.contact_count,
            "builds": s.neighbour_builds, "stages": stages,
            "state": [np.array(a, copy=True) for a in (s.stone_pos, s.stone_y, s.stone_vel, s.stone_vel_y,
                                                       s.stone_quat, s.stone_omega_3d)]}


def run_lammps(n, steps, across):
    peer = peers_dir() / "dem_settle3d" / "run_lammps.sh"
    if shutil.which("lmp") is None or not peer.exists():
        return None
    work = tempfile.mkdtemp(prefix="vofdem_dem_settle3d_")
    try:
        out = subprocess.run([str(peer), str(n), "--steps", str(steps), "--across", str(across), "--work", work],
                             capture_output=True, text=True, env=dict(os.environ, PEERS_NO_RECORD="1"))
        line = next((x for x in out.stdout.splitlines() if x.startswith("RESULT")), None)
        if line is None:
            print(out.stdout, out.stderr, file=sys.stderr)
            return None
        kv = dict(re.findall(r"(\w+)=([^\s(]+)", line))
        case = os.path.join(work, "dem_settle3d_lammps_N%d" % n)
        log = open(os.path.join(case, "log.lammps")).read()
        m = re.search(r"([0-9.]+)% CPU use", log)
        loop = float(kv["loop_s"])
        cpu = loop * float(m.group(1)) / 100.0 if m else float("nan")
        # the final centres from the dump (columns id x y z radius vx vy vz)
        rows = open(os.path.join(case, "final.dump")).read().split("ITEM: ATOMS")[1].splitlines()[1:]
        z = np.array([float(r.split()[3]) for r in rows if r.strip()])
        return {"ns_cpu": cpu / (n * steps) * 1e9, "cpu": cpu, "mean_z": float(z.mean()), "zmax": float(z.max()),
                "ke": float(kv["ke_end"]), "natoms": len(z)}
    finally:
        shutil.rmtree(work, ignore_errors=True)


def same_bits(a, b):
    return all(np.array_equal(x, y) for x, y in zip(a["state"], b["state"]))


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--n", type=int, default=1000, help="number of spheres (>= 1000 for the peer comparison)")
    ap.add_argument("--steps", type=int, default=20000)
    ap.add_argument("--across", type=int, default=10, help="spheres across the flume")
    ap.add_argument("--no-lammps", action="store_true")
    ap.add_argument("--out", default=os.path.join(HERE, "results", "dem_settle3d_peer.md"))
    args = ap.parse_args(argv)
    plane = run_vofdem(args.n, args.steps, args.across, True)
    cells = run_vofdem(args.n, args.steps, args.across, False)
    peer = None if args.no_lammps else run_lammps(args.n, args.steps, args.across)
    bits = same_bits(plane, cells)
    print(f"vofdem plane list {plane['ns_cpu']:.1f}, 3D list {cells['ns_cpu']:.1f} CPU ns/particle-step, "
          f"same bits: {bits}" + (f"; LAMMPS {peer['ns_cpu']:.1f}" if peer else ""), flush=True)

    lines = ["# 3D DEM settling: CPU per particle-step, vofdem's spheres vs LAMMPS (one run)", "",
             f"{args.n} spheres, {args.across} across the flume, {args.steps} steps of {DT:g} s "
             f"({args.steps * DT:g} s), k_n = {KN:g} N/m, e = {E}, mu = {MU}, walls {MU_WALL} "
             "(../shared/peers/dem_settle3d; benchmarks/dem_settle3d_peer.py). One core each; CPU time "
             "(vofdem: process time of `advance`; LAMMPS: loop time x its % CPU use).", "",
             "| code | neighbour list | CPU ns / particle-step | ratio to LAMMPS | listed pairs at end | "
             "contacts at end | list builds | mean centre z [m] | top centre z [m] | kinetic energy at end [J] |",
             "|---|---|---|---|---|---|---|---|---|---|"]

    def ratio(o):
        return f"{o['ns_cpu'] / peer['ns_cpu']:.2f}" if peer else "n/a"

    for name, o in (("plane's (x-z)", plane), ("3D cells", cells)):
        lines.append(f"| vofdem | {name} | {o['ns_cpu']:.1f} | {ratio(o)} | {o['pairs']} | {o['contacts']} | "
                     f"{o['builds']} | {o['mean_z']:.4f} | {o['zmax']:.4f} | {o['ke']:.3g} |")
    if peer:
        lines.append(f"| LAMMPS | binned, skin 6 mm | {peer['ns_cpu']:.1f} | 1 | - | - | - | {peer['mean_z']:.4f} | "
                     f"{peer['zmax']:.4f} | {peer['ke']:.3g} |")
    else:
        lines.append("| LAMMPS | - | not run (lmp or the peers' folder absent) | - | - | - | - | - | - | - |")
    lines += ["", f"- The 3D list against the plane's: {plane['ns_cpu'] / cells['ns_cpu']:.2f} x less CPU, "
              f"{plane['pairs'] / max(cells['pairs'], 1):.1f} x fewer listed pairs; the final states are "
              f"{'the same bits' if bits else 'NOT the same bits'}."]
    for name, o in (("plane's list", plane), ("3D list", cells)):
        shares = ", ".join(f"{k} {v:.0%}" for k, v in o["stages"].items())
        lines.append(f"- vofdem's stages with the {name} (shares of the StageProfile's time): {shares}.")
    if peer:
        dz = abs(cells["mean_z"] - peer["mean_z"]) / peer["mean_z"]
        dtop = abs(cells["zmax"] - peer["zmax"]) / peer["zmax"]
        ok = dz <= SETTLE_TOL and dtop <= SETTLE_TOL
        lines.append(f"- Settling alike (tolerance {SETTLE_TOL:.0%} of LAMMPS's value): mean centre z differs by "
                     f"{dz:.2%}, top centre z by {dtop:.2%}: {'within' if ok else 'OUTSIDE'} the tolerance.")
        lines.append(f"- Aim (at most half of LAMMPS's CPU per particle-step, ratio <= 0.5): 3D list {ratio(cells)}, "
                     f"plane's list {ratio(plane)}.")
    os.makedirs(os.path.dirname(os.path.abspath(args.out)), exist_ok=True)
    with open(args.out, "w") as f:
        f.write("\n".join(lines) + "\n")
    print("wrote", args.out)
    return {"plane": plane, "cells": cells, "peer": peer, "same_bits": bits}


if __name__ == "__main__":
    main()
