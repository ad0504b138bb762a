#!/usr/bin/python3
"""Curvilinear-grid fixtures (tests/data/structured/): .vts files written by VTK's own writer
(python3-vtk9) and PLOT3D files written here byte by byte, then read back by VTK's
vtkMultiBlockPLOT3DReader to prove VTK reads them as we mean them.

The grid is warped (no face is planar): point (i, j, k) of a 6 x 5 x 4 block sits at
    x = 0.5 i + 0.1 sin(0.7 j),  y = 0.4 j + 0.08 k,  z = 0.6 k + 0.05 i j.
.vts, steps t = 0, 1 (times 0.5 and 1.5 in warped.vts.series):
    point f = 1 + 2x + 3y - z + 10 t (Float32), point v = (x, y, z) (Float64),
    cell c = cell index + 100 t (Float32).
PLOT3D, the same grid:
    plot3d/grid.xyz: one block, double precision, Fortran records, little-endian;
    plot3d/flow_0.q, flow_1.q: times 0.5, 1.5; density rho = 1 + 0.1x + 0.2y + 0.3z + t,
    momentum (x, y, z), stagnation energy e = 2.5 + x.
    plot3d_multi/multi.xyz: two blocks (the grid, and the grid moved by +4 in x), single
    precision, no record markers, big-endian, IBLANK (block 1's points with i = 0 blanked);
    multi.q the same solution at t = 0; plot3d_multi/other.xyz a copy (two grids: ambiguous).
Run:
    /usr/bin/python3 tests/data/make_structured_fixtures.py
"""
import json
import os
import shutil

import numpy as np
import vtk
from vtk.util import numpy_support as ns

OUT = os.path.join(os.path.dirname(os.path.abspath(__file__)), "structured")
NI, NJ, NK = 6, 5, 4


def grid_points():
    """(NK, NJ, NI, 3) coordinates, i fastest."""
    k, j, i = np.meshgrid(np.arange(NK), np.arange(NJ), np.arange(NI), indexing="ij")
    x = 0.5 * i + 0.1 * np.sin(0.7 * j)
    y = 0.4 * j + 0.08 * k
    z = 0.6 * k + 0.05 * i * j
    return np.stack([x, y, z], axis=-1)


def write_vts(path, t):
    p = grid_points().reshape(-1, 3)
    sg = vtk.vtkStructuredGrid()
    sg.SetDimensions(NI, NJ, NK)
    pts = vtk.vtkPoints()
    pts.SetData(ns.numpy_to_vtk(p.astype(np.float64), deep=True))
    sg.SetPoints(pts)
    f = (1 + 2 * p[:, 0] + 3 * p[:, 1] - p[:, 2] + 10 * t).astype(np.float32)
    fa = ns.numpy_to_vtk(f, deep=True)
    fa.SetName("f")
    sg.GetPointData().AddArray(fa)
    va = ns.numpy_to_vtk(p.astype(np.float64), deep=True)
    va.SetName("v")
    sg.GetPointData().AddArray(va)
    ncell = (NI - 1) * (NJ - 1) * (NK - 1)
    ca = ns.numpy_to_vtk((np.arange(ncell) + 100 * t).astype(np.float32), deep=True)
    ca.SetName("c")
    sg.GetCellData().AddArray(ca)
    w = vtk.vtkXMLStructuredGridWriter()
    w.SetFileName(path)
    w.SetInputData(sg)
    w.SetDataModeToAppended()
    w.Write()


def solution(p, t):
    x, y, z = p[..., 0], p[..., 1], p[..., 2]
    rho = 1 + 0.1 * x + 0.2 * y + 0.3 * z + t
    return [rho, x, y, z, 2.5 + x]


def record(f, payload, endian):
    n = np.array([len(payload)], dtype=endian + "i4").tobytes()
    f.write(n + payload + n)


