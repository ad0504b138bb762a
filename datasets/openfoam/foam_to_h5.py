#!/usr/bin/env python3
"""Import scalar fields of a single-block uniform OpenFOAM case into one HDF5 file.

A tool for *making* tspplay's datasets, not part of tspplay: it needs Python 3 with numpy
and h5py (Debian: python3-numpy python3-h5py), which tspplay itself never uses.

Reads the ASCII ``internalField`` (``uniform V``, ``nonuniform List<scalar> N (...)`` or the
compact ``N{V}``) of each named field in every time directory of CASE (plain or ``.gz``
files), checks the cell count against the lattice dims, and writes one 4-D float32 dataset
``/NAME`` with shape (T, Z, Y, X), x fastest, per field. The layout follows
``tsp/source/hdf5_writer.h``: chunked by step, attributes ``dims`` (int64[3], x y z), ``steps``,
``axes`` ("t,z,y,x"), ``source``, plus ``times`` (float64[T], simulated seconds),
``case``, ``solver``, ``origin`` and ``spacing`` (float64[3], metres, x y z), ``foam_class``
and ``foam_dimensions``. The file is written under a hidden temporary name beside the target
and renamed at the end; on error nothing is left behind.

Dims come from ``--dims NX NY NZ`` or from ``constant/polyMesh/points``: blockMesh writes the
points of one uniform block as a lattice x fastest, then y, then z, and numbers the cells the
same way; the importer checks that the points really form that lattice with uniform spacing.
If a time directory holds the cell-centre field ``C`` (``postProcess -func writeCellCentres``),
every cell centre is checked against the lattice order too.

Usage: foam_to_h5.py CASE -o OUT.h5 [--field T ...] [--dims NX NY NZ] [--case-name NAME]
                      [--gzip L]

Errors (exit 1) name the file and what was expected versus found.
"""

import argparse
import gzip
import os
import re
import sys
import tempfile

import h5py
import numpy as np

# Relative tolerance for "the points form a uniform lattice" (ASCII mesh files carry ~6-7
# significant digits).
LATTICE_RTOL = 1e-5


class ImportError_(Exception):
    """A problem with the case's files; the message names the file."""


def read_text(path):
    """Returns the text of PATH or PATH.gz; raises ImportError_ when neither exists."""
    if os.path.isfile(path):
        with open(path, "rb") as f:
            data = f.read()
    elif os.path.isfile(path + ".gz"):
        path += ".gz"
        with gzip.open(path, "rb") as f:
            data = f.read()
    else:
        raise ImportError_(f"{path}: no such file (nor {os.path.basename(path)}.gz)")
    try:
        return data.decode("ascii"), path
    except UnicodeDecodeError:
        raise ImportError_(f"{path}: not ASCII text; expected writeFormat ascii")


def exists_field(path):
    return os.path.isfile(path) or os.path.isfile(path + ".gz")


_COMMENTS = re.compile(r"/\*.*?\*/|//[^\n]*", re.S)


def strip_comments(text):
    return _COMMENTS.sub(" ", text)


def parse_header(text, path):
    """Returns the FoamFile header entries as a dict of strings."""
    m = re.search(r"\bFoamFile\s*\{(.*?)\}", text, re.S)
    if not m:
        raise ImportError_(f"{path}: no FoamFile header; expected an OpenFOAM file")
    header = {}
    for entry in m.group(1).split(";"):
        parts = entry.split(None, 1)
        if len(parts) == 2:
            header[parts[0]] = parts[1].strip().strip('"')
    if header.get("format", "ascii") != "ascii":
        raise ImportError_(
            f"{path}: format is '{header['format']}', expected ascii (set writeFormat ascii)")
    return header, m.end()


