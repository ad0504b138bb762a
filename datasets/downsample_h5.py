#!/usr/bin/env python3
"""Makes a small sample of a 4-D (T, Z, Y, X) float32 HDF5 dataset for datasets/samples/.

A dataset-making tool (Python 3 + numpy + h5py), not part of tspplay. Averages FACTOR^3 blocks
of cells (exact for cell-averaged data such as finite-volume output) and keeps every STRIDE-th
step starting at step 0. Copies the dataset's attributes, updating dims, steps, times and
spacing, and appends the reduction to 'source'. Writes under a temporary name, then renames.

Usage: downsample_h5.py IN.h5 --field T -o OUT.h5 [--factor 2] [--stride 4] [--gzip 9]
"""

import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from h5_series import map_series, series_parser  # noqa: E402


def main(argv=None):
    p = series_parser(__doc__)
    p.add_argument("--factor", type=int, default=2, help="cells averaged per axis")
    p.add_argument("--gzip", type=int, default=9, choices=range(0, 10), metavar="L")
    a = p.parse_args(argv)
    r = a.factor

    def plan(shape):
        _, z, y, x = shape
        if r < 1 or a.stride < 1 or z % r or y % r or x % r:
            raise ValueError(f"{a.input}, dataset {a.field}: shape {shape}: cells "
                             f"{x}x{y}x{z} not divisible by factor {r}")
        out_zyx = (z // r, y // r, x // r)

        def step(v):
            return v.reshape(z // r, r, y // r, r, x // r, r).mean(axis=(1, 3, 5))
        return out_zyx, step, r, f"downsampled by downsample_h5.py: mean of {r}^3 cells"

    return map_series("downsample_h5", a, plan, gzip=a.gzip)


if __name__ == "__main__":
    sys.exit(main())
