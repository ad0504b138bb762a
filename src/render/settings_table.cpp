#include "render/settings_table.h"

#include <cmath>
#include <cstdlib>
#include <limits>

#include "tsp/core/error.h"
#include "tsp/core/number_text.h"

namespace tspgl {

namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();
constexpr double kBytesPerMib = double(1 << 20);

// v with every digit a double holds: text that reads back as the same number.
std::string number_text(double v) {
  return tsp::number_text(v, "%.17g");
}

std::string on_off(bool b) { return b ? "on" : "off"; }

// Words of enum-valued settings, in the enum's order.
const std::vector<std::string_view> kToggle{"off", "on"};
const std::vector<std::string_view> kCompositingWords{"slices", "boxes", "rays"};
const std::vector<std::string_view> kSpanStepWords{"first", "middle", "mean"};
const std::vector<std::string_view> kFlatWords{"slices", "exact"};
const std::vector<std::string_view> kSurfaceWords{"off", "boundary"};
const std::vector<std::string_view> kBackendWords{"auto", "gl", "cpu"};

using K = SettingKind;
using G = SettingGroup;

// The quality rows: tolerances, spacing and the sampling modes.
void add_quality(std::vector<SettingSpec>& t) {
  t.push_back({.name = "spatial-tol", .kind = K::number, .group = G::quality,
               .unit = "metric error", .lo = 0, .hi = kInf, .choices = {}, .ui_lo = 0, .ui_hi = 1,
               .help = "Spatial error tolerance: a node whose spatial error is at most this is "
                       "drawn flat, in its mean colour",
               .get = [](const RenderSettings& s) { return number_text(s.tol.spatial); },
               .set = [](RenderSettings& s, double v) { s.tol.spatial = v; }});
  t.push_back({.name = "temporal-tol", .kind = K::number, .group = G::quality,
               .unit = "metric error", .lo = 0, .hi = kInf, .choices = {}, .ui_lo = 0, .ui_hi = 1,
               .help = "Temporal error tolerance: steps whose node changes by at most this share "
                       "one texture",
               .get = [](const RenderSettings& s) { return number_text(s.tol.temporal); },
               .set = [](RenderSettings& s, double v) { s.tol.temporal = v; }});
  t.push_back({.name = "spacing", .kind = K::number, .group = G::quality, .unit = "voxels",
               .lo = kMinSliceSpacing, .hi = kMaxSliceSpacing, .choices = {}, .ui_lo = 0.25, .ui_hi = 8,
               .help = "Slice (sample) spacing along the view",
               .get = [](const RenderSettings& s) { return number_text(s.spacing); },
               .set = [](RenderSettings& s, double v) { s.spacing = v; }});
  t.push_back({.name = "sampling-tol", .kind = K::number, .group = G::quality,
               .unit = "colour change", .lo = 0, .hi = kInf, .choices = {}, .ui_lo = 0, .ui_hi = 1,
               .help = "Adaptive sampling (rays, no probes, not with --preintegrated): each brick "
                       "is sampled every m x spacing, m up to 8, the largest whose step changes "
                       "the premultiplied TF colour by at most this much (e.g. 0.005; 0: off)",
               .get = [](const RenderSettings& s) { return number_text(s.sampling_tol); },
               .set = [](RenderSettings& s, double v) { s.sampling_tol = v; }});
  t.push_back({.name = "refine-tol", .kind = K::number, .group = G::quality,
               .unit = "TF variation", .lo = 0, .hi = kInf, .choices = {}, .ui_lo = 0, .ui_hi = 1,
               .help = "Refinement (rays, no probes, not with --sampling-tol or --preintegrated): "
                       "the TF is cut into pieces that stay within this of a straight line "
                       "(premultiplied colour and opacity); a segment whose sample falls in "
                       "another piece than a neighbour's is sampled 6 times finer, so thin bands "
                       "and sharp surfaces are drawn where they lie (0: off)",
               .get = [](const RenderSettings& s) { return number_text(s.refine_tol); },
               .set = [](RenderSettings& s, double v) { s.refine_tol = v; }});
  t.push_back({.name = "level-tf", .kind = K::toggle, .group = G::quality, .unit = {}, .lo = 0, .hi = 0,
               .choices = kToggle,
               .help = "LOD level bricks (rays) classified by the TF averaged over the spread of "
                       "the voxels a sample stands for, so thin TF bands survive coarse levels",
               .get = [](const RenderSettings& s) { return on_off(s.level_tf); },
               .set = [](RenderSettings& s, double v) { s.level_tf = v != 0; }});
  t.push_back({.name = "span-step", .kind = K::choice, .group = G::quality, .unit = {}, .lo = 0, .hi = 0,
               .choices = kSpanStepWords,
               .help = "What textures a span of several steps: its first step (the paper's), "
                       "its middle one or the per-voxel mean of its steps",
               .get = [](const RenderSettings& s) { return std::string(tsp::to_string(s.span_step)); },
               .set = [](RenderSettings& s, double v) {
                 s.span_step = v == 0 ? tsp::SpanStep::first
                               : v == 1 ? tsp::SpanStep::middle : tsp::SpanStep::mean;
               }});
}

// The compositing rows: how textured bricks are drawn, who draws them, lighting, the surface.
void add_compositing(std::vector<SettingSpec>& t) {
  t.push_back({.name = "compositing", .kind = K::choice, .group = G::compositing, .unit = {}, .lo = 0, .hi = 0,
               .choices = kCompositingWords,
               .help = "Textured boxes as slices (view-aligned polygons), boxes (each brick ray "
                       "cast on its own) or rays (the whole volume ray cast in one pass)",
               .get = [](const RenderSettings& s) { return std::string(to_string(s.compositing)); },
               .set = [](RenderSettings& s, double v) {
                 s.compositing = v == 0 ? Compositing::slices
                                 : v == 1 ? Compositing::boxes : Compositing::rays;
               }});
  t.push_back({.name = "backend", .kind = K::choice, .group = G::compositing, .unit = {}, .lo = 0, .hi = 0,
               .choices = kBackendWords,
               .help = "Who casts the rays: gl (the GLSL caster), cpu (the native caster in RAM, "
                       "both cores) or auto (cpu where the GL renderer is software: llvmpipe, "
                       "softpipe, swrast; gl on a GPU). What the cpu caster cannot draw (probes, "
                       "pre-integration, adaptive sampling, a surface, slices or boxes) is drawn "
                       "by gl, and frames.json says so",
               .get = [](const RenderSettings& s) { return std::string(to_string(s.backend)); },
               .set = [](RenderSettings& s, double v) {
                 s.backend = v == 0 ? Backend::automatic : v == 1 ? Backend::gl : Backend::cpu;
               }});
  t.push_back({.name = "render-scale", .kind = K::number, .group = G::compositing,
               .unit = "share of the pixels per axis", .lo = kMinRenderScale, .hi = 1,
               .choices = {}, .ui_lo = kMinRenderScale, .ui_hi = 1,
               .help = "Rays every 1/S pixels per axis, the picture magnified to the full size "
                       "(VTK's image sample distance 1/S); 1: every pixel",
               .get = [](const RenderSettings& s) { return number_text(s.render_scale); },
               .set = [](RenderSettings& s, double v) { s.render_scale = v; }});
  t.push_back({.name = "preintegrated", .kind = K::toggle, .group = G::compositing, .unit = {}, .lo = 0, .hi = 0,
               .choices = kToggle,
               .help = "Pre-integrated TF lookup over each pair of neighbouring samples",
               .get = [](const RenderSettings& s) { return on_off(s.preintegrated); },
               .set = [](RenderSettings& s, double v) { s.preintegrated = v != 0; }});
  t.push_back({.name = "shade", .kind = K::toggle, .group = G::compositing, .unit = {}, .lo = 0, .hi = 0,
               .choices = kToggle,
               .help = "Light the volume: Blinn-Phong with a headlight (VTK's ambient 0.1, "
                       "diffuse 0.7, specular 0.2, power 10), normals from the scalar's gradient",
               .get = [](const RenderSettings& s) { return on_off(s.shade); },
               .set = [](RenderSettings& s, double v) { s.shade = v != 0; }});
  t.push_back({.name = "surface", .kind = K::choice, .group = G::compositing, .unit = {}, .lo = 0, .hi = 0,
               .choices = kSurfaceWords,
               .help = "boundary: the mesh's boundary (TetSplat's Shell) drawn as an opaque lit "
                       "surface of splats under the volume (rays), which shows where a probe cuts "
                       "it open; needs the mesh (render: --surface-mesh; play: a mesh input)",
               .get = [](const RenderSettings& s) { return std::string(s.surface ? "boundary" : "off"); },
               .set = [](RenderSettings& s, double v) { s.surface = v != 0; }});
  t.push_back({.name = "surface-px", .kind = K::number, .group = G::compositing, .unit = "pixels",
               .lo = 0, .hi = kMaxSurfacePx, .choices = {}, .ui_lo = 0, .ui_hi = 64,
               .help = "Minimum splat size of the boundary surface: its splat hierarchy is cut "
                       "where a splat projects to at most this (0: every leaf triangle); larger "
                       "is coarser and faster",
               .get = [](const RenderSettings& s) { return number_text(s.surface_px); },
               .set = [](RenderSettings& s, double v) { s.surface_px = v; }});
}

// The memory and diagnostics rows.
void add_memory_and_diagnostics(std::vector<SettingSpec>& t) {
  t.push_back({.name = "upload-budget", .kind = K::number, .group = G::memory, .unit = "MiB",
               .lo = 0, .hi = double(kMaxBudgetBytes) / kBytesPerMib, .choices = {}, .ui_lo = 0, .ui_hi = 256,
               .help = "Texture MiB one frame may upload (0: no limit); bricks over it are drawn "
                       "flat in their mean colour and uploaded by later frames",
               .get = [](const RenderSettings& s) {
                 return number_text(double(s.upload_budget) / kBytesPerMib);
               },
               .set = [](RenderSettings& s, double v) {
                 s.upload_budget = std::int64_t(std::llround(v * kBytesPerMib));
               }});
  t.push_back({.name = "flat", .kind = K::choice, .group = G::diagnostics, .unit = {}, .lo = 0, .hi = 0, .choices = kFlatWords,
               .help = "Coherent (flat) nodes: exact (one box, the exact exponential through it) "
                       "or slices (flat slices every spacing: the paper's rule)",
               .get = [](const RenderSettings& s) {
                 return std::string(s.exact_flat ? "exact" : "slices");
               },
               .set = [](RenderSettings& s, double v) { s.exact_flat = v != 0; }});
  t.push_back({.name = "reuse", .kind = K::toggle, .group = G::diagnostics, .unit = {}, .lo = 0, .hi = 0, .choices = kToggle,
               .help = "Partial-image reuse: redraw only where bricks changed since the last "
                       "frame (same view, TF and knobs; exact)",
               .get = [](const RenderSettings& s) { return on_off(s.reuse_image); },
               .set = [](RenderSettings& s, double v) { s.reuse_image = v != 0; }});
  t.push_back({.name = "dense", .kind = K::toggle, .group = G::diagnostics, .unit = {}, .lo = 0, .hi = 0, .choices = kToggle,
               .help = "Rays: a frame that textures every leaf brick is cast through one "
                       "whole-volume texture instead of the brick grid (the same samples)",
               .get = [](const RenderSettings& s) { return on_off(s.dense); },
               .set = [](RenderSettings& s, double v) { s.dense = v != 0; }});
  t.push_back({.name = "skip-transparent", .kind = K::toggle, .group = G::diagnostics, .unit = {}, .lo = 0, .hi = 0,
               .choices = kToggle,
               .help = "A coherent node holding a transparent child is drawn as its children, so "
                       "what zero tolerance skips is never drawn (off: the paper's rule)",
               .get = [](const RenderSettings& s) { return on_off(s.skip_transparent); },
               .set = [](RenderSettings& s, double v) { s.skip_transparent = v != 0; }});
}

std::vector<SettingSpec> make_table() {
  std::vector<SettingSpec> t;
  add_quality(t);
  add_compositing(t);
  add_memory_and_diagnostics(t);
  return t;
}

std::string expected(const SettingSpec& spec) {
  std::string e;
  if (spec.kind == SettingKind::number) {
    e = std::isinf(spec.hi)
            ? "a finite number >= " + tsp::number_text(spec.lo)
            : "a number in [" + tsp::number_text(spec.lo) + ", " + tsp::number_text(spec.hi) + "]";
    if (!spec.unit.empty()) e += " (" + std::string(spec.unit) + ")";
    return e;
  }
  for (std::size_t i = 0; i < spec.choices.size(); ++i)
    e += (i == 0 ? "" : i + 1 == spec.choices.size() ? " or " : ", ") +
         std::string(spec.choices[i]);
  return e;
}

}  // namespace

