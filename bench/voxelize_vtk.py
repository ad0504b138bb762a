#!/usr/bin/python3
"""Voxelizer benchmark against VTK (python3-vtk9, the reference, not a dependency).

    /usr/bin/python3 bench/voxelize_vtk.py MESH.vtu|.vts|.q FIELD RESOLUTION [ROUNDS] [iso|tets|scanK|twoK|twoKj]

Runs build/voxelize_bench (our voxelizer) and VTK's vtkResampleToImage (probe filter: point
location in the mesh, interpolation by the cell's own functions) on the same mesh and grid in
the same run, and prints both throughputs, their ratio, and how far our values are from VTK's
where both find a voxel inside (max and mean difference as a share of the field's spread) and
how many voxels the two disagree on being inside.
"""
import json
import os
import statistics
import subprocess
import sys
import tempfile
import time

import numpy as np
import vtk
from vtk.util import numpy_support as ns

HERE = os.path.dirname(os.path.abspath(__file__))


def read_with_vtk(mesh):
    """The mesh as VTK reads it: .vtu, .vts, or a PLOT3D .q on the only .xyz beside it (VTK's
    reader detects the PLOT3D layout; its blocks are appended into one grid)."""
    if mesh.endswith(".vts"):
        reader = vtk.vtkXMLStructuredGridReader()
        reader.SetFileName(mesh)
    elif mesh.endswith(".q"):
        folder = os.path.dirname(os.path.abspath(mesh))
        grids = [f for f in os.listdir(folder) if f.endswith(".xyz")]
        assert len(grids) == 1, "expected one .xyz beside " + mesh
        p3d = vtk.vtkMultiBlockPLOT3DReader()
        p3d.SetXYZFileName(os.path.join(folder, grids[0]))
        p3d.SetQFileName(mesh)
        p3d.SetAutoDetectFormat(1)
        p3d.AddFunction(110)  # pressure
        p3d.Update()
        reader = vtk.vtkAppendFilter()
        blocks = p3d.GetOutput()
        for b in range(blocks.GetNumberOfBlocks()):
            reader.AddInputData(blocks.GetBlock(b))
    else:
        reader = vtk.vtkXMLUnstructuredGridReader()
        reader.SetFileName(mesh)
    reader.Update()
    return reader.GetOutput()


def main():
    mesh, field, res = sys.argv[1], sys.argv[2], int(sys.argv[3])
    rounds = int(sys.argv[4]) if len(sys.argv) > 4 else 5
    mode = sys.argv[5] if len(sys.argv) > 5 else "iso"
    exe = os.path.join(HERE, "..", "build", "voxelize_bench")
    with tempfile.TemporaryDirectory() as tmp:
        prefix = os.path.join(tmp, "ours")
        out = subprocess.run([exe, mesh, field, str(res), prefix, str(rounds), mode], check=True,
                             capture_output=True, text=True).stdout
        ours = json.loads(out)
        dims = ours["dims"]
        values = np.fromfile(prefix + ".f32", dtype=np.float32)
        inside = np.fromfile(prefix + ".u8", dtype=np.uint8).astype(bool)

    ug = read_with_vtk(mesh)
    ug.GetPointData().SetActiveScalars(field)
    lo = ours["origin"]
    h = ours["spacing"]
    bounds = [lo[0], lo[0] + (dims[0] - 1) * h[0], lo[1], lo[1] + (dims[1] - 1) * h[1],
              lo[2], lo[2] + (dims[2] - 1) * h[2]]
    seconds = []
    for _ in range(rounds):
        r = vtk.vtkResampleToImage()
        r.SetInputDataObject(ug)
        r.SetSamplingDimensions(*dims)
        r.SetUseInputBounds(False)
        r.SetSamplingBounds(bounds)
        t0 = time.perf_counter()
        r.Update()
        seconds.append(time.perf_counter() - t0)
    img = r.GetOutput()
    ref = ns.vtk_to_numpy(img.GetPointData().GetArray(field)).astype(np.float64)
    valid = ns.vtk_to_numpy(img.GetPointData().GetArray("vtkValidPointMask")).astype(bool)
    both = valid & inside
    spread = float(ref[valid].max() - ref[valid].min()) or 1.0
    diff = np.abs(values[both] - ref[both]) / spread
    vtk_s = statistics.median(seconds)
    report = {
        "mesh": mesh, "field": field, "mode": mode, "dims": dims, "cells": ours["cells"], "tets": ours["tets"],
        "ours_s": ours["seconds"], "vtk_s": vtk_s, "speedup": vtk_s / ours["seconds"],
        "ours_cells_per_s": ours["cells_per_s"], "vtk_cells_per_s": ours["cells"] / vtk_s,
        "ours_voxels_per_s": ours["voxels_per_s"], "vtk_voxels_per_s": ours["voxels"] / vtk_s,
        "max_diff_of_spread": float(diff.max()) if diff.size else 0.0,
        "mean_diff_of_spread": float(diff.mean()) if diff.size else 0.0,
        "inside_ours": int(inside.sum()), "inside_vtk": int(valid.sum()),
        "inside_disagree": int((inside != valid).sum()),
    }
    print(json.dumps(report, indent=1))


if __name__ == "__main__":
    main()
