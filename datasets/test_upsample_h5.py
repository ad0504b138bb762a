#!/usr/bin/env python3
"""Tests for upsample_h5.py (python3 -m unittest, needs numpy+h5py; not part of ctest).

Run: python3 datasets/test_upsample_h5.py
"""

import os
import sys
import unittest

import h5py
import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import upsample_h5  # noqa: E402
from series_test_case import SeriesToolTest  # noqa: E402


class UpsampleTest(SeriesToolTest):
    def setUp(self):
        super().setUp()
        z, y, x = np.meshgrid(np.arange(4), np.arange(5), np.arange(6), indexing="ij")
        self.write_input(np.stack([(0.5 * x - 0.25 * y + z + t).astype(np.float32)
                                   for t in range(4)]),
                         times=np.array([0.0, 0.1, 0.2, 0.3]), spacing=np.array([1.0, 1.0, 1.0]))

    def run_main(self, *args):
        return self.run_tool(upsample_h5.main, *args)[0]

    def test_a_linear_field_stays_linear_and_attributes_follow(self):
        self.assertEqual(self.run_main(self.src, "--field", "T", "-o", self.out, "--size", "11",
                                       "--stride", "2"), 0)
        with h5py.File(self.out, "r") as f:
            d = f["T"]
            self.assertEqual(d.shape, (2, 11, 11, 11))
            z, y, x = np.meshgrid(np.linspace(0, 3, 11), np.linspace(0, 4, 11),
                                  np.linspace(0, 5, 11), indexing="ij")
            for k, t in enumerate([0, 2]):
                np.testing.assert_allclose(d[k], 0.5 * x - 0.25 * y + z + t, atol=1e-5)
            np.testing.assert_allclose(d.attrs["times"], [0.0, 0.2])
            np.testing.assert_allclose(d.attrs["spacing"], [0.5, 0.4, 0.3])
            self.assertEqual(list(d.attrs["dims"]), [11, 11, 11])

    def test_bad_input_is_an_error_and_writes_nothing(self):
        self.assertEqual(self.run_main(self.src, "--field", "nope", "-o", self.out), 1)
        self.assertEqual(self.run_main(self.src, "--field", "T", "-o", self.src), 1)
        self.assertFalse(os.path.exists(self.out))


if __name__ == "__main__":
    unittest.main()
