#!/usr/bin/python3
"""VTK's side of benches/io_vs_vtk.rs (run with VTK's Python: /usr/bin/python3).

  bench_vtk.py IN.vtu OUT.vtu REPEATS

Loads IN.vtu (untimed), then times, REPEATS times each (the minimum is reported):
  write:        vtkXMLUnstructuredGridWriter in ParaView's default mode (appended raw
                binary, VTK's default zlib compression) to OUT.vtu;
  read:         vtkXMLUnstructuredGridReader on OUT.vtu (VTK reading its own file);
  read_ours:    vtkXMLUnstructuredGridReader on IN.vtu (VTK reading mtcut's file).
Times exclude interpreter start-up and imports. Prints one JSON object.
"""
import json
import os
import sys
import time

import vtk


def read(path):
    r = vtk.vtkXMLUnstructuredGridReader()
    r.SetFileName(path)
    r.Update()
    g = r.GetOutput()
    if r.GetErrorCode() != 0 or g.GetNumberOfCells() == 0:
        raise SystemExit("VTK could not read " + path)
    return g


def best(f, repeats):
    times = []
    for _ in range(repeats):
        t = time.perf_counter()
        f()
        times.append(time.perf_counter() - t)
    return min(times)


def main(src, dst, repeats):
    grid = read(src)

    def write():
        w = vtk.vtkXMLUnstructuredGridWriter()
        w.SetInputData(grid)
        w.SetFileName(dst)
        w.SetDataModeToAppended()
        w.EncodeAppendedDataOff()
        if w.Write() != 1:
            raise SystemExit("VTK could not write " + dst)

    out = {
        "vtk_version": vtk.vtkVersion.GetVTKVersion(),
        "tets": grid.GetNumberOfCells(),
        "write_s": best(write, repeats),
        "read_s": best(lambda: read(dst), repeats),
        "read_ours_s": best(lambda: read(src), repeats),
        "file_bytes": os.path.getsize(dst),
    }
    print(json.dumps(out))


if __name__ == "__main__":
    if len(sys.argv) != 4:
        sys.stderr.write(__doc__)
        sys.exit(2)
    main(sys.argv[1], sys.argv[2], int(sys.argv[3]))
