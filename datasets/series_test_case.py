"""What the dataset tools' tests share (test_downsample_h5.py, test_upsample_h5.py): a temporary
folder holding the input series file, and the tool's main run with its messages captured."""

import contextlib
import io
import os
import tempfile
import unittest

import h5py


class SeriesToolTest(unittest.TestCase):
    """A test case with self.src (the input file, written by write_input) and self.out (the output
    path) in a temporary folder removed after each test."""

    def setUp(self):
        self.tmp = tempfile.TemporaryDirectory()
        self.src = os.path.join(self.tmp.name, "in.h5")
        self.out = os.path.join(self.tmp.name, "out.h5")

    def tearDown(self):
        self.tmp.cleanup()

    def write_input(self, data, **attrs):
        """Writes data as dataset T of self.src with the given attributes."""
        self.data = data
        with h5py.File(self.src, "w") as f:
            d = f.create_dataset("T", data=data)
            for k, v in attrs.items():
                d.attrs[k] = v

    def run_tool(self, main, *args):
        """(exit code, stderr) of main(args)."""
        err = io.StringIO()
        with contextlib.redirect_stderr(err):
            rc = main(list(args))
        return rc, err.getvalue()
