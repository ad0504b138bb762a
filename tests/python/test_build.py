"""tspplay.build and tspplay.open against the CLI's build of the same data."""
import os
import warnings

import numpy as np
import pytest

import tspplay
from conftest import SHAPE, formula


def same_nodes(a, b):
    na, nb = a.nodes(), b.nodes()
    assert na.keys() == nb.keys()
    for k in na:
        np.testing.assert_array_equal(na[k], nb[k], err_msg=k)


def test_build_from_array_matches_cli_build_of_the_same_samples(series, built, cli, tmp_path):
    # The CLI reads the same float32 samples from raw files.
    for t in range(series.shape[0]):
        series[t].tofile(tmp_path / f"s_{t:04d}.raw")
    out = tmp_path / "cli.tsp"
    t, z, y, x = SHAPE
    cli("build", tmp_path / "s_%04d.raw", "--raw-dims", f"{x},{y},{z}", "--raw-type", "f32",
        "--brick", 8, "--field", "blob", "-o", out)
    c = tspplay.open(out)
    assert built.dims == c.dims == (x, y, z)
    assert built.steps == c.steps == t
    assert built.value_range == c.value_range
    assert built.levels == c.levels
    same_nodes(built, c)
    for k in range(t):
        np.testing.assert_array_equal(built.step(k), c.step(k))


def test_open_inspects_the_file(series, built):
    assert built.shape == series.shape
    assert built.field == "blob" and built.fields == ["blob"]
    assert built.times is None
    info = built.info()
    nodes = built.nodes()
    assert len(nodes["mean"]) == info["tsp_nodes"]
    assert nodes["box"].shape == (info["tsp_nodes"], 6)
    root = 0  # the root node spans every step and voxel
    assert nodes["t0"][root] == 0 and nodes["t1"][root] == series.shape[0] - 1
    assert nodes["min"][root] == pytest.approx(series.min()) and nodes["max"][root] == pytest.approx(series.max())
    lo, hi = built.value_range
    for k in (0, series.shape[0] - 1):
        step = built.step(k)
        assert step.dtype == np.float32 and step.shape == series.shape[1:]
        assert np.abs(step - series[k]).max() <= (hi - lo) / 65535 + 1e-6


def test_list_iterator_strided_and_float64_build_the_same_tree(series, built, tmp_path):
    same_nodes(built, tspplay.build(list(series), tmp_path / "list.tsp", brick=8))
    same_nodes(built, tspplay.build((s for s in series), tmp_path / "iter.tsp", brick=8,
                                    steps=len(series)))
    fortran = np.asfortranarray(series)  # no step is C-contiguous: read element by element
    assert not fortran[0].flags.c_contiguous
    same_nodes(built, tspplay.build(fortran, tmp_path / "f.tsp", brick=8))
    reversed_view = series[:, ::-1, :, :][:, ::-1]  # negative strides, same samples
    same_nodes(built, tspplay.build(reversed_view, tmp_path / "r.tsp", brick=8))
    same_nodes(built, tspplay.build(series.astype(np.float64), tmp_path / "d.tsp", brick=8))


def test_build_from_a_path_as_the_cli(cli, tmp_path):
    h5 = tmp_path / "shock.h5"
    cli("generate", "shock", "--dims", 16, "--steps", 3, "-o", h5)
    cli("build", h5, "-o", tmp_path / "cli.tsp")
    seen = []
    f = tspplay.build(h5, tmp_path / "py.tsp", progress=lambda *a: seen.append(a))
    assert seen and all(len(a) == 3 for a in seen)
    same_nodes(f, tspplay.open(tmp_path / "cli.tsp"))


