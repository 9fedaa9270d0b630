"""Area of the plane sections of a tet mesh, by VTK's vtkCutter: the independent
reference for the cut engine's boundary-area check (tests/cut_vtk.rs).

usage: /usr/bin/python3 cut_section_area.py MESH_BASE PLANES_JSON
  MESH_BASE    path of a TetGen pair without extension (MESH_BASE.node, MESH_BASE.ele)
  PLANES_JSON  [[ox, oy, oz, nx, ny, nz], ...]
prints {"areas": [...]}: the area of each plane's section of the mesh.
"""

import json
import os
import sys

import vtk

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from cut_common import read_tetgen  # noqa: E402


def section_area(grid, plane):
    p = vtk.vtkPlane()
    p.SetOrigin(*plane[:3])
    p.SetNormal(*plane[3:])
    cutter = vtk.vtkCutter()
    cutter.SetInputData(grid)
    cutter.SetCutFunction(p)
    tri = vtk.vtkTriangleFilter()
    tri.SetInputConnection(cutter.GetOutputPort())
    tri.Update()
    out = tri.GetOutput()
    area = 0.0
    for c in range(out.GetNumberOfCells()):
        cell = out.GetCell(c)
        if cell.GetNumberOfPoints() == 3:
            pts = cell.GetPoints()
            area += vtk.vtkTriangle.TriangleArea(pts.GetPoint(0), pts.GetPoint(1), pts.GetPoint(2))
    return area


def main():
    grid = read_tetgen(sys.argv[1])
    planes = json.loads(sys.argv[2])
    print(json.dumps({"areas": [section_area(grid, pl) for pl in planes]}))


if __name__ == "__main__":
    main()
