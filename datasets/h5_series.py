"""Shared by the dataset tools (downsample_h5.py, upsample_h5.py): writing one 4-D (T, Z, Y, X)
series dataset with its attributes atomically (a temporary name in the output's directory,
renamed when complete; removed on any failure) and readable by everyone the umask allows."""

import os
import tempfile

import h5py


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
