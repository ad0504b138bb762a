#!/usr/bin/env python3
"""Tests for downsample_h5.py (python3 -m unittest, needs numpy+h5py; not part of ctest).

Run: python3 datasets/test_downsample_h5.py
"""

import os
import sys
import unittest

import h5py
import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import downsample_h5  # noqa: E402
from series_test_case import SeriesToolTest  # noqa: E402


class DownsampleTest(SeriesToolTest):
    def setUp(self):
        super().setUp()
        rng = np.random.default_rng(7)
        self.write_input(rng.random((5, 4, 6, 8)).astype(np.float32),  # T, Z, Y, X
                         dims=np.array([8, 6, 4], np.int64), steps=np.int64(5),
                         times=np.array([0.0, 0.1, 0.2, 0.3, 0.4]),
                         spacing=np.array([0.5, 0.25, 1.0]), source="test")

    def run_main(self, *args):
        return self.run_tool(downsample_h5.main, self.src, "--field", "T", "-o", self.out, *args)

    def test_block_means_stride_and_attributes(self):
        rc, err = self.run_main("--factor", "2", "--stride", "2")
        self.assertEqual(rc, 0, err)
        with h5py.File(self.out, "r") as f:
            d = f["T"]
            self.assertEqual(d.shape, (3, 2, 3, 4))
            self.assertEqual(d.dtype, np.float32)
            for t, k, j, i in [(0, 0, 0, 0), (1, 1, 2, 3), (2, 0, 1, 2)]:
                block = self.data[2 * t, 2 * k:2 * k + 2, 2 * j:2 * j + 2, 2 * i:2 * i + 2]
                self.assertAlmostEqual(float(d[t, k, j, i]), float(block.astype(np.float64).mean()),
                                       places=6)
            np.testing.assert_array_equal(d.attrs["dims"], [4, 3, 2])
            self.assertEqual(d.attrs["steps"], 3)
            np.testing.assert_allclose(d.attrs["times"], [0.0, 0.2, 0.4])
            np.testing.assert_allclose(d.attrs["spacing"], [1.0, 0.5, 2.0])
            self.assertIn("mean of 2^3 cells, every 2 step(s)", d.attrs["source"])

    def test_not_divisible(self):
        rc, err = self.run_main("--factor", "3")
        self.assertEqual(rc, 1)
        self.assertIn("not divisible by factor 3", err)
        self.assertFalse(os.path.exists(self.out))

    def test_missing_field(self):
        rc, err = self.run_tool(downsample_h5.main, self.src, "--field", "U", "-o", self.out)
        self.assertEqual(rc, 1)
        self.assertIn("no dataset 'U'", err)


if __name__ == "__main__":
    unittest.main()
