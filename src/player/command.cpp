#include "player/command.h"

// GLFW's key codes only (no window, no GL).
#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>

#include <algorithm>
#include <cmath>

#include "jobs/render_job.h"
#include "player/player_state.h"
#include "render/settings_table.h"
#include "tsp/core/error.h"
#include "tsp/lod/selection_filter.h"
#include "tsp/metric/tf_io.h"

namespace tspplayer {

namespace {

// Quality limit, as `tspplay render --quality` accepts it.
constexpr double kMaxQuality = 50;

[[noreturn]] void fail(const std::string& what) { throw tsp::UsageError(what); }

// One check per command that has values to check; the rest need none.
struct Checker {
  void operator()(const cmd::SetSpeed& c) const {
    if (!(c.steps_per_s >= kMinSpeed && c.steps_per_s <= kMaxSpeed))
      fail("speed must be positive: " + std::to_string(kMinSpeed).substr(0, 4) + " to " +
           std::to_string(int(kMaxSpeed)) + " steps per second");
  }
  void operator()(const cmd::StretchTf& c) const {
    using Mode = tsp::TfRangeChoice::Mode;
    // (Named as the window's control, not as play's --tf-range: the panel's field and the
    // script's tf-range both send this.)
    const std::string expected =
        "': expected LO:HI with LO < HI (finite), or data, bulk, step or view";
    tsp::TfRangeChoice r;
    try {
      r = tsp::parse_tf_range(c.range);
    } catch (const tsp::UsageError&) {
      fail("colour range '" + c.range + expected);
    }
    if (r.mode != Mode::data && r.mode != Mode::histogram && r.mode != Mode::step &&
        r.mode != Mode::visible && r.mode != Mode::explicit_range)
      fail("colour range '" + c.range + expected);
  }
  void operator()(const cmd::SetTolerance& c) const {
    if (!(c.spatial >= 0) || !(c.temporal >= 0) || !std::isfinite(c.spatial) ||
        !std::isfinite(c.temporal))
      fail("tolerances must be finite and not negative");
  }
  void operator()(const cmd::SetView& c) const {
    if (!std::isfinite(c.azimuth_deg)) fail("azimuth must be finite");
    if (!(c.elevation_deg > -90 && c.elevation_deg < 90))
      fail("elevation must be in (-90, 90) degrees");
  }
  void operator()(const cmd::SetQuality& c) const {
    if (!(c.mean_de >= 0) || c.mean_de > kMaxQuality)
      fail("quality must be a mean dE in [0, 50] (0: off)");
  }
  void operator()(const cmd::SetZoom& c) const {
    if (!(c.zoom > 0) || !std::isfinite(c.zoom)) fail("zoom must be positive and finite");
  }
  void operator()(const cmd::WaitFrames& c) const {
    if (c.frames < 0) fail("wait-frames must be 0 or more frames");
  }
  void operator()(const cmd::WaitSeconds& c) const {
    if (!(c.seconds >= 0) || c.seconds > kMaxWaitSeconds)
      fail("wait-seconds must be 0 to " + std::to_string(int(kMaxWaitSeconds)) + " seconds");
  }
  void operator()(const cmd::SetTargetFps& c) const {
    if (!(c.fps >= 1 && c.fps <= kMaxTargetFps))
      fail("target-fps must be 1 to " + std::to_string(int(kMaxTargetFps)) +
           " frames per second");
  }
  void operator()(const cmd::SetLodFilter& c) const {
    tsp::parse_lod_filter(c.filter, "lod-filter");  // (throws UsageError naming it)
  }
  void operator()(const cmd::SetScale& c) const {
    for (double k : c.factors)
      if (!(k > 0) || !(k <= tspgl::kMaxScale))
        fail("scale: expected three factors in (0, " + std::to_string(int(tspgl::kMaxScale)) + "]");
  }
  void operator()(const cmd::MoveProbe& c) const {
    if (c.number < 1) fail("probe-move: probes are numbered from 1");
    for (double d : c.by)
      if (!std::isfinite(d)) fail("probe-move: the displacement must be finite");
  }
  void operator()(const cmd::SetSetting& c) const {
    const tspgl::SettingSpec* spec = tspgl::find_setting(c.name);
    if (!spec) fail("no render setting '" + c.name + "'");
    tspgl::RenderSettings scratch;
    tspgl::set_setting(scratch, *spec, c.value, c.name);
  }
  void operator()(const cmd::GoToStep& c) const {
    if (c.step < 0) fail("step must be 0 or more");
  }
  void operator()(const cmd::ShowDialog& c) const {
    for (const char* w : {"open", "save-tf", "record", "save-session", "close"})
      if (c.which == w) return;
    fail("dialog '" + c.which + "': expected open, save-tf, record, save-session or close");
  }
  void operator()(const cmd::MoveTfPoint& c) const {
    tf_point_number(c.number);
    tf_point_value(c.value);
    tf_point_opacity(c.opacity);
  }
  void operator()(const cmd::ColourTfPoint& c) const {
    tf_point_number(c.number);
    for (float v : {c.colour.r, c.colour.g, c.colour.b, c.colour.a})
      if (!(v >= 0 && v <= 1)) fail("tf-point: colour components must be in [0, 1]");
  }
  void operator()(const cmd::AddTfPoint& c) const {
    tf_point_value(c.value);
    if (c.opacity) tf_point_opacity(*c.opacity);
  }
  void operator()(const cmd::RemoveTfPoint& c) const { tf_point_number(c.number); }
  void operator()(const cmd::WaitFile& c) const {
    if (c.path.empty()) fail("wait-file needs a path");
    if (!(c.timeout_s >= 0) || c.timeout_s > kMaxWaitSeconds)
      fail("wait-file's timeout must be 0 to " + std::to_string(int(kMaxWaitSeconds)) + " seconds");
  }
  template <class Other>
  void operator()(const Other&) const {}

