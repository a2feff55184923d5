"""The stone at a toe's tip: where the stones lost first in two ensembles of the same scene and seeds lay
in the packed weir, and the two ensembles member by member (ensemble_pair.py).

Reads each member's run.h5 (the stones' positions at every snapshot and which are fixed), counts the
packings with a free stone on the bed (centre below 0.75 d) beyond the fixed layer's ends, and lists the
stones removed at the first snapshot after the release with their packed position; then pairs the two
ensembles into studies/results/toe_stone.md. Run each ensemble with its own build first:

    vofdem run maeno2008 --quick --seeds 0-29 --out BEFORE     # the packer before the change
    vofdem run maeno2008 --quick --seeds 0-29 --out AFTER      # and after
    python3 studies/toe_stone.py BEFORE AFTER
"""
import argparse
import sys
from pathlib import Path

import h5py
import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parent))
import ensemble_pair  # noqa: E402

ROOT = Path(__file__).resolve().parents[1]


def member_facts(run_h5: Path, release: float) -> dict:
    """Whether a free stone lies on the bed beyond the fixed layer, and the stones removed (moved more than
    their diameter) by the first snapshot after the release, with their packed (x, z)."""
    with h5py.File(run_h5, "r") as f:
        pos, d, t = f["stones/pos"][:], f["stones/diameter"][:], f["time"][:]
        fixed = f["stones/fixed"][:].astype(bool)
    x_fixed = pos[0, fixed, 0]
    on_bed = ~fixed & (pos[0, :, 1] < 0.75 * d)
    tip = on_bed & ((pos[0, :, 0] > x_fixed.max()) | (pos[0, :, 0] < x_fixed.min()))
    k = int(np.searchsorted(t, release, side="right"))
    moved = (np.linalg.norm(pos[k] - pos[0], axis=1) > d) & ~fixed
    return {"tip": [tuple(pos[0, i]) for i in np.where(tip)[0]],
            "first": [(i, tuple(pos[0, i]), bool(tip[i])) for i in np.where(moved)[0]]}


def summary(directory: Path, release: float) -> tuple:
    rows = {}
    for run in sorted(directory.glob("seed*/run.h5"), key=lambda p: int(p.parent.name[4:])):
        rows[run.parent.name] = member_facts(run, release)
    with_tip = sum(bool(r["tip"]) for r in rows.values())
    lost_first = sum(bool(r["first"]) for r in rows.values())
    tip_lost = sum(any(s[2] for s in r["first"]) for r in rows.values())
    only_tip = sum(bool(r["first"]) and all(s[2] for s in r["first"]) for r in rows.values())
    text = (f"{with_tip} of {len(rows)} packings have a free stone on the bed beyond the fixed layer's ends; "
            f"{lost_first} lose a stone by the first snapshot after the release (t = {release:g} s), that "
            f"stone among them in {tip_lost}, the only one in {only_tip}")
    return text, rows


def main(argv=None) -> Path:
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("before", type=Path)
    p.add_argument("after", type=Path)
    p.add_argument("--release", type=float, default=5.0, help="the release time of the held stones [s] "
                   "(the quick Maeno scene's spin-up)")
    p.add_argument("--scene-note", default="maeno2008, quick variant (the draft grid, spin-up 5 s, 10 to 25 l/s in "
                   "30 s), seeds 0-29", help="which scene and seeds both ensembles ran (into the text)")
    p.add_argument("--out", type=Path, default=ROOT / "studies" / "results" / "toe_stone.md")
    args = p.parse_args(argv)
    b, _ = summary(args.before, args.release)
    a, _ = summary(args.after, args.release)
    preamble = (f"Scene {args.scene_note}. Each member run once with the packer before the change (a stone could be laid by hand on "
                f"the bed at a toe's tip) and once after (stones laid by hand only above the fixed layer; "
                f"toe rollers removed in up to three rounds), one member after the other in one process, on a "
                f"machine shared with other builds (CPU rows are no exact cost comparison). Rerun: see "
                f"`studies/toe_stone.py`.\n\nBefore: {b}. After: {a}.")
    ensemble_pair.main([str(args.before), str(args.after), "--title",
                        "The stone at the toe's tip: the same scene and packings before and after the packer kept "
                        "its hand-laid stones above the fixed layer", "--preamble", preamble, "--out", str(args.out)])
    return args.out


if __name__ == "__main__":
    main()
