"""What tspplay.build reads from Python data: numpy arrays, lists, iterators, xarray.DataArray."""
import hashlib
import os

import numpy as np

from ._core import UsageError

_TIME_NAMES = ("time", "t", "Time", "times", "step", "steps")
# Space dimensions recognised by name, as (z, y, x); others keep the order given.
_AXIS_NAMES = (("z", "y", "x"), ("Z", "Y", "X"), ("k", "j", "i"), ("depth", "lat", "lon"),
               ("level", "lat", "lon"), ("lev", "lat", "lon"), ("height", "lat", "lon"),
               ("depth", "latitude", "longitude"), ("level", "latitude", "longitude"))


def _is_xarray(data):
    return type(data).__module__.split(".")[0] == "xarray" and hasattr(data, "dims")


def _step_list(array):
    if array.ndim != 4:
        raise UsageError(f"build: expected a 4-D array (t, z, y, x), got {array.ndim}-D with shape "
                         f"{array.shape} (one step: data[None])")
    return [array[t] for t in range(array.shape[0])]  # views: nothing copied


def _time_dim(da):
    for d in da.dims:
        if d in _TIME_NAMES or (d in da.coords and np.issubdtype(da.coords[d].dtype, np.datetime64)):
            return d
    if da.ndim == 4:
        return da.dims[0]
    raise UsageError(f"build: a DataArray with dims {da.dims} has no time dimension (expected 4 "
                     "dims, one of them named time)")


def _axis(da, dim):
    """(spacing, origin) along dim from its coordinate; (None, None) without one."""
    if dim not in da.coords or da.sizes[dim] < 2:
        return None, None
    c = np.asarray(da.coords[dim].values, dtype=float)
    step = np.diff(c)
    if not np.all(step > 0):
        raise UsageError(f"build: coordinate {dim!r} is not increasing; sort it "
                         f"(da.sortby({dim!r})) or give spacing=")
    if not np.allclose(step, step[0], rtol=1e-6, atol=0):
        raise UsageError(f"build: coordinate {dim!r} is not evenly spaced (steps {step.min():g} "
                         f"to {step.max():g}); tspplay builds regular grids: resample it, or "
                         "give spacing= to ignore it")
    return float(step[0]), float(c[0])


def _times(coord):
    """(times, units, calendar) of a time coordinate."""
    values = coord.values
    if np.issubdtype(values.dtype, np.datetime64):
        t0 = values[0]
        seconds = ((values - t0) / np.timedelta64(1, "s")).astype(float)
        date = np.datetime_as_string(t0, unit="s").replace("T", " ")
        return list(seconds), f"seconds since {date}", "standard"
    if not np.issubdtype(values.dtype, np.number):
        raise UsageError(f"build: time coordinate {coord.name!r} holds {values.dtype} values; "
                         "give times= as numbers")
    return ([float(v) for v in values], str(coord.attrs.get("units", "")),
            str(coord.attrs.get("calendar", "")))


def _from_xarray(da, out):
    tdim = _time_dim(da)
    space = [d for d in da.dims if d != tdim]
    if len(space) != 3:
        raise UsageError(f"build: expected a time dimension and three space dimensions, got "
                         f"{da.dims}")
    for names in _AXIS_NAMES:  # named axes go where their names say, whatever their order
        if set(space) == set(names):
            space = list(names)
    da = da.transpose(tdim, *space)
    spacing, origin = [], []
    for dim in reversed(space):  # x, y, z
        s, o = _axis(da, dim)
        spacing.append(1.0 if s is None else s)
        origin.append(0.0 if o is None else o)
    if any(d in da.coords for d in space):
        out["spacing"] = out["spacing"] or tuple(spacing)
        out["origin"] = out["origin"] or tuple(origin)
    if tdim in da.coords and out["times"] is None:
        out["times"], units, calendar = _times(da.coords[tdim])
        out["time_units"] = out["time_units"] or units
        out["calendar"] = out["calendar"] or calendar
    out["field"] = out["field"] or (str(da.name) if da.name is not None else "")
    out["name"] = f"xarray.DataArray {da.name or ''} {dict(da.sizes)}".replace("  ", " ")
    data = da.data
    if isinstance(data, np.ndarray):
        out["steps"] = _step_list(data)
    else:  # dask and other lazy arrays: one step in memory at a time
        out["steps"] = (np.asarray(da[t].values) for t in range(da.sizes[tdim]))
        out["count"] = da.sizes[tdim]


def series_arguments(data, *, steps, times, time_units, calendar, spacing, origin, field):
    """build_series' arguments for data. Raises UsageError for what it cannot read."""
    out = dict(steps=None, count=0, times=None if times is None else list(times),
               time_units=time_units or "", calendar=calendar or "", spacing=spacing,
               origin=origin, field=field, name="numpy array")
    if _is_xarray(data):
        _from_xarray(data, out)
    elif isinstance(data, np.ndarray):
        out["steps"] = _step_list(data)
        out["name"] = f"numpy array {data.shape} {data.dtype}"
    elif isinstance(data, (list, tuple)):
        out["steps"] = [np.asarray(s) for s in data]
        out["name"] = f"{len(data)} numpy arrays"
    elif hasattr(data, "__iter__"):
        count = steps if steps is not None else (len(data) if hasattr(data, "__len__") else 0)
        if not count:
            raise UsageError("build: an iterator of steps needs steps=N, the number it yields")
        out["steps"], out["count"] = iter(data), int(count)
        out["name"] = "iterator of numpy arrays"
    else:
        raise UsageError(f"build: cannot read a {type(data).__name__}: expected a path, a numpy "
                         "array (t, z, y, x), a list or iterator of 3-D arrays, or an "
                         "xarray.DataArray")
    n = out["count"] or len(out["steps"])
    if out["times"] is not None:
        out["times"] = [float(t) for t in out["times"]]
        if len(out["times"]) != n:
            raise UsageError(f"build: {len(out['times'])} times for {n} steps")
    else:
        out["times"] = []
    return out


def cache_path(data, cache_dir=None):
    """Where play builds data: a file named by a hash of the data (reused while unchanged)."""
    base = cache_dir or os.path.join(os.environ.get("XDG_CACHE_HOME") or
                                     os.path.expanduser("~/.cache"), "tspplay", "python")
    os.makedirs(base, exist_ok=True)
    if _is_xarray(data):
        data = data.values
    if isinstance(data, np.ndarray):
        data = list(data)
    if not isinstance(data, (list, tuple)):
        return os.path.join(base, f"iterator-{os.getpid()}-{id(data)}.tsp")
    h = hashlib.blake2b(digest_size=16)
    for step in data:
        step = np.ascontiguousarray(step)
        h.update(repr((step.shape, step.dtype.str)).encode())
        h.update(memoryview(step).cast("B"))
    return os.path.join(base, h.hexdigest() + ".tsp")
