"""ParaView opens what mtcut writes: each file is read with ParaView's own readers, its
cell and point counts and its point and cell array names are compared with the
expectations, and a screenshot is saved (Surface With Edges; the pieces of a cut mesh
pulled apart so the cut shows).

    pvbatch scripts/pvbatch-check.py --screenshots DIR FILE[=EXPECT.json] ...

FILE is a .vtu or a .pvd. The expectations come from EXPECT.json, by default FILE.json
(the sidecars the C examples write from mtcut's numbers): {"points": N, "cells": N,
"point_arrays": [...], "cell_arrays": [...]}; any key may be left out. A file without
expectations (a .pvd from the demo) is checked to hold at least one tet, with the same
arrays in every step. Exits 1 naming the first difference. Run by scripts/test-c-api.sh
(which finds pvbatch and ParaView's Python package, DESIGN.md section 8).
"""
import json
import os
import sys

from paraview import simple as pv


def arrays(source):
    info = source.GetDataInformation()
    point = sorted(source.PointData.keys())
    cell = sorted(source.CellData.keys())
    return info.GetNumberOfPoints(), info.GetNumberOfCells(), point, cell


def check(path, want):
    reader = pv.OpenDataFile(path)
    if reader is None:
        raise SystemExit(f"{path}: ParaView has no reader for it")
    reader.UpdatePipeline()
    points, cells, point_arrays, cell_arrays = arrays(reader)
    got = {"points": points, "cells": cells, "point_arrays": point_arrays, "cell_arrays": cell_arrays}
    for key, value in want.items():
        if key not in got:
            continue
        expected = sorted(value) if isinstance(value, list) else value
        if got[key] != expected:
            raise SystemExit(f"{path}: ParaView reads {key} = {got[key]}, expected {expected}")
    if cells == 0:
        raise SystemExit(f"{path}: ParaView reads no cells")
    if path.endswith(".pvd"):
        times = list(reader.TimestepValues or [])
        for t in times:
            reader.UpdatePipeline(t)
            if arrays(reader)[2:] != (point_arrays, cell_arrays):
                raise SystemExit(f"{path}: step {t} has other arrays than the first")
        if times:
            reader.UpdatePipeline(times[0])  # the screenshot shows the first step
        print(f"{path}: {len(times)} steps")
    print(f"{path}: ParaView reads {points} points, {cells} cells, point arrays {point_arrays}, "
          f"cell arrays {cell_arrays}" + (" (as expected)" if want else ""))
    return reader, cell_arrays


def screenshot(reader, cell_arrays, out):
    view = pv.CreateRenderView()
    view.ViewSize = [480, 360]
    view.OrientationAxesVisibility = 0
    view.Background = [1, 1, 1]
    try:
        view.UseColorPaletteForBackground = 0
    except AttributeError:
        pass
    # The pieces of a cut mesh, each pulled away from the middle by half its offset, so
    # that the cut surfaces show.
    regions = pv.Connectivity(Input=reader)
    regions.UpdatePipeline()
    count = int(regions.CellData["RegionId"].GetRange()[1]) + 1
    bounds = reader.GetDataInformation().GetBounds()
    middle = [(bounds[2 * k] + bounds[2 * k + 1]) / 2 for k in range(3)]
    preferred = [a for a in ("mtcut:cut", "mt_level") if a in cell_arrays]
    color = (preferred + cell_arrays + [None])[0]
    for region in range(min(count, 8)):
        piece = pv.Threshold(Input=regions, Scalars=["CELLS", "RegionId"])
        piece.LowerThreshold = region
        piece.UpperThreshold = region
        piece.UpdatePipeline()
        b = piece.GetDataInformation().GetBounds()
        shift = [0.5 * ((b[2 * k] + b[2 * k + 1]) / 2 - middle[k]) if count > 1 else 0 for k in range(3)]
        moved = pv.Transform(Input=piece)
        moved.Transform.Translate = shift
        display = pv.Show(moved, view)
        display.SetRepresentationType("Surface With Edges")
        if color:
            pv.ColorBy(display, ("CELLS", color))
    view.ResetCamera()
    camera = view.GetActiveCamera()
    camera.Azimuth(35)
    camera.Elevation(25)
    view.ResetCamera()
    pv.SaveScreenshot(out, view, ImageResolution=[480, 360])
    pv.Delete(view)
    print(f"  screenshot {out} ({count} piece(s))")


def main(argv):
    if len(argv) < 3 or argv[0] != "--screenshots":
        raise SystemExit(__doc__)
    directory = argv[1]
    os.makedirs(directory, exist_ok=True)
    for item in argv[2:]:
        path, _, expect = item.partition("=")
        expect = expect or path + ".json"
        want = {}
        if os.path.exists(expect):
            with open(expect) as f:
                want = json.load(f)
        elif item.find("=") >= 0:
            raise SystemExit(f"{expect}: no such file")
        reader, cell_arrays = check(path, want)
        name = os.path.splitext(os.path.basename(path))[0] + ".png"
        screenshot(reader, cell_arrays, os.path.join(directory, name))
    print("ParaView check passed")


main(sys.argv[1:])
