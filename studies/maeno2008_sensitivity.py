"""Sensitivity of the Maeno 2008 weir's failure to the candidate causes of docs/scenario_diagnosis.md.

Short runs of the quick scene (Scene.maeno2008().quick(): 5 cm x 2 cm grid, 5 s spin-up with the
stones held, then 10 -> 25 l/s over 30 s) built through the Python API, one variant per run:

  ext             the scene as committed, its ramp continued at the same rate to 50 l/s (65 s
                  simulated; identical to the committed quick scene up to 25 l/s)
  no_drag         drag off (which force matters on this grid), 10 -> 25 l/s
  no_pressure     pressure-gradient force off, 10 -> 25 l/s
  k_matched       k1, k2 scaled so that the porous resistance of eq. (7) at the mean porosity actually
                  mapped inside the weir equals the resistance at n_exp = 0.41 (candidate a);
                  k_half: the square roots of those factors (half-way on a log scale)
  lightF          stone density lowered so that the submerged weight is 1/F (e.g. light2: 1/2; how far the
                  forces are from moving the stones; bounds candidate c)
  fine            the paper's grid (2.5 cm x 1 cm, 0.5 cm at the bed; candidate b: the drag samples
                  the overflow sheet better)
  seedN           another packing (seed N instead of 0)
  slow            the paper's ramp rate (10 -> 25 l/s over 120 s) instead of the quick scene's 30 s
  fromQ           the spin-up (stones held) and the release at Q l/s instead of 10, the ramp's rate kept
                  (e.g. from5: 5 -> 25 l/s over 160 s at the paper's rate): is a failure at the release a
                  failure of the start discharge or of releasing the loaded stones at once?
  endT            stop at T s of simulated time
  bed             the bed drag (stones.drag_model = "bed": the reaction of the porous resistance on the
                  stones, docs/coupler.md) in place of the sphere drag of eqs. (16)-(18)
  bulk            the bulk-consistent porosity mapping (stones.porosity_mapping = "bulk": the porosity
                  inside each disc chosen so that the weir's mean mapped porosity is n_exp = 0.41)
Variants combine with '+', e.g. fine+k_matched+ext.

For each: first removal and stage discharges (vofdem.analysis, a stone is removed once it moved more
than its diameter), and the largest fluid force on a loose stone relative to its submerged weight
W' = (rho_s - rho_w) V g at a few discharges. No default of the code is changed.

    PYTHONPATH=python python3 studies/maeno2008_sensitivity.py VARIANT [VARIANT ...]
    PYTHONPATH=python python3 studies/maeno2008_sensitivity.py --table

Each run writes studies/results/maeno2008_sensitivity/VARIANT.json; --table collects them into
studies/results/maeno2008_sensitivity.md.
"""
from __future__ import annotations

import json
import sys
import time
from pathlib import Path

import numpy as np

from vofdem.analysis import analyse
from vofdem.builder import build_simulation
from vofdem.run import grid_faces
from vofdem.scene import Scene

RESULTS = Path(__file__).resolve().parent / "results"
RUN_DIR = RESULTS / "maeno2008_sensitivity"
RHO_W, G = 1000.0, 9.81
N_PAPER = 0.41
VARIANTS = ("ext", "no_drag", "no_pressure", "k_half+ext", "k_matched+ext", "light1.25+ext", "light1.5+ext",
            "light2+ext", "light4+ext", "fine+ext", "fine+no_drag+ext", "fine+no_pressure", "fine+k_half+ext", "fine+k_matched+ext",
            "ext+seed1", "ext+seed2", "k_half+ext+seed1", "fine+ext+seed1", "fine+k_half+ext+seed1",
            "fine+ext+seed2", "fine+k_half+ext+seed2", "fine+k_half+slow",
            "fine+k_half+slow+seed1", "fine+slow", "fine+slow+seed1", "fine+slow+seed2",
            "fine+slow+bed", "fine+slow+bed+seed1", "fine+slow+bed+seed2",
            "fine+slow+bulk", "fine+slow+bulk+seed1", "fine+slow+bulk+seed2",
            "fine+slow+bed+bulk", "fine+slow+bed+bulk+seed1", "fine+slow+bed+bulk+seed2", "fine+slow+bed+bulk+from5", "fine+slow+bulk+from5",
            "fine+slow+from1+end20", "fine+slow+bed+from1+end20", "fine+slow+bulk+from1+end20", "fine+slow+bed+bulk+from1+end20")