def write_plot3d(xyz, q, blocks, t, real, endian, records, multi, iblank):
    """blocks: list of (NK, NJ, NI, 3) arrays."""
    ints = endian + "i4"
    fl = endian + real
    def put(f, payload):
        if records:
            record(f, payload, endian)
        else:
            f.write(payload)
    with open(xyz, "wb") as f:
        if multi:
            put(f, np.array([len(blocks)], dtype=ints).tobytes())
        put(f, np.array([[NI, NJ, NK] for _ in blocks], dtype=ints).tobytes())
        for b, p in enumerate(blocks):
            data = b"".join(p[..., a].astype(fl).tobytes() for a in range(3))
            if iblank:
                ib = np.ones((NK, NJ, NI), dtype=ints)
                if b == 1:
                    ib[:, :, 0] = 0
                data += ib.tobytes()
            put(f, data)
    with open(q, "wb") as f:
        if multi:
            put(f, np.array([len(blocks)], dtype=ints).tobytes())
        put(f, np.array([[NI, NJ, NK] for _ in blocks], dtype=ints).tobytes())
        for p in blocks:
            put(f, np.array([0.8, 2.0, 1000.0, t], dtype=fl).tobytes())
            put(f, b"".join(v.astype(fl).tobytes() for v in solution(p, t)))


def vtk_check(xyz, q, real, endian, records, multi, iblank, blocks, t):
    r = vtk.vtkMultiBlockPLOT3DReader()
    r.SetXYZFileName(xyz)
    r.SetQFileName(q)
    r.SetBinaryFile(1)
    r.SetMultiGrid(1 if multi else 0)
    r.SetHasByteCount(1 if records else 0)
    r.SetIBlanking(1 if iblank else 0)
    r.SetTwoDimensionalGeometry(0)
    r.SetDoublePrecision(1 if real == "f8" else 0)
    if endian == ">":
        r.SetByteOrderToBigEndian()
    else:
        r.SetByteOrderToLittleEndian()
    r.Update()
    out = r.GetOutput()
    assert out.GetNumberOfBlocks() == len(blocks), (xyz, out.GetNumberOfBlocks())
    for b, p in enumerate(blocks):
        g = out.GetBlock(b)
        got = ns.vtk_to_numpy(g.GetPoints().GetData())
        assert np.allclose(got, p.reshape(-1, 3), atol=1e-6), xyz
        rho = ns.vtk_to_numpy(g.GetPointData().GetArray("Density"))
        assert np.allclose(rho, solution(p, t)[0].reshape(-1), atol=1e-6), q
        if r.GetOutput().GetBlock(b).GetPointData().GetArray("Momentum") is not None:
            m = ns.vtk_to_numpy(g.GetPointData().GetArray("Momentum"))
            assert np.allclose(m, p.reshape(-1, 3), atol=1e-6), q


def main():
    if os.path.isdir(OUT):
        shutil.rmtree(OUT)
    os.makedirs(os.path.join(OUT, "plot3d"))
    os.makedirs(os.path.join(OUT, "plot3d_multi"))
    for t in (0, 1):
        write_vts(os.path.join(OUT, "warped_%d.vts" % t), t)
    with open(os.path.join(OUT, "warped.vts.series"), "w") as f:
        json.dump({"file-series-version": "1.0",
                   "files": [{"name": "warped_0.vts", "time": 0.5},
                             {"name": "warped_1.vts", "time": 1.5}]}, f, indent=1)
    p = grid_points()
    d = os.path.join(OUT, "plot3d")
    for t, time in ((0, 0.5), (1, 1.5)):
        args = ("f8", "<", True, False, False)
        write_plot3d(os.path.join(d, "grid.xyz"), os.path.join(d, "flow_%d.q" % t), [p], time, *args)
        vtk_check(os.path.join(d, "grid.xyz"), os.path.join(d, "flow_%d.q" % t), *args, [p], time)
    d = os.path.join(OUT, "plot3d_multi")
    moved = p.copy()
    moved[..., 0] += 4
    args = ("f4", ">", False, True, True)
    write_plot3d(os.path.join(d, "multi.xyz"), os.path.join(d, "multi.q"), [p, moved], 0.0, *args)
    vtk_check(os.path.join(d, "multi.xyz"), os.path.join(d, "multi.q"), *args, [p, moved], 0.0)
    shutil.copy(os.path.join(d, "multi.xyz"), os.path.join(d, "other.xyz"))


if __name__ == "__main__":
    main()
