#!/usr/bin/env python3
"""Makes a small sample of a 4-D (T, Z, Y, X) float32 HDF5 dataset for datasets/samples/.

A dataset-making tool (Python 3 + numpy + h5py), not part of tspplay. Averages FACTOR^3 blocks
of cells (exact for cell-averaged data such as finite-volume output) and keeps every STRIDE-th
step starting at step 0. Copies the dataset's attributes, updating dims, steps, times and
spacing, and appends the reduction to 'source'. Writes under a temporary name, then renames.

Usage: downsample_h5.py IN.h5 --field T -o OUT.h5 [--factor 2] [--stride 4] [--gzip 9]
"""

import argparse
import os
import sys

import h5py
import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from h5_series import write_series  # noqa: E402


def main(argv=None):
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("input")
    p.add_argument("--field", required=True)
    p.add_argument("-o", "--output", required=True)
    p.add_argument("--factor", type=int, default=2, help="cells averaged per axis")
    p.add_argument("--stride", type=int, default=1, help="keep every STRIDE-th step")
    p.add_argument("--gzip", type=int, default=9, choices=range(0, 10), metavar="L")
    a = p.parse_args(argv)
    try:
        with h5py.File(a.input, "r") as f:
            if a.field not in f:
                raise ValueError(f"{a.input}: no dataset '{a.field}'")
            d = f[a.field]
            if d.ndim != 4:
                raise ValueError(
                    f"{a.input}, dataset {a.field}: rank {d.ndim}, expected 4 (T,Z,Y,X)")
            t, z, y, x = d.shape
            r = a.factor
            if r < 1 or a.stride < 1 or z % r or y % r or x % r:
                raise ValueError(f"{a.input}, dataset {a.field}: shape {d.shape}: cells "
                                 f"{x}x{y}x{z} not divisible by factor {r}")
            steps = list(range(0, t, a.stride))
            attrs = dict(d.attrs)
            out = np.empty((len(steps), z // r, y // r, x // r), np.float32)
            for k, s in enumerate(steps):
                v = d[s].astype(np.float64)
                out[k] = v.reshape(z // r, r, y // r, r, x // r, r).mean(axis=(1, 3, 5))
    except (ValueError, OSError) as e:
        print(f"downsample_h5: error: {e}", file=sys.stderr)
        return 1
    attrs["dims"] = np.array([x // r, y // r, z // r], np.int64)
    attrs["steps"] = np.int64(len(steps))
    if "times" in attrs:
        attrs["times"] = np.asarray(attrs["times"])[steps]
    if "spacing" in attrs:
        attrs["spacing"] = np.asarray(attrs["spacing"]) * r
    attrs["source"] = (str(attrs.get("source", "")) +
                       f"; downsampled by downsample_h5.py: mean of {r}^3 cells, every "
                       f"{a.stride} step(s) from {os.path.basename(a.input)}")
    write_series(a.output, a.field, out, attrs, gzip=a.gzip)
    print(f"downsample_h5: wrote {a.output}: {out.shape}, {os.path.getsize(a.output)} bytes",
          file=sys.stderr)
    return 0


if __name__ == "__main__":
    sys.exit(main())
