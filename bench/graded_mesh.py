#!/usr/bin/python3
"""A graded hexahedral mesh for bench/adaptive_octree.sh (issue 31 item 1): an N^3 grid of
hexahedra over [0, 1]^3 whose central 2^3 cells are each split into R^3 (the finest cells are
1/(N R) across, as a CFD mesh refined around an obstacle), with the point field "f", a
Gaussian (sigma = SIGMA, default 1/200: about 0 outside the refined block) that drifts along x
over the steps from CENTER (default: the block's centre, 0.5,0.5,0.5).
Written as STEPS .vtu files and a .vtu.series by VTK's own writer (hanging nodes at the block's
faces: the voxelizer samples cells, not a conforming mesh).
    /usr/bin/python3 bench/graded_mesh.py N R STEPS out_dir [SIGMA [CX,CY,CZ]]
"""
import json
import os
import sys

import numpy as np
import vtk
from vtk.util import numpy_support as ns

SIGMA = 1.0 / 200


def hexes(lo, h, n):
    """Points and VTK hexahedra of an n^3 block of cells of edge h from corner lo."""
    i = np.arange(n + 1)
    z, y, x = np.meshgrid(i, i, i, indexing="ij")
    pts = np.stack([lo[0] + x * h, lo[1] + y * h, lo[2] + z * h], axis=-1).reshape(-1, 3)
    idx = np.arange((n + 1) ** 3).reshape(n + 1, n + 1, n + 1)  # [z, y, x]
    c = idx[:-1, :-1, :-1]
    cells = np.stack([c, c + 1, c + 1 + (n + 1), c + (n + 1),
                      c + (n + 1) ** 2, c + 1 + (n + 1) ** 2, c + 1 + (n + 1) + (n + 1) ** 2,
                      c + (n + 1) + (n + 1) ** 2], axis=-1).reshape(-1, 8)
    return pts, cells


def main():
    n, r, steps, out = int(sys.argv[1]), int(sys.argv[2]), int(sys.argv[3]), sys.argv[4]
    sigma = float(sys.argv[5]) if len(sys.argv) > 5 else SIGMA
    centre = [float(v) for v in sys.argv[6].split(",")] if len(sys.argv) > 6 else [0.5] * 3
    os.makedirs(out, exist_ok=True)
    h = 1.0 / n
    lo_cell = n // 2 - 1  # the central 2^3 cells
    pts, cells = hexes((0, 0, 0), h, n)
    # Drop the coarse cells of the refined block.
    k = np.arange(n)
    z, y, x = np.meshgrid(k, k, k, indexing="ij")
    inside = ((x >= lo_cell) & (x < lo_cell + 2) & (y >= lo_cell) & (y < lo_cell + 2) &
              (z >= lo_cell) & (z < lo_cell + 2)).reshape(-1)
    cells = cells[~inside]
    fine_pts, fine_cells = hexes((lo_cell * h,) * 3, h / r, 2 * r)
    fine_cells = fine_cells + len(pts)
    pts = np.concatenate([pts, fine_pts])
    cells = np.concatenate([cells, fine_cells])
    grid = vtk.vtkUnstructuredGrid()
    vp = vtk.vtkPoints()
    vp.SetData(ns.numpy_to_vtk(pts.astype(np.float64), deep=True))
    grid.SetPoints(vp)
    conn = np.hstack([np.full((len(cells), 1), 8), cells]).astype(np.int64).ravel()
    ca = vtk.vtkCellArray()
    ca.SetCells(len(cells), ns.numpy_to_vtkIdTypeArray(conn, deep=True))
    grid.SetCells(vtk.VTK_HEXAHEDRON, ca)
    files = []
    for t in range(steps):
        c = np.array([centre[0] + 0.002 * t, centre[1], centre[2]])
        f = np.exp(-np.sum((pts - c) ** 2, axis=1) / (2 * sigma ** 2)).astype(np.float32)
        arr = ns.numpy_to_vtk(f, deep=True)
        arr.SetName("f")
        grid.GetPointData().RemoveArray("f")
        grid.GetPointData().AddArray(arr)
        name = "graded_%d.vtu" % t
        w = vtk.vtkXMLUnstructuredGridWriter()
        w.SetFileName(os.path.join(out, name))
        w.SetInputData(grid)
        w.SetDataModeToAppended()
        w.EncodeAppendedDataOff()
        w.Write()
        files.append({"name": name, "time": float(t)})
    with open(os.path.join(out, "graded.vtu.series"), "w") as s:
        json.dump({"file-series-version": "1.0", "files": files}, s)
    print("%d cells, %d points, finest cell 1/%d" % (len(cells), len(pts), n * r))


if __name__ == "__main__":
    main()
