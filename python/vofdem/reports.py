"""Reports of finished runs and packings: what a run until failure says of its critical discharge
(markdown for one run and for an ensemble), and a packed weir's grading against the scene's sieve
curves (table and figure). They read results and scenes; the input modules (flood.py, grading.py)
only describe what is asked.
"""
from __future__ import annotations

import math

import numpy as np

from .builder import dem_params, is_graded
from .fragility import fragility_by_combination
from .grading import Grading, grading_deviation, mass_passing, packed_d
from .outline import zone_index


def critical_discharge(analysis, scene) -> dict:
    """The design answer of an until-failure run: the discharge of its first destruction stage.

    Returns dict(status, q_lps, q_per_width_lps_m, q_per_width_m2s, resolution_lps, first_lps, last_lps):
    status 'stage' (q_lps: the stage's discharge), 'at release' (the weir failed as soon as it was
    loaded: the critical discharge is q_lps = the first discharge or below), or 'none' (no stage up to
    the run's last discharge q_lps: the critical discharge is above it). resolution_lps: the rise
    between two snapshots, the uncertainty of q_lps from the snapshot interval."""
    a, h = analysis, scene.hydrograph
    release = h.ramp_start if h.hold_stones_during_spin_up and h.ramp_start > a.times[0] else float(a.times[0])
    after = a.times[a.times > release + 1e-9]
    first = float(a.discharge_lps_at(float(after[0]))) if after.size else float(a.discharge_lps_at(release))
    last = float(a.discharge_lps_at(float(a.times[-1])))
    if a.stages:
        st = a.stages[0]
        status = "at release" if after.size and st.start_time <= after[0] + 1e-9 else "stage"
        q = float(st.discharge_lps)
    else:
        status, q = "none", last
    rate = h.until_failure_rate_lps_per_s if h.kind == "until_failure" else float("nan")
    width = scene.flume.width
    return dict(status=status, q_lps=q, q_per_width_lps_m=q / width, q_per_width_m2s=q * 1e-3 / width,
                resolution_lps=rate * scene.output.snapshot_interval, first_lps=first, last_lps=last,
                stones=int(a.stages[0].n_stones) if a.stages else 0, width_m=width)


def until_failure_markdown(analysis, scene) -> str:
    """The critical discharge of an until-failure run in words and numbers (until_failure.md)."""
    c = critical_discharge(analysis, scene)
    h = scene.hydrograph
    per = f"{c['q_per_width_lps_m']:.2f} l/s per m of width ({c['q_per_width_m2s']:.4g} m2/s; width {c['width_m']:g} m)"
    if c["status"] == "stage":
        answer = (f"**Critical discharge: {c['q_lps']:.2f} l/s** in total, {per}: the first destruction stage "
                  f"({c['stones']} stones when the run stopped) began there.")
    elif c["status"] == "at release":
        answer = (f"**Critical discharge: {c['q_lps']:.2f} l/s or below** ({per}): the weir lost a stage "
                  f"({c['stones']} stones) as soon as it was loaded, at the first discharge of the rise; a start "
                  f"at a lower discharge (hydrograph) would say how far below.")
    else:
        cut = "" if c["last_lps"] >= h.discharge_end_lps - 1e-9 else (
            f" (the run ended before the largest discharge, {h.discharge_end_lps:g} l/s)")
        answer = (f"**Critical discharge: above {c['q_lps']:.2f} l/s** ({per}): no destruction stage up to the "
                  f"run's last discharge{cut}.")
    return "\n".join([
        f"# Until failure: {scene.name}", "",
        f"The discharge rose from {h.discharge_start_lps:g} l/s at {h.until_failure_rate_lps_per_s:g} l/s per s "
        f"(after a {h.spin_up_duration:g} s spin-up) up to {h.discharge_end_lps:g} l/s at most; the run stops at the "
        f"first destruction stage (at least two stones removed, pauses under 3 s).", "", answer, "",
        f"Resolution: a snapshot every {scene.output.snapshot_interval:g} s, so {c['resolution_lps']:.3g} l/s of "
        f"rise between two; the answer belongs to this rate (a slower rise gives the stones more time) and to "
        f"this packing (seed {scene.seed}; an ensemble over seeds gives its spread).", ""])


def ensemble_until_failure_markdown(members, widths: dict, n_boot: int = 1000, seed: int = 0) -> str:
    """The critical discharge's distribution over an until-failure ensemble (until_failure.md of the
    ensemble): per parameter combination, the fragility of the first stage (fragility.py: censored
    empirical median, lognormal median and 16-84 % band), in total and per unit width. widths:
    {combination: flume width [m]}."""

    out = ["# Until failure: the critical discharge over the ensemble", "",
           "The critical discharge of a member is the discharge of its first destruction stage. Members "
           "without a stage are censored at their last discharge; members that failed as soon as they were "
           "loaded count at the first discharge or below (fragility.md's rules).", "",
           "| combination | members | with a stage (at the first discharge) | empirical median [l/s] | "
           "lognormal median [16-84 %] [l/s] | per unit width: median [16-84 %] [l/s per m] |",
           "|---|---|---|---|---|---|"]
    for combo, evs in fragility_by_combination(members, n_boot, seed).items():
        e = next(x for x in evs if x.event == "stage1")
        r, w = e.row(), widths.get(combo, float("nan"))
        emp = r["empirical_median_lps"]
        if e.fit is None:
            fit = per = "no fit"
        else:
            fit = f"{r['fit_median_lps']:.2f} [{r['fit_q16_lps']:.2f}-{r['fit_q84_lps']:.2f}]"
            per = f"{r['fit_median_lps'] / w:.2f} [{r['fit_q16_lps'] / w:.2f}-{r['fit_q84_lps'] / w:.2f}]"
        out.append(f"| {combo or 'all members'} | {r['members']} | {r['happened']} ({r['at_first_discharge']}) | "
                   f"{'not reached' if emp is None else f'{emp:.2f}'} | {fit} | {per} |")
    return "\n".join(out) + "\n"


