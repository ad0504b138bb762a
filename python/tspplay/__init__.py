"""tspplay from Python: numpy and xarray series in; TSP trees, pictures, metrics and the player out.

The same library as the `tspplay` command (the extension ``tspplay._core``): ``build`` is
``tspplay build``, ``File.render`` is ``tspplay render`` (the same pixels, byte for byte),
``File.metrics`` is ``tspplay metrics``, ``diff`` is ``tspplay diff``, ``play`` runs
``tspplay play``. Errors are the CLI's, as Python exceptions: ``UsageError``, ``FormatError``,
``IoError``, ``GlError`` (all ``tspplay.Error``); Ctrl-C stops a build or render cleanly
(``KeyboardInterrupt``, nothing written). Builds and renders release the GIL. See docs/python.md.
"""
import os
import warnings

from . import _core
from ._core import (Error, FormatError, GlError, IoError, UsageError, preset_names, read_png,
                    settings_table, write_png)
from .series import series_arguments
from .tf import TransferFunction, tf_argument

__all__ = ["build", "open", "File", "Frames", "TransferFunction", "diff", "play", "read_png",
           "write_png", "settings_table", "preset_names", "Error", "UsageError", "FormatError",
           "IoError", "GlError"]

_SETTINGS = {row["name"] for row in _core.settings_table()}


def build(data, out, *, field="", brick=0, spacing=None, origin=None, times=None,
          time_units=None, calendar=None, range=None, compress=0, threads=0, steps=None,
          nonfinite="replace", progress=None):
    """Builds the .tsp file `out` from `data` and returns it opened (a File; its
    `build_report` says what the build did).

    data: a numpy array (t, z, y, x); a list of 3-D arrays (z, y, x); an iterator of 3-D arrays
    (give steps=N, or an object with len()); an xarray.DataArray with a time dimension (its
    coordinates give spacing, origin and times, the time coordinate's attributes their units);
    or a path `tspplay build` reads. Arrays are read in place, step by step (no copy of the
    series; float32 C-contiguous steps are copied straight into the builder's buffers, other
    layouts and types are converted as they are read).
    field, brick, spacing (dx, dy, dz), origin, range (lo, hi): as `tspplay build`'s options;
    compress: deflate level 0-9 (0: none); threads: 0 for all cores.
    nonfinite: "replace" (the CLI's rule: NaN and -Inf become the range's low end, +Inf its high
    end, with a RuntimeWarning) or "error" (FormatError naming the first such sample).
    progress: called as progress(phase, done, total) (bytes) from the build.
    Raises UsageError, FormatError, IoError; KeyboardInterrupt on Ctrl-C (nothing written).
    """
    if nonfinite not in ("replace", "error"):
        raise UsageError(f"nonfinite={nonfinite!r}: expected 'replace' or 'error'")
    out = os.fspath(out)
    common = dict(brick=int(brick), range=_pair(range), spacing=_triple(spacing, "spacing"),
                  origin=_triple(origin, "origin"), deflate=int(compress),
                  threads=int(threads), progress=progress)
    if isinstance(data, (str, os.PathLike)):
        if times is not None or time_units is not None:
            raise UsageError("build: times come from the input file; times= is for arrays")
        report = _core.build_input(os.fspath(data), out, field=field, **common)
    else:
        s = series_arguments(data, steps=steps, times=times, time_units=time_units,
                             calendar=calendar, spacing=common["spacing"],
                             origin=common["origin"], field=field)
        common.update(spacing=s["spacing"], origin=s["origin"])
        report = _core.build_series(s["steps"], out, count=s["count"], field=s["field"],
                                    times=s["times"], time_units=s["time_units"],
                                    calendar=s["calendar"], name=s["name"],
                                    refuse_nonfinite=nonfinite == "error", **common)
    if report["nonfinite_count"]:
        lo, hi = report["value_range"]
        warnings.warn(f"{report['nonfinite_count']} NaN/Inf samples replaced (NaN and -Inf by "
                      f"{lo:g}, +Inf by {hi:g})", RuntimeWarning, stacklevel=2)
    f = File(out)
    f.build_report = report
    return f


