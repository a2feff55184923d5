"""The 3D spheres' DEM cost in the Maeno scenario: CPU per sphere-substep per stage and the real-time factor of a member segment, across builds.

The scene scenes/maeno2008_spheres_rolling_consistent.toml (packing --seed) is packed, spun up with the
stones held as a member is (run.py) and exported at the release of the stones (the ramp's start, 20 s),
once, by the first build. Each build (a directory holding a vofdem package, e.g. a copy of an installed
one; or the interpreter's own) then restarts from that state in a child process, lets the stones go and
runs --segment s of the member in the run's 0.5-s snapshot windows, the builds alternating round by round
on one core. Per run: CPU (process) time and the real-time factor of the segment (CPU / simulated), the
coupler's stages and the DEM's (their timers are wall clock: shares of the segment), the DEM substeps
per flow step, the cost per sphere-substep (mobile spheres x substeps) and per contact-substep, the
neighbour list's builds, the contacts, and the sha256 of the final state, so that the table also says
whether the builds computed the same bits.

    OMP_NUM_THREADS=1 PYTHONPATH=python python3 benchmarks/sphere_dem_cost.py [--segment 10] [--rounds 3]
        [--build before=DIR after=DIR] [--seed 0] [--out FILE]

Writes benchmarks/results/sphere_dem_cost.md (medians over the rounds, ranges in brackets).
"""
import argparse
import hashlib
import json
import os
import platform
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

os.environ.setdefault("OMP_NUM_THREADS", "1")
ROOT = Path(__file__).resolve().parents[1]
SCENE = "scenes/maeno2008_spheres_rolling_consistent.toml"
WINDOW = 0.5  # s: the run's snapshot interval (run.py advances the coupler window by window)


def state_hash(state: dict) -> str:
    """sha256 of a state's named arrays in key order (the bits)"""
    import numpy as np

    h = hashlib.sha256()
    for name in sorted(state):
        h.update(name.encode())
        h.update(np.ascontiguousarray(np.asarray(state[name], dtype=float)).tobytes())
    return h.hexdigest()[:16]


def scene_of(seed: int):
    from vofdem.scene import load_scene

    return load_scene(ROOT / SCENE).replace(seed=seed)


def prepare(seed: int, path: Path) -> dict:
    """packs the weir, spins it up held to the release and saves the state there (npz)"""
    import numpy as np

    from vofdem.builder import build_simulation

    scene = scene_of(seed)
    cpu0 = time.process_time()
    sim = build_simulation(scene)
    cpu_build = time.process_time() - cpu0
    release = scene.hydrograph.ramp_start
    sim.stones.held = True
    cpu0 = time.process_time()
    t = 0.0
    while t < release - 1e-9:
        t = min(release, t + WINDOW)
        sim.advance(t)
    cpu_spin = time.process_time() - cpu0
    np.savez(path, **{k: np.asarray(v) for k, v in sim.export_state().items()})
    return dict(cpu_build=cpu_build, cpu_spin_up=cpu_spin, spin_up=release, steps_spin_up=int(sim.step_count))


def restarted(scene, state: dict):
    """the coupled simulation at a saved state, built as builder.build_simulation builds it but with the
    stones made from the state's 'dem/' part (the packing, 35 CPU-s, is not made again)"""
    from vofdem import _core, builder

    stones = _core.DEMSystem(builder.dem_params(scene), 0)
    stones.import_state({k[4:]: v for k, v in state.items() if k.startswith("dem/")})
    sim = _core.Coupler(builder.build_fluid(scene), stones,
                        builder.coupler_params(scene, builder.disc_porosity(scene, stones)[0]))
    t, q = scene.hydrograph.table(scene.duration)
    sim.set_inflow_table([float(v) for v in t], [float(v) for v in q])
    sim.import_state(state)
    return sim


