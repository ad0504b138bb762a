#!/usr/bin/python3
"""Writes the small reader fixtures in tests/data with real writers (VTK 9 and h5py).

Every field holds f(x, y, z, t) = x + 10*y + 100*z + 1000*t on a grid of NX x NY x NZ points
(x fastest), so the C++ tests check exact values against the formula. Run from anywhere:
    /usr/bin/python3 tests/data/make_fixtures.py
Needs python3-vtk9 and python3-h5py (Debian); they are not runtime dependencies.
"""
import json
import os

import h5py
import numpy as np
import vtk
from vtk.util import numpy_support

HERE = os.path.dirname(os.path.abspath(__file__))
NX, NY, NZ = 5, 4, 3
STEPS = 3
# Time values deliberately not in file-name order: readers must sort by time.
TIMES = [0.0, 0.25, 0.5]


def f(t, shape=(NZ, NY, NX)):
    """f on a (z, y, x) grid, as float64."""
    z, y, x = np.meshgrid(*(np.arange(n) for n in shape), indexing="ij")
    return (x + 10 * y + 100 * z + 1000 * t).astype(np.float64)


def cell_f(t):
    """f at the lower corner of each cell: the value a cell-data field stores."""
    return f(t, (NZ - 1, NY - 1, NX - 1))


# ---------------------------------------------------------------- VTK XML image data
def make_image(t, dims=(NX, NY, NZ)):
    img = vtk.vtkImageData()
    img.SetDimensions(*dims)
    img.SetOrigin(0.0, 0.0, 0.0)
    img.SetSpacing(1.0, 1.0, 1.0)
    nx, ny, nz = dims
    vals = f(t, (nz, ny, nx)).ravel()  # C order of (z, y, x) = x fastest, as VTK stores points
    a = numpy_support.numpy_to_vtk(vals.astype(np.float32), deep=1)
    a.SetName("f")
    img.GetPointData().AddArray(a)
    g = numpy_support.numpy_to_vtk(vals.astype(np.int16), deep=1, array_type=vtk.VTK_SHORT)
    g.SetName("g")
    img.GetPointData().AddArray(g)
    v = numpy_support.numpy_to_vtk(np.repeat(vals, 3).reshape(-1, 3).astype(np.float32), deep=1)
    v.SetName("v")
    img.GetPointData().AddArray(v)
    img.GetPointData().SetActiveScalars("f")
    if dims == (NX, NY, NZ):
        c = numpy_support.numpy_to_vtk(cell_f(t).ravel().astype(np.float64), deep=1)
        c.SetName("c")
        img.GetCellData().AddArray(c)
    return img


# name -> writer configuration
VTI_VARIANTS = {
    "ascii": dict(mode="ascii"),
    "binary": dict(mode="binary"),
    "appended_raw": dict(mode="appended", encode=False, header64=True),
    "appended_b64": dict(mode="appended", encode=True),
    "zlib_appended": dict(mode="appended", encode=False, zlib=True),
    "zlib_binary_be": dict(mode="binary", zlib=True, big_endian=True, header64=True),
    "pieces": dict(mode="appended", encode=False, pieces=3),
}


def write_vti(path, img, mode, encode=False, header64=False, zlib=False, big_endian=False,
              pieces=1, lz4=False):
    w = vtk.vtkXMLImageDataWriter()
    w.SetFileName(path)
    w.SetInputData(img)
    {"ascii": w.SetDataModeToAscii, "binary": w.SetDataModeToBinary,
     "appended": w.SetDataModeToAppended}[mode]()
    w.SetEncodeAppendedData(1 if encode else 0)
    w.SetHeaderTypeToUInt64() if header64 else w.SetHeaderTypeToUInt32()
    if zlib:
        w.SetCompressorTypeToZLib()
        w.SetBlockSize(64)  # several blocks and a partial last one
    elif lz4:
        w.SetCompressorTypeToLZ4()
    else:
        w.SetCompressorTypeToNone()
    w.SetByteOrderToBigEndian() if big_endian else w.SetByteOrderToLittleEndian()
    w.SetNumberOfPieces(pieces)
    assert w.Write() == 1, path


