"""Writes c-examples/data/box.vtu, the input of the VTK example: a 2 x 1 x 1 box as a
6 x 4 x 4-point grid split into tets by VTK (vtkDataSetTriangleFilter), with point data
(a scalar "temperature", a 3-vector "displacement") and cell data (an integer
"material"), written by VTK's own XML writer with its defaults (appended raw binary,
zlib-compressed) -- the kind of file a VTK-based host hands to mtcut. Run once; the file
is committed.

Usage: /usr/bin/python3 scripts/vtk/make_c_example_input.py c-examples/data/box.vtu
"""
import sys

import vtk

image = vtk.vtkImageData()
image.SetDimensions(6, 4, 4)
image.SetSpacing(0.4, 1.0 / 3.0, 1.0 / 3.0)
tets = vtk.vtkDataSetTriangleFilter()
tets.SetInputData(image)
tets.Update()
grid = tets.GetOutput()

temperature = vtk.vtkFloatArray()
temperature.SetName("temperature")
displacement = vtk.vtkDoubleArray()
displacement.SetName("displacement")
displacement.SetNumberOfComponents(3)
for i in range(grid.GetNumberOfPoints()):
    x, y, z = grid.GetPoint(i)
    temperature.InsertNextValue(20.0 + 40.0 * x)
    displacement.InsertNextTuple3(0.0, 0.0, -0.01 * x * x)
grid.GetPointData().AddArray(temperature)
grid.GetPointData().AddArray(displacement)

material = vtk.vtkIntArray()
material.SetName("material")
for c in range(grid.GetNumberOfCells()):
    material.InsertNextValue(1 if grid.GetCell(c).GetBounds()[0] < 1.0 else 2)
grid.GetCellData().AddArray(material)

writer = vtk.vtkXMLUnstructuredGridWriter()
writer.SetFileName(sys.argv[1])
writer.SetInputData(grid)
assert writer.Write() == 1
print(f"{sys.argv[1]}: {grid.GetNumberOfPoints()} points, {grid.GetNumberOfCells()} cells")
