#!/usr/bin/env python3
"""Makes a larger series from a 4-D (T, Z, Y, X) float32 HDF5 dataset, for LOD benchmarks.

A dataset-making tool (Python 3 + numpy + h5py), not part of tspplay. Resamples every kept step
trilinearly onto SIZE samples per axis spanning the same extent (sample i of the output lies at
input coordinate i * (D - 1) / (SIZE - 1)), keeping every STRIDE-th step from step 0. The result
holds no detail the input lacks: it is the real series at a size where levels of detail matter.
Copies the dataset's attributes, updating dims, steps, times and spacing, and appends the
resampling to 'source'. Writes under a temporary name, then renames.

Usage: upsample_h5.py IN.h5 --field p -o OUT.h5 [--size 256] [--stride 8]
"""

import argparse
import os
import sys

import h5py
import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from h5_series import write_series  # noqa: E402


def resample_axis(v, axis, n):
    """Linear interpolation of v along axis onto n samples spanning the same extent."""
    d = v.shape[axis]
    pos = np.linspace(0.0, d - 1.0, n)
    lo = np.minimum(np.floor(pos).astype(np.int64), d - 2) if d > 1 else np.zeros(n, np.int64)
    w = (pos - lo) if d > 1 else np.zeros(n)
    a = np.take(v, lo, axis=axis)
    b = np.take(v, np.minimum(lo + 1, d - 1), axis=axis)
    shape = [1] * v.ndim
    shape[axis] = n
    w = w.reshape(shape)
    return a * (1.0 - w) + b * w


def main(argv=None):
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("input")
    p.add_argument("--field", required=True)
    p.add_argument("-o", "--output", required=True)
    p.add_argument("--size", type=int, default=256, help="samples per axis of the output")
    p.add_argument("--stride", type=int, default=1, help="keep every STRIDE-th step")
    a = p.parse_args(argv)
    if os.path.abspath(a.input) == os.path.abspath(a.output):
        print("upsample_h5: error: the output would overwrite the input", file=sys.stderr)
        return 1
    try:
        with h5py.File(a.input, "r") as f:
            if a.field not in f:
                raise ValueError(f"{a.input}: no dataset '{a.field}'")
            d = f[a.field]
            if d.ndim != 4:
                raise ValueError(
                    f"{a.input}, dataset {a.field}: rank {d.ndim}, expected 4 (T,Z,Y,X)")
            if a.size < 2 or a.size > 2048 or a.stride < 1:
                raise ValueError(f"--size {a.size} / --stride {a.stride}: expected a size in "
                                 "[2, 2048] and a stride >= 1")
            t, z, y, x = d.shape
            steps = list(range(0, t, a.stride))
            attrs = dict(d.attrs)
            n = a.size
            out = np.empty((len(steps), n, n, n), np.float32)
            for k, s in enumerate(steps):
                v = d[s].astype(np.float64)
                for axis in (0, 1, 2):
                    v = resample_axis(v, axis, n)
                out[k] = v
    except (ValueError, OSError) as e:
        print(f"upsample_h5: error: {e}", file=sys.stderr)
        return 1
    attrs["dims"] = np.array([n, n, n], np.int64)
    attrs["steps"] = np.int64(len(steps))
    if "times" in attrs:
        attrs["times"] = np.asarray(attrs["times"])[steps]
    if "spacing" in attrs:
        attrs["spacing"] = np.asarray(attrs["spacing"], np.float64) * (
            np.array([x - 1, y - 1, z - 1], np.float64) / (n - 1))
    attrs["source"] = (str(attrs.get("source", "")) +
                       f"; upsampled by upsample_h5.py: trilinear onto {n}^3, every "
                       f"{a.stride} step(s) from {os.path.basename(a.input)}")
    write_series(a.output, a.field, out, attrs, gzip=0)
    print(f"upsample_h5: wrote {a.output}: {out.shape}", file=sys.stderr)
    return 0


if __name__ == "__main__":
    sys.exit(main())