def make_vti():
    out = os.path.join(HERE, "vti")
    os.makedirs(out, exist_ok=True)
    for name, cfg in VTI_VARIANTS.items():
        files = []
        for t in range(STEPS):
            fname = f"{name}_{t}.vti"
            write_vti(os.path.join(out, fname), make_image(t), **cfg)
            files.append(fname)
        # .pvd lists the steps out of order; timestep values give the order.
        order = [2, 0, 1]
        with open(os.path.join(out, f"{name}.pvd"), "w") as fh:
            fh.write('<?xml version="1.0"?>\n<VTKFile type="Collection" version="0.1">\n'
                     '  <Collection>\n')
            for t in order:
                fh.write(f'    <DataSet timestep="{TIMES[t]}" part="0" file="{files[t]}"/>\n')
            fh.write("  </Collection>\n</VTKFile>\n")
        series = {"file-series-version": "1.0",
                  "files": [{"name": files[t], "time": TIMES[t]} for t in order]}
        with open(os.path.join(out, f"{name}.vti.series"), "w") as fh:
            json.dump(series, fh, indent=1)
    # A grid of another size, for the inconsistent-steps test.
    write_vti(os.path.join(out, "other_dims.vti"), make_image(0, (4, 4, 3)), mode="ascii")
    # A compressor the readers do not support.
    write_vti(os.path.join(out, "lz4.vti"), make_image(0), mode="appended", lz4=True)


# ---------------------------------------------------------------- HDF5 / NetCDF-like / VTKHDF
def make_h5():
    out = os.path.join(HERE, "h5")
    os.makedirs(out, exist_ok=True)
    all_steps = np.stack([f(t) for t in range(STEPS)])  # (T, Z, Y, X)

    with h5py.File(os.path.join(out, "grid4d.h5"), "w") as h:
        h.create_dataset("f", data=all_steps.astype(np.float32))
        h.create_dataset("time", data=np.array(TIMES))
        h.create_dataset("single", data=f(0).astype(np.float64))  # a 3-D dataset: one step
        g = h.create_group("grp")
        g.create_dataset("d", data=f(2).astype(np.float64))
        h.create_dataset("plane", data=f(0)[0].astype(np.float32))  # 2-D: wrong rank

    with h5py.File(os.path.join(out, "group_steps.h5"), "w") as h:
        g = h.create_group("steps")
        # Natural order must give t1, t2, t10 (plain string order would be t1, t10, t2).
        for t in (10, 2, 1):
            g.create_dataset(f"t{t}", data=f(t).astype(np.float32))
        bad = h.create_group("mixed")
        bad.create_dataset("a0", data=f(0).astype(np.float32))
        bad.create_dataset("a1", data=f(1, (NZ, NY, NX + 1)).astype(np.float32))

    with h5py.File(os.path.join(out, "int16.h5"), "w") as h:
        h.create_dataset("plain", data=all_steps.astype(np.int16))
        # NetCDF/CF packing: stored s, value = s * scale_factor + add_offset.
        # The stored s is 2*f so the unpacked value is f + 100 (exact in float).
        packed = (2 * all_steps).astype(np.int16)
        packed[1, 0, 0, 0] = -1  # _FillValue
        packed[2, 1, 2, 3] = -2  # missing_value
        d = h.create_dataset("packed", data=packed)
        d.attrs["scale_factor"] = np.float32(0.5)
        d.attrs["add_offset"] = np.float64(100.0)
        d.attrs["_FillValue"] = np.int16(-1)
        d.attrs["missing_value"] = np.int16(-2)
        u = h.create_dataset("u64", data=all_steps.astype(np.uint64))
        u.attrs["units"] = "m"

    with h5py.File(os.path.join(out, "bad_types.h5"), "w") as h:
        h.create_dataset("text", data=np.full((NZ, NY, NX), b"abc", dtype="S3"))
        cmp_t = np.dtype([("a", np.float32), ("b", np.int32)])
        h.create_dataset("compound", data=np.zeros((NZ, NY, NX), dtype=cmp_t))
        h.create_dataset("plane", data=f(0)[0].astype(np.float32))
        d = h.create_dataset("bad_scale", data=f(0).astype(np.float32))
        d.attrs["scale_factor"] = "two"  # a string where a number is expected

    write_vtkhdf_transient(os.path.join(out, "vtkhdf_transient.hdf"))
    write_vtkhdf_static(os.path.join(out, "vtkhdf_static.hdf"))


