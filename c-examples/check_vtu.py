"""Reads .vtu files with VTK's own reader and compares them with what mtcut reported
when it wrote them (the sidecar FILE.vtu.json the examples write): point and cell counts,
every cell a tetrahedron, the total volume (computed by VTK), the point and cell array
names. Run by ctest with VTK's Python (/usr/bin/python3 with python3-vtk9):

    python3 check_vtu.py FILE.vtu [FILE.vtu...]

Exits 1 naming the first difference.
"""
import json
import sys

import vtk


def check(path):
    with open(path + ".json") as f:
        want = json.load(f)
    reader = vtk.vtkXMLUnstructuredGridReader()
    reader.SetFileName(path)
    reader.Update()
    if reader.GetErrorCode() != 0:
        raise SystemExit(f"{path}: VTK cannot read it")
    grid = reader.GetOutput()
    got_points, got_cells = grid.GetNumberOfPoints(), grid.GetNumberOfCells()
    if (got_points, got_cells) != (want["points"], want["cells"]):
        raise SystemExit(
            f"{path}: VTK reads {got_points} points and {got_cells} cells, "
            f"mtcut wrote {want['points']} and {want['cells']}"
        )
    volume = 0.0
    points = grid.GetPoints()
    ids = vtk.vtkIdList()
    corners = [[0.0] * 3 for _ in range(4)]
    for c in range(got_cells):
        if grid.GetCellType(c) != vtk.VTK_TETRA:
            raise SystemExit(f"{path}: cell {c} has VTK type {grid.GetCellType(c)}, not a tetrahedron")
        grid.GetCellPoints(c, ids)
        for k in range(4):
            points.GetPoint(ids.GetId(k), corners[k])
        volume += vtk.vtkTetra.ComputeVolume(*corners)
    if abs(volume - want["volume"]) > 1e-9 * abs(want["volume"]):
        raise SystemExit(f"{path}: volume by VTK {volume!r}, by mtcut {want['volume']!r}")
    for key, data in (("point_arrays", grid.GetPointData()), ("cell_arrays", grid.GetCellData())):
        names = sorted(data.GetArrayName(i) for i in range(data.GetNumberOfArrays()))
        if names != sorted(want[key]):
            raise SystemExit(f"{path}: {key} {names}, mtcut wrote {sorted(want[key])}")
    print(f"{path}: {got_points} points, {got_cells} tets, volume {volume:.9g}, arrays as written")


for p in sys.argv[1:]:
    check(p)