def parse_list(body, pos, path, what, width):
    """Parses an OpenFOAM list at body[pos:]: 'N ( ... )' or 'N{V}'.

    Returns (array of N*width floats, end position). width is 1 for scalars, 3 for vectors.
    """
    m = re.compile(r"\s*(\d+)\s*([({])").match(body, pos)
    if not m:
        raise ImportError_(f"{path}: {what}: expected a list 'N (...)' or 'N{{value}}'")
    n = int(m.group(1))
    if m.group(2) == "{":
        close = body.find("}", m.end())
        if close < 0:
            raise ImportError_(f"{path}: {what}: unterminated 'N{{value}}' list")
        value = parse_values(body[m.end():close], path, what, width)
        if value.size != width:
            raise ImportError_(
                f"{path}: {what}: 'N{{value}}' holds {value.size} numbers, expected {width}")
        return np.tile(value, n), close + 1
    # The list ends at the first ')' followed by ';' or, in a mesh file, by the end of the
    # text (vector entries are themselves in parentheses, followed by other entries).
    end = re.compile(r"\)\s*(?:;|\Z)").search(body, m.end())
    if not end:
        raise ImportError_(f"{path}: {what}: unterminated list of {n} entries")
    values = parse_values(body[m.end():end.start()], path, what, width)
    if values.size != n * width:
        raise ImportError_(
            f"{path}: {what}: list says {n} entries but holds {values.size // width}")
    return values, end.start() + 1


def parse_values(text, path, what, width):
    if width != 1:
        text = text.replace("(", " ").replace(")", " ")
    try:
        return np.array(text.split(), dtype=np.float64)
    except ValueError as e:
        raise ImportError_(f"{path}: {what}: not a number in the list ({e})")


def read_internal_field(path, n_cells, width=1):
    """Returns (float64 array of n_cells*width values, header dict) of a volume field file."""
    text, path = read_text(path)
    header, pos = parse_header(text, path)
    body = strip_comments(text[pos:])
    expected_class = "volScalarField" if width == 1 else "volVectorField"
    if header.get("class") != expected_class:
        raise ImportError_(
            f"{path}: class is '{header.get('class')}', expected {expected_class}")
    m = re.search(r"\binternalField\s+(uniform|nonuniform)\b", body)
    if not m:
        raise ImportError_(f"{path}: no 'internalField uniform|nonuniform' entry")
    if m.group(1) == "uniform":
        end = body.find(";", m.end())
        value = parse_values(body[m.end():end], path, "internalField uniform", width)
        if value.size != width:
            raise ImportError_(
                f"{path}: internalField uniform holds {value.size} numbers, expected {width}")
        return np.tile(value, n_cells), header
    list_type = "List<scalar>" if width == 1 else "List<vector>"
    t = re.compile(r"\s*" + re.escape(list_type)).match(body, m.end())
    if not t:
        found = body[m.end():m.end() + 30].split()
        raise ImportError_(
            f"{path}: internalField nonuniform is '{found[0] if found else ''}', "
            f"expected {list_type}")
    values, _ = parse_list(body, t.end(), path, "internalField", width)
    if values.size != n_cells * width:
        raise ImportError_(
            f"{path}: internalField has {values.size // width} cells, expected {n_cells} "
            f"(lattice dims)")
    return values, header


