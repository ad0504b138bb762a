"""tspplay.TransferFunction: colour and opacity over the data, as render's --tf takes them."""
import atexit
import json
import os
import shutil
import tempfile

from . import _core
from ._core import UsageError

_tmpdir = None


def _scratch():
    """A folder for the JSON files of point-made TFs (removed at exit)."""
    global _tmpdir
    if _tmpdir is None:
        _tmpdir = tempfile.mkdtemp(prefix="tspplay-tf-")
        atexit.register(shutil.rmtree, _tmpdir, True)
    return _tmpdir


class TransferFunction:
    """A transfer function: points (x, r, g, b, a) in data units, a preset, a file (ours or a
    ParaView preset), or a matplotlib colour map. It reaches the library as render's --tf does
    (a preset name or a JSON file), so its checks, messages and placement (tf_range) are the
    CLI's.

    TransferFunction([(x, r, g, b, a), ...], range=(lo, hi)) — points; components in [0, 1]
    TransferFunction.preset("viridis") / TransferFunction.from_file("map.json")
    TransferFunction.from_matplotlib("magma", opacity=(0.0, 0.8))
    """

    def __init__(self, points, range=None):
        pts = [[float(v) for v in p] for p in points]
        if not pts or any(len(p) != 5 for p in pts):
            raise UsageError("TransferFunction: expected points (x, r, g, b, a), at least one")
        xs = [p[0] for p in pts]
        lo, hi = (min(xs), max(xs)) if range is None else (float(range[0]), float(range[1]))
        self._text = json.dumps({"range": [lo, hi], "points": pts})
        _core.parse_tf(self._text, "TransferFunction(points)")  # the file's checks, now
        self._arg = None

    @classmethod
    def preset(cls, name):
        """A built-in preset (tspplay.preset_names()), stretched over the data."""
        name = name[len("preset:"):] if name.startswith("preset:") else name
        if name not in _core.preset_names():
            raise UsageError(f"unknown preset '{name}'; the presets are "
                             f"{', '.join(_core.preset_names())}")
        return cls._of_arg("preset:" + name)

    @classmethod
    def from_file(cls, path):
        """Our JSON or a ParaView colour-map preset file (read now: IoError, FormatError)."""
        path = os.fspath(path)
        _core.tf_table(path)
        return cls._of_arg(path)

    @classmethod
    def from_matplotlib(cls, name, opacity=(0.0, 1.0), samples=64):
        """A matplotlib colour map (needs matplotlib) over [0, 1] (stretched over the data as
        ParaView's normalised presets are), with opacity ramping linearly from opacity[0] to
        opacity[1]."""
        try:
            import matplotlib
        except ImportError as e:
            raise UsageError("TransferFunction.from_matplotlib needs matplotlib "
                             "(apt-get install python3-matplotlib)") from e
        cmap = matplotlib.colormaps[name]
        pts = []
        for k in range(samples):
            x = k / (samples - 1)
            r, g, b, _ = cmap(x)
            pts.append((x, r, g, b, opacity[0] + (opacity[1] - opacity[0]) * x))
        return cls(pts, range=(0.0, 1.0))

    @classmethod
    def _of_arg(cls, arg):
        tf = cls.__new__(cls)
        tf._text, tf._arg = None, arg
        return tf

    @property
    def arg(self):
        """The --tf argument that gives this TF (a preset:NAME, a file, or a JSON file written
        for points)."""
        if self._arg is None:
            fd, path = tempfile.mkstemp(suffix=".json", dir=_scratch())
            with os.fdopen(fd, "w") as f:
                f.write(self._text)
            self._arg = path
        return self._arg

    def table(self, file=None, range=(0.0, 1.0), entries=256, tf_range="auto"):
        """The sampled table ((lo, hi), entries (K, 4) float32): over file's data as render
        places it (file: a tspplay.File), else over range."""
        core = file._f if file is not None else None
        return _core.tf_table(self.arg, float(range[0]), float(range[1]), int(entries),
                              tf_range, core)

    def __repr__(self):
        return f"<tspplay.TransferFunction {self._arg or 'points'}>"


def tf_argument(tf):
    """render's --tf text for tf: a TransferFunction, a preset name, "preset:NAME" or a path."""
    if tf is None:
        return "preset:auto"
    if isinstance(tf, TransferFunction):
        return tf.arg
    tf = os.fspath(tf)
    if not tf.startswith("preset:") and not os.path.exists(tf) and tf in _core.preset_names():
        return "preset:" + tf
    return tf
