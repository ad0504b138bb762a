#!/usr/bin/python3
"""A curvilinear test case for the structured-grid readers' benchmark (bench/voxelize_vtk.py):
a flared, twisted channel (no face planar, cells shrinking towards the wall), N x N/2 x N/2
points, written as a .vts series (VTK's writer) and as PLOT3D (grid.xyz + flow_T.q, double
precision, Fortran records), steps t = 0..STEPS-1. The field is smooth but not linear, so
interpolation differences show:
    f = sin(3x) cos(2y) + z^2 + 0.3 t,  density = 1 + 0.5 f,  momentum = (y, -x, z t).
    /usr/bin/python3 bench/make_curvilinear.py OUT_DIR [N=64] [STEPS=2]
"""
import os
import sys

import numpy as np
import vtk
from vtk.util import numpy_support as ns


def points(n):
    ni, nj, nk = n, n // 2, n // 2
    k, j, i = np.meshgrid(np.linspace(0, 1, nk), np.linspace(0, 1, nj) ** 1.5,
                          np.linspace(0, 1, ni), indexing="ij")
    flare = 1 + 0.6 * i
    twist = 0.5 * i
    r = 0.3 + j * flare
    a = np.pi * (k - 0.5) + twist
    return np.stack([2 * i, r * np.cos(a), r * np.sin(a)], axis=-1), (ni, nj, nk)


def main():
    out = sys.argv[1]
    n = int(sys.argv[2]) if len(sys.argv) > 2 else 64
    steps = int(sys.argv[3]) if len(sys.argv) > 3 else 2
    os.makedirs(out, exist_ok=True)
    p, (ni, nj, nk) = points(n)
    flat = p.reshape(-1, 3)
    x, y, z = flat[:, 0], flat[:, 1], flat[:, 2]
    rec = lambda f, b: f.write(np.array([len(b)], "<i4").tobytes() + b +
                               np.array([len(b)], "<i4").tobytes())
    with open(os.path.join(out, "grid.xyz"), "wb") as f:
        rec(f, np.array([ni, nj, nk], "<i4").tobytes())
        rec(f, b"".join(flat[:, a].astype("<f8").tobytes() for a in range(3)))
    for t in range(steps):
        fval = np.sin(3 * x) * np.cos(2 * y) + z * z + 0.3 * t
        sg = vtk.vtkStructuredGrid()
        sg.SetDimensions(ni, nj, nk)
        pts = vtk.vtkPoints()
        pts.SetData(ns.numpy_to_vtk(flat.astype(np.float64), deep=True))
        sg.SetPoints(pts)
        arr = ns.numpy_to_vtk(fval.astype(np.float32), deep=True)
        arr.SetName("f")
        sg.GetPointData().AddArray(arr)
        w = vtk.vtkXMLStructuredGridWriter()
        w.SetFileName(os.path.join(out, "channel_%d.vts" % t))
        w.SetInputData(sg)
        w.Write()
        q = [1 + 0.5 * fval, y, -x, z * t, 2.5 + fval]
        with open(os.path.join(out, "flow_%d.q" % t), "wb") as f:
            rec(f, np.array([ni, nj, nk], "<i4").tobytes())
            rec(f, np.array([0.5, 0.0, 1e4, float(t)], "<f8").tobytes())
            rec(f, b"".join(v.astype("<f8").tobytes() for v in q))


if __name__ == "__main__":
    main()