def lattice_from_points(case):
    """Returns (dims[3], origin[3], spacing[3]) of a single uniform block's point lattice."""
    path = os.path.join(case, "constant", "polyMesh", "points")
    text, path = read_text(path)
    header, pos = parse_header(text, path)
    body = strip_comments(text[pos:])
    pts, _ = parse_list(body, 0, path, "points", 3)
    pts = pts.reshape(-1, 3)
    axes = []
    for a in range(3):
        u = np.unique(pts[:, a])
        lo, hi = u[0], u[-1]
        tol = LATTICE_RTOL * max(hi - lo, 1e-30)
        # Merge coordinates that differ only by ASCII rounding.
        keep = np.concatenate(([True], np.diff(u) > tol))
        axes.append((u[keep], tol))
    dims = [len(c) - 1 for c, _ in axes]
    if np.prod([d + 1 for d in dims]) != len(pts):
        raise ImportError_(
            f"{path}: {len(pts)} points do not form one lattice: distinct coordinates give "
            f"{dims[0] + 1}x{dims[1] + 1}x{dims[2] + 1} = {np.prod([d + 1 for d in dims])} "
            f"points; expected a single-block uniform blockMesh")
    origin, spacing = [], []
    for a, (c, tol) in enumerate(axes):
        step = (c[-1] - c[0]) / dims[a]
        if np.abs(np.diff(c) - step).max() > tol:
            raise ImportError_(
                f"{path}: axis {'xyz'[a]} spacing is not uniform (expected {step:g} everywhere)")
        origin.append(c[0])
        spacing.append(step)
    # Lattice order: x fastest, then y, then z.
    i = np.arange(len(pts))
    nx1, ny1 = dims[0] + 1, dims[1] + 1
    ijk = (i % nx1, (i // nx1) % ny1, i // (nx1 * ny1))
    for a in range(3):
        expect = origin[a] + ijk[a] * spacing[a]
        bad = np.flatnonzero(np.abs(pts[:, a] - expect) > axes[a][1])
        if bad.size:
            k = bad[0]
            raise ImportError_(
                f"{path}: point {k} is {tuple(pts[k])}, expected "
                f"{'xyz'[a]}={expect[k]:g} for a lattice ordered x fastest, then y, then z")
    return dims, np.array(origin), np.array(spacing)


def time_dirs(case):
    """Returns [(time value, directory name)] of CASE's time directories, in time order."""
    out = []
    for name in os.listdir(case):
        if not os.path.isdir(os.path.join(case, name)):
            continue
        try:
            out.append((float(name), name))
        except ValueError:
            pass
    out.sort()
    return out


def check_cell_centres(case, times, dims, origin, spacing):
    """Checks cell order against a 'C' field, if the case has one in some time directory."""
    for _, name in times:
        path = os.path.join(case, name, "C")
        if exists_field(path):
            n = int(np.prod(dims))
            c, _ = read_internal_field(path, n, width=3)
            c = c.reshape(-1, 3)
            i = np.arange(n)
            ijk = np.stack((i % dims[0], (i // dims[0]) % dims[1], i // (dims[0] * dims[1])), 1)
            expect = origin + (ijk + 0.5) * spacing
            err = np.abs(c - expect).max(axis=1)
            bad = np.flatnonzero(err > 1e-3 * spacing.min())
            if bad.size:
                k = bad[0]
                raise ImportError_(
                    f"{path}: cell {k} centre is {tuple(c[k])}, expected {tuple(expect[k])} "
                    f"for cells ordered x fastest, then y, then z")
            return path
    return None


def controldict_application(case):
    try:
        text, _ = read_text(os.path.join(case, "system", "controlDict"))
    except ImportError_:
        return ""
    m = re.search(r"^\s*application\s+([^;\s]+)\s*;", strip_comments(text), re.M)
    return m.group(1) if m else ""


def umask_mode():
    """Returns the mode a new file gets (mkstemp's 0600 would hide the data from others)."""
    mask = os.umask(0)
    os.umask(mask)
    return 0o666 & ~mask


def write_h5(out, case, case_name, fields, dims, origin, spacing, times, gzip_level):
    """Reads every field at every time and writes OUT via a temporary file in its directory."""
    out_dir = os.path.dirname(os.path.abspath(out))
    fd, tmp = tempfile.mkstemp(prefix="." + os.path.basename(out) + ".", suffix=".tmp",
                               dir=out_dir)
    os.close(fd)
    n = int(np.prod(dims))
    solver = controldict_application(case)
    try:
        with h5py.File(tmp, "w") as f:
            for field in fields:
                shape = (len(times), dims[2], dims[1], dims[0])
                kw = {}
                if gzip_level:
                    kw = dict(compression="gzip", compression_opts=gzip_level, shuffle=True)
                ds = f.create_dataset(field, shape=shape, dtype="<f4",
                                      chunks=(1,) + shape[1:], **kw)
                header = None
                for k, (_, name) in enumerate(times):
                    values, header_k = read_internal_field(os.path.join(case, name, field), n)
                    header = header or header_k
                    ds[k] = values.astype(np.float32).reshape(shape[1:])
                    print(f"  {field} t={name}: min {values.min():.6g} max {values.max():.6g}",
                          file=sys.stderr)
                dim_text, _ = read_text(os.path.join(case, times[0][1], field))
                dm = re.search(r"^\s*dimensions\s+(\[[^\]]*\])", dim_text, re.M)
                ds.attrs["dims"] = np.array(dims, dtype=np.int64)
                ds.attrs["steps"] = np.int64(len(times))
                ds.attrs["axes"] = "t,z,y,x"
                ds.attrs["source"] = (f"OpenFOAM case '{case_name}' ({solver}), field {field}, "
                                      f"cell values, imported by foam_to_h5.py")
                ds.attrs["times"] = np.array([t for t, _ in times], dtype=np.float64)
                ds.attrs["case"] = case_name
                ds.attrs["solver"] = solver
                ds.attrs["origin"] = origin.astype(np.float64)
                ds.attrs["spacing"] = spacing.astype(np.float64)
                ds.attrs["foam_class"] = header.get("class", "")
                ds.attrs["foam_dimensions"] = dm.group(1) if dm else ""
        os.chmod(tmp, umask_mode())
        os.replace(tmp, out)
    except BaseException:
        os.unlink(tmp)
        raise


def main(argv=None):
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("case", help="OpenFOAM case directory")
    p.add_argument("-o", "--output", required=True, help="HDF5 file to write")
    p.add_argument("--field", action="append",
                   help="scalar field name (repeatable; default T)")
    p.add_argument("--dims", nargs=3, type=int, metavar=("NX", "NY", "NZ"),
                   help="cell counts; default: from constant/polyMesh/points")
    p.add_argument("--origin", nargs=3, type=float, default=[0.0, 0.0, 0.0],
                   help="lattice origin, only used with --dims")
    p.add_argument("--spacing", nargs=3, type=float, default=[1.0, 1.0, 1.0],
                   help="cell size, only used with --dims")
    p.add_argument("--case-name",
                   help="name stored in the 'case' attribute (default: CASE's directory name)")
    p.add_argument("--gzip", type=int, default=0, choices=range(0, 10), metavar="L",
                   help="gzip level 1-9 for the datasets (default 0: none)")
    args = p.parse_args(argv)
    fields = args.field or ["T"]
    try:
        if not os.path.isdir(args.case):
            raise ImportError_(f"{args.case}: not a directory; expected an OpenFOAM case")
        if args.dims:
            if min(args.dims) < 1:
                raise ImportError_(f"--dims {args.dims}: expected three positive cell counts")
            dims = list(args.dims)
            origin, spacing = np.array(args.origin), np.array(args.spacing)
        else:
            dims, origin, spacing = lattice_from_points(args.case)
        times = time_dirs(args.case)
        if not times:
            raise ImportError_(f"{args.case}: no time directories")
        for field in fields:
            missing = [name for _, name in times
                       if not exists_field(os.path.join(args.case, name, field))]
            if missing:
                raise ImportError_(
                    f"{args.case}: field '{field}' missing in time directories "
                    f"{', '.join(missing[:5])}{' ...' if len(missing) > 5 else ''}; "
                    f"expected it in all {len(times)}")
        checked = check_cell_centres(args.case, times, dims, origin, spacing)
        print(f"foam_to_h5: {args.case}: {dims[0]}x{dims[1]}x{dims[2]} cells, "
              f"{len(times)} times {times[0][1]}..{times[-1][1]}"
              f"{', cell order checked against ' + checked if checked else ''}",
              file=sys.stderr)
        case_name = args.case_name or os.path.basename(os.path.abspath(args.case))
        write_h5(args.output, args.case, case_name, fields, dims, origin, spacing, times, args.gzip)
    except (ImportError_, OSError) as e:
        print(f"foam_to_h5: error: {e}", file=sys.stderr)
        return 1
    print(f"foam_to_h5: wrote {args.output}", file=sys.stderr)
    return 0


if __name__ == "__main__":
    sys.exit(main())
