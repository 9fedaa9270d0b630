"""VTK's reference for the region-of-interest tests (tests/mt_roi.rs): the volume of a tet
mesh clipped to an axis-aligned box, by six successive vtkTableBasedClipDataSet clips with
the box's face planes (each linear, so exact up to rounding), tetrahedralized with
vtkDataSetTriangleFilter and summed with numpy.

usage: /usr/bin/python3 roi_box_clip.py MESH.vtu X0 Y0 Z0 X1 Y1 Z1
prints JSON: the clipped volume, its cells and the VTK version.
"""

import json
import sys

import numpy as np
import vtk
from vtk.util.numpy_support import vtk_to_numpy


def main():
    path = sys.argv[1]
    lo = [float(x) for x in sys.argv[2:5]]
    hi = [float(x) for x in sys.argv[5:8]]
    reader = vtk.vtkXMLUnstructuredGridReader()
    reader.SetFileName(path)
    reader.Update()
    data = reader.GetOutput()
    for axis in range(3):
        for value, keep_above in ((lo[axis], True), (hi[axis], False)):
            normal = [0.0, 0.0, 0.0]
            normal[axis] = 1.0
            origin = [0.0, 0.0, 0.0]
            origin[axis] = value
            plane = vtk.vtkPlane()
            plane.SetOrigin(*origin)
            plane.SetNormal(*normal)
            clip = vtk.vtkTableBasedClipDataSet()
            clip.SetInputData(data)
            clip.SetClipFunction(plane)
            # Kept by default: where the plane function is above 0.
            clip.SetInsideOut(not keep_above)
            clip.Update()
            data = clip.GetOutput()
    tets = vtk.vtkDataSetTriangleFilter()
    tets.SetInputData(data)
    tets.Update()
    grid = tets.GetOutput()
    volume = 0.0
    if grid.GetNumberOfCells() > 0:
        pts = vtk_to_numpy(grid.GetPoints().GetData())
        conn = vtk_to_numpy(grid.GetCells().GetConnectivityArray()).reshape(-1, 4)
        a, b, c, d = (pts[conn[:, k]] for k in range(4))
        volume = float(np.abs(np.einsum("ij,ij->i", b - a, np.cross(c - a, d - a))).sum() / 6.0)
    print(
        json.dumps(
            {
                "volume": volume,
                "cells": grid.GetNumberOfCells(),
                "vtk_version": vtk.vtkVersion.GetVTKVersion(),
            }
        )
    )


if __name__ == "__main__":
    main()
