#!/usr/bin/python3
"""VTK's side of mtcut's .vtu cross-checks (run with VTK's Python: /usr/bin/python3).

  vtu_tool.py dump IN.vtu OUTDIR [IN.vtu OUTDIR ...]
      Read each file with vtkXMLUnstructuredGridReader and dump what VTK holds, exactly:
      points.f64 (float64, little-endian), connectivity.i64, offsets.i64 (end offsets),
      types.u8, one .f64 file per point/cell data array, and manifest.json.

  vtu_tool.py write NODE ELE OUTDIR MODE [MODE ...]
      Build an unstructured grid from a TetGen .node/.ele pair (ids as in the files,
      0- or 1-based), add point and cell data arrays of many VTK types, write it with
      vtkXMLUnstructuredGridWriter once per MODE as OUTDIR/MODE.vtu, read it back with
      VTK's reader and dump that (as above) into OUTDIR/MODE.dump/.

Modes: 'default' (VTK's own defaults: appended, base64-encoded, zlib, UInt32 headers),
'raw-zlib' (appended raw + zlib: ParaView's default), 'raw-none', 'raw-lz4', 'raw-lzma',
'raw-zlib-uint64', 'raw-zlib-float32' (Float32 points), 'raw-zlib-bigendian',
'binary-zlib' (inline base64), 'binary-none', 'base64-none' (appended base64), 'ascii'.
"""
import json
import os
import sys

import numpy as np
import vtk
from vtk.util import numpy_support as ns


def dump(grid, outdir):
    os.makedirs(outdir, exist_ok=True)
    pts = ns.vtk_to_numpy(grid.GetPoints().GetData())
    np.asarray(pts, dtype="<f8").tofile(os.path.join(outdir, "points.f64"))
    cells = grid.GetCells()
    conn = ns.vtk_to_numpy(cells.GetConnectivityArray())
    offs = ns.vtk_to_numpy(cells.GetOffsetsArray())[1:]
    np.asarray(conn, dtype="<i8").tofile(os.path.join(outdir, "connectivity.i64"))
    np.asarray(offs, dtype="<i8").tofile(os.path.join(outdir, "offsets.i64"))
    types = ns.vtk_to_numpy(grid.GetCellTypesArray())
    np.asarray(types, dtype="u1").tofile(os.path.join(outdir, "types.u8"))
    manifest = {
        "n_points": grid.GetNumberOfPoints(),
        "n_cells": grid.GetNumberOfCells(),
        "points_type": grid.GetPoints().GetData().GetDataTypeAsString(),
    }
    for key, data in (("point_data", grid.GetPointData()), ("cell_data", grid.GetCellData())):
        arrays = []
        for i in range(data.GetNumberOfArrays()):
            a = data.GetAbstractArray(i)
            fname = "%s_%d.f64" % (key, i)
            np.asarray(ns.vtk_to_numpy(a), dtype="<f8").reshape(-1).tofile(
                os.path.join(outdir, fname))
            arrays.append({
                "name": a.GetName(),
                "components": a.GetNumberOfComponents(),
                "type": a.GetDataTypeAsString(),
                "file": fname,
            })
        manifest[key] = arrays
    with open(os.path.join(outdir, "manifest.json"), "w") as f:
        json.dump(manifest, f)


def read_vtu(path):
    r = vtk.vtkXMLUnstructuredGridReader()
    r.SetFileName(path)
    r.Update()
    if r.GetErrorCode() != 0:
        raise SystemExit("VTK could not read %s (error code %d)" % (path, r.GetErrorCode()))
    g = r.GetOutput()
    if g.GetNumberOfCells() == 0:
        raise SystemExit("VTK read no cells from %s" % path)
    return g


def read_tetgen(node, ele):
    def rows(path):
        with open(path) as f:
            lines = [l.split("#")[0].split() for l in f]
        return [l for l in lines if l]
    nrows = rows(node)
    n = int(nrows[0][0])
    first = int(nrows[1][0])
    pts = np.array([[float(x) for x in r[1:4]] for r in nrows[1:1 + n]], dtype="f8")
    erows = rows(ele)
    m = int(erows[0][0])
    tets = np.array([[int(x) - first for x in r[1:5]] for r in erows[1:1 + m]], dtype="i8")
    return pts, tets


def arr(values, vtk_type, name, comps):
    a = ns.numpy_to_vtk(np.ascontiguousarray(values), deep=1, array_type=vtk_type)
    a.SetName(name)
    a.SetNumberOfComponents(comps)
    return a


