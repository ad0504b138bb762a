#!/usr/bin/env python3
"""Times VTK's volume renderers on the same data, transfer function and view as `tspplay render`,
and writes their images for a same-picture comparison with `tspplay diff`.

This is the reference the product's bar is stated against (VTK, the engine under ParaView): its
CPU ray caster (vtkFixedPointVolumeRayCastMapper) and its GPU ray caster
(vtkOpenGLGPUVolumeRayCastMapper; on llvmpipe here). Like a ParaView user playing a series, it
caches nothing between steps: each step is a new vtkImageData.

Needs python3-vtk9, python3-h5py, python3-numpy (tools for this benchmark only, not tspplay
dependencies) and a display (run under `xvfb-run -a -s "-screen 0 1280x1024x24"`).

    xvfb-run -a /usr/bin/python3 bench/vtk_reference.py DATA.h5 FIELD TF.json OUT_DIR \
        [--steps A:B] [--size 640x480] [--view 30,20] [--spacing 0.5] [--mapper cpu|gpu|both]

TF.json is tspplay's own format (e.g. the demo's sparse_tf.json or `tspplay` presets saved with
save_transfer_function); its points become VTK's colour and opacity functions. Opacity is per
unit distance of one voxel in both (spec §9), the sample distance is --spacing voxels, shading off,
trilinear interpolation, orthographic camera fitted as tsp/frame/camera.cpp fits it.
"""
import argparse
import json
import math
import os
import statistics
import sys
import time

import h5py
import numpy as np
import vtk
from vtk.util import numpy_support


def camera_setup(ren, dims, az_deg, el_deg, width, height):
    extent = np.array([max(d - 1, 0) for d in dims], dtype=float)
    centre = extent / 2
    radius = max(0.5 * float(np.linalg.norm(extent)), 0.5)
    az, el = math.radians(az_deg), math.radians(el_deg)
    to_eye = np.array([math.cos(el) * math.sin(az), -math.cos(el) * math.cos(az), math.sin(el)])
    right = np.cross(-to_eye, [0, 0, 1])
    right /= np.linalg.norm(right)
    up = np.cross(right, -to_eye)
    aspect = width / height
    cam = ren.GetActiveCamera()
    cam.ParallelProjectionOn()
    cam.SetFocalPoint(*centre)
    cam.SetPosition(*(centre + to_eye * radius * 3))
    cam.SetViewUp(*up)
    cam.SetParallelScale(radius * (1 / aspect if aspect < 1 else 1))
    cam.SetClippingRange(radius * 3 - radius * 1.01, radius * 3 + radius * 1.01)


def load_tf(path):
    with open(path) as f:
        tf = json.load(f)
    colour, opacity = vtk.vtkColorTransferFunction(), vtk.vtkPiecewiseFunction()
    for x, r, g, b, a in tf["points"]:
        colour.AddRGBPoint(x, r, g, b)
        opacity.AddPoint(x, a)
    return colour, opacity


def main():
    p = argparse.ArgumentParser()
    p.add_argument("data")
    p.add_argument("field")
    p.add_argument("tf")
    p.add_argument("out")
    p.add_argument("--steps", default="")
    p.add_argument("--size", default="640x480")
    p.add_argument("--view", default="30,20")
    p.add_argument("--spacing", type=float, default=0.5)
    p.add_argument("--mapper", default="both", choices=["cpu", "gpu", "both"])
    a = p.parse_args()
    width, height = (int(v) for v in a.size.split("x"))
    az, el = (float(v) for v in a.view.split(","))
    with h5py.File(a.data, "r") as f:
        ds = f[a.field]
        steps = ds.shape[0]
        first, last = 0, steps - 1
        if a.steps:
            lo, _, hi = a.steps.partition(":")
            first, last = int(lo), int(hi) if hi else (int(lo) if ":" not in a.steps else steps - 1)
        series = [np.ascontiguousarray(ds[t], dtype=np.float32) for t in range(first, last + 1)]
    nz, ny, nx = series[0].shape
    colour, opacity = load_tf(a.tf)
    os.makedirs(a.out, exist_ok=True)
    results = {}
    for kind in (["cpu", "gpu"] if a.mapper == "both" else [a.mapper]):
        win = vtk.vtkRenderWindow()
        win.SetOffScreenRendering(1)
        win.SetSize(width, height)
        ren = vtk.vtkRenderer()
        ren.SetBackground(0, 0, 0)
        win.AddRenderer(ren)
        prop = vtk.vtkVolumeProperty()
        prop.SetColor(colour)
        prop.SetScalarOpacity(opacity)
        prop.SetScalarOpacityUnitDistance(1.0)
        prop.SetInterpolationTypeToLinear()
        prop.ShadeOff()
        mapper = (vtk.vtkFixedPointVolumeRayCastMapper() if kind == "cpu"
                  else vtk.vtkOpenGLGPUVolumeRayCastMapper())
        mapper.SetAutoAdjustSampleDistances(0)
        mapper.SetSampleDistance(a.spacing)
        volume = vtk.vtkVolume()
        volume.SetMapper(mapper)
        volume.SetProperty(prop)
        ren.AddVolume(volume)
        camera_setup(ren, (nx, ny, nz), az, el, width, height)
        times = []
        for i, data in enumerate(series):
            img = vtk.vtkImageData()  # a new dataset per step: nothing cached between steps
            img.SetDimensions(nx, ny, nz)
            arr = numpy_support.numpy_to_vtk(data.ravel(), deep=1)
            arr.SetName(a.field)
            img.GetPointData().SetScalars(arr)
            mapper.SetInputData(img)
            t0 = time.perf_counter()
            win.Render()
            win.WaitForCompletion()
            times.append((time.perf_counter() - t0) * 1e3)
            grab = vtk.vtkWindowToImageFilter()
            grab.SetInput(win)
            grab.ReadFrontBufferOff()
            grab.Update()
            writer = vtk.vtkPNGWriter()
            writer.SetFileName(os.path.join(a.out, kind, "step_%04d.png" % (first + i)))
            os.makedirs(os.path.join(a.out, kind), exist_ok=True)
            writer.SetInputConnection(grab.GetOutputPort())
            writer.Write()
        steady = times[1:] if len(times) > 1 else times
        results[kind] = {"median_ms": statistics.median(steady), "first_ms": times[0],
                         "frames": len(times), "renderer": win.ReportCapabilities().splitlines()[0]
                         if hasattr(win, "ReportCapabilities") else ""}
        print("%s: median %.2f ms over %d steps (first frame %.2f ms) -> %s/" %
              (kind, results[kind]["median_ms"], len(steady), times[0], os.path.join(a.out, kind)))
    with open(os.path.join(a.out, "vtk.json"), "w") as f:
        json.dump(results, f, indent=2)


if __name__ == "__main__":
    sys.exit(main())
