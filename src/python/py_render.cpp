// tspplay._core.render, transfer functions, diff and PNGs: `tspplay render` as a call — the
// options go through the CLI's own mapping (cli/render_args.h) and the settings table by name,
// so every check and message is the CLI's; the frames come back as numpy arrays.
#include <filesystem>
#include <string>
#include <vector>

#include "cli/render_args.h"
#include "py_common.h"
#include "render/settings_table.h"
#include "tsp/core/error.h"
#include "tsp/core/stopwatch.h"
#include "tsp/metric/tf_io.h"
#include "tsp/report/image_diff.h"
#include "tsp/store/tsp_file.h"

namespace tsppy {
namespace {

// The settings table as Python dicts (name, kind, group, unit, range, choices, default, help).
py::list settings_rows() {
  py::list rows;
  for (const tspgl::SettingSpec& spec : tspgl::settings_table()) {
    py::dict r;
    r["name"] = std::string(spec.name);
    r["kind"] = spec.kind == tspgl::SettingKind::number   ? "number"
                : spec.kind == tspgl::SettingKind::toggle ? "toggle"
                                                          : "choice";
    r["group"] = tspgl::group_title(spec.group);
    r["unit"] = std::string(spec.unit);
    r["range"] = py::make_tuple(spec.lo, spec.hi);
    py::list choices;
    for (std::string_view c : spec.choices) choices.append(std::string(c));
    r["choices"] = choices;
    r["default"] = tspgl::default_text(spec);
    r["help"] = std::string(spec.help);
    rows.append(r);
  }
  return rows;
}

// The render job for args (the CLI's option names → text, "probe" → a list of texts) and
// settings (table names → text). Throws tsp::UsageError for an unknown name or a bad value.
tspgl::RenderJobOptions job_options(const py::dict& args, const py::dict& settings) {
  tspcli::RenderArgs a;
  for (const auto& [key, value] : args) {
    const std::string name = py::str(key);
    std::vector<std::string> texts;
    if (py::isinstance<py::list>(value) || py::isinstance<py::tuple>(value)) {
      for (const auto& v : value) texts.push_back(py::str(v));
    } else {
      texts.push_back(py::str(value));
    }
    for (const std::string& text : texts)
      if (!tspcli::set_render_arg(a, name, text)) {
        std::string known;
        for (const std::string& n : tspcli::render_arg_names()) known += " " + n;
        throw tsp::UsageError("render: no option --" + name + "; the options are" + known +
                              " and the settings table's (tspplay.settings_table())");
      }
  }
  tspgl::RenderSettings s;
  std::vector<std::string> given;
  for (const auto& [key, value] : settings) {
    const std::string name = py::str(key);
    const tspgl::SettingSpec* spec = tspgl::find_setting(name);
    if (!spec) throw tsp::UsageError("render: no setting --" + name);
    tspgl::set_setting(s, *spec, py::str(value), "--" + name);
    given.push_back("--" + name);
  }
  tspgl::validate(s);
  return tspcli::render_job_options(a, s, given);
}

// Runs the job without the GIL: the last pass's images and every frame's record, with Ctrl-C
// checked and progress relayed after every frame.
py::dict run_job(tspgl::RenderJobOptions o, const py::object& progress) {
  std::vector<tsp::Image> images;
  std::vector<int> image_steps;
  const int last_pass = o.passes;
  o.on_frame = [&](const tspgl::FrameRecord& rec, const tsp::Image& pixels) {
    if (rec.pass != last_pass) return;
    images.push_back(pixels);
    image_steps.push_back(rec.report.step);
  };
  const auto relay = progress_relay(progress);
  tspgl::RenderJobResult r;
  double job_ms = 0;
  {
    py::gil_scoped_release release;
    check_signals();
    const tsp::Stopwatch watch;
    r = tspgl::run_render_job(
        o, [&](int done, int total) { relay("render", done, total); },
        [&](const std::string& phase, int done, int total) {
          relay("calibrate " + phase, done, total);
        });
    job_ms = watch.ms();
  }
  py::list frames, pictures;
  for (const tspgl::FrameRecord& f : r.frames) frames.append(to_python(nlohmann::json(f)));
  for (tsp::Image& img : images) pictures.append(image_array(std::move(img)));
  py::dict d;
  d["images"] = pictures;
  d["image_steps"] = image_steps;
  d["frames"] = frames;
  d["renderer"] = r.renderer;
  d["gl_vendor"] = r.gl_vendor;
  d["context"] = r.context;
  d["metric_ms"] = r.metric_ms;
  d["warnings"] = r.warnings;
  d["quality_options"] = r.quality_options;
  d["quality_calibrated_de"] = r.quality_calibrated_de;
  d["calibration_file"] = r.calibration_file;
  d["median_ms"] = tspgl::median_frame_ms(r, last_pass);
  d["job_ms"] = job_ms;  // inside run_render_job: the rest of the call is the binding's
  return d;
}

// tf's table as (domain, entries (K, 4) float32).
py::tuple tf_tuple(const tsp::TransferFunction& tf) {
  py::array_t<float> entries({py::ssize_t(tf.size()), py::ssize_t(4)});
  auto e = entries.mutable_unchecked<2>();
  for (int j = 0; j < tf.size(); ++j) {
    const tsp::Rgba& c = tf.entry(j);
    e(j, 0) = c.r;
    e(j, 1) = c.g;
    e(j, 2) = c.b;
    e(j, 3) = c.a;
  }
  return py::make_tuple(py::make_tuple(tf.domain().lo, tf.domain().hi), entries);
}

}  // namespace

void bind_render(py::module_& m) {
  m.def("settings_table", &settings_rows,
        "Every render setting (the table `render`, `play` and scripts share) as dicts.");
  m.def("render_arg_names", &tspcli::render_arg_names,
        "The names of `render`'s options besides the settings table's.");
  m.def(
      "render",
      [](const py::dict& args, const py::dict& settings, py::object progress) {
        return run_job(job_options(args, settings), progress);
      },
      py::arg("args"), py::arg("settings"), py::arg("progress") = py::none(),
      "`tspplay render` as a call: args by the CLI's option names (text), settings by the "
      "table's names. Returns images (last pass), frames (frames.json's entries) and the job's "
      "context. Raises UsageError, FormatError, IoError, GlError, KeyboardInterrupt.");
  m.def(
      "tf_table",
      [](const std::string& arg, double lo, double hi, int entries, const std::string& range,
         const tsp::TspFile* file) {
        tsp::TfRangeChoice choice = tsp::parse_tf_range(range);
        if (!file)
          return tf_tuple(tsp::transfer_function_from_arg(arg, tsp::preset_domain({lo, hi}),
                                                          entries, choice, nullptr));
        const tsp::ValueHistogram histogram = tsp::histogram_of(*file);
        const tsp::ValueRange domain = tsp::tf_domain_of(choice, *file, 0);
        return tf_tuple(tsp::transfer_function_from_arg(arg, domain, entries, choice, &histogram));
      },
      py::arg("tf"), py::arg("lo") = 0.0, py::arg("hi") = 1.0, py::arg("entries") = 256,
      py::arg("tf_range") = "auto", py::arg("file") = nullptr,
      "The table of --tf ARG (a file or preset:NAME) placed over [lo, hi], or over file's data "
      "as render places it: ((lo, hi), entries (K, 4)). Raises UsageError, IoError, FormatError.");
  m.def(
      "parse_tf",
      [](const std::string& text, const std::string& origin, int entries) {
        return tf_tuple(tsp::parse_transfer_function(text, origin, entries));
      },
      py::arg("text"), py::arg("origin"), py::arg("entries") = 256,
      "Parses a transfer function's JSON text (ours or a ParaView preset). Raises FormatError.");
  m.def("preset_names", &tsp::preset_names, "The built-in transfer-function presets.");
  m.def(
      "diff",
      [](const py::object& a, const py::object& b, bool want_image) {
        const tsp::Image ia = to_image(a, "diff: first image");
        const tsp::Image ib = to_image(b, "diff: second image");
        tsp::Image out;
        tsp::DiffStats s;
        {
          py::gil_scoped_release release;
          s = tsp::diff_images(ia, ib, want_image ? &out : nullptr);
        }
        py::dict d = to_python(nlohmann::json(s)).cast<py::dict>();
        if (want_image) d["image"] = image_array(std::move(out));
        return d;
      },
      py::arg("a"), py::arg("b"), py::arg("image") = false,
      "`tspplay diff`: mean, p99 and max per-pixel dE in CIE L*u*v* of two images (uint8 arrays "
      "or PNG paths). Raises UsageError (sizes differ), IoError, FormatError.");
  m.def(
      "read_png", [](const std::string& path) { return image_array(tsp::read_png(path)); },
      py::arg("path"), "A PNG as a uint8 array (height, width, 4). Raises IoError, FormatError.");
  m.def(
      "write_png",
      [](const std::string& path, const py::object& img) {
        tsp::write_png(path, to_image(img, "write_png"));
      },
      py::arg("path"), py::arg("image"), "Writes an RGBA or RGB uint8 array as an sRGB PNG.");
  m.def("tspplay_binary", [] {
    namespace fs = std::filesystem;
    std::error_code ec;
    if (fs::exists(TSPPLAY_BUILD_BIN, ec)) return std::string(TSPPLAY_BUILD_BIN);
    if (fs::exists(TSPPLAY_INSTALL_BIN, ec)) return std::string(TSPPLAY_INSTALL_BIN);
    return std::string("tspplay");  // from PATH
  }, "The tspplay executable `play` runs (the build tree's, the installed one, or PATH's).");
}

}  // namespace tsppy
