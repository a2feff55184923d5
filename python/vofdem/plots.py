"""Figures of a run in the manner of Maeno & Tomita (2008), and an animation of the whole run.

Every function takes a `RunData` (the run's HDF5 file) and draws with matplotlib's object-oriented
API on its own `Figure` (Agg canvas, no pyplot state), so it works the same in scripts, tests and
notebooks. Figures:

* `fig_porosity`            the paper's Fig. 4: porosity field with the stones
* `fig_stones_velocity`     Figs. 6-7: stones (coloured by displacement) with pore-velocity vectors
* `fig_pressure_gradient`   Fig. 8: pressure-gradient force on each stone over the pressure field
* `fig_drag`                Fig. 9: drag force on each stone over the pore speed
* `fig_velocity_distribution` Fig. 10: velocity vectors at several discharges, weir outline in orange
* `fig_rating_curve`        upstream water level against discharge
* `fig_timeline`            discharge, stones removed and crest lowering against time, stages shaded
* `fig_hydrograph`          the flood the run followed (ramp, table or a measured CSV flood) with the
                            destruction stages marked at their discharges
* `fig_destruction`         the weir before and after: each stone where it ended, coloured by the
                            stage that removed it, the stones' initial places and surface outlined
* `fig_plan_view`           3D stones only: the weir seen from above between the flume's side walls,
                            at the start and at a later snapshot, coloured by the stage that removed them
"""
from __future__ import annotations

from pathlib import Path
from typing import List, Optional, Sequence

import matplotlib
import numpy as np
from matplotlib.collections import EllipseCollection, PolyCollection
from matplotlib.figure import Figure
from matplotlib.patches import Patch

from .analysis import surface_profile

WEIR_COLOR = "tab:orange"
# matplotlib 3.6 renamed transOffset to offset_transform
_MPL_36 = tuple(int(v) for v in matplotlib.__version__.split(".")[:2]) >= (3, 6)


def _axes(scene, data, width=9.0, height=3.6, layout="constrained"):
    fig = Figure(figsize=(width, height), layout=layout)
    ax = fig.add_subplot()
    _frame(ax, scene, data)
    return fig, ax


def _frame(ax, scene, data):
    w = scene.weir
    margin = 0.25
    ax.set_xlim(max(data.x_faces[0], w.toe_x - margin), min(data.x_faces[-1], w.x_toe_down + margin))
    ax.set_ylim(0.0, min(data.z_faces[-1], w.height * 1.7))
    ax.set_aspect("equal")
    ax.set_xlabel("x [m]")
    ax.set_ylabel("z [m]")


def _stones(ax, data, k, colors=None, alpha=1.0):
    pos = data.pos[k]
    keep = data.active[k]
    if colors is None:
        colors = np.where(data.fixed, "0.45", "tan")
    face = "none" if isinstance(colors, str) else list(np.asarray(colors)[keep])
    outlines = data.stone_outlines(k) if hasattr(data, "stone_outlines") else None
    if outlines is not None:  # polygon stones
        col = PolyCollection([o for o, a in zip(outlines, keep) if a], facecolors=face, edgecolors="0.2",
                             linewidths=0.4, alpha=alpha, zorder=3)
        ax.add_collection(col)
        return col
    col = EllipseCollection(data.diameter[keep], data.diameter[keep], np.zeros(keep.sum()), units="xy",
                            offsets=pos[keep], facecolors=face,
                            edgecolors="0.2", linewidths=0.4, alpha=alpha, zorder=3,
                            **{"offset_transform" if _MPL_36 else "transOffset": ax.transData})
    ax.add_collection(col)
    return col


def _surface(ax, data, fields):
    if np.nanmax(fields["F"]) > 0.5 > np.nanmin(fields["F"]):
        ax.contour(data.x_centers, data.z_centers, fields["F"], levels=[0.5], colors="tab:blue", linewidths=1.2,
                   zorder=4)


def _outline(ax, scene):
    x, z = scene.weir.outline_xz()
    ax.plot(x, z, color=WEIR_COLOR, lw=1.3, zorder=5)