def segment(seed: int, path: Path, duration: float) -> dict:
    """the member's segment after the release, from the saved state"""
    import numpy as np

    scene = scene_of(seed)
    with np.load(path) as z:
        state = {k: z[k] for k in z.files}
    sim = restarted(scene, state)
    st = sim.stones
    st.held = False
    for prof in (sim.profile, st.profile):
        prof.reset()
    mobile = int(np.sum(np.asarray(st.stone_active).astype(bool) & ~np.asarray(st.stone_fixed).astype(bool)))
    t0, steps0, sub0, nb0 = float(sim.time), int(sim.step_count), int(st.steps), int(st.neighbour_builds)
    contacts, walls, pairs = [], [], []
    cpu = 0.0
    t = t0
    while t < t0 + duration - 1e-9:
        t = min(t0 + duration, t + WINDOW)
        c0 = time.process_time()
        sim.advance(t)
        cpu += time.process_time() - c0
        contacts.append(int(st.contact_count))
        walls.append(int(st.wall_contact_count))
        pairs.append(len(st.neighbour_pairs()))
    sub = int(st.steps) - sub0
    out = dict(cpu=cpu, simulated=float(sim.time) - t0, flow_steps=int(sim.step_count) - steps0, substeps=sub,
               builds=int(st.neighbour_builds) - nb0, mobile=mobile, active=int(np.sum(st.stone_active)),
               contacts=statistics.mean(contacts), wall_contacts=statistics.mean(walls), pairs=statistics.mean(pairs),
               hash=state_hash(sim.export_state()))
    # the step and what bounds it, read after the state is hashed
    out.update(dt=float(st.params.dt), contact_steps=float(st.params.contact_steps), stable_dt=float(st.stable_dt()),
               kn=float(st.stiffness_normal))
    out["coupler"] = {n: s for n, s, c in zip(sim.profile.names, sim.profile.seconds, sim.profile.calls) if c}
    out["dem"] = {n: s for n, s, c in zip(st.profile.names, st.profile.seconds, st.profile.calls) if c}
    return out


def run_child(build, args, mode: str) -> dict:
    env = dict(os.environ, OMP_NUM_THREADS="1")
    if build:
        env["PYTHONPATH"] = build + os.pathsep + env.get("PYTHONPATH", "")
    cmd = [sys.executable, str(Path(__file__).resolve()), "--child", mode, "--seed", str(args.seed),
           "--segment", str(args.segment), "--state", str(args.state)]
    done = subprocess.run(cmd, capture_output=True, text=True, env=env, cwd="/")
    if done.returncode != 0:
        raise SystemExit(f"child ({mode}) failed:\n{done.stderr[-3000:]}")
    return json.loads(done.stdout.strip().splitlines()[-1])


def med(values, fmt="{:.4g}") -> str:
    """median [min to max]"""
    values = list(values)
    if len(values) == 1:
        return fmt.format(values[0])
    return f"{fmt.format(statistics.median(values))} [{fmt.format(min(values))} to {fmt.format(max(values))}]"


def build_table(labels, runs) -> list:
    rows = ["| build | CPU [s] | real-time factor (CPU / simulated) | ns per sphere-substep | "
            "ns per contact-substep (all the CPU) | ratio (CPU, to the first build) | same bits |",
            "|---|---|---|---|---|---|---|"]
    base = statistics.median(r["cpu"] for r in runs[0])
    hashes = {r["hash"] for rs in runs for r in rs}
    for label, rs in zip(labels, runs):
        rows.append(f"| {label} | {med(r['cpu'] for r in rs)} | {med(r['cpu'] / r['simulated'] for r in rs)} | "
                    f"{med(1e9 * r['cpu'] / (r['mobile'] * r['substeps']) for r in rs)} | "
                    f"{med(1e9 * r['cpu'] / (r['contacts'] * r['substeps']) for r in rs)} | "
                    f"{statistics.median(r['cpu'] for r in rs) / base:.3f} | "
                    f"{'yes' if len(hashes) == 1 else 'NO: ' + ', '.join(sorted({r['hash'] for r in rs}))} |")
    return rows


def stage_table(r: dict) -> list:
    """one run's stages: share of the segment's timed total, and the DEM's per sphere-substep"""
    rows = ["| timer | stage | share of the segment | ns per sphere-substep (of the CPU, by share) |",
            "|---|---|---|---|"]
    total = sum(r["coupler"].values())
    units = r["mobile"] * r["substeps"]
    for name, s in r["coupler"].items():
        rows.append(f"| coupler | {name} | {s / total:.1%} | |")
    for name, s in r["dem"].items():
        rows.append(f"| DEM | {name} | {s / total:.1%} | {1e9 * r['cpu'] * s / total / units:.1f} |")
    return rows


def contact_ns(r: dict) -> float:
    """the DEM's contact stage per touching sphere-sphere contact and substep [ns] (its share of the CPU)"""
    share = r["dem"].get("contacts", 0.0) / sum(r["coupler"].values())
    return 1e9 * r["cpu"] * share / (r["contacts"] * r["substeps"])


