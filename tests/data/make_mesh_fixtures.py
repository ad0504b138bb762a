#!/usr/bin/python3
"""Unstructured-grid reader fixtures (tests/data/vtu/), written by VTK's own writers (python3-vtk9)
and, for VTKHDF, by h5py following VTK's "VTKHDF File Format" specification.

One mesh of six disjoint cells, one of each type the voxelizer reads (tetra, voxel, hexahedron,
wedge, pyramid, polyhedron), steps t = 0, 1, 2. Point field f = x + 10·y + 100·z + 1000·t
(Float32), point vector v = (x, 2y, 3z) (Float64, 3 components), cell field c = 7·cell + t
(Float32). Point coordinates are small multiples of 1/4, so f is exact in float. Run:
    /usr/bin/python3 tests/data/make_mesh_fixtures.py
"""
import json
import os

import h5py
import numpy as np
import vtk

OUT = os.path.join(os.path.dirname(os.path.abspath(__file__)), "vtu")
STEPS = [0, 1, 2]
TIMES = [0.5, 0.0, 0.25]  # listed in this order; readers sort by time (step t has TIMES[t])


def cells():
    """(type, points) for the six cells, each placed in its own unit box along x."""
    tet = [(0, 0, 0), (1, 0, 0), (0, 1, 0), (0, 0, 1)]
    vox = [(0, 0, 0), (1, 0, 0), (0, 1, 0), (1, 1, 0), (0, 0, 1), (1, 0, 1), (0, 1, 1), (1, 1, 1)]
    hexa = [(0, 0, 0), (1, 0, 0), (1, 1, 0), (0, 1, 0), (0, 0, 1), (1, 0, 1), (1, 1, 1), (0, 1, 1)]
    wedge = [(0, 0, 0), (1, 0, 0), (0, 1, 0), (0, 0, 1), (1, 0, 1), (0, 1, 1)]
    pyr = [(0, 0, 0), (1, 0, 0), (1, 1, 0), (0, 1, 0), (0.5, 0.5, 1)]
    return [(vtk.VTK_TETRA, tet), (vtk.VTK_VOXEL, vox), (vtk.VTK_HEXAHEDRON, hexa),
            (vtk.VTK_WEDGE, wedge), (vtk.VTK_PYRAMID, pyr), (vtk.VTK_POLYHEDRON, hexa)]


def make_grid(t):
    ug = vtk.vtkUnstructuredGrid()
    pts = vtk.vtkPoints()
    pts.SetDataTypeToFloat()
    coords = []
    for k, (ctype, local) in enumerate(cells()):
        ids = []
        for (x, y, z) in local:
            ids.append(pts.InsertNextPoint(x + 2 * k, y, z))
            coords.append((x + 2 * k, y, z))
        if ctype == vtk.VTK_POLYHEDRON:
            faces = [[0, 3, 2, 1], [4, 5, 6, 7], [0, 1, 5, 4], [1, 2, 6, 5], [2, 3, 7, 6], [3, 0, 4, 7]]
            stream = [len(faces)]
            for fc in faces:
                stream += [len(fc)] + [ids[i] for i in fc]
            idl = vtk.vtkIdList()
            for v in stream:
                idl.InsertNextId(v)
            ug.InsertNextCell(ctype, idl)
        else:
            ug.InsertNextCell(ctype, len(ids), ids)
    ug.SetPoints(pts)
    xyz = np.array(coords, dtype=np.float64)
    f = vtk.vtkFloatArray()
    f.SetName("f")
    for x, y, z in xyz:
        f.InsertNextValue(x + 10 * y + 100 * z + 1000 * t)
    v = vtk.vtkDoubleArray()
    v.SetName("v")
    v.SetNumberOfComponents(3)
    for x, y, z in xyz:
        v.InsertNextTuple3(x, 2 * y, 3 * z)
    c = vtk.vtkFloatArray()
    c.SetName("c")
    for k in range(ug.GetNumberOfCells()):
        c.InsertNextValue(7 * k + t)
    ug.GetPointData().AddArray(f)
    ug.GetPointData().AddArray(v)
    ug.GetPointData().SetActiveScalars("f")
    ug.GetCellData().AddArray(c)
    return ug


VARIANTS = {
    "ascii": dict(mode="ascii"),
    "binary": dict(mode="binary"),
    "appended": dict(mode="appended"),
    "base64": dict(mode="appended", encode=True),
    "zlib64": dict(mode="appended", zlib=True, header64=True),
    "zlib_binary": dict(mode="binary", zlib=True),
}


def write_vtu(path, ug, mode, encode=False, zlib=False, header64=False):
    w = vtk.vtkXMLUnstructuredGridWriter()
    w.SetFileName(path)
    w.SetInputData(ug)
    {"ascii": w.SetDataModeToAscii, "binary": w.SetDataModeToBinary,
     "appended": w.SetDataModeToAppended}[mode]()
    w.SetEncodeAppendedData(1 if encode else 0)
    w.SetHeaderTypeToUInt64() if header64 else w.SetHeaderTypeToUInt32()
    w.SetCompressorTypeToZLib() if zlib else w.SetCompressorTypeToNone()
    assert w.Write() == 1, path