def _pore_velocity(fields):
    n = np.clip(fields["porosity"], 0.05, 1.0)
    wet = (fields["F"] > 0.5) & (fields["porosity"] > 0.05)
    return np.where(wet, fields["u"] / n, np.nan), np.where(wet, fields["w"] / n, np.nan)


def _title(ax, data, k, what):
    ax.set_title(f"{what}  t = {data.times[k]:.1f} s, Q = {1e3 * data.discharge[k]:.2f} l/s", fontsize=10)


def fig_porosity(data, scene, k: int = 0) -> Figure:
    """The porosity field with the stones on it (the paper's Fig. 4)."""
    f = data.fields(k)
    fig, ax = _axes(scene, data)
    m = ax.pcolormesh(data.x_faces, data.z_faces, f["porosity"], cmap="viridis", vmin=0.0, vmax=1.0,
                      shading="flat", zorder=1)
    _stones(ax, data, k, colors="none", alpha=0.8)
    fig.colorbar(m, ax=ax, label="porosity n [-]", shrink=0.8)
    _title(ax, data, k, "Porosity")
    return fig


def fig_stones_velocity(data, scene, k: int, stride: int = 1) -> Figure:
    """Stones coloured by displacement, pore-velocity vectors, water surface (the paper's Figs. 6-7)."""
    f = data.fields(k)
    fig, ax = _axes(scene, data)
    disp = np.linalg.norm(data.pos[k] - data.pos[0], axis=1) / data.diameter
    colors = np.where(data.fixed, "0.45", np.where(disp > 1.0, "tab:red", np.where(disp > 0.2, "gold", "tan")))
    _stones(ax, data, k, colors)
    U, W = _pore_velocity(f)
    X, Z = np.meshgrid(data.x_centers, data.z_centers)
    s = (slice(None, None, stride), slice(None, None, stride))
    q = ax.quiver(X[s], Z[s], U[s], W[s], angles="xy", scale_units="xy", scale=8.0, width=0.0018, color="k",
                  zorder=6)
    ax.quiverkey(q, 0.9, 1.03, 0.5, "0.5 m/s", labelpos="E", fontproperties={"size": 8})
    _surface(ax, data, f)
    _outline(ax, scene)
    _title(ax, data, k, "Stones (red: moved > 1 d, gold: > 0.2 d) and pore velocity")
    return fig


def _force_arrows(ax, data, k: int, F, color: str) -> None:
    """A force [N] on each loose stone of snapshot k, with a 1 N key."""
    act = data.active[k] & ~data.fixed
    q = ax.quiver(data.pos[k, act, 0], data.pos[k, act, 1], F[act, 0], F[act, 1], angles="xy", scale_units="xy",
                  scale=20.0, color=color, width=0.003, zorder=6)
    ax.quiverkey(q, 0.9, 1.03, 1.0, "1 N", labelpos="E", fontproperties={"size": 8})


def _force_figure(data, scene, k: int, f, field, cmap: str, label: str, F, color: str, title: str) -> Figure:
    """A field of snapshot k under the stones with one force on each stone as an arrow (Figs. 8 and 9)."""
    fig, ax = _axes(scene, data)
    m = ax.pcolormesh(data.x_faces, data.z_faces, field, cmap=cmap, shading="flat", zorder=1)
    fig.colorbar(m, ax=ax, label=label, shrink=0.8)
    _stones(ax, data, k, "none")
    _force_arrows(ax, data, k, F, color)
    _surface(ax, data, f)
    _outline(ax, scene)
    _title(ax, data, k, title)
    return fig


def fig_pressure_gradient(data, scene, k: int) -> Figure:
    """Pressure field and the pressure-gradient force on each stone (the paper's Fig. 8)."""
    f = data.fields(k)
    p = np.where(f["F"] > 0.01, f["p"], np.nan)
    return _force_figure(data, scene, k, f, p, "Blues", "pressure p [Pa]", data.force_pressure[k], "tab:red",
                         "Pressure-gradient force on stones")