Q_PROBES = (10.0, 15.0, 20.0, 25.0, 30.0, 40.0, 50.0)


def resistance_factors(n_map: float, n_ref: float = N_PAPER):
    """(f1, f2) such that k1 f1 and k2 f2 at porosity n_map give the linear and quadratic resistance of
    eq. (7) that k1, k2 give at n_ref: nu/K ~ k1 (1-n)^2 / n^3, C/sqrt(K) ~ k2 (1-n) / n^3."""
    lin = lambda n: (1.0 - n) ** 2 / n ** 3  # noqa: E731
    quad = lambda n: (1.0 - n) / n ** 3  # noqa: E731
    return lin(n_ref) / lin(n_map), quad(n_ref) / quad(n_map)


def mapped_weir_porosity(scene: Scene):
    """Mean, min and max cell porosity mapped from the packed stones in the cells whose centre lies
    inside the weir's outline (and below 0.99, i.e. covered by stones)."""
    sim = build_simulation(scene)
    g = sim.fluid.grid
    xf, zf = grid_faces(g)
    xc, zc = 0.5 * (xf[1:] + xf[:-1]), 0.5 * (zf[1:] + zf[:-1])
    n = np.asarray(sim.fluid.cell_porosity, float).reshape(g.nz, g.nx)
    top = np.asarray(scene.weir.surface(xc), float)
    inside = (zc[:, None] < top[None, :]) & (n < 0.99)
    vals = n[inside]
    return float(vals.mean()), float(vals.min()), float(vals.max()), int(vals.size)


def variant_scene(name: str):
    """Scene of a variant; the name is a '+'-joined list of changes to the quick scene."""
    from vofdem.scene import GridSpec

    s = Scene.maeno2008().quick()
    info = {}
    tokens = set(name.split("+"))
    if "fine" in tokens:  # the paper's grid (2.5 cm x 1 cm, 0.5 cm at the bed) on the quick flume
        s.grid = GridSpec(dx=0.025, dz=0.01, dz_bed=0.005, bed_layer_height=0.005)
    for tok in tokens:  # 'lightF': submerged weight divided by F, same flow forces
        if tok.startswith("light"):
            s.stones.density = RHO_W + (s.stones.density - RHO_W) / float(tok[5:])
    if "k_matched" in tokens or "k_half" in tokens:  # k_half: the square roots of the factors
        n_mean, n_min, n_max, cells = mapped_weir_porosity(s)
        f1, f2 = resistance_factors(n_mean)
        if "k_half" in tokens:
            f1, f2 = f1 ** 0.5, f2 ** 0.5
        s.stones.k1 *= f1
        s.stones.k2 *= f2
        info.update(n_mean=n_mean, n_min=n_min, n_max=n_max, cells=cells, f1=f1, f2=f2,
                    k1=s.stones.k1, k2=s.stones.k2)
    if "bed" in tokens:
        s.stones.drag_model = "bed"
    if "no_drag" in tokens:
        s.effects.drag = False
    if "no_pressure" in tokens:
        s.effects.pressure_gradient = False
    for tok in tokens:  # 'seedN': another packing of the weir
        if tok.startswith("seed"):
            s.seed = int(tok[4:])
    if "bulk" in tokens:  # n_s, phi and the mean mapped porosity (after the seed is set)
        s.stones.porosity_mapping = "bulk"
    if "slow" in tokens:  # the paper's rate, 10 -> 25 l/s over 120 s
        s.hydrograph.ramp_duration = 120.0
    if "ext" in tokens:  # the ramp continued at the same rate (0.5 l/s per s) to 50 l/s
        rate = (s.hydrograph.discharge_end_lps - s.hydrograph.discharge_start_lps) / s.hydrograph.ramp_duration
        s.hydrograph.discharge_end_lps = 50.0
        s.hydrograph.ramp_duration = (50.0 - s.hydrograph.discharge_start_lps) / rate
    for tok in tokens:  # 'fromQ': the stones released at Q l/s instead of 10, the ramp's rate kept
        if tok.startswith("from"):
            h = s.hydrograph
            rate = (h.discharge_end_lps - h.discharge_start_lps) / h.ramp_duration
            h.discharge_start_lps = float(tok[4:])
            h.ramp_duration = (h.discharge_end_lps - h.discharge_start_lps) / rate
    for tok in tokens:  # 'endT': stop at T s of simulated time
        if tok.startswith("end"):
            s.end_time = float(tok[3:])
    s.validate()
    if "bulk" in tokens:
        from vofdem.builder import build_stones, disc_porosity

        n_s, phi = disc_porosity(s, build_stones(s)[0])
        n_mean, n_min, n_max, cells = mapped_weir_porosity(s)
        info.update(n_s=n_s, phi=phi, bulk_n_mean=n_mean, bulk_cells=cells)
    return s, info


