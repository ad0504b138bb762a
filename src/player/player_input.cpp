// The player's input: keys (from GLFW's callback, in order), mouse over the volume, script
// actions, and --trace lines for what changed (docs/player.md).
// Our loader (gl/gl_api.h) declares the GL functions; GLFW must not pull in GL/gl.h.
#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>
#include <imgui.h>

#include <algorithm>
#include <filesystem>
#include <cmath>
#include <cstdio>

#include "jobs/visible_range.h"
#include "player/player_app.h"
#include "tsp/core/error.h"
#include "tsp/metric/tf_io.h"

namespace tspplayer {

namespace {
constexpr double kOrbitDegPerPixel = 0.4;
constexpr double kZoomPerWheelStep = 1.1;
constexpr double kMaxElevation = 89;
}  // namespace

void PlayerApp::handle_input() {
  const ImGuiIO& io = ImGui::GetIO();
  const bool gizmo = !io.WantCaptureMouse && state.camera.width > 0 && state.camera.height > 0 &&
                     probe_gizmo(tsp::Camera(file->tree().octree().dims(), state.camera));
  if (!io.WantCaptureMouse && !gizmo) {
    const bool pan = io.MouseDown[1] || io.MouseDown[2] || (io.MouseDown[0] && io.KeyShift);
    if (pan) {
      const double scale = 2.0 / (state.camera.zoom * std::max(1, std::min(state.camera.width, state.camera.height)));
      state.camera.pan[0] -= io.MouseDelta.x * scale;
      state.camera.pan[1] += io.MouseDelta.y * scale;
    } else if (io.MouseDown[0]) {
      state.camera.azimuth_deg -= io.MouseDelta.x * kOrbitDegPerPixel;
      state.camera.elevation_deg = std::clamp(state.camera.elevation_deg + io.MouseDelta.y * kOrbitDegPerPixel,
                                        -kMaxElevation, kMaxElevation);
    }
    if (io.MouseWheel != 0) state.camera.zoom *= std::pow(kZoomPerWheelStep, io.MouseWheel);
    if (io.MouseDoubleClicked[0])
      set_focus_at(io.MousePos.x - layout.view.x, io.MousePos.y - layout.view.y);
  }
  // Every press since the last frame, in order (a text field with the focus takes them all).
  std::vector<int> keys;
  keys.swap(key_queue_);
  if (io.WantCaptureKeyboard) return;
  for (int key : keys) {
    apply_key(key);
    if (options_.trace) trace_changes();
  }
}

bool PlayerApp::shortcut(int key, int mods) {
  if (!(mods & GLFW_MOD_CONTROL)) return false;
  if (key == GLFW_KEY_A) {  // (Dear ImGui selects, from the input queue)
    trace("select all (Ctrl+A)");
    return true;
  }
  if (key == GLFW_KEY_O) {
    open_requested = true;
    return true;
  }
  if (key == GLFW_KEY_Q) {  // as File > Quit
    glfwSetWindowShouldClose(static_cast<GLFWwindow*>(ctx->native_window()), 1);
    return true;
  }
  return false;
}

void PlayerApp::trace(const std::string& what) const {
  if (!options_.trace) return;
  std::printf("trace: %s\n", what.c_str());
  std::fflush(stdout);
}

void PlayerApp::trace_tf_canvas(float x, float y, float w, float h) {
  if (!options_.trace) return;
  const std::array<float, 4> r{x, y, w, h};
  if (r == traced_canvas_) return;
  traced_canvas_ = r;
  std::printf("trace: tf canvas %.0f %.0f %.0f %.0f\n", x, y, w, h);
  std::fflush(stdout);
}

void PlayerApp::command(const ScriptAction& a) {
  try {
    validate(a);
    apply(a);
  } catch (const tsp::Error& e) {
    status = e.what();
    std::fprintf(stderr, "tspplay: %s\n", e.what());
  }
}

void PlayerApp::apply_key(int key) {
  using Kind = ScriptAction::Kind;
  const int last = steps() - 1;
  switch (key) {
    case GLFW_KEY_SPACE:
      command(command_of(state.playing ? Kind::pause : Kind::play));
      break;
    case GLFW_KEY_LEFT:
      command(step_command(std::max(0, state.step - 1)));
      break;
    case GLFW_KEY_RIGHT:
      command(step_command(std::min(last, state.step + 1)));
      break;
    case GLFW_KEY_HOME:
      command(step_command(0));
      break;
    case GLFW_KEY_END:
      command(step_command(last));
      break;
    case GLFW_KEY_S:  // a view-only action: saves a file, changes nothing shown
      request_save();
      break;
    case GLFW_KEY_L:
      command(command_of(Kind::show_cut, !state.show_cut));
      break;
    case GLFW_KEY_R:
      command(command_of(Kind::reset_camera));
      break;
    case GLFW_KEY_F1:
    case GLFW_KEY_SLASH:  // '?' on most layouts: the help overlay (no player state)
      show_help = !show_help;
      break;
    case GLFW_KEY_TAB:
      command(command_of(Kind::panels, !state.panels));
      break;
    case GLFW_KEY_P:
      command(command_of(Kind::projection, state.camera.projection == tsp::Projection::orthographic));
      break;
    default:
      break;
  }
}

void PlayerApp::apply(const ScriptAction& a) {
  using Kind = ScriptAction::Kind;
  switch (a.kind) {
    case Kind::step:
      if (a.number >= steps())
        throw tsp::UsageError(options_.script + ":" + std::to_string(a.line) + ": step " +
                              std::to_string(a.number) + ": the file has steps 0.." +
                              std::to_string(steps() - 1));
      go_to(a.number);
      break;
    case Kind::play:
      state.playing = true;
      advance_tuning();  // tuned at once if it must be: a script's next action waits for it
      break;
    case Kind::pause:
      state.playing = false;
      break;
    case Kind::speed:
      state.speed = a.value;
      speed_chosen_ = true;  // kept when another file opens
      break;
    case Kind::loop:
      state.loop = a.flag;
      break;
    case Kind::tf: {
      const tsp::ValueHistogram histogram = tsp::histogram_of(*file);
      set_tf(tsp::transfer_function_from_arg(a.text, file->tree().value_range(), tf.size(), {},
                                             &histogram),
             true);
      tf_label = tf_label_of(a.text);
      break;
    }
    case Kind::tf_range: {  // the map as it is, stretched over the chosen range
      const tsp::TfRangeChoice c = tsp::parse_tf_range(a.text);
      const tsp::ValueRange to =
          c.mode == tsp::TfRangeChoice::Mode::explicit_range ? c.range
          : c.mode == tsp::TfRangeChoice::Mode::visible
              ? tspgl::visible_value_range(
                    file->tree(), state.step,
                    tsp::Camera(file->tree().octree().dims(), state.camera),
                    tsp::ClipRegion(state.probes, state.probe_op, file->metadata().origin,
                                    file->metadata().spacing))
              : tsp::tf_domain_of(c, *file, state.step);
      set_tf(tsp::rescaled(tf, to), true);
      status = "transfer function stretched over " + a.text + " [" + std::to_string(to.lo) +
               ", " + std::to_string(to.hi) + "]";
      break;
    }
    case Kind::tolerance:
      set_tolerances({a.value, a.value2});
      break;
    case Kind::metric:
      set_metric(tsp::parse_metric(a.text));
      break;
    case Kind::cache:
      set_cache(a.flag, state.texture_budget_mb);
      break;
    case Kind::prefetch:
      state.prefetch_on = a.flag;
      break;
    case Kind::view:
      state.camera.azimuth_deg = a.value;
      state.camera.elevation_deg = a.value2;
      break;
    case Kind::zoom:
      state.camera.zoom = a.value;
      break;
    case Kind::projection:
      state.camera.projection = a.flag ? tsp::Projection::perspective : tsp::Projection::orthographic;
      break;
    case Kind::screenshot:
    case Kind::screenshot_ui:
      pending_shot_ = a.text;
      pending_with_ui_ = a.kind == Kind::screenshot_ui;
      break;
    case Kind::wait_frames:
      wait_frames_ = a.number;
      break;
    case Kind::wait_seconds:
      wait_until_s_ = clock_.seconds() + a.value;
      break;
    case Kind::setting:
      set_setting(a.text, a.text2);
      break;
    case Kind::quality:
      apply_quality(a.value);
      break;
    case Kind::stats:
      write_stats(a.text);
      break;
    case Kind::lod:
      set_lod(a.flag);
      break;
    case Kind::lod_filter:
      state.lod_filter = tsp::parse_lod_filter(a.text, "lod-filter");
      break;
    case Kind::target_fps:
      state.target_fps = float(a.value);
      break;
    case Kind::show_cut:
      state.show_cut = a.flag;
      break;
    case Kind::panels:
      state.panels = a.flag;
      break;
    case Kind::every_step:
      state.every_step = a.flag;
      break;
    case Kind::log_opacity:
      state.log_opacity = a.flag;
      break;
    case Kind::open:
      open_input(a.text, a.text2, a.text3);
      break;
    case Kind::field:
      try {
        switch_field(a.text);
      } catch (const tsp::UsageError& e) {  // a script line says where
        if (a.line <= 0) throw;
        throw tsp::UsageError(options_.script + ":" + std::to_string(a.line) + ": " + e.what());
      }
      break;
    case Kind::probe:
      add_probe(tsp::parse_probe(a.text));
      break;
    case Kind::probe_op:
      state.probe_op = tsp::parse_probe_op(a.text);
      probes_changed();
      break;
    case Kind::probe_surface:
      state.probe_surface = a.flag;
      probes_changed();
      break;
    case Kind::probe_clear:
      state.probes.clear();
      probe_selected = -1;
      probes_changed();
      break;
    case Kind::probe_move:
      if (a.number < 1 || a.number > int(state.probes.size()))
        throw tsp::UsageError(options_.script + ":" + std::to_string(a.line) + ": probe " +
                              std::to_string(a.number) + ": there are " +
                              std::to_string(state.probes.size()) + " probes");
      tsp::move_probe(state.probes[std::size_t(a.number - 1)], {a.value, a.value2, a.value3});
      probes_changed();
      break;
    case Kind::record:
      start_recording(a.text);
      break;
    case Kind::record_stop:
      stop_recording();
      break;
    case Kind::playback:
      state.keep_quality = a.flag;
      break;
    case Kind::capture:  // every frame from the next on, as drawn (player_refine.cpp)
      capture_dir_ = a.text == "off" ? "" : a.text;
      capture_count_ = 0;
      if (!capture_dir_.empty()) {
        std::filesystem::create_directories(capture_dir_);
        std::filesystem::remove(std::filesystem::path(capture_dir_) / "frames.jsonl");
      }
      break;
    case Kind::reset_camera:
      state.camera = initial_camera;
      if (options_.trace) {
        std::printf("trace: camera reset\n");
        std::fflush(stdout);
      }
      break;
    case Kind::quit:
      quit_ = true;
      break;
    case Kind::save_session:
      save_session_as(a.text);
      break;
    case Kind::scale:
      set_scale({a.value, a.value2, a.value3});
      break;
    case Kind::expand:
      expand_sections = a.flag ? 1 : -1;
      break;
  }
}

// Runs actions until one needs frames to pass: a screenshot (saved after this frame's render),
// a wait of more than 0 frames or seconds, or quit.
void PlayerApp::run_script() {
  // An open waits for its build, a quality target for its playback tuning.
  if (!pending_shot_.empty() || open_job_ || tuner_) return;
  if (wait_frames_ > 0) {
    --wait_frames_;
    return;
  }
  if (clock_.seconds() < wait_until_s_) return;
  while (script_pos_ < script_.size() && !quit_) {
    const ScriptAction& a = script_[script_pos_++];
    apply(a);
    if (options_.trace) trace_changes();  // each action's effect on its own line
    if (waits_for_frames(a)) break;
    if (open_job_ || tuner_) break;  // the next actions wait for the build or the tuning
  }
}

void PlayerApp::trace_changes() {
  Traced& t = traced_;
  auto line = [](const std::string& s) {
    std::printf("trace: %s\n", s.c_str());
    std::fflush(stdout);
  };
  if (t.first || state.step != t.step) line("step " + std::to_string(state.step));
  if (!t.first && tf.version() != t.tf_version)
    line("transfer function edited (" + std::to_string(tf.size()) + " entries over [" +
         std::to_string(tf.domain().lo) + ", " + std::to_string(tf.domain().hi) + "])");
  const tsp::Tolerances& tol = state.settings.tol;
  if (!t.first && (tol.spatial != t.tol.spatial || tol.temporal != t.tol.temporal))
    line("tolerances spatial " + std::to_string(tol.spatial) + ", temporal " +
         std::to_string(tol.temporal));
  if (!t.first && state.metric != t.metric) line(std::string("metric ") + tsp::to_string(state.metric));
  if (t.first || state.playing != t.playing) line(state.playing ? "playing" : "paused");
  if (!t.first && state.lod_on != t.lod_on) line(std::string("lod ") + (state.lod_on ? "on" : "off"));
  if (!t.first && state.panels != t.panels) line(std::string("panels ") + (state.panels ? "on" : "off"));
  t = {state.step, tf.version(), state.settings.tol, state.metric, state.playing, state.lod_on, state.panels, false};
}

// The back end polled the pointer (the position now, after every queued event); the queue's
// state replaces it with where the events it took left it, and its buttons, keys and text.
void PlayerApp::feed_imgui(const InputFrame& in) {
  ImGuiIO& io = ImGui::GetIO();
  io.MousePos = ImVec2(in.x, in.y);
  for (int b = 0; b < InputFrame::kButtons; ++b) io.MouseDown[b] = in.buttons[std::size_t(b)];
  for (int k = 0; k < InputFrame::kKeys; ++k) io.KeysDown[k] = in.keys[std::size_t(k)];
  auto held = [&in](int a, int b) { return in.keys[std::size_t(a)] || in.keys[std::size_t(b)]; };
  io.KeyCtrl = held(GLFW_KEY_LEFT_CONTROL, GLFW_KEY_RIGHT_CONTROL);
  io.KeyShift = held(GLFW_KEY_LEFT_SHIFT, GLFW_KEY_RIGHT_SHIFT);
  io.KeyAlt = held(GLFW_KEY_LEFT_ALT, GLFW_KEY_RIGHT_ALT);
  io.KeySuper = held(GLFW_KEY_LEFT_SUPER, GLFW_KEY_RIGHT_SUPER);
  io.MouseWheelH += in.wheel_x;
  io.MouseWheel += in.wheel_y;
  for (unsigned c : in.text) io.AddInputCharacter(c);
}

}  // namespace tspplayer