def fixed_string(s):
    """An ASCII fixed-length string attribute value, as VTK's own writer stores Type."""
    return np.bytes_(s)


def write_vtkhdf_transient(path):
    # VTKHDF 2.x transient ImageData: arrays (time, z, y, x[, comps]), Steps/NSteps, and
    # Steps/{Point,Cell}DataOffsets/<name> = index along time per step. Four steps replay three
    # stored volumes: step 2 re-reads stored index 1.
    nsteps, stored = 4, [0, 1, 2]
    offsets = np.array([0, 1, 1, 2], dtype=np.int64)
    with h5py.File(path, "w") as h:
        root = h.create_group("VTKHDF")
        root.attrs["Version"] = np.array([2, 1], dtype=np.int64)
        root.attrs.create("Type", fixed_string("ImageData"))
        root.attrs["WholeExtent"] = np.array([0, NX - 1, 0, NY - 1, 0, NZ - 1], dtype=np.int64)
        root.attrs["Origin"] = np.zeros(3)
        root.attrs["Spacing"] = np.ones(3)
        root.attrs["Direction"] = np.eye(3).ravel()
        pd = root.create_group("PointData")
        pd.attrs.create("Scalars", fixed_string("f"))
        pd.create_dataset("f", data=np.stack([f(t) for t in stored]).astype(np.float32))
        vec = np.stack([f(t) for t in stored])[..., None].repeat(3, axis=-1)
        pd.create_dataset("v", data=vec.astype(np.float32))
        cd = root.create_group("CellData")
        cd.create_dataset("c", data=np.stack([cell_f(t) for t in stored]).astype(np.float64))
        steps = root.create_group("Steps")
        steps.attrs["NSteps"] = np.int64(nsteps)
        steps.create_dataset("Values", data=np.arange(nsteps) * 0.5)
        pdo = steps.create_group("PointDataOffsets")
        pdo.create_dataset("f", data=offsets)
        pdo.create_dataset("v", data=offsets)
        cdo = steps.create_group("CellDataOffsets")
        cdo.create_dataset("c", data=offsets)


def write_vtkhdf_static(path):
    with h5py.File(path, "w") as h:
        root = h.create_group("VTKHDF")
        root.attrs["Version"] = np.array([2, 0], dtype=np.int64)
        root.attrs["Type"] = "ImageData"  # h5py writes a variable-length UTF-8 string
        root.attrs["WholeExtent"] = np.array([0, NX - 1, 0, NY - 1, 0, NZ - 1], dtype=np.int64)
        root.attrs["Origin"] = np.zeros(3)
        root.attrs["Spacing"] = np.ones(3)
        root.attrs["Direction"] = np.eye(3).ravel()
        pd = root.create_group("PointData")
        pd.create_dataset("f", data=f(0).astype(np.float64))