def build(node, ele, float32_points=False):
    pts, tets = read_tetgen(node, ele)
    n, m = len(pts), len(tets)
    g = vtk.vtkUnstructuredGrid()
    points = vtk.vtkPoints()
    if float32_points:
        points.SetData(ns.numpy_to_vtk(pts.astype("f4"), deep=1))
    else:
        points.SetData(ns.numpy_to_vtk(pts, deep=1))
    g.SetPoints(points)
    ca = vtk.vtkCellArray()
    offsets = np.arange(0, 4 * m + 1, 4, dtype="i8")
    ca.SetData(ns.numpy_to_vtk(offsets, deep=1, array_type=vtk.VTK_ID_TYPE),
               ns.numpy_to_vtk(tets.reshape(-1), deep=1, array_type=vtk.VTK_ID_TYPE))
    g.SetCells(vtk.VTK_TETRA, ca)
    x, y, z = pts[:, 0], pts[:, 1], pts[:, 2]
    pd, cd = g.GetPointData(), g.GetCellData()
    pd.AddArray(arr(x + 2 * y - z / 3, vtk.VTK_DOUBLE, "temperature", 1))
    pd.AddArray(arr(np.stack([y, -x, z * 1e3], 1).astype("f4"), vtk.VTK_FLOAT, "velocity", 3))
    pd.AddArray(arr((np.arange(n) * 7919) % 100003 - 50000, vtk.VTK_INT, "label", 1))
    pd.AddArray(arr(np.arange(n, dtype="u2") % 65535, vtk.VTK_UNSIGNED_SHORT, "u16", 1))
    pd.AddArray(arr(np.sin(np.arange(9 * n, dtype="f8")).reshape(n, 9), vtk.VTK_DOUBLE,
                    "tensor", 9))
    cd.AddArray(arr(np.arange(m, dtype="i2") % 300 - 150, vtk.VTK_SHORT, "region", 1))
    cd.AddArray(arr(np.cos(np.arange(m, dtype="f8")), vtk.VTK_DOUBLE, "quality", 1))
    cd.AddArray(arr((np.arange(2 * m) % 256).astype("u1").reshape(m, 2),
                    vtk.VTK_UNSIGNED_CHAR, "flags", 2))
    cd.AddArray(arr(np.arange(m, dtype="i8") * 1000003 - 2 ** 40, vtk.VTK_LONG_LONG, "big", 1))
    cd.AddArray(arr(np.arange(m, dtype="i1") % 100 - 50, vtk.VTK_SIGNED_CHAR, "i8", 1))
    cd.AddArray(arr(np.arange(m, dtype="u4") * 3, vtk.VTK_UNSIGNED_INT, "u32", 1))
    cd.AddArray(arr(np.arange(m, dtype="u8") * 5, vtk.VTK_UNSIGNED_LONG_LONG, "u64", 1))
    return g


def configure(w, mode):
    if mode == "default":
        return
    if mode == "ascii":
        w.SetDataModeToAscii()
        return
    kind, comp = mode.split("-")[:2]
    if kind == "raw":
        w.SetDataModeToAppended()
        w.EncodeAppendedDataOff()
    elif kind == "binary":
        w.SetDataModeToBinary()
    elif kind == "base64":
        w.SetDataModeToAppended()
        w.EncodeAppendedDataOn()
    else:
        raise SystemExit("unknown mode " + mode)
    {"zlib": w.SetCompressorTypeToZLib, "lz4": w.SetCompressorTypeToLZ4,
     "lzma": w.SetCompressorTypeToLZMA, "none": w.SetCompressorTypeToNone}[comp]()
    if mode.endswith("-uint64"):
        w.SetHeaderTypeToUInt64()
    if mode.endswith("-bigendian"):
        w.SetByteOrderToBigEndian()


def main(argv):
    if len(argv) >= 3 and argv[0] == "dump" and len(argv) % 2 == 1:
        for i in range(1, len(argv), 2):
            dump(read_vtu(argv[i]), argv[i + 1])
    elif len(argv) >= 5 and argv[0] == "write":
        node, ele, outdir = argv[1:4]
        os.makedirs(outdir, exist_ok=True)
        for mode in argv[4:]:
            g = build(node, ele, float32_points=mode.endswith("-float32"))
            w = vtk.vtkXMLUnstructuredGridWriter()
            w.SetInputData(g)
            path = os.path.join(outdir, mode + ".vtu")
            w.SetFileName(path)
            configure(w, mode)
            if w.Write() != 1:
                raise SystemExit("VTK could not write " + path)
            # What VTK reads back from its own file (its ASCII writer, for one, writes
            # -0.0 as "0"): the reference mtcut's reading must match.
            dump(read_vtu(path), os.path.join(outdir, mode + ".dump"))
    else:
        sys.stderr.write(__doc__)
        return 2
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
