#include "cli/render_args.h"

#include "cli/session_options.h"

#include <algorithm>
#include <array>
#include <cstdint>
#include <string>
#include <tuple>
#include <climits>
#include <utility>
#include <variant>

#include "cli/args.h"
#include "tsp/core/error.h"

namespace tspcli {
namespace {

/// The knobs --quality picks itself (giving one of them with it is an error).
constexpr const char* kQualityKnobs[] = {"--spatial-tol", "--temporal-tol", "--spacing",
                                         "--compositing", "--preintegrated", "--sampling-tol"};

/// Checks that text is on or off (as CLI11's IsMember does for the command line). Throws
/// tsp::UsageError.
void check_on_off(const std::string& text, const char* option) {
  if (text != "on" && text != "off")
    throw tsp::UsageError(std::string(option) + " '" + text + "': expected on or off");
}

using StringField = std::string RenderArgs::*;
using IntField = int RenderArgs::*;
using DoubleField = double RenderArgs::*;
using ListField = std::vector<std::string> RenderArgs::*;
using Field = std::variant<StringField, IntField, DoubleField, ListField>;

/// Every option of RenderArgs by its long name, in --help's order of groups.
const std::vector<std::pair<std::string, Field>>& fields() {
  static const std::vector<std::pair<std::string, Field>> kFields = {
      {"file", &RenderArgs::file},
      {"field", &RenderArgs::field},
      {"tf", &RenderArgs::tf},
      {"output", &RenderArgs::out},
      {"tf-range", &RenderArgs::tf_range},
      {"annotate", &RenderArgs::annotate},
      {"movie", &RenderArgs::movie},
      {"fps", &RenderArgs::fps},
      {"steps", &RenderArgs::steps},
      {"passes", &RenderArgs::passes},
      {"save-tf", &RenderArgs::save_tf},
      {"size", &RenderArgs::size},
      {"view", &RenderArgs::view},
      {"perspective", &RenderArgs::perspective},
      {"eye", &RenderArgs::eye},
      {"proportions", &RenderArgs::proportions},
      {"scale", &RenderArgs::scale},
      {"orbit", &RenderArgs::orbit},
      {"metric", &RenderArgs::metric},
      {"quality", &RenderArgs::quality},
      {"calibration-dir", &RenderArgs::calibration_dir},
      {"lod", &RenderArgs::lod},
      {"lod-filter", &RenderArgs::lod_filter},
      {"lod-fallback", &RenderArgs::lod_fallback},
      {"target-fps", &RenderArgs::target_fps},
      {"target-ms", &RenderArgs::target_ms},
      {"split-limit", &RenderArgs::split_limit},
      {"focus", &RenderArgs::focus},
      {"probe", &RenderArgs::probes},
      {"probe-op", &RenderArgs::probe_op},
      {"probe-surface", &RenderArgs::probe_surface},
      {"probe-motion", &RenderArgs::probe_motion},
      {"probe-tf", &RenderArgs::probe_tf},
      {"surface-mesh", &RenderArgs::surface_mesh},
      {"surface-field", &RenderArgs::surface_field},
      {"surface-tf", &RenderArgs::surface_tf},
      {"surface-target-ms", &RenderArgs::surface_target_ms},
      {"texture-budget", &RenderArgs::texture_budget_mb},
      {"ram-budget", &RenderArgs::ram_budget_mb},
      {"gl", &RenderArgs::gl},
      {"gpu", &RenderArgs::gpu},
      {"baseline", &RenderArgs::baseline},
      {"cache", &RenderArgs::cache},
  };
  return kFields;
}

}  // namespace

std::vector<std::string> render_arg_names() {
  std::vector<std::string> names;
  for (const auto& [name, field] : fields()) names.push_back(name);
  return names;
}

bool set_render_arg(RenderArgs& a, const std::string& name, const std::string& text) {
  const std::string option = "--" + name;
  for (const auto& [n, field] : fields()) {
    if (n != name) continue;
    if (const auto* s = std::get_if<StringField>(&field)) {
      a.*(*s) = text;
    } else if (const auto* i = std::get_if<IntField>(&field)) {
      a.*(*i) = int(parse_integer(text, option, INT_MIN, INT_MAX, "an integer"));
    } else if (const auto* d = std::get_if<DoubleField>(&field)) {
      a.*(*d) = parse_number(text, option);
    } else {
      (a.*std::get<ListField>(field)).push_back(text);
    }
    return true;
  }
  return false;
}

namespace {

// --lod, --target-fps/--target-ms, --split-limit, --lod-fallback, --focus and --lod-filter.
void set_lod_options(const RenderArgs& a, tspgl::RenderJobOptions& o) {
  const std::string lod =
      a.lod.empty() ? (a.target_ms > 0 || a.target_fps > 0 ? "auto" : "off") : lod_word(a.lod);
  if (lod == "off") {
    o.lod = tspgl::LodMode::off;
  } else if (lod == "auto") {
    o.lod = tspgl::LodMode::adaptive;
  } else if (lod.rfind("splat:", 0) == 0) {
    o.lod = tspgl::LodMode::splat;
    o.splat_px = parse_number(lod.substr(6), "--lod splat:PX");
    if (!(o.splat_px >= 0))
      throw tsp::UsageError("--lod " + lod + ": expected a minimum splat size of 0 pixels or more");
  } else {
    o.lod = tspgl::LodMode::fixed;
    o.lod_level = int(parse_integer(lod, "--lod", 0, 30, "off, auto or a level 0 to 30"));
  }
  if (a.target_fps != 0) {  // the player's unit; --target-ms is the same target as a frame time
    if (a.target_ms != 0)
      throw tsp::UsageError("--target-fps and --target-ms set the same target: give one");
    if (!(a.target_fps >= 1 && a.target_fps <= kMaxTargetFps))
      throw tsp::UsageError("--target-fps " + std::to_string(a.target_fps) + ": expected 1 to " +
                            std::to_string(int(kMaxTargetFps)) + " frames per second");
    o.target_ms = 1000.0 / a.target_fps;
  } else {
    o.target_ms = a.target_ms;
  }
  o.orbit_deg = a.orbit;
  if (a.split_limit < 1) throw tsp::UsageError("--split-limit " + std::to_string(a.split_limit) +
                                               ": expected at least 1 split per frame");
  o.lod_options.split_limit = a.split_limit;
  o.lod_options.fallback = tsp::parse_lod_fallback(a.lod_fallback, "--lod-fallback");
  if (!a.focus.empty()) o.lod_options.focus = parse_triple(a.focus, "--focus", "X,Y,Z in voxels");
  o.lod_filter = tsp::parse_lod_filter(a.lod_filter, "--lod-filter");
  if (o.lod_filter.kind != tsp::LodFilter::error) {  // LaMar's filters choose the cut themselves
    if (!a.lod.empty() || a.target_ms != 0 || a.target_fps != 0)
      throw tsp::UsageError("--lod-filter " + a.lod_filter +
                            " chooses the cut from where the tiles lie: drop --lod, --target-ms "
                            "and --target-fps (--lod-filter error is the error-driven cut)");
    o.lod = tspgl::LodMode::filter;
  }
}

// The RAM and texture budgets, and the movie (checked before rendering: a bad movie request
// wastes no frames).
void set_budgets_and_movie(const RenderArgs& a, tspgl::RenderJobOptions& o) {
  if (!(a.texture_budget_mb > 0) || !(a.texture_budget_mb <= double(tspgl::kMaxBudgetBytes >> 20)))
    throw tsp::UsageError("--texture-budget " + std::to_string(a.texture_budget_mb) +
                          ": expected a budget in (0, " +
                          std::to_string(tspgl::kMaxBudgetBytes >> 20) + "] MiB");
  o.texture_budget = std::max<std::int64_t>(1, std::int64_t(a.texture_budget_mb * (1 << 20)));
  if (!(a.ram_budget_mb > 0) || !(a.ram_budget_mb <= double(tspgl::kMaxBudgetBytes >> 20)))
    throw tsp::UsageError("--ram-budget " + std::to_string(a.ram_budget_mb) +
                          ": expected a budget in (0, " +
                          std::to_string(tspgl::kMaxBudgetBytes >> 20) + "] MiB");
  o.ram_budget = std::max<std::int64_t>(1, std::int64_t(a.ram_budget_mb * (1 << 20)));
  if (!a.movie.empty()) {
    tspgl::check_movie_name(a.movie, "--movie");
    if (a.fps < 1 || a.fps > 120)
      throw tsp::UsageError("--fps " + std::to_string(a.fps) + ": expected 1..120");
    if (!tspgl::find_on_path("ffmpeg"))
      throw tsp::IoError("--movie " + a.movie +
                         ": ffmpeg is not on PATH (apt-get install ffmpeg; scripts/install-deps.sh "
                         "installs it)");
    o.movie = a.movie;
    o.fps = a.fps;
  }
}

}  // namespace

tspgl::RenderJobOptions render_job_options(const RenderArgs& a, const tspgl::RenderSettings& settings,
                                           const std::vector<std::string>& given_settings) {
  check_on_off(a.annotate, "--annotate");
  check_on_off(a.cache, "--cache");
  check_on_off(a.baseline, "--baseline");
  check_on_off(a.perspective, "--perspective");
  check_on_off(a.probe_surface, "--probe-surface");
  tspgl::RenderJobOptions o;
  o.tsp_path = a.file;
  o.field = a.field;
  o.tf = a.tf;
  o.tf_range = tsp::parse_tf_range(a.tf_range);
  o.annotate = a.annotate == "on";
  o.out_dir = a.out;
  const StepRange steps = parse_steps(a.steps);
  o.first_step = steps.first;
  o.last_step = steps.last;
  o.step_stride = steps.stride;
  o.settings = settings;
  o.metric = tsp::parse_metric(a.metric);
  o.cache = a.cache == "off" ? tsp::CachePolicy::off : tsp::CachePolicy::on;
  o.baseline = a.baseline == "on";
  std::tie(o.camera.width, o.camera.height) = parse_size(a.size);
  auto view = tsp::parse_view_angles(a.view);
  o.camera.azimuth_deg = view[0];
  o.camera.elevation_deg = view[1];
  o.camera.projection =
      a.perspective == "on" ? tsp::Projection::perspective : tsp::Projection::orthographic;
  o.passes = a.passes;
  o.gl = tspgl::parse_headless_gl(a.gl, "--gl");
  o.gpu = a.gpu;
  if (a.quality != 0)
    for (const std::string& given : given_settings)
      for (const char* knob : kQualityKnobs)
        if (given == knob)
          throw tsp::UsageError("--quality picks compositing, spacing, tolerances and "
                                "pre-integration itself: drop " + given);
  if (a.quality != 0 && o.baseline)
    throw tsp::UsageError("--quality is for the TSP renderer: drop --baseline");
  o.quality = a.quality;
  o.calibration_dir = a.calibration_dir;
  o.save_tf = a.save_tf;
  set_lod_options(a, o);
  if (!a.eye.empty()) {  // a placed eye looks along the view's direction, in perspective
    const auto e = parse_triple(a.eye, "--eye", "X,Y,Z in voxels");
    o.camera.eye = std::array<double, 3>{e[0], e[1], e[2]};
    o.camera.projection = tsp::Projection::perspective;
  }
  if (a.proportions != "physical" && a.proportions != "samples")
    throw tsp::UsageError("--proportions '" + a.proportions + "': expected physical or samples");
  o.physical_proportions = a.proportions == "physical";
  for (const std::string& p : a.probes) o.probes.push_back(tsp::parse_probe(p));
  o.probe_op = tsp::parse_probe_op(a.probe_op);
  o.probe_surface = a.probe_surface == "on";
  o.probe_tf = a.probe_tf;
  o.surface_mesh = a.surface_mesh;
  o.surface_field = a.surface_field;
  o.surface_tf = a.surface_tf;
  o.surface_target_ms = a.surface_target_ms;
  if (!a.probe_motion.empty())
    o.probe_motion = parse_triple(a.probe_motion, "--probe-motion", "DX,DY,DZ per frame");
  if (!a.scale.empty())
    o.scale = parse_triple(a.scale, "--scale", "SX,SY,SZ, factors on the voxel spacing");
  set_budgets_and_movie(a, o);
  return o;
}

}  // namespace tspcli