def cell_arrays(ug):
    """ug's cells but polyhedra (their ids), and VTKHDF's Connectivity, Offsets and Types of them."""
    nonpoly = [k for k in range(ug.GetNumberOfCells()) if ug.GetCellType(k) != vtk.VTK_POLYHEDRON]
    conn, offs, types = [], [0], []
    for k in nonpoly:
        ids = ug.GetCell(k).GetPointIds()
        conn += [ids.GetId(i) for i in range(ids.GetNumberOfIds())]
        offs.append(len(conn))
        types.append(ug.GetCellType(k))
    return nonpoly, conn, offs, types


def write_vtkhdf(path, ug, t):
    """A static VTKHDF UnstructuredGrid (version 2.0), one partition."""
    from vtk.util import numpy_support as ns
    with h5py.File(path, "w") as h:
        g = h.create_group("VTKHDF")
        g.attrs["Version"] = np.array([2, 0], dtype=np.int64)
        s = "UnstructuredGrid".encode("ascii")
        g.attrs.create("Type", s, dtype=h5py.string_dtype("ascii", len(s)))
        pts = ns.vtk_to_numpy(ug.GetPoints().GetData()).astype(np.float64)
        nonpoly, conn, offs, types = cell_arrays(ug)
        g["NumberOfPoints"] = np.array([len(pts)], dtype=np.int64)
        g["NumberOfCells"] = np.array([len(types)], dtype=np.int64)
        g["NumberOfConnectivityIds"] = np.array([len(conn)], dtype=np.int64)
        g["Points"] = pts
        g["Connectivity"] = np.array(conn, dtype=np.int64)
        g["Offsets"] = np.array(offs, dtype=np.int64)
        g["Types"] = np.array(types, dtype=np.uint8)
        pd = g.create_group("PointData")
        pd["f"] = ns.vtk_to_numpy(ug.GetPointData().GetArray("f"))
        pd["v"] = ns.vtk_to_numpy(ug.GetPointData().GetArray("v"))
        cd = g.create_group("CellData")
        cd["c"] = ns.vtk_to_numpy(ug.GetCellData().GetArray("c"))[nonpoly]


def main():
    os.makedirs(OUT, exist_ok=True)
    for name, opts in VARIANTS.items():
        for t in STEPS:
            write_vtu(os.path.join(OUT, f"{name}_{t}.vtu"), make_grid(t), **opts)
    # Collections over the zlib64 files, listed out of time order.
    order = [2, 0, 1]
    with open(os.path.join(OUT, "mixed.pvd"), "w") as p:
        p.write('<?xml version="1.0"?>\n<VTKFile type="Collection" version="0.1">\n<Collection>\n')
        for t in order:
            p.write(f'  <DataSet timestep="{TIMES[t]}" part="0" file="zlib64_{t}.vtu"/>\n')
        p.write("</Collection>\n</VTKFile>\n")
    with open(os.path.join(OUT, "mixed.vtu.series"), "w") as s:
        json.dump({"file-series-version": "1.0",
                   "files": [{"name": f"binary_{t}.vtu", "time": TIMES[t]} for t in order]}, s)
    # foamToVTK's layout: a .vtm per step whose "internal" block is the volume, boundary beside.
    for t in STEPS:
        with open(os.path.join(OUT, f"case_{t}.vtm"), "w") as m:
            m.write("<?xml version='1.0'?>\n<VTKFile type='vtkMultiBlockDataSet' version='1.0'>\n"
                    "  <vtkMultiBlockDataSet>\n"
                    f"    <DataSet name='internal' file='appended_{t}.vtu' />\n"
                    "    <Block name='boundary'>\n"
                    f"      <DataSet name='wall' file='wall_{t}.vtp' />\n"
                    "    </Block>\n  </vtkMultiBlockDataSet>\n</VTKFile>\n")
    with open(os.path.join(OUT, "case.vtm.series"), "w") as s:
        json.dump({"file-series-version": "1.0",
                   "files": [{"name": f"case_{t}.vtm", "time": TIMES[t]} for t in order]}, s)
    for t in STEPS:
        write_vtkhdf(os.path.join(OUT, f"mesh_{t}.hdf"), make_grid(t), t)
    write_vtkhdf_transient(os.path.join(OUT, "transient.hdf"))
    make_hostile()



