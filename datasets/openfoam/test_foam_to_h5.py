#!/usr/bin/env python3
"""Tests for foam_to_h5.py on small hand-written cases (python3 -m unittest, needs numpy+h5py).

Not part of the ctest suite: numpy and h5py are dataset-making tools, not tspplay dependencies.
Run: python3 datasets/openfoam/test_foam_to_h5.py
"""

import contextlib
import gzip
import io
import os
import sys
import tempfile
import unittest

import h5py
import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import foam_to_h5  # noqa: E402

HEADER = """/* comment with a ( and a ; */
FoamFile
{{
    version     2.0;
    format      {fmt};
    class       {cls};
    object      {obj};
}}
// * * //
"""


def write(path, text, gz=False):
    os.makedirs(os.path.dirname(path), exist_ok=True)
    if gz:
        with gzip.open(path + ".gz", "wt") as f:
            f.write(text)
    else:
        with open(path, "w") as f:
            f.write(text)


def points_text(dims, origin, spacing, order=None):
    nx, ny, nz = (d + 1 for d in dims)
    pts = [(origin[0] + i * spacing[0], origin[1] + j * spacing[1], origin[2] + k * spacing[2])
           for k in range(nz) for j in range(ny) for i in range(nx)]
    if order is not None:
        pts = [pts[i] for i in order]
    body = "\n".join(f"({x:.7g} {y:.7g} {z:.7g})" for x, y, z in pts)
    return (HEADER.format(fmt="ascii", cls="vectorField", obj="points")
            + f"\n{len(pts)}\n(\n{body}\n)\n\n// end\n")


def scalar_text(internal, fmt="ascii", cls="volScalarField"):
    return (HEADER.format(fmt=fmt, cls=cls, obj="T")
            + "dimensions [0 0 0 1 0 0 0];\n\ninternalField   " + internal + ";\n\n"
            + "boundaryField\n{\n    floor\n    {\n        type fixedValue;\n"
            + "        value nonuniform List<scalar> 2(1 2);\n    }\n}\n")


def nonuniform(values):
    return ("nonuniform List<scalar> \n" + str(len(values)) + "\n(\n"
            + "\n".join(repr(float(v)) for v in values) + "\n)\n")