const char* group_title(SettingGroup g) {
  switch (g) {
    case SettingGroup::quality: return "Quality";
    case SettingGroup::compositing: return "Compositing";
    case SettingGroup::memory: return "Memory";
    case SettingGroup::diagnostics: return "Diagnostics";
  }
  return "?";
}

std::string SettingSpec::json_key() const {
  std::string k(name);
  for (char& c : k)
    if (c == '-') c = '_';
  return k;
}

const std::vector<SettingSpec>& settings_table() {
  static const std::vector<SettingSpec> table = make_table();
  return table;
}

const SettingSpec* find_setting(std::string_view name) {
  for (const SettingSpec& s : settings_table())
    if (s.name == name) return &s;
  return nullptr;
}

void set_setting(RenderSettings& s, const SettingSpec& spec, const std::string& text,
                 const std::string& where) {
  auto fail = [&] {
    std::string quoted = text.size() > 40 ? text.substr(0, 40) + "..." : text;
    throw tsp::UsageError(where + " '" + quoted + "': expected " + expected(spec));
  };
  if (spec.kind == SettingKind::number) {
    const char* begin = text.c_str();
    char* end = nullptr;
    const double v = text.empty() ? NAN : std::strtod(begin, &end);
    if (text.empty() || end != begin + text.size() || !std::isfinite(v) || v < spec.lo ||
        v > spec.hi)
      fail();
    spec.set(s, v);
    return;
  }
  for (std::size_t i = 0; i < spec.choices.size(); ++i)
    if (text == spec.choices[i]) {
      spec.set(s, double(i));
      return;
    }
  fail();
}

