"""VTK's reference for the cut benchmark (benches/cut_vs_vtk.rs): clip a tet mesh by a
plane with vtkTableBasedClipDataSet, both sides (GenerateClippedOutput on), timed here
around Update() only (the mesh is read and converted before timing).

usage: /usr/bin/python3 cut_vtk_clip.py MESH_BASE OX OY OZ NX NY NZ REPETITIONS
prints JSON: median and minimum time of one clip in milliseconds, the cells on each side,
the cells the plane crosses, and the VTK version.
"""

import json
import os
import statistics
import sys
import time

import numpy as np
import vtk
from vtk.util.numpy_support import vtk_to_numpy

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from cut_common import read_tetgen  # noqa: E402


def main():
    base = sys.argv[1]
    origin = [float(x) for x in sys.argv[2:5]]
    normal = [float(x) for x in sys.argv[5:8]]
    reps = int(sys.argv[8])
    t0 = time.perf_counter()
    grid = read_tetgen(base)
    load_s = time.perf_counter() - t0
    plane = vtk.vtkPlane()
    plane.SetOrigin(*origin)
    plane.SetNormal(*normal)
    clip = vtk.vtkTableBasedClipDataSet()
    clip.SetInputData(grid)
    clip.SetClipFunction(plane)
    clip.GenerateClippedOutputOn()
    times = []
    for _ in range(reps):
        clip.Modified()
        t = time.perf_counter()
        clip.Update()
        times.append(time.perf_counter() - t)
    pts = vtk_to_numpy(grid.GetPoints().GetData())
    d = (pts - np.array(origin)) @ np.array(normal)
    conn = vtk_to_numpy(grid.GetCells().GetConnectivityArray()).reshape(-1, 4)
    s = np.sign(d[conn])
    crossed = int(((s.max(axis=1) > 0) & (s.min(axis=1) < 0)).sum())
    print(
        json.dumps(
            {
                "median_ms": statistics.median(times) * 1e3,
                "min_ms": min(times) * 1e3,
                "cells_kept": clip.GetOutput().GetNumberOfCells(),
                "cells_clipped": clip.GetClippedOutput().GetNumberOfCells(),
                "cells_crossed": crossed,
                "load_s": load_s,
                "vtk_version": vtk.vtkVersion.GetVTKVersion(),
            }
        )
    )


if __name__ == "__main__":
    main()
