"""Shared helpers of the cut scripts: read a TetGen .node/.ele pair into a
vtkUnstructuredGrid of tetrahedra (numpy only, no TetGen reader in VTK)."""

import numpy as np
import vtk
from vtk.util.numpy_support import numpy_to_vtk, numpy_to_vtkIdTypeArray


def _numbers(path):
    """The non-comment content of a TetGen file as rows of tokens."""
    rows = []
    with open(path) as f:
        for line in f:
            line = line.split("#", 1)[0].split()
            if line:
                rows.append(line)
    return rows


def read_tetgen(base):
    """The tets of base.node/base.ele as a vtkUnstructuredGrid (VTK_TETRA)."""
    node = _numbers(base + ".node")
    n = int(node[0][0])
    pts = np.array([[float(x) for x in r[1:4]] for r in node[1 : 1 + n]])
    first_node = int(node[1][0])
    ele = _numbers(base + ".ele")
    m = int(ele[0][0])
    tets = np.array([[int(x) for x in r[1:5]] for r in ele[1 : 1 + m]], dtype=np.int64)
    tets -= first_node
    grid = vtk.vtkUnstructuredGrid()
    points = vtk.vtkPoints()
    points.SetData(numpy_to_vtk(pts, deep=1))
    grid.SetPoints(points)
    cells = np.hstack([np.full((m, 1), 4, dtype=np.int64), tets]).ravel()
    array = vtk.vtkCellArray()
    array.SetCells(m, numpy_to_vtkIdTypeArray(cells, deep=1))
    grid.SetCells(vtk.VTK_TETRA, array)
    return grid
