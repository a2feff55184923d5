"""Cost of the coupler in scenes that use one module only, against that module alone.

A scene without stones (a dam break, 80 x 40 cells) is run by the bare VOFGrid and through the Coupler;
a scene without water (200 stones settling in a box) by the bare DEMSystem (advance in 0.01 s chunks,
the coupler's exchange step without water) and through the Coupler. Each run is repeated, interleaved,
and the fastest of each kind is kept. A full two-way scene's stage costs are listed too.
Writes benchmarks/results/coupler_overhead.md.

    PYTHONPATH=python python3 benchmarks/coupler_overhead.py
"""
import time
from pathlib import Path

import numpy as np

import vofdem
from vofdem import _core
from vofdem.flow import tank_params

REPEATS = 5
OUT = Path(__file__).resolve().parent / "results" / "coupler_overhead.md"


def fluid_scene():
    grid = vofdem.Grid2D.uniform(80, 40, 0.8, 0.4)
    f = vofdem.VOFGrid(grid, tank_params())
    f.fill_water_box(0.0, 0.2, 0.0, 0.3)
    f.set_hydrostatic_pressure()
    return f


def stone_scene(n=200):
    rng = np.random.default_rng(1)
    dp = vofdem.DEMParams()
    dp.add_flume(0.0, 0.6, 0.0)
    cols = 10
    pos = np.array([[0.04 + 0.055 * (j % cols) + 0.004 * rng.random(), 0.04 + 0.055 * (j // cols)] for j in range(n)])
    return vofdem.DEMSystem(dp, pos=pos, density=[2650.0], radius=np.full(n, 0.024))


def timed(fn):
    t0 = time.perf_counter()
    fn()
    return time.perf_counter() - t0


def run_fluid(T=0.6):
    bare, coupled, steps = [], [], 0
    for _ in range(REPEATS):
        f = fluid_scene()
        bare.append(timed(lambda: f.advance(T)))
        steps = f.step_count
        g = fluid_scene()
        sim = _core.Coupler(g, None)
        coupled.append(timed(lambda: sim.advance(T)))
        assert np.array_equal(np.asarray(f.cell_F), np.asarray(g.cell_F))
    return min(bare), min(coupled), steps, 80 * 40


def run_stones(T=1.0):
    bare, coupled = [], []
    substeps = 0
    for _ in range(REPEATS):
        s = stone_scene()

        def chunks():
            for _ in range(int(round(T / 0.01))):
                s.advance(0.01)

        bare.append(timed(chunks))
        substeps = s.steps
        c = stone_scene()
        sim = _core.Coupler(None, c)
        coupled.append(timed(lambda: sim.advance(T)))
        assert c.steps == s.steps  # the same number of DEM substeps
    return min(bare), min(coupled), substeps, 200


def coupled_profile(T=0.4):
    grid = vofdem.Grid2D.uniform(40, 50, 0.4, 0.5)
    fp = tank_params()
    fp.flags |= vofdem.FlowEffect.RELATIVE_VELOCITY  # two-way: resistance relative to the stones
    f = vofdem.VOFGrid(grid, fp)
    f.fill_water_below(0.25)
    f.set_hydrostatic_pressure()
    dp = vofdem.DEMParams()
    dp.submerged = True  # the Coupler hands the stones the flow's medium
    dp.add_flume(0.0, 0.4, 0.0)
    pos = np.array([[0.12 + 0.06 * (j % 3) + 0.003 * j, 0.32 + 0.06 * (j // 3)] for j in range(6)])
    s = vofdem.DEMSystem(dp, pos=pos, density=[2650.0], radius=np.full(6, 0.024))
    sim = _core.Coupler(f, s)
    wall = timed(lambda: sim.advance(T))
    p = sim.profile
    return wall, sim.step_count, list(zip(p.names, p.seconds, p.calls))


def main():
    fb, fc, fsteps, ncell = run_fluid()
    sb, sc, ssteps, nst = run_stones()
    wall, steps, stages = coupled_profile()
    lines = [
        "# Coupler overhead in one-module scenes",
        "",
        f"Fastest of {REPEATS} interleaved runs each; the fluid scene gives the same fields bit for bit, the stone scene the same number of substeps (asserted).",
        "",
        "| scene | bare module [s] | through Coupler [s] | ratio | cost |",
        "|---|---|---|---|---|",
        f"| no stones: dam break 80 x 40 cells, 0.6 s ({fsteps} steps) | {fb:.4f} | {fc:.4f} | {fc / fb:.3f} | "
        f"{1e6 * fb / (fsteps * ncell):.3f} us per cell-step (bare) |",
        f"| no water: 200 stones settling, 1.0 s ({ssteps} substeps) | {sb:.4f} | {sc:.4f} | {sc / sb:.3f} | "
        f"{1e9 * sb / (ssteps * nst):.1f} ns per stone-substep (bare) |",
        "",
        f"Two-way scene (examples/cpp: 6 stones into a pool, 40 x 50 cells, 0.4 s, {steps} steps, "
        f"{wall:.3f} s wall):",
        "",
        "| stage | seconds | calls | ms per call |",
        "|---|---|---|---|",
    ]
    for name, sec, calls in stages:
        lines.append(f"| {name} | {sec:.4f} | {calls} | {1e3 * sec / calls if calls else 0:.4f} |")
    OUT.parent.mkdir(parents=True, exist_ok=True)
    OUT.write_text("\n".join(lines) + "\n", encoding="utf-8")
    print("\n".join(lines))
    print(f"no-stones ratio {fc / fb:.3f}, no-water ratio {sc / sb:.3f}")


if __name__ == "__main__":
    main()
