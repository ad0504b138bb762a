"""Fixtures of the Python module's tests: a small series from a formula, its tree built from
Python, and the CLI (TSPPLAY_BIN, set by ctest) to compare against."""
import os
import subprocess

import numpy as np
import pytest

import tspplay

# Not cubic, so that an axis swapped anywhere shows.
SHAPE = (6, 24, 20, 28)  # t, z, y, x


def formula(shape=SHAPE):
    """A 4-D float32 series: a blob moving along x over a slow ramp."""
    t, z, y, x = np.meshgrid(*[np.arange(n, dtype=np.float32) for n in shape], indexing="ij")
    cx = 6 + 3 * t
    blob = np.exp(-((x - cx) ** 2 + (y - 10) ** 2 + (z - 12) ** 2) / 20.0)
    return (blob + 0.02 * z + 0.01 * np.sin(x + t)).astype(np.float32)


@pytest.fixture(scope="session")
def cli():
    """Runs the tspplay executable; returns the completed process (check=True)."""
    binary = os.environ.get("TSPPLAY_BIN") or tspplay._core.tspplay_binary()

    def run(*args, check=True):
        return subprocess.run([binary, *map(str, args)], check=check, capture_output=True,
                              text=True)
    return run


@pytest.fixture(scope="session")
def series():
    return formula()


@pytest.fixture(scope="session")
def built(series, tmp_path_factory):
    """The series built from Python (brick 8)."""
    out = tmp_path_factory.mktemp("built") / "py.tsp"
    return tspplay.build(series, out, brick=8, field="blob")