def test_xarray_coordinates_give_spacing_origin_and_times(series, tmp_path):
    xr = pytest.importorskip("xarray")
    t, z, y, x = series.shape
    da = xr.DataArray(
        series, dims=("time", "z", "y", "x"), name="density",
        coords={"time": np.datetime64("2020-01-01T00:00") + np.arange(t) * np.timedelta64(1, "h"),
                "z": 10 + 2.0 * np.arange(z), "y": 0.25 * np.arange(y), "x": -1 + 0.5 * np.arange(x)})
    f = tspplay.build(da, tmp_path / "xa.tsp", brick=8)
    assert f.spacing == (0.5, 0.25, 2.0)
    assert f.origin == (-1.0, 0.0, 10.0)
    np.testing.assert_array_equal(f.times, 3600.0 * np.arange(t))
    assert f.time_units == "seconds since 2020-01-01 00:00:00"
    assert f.field == "density"
    # Dimensions in another order are put back as (time, z, y, x).
    g = tspplay.build(da.transpose("y", "time", "x", "z"), tmp_path / "xb.tsp", brick=8)
    np.testing.assert_array_equal(g.nodes()["mean"], f.nodes()["mean"])
    # A numeric time coordinate keeps its CF units.
    days = da.assign_coords(time=("time", 1.5 * np.arange(t), {"units": "days since 2000-01-01"}))
    h = tspplay.build(days, tmp_path / "xc.tsp", brick=8)
    np.testing.assert_array_equal(h.times, 1.5 * np.arange(t))
    assert h.time_units == "days since 2000-01-01"
    uneven = da.assign_coords(x=np.r_[0.0, 0.1, 5 + np.arange(x - 2)])
    with pytest.raises(tspplay.UsageError, match="not evenly spaced"):
        tspplay.build(uneven, tmp_path / "xd.tsp")


def test_bad_arrays_are_python_errors(series, tmp_path):
    out = tmp_path / "bad.tsp"
    with pytest.raises(tspplay.UsageError, match="4-D array"):
        tspplay.build(series[0], out)
    with pytest.raises(tspplay.UsageError, match="3-D array"):
        tspplay.build([series[0], series[0, 0]], out)
    with pytest.raises(tspplay.UsageError, match="shape"):
        tspplay.build([series[0], series[0, :-1]], out)
    with pytest.raises(tspplay.UsageError, match="dtype"):
        tspplay.build(series.astype(complex), out)
    with pytest.raises(tspplay.UsageError, match="steps=N"):
        tspplay.build(iter(list(series)), out)
    with pytest.raises(tspplay.UsageError, match="iterator ended"):
        tspplay.build(iter(list(series)), out, steps=len(series) + 1)
    with pytest.raises(tspplay.UsageError, match="brick"):
        tspplay.build(series, out, brick=7)
    nan = series.copy()
    nan[2, 3, 4, 5] = np.nan
    with pytest.raises(tspplay.FormatError, match=r"step 2: sample \(z, y, x\) = \(3, 4, 5\) is NaN"):
        tspplay.build(nan, out, nonfinite="error")
    assert not out.exists()
    with warnings.catch_warnings(record=True) as w:
        warnings.simplefilter("always")
        f = tspplay.build(nan, out, brick=8)
    assert f.build_report["nonfinite_count"] == 1
    assert any("NaN/Inf samples replaced" in str(x.message) for x in w)


def test_file_errors_carry_the_cli_messages(cli, tmp_path):
    with pytest.raises(tspplay.IoError):
        tspplay.open(tmp_path / "missing.tsp")
    text = tmp_path / "text.tsp"
    text.write_text("not a tsp file\n")
    with pytest.raises(tspplay.Error) as e:
        tspplay.open(text)
    r = cli("info", text, check=False)
    assert r.returncode != 0 and str(e.value) in r.stderr


def test_interrupted_build_writes_nothing(series, tmp_path):
    import signal
    out = tmp_path / "stopped.tsp"

    def ctrl_c(phase, done, total):  # Ctrl-C while the build runs
        signal.raise_signal(signal.SIGINT)

    with pytest.raises(KeyboardInterrupt):
        tspplay.build(series, out, brick=8, progress=ctrl_c)
    assert os.listdir(tmp_path) == []


def test_python_exceptions_from_the_data_or_the_callback_pass_through(tmp_path):
    out = tmp_path / "e.tsp"

    def crashing():
        for t in range(4):
            if t == 2:
                raise ValueError("simulation crashed at step 2")
            yield np.full((16, 16, 16), t, np.float32)

    with pytest.raises(ValueError, match="crashed at step 2"):
        tspplay.build(crashing(), out, steps=4)

    def refuse(phase, done, total):
        raise RuntimeError("stop from the callback")

    with pytest.raises(RuntimeError, match="stop from the callback"):
        tspplay.build(np.ones((3, 16, 16, 16), np.float32), out, progress=refuse)
    assert os.listdir(tmp_path) == []