def centres_text(dims, origin, spacing, swap_first_two=False):
    n = int(np.prod(dims))
    i = np.arange(n)
    ijk = np.stack((i % dims[0], (i // dims[0]) % dims[1], i // (dims[0] * dims[1])), 1)
    c = np.array(origin) + (ijk + 0.5) * np.array(spacing)
    if swap_first_two:
        c[[0, 1]] = c[[1, 0]]
    body = "\n".join(f"({x:.7g} {y:.7g} {z:.7g})" for x, y, z in c)
    return (HEADER.format(fmt="ascii", cls="volVectorField", obj="C")
            + f"dimensions [0 1 0 0 0 0 0];\ninternalField nonuniform List<vector> \n{n}\n(\n"
            + body + "\n)\n;\nboundaryField\n{\n}\n")


class FoamToH5Test(unittest.TestCase):
    DIMS = (3, 2, 4)          # deliberately all different: catches axis mix-ups
    ORIGIN = (-1.0, 0.5, 2.0)
    SPACING = (0.25, 0.5, 0.125)

    def setUp(self):
        self.tmp = tempfile.TemporaryDirectory()
        self.case = os.path.join(self.tmp.name, "box")
        self.out = os.path.join(self.tmp.name, "box.h5")
        write(os.path.join(self.case, "constant", "polyMesh", "points"),
              points_text(self.DIMS, self.ORIGIN, self.SPACING))
        write(os.path.join(self.case, "system", "controlDict"),
              HEADER.format(fmt="ascii", cls="dictionary", obj="controlDict")
              + "application     buoyantBoussinesqPimpleFoam;\n")
        self.n = int(np.prod(self.DIMS))

    def tearDown(self):
        self.tmp.cleanup()

    def run_main(self, *extra):
        err = io.StringIO()
        with contextlib.redirect_stderr(err):
            rc = foam_to_h5.main([self.case, "-o", self.out, *extra])
        return rc, err.getvalue()

    def test_uniform_nonuniform_compact_and_gzip_steps(self):
        ramp = np.arange(self.n) * 0.5 + 300.25
        write(os.path.join(self.case, "0", "T"), scalar_text("uniform 300"))
        write(os.path.join(self.case, "0.5", "T"), scalar_text(nonuniform(ramp)), gz=True)
        write(os.path.join(self.case, "1e-1", "T"),
              scalar_text(f"nonuniform List<scalar> {self.n}{{301.5}}"))
        os.makedirs(os.path.join(self.case, "notATime"))
        rc, err = self.run_main()
        self.assertEqual(rc, 0, err)
        with h5py.File(self.out, "r") as f:
            d = f["T"]
            nx, ny, nz = self.DIMS
            self.assertEqual(d.shape, (3, nz, ny, nx))
            self.assertEqual(d.dtype, np.float32)
            np.testing.assert_array_equal(d.attrs["times"], [0.0, 0.1, 0.5])
            np.testing.assert_array_equal(d.attrs["dims"], [nx, ny, nz])
            np.testing.assert_allclose(d.attrs["origin"], self.ORIGIN)
            np.testing.assert_allclose(d.attrs["spacing"], self.SPACING)
            self.assertEqual(d.attrs["steps"], 3)
            self.assertEqual(d.attrs["axes"], "t,z,y,x")
            self.assertEqual(d.attrs["solver"], "buoyantBoussinesqPimpleFoam")
            self.assertEqual(d.attrs["case"], "box")
            self.assertEqual(d.attrs["foam_dimensions"], "[0 0 0 1 0 0 0]")
            np.testing.assert_array_equal(d[0], np.full((nz, ny, nx), 300, np.float32))
            np.testing.assert_array_equal(d[1], np.full((nz, ny, nx), 301.5, np.float32))
            # Cell n = i + nx*(j + ny*k) lands at [k, j, i].
            for k, j, i in [(0, 0, 1), (0, 1, 0), (1, 0, 0), (3, 1, 2)]:
                self.assertEqual(d[2, k, j, i], np.float32(ramp[i + nx * (j + ny * k)]))
        leftovers = [p for p in os.listdir(self.tmp.name) if p.endswith(".tmp")]
        self.assertEqual(leftovers, [])

    def test_cell_centres_checked(self):
        write(os.path.join(self.case, "0", "T"), scalar_text("uniform 300"))
        write(os.path.join(self.case, "0", "C"),
              centres_text(self.DIMS, self.ORIGIN, self.SPACING))
        rc, err = self.run_main()
        self.assertEqual(rc, 0, err)
        self.assertIn("cell order checked", err)
        write(os.path.join(self.case, "0", "C"),
              centres_text(self.DIMS, self.ORIGIN, self.SPACING, swap_first_two=True))
        rc, err = self.run_main()
        self.assertEqual(rc, 1)
        self.assertIn("0/C: cell 0 centre", err)
        self.assertFalse(os.path.exists(self.out + ".x"))

    def test_case_name_and_file_mode(self):
        write(os.path.join(self.case, "0", "T"), scalar_text("uniform 1"))
        old = os.umask(0o022)
        try:
            rc, err = self.run_main("--case-name", "hotBox")
        finally:
            os.umask(old)
        self.assertEqual(rc, 0, err)
        self.assertEqual(os.stat(self.out).st_mode & 0o777, 0o644)
        with h5py.File(self.out, "r") as f:
            self.assertEqual(f["T"].attrs["case"], "hotBox")

    def test_given_dims_skip_points(self):
        os.remove(os.path.join(self.case, "constant", "polyMesh", "points"))
        write(os.path.join(self.case, "0", "T"), scalar_text("uniform 7"))
        rc, err = self.run_main("--dims", "3", "2", "4")
        self.assertEqual(rc, 0, err)
        with h5py.File(self.out, "r") as f:
            self.assertEqual(f["T"].shape, (1, 4, 2, 3))

    def expect_error(self, *fragments, extra=()):
        rc, err = self.run_main(*extra)
        self.assertEqual(rc, 1, err)
        for frag in fragments:
            self.assertIn(frag, err)
        self.assertFalse(os.path.exists(self.out))
        self.assertEqual([p for p in os.listdir(self.tmp.name) if p.endswith(".tmp")], [])

    def test_wrong_cell_count(self):
        write(os.path.join(self.case, "0", "T"), scalar_text(nonuniform(np.zeros(self.n - 1))))
        self.expect_error("0/T: internalField has 23 cells, expected 24")

    def test_list_count_mismatch(self):
        text = scalar_text(nonuniform(np.zeros(self.n)))
        text = text.replace(f"\n{self.n}\n", f"\n{self.n + 1}\n")
        write(os.path.join(self.case, "0", "T"), text)
        self.expect_error("0/T: internalField: list says 25 entries but holds 24")

    def test_binary_rejected(self):
        write(os.path.join(self.case, "0", "T"), scalar_text("uniform 1", fmt="binary"))
        self.expect_error("0/T: format is 'binary', expected ascii")

    def test_vector_field_rejected(self):
        write(os.path.join(self.case, "0", "T"),
              scalar_text("uniform (1 2 3)", cls="volVectorField"))
        self.expect_error("0/T: class is 'volVectorField', expected volScalarField")

    def test_field_missing_in_a_time(self):
        write(os.path.join(self.case, "0", "T"), scalar_text("uniform 1"))
        os.makedirs(os.path.join(self.case, "2"))
        self.expect_error("field 'T' missing in time directories 2; expected it in all 2")

    def test_no_time_directories(self):
        self.expect_error("no time directories")

    def test_points_not_a_lattice(self):
        write(os.path.join(self.case, "0", "T"), scalar_text("uniform 1"))
        text = points_text(self.DIMS, self.ORIGIN, self.SPACING)
        text = text.replace("(-1 0.5 2)", "(-1.1 0.5 2)")
        write(os.path.join(self.case, "constant", "polyMesh", "points"), text)
        self.expect_error("polyMesh/points", "do not form one lattice")

    def test_points_out_of_lattice_order(self):
        write(os.path.join(self.case, "0", "T"), scalar_text("uniform 1"))
        n_pts = int(np.prod([d + 1 for d in self.DIMS]))
        order = list(range(n_pts))
        order[0], order[1] = order[1], order[0]
        write(os.path.join(self.case, "constant", "polyMesh", "points"),
              points_text(self.DIMS, self.ORIGIN, self.SPACING, order))
        self.expect_error("polyMesh/points: point 0", "x fastest")

    def test_non_uniform_spacing(self):
        write(os.path.join(self.case, "0", "T"), scalar_text("uniform 1"))
        text = points_text(self.DIMS, self.ORIGIN, self.SPACING)
        # Move the whole x = -0.75 plane to -0.8: still a lattice, not uniform.
        text = text.replace("(-0.75 ", "(-0.8 ")
        write(os.path.join(self.case, "constant", "polyMesh", "points"), text)
        self.expect_error("axis x spacing is not uniform")

    def test_not_a_number(self):
        vals = [repr(float(v)) for v in np.zeros(self.n)]
        vals[5] = "nan?"
        text = scalar_text("nonuniform List<scalar> \n%d\n(\n%s\n)\n" % (self.n, "\n".join(vals)))
        write(os.path.join(self.case, "0", "T"), text)
        self.expect_error("0/T: internalField: not a number")

    def test_existing_output_untouched_on_error(self):
        with open(self.out, "w") as f:
            f.write("old")
        write(os.path.join(self.case, "0", "T"), scalar_text(nonuniform(np.zeros(3))))
        rc, _ = self.run_main()
        self.assertEqual(rc, 1)
        with open(self.out) as f:
            self.assertEqual(f.read(), "old")


if __name__ == "__main__":
    unittest.main()