def make_scales(path):
    """h5/scales.h5: f over steps as a 4-D (t, z, y, x) dataset with NetCDF-4-style dimension
    scales attached: z = 10, 12, 14 and y = 0, 0.5, 1, 1.5 step uniformly, x (1, 1.1, 1.3, 1.4,
    2) does not, so the reader takes origin (0, 0, 10) and spacing (1, 0.5, 2)."""
    with h5py.File(path, "w") as h:
        h["time"] = np.arange(3, dtype=np.float64)
        h["z"] = np.array([10.0, 12.0, 14.0])
        h["y"] = np.array([0.0, 0.5, 1.0, 1.5])
        h["x"] = np.array([1.0, 1.1, 1.3, 1.4, 2.0])
        d = h.create_dataset("f", data=np.stack([f(t) for t in range(3)]))
        for i, name in enumerate(["time", "z", "y", "x"]):
            h[name].make_scale(name)
            d.dims[i].attach_scale(h[name])


def make_wrf_like(path):
    """h5/wrf_like.nc: what a WRF output file gives the reader, small: global DX = 2000 and
    DY = 3000 (metres), T over 2 steps of (z, y, x) = (3, 4, 5), the geopotential PH + PHB on 4
    staggered levels at heights 100, 400, 700, 1000 m (times g = 9.81; PH carries a part of it
    that varies across the plane and averages to 0), and Times 3 hours apart. The reader takes
    spacing (2000, 3000, 300), origin z 250 (half a layer above the lowest level) and times 0,
    10800."""
    g = 9.81
    heights = np.array([100.0, 400.0, 700.0, 1000.0])
    with h5py.File(path, "w") as h:
        h.attrs["DX"] = np.float32(2000)
        h.attrs["DY"] = np.float32(3000)
        h["T"] = np.stack([f(t) for t in range(2)]).astype(np.float32)
        wobble = np.tile(np.array([[1.0, -1.0, 2.0, -2.0, 0.0]]), (NY, 1))  # sums to 0 per row
        ph = np.stack([np.stack([g * 0.5 * hz + wobble for hz in heights]) for _ in range(2)])
        phb = np.stack([np.stack([g * 0.5 * hz * np.ones((NY, NX)) for hz in heights])
                        for _ in range(2)])
        h["PH"] = ph.astype(np.float64)
        h["PHB"] = phb.astype(np.float64)
        dates = ["2005-08-28_12:00:00", "2005-08-28_15:00:00"]
        h["Times"] = np.array([list(d) for d in dates], dtype="S1")


def make_map_over_time(path):
    """h5/map_over_time.nc: NetCDF-4-style dimension scales Time, south_north, west_east; /T2 is a
    2-D field over 3 times (3, 4, 5), like WRF's T2; /T a 4-D field (3, 2, 4, 5); /slab a plain
    3-D (z, y, x) = (3, 4, 5) dataset whose first dimension is not time. The reader refuses T2
    as a map over time, names it so among the candidates, and reads slab as one volume. Time is a
    CF time coordinate: 0, 6, 12 "hours since 2000-01-01 00:00:00", calendar "standard"."""
    with h5py.File(path, "w") as h:
        for name, n in (("Time", 3), ("bottom_top", 2), ("south_north", NY), ("west_east", NX)):
            h[name] = np.arange(n, dtype=np.float64) * (6.0 if name == "Time" else 1.0)
            h[name].make_scale(name)
        h["Time"].attrs["units"] = "hours since 2000-01-01 00:00:00"
        h["Time"].attrs["calendar"] = "standard"
        t2 = h.create_dataset("T2", data=np.stack([f(t)[0] for t in range(3)]).astype(np.float32))
        for i, name in enumerate(["Time", "south_north", "west_east"]):
            t2.dims[i].attach_scale(h[name])
        t = h.create_dataset("T", data=np.stack([f(t)[:2] for t in range(3)]).astype(np.float32))
        for i, name in enumerate(["Time", "bottom_top", "south_north", "west_east"]):
            t.dims[i].attach_scale(h[name])
        h["slab"] = f(0).astype(np.float32)


if __name__ == "__main__":
    make_vti()
    make_h5()
    make_scales(os.path.join(HERE, "h5", "scales.h5"))
    make_wrf_like(os.path.join(HERE, "h5", "wrf_like.nc"))
    make_map_over_time(os.path.join(HERE, "h5", "map_over_time.nc"))