 private:
  static void tf_point_number(int n) {
    if (n < 1) fail("tf-point: points are numbered from 1");
  }
  static void tf_point_value(double v) {
    if (!std::isfinite(v)) fail("tf-point: the value must be finite");
  }
  static void tf_point_opacity(double a) {
    if (!(a >= 0 && a <= 1)) fail("tf-point: opacity must be in [0, 1]");
  }
};

}  // namespace

bool waits_for_frames(const Command& c) {
  if (std::holds_alternative<cmd::Screenshot>(c) || std::holds_alternative<cmd::WaitFile>(c))
    return true;
  if (const auto* w = std::get_if<cmd::WaitFrames>(&c)) return w->frames > 0;
  if (const auto* w = std::get_if<cmd::WaitSeconds>(&c)) return w->seconds > 0;
  return false;
}

void validate(const Command& c) { std::visit(Checker{}, c); }

std::optional<Command> key_command(int key, const PlayerState& s, int steps) {
  const int last = std::max(0, steps - 1);
  switch (key) {
    case GLFW_KEY_SPACE:
      if (s.playing) return cmd::Pause{};
      return cmd::Play{};
    case GLFW_KEY_LEFT:
      return cmd::GoToStep{std::max(0, s.step - 1)};
    case GLFW_KEY_RIGHT:
      return cmd::GoToStep{std::min(last, s.step + 1)};
    case GLFW_KEY_HOME:
      return cmd::GoToStep{0};
    case GLFW_KEY_END:
      return cmd::GoToStep{last};
    case GLFW_KEY_S:
      return cmd::SavePicture{};
    case GLFW_KEY_L:
      return cmd::ShowCut{!s.show_cut};
    case GLFW_KEY_R:
      return cmd::ResetCamera{};
    case GLFW_KEY_TAB:
      return cmd::ShowPanels{!s.panels};
    case GLFW_KEY_P:
      return cmd::SetProjection{s.camera.projection == tsp::Projection::orthographic};
    default:
      return std::nullopt;
  }
}

}  // namespace tspplayer
