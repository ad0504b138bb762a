// The script's handshakes with a test that drives the window from outside (xdotool):
// `wait-file PATH` holds the script until the test has made PATH — after its input — and the
// window has taken and settled every event sent before it; `signal PATH` tells the test that
// the script got there (docs/player.md "Scripts"). Tests wait on these, never on the clock.
// Our loader (gl/gl_api.h) declares the GL functions; GLFW must not pull in GL/gl.h.
#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>

#include <filesystem>
#include <system_error>

#include "player/player_app.h"
#include "tsp/core/error.h"
#include "tsp/core/number_text.h"
#include "tsp/core/temp_output.h"

namespace tspplayer {

namespace {
std::string script_line(const std::string& script, int line) {
  return line > 0 ? script + ":" + std::to_string(line) + ": " : "";
}
}  // namespace

void PlayerApp::start_wait_file(const cmd::WaitFile& c, int line) {
  wait_file_ = c;
  wait_file_until_s_ = clock_.seconds() + c.timeout_s;
  wait_file_line_ = line;
  wait_file_seen_ = false;
}

void PlayerApp::write_signal(const cmd::Signal& c, int line) {
  try {
    tsp::write_file_atomically(c.path, "frame " + std::to_string(frames_drawn_) + "\n");
  } catch (const tsp::Error& e) {
    throw tsp::IoError(script_line(options_.script, line) + "signal " + c.path + ": " + e.what());
  }
  trace("signal " + c.path);
}

bool PlayerApp::file_not_there_yet() const {
  std::error_code ec;
  return !wait_file_.path.empty() && !wait_file_seen_ &&
         !std::filesystem::exists(wait_file_.path, ec) &&
         clock_.seconds() <= wait_file_until_s_;
}

bool PlayerApp::waiting_for_file() {
  if (wait_file_.path.empty()) return false;
  if (!wait_file_seen_) {
    std::error_code ec;
    if (!std::filesystem::exists(wait_file_.path, ec)) {
      if (clock_.seconds() <= wait_file_until_s_) return true;
      throw tsp::IoError(script_line(options_.script, wait_file_line_) + "wait-file " +
                         wait_file_.path + ": not there after " +
                         tsp::number_text(wait_file_.timeout_s) + " s");
    }
    // The test made the file after its input. Asking the X server where the pointer is waits
    // for its answer, which comes after every event it sent this window before; GLFW queues
    // them meanwhile, and polling hands them to the callbacks (the input queue).
    double x = 0, y = 0;
    glfwGetCursorPos(static_cast<GLFWwindow*>(ctx->native_window()), &x, &y);
    ctx->poll_events();
    wait_file_seen_ = true;
    trace("wait-file " + wait_file_.path + " seen");
    return true;
  }
  // Every event taken by Dear ImGui and settled (kSettleFrames frames after the last).
  if (input_queue_.pending() || settle_frames_ > 0 || events_ != events_seen_) return true;
  wait_file_ = {};
  wait_file_seen_ = false;
  return false;
}

}  // namespace tspplayer
