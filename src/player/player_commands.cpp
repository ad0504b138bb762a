// Carrying out the player's commands (command.h): one function per command, reached through
// apply() — what script lines, keys and panel widgets all send (docs/player.md).
#include <cmath>
#include <cstdio>
#include <filesystem>

#include "jobs/visible_range.h"
#include "player/player_app.h"
#include "player/player_ui.h"
#include "tsp/core/error.h"
#include "tsp/core/number_text.h"
#include "tsp/metric/tf_io.h"

namespace tspplayer {

// What each command does to the player (a friend of PlayerApp).
struct CommandApplier {
  PlayerApp& app;
  int line;  // the script line (0: a key or a panel)

  // "SCRIPT:LINE: " for a script line's errors, else "".
  std::string where() const {
    return line > 0 ? app.options_.script + ":" + std::to_string(line) + ": " : "";
  }
  PlayerState& state() const { return app.state_; }

  void operator()(const cmd::GoToStep& c) const {
    if (c.step >= app.steps())
      throw tsp::UsageError(where() + "step " + std::to_string(c.step) +
                            ": the file has steps 0.." + std::to_string(app.steps() - 1));
    app.go_to(c.step);
  }
  void operator()(const cmd::Play&) const {
    state().playing = true;
    // The tuning starts (a script's next action waits for it), its pictures from the frame after
    // this one on: the window shows Pause and a provisional frame first (the seventh walk saw
    // nothing for 2.7 s after Space while the first full-quality probe was drawn).
    app.begin_tuning();
  }
  void operator()(const cmd::Pause&) const { state().playing = false; }
  void operator()(const cmd::SetSpeed& c) const {
    state().speed = c.steps_per_s;
    app.speed_chosen_ = true;  // this series' (saved in its session); --speed is kept on open
  }
  void operator()(const cmd::SetLoop& c) const { state().loop = c.on; }
  void operator()(const cmd::LoadTf& c) const {
    const tsp::ValueHistogram histogram = tsp::histogram_of(app.viewer().file());
    const tsp::ValueRange over =
        c.over_present_range ? app.tf.domain() : app.viewer().file().tree().value_range();
    app.set_tf(tsp::transfer_function_from_arg(c.arg, over, app.tf.size(), {}, &histogram), true);
    app.tf_label = tf_label_of(c.arg);
    if (c.arg.rfind("preset:", 0) != 0) {  // a file: said, and whether it misses the data
      const std::string w =
          tsp::tf_range_warning(app.tf, app.viewer().file().metadata().data_range, "fit to data");
      app.status = "loaded " + c.arg + (w.empty() ? "" : "; " + w);
    }
  }
  void operator()(const cmd::StretchTf& c) const {  // the map as it is, over the chosen range
    const tsp::TfRangeChoice r = tsp::parse_tf_range(c.range);
    const tsp::TspFile& f = app.viewer().file();
    const tsp::ValueRange to =
        r.mode == tsp::TfRangeChoice::Mode::explicit_range ? r.range
        : r.mode == tsp::TfRangeChoice::Mode::visible
            ? tspgl::visible_value_range(
                  f.tree(), state().step, tsp::Camera(f.tree().octree().dims(), state().camera),
                  tsp::ClipRegion(state().probes, state().probe_op, f.metadata().origin,
                                  f.metadata().spacing))
            : tsp::tf_domain_of(r, f, state().step);
    const std::uint64_t before = app.tf.version();
    const tsp::ValueRange from = app.tf.domain();
    app.set_tf(tsp::rescaled(app.tf, to), false);
    // Every point kept, rescaled with the map (placed again from the table, a fit lost some).
    app.tf_handles_ = rescale_handles(app.tf_points_, from, app.tf);
    app.tf_points_ = app.tf_handles_.placed;
    // Six significant digits, a rounding speck (|v| below a millionth of the width) as 0: the
    // seventh walk read "[-0.000000, 299.999908]", wrapped inside a number.
    const double speck = 1e-6 * std::abs(to.hi - to.lo);
    auto text = [speck](double v) { return tsp::number_text(std::abs(v) <= speck ? 0.0 : v, "%.6g"); };
    const std::string range = "[" + text(to.lo) + ", " + text(to.hi) + "]";
    if (app.tf.version() == before) {  // a fit that moves nothing says so (it said nothing)
      app.status = "colour range already fits " + fit_name(r.mode) + " " + range +
                   ": nothing changed";
      app.trace(app.status);
      return;
    }
    app.status = "transfer function stretched over " + c.range + " " + range;
  }
  // What a fit fits, as the panel's buttons name it ("fit to bulk": "the bulk").
  static std::string fit_name(tsp::TfRangeChoice::Mode m) {
    using Mode = tsp::TfRangeChoice::Mode;
    return m == Mode::data        ? "the data"
           : m == Mode::histogram ? "the bulk"
           : m == Mode::step      ? "the step"
           : m == Mode::visible   ? "the view"
                                  : "the range";
  }
  void operator()(const cmd::SetTolerance& c) const {
    if (c.settled)
      app.set_tolerances({c.spatial, c.temporal});
    else  // a slider still dragging: frames follow; set_tolerances once it settles
      state().settings.tol = {c.spatial, c.temporal};
  }
  void operator()(const cmd::SetSetting& c) const { app.set_setting(c.name, c.value); }
  void operator()(const cmd::SetMetric& c) const { app.set_metric(c.metric); }
  void operator()(const cmd::SetCache& c) const {
    app.set_cache(c.on, c.budget_mb >= 0 ? c.budget_mb : state().texture_budget_mb);
  }
  void operator()(const cmd::SetPrefetch& c) const { state().prefetch_on = c.on; }
  void operator()(const cmd::SetView& c) const {
    state().camera.azimuth_deg = c.azimuth_deg;
    state().camera.elevation_deg = c.elevation_deg;
  }
  void operator()(const cmd::SetZoom& c) const { state().camera.zoom = c.zoom; }
  void operator()(const cmd::SetProjection& c) const {
    state().camera.projection =
        c.perspective ? tsp::Projection::perspective : tsp::Projection::orthographic;
  }
  void operator()(const cmd::Screenshot& c) const {
    app.pending_shot_ = c.path;
    app.pending_with_ui_ = c.with_ui;
  }
  void operator()(const cmd::WaitFrames& c) const { app.wait_frames_ = c.frames; }
  void operator()(const cmd::WaitSeconds& c) const {
    app.wait_until_s_ = app.clock_.seconds() + c.seconds;
  }
  void operator()(const cmd::SetQuality& c) const { app.apply_quality(c.mean_de); }
  void operator()(const cmd::WriteStats& c) const { app.write_stats(c.path); }
  void operator()(const cmd::SetLod& c) const { app.set_lod(c.on); }
  void operator()(const cmd::SetTargetFps& c) const { state().target_fps = float(c.fps); }
  void operator()(const cmd::SetLodFilter& c) const {
    state().lod_filter = tsp::parse_lod_filter(c.filter, "lod-filter");
  }
  void operator()(const cmd::ShowCut& c) const { state().show_cut = c.on; }
  void operator()(const cmd::ShowPanels& c) const { state().panels = c.on; }
  void operator()(const cmd::EveryStep& c) const { state().every_step = c.on; }
  void operator()(const cmd::LogOpacity& c) const { state().log_opacity = c.on; }
  void operator()(const cmd::OpenInput& c) const {
    app.open_input(c.path, c.field, c.build_options);
  }
  void operator()(const cmd::ShowField& c) const {
    try {
      app.switch_field(c.name);
    } catch (const tsp::UsageError& e) {  // a script line says where
      if (line <= 0) throw;
      throw tsp::UsageError(where() + e.what());
    }
  }
  void operator()(const cmd::AddProbe& c) const { app.add_probe(c.probe); }
  void operator()(const cmd::SetProbeOp& c) const {
    state().probe_op = c.op;
    app.probes_changed();
  }
  void operator()(const cmd::ProbeSurface& c) const {
    state().probe_surface = c.on;
    app.probes_changed();
  }
  void operator()(const cmd::ClearProbes&) const {
    state().probes.clear();
    app.probe_selected_ = -1;
    app.probes_changed();
  }
  void operator()(const cmd::MoveProbe& c) const {
    if (c.number < 1 || c.number > int(state().probes.size()))
      throw tsp::UsageError(where() + "probe " + std::to_string(c.number) + ": there are " +
                            std::to_string(state().probes.size()) + " probes");
    tsp::move_probe(state().probes[std::size_t(c.number - 1)], c.by);
    app.probes_changed();
  }
  void operator()(const cmd::StartRecording& c) const { app.start_recording(c.path); }
  void operator()(const cmd::StopRecording&) const { app.stop_recording(); }
  void operator()(const cmd::ResetCamera&) const {  // the view, in the window's size
    const int w = state().camera.width, h = state().camera.height;
    state().camera = app.initial_camera;
    state().camera.width = w;
    state().camera.height = h;
    app.trace("camera reset");
  }
  void operator()(const cmd::KeepQuality& c) const { state().keep_quality = c.on; }
  void operator()(const cmd::Capture& c) const {  // every frame from the next on, as drawn
    app.capture_dir_ = c.dir;
    app.capture_count_ = 0;
    if (!c.dir.empty()) {
      std::filesystem::create_directories(c.dir);
      std::filesystem::remove(std::filesystem::path(c.dir) / "frames.jsonl");
    }
  }
  void operator()(const cmd::Quit&) const { app.quit_ = true; }
  void operator()(const cmd::SaveSession& c) const { app.save_session_as(c.path); }
  void operator()(const cmd::SetScale& c) const { app.set_scale(c.factors); }
  void operator()(const cmd::ExpandSections& c) const { app.expand_sections = c.on ? 1 : -1; }
  void operator()(const cmd::SavePicture&) const { app.request_save(); }
  void operator()(const cmd::ShowAnnotations& c) const { state().annotations = c.on; }
  void operator()(const cmd::SplatFallback& c) const { state().splat_fallback = c.on; }
  void operator()(const cmd::EditProbe& c) const {
    if (c.index < 0 || c.index >= int(state().probes.size()))
      throw tsp::UsageError("probe " + std::to_string(c.index + 1) + ": there are " +
                            std::to_string(state().probes.size()) + " probes");
    state().probes[std::size_t(c.index)] = c.probe;
    app.probe_selected_ = c.index;
    app.probes_changed();
  }
  void operator()(const cmd::ShowDialog& c) const { show_dialog(c.which); }
  // The TF editor's points (tf_handles.h): point `number` (1-based) as an index, and a value
  // inside the map's range, or a UsageError saying what there is.
  std::size_t tf_point(int number, const char* action) const {
    const std::size_t n = app.tf_points_.size();
    if (number < 1 || std::size_t(number) > n)
      throw tsp::UsageError(where() + "tf-point " + action + " " + std::to_string(number) +
                            ": the map has points 1.." + std::to_string(n));
    return std::size_t(number - 1);
  }
  void tf_value(double v, const char* action) const {
    const tsp::ValueRange d = app.tf.domain();
    if (!(v >= d.lo && v <= d.hi))
      throw tsp::UsageError(where() + "tf-point " + action + ": value " + tsp::number_text(v) +
                            " is outside the map's range " + tsp::number_text(d.lo) + ":" +
                            tsp::number_text(d.hi));
  }
  void operator()(const cmd::MoveTfPoint& c) const {
    const std::size_t i = tf_point(c.number, "move");
    tf_value(c.value, "move");
    tsp::TfPoint& p = app.tf_points_[i];
    p.x = clamp_handle_x(app.tf_points_, int(i), c.value);  // (handles keep their order)
    p.c.a = float(c.opacity);
    app.apply_tf_points();  // lazy metric: only the touched nodes recompute next frame
  }
  void operator()(const cmd::ColourTfPoint& c) const {
    app.tf_points_[tf_point(c.number, "colour")].c = c.colour;
    app.apply_tf_points();
  }
  void operator()(const cmd::AddTfPoint& c) const {
    tf_value(c.value, "add");
    tsp::Rgba colour = sample_tf(app.tf, c.value);
    if (c.opacity) colour.a = float(*c.opacity);
    add_handle(app.tf_handles_, app.tf_points_, app.tf, c.value, colour);
    app.apply_tf_points();
  }
  void operator()(const cmd::RemoveTfPoint& c) const {  // straight between its neighbours
    const std::size_t i = tf_point(c.number, "remove");
    if (app.tf_points_.size() < 3)
      throw tsp::UsageError(where() + "tf-point remove: the map keeps at least 2 points");
    app.set_tf(remove_handle(app.tf_handles_, app.tf_points_, app.tf, int(i)), false);
    app.tf_label = "edited";
  }
  void operator()(const cmd::SelectProbe& c) const {
    if (c.index >= 0 && c.index < int(state().probes.size())) app.probe_selected_ = c.index;
  }
  void operator()(const cmd::ShowHelp& c) const { app.show_help_ = c.on; }
  void operator()(const cmd::WaitFile& c) const { app.start_wait_file(c, line); }
  void operator()(const cmd::Signal& c) const { app.write_signal(c, line); }
  void operator()(const cmd::RemoveProbe& c) const {
    if (c.index < 0 || c.index >= int(state().probes.size())) return;  // (already gone)
    state().probes.erase(state().probes.begin() + c.index);
    app.probe_selected_ = state().probes.empty() ? -1 : 0;
    app.probes_changed();
  }
};

void apply(PlayerApp& app, const Command& c, int line) {
  std::visit(CommandApplier{app, line}, c);
}

void PlayerApp::command(const Command& c) {
  const std::uint64_t errors_before = errors_;
  try {
    validate(c);
    apply(*this, c);
  } catch (const tsp::Error& e) {
    set_error(e.what());
    return;
  }
  cleared_by_action(c, errors_before);
}

void PlayerApp::set_error(const std::string& what) {
  status = error_status_ = what;
  ++errors_;
  std::fprintf(stderr, "tspplay: %s\n", what.c_str());
}

void PlayerApp::cleared_by_action(const Command& c, std::uint64_t errors_before) {
  if (error_status_.empty() || errors_ != errors_before) return;  // (this one failed: it stays)
  if (status != error_status_) {  // replaced by another message meanwhile
    error_status_.clear();
    return;
  }
  const bool passive = std::holds_alternative<cmd::WaitFrames>(c) ||
                       std::holds_alternative<cmd::WaitSeconds>(c) ||
                       std::holds_alternative<cmd::WriteStats>(c) ||
                       std::holds_alternative<cmd::Screenshot>(c) ||
                       std::holds_alternative<cmd::Capture>(c) ||
                       std::holds_alternative<cmd::Quit>(c) ||
                       std::holds_alternative<cmd::WaitFile>(c) ||
                       std::holds_alternative<cmd::Signal>(c);
  if (passive) return;
  status.clear();  // (a stale error stayed for the rest of the session)
  error_status_.clear();
  trace("error cleared: the next action succeeded");
}

void PlayerApp::apply_commands() {
  // (A command may push more: taken in turns until none is left.)
  while (!pending_commands_.empty()) {
    std::vector<Command> now;
    now.swap(pending_commands_);
    for (const Command& c : now) command(c);
  }
}

}  // namespace tspplayer
