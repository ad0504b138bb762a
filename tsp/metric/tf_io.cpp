#include "tsp/metric/tf_io.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>

#include "tsp/core/error.h"
#include "tsp/core/json_read.h"
#include "tsp/core/input_file.h"
#include "tsp/core/temp_output.h"
#include "tsp/core/json_text.h"
#include "tsp/store/tsp_file.h"

namespace tsp {

namespace {

using nlohmann::json;

// ParaView stores each colour point as (x, r, g, b) and each opacity point as
// (x, alpha, midpoint, sharpness).
constexpr std::size_t kParaViewColourStride = 4;
constexpr std::size_t kParaViewOpacityStride = 4;
constexpr const char* kPresetPrefix = "preset:";

[[noreturn]] void fail(const std::string& origin, const std::string& key, const std::string& what) {
  throw FormatError(origin + ": transfer function key \"" + key + "\": " + what);
}

double number(const json& v, const std::string& origin, const std::string& key) {
  if (!v.is_number()) fail(origin, key, "expected a number, found " + json_text(v));
  const double d = v.get<double>();
  if (!std::isfinite(d)) fail(origin, key, "expected a finite number, found " + json_text(v));
  return d;
}

float unit(const json& v, const std::string& origin, const std::string& key) {
  const double d = number(v, origin, key);
  if (d < 0 || d > 1) fail(origin, key, "expected a value in [0, 1], found " + json_text(v));
  return float(d);
}

const json& require(const json& obj, const char* key, const std::string& origin) {
  auto it = obj.find(key);
  if (it == obj.end()) fail(origin, key, "missing");
  return *it;
}

TransferFunction parse_ours(const json& doc, const std::string& origin, int entries) {
  const json& range = require(doc, "range", origin);
  if (!range.is_array() || range.size() != 2)
    fail(origin, "range", "expected [lo, hi], found " + json_text(range));
  const ValueRange domain{number(range[0], origin, "range[0]"),
                          number(range[1], origin, "range[1]")};
  if (!(domain.lo < domain.hi)) fail(origin, "range", "expected lo < hi, found " + json_text(range));
  if (!std::isfinite(domain.width()))
    fail(origin, "range", "expected a finite width hi - lo, found " + json_text(range));
  const json& pts = require(doc, "points", origin);
  if (!pts.is_array() || pts.empty())
    fail(origin, "points", "expected a non-empty list of [x, r, g, b, a]");
  std::vector<TfPoint> points;
  for (std::size_t i = 0; i < pts.size(); ++i) {
    const std::string key = "points[" + std::to_string(i) + "]";
    const json& p = pts[i];
    if (!p.is_array() || p.size() != 5)
      fail(origin, key, "expected [x, r, g, b, a], found " + json_text(p));
    points.push_back({number(p[0], origin, key + "[0]"),
                      {unit(p[1], origin, key + "[1]"), unit(p[2], origin, key + "[2]"),
                       unit(p[3], origin, key + "[3]"), unit(p[4], origin, key + "[4]")}});
  }
  return TransferFunction::from_points(domain, points, entries);
}

std::vector<double> flat_numbers(const json& arr, const std::string& origin, const char* key,
                                 std::size_t stride) {
  if (!arr.is_array() || arr.empty() || arr.size() % stride != 0)
    fail(origin, key,
         "expected a non-empty flat list with a multiple of " + std::to_string(stride) +
             " numbers, found " + std::to_string(arr.is_array() ? arr.size() : 0) + " values");
  std::vector<double> v;
  for (std::size_t i = 0; i < arr.size(); ++i)
    v.push_back(number(arr[i], origin, std::string(key) + "[" + std::to_string(i) + "]"));
  return v;
}

// Piecewise-linear interpolation of (x, y) knots at x, constant beyond the ends.
double interpolate(const std::vector<std::pair<double, double>>& knots, double x) {
  if (x <= knots.front().first) return knots.front().second;
  if (x >= knots.back().first) return knots.back().second;
  auto hi = std::upper_bound(knots.begin(), knots.end(), x,
                             [](double v, const auto& k) { return v < k.first; });
  auto lo = hi - 1;
  const double w = hi->first - lo->first;
  return w > 0 ? lo->second + (hi->second - lo->second) * (x - lo->first) / w : hi->second;
}

TransferFunction parse_paraview(const json& preset, const std::string& origin, int entries) {
  const std::vector<double> rgb = flat_numbers(require(preset, "RGBPoints", origin), origin,
                                               "RGBPoints", kParaViewColourStride);
  std::vector<TfPoint> colour;
  for (std::size_t i = 0; i < rgb.size(); i += kParaViewColourStride) {
    auto key = [&](std::size_t k) { return "RGBPoints[" + std::to_string(i + k) + "]"; };
    auto check = [&](std::size_t k) {
      if (rgb[i + k] < 0 || rgb[i + k] > 1)
        fail(origin, key(k),
             "expected a colour component in [0, 1], found " + std::to_string(rgb[i + k]));
      return float(rgb[i + k]);
    };
    colour.push_back({rgb[i], {check(1), check(2), check(3), 0}});
  }
  auto [lo_it, hi_it] =
      std::minmax_element(colour.begin(), colour.end(), [](auto& a, auto& b) { return a.x < b.x; });
  const ValueRange domain{lo_it->x, hi_it->x};
  if (!(domain.lo < domain.hi))
    fail(origin, "RGBPoints", "all points lie at x = " + std::to_string(domain.lo));
  if (!std::isfinite(domain.width()))
    fail(origin, "RGBPoints", "the points span more than the double range (x from " +
                                  std::to_string(domain.lo) + " to " + std::to_string(domain.hi) + ")");
  // ParaView's default opacity when a preset carries none: a ramp from 0 to 1 over the domain.
  std::vector<std::pair<double, double>> opacity = {{domain.lo, 0.0}, {domain.hi, 1.0}};
  if (auto it = preset.find("Points"); it != preset.end()) {
    const std::vector<double> pts = flat_numbers(*it, origin, "Points", kParaViewOpacityStride);
    opacity.clear();
    for (std::size_t i = 0; i < pts.size(); i += kParaViewOpacityStride) {
      if (pts[i + 1] < 0 || pts[i + 1] > 1)
        fail(origin, "Points[" + std::to_string(i + 1) + "]",
             "expected an opacity in [0, 1], found " + std::to_string(pts[i + 1]));
      opacity.push_back({pts[i], pts[i + 1]});
    }
    std::stable_sort(opacity.begin(), opacity.end(),
                     [](auto& a, auto& b) { return a.first < b.first; });
  }
  TransferFunction tf = TransferFunction::from_points(domain, colour, entries);
  std::vector<Rgba> table(tf.entries().begin(), tf.entries().end());
  for (int j = 0; j < entries; ++j) table[j].a = float(interpolate(opacity, tf.entry_value(j)));
  tf.set_entries(0, table);
  return tf;
}

std::string slurp(const std::string& path) {
  return read_input_file(path, "transfer function file");
}

struct PresetKnot {
  double t;  // position in [0, 1] of the domain
  Rgba c;
};

struct Rgb {
  float r, g, b;
};

// Colours at equal steps over [0, 1] with ParaView's default linear opacity ramp.
std::vector<PresetKnot> ramp(std::initializer_list<Rgb> colours) {
  std::vector<PresetKnot> k;
  const double n = double(colours.size() - 1);
  int i = 0;
  for (const Rgb& c : colours) {
    const double t = i++ / n;
    k.push_back({t, {c.r, c.g, c.b, float(t)}});
  }
  return k;
}

const std::vector<std::pair<std::string, std::vector<PresetKnot>>>& presets() {
  static const std::vector<std::pair<std::string, std::vector<PresetKnot>>> p = {
      // Two narrow opaque bands, transparent elsewhere: most nodes become transparent (the
      // paper's "sparse" transfer functions).
      {"sparse",
       {{0.00, {0, 0, 0, 0}},
        {0.55, {1.0f, 0.6f, 0.1f, 0}},
        {0.60, {1.0f, 0.6f, 0.1f, 0.6f}},
        {0.65, {1.0f, 0.6f, 0.1f, 0}},
        {0.80, {0.3f, 0.6f, 1.0f, 0}},
        {0.85, {0.3f, 0.6f, 1.0f, 0.9f}},
        {0.90, {0.3f, 0.6f, 1.0f, 0}},
        {1.00, {0, 0, 0, 0}}}},
      // Every value visible: a blue–white–red map with opacity rising over the domain.
      {"filled",
       {{0.0, {0.23f, 0.30f, 0.75f, 0.05f}},
        {0.5, {0.87f, 0.87f, 0.87f, 0.30f}},
        {1.0, {0.71f, 0.02f, 0.15f, 0.60f}}}},
      // Grey ramp with ParaView's default linear opacity.
      {"grey", {{0.0, {0, 0, 0, 0}}, {1.0, {1, 1, 1, 1}}}},
      // ParaView's common colour maps, with its default linear opacity (0 at the low end, 1 at
      // the high end). Colours at the maps' published control points: viridis and inferno as
      // matplotlib's 8- and 10-step palettes, Cool to Warm as Moreland's three points, Jet as
      // ParaView's seven; "rainbow-uniform" is our equal-step blue–cyan–green–yellow–red
      // approximation of ParaView's Rainbow Uniform (not its exact table).
      {"viridis", ramp({{0.267f, 0.005f, 0.329f}, {0.275f, 0.196f, 0.494f},
                        {0.212f, 0.361f, 0.553f}, {0.153f, 0.498f, 0.557f},
                        {0.122f, 0.631f, 0.529f}, {0.290f, 0.757f, 0.427f},
                        {0.627f, 0.855f, 0.224f}, {0.992f, 0.906f, 0.145f}})},
      {"inferno", ramp({{0.000f, 0.000f, 0.016f}, {0.106f, 0.047f, 0.255f},
                        {0.290f, 0.047f, 0.420f}, {0.471f, 0.110f, 0.427f},
                        {0.647f, 0.173f, 0.376f}, {0.812f, 0.267f, 0.275f},
                        {0.929f, 0.412f, 0.145f}, {0.984f, 0.608f, 0.024f},
                        {0.969f, 0.820f, 0.239f}, {0.988f, 1.000f, 0.643f}})},
      {"cool-to-warm",
       {{0.0, {0.230f, 0.299f, 0.754f, 0}},
        {0.5, {0.865f, 0.865f, 0.865f, 0.5f}},
        {1.0, {0.706f, 0.016f, 0.150f, 1}}}},
      {"jet",
       {{0.0, {0, 0, 0.5625f, 0}},
        {0.1111, {0, 0, 1, 0.1111f}},
        {0.3651, {0, 1, 1, 0.3651f}},
        {0.4921, {0.5f, 1, 0.5f, 0.4921f}},
        {0.6190, {1, 1, 0, 0.6190f}},
        {0.8730, {1, 0, 0, 0.8730f}},
        {1.0, {0.5f, 0, 0, 1}}}},
      {"grayscale", {{0.0, {0, 0, 0, 0}}, {1.0, {1, 1, 1, 1}}}},
      {"rainbow-uniform", ramp({{0.0f, 0.0f, 1.0f}, {0.0f, 1.0f, 1.0f}, {0.0f, 1.0f, 0.0f},
                                {1.0f, 1.0f, 0.0f}, {1.0f, 0.0f, 0.0f}})},
  };
  return p;
}

TransferFunction parse_document(const json& doc, const std::string& origin, int entries) {
  if (doc.is_object() && doc.contains("points")) return parse_ours(doc, origin, entries);
  if (doc.is_object() && doc.contains("RGBPoints")) return parse_paraview(doc, origin, entries);
  if (doc.is_array()) {
    // A ParaView preset file is a list of presets; we take the first colour map in it.
    for (const json& p : doc)
      if (p.is_object() && p.contains("RGBPoints")) return parse_paraview(p, origin, entries);
    throw FormatError(origin + ": a list without any ParaView preset holding \"RGBPoints\"");
  }
  throw FormatError(origin +
                    ": neither our transfer function (keys \"range\", \"points\") nor a ParaView "
                    "preset (key \"RGBPoints\")");
}

}  // namespace

TransferFunction parse_transfer_function(const std::string& text, const std::string& origin,
                                         int entries) {
  const json doc = parse_json(text, origin);
  try {
    return parse_document(doc, origin, entries);
  } catch (const json::exception& e) {
    throw FormatError(origin + ": unexpected transfer function contents: " + e.what());
  }
}

TransferFunction load_transfer_function(const std::string& path, int entries) {
  return parse_transfer_function(slurp(path), path, entries);
}

void save_transfer_function(const TransferFunction& tf, const std::string& path) {
  json doc;
  doc["range"] = {tf.domain().lo, tf.domain().hi};
  json pts = json::array();
  for (int j = 0; j < tf.size(); ++j) {
    const Rgba& c = tf.entry(j);
    pts.push_back({tf.entry_value(j), c.r, c.g, c.b, c.a});
  }
  doc["points"] = std::move(pts);
  write_file_atomically(path, json_text(doc, 1) + "\n");
}

std::vector<std::string> preset_names() {
  std::vector<std::string> names{kAutoPreset};
  for (auto& [name, knots] : presets()) names.push_back(name);
  return names;
}

TransferFunction preset_transfer_function(const std::string& name, ValueRange domain, int entries,
                                          const ValueHistogram* histogram) {
  if (name == kAutoPreset) {
    if (histogram == nullptr)
      throw UsageError("preset:auto is built from the data's histogram, which is not at hand "
                       "here; name another preset or a transfer function file");
    return histogram_transfer_function(*histogram, domain, entries);
  }
  for (auto& [n, knots] : presets()) {
    if (n != name) continue;
    std::vector<TfPoint> points;
    for (const PresetKnot& k : knots) points.push_back({domain.lo + k.t * domain.width(), k.c});
    return TransferFunction::from_points(domain, points, entries);
  }
  std::string known;
  for (auto& n : preset_names()) known += (known.empty() ? "" : ", ") + n;
  throw UsageError("unknown transfer function preset \"" + name + "\" (known: " + known + ")");
}

ValueRange preset_domain(ValueRange r) {
  if (!std::isfinite(r.lo) || !std::isfinite(r.hi) || !std::isfinite(r.width())) return {0, 1};
  if (r.lo < r.hi) return r;
  const double c = 0.5 * (r.lo + r.hi), half = 0.5 * std::max(1.0, std::fabs(c) * 1e-3);
  return {c - half, c + half};
}

TfRangeChoice parse_tf_range(const std::string& text) {
  TfRangeChoice c;
  if (text.empty() || text == "auto") return c;
  if (text == "data") {
    c.mode = TfRangeChoice::Mode::data;
    return c;
  }
  if (text == "file") {
    c.mode = TfRangeChoice::Mode::file;
    return c;
  }
  if (text == "bulk" || text == "histogram") {  // (the player's "fit to bulk")
    c.mode = TfRangeChoice::Mode::histogram;
    return c;
  }
  if (text == "step") {
    c.mode = TfRangeChoice::Mode::step;
    return c;
  }
  if (text == "view" || text == "visible") {  // (the player's "fit to view")
    c.mode = TfRangeChoice::Mode::visible;
    return c;
  }
  const auto colon = text.find(':', 1);
  double lo = 0, hi = 0;
  bool ok = colon != std::string::npos;
  if (ok) {
    try {
      std::size_t a = 0, b = 0;
      lo = std::stod(text.substr(0, colon), &a);
      hi = std::stod(text.substr(colon + 1), &b);
      ok = a == colon && b == text.size() - colon - 1;
    } catch (const std::exception&) {
      ok = false;
    }
  }
  if (!ok || !std::isfinite(lo) || !std::isfinite(hi) || !(lo < hi))
    throw UsageError("--tf-range '" + text +
                     "': expected auto, data, file, bulk, step, view or LO:HI with LO < HI (histogram and "
                     "visible: bulk and view)");
  if (!std::isfinite(hi - lo))
    throw UsageError("--tf-range '" + text + "': HI - LO is beyond the double range; expected a "
                     "range of finite width");
  c.mode = TfRangeChoice::Mode::explicit_range;
  c.range = {lo, hi};
  return c;
}

TransferFunction rescaled(const TransferFunction& tf, ValueRange to) {
  if (!std::isfinite(to.lo) || !std::isfinite(to.hi) || !(to.lo < to.hi) ||
      !std::isfinite(to.hi - to.lo))
    throw UsageError("transfer function range [" + std::to_string(to.lo) + ", " +
                     std::to_string(to.hi) + "]: expected finite lo < hi and a finite width");
  const ValueRange from = tf.domain();
  std::vector<TfPoint> pts;
  for (int j = 0; j < tf.size(); ++j) {
    const double u = (tf.entry_value(j) - from.lo) / (from.hi - from.lo);
    pts.push_back({to.lo + u * (to.hi - to.lo), tf.entry(j)});
  }
  return TransferFunction::from_points(to, pts, tf.size());
}

std::string tf_range_warning(const TransferFunction& tf, ValueRange data, const std::string& fix) {
  const ValueRange d = tf.domain();
  if (d.hi >= data.lo && d.lo <= data.hi) return "";
  return "the transfer function covers [" + std::to_string(d.lo) + ", " + std::to_string(d.hi) +
         "] but the data lie in [" + std::to_string(data.lo) + ", " + std::to_string(data.hi) +
         "]: nothing will show; " + fix + " stretches it over the data";
}

ValueRange histogram_range(std::span<const std::uint64_t> histogram, ValueRange value_range) {
  long double total = 0;
  for (std::uint64_t n : histogram) total += (long double)n;
  if (histogram.empty() || total <= 0 || !(value_range.lo < value_range.hi)) return value_range;
  const double width = (value_range.hi - value_range.lo) / double(histogram.size());
  // The value below which a share q of the samples lie, linear inside its bin.
  const auto quantile = [&](double q) {
    const long double want = q * total;
    long double below = 0;
    for (std::size_t b = 0; b < histogram.size(); ++b) {
      const long double n = (long double)histogram[b];
      if (n > 0 && below + n >= want)
        return value_range.lo + width * (double(b) + double((want - below) / n));
      below += n;
    }
    return value_range.hi;
  };
  const ValueRange r{quantile(kHistogramTail), quantile(1 - kHistogramTail)};
  return r.lo < r.hi ? r : value_range;
}

ValueRange tf_domain_of(const TfRangeChoice& c, ValueRange value_range,
                        std::span<const std::uint64_t> histogram, ValueRange step_range) {
  switch (c.mode) {
    case TfRangeChoice::Mode::histogram:
      return histogram_range(histogram, value_range);
    case TfRangeChoice::Mode::step:
    case TfRangeChoice::Mode::visible:
      return std::isfinite(step_range.lo) && std::isfinite(step_range.hi) &&
                     step_range.lo < step_range.hi
                 ? step_range
                 : value_range;
    default:
      return value_range;
  }
}

ValueRange tf_domain_of(const TfRangeChoice& c, const TspFile& file, int step) {
  return tf_domain_of(c, file.tree().value_range(), file.metadata().histogram,
                      step_value_range(file.tree(), step));
}

ValueHistogram histogram_of(const TspFile& file) {
  return {file.histogram(), preset_domain(file.tree().value_range())};
}

TransferFunction transfer_function_from_arg(const std::string& arg, ValueRange default_domain,
                                            int entries, const TfRangeChoice& range,
                                            const ValueHistogram* histogram) {
  using Mode = TfRangeChoice::Mode;
  const std::string prefix = kPresetPrefix;
  const ValueRange data = preset_domain(default_domain);
  if (arg.rfind(prefix, 0) == 0)
    return preset_transfer_function(arg.substr(prefix.size()),
                                    range.mode == Mode::explicit_range ? range.range : data,
                                    entries, histogram);
  TransferFunction tf = load_transfer_function(arg, entries);
  switch (range.mode) {
    case Mode::file:
      return tf;
    case Mode::data:
    case Mode::histogram:  // (the caller's domain is the histogram's or the step's: tf_domain_of)
    case Mode::step:
    case Mode::visible:
      return rescaled(tf, data);
    case Mode::explicit_range:
      return rescaled(tf, range.range);
    case Mode::automatic: {
      const ValueRange d = tf.domain();
      const bool normalised = d.lo == 0 && d.hi == 1;
      const bool data_inside = data.lo >= 0 && data.hi <= 1;
      return normalised && !data_inside ? rescaled(tf, data) : tf;
    }
  }
  return tf;
}

}  // namespace tsp