def run_variant(name: str, dt_snap: float = 0.5) -> dict:
    scene, info = variant_scene(name)
    sim = build_simulation(scene)
    st = sim.stones
    fixed0 = np.asarray(st.stone_fixed).astype(bool).copy()
    r = np.asarray(st.stone_radius, float)
    rho_s = np.asarray(st.stone_density, float)
    w_sub = (rho_s - RHO_W) * (4.0 / 3.0) * np.pi * r ** 3 * G
    loose = ~fixed0
    pos0 = np.asarray(st.stone_pos, float).reshape(-1, 2).copy()
    ramp = scene.hydrograph.ramp_start
    st.held = True  # held during the spin-up with their contacts, as run_scene does (DEMSystem.held)
    times, pos, active, rows = [], [], [], []
    wall0 = time.perf_counter()
    t_end = scene.duration
    targets = np.round(np.arange(dt_snap, t_end + 1e-9, dt_snap), 9)
    held = True
    for t in targets:
        sim.advance(float(t))
        if held and float(sim.time) >= ramp - 1e-9:
            st.held = held = False
        p = np.asarray(st.stone_pos, float).reshape(-1, 2).copy()
        fd = np.asarray(sim.stone_force_drag, float).reshape(-1, 2)
        fs = np.asarray(sim.stone_force_pressure, float).reshape(-1, 2)
        tot = np.linalg.norm(fd + fs, axis=1) / w_sub
        q = float(scene.hydrograph.discharge_lps_at(float(sim.time)))
        times.append(float(sim.time))
        pos.append(p)
        active.append(np.asarray(st.stone_active).astype(bool).copy())
        disp = np.linalg.norm(p - pos0, axis=1)
        rows.append(dict(t=float(sim.time), q=q,
                         moved=int(np.sum(loose & (disp > 2.0 * r))),
                         f_tot_max=float(tot[loose].max()),
                         f_s_max=float((np.linalg.norm(fs, axis=1) / w_sub)[loose].max()),
                         f_d_max_N=float(np.linalg.norm(fd, axis=1)[loose].max())))
    wall = time.perf_counter() - wall0
    a = analyse(np.array(times), np.array(pos), 2.0 * r, scene.weir, scene.hydrograph.discharge_lps_at,
                active=np.array(active), fixed=fixed0, ramp_start=ramp)
    removal = a.removal_time[np.isfinite(a.removal_time)]
    first_q = float(scene.hydrograph.discharge_lps_at(removal.min())) if removal.size else None
    stages = [dict(number=s.number, q=s.discharge_lps, stones=len(s.stones),
                   regions={k: int(v) for k, v in s.region_counts.items() if v}) for s in a.stages]
    probes = {}
    for qp in Q_PROBES:
        after = [row for row in rows if row["t"] > ramp + 0.25]  # released stones only
        if not after or qp > max(row["q"] for row in after) + 0.3:
            continue
        probes[f"{qp:g}"] = min(after, key=lambda row: abs(row["q"] - qp))
    out = dict(variant=name, info=info, wall_s=wall, simulated_s=float(sim.time), q_end=rows[-1]["q"],
               removed=int(removal.size), first_removal_lps=first_q, stages=stages,
               isolated=len(a.isolated), probes=probes, rows=rows,
               loose_stones=int(loose.sum()), w_sub_range=[float(w_sub[loose].min()), float(w_sub[loose].max())])
    RUN_DIR.mkdir(parents=True, exist_ok=True)
    (RUN_DIR / f"{name}.json").write_text(json.dumps(out, indent=1))
    return out


