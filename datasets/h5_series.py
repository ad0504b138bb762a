"""Shared by the dataset tools (downsample_h5.py, upsample_h5.py): reading a 4-D (T, Z, Y, X)
series, mapping every kept step and its attributes onto a new grid, and writing the result with its
attributes atomically (a temporary name in the output's directory, renamed when complete; removed
on any failure) and readable by everyone the umask allows."""

import argparse
import os
import sys
import tempfile

import h5py
import numpy as np


def series_parser(doc):
    """Command line of a dataset tool: IN.h5 --field F -o OUT.h5 [--stride N], described by the
    first paragraph of doc; the tool adds its own options."""
    p = argparse.ArgumentParser(description=doc.split("\n\n")[0])
    p.add_argument("input")
    p.add_argument("--field", required=True)
    p.add_argument("-o", "--output", required=True)
    p.add_argument("--stride", type=int, default=1, help="keep every STRIDE-th step")
    return p


def write_series(path, field, data, attrs, gzip=0):
    """Writes data as dataset `field` of a new HDF5 file at path, one chunk per step."""
    out_dir = os.path.dirname(os.path.abspath(path))
    fd, tmp = tempfile.mkstemp(prefix="." + os.path.basename(path) + ".", suffix=".tmp",
                               dir=out_dir)
    os.close(fd)
    try:
        with h5py.File(tmp, "w") as f:
            kw = dict(compression="gzip", compression_opts=gzip, shuffle=True) if gzip else {}
            ds = f.create_dataset(field, data=data, chunks=(1,) + data.shape[1:], **kw)
            for k, v in attrs.items():
                ds.attrs[k] = v
        mask = os.umask(0)
        os.umask(mask)
        os.chmod(tmp, 0o666 & ~mask)  # mkstemp's 0600 would hide the file from others
        os.replace(tmp, path)
    except BaseException:
        os.unlink(tmp)
        raise


def map_series(tool, a, plan, gzip=0):
    """Main of a dataset tool: maps every a.stride-th step of 4-D dataset a.field in a.input and
    writes the result to a.output. plan(shape) checks the dataset's (T, Z, Y, X) shape (ValueError
    to refuse it) and returns (out_zyx, step, spacing_scale, note): the output grid, the function
    from one step (float64, Z, Y, X) to it, the factor on the 'spacing' attribute and what 'source'
    gains. Returns the exit code; errors are printed as `tool: error: ...`."""
    try:
        with h5py.File(a.input, "r") as f:
            if a.field not in f:
                raise ValueError(f"{a.input}: no dataset '{a.field}'")
            d = f[a.field]
            if d.ndim != 4:
                raise ValueError(
                    f"{a.input}, dataset {a.field}: rank {d.ndim}, expected 4 (T,Z,Y,X)")
            out_zyx, step, spacing_scale, note = plan(d.shape)
            steps = list(range(0, d.shape[0], a.stride))
            attrs = dict(d.attrs)
            out = np.empty((len(steps),) + tuple(out_zyx), np.float32)
            for k, s in enumerate(steps):
                out[k] = step(d[s].astype(np.float64))
    except (ValueError, OSError) as e:
        print(f"{tool}: error: {e}", file=sys.stderr)
        return 1
    attrs["dims"] = np.array(out_zyx[::-1], np.int64)
    attrs["steps"] = np.int64(len(steps))
    if "times" in attrs:
        attrs["times"] = np.asarray(attrs["times"])[steps]
    if "spacing" in attrs:
        attrs["spacing"] = np.asarray(attrs["spacing"], np.float64) * spacing_scale
    attrs["source"] = (str(attrs.get("source", "")) + f"; {note}, every {a.stride} step(s) from "
                       f"{os.path.basename(a.input)}")
    write_series(a.output, a.field, out, attrs, gzip=gzip)
    print(f"{tool}: wrote {a.output}: {out.shape}, {os.path.getsize(a.output)} bytes",
          file=sys.stderr)
    return 0
