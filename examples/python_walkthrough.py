#!/usr/bin/env python3
"""docs/python.md's walk-through as one script: a 4-D numpy array from a formula -> a TSP tree ->
8 frames -> a movie -> the colour difference between tolerances.

Usage: PYTHONPATH=build/python python3 examples/python_walkthrough.py [OUT_DIR]
(after `cmake --install build`, plain python3).
"""
import os
import shutil
import sys

import numpy as np

import tspplay

out = sys.argv[1] if len(sys.argv) > 1 else "walkthrough"
os.makedirs(out, exist_ok=True)

# 1. A time series from a formula: a warm bubble rising through a stratified box, (t, z, y, x).
t, z, y, x = np.meshgrid(np.arange(16), np.linspace(0, 1, 48), np.linspace(-1, 1, 64),
                         np.linspace(-1, 1, 64), indexing="ij", sparse=True)
height = 0.2 + 0.04 * t
series = (np.exp(-((x ** 2 + y ** 2) / 0.08 + (z - height) ** 2 / 0.02))
          * (1 + 0.2 * np.sin(8 * x + t)) + 0.1 * z).astype(np.float32)
print("series", series.shape, series.dtype)

# 2. The TSP tree (the array is read in place, step by step).
f = tspplay.build(series, os.path.join(out, "bubble.tsp"), field="temperature",
                  spacing=(2 / 63, 2 / 63, 1 / 47), times=0.5 * np.arange(16))
print(f, "levels", f.levels, "build", f"{f.build_report['seconds']:.2f} s")
nodes = f.nodes()
print("TSP nodes", len(nodes["mean"]), "root spatial error", nodes["spatial_error"][0])

# 3. Eight frames, as numpy RGBA images (the pixels `tspplay render` writes).
tf = tspplay.TransferFunction.preset("auto")  # opacity where the data is rare
frames = f.render(steps=range(0, 16, 2), tf=tf, size=(320, 240), view=(30, 20))
print(len(frames), "frames", frames[0].shape, "median", f"{frames.info['median_ms']:.1f} ms",
      "caster", frames.reports[0]["caster"])
tspplay.write_png(os.path.join(out, "frame0.png"), frames[0])

# 4. A movie (needs ffmpeg).
if shutil.which("ffmpeg"):
    f.movie(os.path.join(out, "bubble.mp4"), tf=tf, size=(320, 240), fps=8)
    print("wrote", os.path.join(out, "bubble.mp4"))

# 5. What the tolerances cost in colour: mean/p99/max dE L*u*v* against the exact picture.
exact = f.render(steps=8, tf=tf, size=(320, 240))[0]
for tol in (0.05, 0.2, 0.5):
    loose = f.render(steps=8, tf=tf, size=(320, 240), spatial_tol=tol, temporal_tol=tol)
    d = tspplay.diff(exact, loose[0])
    print(f"tolerance {tol}: dE mean {d['mean']:.3f} p99 {d['p99']:.3f} max {d['max']:.3f}, "
          f"{loose.reports[0]['ms']:.1f} ms")
