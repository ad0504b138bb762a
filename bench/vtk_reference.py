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
        [--shade on|off]

With --search 1,3 it judges VTK as tspplay's bench judges our renderers (docs/bench.md): the
reference is VTK's own CPU caster at 0.25-voxel sample distance (image sample distance 1); every
mapper × --spacings × --image-sample-distances value is rendered (lit with --shade on), its mean ΔE against the reference measured with `tspplay diff`, and for each target
the fastest configuration within it is VTK's best. With --against report.json --tsp FILE.tsp
--tf-arg preset:NAME, the bench's Table-4 TSP winners for the same TF are timed head to head with
VTK's best, alternating for --rounds rounds (`tspplay render` with the row's render_options), and
the ratios printed and written to OUT_DIR/vtk_search.json.

TF.json is tspplay's own format (e.g. the demo's sparse_tf.json or `tspplay` presets saved with
save_transfer_function); its points become VTK's colour and opacity functions. Opacity is per
unit distance of one voxel in both (spec §9), the sample distance is --spacing voxels, shading on
as tspplay's default (VTK's default lighting, to compare with `tspplay render`; --shade off to
compare with `tspplay render --shade off`),
trilinear interpolation, orthographic camera fitted as tsp/frame/camera.cpp fits it.
"""
import argparse
import json
import math
import os
import re
import subprocess
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


def make_pipeline(kind, colour, opacity, dims, az, el, width, height, shade=False):
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
    # Shading on: VTK's default coefficients (ambient 0.1, diffuse 0.7, specular 0.2, power 10)
    # and its default light, a headlight — what `tspplay render --shade on` draws.
    if shade:
        prop.ShadeOn()
    else:
        prop.ShadeOff()
    mapper = (vtk.vtkFixedPointVolumeRayCastMapper() if kind == "cpu"
              else vtk.vtkOpenGLGPUVolumeRayCastMapper())
    mapper.SetAutoAdjustSampleDistances(0)
    volume = vtk.vtkVolume()
    volume.SetMapper(mapper)
    volume.SetProperty(prop)
    ren.AddVolume(volume)
    camera_setup(ren, dims, az, el, width, height)
    return win, mapper


def render_series(win, mapper, series, field, dims, spacing, out_dir, first):
    """Renders every step at sample distance `spacing`; writes PNGs; returns the frame times."""
    nx, ny, nz = dims
    mapper.SetSampleDistance(spacing)
    if out_dir:
        os.makedirs(out_dir, exist_ok=True)
    times = []
    for i, data in enumerate(series):
        img = vtk.vtkImageData()  # a new dataset per step: nothing cached between steps
        img.SetDimensions(nx, ny, nz)
        arr = numpy_support.numpy_to_vtk(data.ravel(), deep=1)
        arr.SetName(field)
        img.GetPointData().SetScalars(arr)
        mapper.SetInputData(img)
        t0 = time.perf_counter()
        win.Render()
        win.WaitForCompletion()
        times.append((time.perf_counter() - t0) * 1e3)
        if out_dir:
            grab = vtk.vtkWindowToImageFilter()
            grab.SetInput(win)
            grab.ReadFrontBufferOff()
            grab.Update()
            writer = vtk.vtkPNGWriter()
            writer.SetFileName(os.path.join(out_dir, "step_%04d.png" % (first + i)))
            writer.SetInputConnection(grab.GetOutputPort())
            writer.Write()
    return times


def mean_delta_e(tspplay, dir_a, dir_b, steps):
    total = 0.0
    for t in steps:
        name = "step_%04d.png" % t
        out = subprocess.run([tspplay, "diff", os.path.join(dir_a, name), os.path.join(dir_b, name),
                              "--json"], check=True, capture_output=True, text=True).stdout
        total += json.loads(out)["mean"]
    return total / len(steps)


def tspplay_median(tspplay, tsp, tf_arg, steps, size, view, options, out_dir):
    cmd = [tspplay, "render", tsp, "--tf", tf_arg, "--steps", steps, "--size", size, "--view", view,
           "--passes", "2", "-o", out_dir] + options.split()
    out = subprocess.run(cmd, check=True, capture_output=True, text=True).stdout
    m = re.search(r"median frame ([0-9.]+) ms \(last pass\)", out)
    if not m:
        raise RuntimeError("no median in tspplay output: " + out)
    return float(m.group(1))


def search(a, series, colour, opacity, dims, az, el, width, height, first):
    kinds = ["cpu", "gpu"] if a.mapper == "both" else [a.mapper]
    targets = [float(v) for v in a.search.split(",")]
    spacings = [float(v) for v in a.spacings.split(",")]
    steps = list(range(first, first + len(series)))
    shade = a.shade == "on"
    isds = [float(v) for v in a.image_sample_distances.split(",")]
    pipes = {k: make_pipeline(k, colour, opacity, dims, az, el, width, height, shade) for k in kinds}
    ref_dir = os.path.join(a.out, "reference")
    ref_pipe = pipes.get("cpu") or make_pipeline("cpu", colour, opacity, dims, az, el, width, height,
                                                 shade)
    ref_pipe[1].SetImageSampleDistance(1.0)
    render_series(*ref_pipe, series, a.field, dims, 0.25, ref_dir, first)
    configs = []
    for kind in kinds:
        for isd in isds:
            # Rays every isd pixels, the picture interpolated up (ParaView's "image reduction").
            pipes[kind][1].SetImageSampleDistance(isd)
            for sp in spacings:
                d = os.path.join(a.out, "%s_%g_isd%g" % (kind, sp, isd))
                times = render_series(*pipes[kind], series, a.field, dims, sp, d, first)
                steady = times[1:] if len(times) > 1 else times
                de = mean_delta_e(a.tspplay, d, ref_dir, steps)
                configs.append({"mapper": kind, "spacing": sp, "image_sample_distance": isd,
                                "median_ms": statistics.median(steady), "mean_delta_e": de})
                print("%s spacing %g isd %g: %.2f ms, mean dE %.3f" % (
                    kind, sp, isd, configs[-1]["median_ms"], de))
    best = {}
    for t in targets:
        ok = [c for c in configs if c["mean_delta_e"] <= t]
        best[t] = min(ok, key=lambda c: c["median_ms"]) if ok else None
        print("target dE %g: VTK best %s" % (t, best[t]))
    result = {"reference": {"mapper": "cpu", "spacing": 0.25}, "configs": configs,
              "best": {str(t): b for t, b in best.items()}, "head_to_head": []}
    if a.against:
        with open(a.against) as f:
            report = json.load(f)
        lo = steps[0]
        step_arg = "%d:%d" % (lo, steps[-1])
        for t in targets:
            rows = [r for r in report["table4"] if r.get("renderer") == "tsp" and
                    r.get("tf") == a.tf_arg and r.get("target_delta_e") == t and r.get("target_met")]
            if not rows or not best[t]:
                continue
            b = best[t]
            for r in rows:
                vtk_ms, tsp_ms = [], []
                pipes[b["mapper"]][1].SetImageSampleDistance(b["image_sample_distance"])
                for _ in range(a.rounds):
                    times = render_series(*pipes[b["mapper"]], series, a.field, dims, b["spacing"],
                                          "", first)
                    vtk_ms.append(statistics.median(times[1:] if len(times) > 1 else times))
                    tsp_ms.append(tspplay_median(a.tspplay, a.tsp, a.tf_arg, step_arg, a.size,
                                                 a.view, r["render_options"],
                                                 os.path.join(a.out, "tsp_h2h")))
                h = {"target_delta_e": t, "metric": r["metric"], "vtk": b,
                     "vtk_median_ms": statistics.median(vtk_ms),
                     "tsp_render_options": r["render_options"],
                     "tsp_median_ms": statistics.median(tsp_ms)}
                h["speedup_vs_vtk"] = h["vtk_median_ms"] / h["tsp_median_ms"]
                result["head_to_head"].append(h)
                print("target dE %g: VTK %s %g %.2f ms, TSP %.2f ms [%s]: x%.2f" % (
                    t, b["mapper"], b["spacing"], h["vtk_median_ms"], h["tsp_median_ms"],
                    r["render_options"], h["speedup_vs_vtk"]))
    with open(os.path.join(a.out, "vtk_search.json"), "w") as f:
        json.dump(result, f, indent=2)


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
    p.add_argument("--shade", default="on", choices=["on", "off"],
                   help="light the volume (VTK's default coefficients and headlight)")
    p.add_argument("--search", default="", help="target mean dE values, e.g. 1,3")
    p.add_argument("--spacings", default="0.25,0.5,1,1.5,2,3,4,6,8")
    p.add_argument("--image-sample-distances", default="1,1.5,2,3",
                   help="VTK's image sample distances searched with every spacing (rays every N "
                        "pixels)")
    p.add_argument("--tspplay", default=os.path.join(os.path.dirname(os.path.abspath(__file__)),
                                                     "..", "build", "tspplay"))
    p.add_argument("--against", default="", help="a tspplay bench report.json")
    p.add_argument("--tsp", default="", help="the .tsp file the report was made on")
    p.add_argument("--tf-arg", default="", help="the report's --tf argument for this TF")
    p.add_argument("--rounds", type=int, default=3)
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
    if a.search:
        search(a, series, colour, opacity, (nx, ny, nz), az, el, width, height, first)
        return 0
    results = {}
    for kind in (["cpu", "gpu"] if a.mapper == "both" else [a.mapper]):
        win, mapper = make_pipeline(kind, colour, opacity, (nx, ny, nz), az, el, width, height,
                                    a.shade == "on")
        times = render_series(win, mapper, series, a.field, (nx, ny, nz), a.spacing,
                              os.path.join(a.out, kind), first)
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
