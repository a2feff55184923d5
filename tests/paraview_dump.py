"""Run by ParaView's pvbatch (tests/test_paraview.py): reads a run's XDMF file with one of ParaView's
XDMF readers and saves every time step's arrays to an .npz for the test to compare with the HDF5 file.

    pvbatch paraview_dump.py RUN.xmf OUT_PREFIX READER [READER ...]

READER: XDMFReader (XDMF 2 library), Xdmf3ReaderS or Xdmf3ReaderT; each writes OUT_PREFIX<READER>.npz
with the keys 'times', '<block>/<step>/<cell|point>/<array>', '<block>/<step>/points' and (polygons)
'<block>/<step>/cell_types', '.../offsets', '.../connectivity' for each block of each step (block:
'fields', 'stones' or 'stone_polygons')."""
import sys

import numpy as np
from paraview import servermanager as sm
from paraview import simple
from vtkmodules.util.numpy_support import vtk_to_numpy


def blocks(data):
    """The leaf data sets of a reader's output."""
    if data.IsA("vtkDataSet"):
        return [data]
    it = data.NewIterator()
    it.InitTraversal()
    out = []
    while not it.IsDoneWithTraversal():
        out.append(it.GetCurrentDataObject())
        it.GoToNextItem()
    return out


def name_of(ds):
    """'fields' for the grid (its cells carry the water fraction F), 'stone_polygons' for the polygon
    stones (their cells carry the angle), 'stones' for the point cloud."""
    if ds.GetCellData().GetArray("F") is not None:
        return "fields"
    return "stone_polygons" if ds.GetCellData().GetArray("angle") is not None else "stones"


def cells_of(ds, b, k, saved):
    """The polygons as ParaView holds them: VTK cell types, offsets and connectivity."""
    cells = ds.GetCells()
    saved[f"{b}/{k}/cell_types"] = np.array([ds.GetCellType(c) for c in range(ds.GetNumberOfCells())])
    saved[f"{b}/{k}/offsets"] = vtk_to_numpy(cells.GetOffsetsArray()).copy()
    saved[f"{b}/{k}/connectivity"] = vtk_to_numpy(cells.GetConnectivityArray()).copy()


def main(xmf, reader, out):
    if reader == "XDMFReader":
        r = simple.XDMFReader(FileNames=[xmf])
    else:
        r = getattr(simple, reader)(FileName=[xmf])
    times = list(r.TimestepValues)
    saved = {"times": np.array(times, float)}
    for k, t in enumerate(times):
        r.UpdatePipeline(t)
        for ds in blocks(sm.Fetch(r)):
            b = name_of(ds)
            saved[f"{b}/{k}/points"] = vtk_to_numpy(ds.GetPoints().GetData()).copy()
            if b == "stone_polygons":
                cells_of(ds, b, k, saved)
            for kind, arrays in (("cell", ds.GetCellData()), ("point", ds.GetPointData())):
                for i in range(arrays.GetNumberOfArrays()):
                    a = arrays.GetArray(i)
                    saved[f"{b}/{k}/{kind}/{a.GetName()}"] = vtk_to_numpy(a).copy()
    np.savez(out, **saved)
    print(f"{reader}: {len(times)} time steps saved to {out}")


if __name__ == "__main__":
    for name in sys.argv[3:]:
        main(sys.argv[1], name, f"{sys.argv[2]}{name}.npz")