def open(path, field=""):  # noqa: A001 (tspplay.open, as the issue names it)
    """Opens a .tsp file (field: one of its fields; '' the first). Raises IoError, FormatError,
    UsageError."""
    return File(path, field)


class Frames(list):
    """The images of a render (numpy uint8 arrays (height, width, 4), one per step drawn) with
    `reports` (frames.json's entries, as dicts, one per frame of every pass), `steps` (the step
    of each image) and `info` (renderer, context, warnings, median_ms, ...)."""

    def __init__(self, result):
        super().__init__(result.pop("images"))
        self.steps = result.pop("image_steps")
        self.reports = result.pop("frames")
        self.info = result


class File:
    """An open .tsp file: what `tspplay info` shows, node statistics, steps, renders."""

    def __init__(self, path, field=""):
        self._f = _core.TspFile(os.fspath(path), field)
        self._info = self._f.info()
        self.build_report = None

    path = property(lambda self: self._f.path, doc="The file's path.")
    fields = property(lambda self: self._f.fields, doc="Every field in the file.")
    field = property(lambda self: self._f.field, doc="The field opened.")
    dims = property(lambda self: tuple(self._info["dims"]), doc="Grid size (x, y, z).")
    steps = property(lambda self: self._info["steps"], doc="Number of time steps.")
    shape = property(lambda self: (self.steps,) + tuple(reversed(self.dims)),
                     doc="(t, z, y, x), as numpy sees the series.")
    spacing = property(lambda self: tuple(self._info["spacing"]), doc="Voxel size (dx, dy, dz).")
    origin = property(lambda self: tuple(self._info["origin"]), doc="Position of voxel 0.")
    value_range = property(lambda self: tuple(self._info["value_range"]))
    data_range = property(lambda self: tuple(self._info["data_range"]))
    time_units = property(lambda self: self._info["time_units"])
    levels = property(lambda self: len(self._info["lod_levels"]),
                      doc="Number of LOD levels (level 0: full resolution).")

    @property
    def times(self):
        """Physical time of every step as a numpy array, or None when the input named none."""
        import numpy as np
        return np.asarray(self._info["times"], dtype=float) if self._info["times"] else None

    def info(self):
        """What `tspplay info --json` prints, as a dict."""
        return self._f.info()

    def nodes(self):
        """Every TSP node's statistics by node id, as numpy columns (`info --nodes`)."""
        return self._f.nodes()

    def step(self, k):
        """Step k as a float32 array (z, y, x), decoded from the file's 16-bit bricks."""
        return self._f.step(int(k))

    def metrics(self, tf="preset:auto", metric="approximate", entries=256, threads=0):
        """`tspplay metrics`: per-node spatial/temporal errors of one metric for tf, with
        recompute_ms; numpy columns by node id."""
        return self._f.metrics(tf_argument(tf), metric, int(entries), int(threads))

    def render(self, steps=None, tf=None, size=(640, 480), view=(30, 20), progress=None,
               **options):
        """`tspplay render` on this file, returned in memory: a Frames list of RGBA images
        (height, width, 4) uint8 — the pixels `render` writes to its PNGs, byte for byte.

        steps: None (all), k, range(a, b[, s]), slice, or "A:B[:S]" as --steps.
        tf: a TransferFunction, a preset name, "preset:NAME" or a file (default preset:auto).
        options: every render option by name with '_' for '-' — the settings table's
        (spatial_tol=0.1, compositing="rays", shade=False, ...; tspplay.settings_table()) and
        render's own (metric, tf_range, lod, eye, probe=[...], output="frames/", movie=...,
        gl, backend, ...), with the CLI's checks and messages (which name the CLI's --option).
        progress: progress(phase, done, total) after every frame.
        Raises UsageError, FormatError, IoError, GlError; KeyboardInterrupt on Ctrl-C.
        """
        args, settings = {"file": self.path, "field": self.field,
                          "tf": tf_argument(tf), "size": _size(size),
                          "view": _csv(view, "view")}, {}
        if steps is not None:
            args["steps"] = _steps(steps, self.steps)
        for key, value in options.items():
            name = key.replace("_", "-")
            if name in _SETTINGS:
                settings[name] = _text(value)
            elif name == "probe":
                args[name] = [value] if isinstance(value, str) else list(value)
            else:
                args[name] = _text(value)
        return Frames(_core.render(args, settings, progress))

    def movie(self, path, steps=None, fps=8, **options):
        """Renders the steps into a movie (out.mp4 or out.gif, through ffmpeg) as
        `tspplay render --movie` does; returns the Frames. Raises like render, and IoError
        without ffmpeg."""
        import tempfile
        with tempfile.TemporaryDirectory(prefix="tspplay-movie-") as tmp:
            return self.render(steps=steps, output=os.path.join(tmp, "frames"),
                               movie=os.fspath(path), fps=int(fps), **options)

    def play(self, block=True, **options):
        """Opens the player window on this file (`tspplay play`, in its own process); options
        as play's (--step, --size WxH, --tf, ...). block=False returns the subprocess.Popen."""
        return _play(self.path, block, ["--field", self.field] if self.field else [], options)

    def __repr__(self):
        x, y, z = self.dims
        return f"<tspplay.File {self.path!r} field {self.field!r}: {x}x{y}x{z}, {self.steps} steps>"


