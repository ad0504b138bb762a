// The player's input: keys (from GLFW's callback, in order), mouse over the volume, script
// actions, and --trace lines for what changed (docs/player.md).
// Our loader (gl/gl_api.h) declares the GL functions; GLFW must not pull in GL/gl.h.
#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>
#include <imgui.h>

#include <algorithm>
#include <cfloat>
#include <cmath>
#include <cstdio>

#include "player/player_app.h"
#include "tsp/core/error.h"

namespace tspplayer {

namespace {
constexpr double kOrbitDegPerPixel = 0.4;
constexpr double kZoomPerWheelStep = 1.1;
constexpr double kMaxElevation = 89;
}  // namespace

// The window's callbacks: each counts an event and queues it (input_queue_: Dear ImGui's share,
// handed over by frame()); a key's press or repeat is marked for the player's own keys unless a
// shortcut takes it, so the player sees it in the frame Dear ImGui does (a key typed into a text
// field is never also a player key, however slow the frames).
void PlayerApp::install_callbacks() {
  GLFWwindow* window = static_cast<GLFWwindow*>(ctx->native_window());
  glfwSetWindowUserPointer(window, this);
  // Every callback counts an event: an idle window draws again only after one (run()).
  glfwSetKeyCallback(window, [](GLFWwindow* w, int key, int, int action, int mods) {
    auto* app = static_cast<PlayerApp*>(glfwGetWindowUserPointer(w));
    ++app->events_;
    // Ctrl+A, Ctrl+O and Ctrl+Q are shortcuts, not the player's keys; Dear ImGui sees every
    // key through the input queue (a Ctrl+A shorter than a frame still selects).
    const bool down = action == GLFW_PRESS || action == GLFW_REPEAT;
    const bool to_player = down && !app->shortcut(key, mods);
    // (A repeat changes no key's state: a held key repeats in Dear ImGui by itself.)
    app->input_queue_.push({InputEvent::Kind::key, 0, 0, key, down, to_player});
  });
  // The cursor as motion events report it, in order (glfwGetCursorPos asks X for the pointer
  // now, after every queued event): so a press knows where it happened.
  glfwSetCursorPosCallback(window, [](GLFWwindow* w, double x, double y) {
    auto* app = static_cast<PlayerApp*>(glfwGetWindowUserPointer(w));
    ++app->events_;
    app->cursor_ = {float(x), float(y)};
    app->input_queue_.push({InputEvent::Kind::cursor, float(x), float(y)});
  });
  glfwSetMouseButtonCallback(window, [](GLFWwindow* w, int button, int action, int) {
    auto* app = static_cast<PlayerApp*>(glfwGetWindowUserPointer(w));
    ++app->events_;
    app->input_queue_.push({InputEvent::Kind::button, 0, 0, button, action == GLFW_PRESS});
    if (button != GLFW_MOUSE_BUTTON_LEFT || action != GLFW_PRESS) return;
    app->left_press_ = app->cursor_;
  });
  glfwSetScrollCallback(window, [](GLFWwindow* w, double dx, double dy) {
    auto* app = static_cast<PlayerApp*>(glfwGetWindowUserPointer(w));
    ++app->events_;
    app->input_queue_.push({InputEvent::Kind::scroll, float(dx), float(dy)});
  });
  glfwSetCharCallback(window, [](GLFWwindow* w, unsigned c) {
    auto* app = static_cast<PlayerApp*>(glfwGetWindowUserPointer(w));
    ++app->events_;
    app->input_queue_.push({InputEvent::Kind::text, 0, 0, int(c)});
  });
  glfwSetCursorEnterCallback(window, [](GLFWwindow* w, int entered) {
    auto* app = static_cast<PlayerApp*>(glfwGetWindowUserPointer(w));
    ++app->events_;
    if (!entered) app->input_queue_.push({InputEvent::Kind::cursor, -FLT_MAX, -FLT_MAX});
  });
  glfwSetWindowFocusCallback(window, [](GLFWwindow* w, int focused) {
    ++static_cast<PlayerApp*>(glfwGetWindowUserPointer(w))->events_;
    ImGui::GetIO().AddFocusEvent(focused != 0);
  });
  glfwSetFramebufferSizeCallback(window, [](GLFWwindow* w, int, int) {
    ++static_cast<PlayerApp*>(glfwGetWindowUserPointer(w))->events_;
  });
  glfwSetWindowRefreshCallback(window, [](GLFWwindow* w) {  // uncovered: draw it again
    ++static_cast<PlayerApp*>(glfwGetWindowUserPointer(w))->events_;
  });
}

void PlayerApp::handle_input() {
  const ImGuiIO& io = ImGui::GetIO();
  const bool gizmo = !io.WantCaptureMouse && state_.camera.width > 0 && state_.camera.height > 0 &&
                     probe_gizmo(tsp::Camera(viewer_->file().tree().octree().dims(), state_.camera));
  // The frame a button goes down carries the cursor's way to the press (from the timeline, say,
  // in one motion with the press): a drag moves the view from the press on, not by that jump.
  const bool pressed_now = io.MouseClicked[0] || io.MouseClicked[1] || io.MouseClicked[2];
  if (!io.WantCaptureMouse && !gizmo) {
    const bool pan = io.MouseDown[1] || io.MouseDown[2] || (io.MouseDown[0] && io.KeyShift);
    if (pan && !pressed_now) {
      const double scale = 2.0 / (state_.camera.zoom * std::max(1, std::min(state_.camera.width, state_.camera.height)));
      state_.camera.pan[0] -= io.MouseDelta.x * scale;
      state_.camera.pan[1] += io.MouseDelta.y * scale;
    } else if (io.MouseDown[0] && !pan && !pressed_now) {
      state_.camera.azimuth_deg -= io.MouseDelta.x * kOrbitDegPerPixel;
      state_.camera.elevation_deg = std::clamp(state_.camera.elevation_deg + io.MouseDelta.y * kOrbitDegPerPixel,
                                        -kMaxElevation, kMaxElevation);
    }
    if (io.MouseWheel != 0) state_.camera.zoom *= std::pow(kZoomPerWheelStep, io.MouseWheel);
    if (io.MouseDoubleClicked[0])
      set_focus_at(io.MousePos.x - layout.view.x, io.MousePos.y - layout.view.y);
  }
  // The presses this frame handed Dear ImGui, in order (a text field with the focus takes them).
  if (io.WantCaptureKeyboard) return;
  for (int key : input_queue_.state().pressed) {
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
  if (key == GLFW_KEY_O) {  // as File > Open...
    push(cmd::ShowDialog{"open"});
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

void PlayerApp::apply_key(int key) {
  if (key == GLFW_KEY_F1 || key == GLFW_KEY_SLASH) {  // '?' on most layouts: the help overlay
    show_help_ = !show_help_;  // (no player state)
    return;
  }
  if (std::optional<Command> c = key_command(key, state_, steps())) command(*c);
}

// Runs actions until one needs frames to pass: a screenshot (saved after this frame's render),
// a wait of more than 0 frames or seconds, or quit.
void PlayerApp::run_script() {
  // An open waits for its build, a quality target for its playback tuning.
  if (!pending_shot_.empty() || open_job_ || tuning_.tuner()) return;
  if (wait_frames_ > 0) {
    --wait_frames_;
    return;
  }
  if (clock_.seconds() < wait_until_s_) return;
  if (waiting_for_file()) return;  // wait-file: the test's file and the input sent before it
  while (script_pos_ < script_.size() && !quit_) {
    const ScriptLine& a = script_[script_pos_++];
    const std::uint64_t errors_before = errors_;
    apply(*this, a.command, a.line);
    cleared_by_action(a.command, errors_before);
    if (options_.trace) trace_changes();  // each action's effect on its own line
    if (waits_for_frames(a.command)) break;
    if (open_job_ || tuning_.tuner()) break;  // the next actions wait for the build or the tuning
  }
}

void PlayerApp::trace_changes() {
  Traced& t = traced_;
  auto line = [](const std::string& s) {
    std::printf("trace: %s\n", s.c_str());
    std::fflush(stdout);
  };
  if (t.first || state_.step != t.step) line("step " + std::to_string(state_.step));
  if (!t.first && tf.version() != t.tf_version)
    line("transfer function edited (" + std::to_string(tf.size()) + " entries over [" +
         std::to_string(tf.domain().lo) + ", " + std::to_string(tf.domain().hi) + "])");
  const tsp::Tolerances& tol = state_.settings.tol;
  if (!t.first && (tol.spatial != t.tol.spatial || tol.temporal != t.tol.temporal))
    line("tolerances spatial " + std::to_string(tol.spatial) + ", temporal " +
         std::to_string(tol.temporal));
  if (!t.first && state_.metric != t.metric) line(std::string("metric ") + tsp::to_string(state_.metric));
  if (t.first || state_.playing != t.playing) line(state_.playing ? "playing" : "paused");
  if (!t.first && state_.lod_on != t.lod_on) line(std::string("lod ") + (state_.lod_on ? "on" : "off"));
  if (!t.first && state_.panels != t.panels) line(std::string("panels ") + (state_.panels ? "on" : "off"));
  t = {state_.step, tf.version(), state_.settings.tol, state_.metric, state_.playing, state_.lod_on, state_.panels, false};
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
