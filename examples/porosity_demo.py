"""Porosity of a rubble mound weir from its stones (seed paper section 2.4, eq. 11, Fig. 4).

Builds the paper's trapezoidal weir of 4.8 cm stones (0.25 m high, 0.20 m crest, 27 degree slopes)
packed under gravity by the DEM (`vofdem.pack_weir`, weir_packing.h), maps the cell porosity on the paper's grid (2.5 cm x 1.0 cm,
0.5 cm rows up to 2 cm) with the exact disc-cell areas and with the paper's lookup table, and writes
a figure in the manner of the paper's Fig. 4 and the arrays.

    python3 examples/porosity_demo.py --out out [--m 8] [--seed 0]
"""
from __future__ import annotations

import argparse
import os

import numpy as np

import matplotlib  # noqa: E402

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
from matplotlib.collections import PatchCollection  # noqa: E402
from matplotlib.patches import Circle  # noqa: E402

import vofdem  # noqa: E402

N_EXP = 0.41


def map_porosity(grid, x, z, r, method, m):
    mapper = vofdem.make_porosity_mapper(grid, r.min(), r.max(), method=method, m=m, n_exp=N_EXP, max_discs=x.size)
    mapper.map(x, z, r)
    return np.array(mapper.cell_porosity), np.array(mapper.cell_solid_area)


def draw(ax, grid, field, x, z, d, title, cmap="viridis_r", vmin=N_EXP, vmax=1.0):
    xf = grid.x0 + grid.dx * np.arange(grid.nx + 1)
    zf = np.asarray(grid.z_faces)
    mesh = ax.pcolormesh(xf, zf, field, cmap=cmap, vmin=vmin, vmax=vmax, shading="flat")
    stones = PatchCollection([Circle((a, b), 0.5 * c) for a, b, c in zip(x, z, d)], facecolor="none",
                             edgecolor="k", linewidth=0.6)
    ax.add_collection(stones)
    ax.set_aspect("equal")
    ax.set_xlim(xf[0], xf[-1])
    ax.set_ylim(zf[0], zf[-1])
    ax.set_title(title, fontsize=9)
    ax.set_ylabel("z [m]")
    return mesh


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--out", default="out", help="output directory")
    ap.add_argument("--m", type=int, default=8, help="sub-areas per cell side of the lookup table")
    ap.add_argument("--seed", type=int, default=0, help="seed of the stone diameters")
    args = ap.parse_args(argv)
    os.makedirs(args.out, exist_ok=True)

    spec = vofdem.WeirSpec()
    spec.x_toe, spec.seed = 0.20, args.seed  # the paper's trapezoid is the spec's default
    spec.d_mean, spec.density = 0.048, 2650.0  # the paper's stones: the core has no stone default
    stones, _ = vofdem.pack_weir(spec)
    pos = np.asarray(stones.stone_pos)
    x, z, r = pos[:, 0].copy(), pos[:, 1].copy(), np.asarray(stones.stone_radius).copy()
    d = 2.0 * r
    grid = vofdem.Grid2D.graded(nx=64, length_x=1.60, height_z=0.35, dz=0.01, dz_bed=0.005, z_bed_top=0.02)
    n_exact, as_exact = map_porosity(grid, x, z, r, "exact", args.m)
    n_lookup, as_lookup = map_porosity(grid, x, z, r, "lookup", args.m)
    diff = n_lookup - n_exact

    fig, axes = plt.subplots(3, 1, figsize=(10, 5.6), sharex=True, constrained_layout=True)
    m1 = draw(axes[0], grid, n_exact, x, z, d, f"porosity n, eq. (11), exact areas ({x.size} stones, n_exp = {N_EXP})")
    draw(axes[1], grid, n_lookup, x, z, d, f"porosity n, lookup table m = {args.m}")
    lim = max(1e-3, float(np.abs(diff).max()))
    m3 = draw(axes[2], grid, diff, x, z, d, f"lookup - exact (max |dn| = {np.abs(diff).max():.3f})",
              cmap="RdBu_r", vmin=-lim, vmax=lim)
    axes[2].set_xlabel("x [m]")
    fig.colorbar(m1, ax=axes[:2], label="n [-]", shrink=0.8)
    fig.colorbar(m3, ax=axes[2], label="dn [-]", shrink=0.8)
    png = os.path.join(args.out, "porosity_weir.png")
    fig.savefig(png, dpi=150)
    plt.close(fig)

    npz = os.path.join(args.out, "porosity_weir.npz")
    np.savez(npz, x_faces=grid.x0 + grid.dx * np.arange(grid.nx + 1), z_faces=np.asarray(grid.z_faces),
             disc_x=x, disc_z=z, disc_d=d, cell_porosity_exact=n_exact, cell_porosity_lookup=n_lookup,
             cell_solid_area_exact=as_exact, cell_solid_area_lookup=as_lookup, m=args.m, n_exp=N_EXP)

    # the stone area of the weir on the grid equals the sum of the disc areas (all discs inside)
    print(f"{x.size} stones, d = {d.min() * 100:.2f} .. {d.max() * 100:.2f} cm; grid {grid.nx} x {grid.nz} cells")
    print(f"stone area mapped {as_exact.sum():.6f} m^2, sum of discs {np.sum(np.pi * r * r):.6f} m^2")
    print(f"mean porosity inside the weir's cells (n < 1): {n_exact[n_exact < 1].mean():.3f}")
    print(f"lookup m = {args.m}: max |dn| = {np.abs(diff).max():.4f}, RMS over touched cells = "
          f"{np.sqrt(np.mean(diff[(n_exact < 1) | (n_lookup < 1)] ** 2)):.4f}")
    print(f"wrote {png}")
    print(f"wrote {npz}")


if __name__ == "__main__":
    main()