def table() -> str:
    runs = [json.loads((RUN_DIR / f"{v}.json").read_text()) for v in
            VARIANTS
            if (RUN_DIR / f"{v}.json").exists()]
    lines = ["# Maeno 2008 weir: sensitivity of the failure to the candidate causes", "",
             "Written by `studies/maeno2008_sensitivity.py` (variants explained in its docstring). Quick scene",
             "(5 cm x 2 cm grid, quick flume, 5 s spin-up with the stones held, then a ramp from 10 l/s at 0.5 l/s",
             "per s: 4x faster than the paper's; `fine`: the paper's grid; `slow`: the paper's rate), seed 0 unless",
             "`seedN`. A stone is removed once it moved more than its diameter; a stage needs >= 2 removals within",
             "3 s (vofdem.analysis). The isolated removal at 10.25 l/s (10.5 with F_S off) is the unfixed toe stone.",
             "F/W' = |F_S + F_D| / ((rho_s - rho_w) V g), the largest over the loose stones at the snapshot nearest",
             "the discharge (after a stage it is the moved stones'); F_D max in N; wall s on one core of a loaded",
             "2-core machine. Stage regions are in the JSON files of studies/results/maeno2008_sensitivity/.",
             "`bed`: the drag is the bed drag (reaction of the porous resistance; F_D is then that force);",
             "`bulk`: the porosity inside each disc makes the weir's mean mapped porosity n_exp (docs/scenario.md).", ""]
    seen = set()
    for r in runs:
        if "n_s" in r["info"]:
            i = r["info"]
            lines.append(f"- `{r['variant']}`: packing's solid fraction phi = {i['phi']:.4f}, inner porosity "
                         f"n_s = 1 - 0.59 / phi = {i['n_s']:.4f}; mean mapped porosity in the weir's cells "
                         f"{i['bulk_n_mean']:.3f} ({i['bulk_cells']} cells; the paper's mapping: ~0.53).")
        if "f1" in r["info"] and ("fine" in r["variant"], "k_half" in r["variant"]) not in seen:
            seen.add(("fine" in r["variant"], "k_half" in r["variant"]))
            i = r["info"]
            lines.append(f"- `{r['variant']}`: mean mapped porosity in the weir's cells {i['n_mean']:.3f} "
                         f"(range {i['n_min']:.2f}-{i['n_max']:.2f}, {i['cells']} cells); factors to match "
                         f"n = 0.41: k1 x {i['f1']:.2f}, k2 x {i['f2']:.2f} -> (k1, k2) = ({i['k1']:.0f}, {i['k2']:.2f}).")
    lines += ["", "| variant | Q range [l/s] | removed | first removal [l/s] | stages (Q l/s: stones) | "
              "F/W' max at 10 / 15 / 20 / 25 l/s | F/W' at 30 / 40 / 50 | F_D max at 25 l/s [N] | wall s |",
              "|---|---|---|---|---|---|---|---|---|"]
    for r in runs:
        pr = r["probes"]
        f = lambda q: f"{pr[q]['f_tot_max']:.2f}" if q in pr else "-"  # noqa: E731
        st = ", ".join(f"{s['q']:.2f}: {s['stones']}" for s in r["stages"]) or "none"
        first = f"{r['first_removal_lps']:.2f}" if r["first_removal_lps"] is not None else "none"
        fd25 = f"{pr['25']['f_d_max_N']:.3f}" if "25" in pr else "-"
        lines.append(f"| {r['variant']} | {r['rows'][0]['q']:.0f}-{r['q_end']:.0f} | {r['removed']} ({r['isolated']} isolated) | {first} | "
                     f"{st} | {f('10')} / {f('15')} / {f('20')} / {f('25')} | {f('30')} / {f('40')} / {f('50')} | "
                     f"{fd25} | {r['wall_s']:.0f} |")
    lines.append("")
    return "\n".join(lines)


def main(argv):
    if argv and argv[0] == "--table":
        text = table()
        (RESULTS / "maeno2008_sensitivity.md").write_text(text)
        print(text)
        return
    for name in argv or ["baseline"]:
        r = run_variant(name)
        print(name, {k: r[k] for k in ("removed", "first_removal_lps", "stages", "wall_s")},
              {q: round(p["f_tot_max"], 3) for q, p in r["probes"].items()}, flush=True)


if __name__ == "__main__":
    main(sys.argv[1:])