def fig_drag(data, scene, k: int) -> Figure:
    """Pore speed and the drag force on each stone (the paper's Fig. 9)."""
    f = data.fields(k)
    U, W = _pore_velocity(f)
    return _force_figure(data, scene, k, f, np.hypot(U, W), "magma_r", "pore speed |U| [m/s]", data.force_drag[k],
                         "tab:green", "Drag force on stones")


def fig_velocity_distribution(data, scene, discharges_lps: Sequence[float] = (12.0, 17.0, 22.0)) -> Figure:
    """Velocity vectors and water surface at several discharges (the paper's Fig. 10)."""
    q = 1e3 * data.discharge
    fig = Figure(figsize=(9.0, 2.6 * len(discharges_lps)), layout="constrained")
    for j, ql in enumerate(discharges_lps):
        k = int(np.argmin(np.abs(q - ql)))
        ax = fig.add_subplot(len(discharges_lps), 1, j + 1)
        _frame(ax, scene, data)
        f = data.fields(k)
        _stones(ax, data, k, alpha=0.5)
        U, W = _pore_velocity(f)
        X, Z = np.meshgrid(data.x_centers, data.z_centers)
        # at most about 60 arrows a row: denser ones blur into each other (and bloat the file)
        sx = slice(None, None, -(-len(data.x_centers) // 60))
        ax.quiver(X[:, sx], Z[:, sx], U[:, sx], W[:, sx], angles="xy", scale_units="xy", scale=8.0, width=0.0015,
                  zorder=6)
        _surface(ax, data, f)
        _outline(ax, scene)
        _title(ax, data, k, "Velocity")
    return fig


def fig_rating_curve(data, scene) -> Figure:
    """Upstream water level against discharge, with the weir's crest height."""
    fig = Figure(figsize=(5.0, 4.0), layout="constrained")
    ax = fig.add_subplot()
    sc = ax.scatter(1e3 * data.discharge, data.upstream_level, c=data.times, s=8, cmap="viridis")
    ax.axhline(scene.weir.height, color=WEIR_COLOR, lw=1, ls="--", label="initial crest")
    fig.colorbar(sc, ax=ax, label="t [s]")
    ax.set_xlabel("discharge Q [l/s]")
    ax.set_ylabel(f"water level at x = {scene.gauge_x:.2f} m [m]")
    ax.set_title("Rating curve", fontsize=10)
    ax.legend(fontsize=8)
    return fig


def fig_timeline(analysis, data, scene) -> Figure:
    """Discharge, stones removed and crest lowering against time; stages shaded."""
    a = analysis
    fig = Figure(figsize=(8.0, 6.0), layout="constrained")
    axs = [fig.add_subplot(3, 1, j + 1) for j in range(3)]
    t = a.times
    axs[0].plot(t, 1e3 * data.discharge, color="tab:blue")
    axs[0].set_ylabel("Q [l/s]")
    _reference_levels(axs[0], getattr(scene, "reference", None), t[0])
    axs[1].step(t, a.removed_count, where="post", color="tab:red")
    axs[1].set_ylabel("stones removed")
    axs[2].plot(t, 1e3 * a.crest_lowering, color="tab:brown")
    axs[2].set_ylabel("crest lowering [mm]")
    axs[2].set_xlabel("simulation time t [s]")
    for ax in axs:
        if a.ramp_start > t[0]:
            ax.axvspan(t[0], a.ramp_start, color="0.9", zorder=0)
        for s in a.stages:
            ax.axvspan(s.start_time, max(s.end_time, s.start_time + 0.5 * (t[1] - t[0] if t.size > 1 else 1)),
                       color="tab:red", alpha=0.2, zorder=0)
    for s in a.stages:
        axs[1].annotate(f"{s.number}", (s.start_time, a.removed_count.max() * 0.9 + 0.1), fontsize=8)
    axs[0].set_title("Destruction timeline (grey: spin-up; red: stages)", fontsize=10)
    return fig


def _reference_levels(ax, ref, x_text: float) -> None:
    """The reference's observed stage discharges as horizontal lines, when the scene has any."""
    stages = ref.stages() if ref is not None and ref.has_observed else {}
    if not stages:
        return
    for (k, (q, _)), ls in zip(sorted(stages.items()), (":", "--", "-.", (0, (1, 3)))):
        ax.axhline(q, color="0.5", lw=0.8, ls=ls)
    values = " / ".join(f"{q:g}" for _, (q, _) in sorted(stages.items()))
    ax.text(x_text, max(q for q, _ in stages.values()), f" observed stages {values} l/s ({ref.short()})",
            fontsize=7, color="0.4", va="bottom")


STAGE_COLORS = ("tab:red", "tab:purple", "tab:blue", "tab:green", "tab:brown")


def fig_hydrograph(analysis, data, scene) -> Figure:
    """The scene's hydrograph over the whole flood (the run may stop before its end) with the stages marked
    where they began, the first removal, the spin-up shaded, and the reference's observed stage discharges
    when the scene has any."""
    h, a = scene.hydrograph, analysis
    fig = Figure(figsize=(8.0, 3.6), layout="constrained")
    ax = fig.add_subplot()
    t_end = max(scene.duration, float(data.times[-1]))
    t = np.linspace(0.0, t_end, 600)
    ax.plot(t, h.discharge_lps_at(t), color="tab:blue", lw=1.4, label="hydrograph")
    ax.plot(data.times, 1e3 * data.discharge, color="tab:blue", ls="none", marker=".", ms=3,
            label=f"the run (to t = {data.times[-1]:.1f} s)")
    if h.ramp_start > 0:
        ax.axvspan(0.0, h.ramp_start, color="0.9", zorder=0, label="spin-up")
    fr = a.first_removal
    if fr is not None:
        ax.plot([fr], [a.discharge_lps_at(fr)], marker="v", color="gold", mec="0.3", ms=8, ls="none",
                label=f"first removal: {a.discharge_lps_at(fr):.2f} l/s")
    for s in a.stages:
        c = STAGE_COLORS[(s.number - 1) % len(STAGE_COLORS)]
        ax.axvline(s.start_time, color=c, lw=1.0, ls="--")
        ax.plot([s.start_time], [s.discharge_lps], marker="o", color=c, ls="none",
                label=f"stage {s.number}: {s.discharge_lps:.2f} l/s, {s.n_stones} stones")
    _reference_levels(ax, getattr(scene, "reference", None), 0.0)
    ax.set_xlabel("simulation time t [s]")
    ax.set_ylabel("discharge Q [l/s]")
    ax.set_xlim(0.0, t_end)
    ax.grid(alpha=0.3)
    ax.legend(fontsize=7, loc="best")
    ax.set_title(f"Hydrograph: {h.source()}" + ("" if a.stages else " (no destruction stage)"), fontsize=10)
    return fig


def stage_of_stones(analysis) -> np.ndarray:
    """(n,) stage number that removed each stone; -1 isolated removal, 0 never removed."""
    label = np.zeros(analysis.removal_time.size, int)
    label[np.isfinite(analysis.removal_time)] = -1
    for s in analysis.stages:
        label[s.stones] = s.number
    return label


def fig_destruction(analysis, data, scene, k: Optional[int] = None) -> Figure:
    """The weir at snapshot k (default: the last) over its initial state: stones where they are, coloured
    by the stage that removed them, their initial places and the initial and present stone surface."""
    k = data.times.size - 1 if k is None else k
    fig, ax = _axes(scene, data, height=3.8)
    label = stage_of_stones(analysis)
    colors = np.where(data.fixed, "0.45", "tan").astype(object)
    handles = []
    for s in analysis.stages:
        c = STAGE_COLORS[(s.number - 1) % len(STAGE_COLORS)]
        colors[label == s.number] = c
        handles.append(Patch(color=c, label=f"stage {s.number}: {s.discharge_lps:.1f} l/s, "
                                                                 f"{s.n_stones} stones"))
    colors[label == -1] = "gold"
    if (label == -1).any():
        handles.append(Patch(color="gold", label="removed alone"))
    moved = label != 0
    ax.scatter(data.pos[0, moved, 0], data.pos[0, moved, 1], s=6, marker="x", color="0.3", zorder=2,
               label="initial places of removed stones")
    _stones(ax, data, k, colors)
    xs = np.linspace(scene.weir.toe_x, scene.weir.x_toe_down, 120)
    prof = surface_profile(data.pos[[0, k]], 0.5 * data.diameter, xs, data.active[[0, k]])
    ax.plot(xs, prof[0], color="0.3", ls="--", lw=1.0, zorder=5, label="stone surface at the start")
    ax.plot(xs, prof[1], color="k", lw=1.2, zorder=5, label="stone surface now")
    if data.has_fields:
        _surface(ax, data, data.fields(k))
    n_rem = int(np.isfinite(analysis.removal_time).sum())
    ax.legend(handles=handles + ax.get_legend_handles_labels()[0], fontsize=7, loc="upper left", ncol=2)
    _title(ax, data, k, f"Destruction ({n_rem} of {label.size} stones removed)")
    return fig


def _plan_stones(ax, x, y, d, colors, alpha, edge="0.2"):
    col = EllipseCollection(d, d, np.zeros(d.size), units="xy", offsets=np.column_stack([x, y]), facecolors=colors,
                            edgecolors=edge, linewidths=0.4, alpha=alpha, zorder=3,
                            **{"offset_transform" if _MPL_36 else "transOffset": ax.transData})
    ax.add_collection(col)


def fig_plan_view(data, scene, analysis=None, k: Optional[int] = None) -> Figure:
    """3D stones (data.y not None) seen from above: the flume between its side walls y = 0 and B, the
    stones at the start (left) and at snapshot k (right; default the last), each coloured by the stage
    that removed it (analysis given) or grey if fixed, tan if loose; the weir's toes dashed."""
    if getattr(data, "y", None) is None:
        raise ValueError("fig_plan_view draws 3D stones (stones.shape = 'sphere'); this run's stones are in the plane")
    k = data.times.size - 1 if k is None else k
    w = scene.weir
    colors = np.where(data.fixed, "0.45", "tan").astype(object)
    if analysis is not None:
        label = stage_of_stones(analysis)
        for st in analysis.stages:
            colors[label == st.number] = STAGE_COLORS[(st.number - 1) % len(STAGE_COLORS)]
        colors[label == -1] = "gold"
    x0, x1 = max(data.x_faces[0], w.toe_x - 0.25), min(data.x_faces[-1], w.x_toe_down + 0.25)
    fig = Figure(figsize=(9.0, 1.2 + 2 * 8.0 * data.width / (x1 - x0)), layout="constrained")
    axes = fig.subplots(2, 1, sharex=True)
    for ax, j, what in ((axes[0], 0, "start"), (axes[1], k, "now")):
        keep = data.active[j]
        # the lowest stones first, so that the top layer is drawn over them
        order = np.argsort(data.pos[j, :, 1])
        order = order[keep[order]]
        _plan_stones(ax, data.pos[j, order, 0], data.y[j, order], data.diameter[order], list(colors[order]), 0.9)
        for yw in (0.0, data.width):
            ax.axhline(yw, color="k", lw=1.2)
        for xt in (w.toe_x, w.x_toe_down):
            ax.axvline(xt, color=WEIR_COLOR, lw=1.0, ls="--")
        ax.set_xlim(x0, x1)
        ax.set_ylim(-0.05 * data.width, 1.05 * data.width)
        ax.set_aspect("equal")
        ax.set_ylabel("y [m]")
        _title(ax, data, j, f"Plan view ({what}, {int(keep.sum())} stones in the flume)")
    axes[1].set_xlabel("x [m]")
    return fig


def make_figures(data, analysis, scene, out_dir) -> List[Path]:
    """Writes every figure as PNG to out_dir; returns their paths."""
    out = Path(out_dir)
    out.mkdir(parents=True, exist_ok=True)
    files = []

    def save(fig, name, dpi=110):
        p = out / name
        fig.savefig(p, dpi=dpi)
        files.append(p)

    save(fig_timeline(analysis, data, scene), "timeline.png")
    save(fig_hydrograph(analysis, data, scene), "hydrograph.png")
    save(fig_destruction(analysis, data, scene), "destruction.png")
    save(fig_rating_curve(data, scene), "rating_curve.png")
    if getattr(data, "y", None) is not None:
        save(fig_plan_view(data, scene, analysis), "plan_view.png")
    if not data.has_fields:
        return files
    save(fig_porosity(data, scene, 0), "porosity_initial.png")
    moments = [(f"stage{s.number}", data.index_at(s.start_time)) for s in analysis.stages[:3]]
    if not moments:
        moments = [("final", data.times.size - 1)]
    for name, k in moments:
        save(fig_stones_velocity(data, scene, k), f"stones_velocity_{name}.png")
        save(fig_pressure_gradient(data, scene, k), f"pressure_gradient_{name}.png")
        save(fig_drag(data, scene, k), f"drag_{name}.png")
    save(fig_porosity(data, scene, data.times.size - 1), "porosity_final.png")
    q = 1e3 * data.discharge
    # thirds of the rise: the lowest discharge is the start, before the flow has formed
    levels = np.linspace(q.min(), q.max(), 4)[1:] if q.max() > q.min() else [q[0]]
    save(fig_velocity_distribution(data, scene, levels), "velocity_distribution.png", dpi=90)  # its arrows: < 300 kB
    return files


def animate(data, scene, path_base, analysis=None, fps: Optional[float] = None, max_frames: int = 400,
            dpi: int = 80) -> Path:
    """Animation of the run (water, porosity, stones): mp4 when ffmpeg is present, gif otherwise.
    path_base has no suffix; returns the file written."""
    from matplotlib import animation as anim

    fps = fps or scene.output.animation_fps
    frames = np.unique(np.linspace(0, data.times.size - 1, min(max_frames, data.times.size)).astype(int))
    fig, ax = _axes(scene, data, 8.0, 3.4, layout=None)  # a fixed layout: much faster per frame
    fig.subplots_adjust(left=0.08, right=0.98, bottom=0.14, top=0.9)
    f0 = data.fields(0)
    mesh = ax.pcolormesh(data.x_faces, data.z_faces, _water_image(f0), cmap="Blues", vmin=0, vmax=1.5,
                         shading="flat", zorder=1)
    _outline(ax, scene)
    state = {"stones": _stones(ax, data, 0)}
    title = ax.set_title("", fontsize=10)
    pos0 = data.pos[0]

    def draw(k):
        f = data.fields(k)
        mesh.set_array(_water_image(f).ravel())
        state["stones"].remove()
        disp = np.linalg.norm(data.pos[k] - pos0, axis=1) / data.diameter
        colors = np.where(data.fixed, "0.45", np.where(disp > 1.0, "tab:red", "tan"))
        state["stones"] = _stones(ax, data, k, colors)
        removed = int(analysis.removed_count[k]) if analysis is not None else int(np.sum(disp > 1.0))
        title.set_text(f"t = {data.times[k]:.1f} s   Q = {1e3 * data.discharge[k]:.2f} l/s   removed: {removed}")
        return [mesh, state["stones"], title]

    ani = anim.FuncAnimation(fig, draw, frames=frames, blit=False)
    if anim.writers.is_available("ffmpeg"):
        path = Path(str(path_base) + ".mp4")
        ani.save(path, writer=anim.FFMpegWriter(fps=fps, bitrate=1500), dpi=dpi)
    else:
        path = Path(str(path_base) + ".gif")
        ani.save(path, writer=anim.PillowWriter(fps=fps), dpi=dpi)
    return path


def _water_image(f):
    """Water fraction shown darker where the porosity is low (the weir's stones)."""
    return np.where(f["F"] > 0.02, f["F"] * (1.5 - 0.5 * f["porosity"]), np.nan)