def diff(a, b, image=False):
    """`tspplay diff`: mean, p99 and max per-pixel dE in CIE L*u*v* of two images (uint8 arrays
    (h, w, 3|4) or PNG paths) as a dict; image=True adds the grey difference image."""
    return _core.diff(a, b, image)


def play(data, block=True, cache_dir=None, **options):
    """Opens the player window on data: a .tsp file, any input `tspplay play` takes, or an array,
    list, iterator or xarray.DataArray, built first into the cache (~/.cache/tspplay/python,
    reused while the data is unchanged). block=False returns the subprocess.Popen."""
    if isinstance(data, (str, os.PathLike)):
        return _play(os.fspath(data), block, [], options)
    from .series import cache_path
    path = cache_path(data, cache_dir)
    if not os.path.exists(path):
        build(data, path)
    return _play(path, block, [], options)


def _play(path, block, extra, options):
    import subprocess
    cmd = [_core.tspplay_binary(), "play", path] + extra
    for key, value in options.items():
        cmd += ["--" + key.replace("_", "-"), _size(value) if key == "size" else _text(value)]
    return subprocess.run(cmd, check=True) if block else subprocess.Popen(cmd)


def _text(value):
    """An option's value as the CLI's text: on/off, A,B,C, numbers in full precision."""
    if isinstance(value, bool):
        return "on" if value else "off"
    if isinstance(value, (tuple, list)):
        return ",".join(_text(v) for v in value)
    if isinstance(value, float):
        return repr(value)
    return str(value)


def _csv(value, what):
    return value if isinstance(value, str) else _text(tuple(value))


def _size(size):
    if isinstance(size, str):
        return size
    w, h = size
    return f"{int(w)}x{int(h)}"


def _steps(steps, count):
    if isinstance(steps, str):
        return steps
    if isinstance(steps, slice):
        steps = range(*steps.indices(count))
    if isinstance(steps, range):
        if len(steps) == 0 or steps.step < 1:
            raise UsageError(f"steps={steps!r}: expected a non-empty increasing range")
        return f"{steps[0]}:{steps[-1]}:{steps.step}"
    if isinstance(steps, (tuple, list)) and len(steps) == 2:
        return f"{int(steps[0])}:{int(steps[1])}"
    return str(int(steps))


def _pair(value):
    return None if value is None else (float(value[0]), float(value[1]))


def _triple(value, what):
    if value is None:
        return None
    if len(value) != 3:
        raise UsageError(f"{what}={value!r}: expected three numbers (x, y, z)")
    return tuple(float(v) for v in value)