def write_vtkhdf_transient(path):
    """One transient VTKHDF UnstructuredGrid file: the steps' meshes one after another (one
    partition each, the mesh moved by +t along x at step t), with the Steps offsets tables."""
    from vtk.util import numpy_support as ns
    grids = []
    for t in STEPS:
        ug = make_grid(t)
        pts = ug.GetPoints()
        for i in range(pts.GetNumberOfPoints()):
            x, y, z = pts.GetPoint(i)
            pts.SetPoint(i, x + t, y, z)
        f = ug.GetPointData().GetArray("f")
        for i in range(pts.GetNumberOfPoints()):
            x, y, z = pts.GetPoint(i)
            f.SetValue(i, x + 10 * y + 100 * z + 1000 * t)
        grids.append(ug)
    with h5py.File(path, "w") as h:
        g = h.create_group("VTKHDF")
        g.attrs["Version"] = np.array([2, 0], dtype=np.int64)
        s = "UnstructuredGrid".encode("ascii")
        g.attrs.create("Type", s, dtype=h5py.string_dtype("ascii", len(s)))
        cat = {k: [] for k in ("np", "nc", "nconn", "pts", "conn", "offs", "types", "f", "c")}
        for ug in grids:
            nonpoly, conn, offs, types = cell_arrays(ug)
            cat["np"].append(ug.GetNumberOfPoints())
            cat["nc"].append(len(types))
            cat["nconn"].append(len(conn))
            cat["pts"].append(ns.vtk_to_numpy(ug.GetPoints().GetData()).astype(np.float64))
            cat["conn"] += conn
            cat["offs"] += offs
            cat["types"] += types
            cat["f"].append(ns.vtk_to_numpy(ug.GetPointData().GetArray("f")))
            cat["c"].append(ns.vtk_to_numpy(ug.GetCellData().GetArray("c"))[nonpoly])
        g["NumberOfPoints"] = np.array(cat["np"], dtype=np.int64)
        g["NumberOfCells"] = np.array(cat["nc"], dtype=np.int64)
        g["NumberOfConnectivityIds"] = np.array(cat["nconn"], dtype=np.int64)
        g["Points"] = np.concatenate(cat["pts"])
        g["Connectivity"] = np.array(cat["conn"], dtype=np.int64)
        g["Offsets"] = np.array(cat["offs"], dtype=np.int64)
        g["Types"] = np.array(cat["types"], dtype=np.uint8)
        g.create_group("PointData")["f"] = np.concatenate(cat["f"])
        g.create_group("CellData")["c"] = np.concatenate(cat["c"])
        st = g.create_group("Steps")
        st.attrs["NSteps"] = np.int64(len(STEPS))
        st["Values"] = np.array(sorted(TIMES), dtype=np.float64)  # VTKHDF times must increase
        st["PartOffsets"] = np.arange(len(STEPS), dtype=np.int64)
        st["NumberOfParts"] = np.ones(len(STEPS), dtype=np.int64)
        cum = lambda v: np.concatenate([[0], np.cumsum(v)[:-1]]).astype(np.int64)
        st["PointOffsets"] = cum(cat["np"])
        st["CellOffsets"] = cum(cat["nc"])
        st["ConnectivityIdOffsets"] = cum(cat["nconn"])
        st.create_group("PointDataOffsets")["f"] = cum(cat["np"])
        st.create_group("CellDataOffsets")["c"] = cum(cat["nc"])


def make_hostile():
    """hostile_zlib_lie.vtu: the zlib_binary fixture whose Points header claims one block of
    2^40 bytes (a size the data cannot inflate to); hostile_vtkhdf_*.hdf: mesh_0.hdf with a
    connectivity entry, a cell type or an offset broken."""
    import base64
    import re
    import shutil
    import struct
    text = open(os.path.join(OUT, "zlib_binary_0.vtu")).read()
    m = re.search(r'(Name="Points"[^>]*>\s*)([A-Za-z0-9+/=]+)', text)
    b64 = m.group(2)
    # UInt32 header: [nblocks][blocksize][lastsize][csize...], base64-encoded on its own.
    head_len = 4 * 4  # one block
    head = base64.b64decode(b64[:((head_len + 2) // 3) * 4])
    nblocks, bsize, last, csize = struct.unpack("<4I", head[:16])
    lie = struct.pack("<4I", nblocks, 0xFFFFFFFF, 0xFFFFFFFF, csize)
    lie_b64 = base64.b64encode(lie).decode()
    new = lie_b64 + b64[len(lie_b64):]
    open(os.path.join(OUT, "hostile_zlib_lie.vtu"), "w").write(
        text[:m.start(2)] + new + text[m.end(2):])
    for name, dataset, index, value in [("connectivity", "Connectivity", 0, 999),
                                        ("type", "Types", 0, 77),
                                        ("offsets", "Offsets", 2, 1)]:
        path = os.path.join(OUT, f"hostile_vtkhdf_{name}.hdf")
        shutil.copy(os.path.join(OUT, "mesh_0.hdf"), path)
        with h5py.File(path, "r+") as h:
            h["VTKHDF/" + dataset][index] = value


if __name__ == "__main__":
    main()
