// The module `tspplay._core`: exceptions, Ctrl-C, conversions; the bindings register themselves
// from py_build.cpp, py_file.cpp and py_render.cpp.
#include <cstring>
#include <memory>
#include <vector>

#include "gl/gl_error.h"
#include "py_common.h"
#include "tsp/core/error.h"
#include "tsp/core/interrupt.h"
#include "tsp/report/image.h"

namespace tsppy {

namespace {

// The exception classes, created once by register_exceptions (owned by the module).
PyObject* g_error = nullptr;
PyObject* g_usage = nullptr;
PyObject* g_format = nullptr;
PyObject* g_io = nullptr;
PyObject* g_gl = nullptr;

// A new exception class tspplay.NAME with the given bases, added to m.
PyObject* add_exception(py::module_& m, const char* name, py::tuple bases, const char* doc) {
  const std::string qualified = std::string("tspplay.") + name;
  PyObject* type = PyErr_NewExceptionWithDoc(qualified.c_str(), doc, bases.ptr(), nullptr);
  if (!type) throw py::error_already_set();
  m.add_object(name, py::handle(type));
  return type;
}

// The nlohmann number or string j as a Python object.
py::object scalar_to_python(const nlohmann::json& j) {
  switch (j.type()) {
    case nlohmann::json::value_t::boolean: return py::bool_(j.get<bool>());
    case nlohmann::json::value_t::number_integer: return py::int_(j.get<std::int64_t>());
    case nlohmann::json::value_t::number_unsigned: return py::int_(j.get<std::uint64_t>());
    case nlohmann::json::value_t::number_float: return py::float_(j.get<double>());
    case nlohmann::json::value_t::string: return py::str(j.get<std::string>());
    default: return py::none();
  }
}

}  // namespace

void register_exceptions(py::module_& m) {
  g_error = add_exception(m, "Error", py::make_tuple(py::handle(PyExc_RuntimeError)),
                          "Base of tspplay's errors: what() names the file, field and problem.");
  g_usage = add_exception(m, "UsageError",
                          py::make_tuple(py::handle(g_error), py::handle(PyExc_ValueError)),
                          "An invalid or inconsistent request (an option's value, an argument).");
  g_format = add_exception(m, "FormatError",
                           py::make_tuple(py::handle(g_error), py::handle(PyExc_ValueError)),
                           "Data that does not hold what was expected (rank, type, field, ...).");
  g_io = add_exception(m, "IoError", py::make_tuple(py::handle(g_error)),
                       "The file system failed: a missing, unreadable or unwritable file.");
  g_gl = add_exception(m, "GlError", py::make_tuple(py::handle(g_error)),
                       "OpenGL failed: no context, a shader or a draw failed.");
  py::register_exception_translator([](std::exception_ptr p) {
    try {
      if (p) std::rethrow_exception(p);
    } catch (const tsp::Interrupted& e) {
      PyErr_SetString(PyExc_KeyboardInterrupt, e.what());
    } catch (const tsp::UsageError& e) {
      PyErr_SetString(g_usage, e.what());
    } catch (const tsp::FormatError& e) {
      PyErr_SetString(g_format, e.what());
    } catch (const tsp::IoError& e) {
      PyErr_SetString(g_io, e.what());
    } catch (const tsp::GlError& e) {
      PyErr_SetString(g_gl, e.what());
    } catch (const tsp::Error& e) {
      PyErr_SetString(g_error, e.what());
    }
  });
}

void check_signals() {
  py::gil_scoped_acquire gil;
  if (PyErr_CheckSignals() == 0) return;
  if (PyErr_ExceptionMatches(PyExc_KeyboardInterrupt)) {
    PyErr_Clear();
    // The library unwinds as from SIGINT in the CLI: temporaries removed, outputs untouched.
    throw tsp::Interrupted("interrupted (KeyboardInterrupt); nothing was written");
  }
  throw py::error_already_set();
}

std::function<void(const std::string&, long long, long long)> progress_relay(
    const py::object& callback) {
  const py::object* cb = &callback;
  return [cb](const std::string& phase, long long done, long long total) {
    check_signals();
    if (cb->is_none()) return;
    py::gil_scoped_acquire gil;
    (*cb)(phase, done, total);
  };
}

py::object to_python(const nlohmann::json& j) {
  if (j.is_object()) {
    py::dict d;
    for (auto it = j.begin(); it != j.end(); ++it) d[py::str(it.key())] = to_python(it.value());
    return d;
  }
  if (j.is_array()) {
    py::list l;
    for (const auto& v : j) l.append(to_python(v));
    return l;
  }
  return scalar_to_python(j);
}

py::array image_array(tsp::Image&& img) {
  auto* pixels = new std::vector<std::uint8_t>(std::move(img.rgba));
  py::capsule owner(pixels, [](void* p) { delete static_cast<std::vector<std::uint8_t>*>(p); });
  const py::ssize_t h = img.height, w = img.width;
  return py::array_t<std::uint8_t>({h, w, py::ssize_t(4)}, {w * 4, py::ssize_t(4), py::ssize_t(1)},
                                   pixels->data(), owner);
}

tsp::Image to_image(const py::object& obj, const std::string& what) {
  if (py::isinstance<py::str>(obj) || py::hasattr(obj, "__fspath__")) {
    const std::string path = py::str(py::module_::import("os").attr("fspath")(obj));
    return tsp::read_png(path);
  }
  py::array a = py::array::ensure(obj);
  if (!a || a.ndim() != 3 || (a.shape(2) != 3 && a.shape(2) != 4) ||
      !a.dtype().is(py::dtype::of<std::uint8_t>()))
    throw tsp::UsageError(what + ": expected a PNG path or a uint8 array (height, width, 3 or 4)");
  const auto c = py::array_t<std::uint8_t, py::array::c_style | py::array::forcecast>::ensure(a);
  const int h = int(c.shape(0)), w = int(c.shape(1)), ch = int(c.shape(2));
  if (h < 1 || w < 1) throw tsp::UsageError(what + ": the image is empty");
  tsp::Image img(w, h);
  const std::uint8_t* src = c.data();
  if (ch == 4) {
    std::memcpy(img.rgba.data(), src, img.rgba.size());
  } else {
    for (std::int64_t p = 0; p < img.pixels(); ++p) {
      std::memcpy(&img.rgba[std::size_t(4 * p)], src + 3 * p, 3);
      img.rgba[std::size_t(4 * p + 3)] = 255;
    }
  }
  return img;
}

}  // namespace tsppy

PYBIND11_MODULE(_core, m) {
  m.doc() = "tspplay's library: build, open, render, metrics and diff (see the tspplay package)";
  tsppy::register_exceptions(m);
  tsppy::bind_build(m);
  tsppy::bind_file(m);
  tsppy::bind_render(m);
}
