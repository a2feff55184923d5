"""A run in ParaView: the porosity, the water and the stones coloured by their speed, at one snapshot.

    pvbatch examples/paraview_view.py RUN_DIR [--time T] [--png FILE]   # a screenshot, no window
    pvpython examples/paraview_view.py RUN_DIR --show                    # the same in a window
    pvbatch examples/paraview_view.py RUN_DIR --check                    # the pipeline, no rendering

RUN_DIR is the output of `vofdem run` (run.xmf, stones.xmf, run.h5). The fields are read from run.xmf
(its 'fields' collection: cell-centred F, p, porosity, u, w on the flume's quadrilaterals), the stones
from stones.xmf (a point cloud with diameter, velocity and the fluid forces). Coordinates are (x, z)
of the flume as ParaView's (X, Y). Default time: the last snapshot; default screenshot: RUN_DIR/paraview.png.
Run by pvbatch/pvpython (Debian: apt-get install paraview python3-paraview), not by vofdem's Python.
"""
import argparse
from pathlib import Path

from paraview import simple as pv


def load(run_dir: Path):
    """(fields reader, stones reader) of a run directory."""
    fields = pv.XDMFReader(registrationName="fields", FileNames=[str(run_dir / "run.xmf")])
    # run.xmf holds the stones too: keep the grids of the 'fields' collection (fields_0, fields_1, ...)
    fields.GridStatus = [g for g in fields.GetProperty("GridStatus").Available if g.startswith("fields_")]
    stones = pv.XDMFReader(registrationName="stones", FileNames=[str(run_dir / "stones.xmf")])
    return fields, stones


def check(fields, stones, t) -> int:
    """The pipeline without rendering (no display needed): prints what each part holds at time t;
    1 if the water or the stones are missing."""
    water = pv.Threshold(Input=fields, Scalars=["CELLS", "F"], LowerThreshold=0.5, UpperThreshold=1.0)
    glyphs = pv.Glyph(Input=stones, GlyphType="Sphere", ScaleArray=["POINTS", "diameter"], ScaleFactor=1.0,
                      GlyphMode="All Points")
    counts = {}
    for name, src in (("cells", fields), ("water cells", water), ("stones", stones), ("glyph points", glyphs)):
        src.UpdatePipeline(t)
        info = src.GetDataInformation()
        counts[name] = info.GetNumberOfCells() if "cells" in name else info.GetNumberOfPoints()
    arrays = sorted(a.GetName() for a in fields.CellData) + sorted(a.GetName() for a in stones.PointData)
    print(f"t = {t:g} s: " + ", ".join(f"{k} {v}" for k, v in counts.items()) + "; arrays " + " ".join(arrays))
    return 0 if counts["water cells"] > 0 and counts["stones"] > 0 and counts["glyph points"] > 0 else 1


def show_porosity(view, fields):
    disp = pv.Show(fields, view)
    pv.ColorBy(disp, ("CELLS", "porosity"))
    lut = pv.GetColorTransferFunction("porosity")
    lut.ApplyPreset("Grayscale", True)
    lut.RescaleTransferFunction(0.0, 1.0)
    disp.SetScalarBarVisibility(view, True)
    return disp


def show_water(view, fields):
    """The cells more than half full of water, blue and half transparent over the porosity."""
    water = pv.Threshold(registrationName="water", Input=fields, Scalars=["CELLS", "F"],
                         LowerThreshold=0.5, UpperThreshold=1.0)
    disp = pv.Show(water, view)
    disp.ColorArrayName = ["POINTS", ""]
    disp.AmbientColor = disp.DiffuseColor = [0.2, 0.45, 0.9]
    disp.Opacity = 0.45
    return disp


def show_stones(view, stones):
    """A disc of each stone's diameter, coloured by the magnitude of its velocity [m/s]."""
    glyphs = pv.Glyph(registrationName="stone discs", Input=stones, GlyphType="Sphere")
    glyphs.ScaleArray = ["POINTS", "diameter"]
    glyphs.ScaleFactor = 1.0  # the sphere source's diameter is 1: a glyph of the stone's diameter
    glyphs.GlyphMode = "All Points"
    glyphs.GlyphType.ThetaResolution = glyphs.GlyphType.PhiResolution = 24
    disp = pv.Show(glyphs, view)
    pv.ColorBy(disp, ("POINTS", "velocity", "Magnitude"))
    lut = pv.GetColorTransferFunction("velocity")
    lut.ApplyPreset("Inferno (matplotlib)", True)
    disp.RescaleTransferFunctionToDataRange(False, True)
    disp.SetScalarBarVisibility(view, True)
    return disp


def main():
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("run_dir", type=Path)
    p.add_argument("--time", type=float, default=None, help="simulated time [s] (default: the last snapshot)")
    p.add_argument("--png", type=Path, default=None, help="screenshot file (default: RUN_DIR/paraview.png)")
    p.add_argument("--show", action="store_true", help="open a window instead of writing a screenshot")
    p.add_argument("--check", action="store_true", help="build the pipeline without rendering and print it")
    args = p.parse_args()
    run_dir = args.run_dir.resolve()
    fields, stones = load(run_dir)
    times = list(fields.TimestepValues)
    t = times[-1] if args.time is None else min(times, key=lambda v: abs(v - args.time))
    if args.check:
        raise SystemExit(check(fields, stones, t))
    view = pv.CreateView("RenderView")
    view.ViewSize = [1600, 420]
    view.UseColorPaletteForBackground = 0
    view.Background = [1.0, 1.0, 1.0]
    view.OrientationAxesVisibility = 0
    view.ViewTime = t
    show_porosity(view, fields)
    show_water(view, fields)
    show_stones(view, stones)
    text = pv.Text(registrationName="time", Text=f"{run_dir.name}   t = {t:.1f} s")
    tdisp = pv.Show(text, view)
    tdisp.Color = [0, 0, 0]
    for name in ("porosity", "velocity"):
        bar = pv.GetScalarBar(pv.GetColorTransferFunction(name), view)
        bar.TitleColor = bar.LabelColor = [0, 0, 0]
    tdisp.WindowLocation = "Upper Left Corner"
    view.InteractionMode = "2D"
    pv.ResetCamera(view)
    # the flume fills the picture: half its height, or of its length over the picture's aspect ratio
    x0, x1, y0, y1, _, _ = fields.GetDataInformation().GetBounds()
    view.CameraParallelScale = 0.52 * max(y1 - y0, (x1 - x0) * 420 / 1600)
    if args.show:
        pv.Interact(view)
        return
    png = args.png or run_dir / "paraview.png"
    pv.SaveScreenshot(str(png), view, ImageResolution=[1600, 420], TransparentBackground=0)
    print(f"wrote {png} (t = {t:.2f} s)")


if __name__ == "__main__":
    main()
