"""Independent reference for `mtcut info`: tet count, volume and boundary-face count of a
TetGen mesh, computed with numpy (parsing) and VTK (volume, surface extraction) — code
that shares nothing with mtcut. Prints one JSON object.

Usage: /usr/bin/python3 info_reference.py MESH.node
"""
import json
import sys

import numpy as np
import vtk
from vtk.util import numpy_support


def rows(path):
    """Numeric rows of a TetGen file, comments and blank lines dropped."""
    out = []
    with open(path) as f:
        for line in f:
            line = line.split("#", 1)[0].split()
            if line:
                out.append(line)
    return out


def main():
    base = sys.argv[1].rsplit(".", 1)[0]
    node = rows(base + ".node")
    n = int(node[0][0])
    pts = np.array([[float(x) for x in r[1:4]] for r in node[1 : n + 1]])
    first_id = int(node[1][0])
    ele = rows(base + ".ele")
    m = int(ele[0][0])
    tets = np.array([[int(x) for x in r[1:5]] for r in ele[1 : m + 1]]) - first_id

    grid = vtk.vtkUnstructuredGrid()
    points = vtk.vtkPoints()
    points.SetData(numpy_support.numpy_to_vtk(pts, deep=True))
    grid.SetPoints(points)
    cells = vtk.vtkCellArray()
    conn = np.hstack([np.full((m, 1), 4), tets]).astype(np.int64).ravel()
    cells.SetCells(m, numpy_support.numpy_to_vtkIdTypeArray(conn, deep=True))
    grid.SetCells(vtk.VTK_TETRA, cells)

    sizes = vtk.vtkCellSizeFilter()
    sizes.SetInputData(grid)
    sizes.ComputeVolumeOn()
    sizes.Update()
    vol = numpy_support.vtk_to_numpy(sizes.GetOutput().GetCellData().GetArray("Volume"))

    surface = vtk.vtkDataSetSurfaceFilter()
    surface.SetInputData(grid)
    surface.Update()

    print(json.dumps({
        "tets": int(grid.GetNumberOfCells()),
        "volume": float(np.sum(vol)),
        "boundary_faces": int(surface.GetOutput().GetNumberOfCells()),
    }))


main()