void check_setting(const RenderSettings& s, const SettingSpec& spec, const std::string& where) {
  RenderSettings scratch;  // (the value as text, parsed back as a typed one is: 17 digits)
  set_setting(scratch, spec, spec.get(s), where);
}

std::string get_setting(const RenderSettings& s, const SettingSpec& spec) { return spec.get(s); }

std::string default_text(const SettingSpec& spec) { return spec.get(RenderSettings{}); }

std::string to_options(const RenderSettings& s) {
  const RenderSettings d;
  std::string out;
  for (const SettingSpec& spec : settings_table()) {
    const std::string v = spec.get(s);
    if (v == spec.get(d)) continue;
    out += (out.empty() ? "--" : " --") + std::string(spec.name) + " " + v;
  }
  return out;
}

nlohmann::json settings_json(const RenderSettings& s) {
  nlohmann::json j = nlohmann::json::object();
  for (const SettingSpec& spec : settings_table()) {
    const std::string v = spec.get(s);
    switch (spec.kind) {
      case SettingKind::number: j[spec.json_key()] = std::strtod(v.c_str(), nullptr); break;
      case SettingKind::toggle: j[spec.json_key()] = v == "on"; break;
      case SettingKind::choice: j[spec.json_key()] = v; break;
    }
  }
  return j;
}

}  // namespace tspgl