def main(argv=None) -> None:
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--build", nargs="+", default=None, metavar="LABEL=DIR",
                    help="builds: a directory holding a vofdem package each (default: this interpreter's own)")
    ap.add_argument("--rounds", type=int, default=3)
    ap.add_argument("--segment", type=float, default=10.0, help="simulated seconds after the release [s]")
    ap.add_argument("--seed", type=int, default=0, help="the packing")
    ap.add_argument("--out", type=Path, default=ROOT / "benchmarks" / "results" / "sphere_dem_cost.md")
    ap.add_argument("--child", choices=["prepare", "segment"], help=argparse.SUPPRESS)
    ap.add_argument("--state", type=Path, help=argparse.SUPPRESS)
    args = ap.parse_args(argv)
    if args.segment <= 0 or args.rounds < 1:
        raise ValueError(f"--segment {args.segment} s and --rounds {args.rounds}: need segment > 0 s, rounds >= 1")
    if args.child == "prepare":
        return print(json.dumps(prepare(args.seed, args.state)))
    if args.child == "segment":
        return print(json.dumps(segment(args.seed, args.state, args.segment)))
    builds = [b.rsplit("=", 1) for b in (args.build or ["this build="])]
    if any(len(b) != 2 for b in builds):
        raise ValueError(f"--build {args.build}: each build as LABEL=DIR (DIR empty: this interpreter's vofdem)")
    labels = [b[0] for b in builds]
    loads = [os.getloadavg()[0]]
    with tempfile.TemporaryDirectory() as tmp:
        args.state = Path(tmp) / "release.npz"
        prep = run_child(builds[0][1], args, "prepare")
        runs = [[] for _ in builds]
        for r in range(args.rounds):
            for k, (_, path) in enumerate(builds):
                runs[k].append(run_child(path, args, "segment"))
                loads.append(os.getloadavg()[0])
            print(f"round {r + 1}/{args.rounds} done", file=sys.stderr)
    last = runs[-1][-1]
    text = [f"# The 3D spheres' DEM cost in a Maeno member's segment", "",
            f"`benchmarks/sphere_dem_cost.py --segment {args.segment:g} --rounds {args.rounds} --seed {args.seed}`, "
            f"{time.strftime('%Y-%m-%d %H:%M UTC', time.gmtime())}, {platform.processor() or platform.machine()}, "
            f"one core per child (OMP_NUM_THREADS=1), builds alternating round by round on a shared machine "
            f"(load average {min(loads):.2f}-{max(loads):.2f}); CPU is process time.", "",
            f"Scene `{SCENE}`, packing {args.seed}: {last['active']} spheres ({last['mobile']} mobile). Untimed "
            f"before the segment: the packing ({prep['cpu_build']:.1f} CPU-s) and the {prep['spin_up']:g}-s spin-up "
            f"with the stones held ({prep['cpu_spin_up']:.1f} CPU-s, {prep['steps_spin_up']} flow steps, "
            f"real-time factor {prep['cpu_spin_up'] / prep['spin_up']:.3f}). The segment: {args.segment:g} s after "
            "the release, restarted from the state at the release.", "",
            "- " + "\n- ".join(f"build {k}: {label}" for k, label in enumerate(labels)), "",
            "## Cost of the segment (median [range] over the rounds)", "", *build_table(labels, runs), "",
            f"## Where the time goes (the last build's last round)", "",
            f"{last['flow_steps']} flow steps ({1e3 * last['simulated'] / last['flow_steps']:.2f} ms on average), "
            f"{last['substeps']} DEM substeps ({last['substeps'] / last['flow_steps']:.1f} per flow step: the DEM "
            f"step {last['dt']:.4g} s, {last['contact_steps']:g} steps per contact, with the normal stiffness that "
            f"follows, {last['kn']:.4g} N/m; the stable step {last['stable_dt']:.4g} s), {last['builds']} neighbour-list builds "
            f"(one per {last['substeps'] / max(1, last['builds']):.0f} substeps); at the ends of the 0.5-s windows "
            f"on average {last['pairs']:.0f} listed pairs, {last['contacts']:.0f} touching sphere-sphere "
            f"contacts ({last['contacts'] / last['mobile']:.2f} per mobile sphere) and {last['wall_contacts']:.0f} "
            f"plane contacts (bed, side walls, end walls). The contact stage: {contact_ns(last):.1f} ns per touching "
            "contact and substep. The timers are wall clock: their shares apportion the process time.", "",
            *stage_table(last), ""]
    from vofdem.study import write_page  # here: the builds measured are the children's, not this process's

    write_page(args.out, text)


if __name__ == "__main__":
    main()