def grading_table(grading: Grading, diameters, label: str = "stones") -> str:
    """Markdown: the requested and the packed mass fraction passing at the curve's points and at d15 / d50
    / d85, and the packed characteristic sizes."""
    d = np.asarray(diameters, float)
    sizes = sorted({round(v, 9) for v in (*grading.diameters, *(grading.d(p) for p in (0.15, 0.5, 0.85)))})
    rows = [f"**{label}**: {d.size} stones, {1e3 * d.min():.1f}-{1e3 * d.max():.1f} mm; largest deviation of "
            f"the packed curve from the requested one {grading_deviation(grading, d):.3f} (mass fraction).", "",
            "| size [mm] | requested passing | packed passing |", "|---|---|---|"]
    packed = mass_passing(d, sizes)
    for s, f in zip(sizes, packed):
        rows.append(f"| {1e3 * s:.1f} | {float(grading.passing_at(s)):.3f} | {f:.3f} |")
    rows += ["", "| | d15 [mm] | d50 [mm] | d85 [mm] |", "|---|---|---|---|",
             "| requested | " + " | ".join(f"{1e3 * grading.d(p):.1f}" for p in (0.15, 0.5, 0.85)) + " |",
             "| packed | " + " | ".join(f"{1e3 * packed_d(d, p):.1f}" for p in (0.15, 0.5, 0.85)) + " |"]
    return "\n".join(rows) + "\n"


def fig_grading(curves):
    """Sieve curves: per (label, Grading, packed diameters), the requested curve (line) and the packed
    weir's (steps), mass fraction passing against size on a log axis."""
    from matplotlib.figure import Figure

    fig = Figure(figsize=(6.0, 4.0), layout="constrained")
    ax = fig.add_subplot()
    for j, (label, g, d) in enumerate(curves):
        c = f"C{j}"
        sizes = np.exp(np.linspace(math.log(g.d_min), math.log(g.d_max), 200))
        ax.plot(1e3 * sizes, g.passing_at(sizes), color=c, lw=1.6, label=f"{label}: requested")
        ds = np.sort(np.asarray(d, float))
        ax.step(1e3 * ds, mass_passing(ds, ds), where="post", color=c, ls="--", lw=1.2,
                label=f"{label}: packed ({ds.size} stones)")
    ax.set_xscale("log")
    ax.set_xlabel("stone size d [mm]")
    ax.set_ylabel("mass fraction passing [-]")
    ax.set_ylim(0.0, 1.02)
    ax.grid(alpha=0.3, which="both")
    ax.legend(fontsize=8)
    ax.set_title("Grading: requested and packed", fontsize=10)
    return fig


def packed_report(scene, pos, diameters, zone=None):
    """(markdown, figure) of a packed weir's grading against the scene's sieve curves, per zone and the
    core: the table of `grading_table` and the curves of `fig_grading`, with the DEM contact the builder
    chose for the grading (builder.graded_contact). zone: the zone each stone was drawn for (the outline
    packer's OutlinePackingReport.zone, -1 the core); without it a stone counts in the zone where its
    centre lies. (None, None) when the scene has no sieve curve."""
    if not is_graded(scene):
        return None, None
    pos = np.asarray(pos, float).reshape(-1, 2)
    d = np.asarray(diameters, float)
    where = zone_index(pos[:, 0], pos[:, 1], scene.weir.body(), scene.zones)
    label = where if zone is None else np.asarray(zone, int)
    parts = [(zn.name, zn.grading(), label == j) for j, zn in enumerate(scene.zones)]
    core = scene.stones.grading()
    if core is not None:
        parts.append(("core" if scene.zones else "stones", core, label == -1))
    p, n = dem_params(scene), scene.numerics
    how = ("Each stone counts in the zone it was drawn for (the packer's label); the share of them whose "
           "centre lies in that zone in the packed weir is given." if zone is not None else
           "Each stone counts in the zone where its centre lies in the packed weir.")
    lines = [f"# Grading of the packed weir: {scene.name} (seed {scene.seed})", "",
             how + " Masses as spheres of the stones' diameters (d^3).", ""]
    for (label_, g, sel), j in zip(parts, list(range(len(scene.zones))) + [-1]):
        if not sel.any():
            lines.append(f"**{label_}**: no stone\n")
            continue
        lines.append(grading_table(g, d[sel], label_))
        if zone is not None and scene.zones:
            lines.append(f"Centres in their zone: {np.mean(where[sel] == j):.0%} of the {label_} stones.\n")
    lines += [f"DEM contact of the graded stones: k_n = {p.stiffness_normal:.4g} N/m ({n.dem_contact_steps:g} steps "
              f"of {n.dem_dt:g} s per contact of two stones of the finest d50), DEM step {p.dt:.3g} s"
              + (" (lowered from numerics.dem_dt for the smallest stones)" if p.dt < n.dem_dt else "") + ".", ""]
    fig = fig_grading([(label_, g, d[sel]) for label_, g, sel in parts if sel.any()])
    return "\n".join(lines), fig
