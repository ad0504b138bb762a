#!/usr/bin/env python3
"""The Python module's two targets (issue 46), on one machine in one sitting:

1. Building from an in-memory numpy array vs `tspplay build` of the same samples from HDF5:
   throughput (MB of float32 samples a second, the builds' own timers) and its ratio; target
   >= 0.8x. Runs alternate (CLI, Python, CLI, ...) and the medians are compared.
2. A render call's overhead over the library's frame time at 640x480: the call's wall time
   minus the time spent inside the render job (`job_ms`, timed in C++), over the frames' own
   times (frames.json's `ms`); target < 5 %.

Usage: PYTHONPATH=build/python python3 bench/python_build.py [--dims 96] [--steps 32]
       [--runs 3] [--frames 8] [--tspplay build/tspplay]
Needs h5py (python3-h5py) to read the HDF5 series into memory.
"""
import argparse
import os
import re
import statistics
import subprocess
import sys
import tempfile
import time

import tspplay


def main():
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--dims", type=int, default=96)
    p.add_argument("--steps", type=int, default=32)
    p.add_argument("--runs", type=int, default=3)
    p.add_argument("--frames", type=int, default=8)
    p.add_argument("--tspplay", default=tspplay._core.tspplay_binary())
    a = p.parse_args()
    import h5py

    with tempfile.TemporaryDirectory(prefix="tspplay-bench-") as tmp:
        h5 = os.path.join(tmp, "shock.h5")
        subprocess.run([a.tspplay, "generate", "shock", "--dims", str(a.dims), "--steps",
                        str(a.steps), "-o", h5], check=True, capture_output=True)
        with h5py.File(h5, "r") as f:
            data = f["shock"][()]  # (t, z, y, x) float32, in memory before timing
        mb = data.nbytes / 1e6
        print(f"series: shock {a.dims}^3 x {a.steps} steps, {mb:.1f} MB float32, "
              f"{os.cpu_count()} cores")
        cli_s, py_s, py_wall = [], [], []
        for run in range(a.runs):
            out = os.path.join(tmp, "cli.tsp")
            r = subprocess.run([a.tspplay, "build", h5, "-o", out], check=True,
                               capture_output=True, text=True)
            cli_s.append(float(re.search(r"MB in ([0-9.]+) s", r.stdout).group(1)))
            os.remove(out)
            out = os.path.join(tmp, "py.tsp")
            t0 = time.perf_counter()
            f = tspplay.build(data, out)
            py_wall.append(time.perf_counter() - t0)
            py_s.append(f.build_report["seconds"])
            del f
            os.remove(out)
            print(f"  run {run + 1}: CLI from HDF5 {cli_s[-1]:.2f} s, Python from the array "
                  f"{py_s[-1]:.2f} s (call {py_wall[-1]:.2f} s)")
        c, q, w = statistics.median(cli_s), statistics.median(py_s), statistics.median(py_wall)
        print(f"build: CLI {mb / c:.1f} MB/s, Python {mb / q:.1f} MB/s (whole call: "
              f"{mb / w:.1f} MB/s); Python/CLI throughput {c / q:.2f}x (whole call "
              f"{c / w:.2f}x); target >= 0.8x")

        f = tspplay.build(data, os.path.join(tmp, "r.tsp"))
        steps = range(0, min(a.frames, f.steps))
        f.render(steps=0)  # warm: shader compilation, page cache
        over, frame_ms = [], []
        for run in range(a.runs):
            t0 = time.perf_counter()
            frames = f.render(steps=steps, size=(640, 480))
            wall = (time.perf_counter() - t0) * 1e3
            ms = sum(r["ms"] for r in frames.reports)
            over.append(wall - frames.info["job_ms"])
            frame_ms.append(ms)
            print(f"  run {run + 1}: call {wall:.1f} ms, inside the job {frames.info['job_ms']:.1f}"
                  f" ms, frames {ms:.1f} ms ({len(frames)} frames, {frames.reports[0]['caster']},"
                  f" {frames.info['context']})")
        o, fm = statistics.median(over), statistics.median(frame_ms)
        print(f"render: the binding's overhead {o:.2f} ms per call of {len(steps)} frames at "
              f"640x480 = {100 * o / fm:.2f} % of the frames' {fm:.1f} ms; target < 5 %")
    return 0


if __name__ == "__main__":
    sys.exit(main())
