// src/python: the Python module `tspplay._core` over the library the CLI uses (docs/python.md);
// may include tsp/, gl/, render/, jobs/ and cli/'s option mapping (render_args, args,
// info_report). What the bindings share: exceptions, Ctrl-C, JSON and images as Python objects.
#pragma once
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <functional>
#include <nlohmann/json.hpp>
#include <string>

#include "tsp/report/image.h"

namespace tsppy {

namespace py = pybind11;

/// Registers tspplay.Error and its subclasses (UsageError, FormatError, IoError, GlError) in m
/// and the translator that raises them for the library's typed exceptions (tsp::Interrupted
/// becomes KeyboardInterrupt). Call once, from the module's init.
void register_exceptions(py::module_& m);

/// Checks for a pending Python signal (Ctrl-C) from library code running without the GIL: takes
/// the GIL, runs Python's signal handlers and throws tsp::Interrupted when they raised
/// KeyboardInterrupt (py::error_already_set for another exception). Any thread; a thread other
/// than Python's main thread never sees signals (Python runs handlers there only).
void check_signals();

/// A progress callback for library code that runs without the GIL: every call checks for
/// Ctrl-C (check_signals) and calls callback (when it is not None) with the GIL held. The
/// returned function is safe to call from any thread; callback must outlive it.
std::function<void(const std::string&, long long, long long)> progress_relay(const py::object& callback);

/// json as Python objects (dict, list, str, int, float, bool, None). Call with the GIL held.
py::object to_python(const nlohmann::json& j);

/// img as a numpy array (height, width, 4) of uint8 that owns img's pixels (no copy). Call with
/// the GIL held.
py::array image_array(tsp::Image&& img);

/// A numpy array (height, width, 3 or 4) of uint8, or a PNG path, as an RGBA image (alpha 255
/// added to RGB). Throws tsp::UsageError for another shape or type, what tsp::read_png throws
/// for a path. Call with the GIL held.
tsp::Image to_image(const py::object& obj, const std::string& what);

/// Binding registrars, one per source file (module.cpp calls them in order).
void bind_build(py::module_& m);
void bind_file(py::module_& m);
void bind_render(py::module_& m);

}  // namespace tsppy
