#!/usr/bin/python3
"""A dense unstructured mesh for bench/surface_splats.sh: the hexahedra of an N^3 grid whose
centres lie within a ball (a voxelized sphere, VTK's vtkThreshold over a distance field), with
the point field "d" (distance from the centre) and "x" (the x coordinate), written as .vtu by
VTK's own writer. Its boundary (the staircase sphere) has about 7 N^2 quads.
    /usr/bin/python3 bench/sphere_mesh.py N out.vtu
"""
import sys

import vtk


def main():
    n, out = int(sys.argv[1]), sys.argv[2]
    img = vtk.vtkImageData()
    img.SetDimensions(n + 1, n + 1, n + 1)
    img.SetSpacing(1.0 / n, 1.0 / n, 1.0 / n)
    c = 0.5
    d = vtk.vtkFloatArray()
    d.SetName("d")
    x = vtk.vtkFloatArray()
    x.SetName("x")
    for k in range(n + 1):
        for j in range(n + 1):
            for i in range(n + 1):
                px, py, pz = i / n, j / n, k / n
                d.InsertNextValue(((px - c) ** 2 + (py - c) ** 2 + (pz - c) ** 2) ** 0.5)
                x.InsertNextValue(px)
    img.GetPointData().AddArray(d)
    img.GetPointData().AddArray(x)
    img.GetPointData().SetActiveScalars("d")
    # Cells whose every point lies within the ball.
    th = vtk.vtkThreshold()
    th.SetInputData(img)
    th.SetInputArrayToProcess(0, 0, 0, vtk.vtkDataObject.FIELD_ASSOCIATION_POINTS, "d")
    th.SetLowerThreshold(0.0)
    th.SetUpperThreshold(0.45)
    th.SetThresholdFunction(vtk.vtkThreshold.THRESHOLD_BETWEEN)
    th.AllScalarsOn()
    th.Update()
    w = vtk.vtkXMLUnstructuredGridWriter()
    w.SetFileName(out)
    w.SetInputData(th.GetOutput())
    w.SetDataModeToAppended()
    w.EncodeAppendedDataOff()
    w.Write()
    print(f"{out}: {th.GetOutput().GetNumberOfCells()} cells")


if __name__ == "__main__":
    main()
