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

import os
import sys

import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from h5_series import map_series, series_parser  # noqa: E402


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
    p = series_parser(__doc__)
    p.add_argument("--size", type=int, default=256, help="samples per axis of the output")
    a = p.parse_args(argv)
    if os.path.abspath(a.input) == os.path.abspath(a.output):
        print("upsample_h5: error: the output would overwrite the input", file=sys.stderr)
        return 1
    n = a.size

    def plan(shape):
        _, z, y, x = shape
        if n < 2 or n > 2048 or a.stride < 1:
            raise ValueError(f"--size {n} / --stride {a.stride}: expected a size in "
                             "[2, 2048] and a stride >= 1")

        def step(v):
            for axis in (0, 1, 2):
                v = resample_axis(v, axis, n)
            return v
        scale = np.array([x - 1, y - 1, z - 1], np.float64) / (n - 1)
        return (n, n, n), step, scale, f"upsampled by upsample_h5.py: trilinear onto {n}^3"

    return map_series("upsample_h5", a, plan)


if __name__ == "__main__":
    sys.exit(main())
