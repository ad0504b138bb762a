// Space pauses on the step on screen (docs/player.md "Controls"): a press that comes while a
// frame draws the next step would pause on that step, shown after the press (a step late).
// Before a playing frame draws a new step the picture on screen is held (a copy of the 16-bit
// render target); once the frame is drawn, before it is shown, the window's events are read, and
// when a Space press for the player came meanwhile the held picture is put back and the frame
// shows the held step again. The press then pauses there, and the refinement's bands are drawn
// over that picture: no step back, no coarser picture after the pause.
// Our loader (gl/gl_api.h) declares the GL functions; GLFW must not pull in GL/gl.h.
#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>
#include <imgui.h>

#include <string>

#include "player/player_app.h"

namespace tspplayer {

void PlayerApp::hold_shown() {
  held_.step = -1;  // (held for this frame only)
  if (!state_.playing || drawn_step_ < 0 || state_.step == drawn_step_ || !viewer_->has_renderer()) return;
  viewer_->renderer().compositor()->target().hold();
  held_ = {drawn_step_, &viewer_->renderer(), layout.view, last, lod_loop_.stats(), within_,
           picture_fragments_};
}

bool PlayerApp::drop_for_space() {
  if (held_.step < 0 || !state_.playing || state_.step == held_.step) return false;
  ctx->poll_events();  // (what came while the frame was drawn; queued for the next frame)
  if (ImGui::GetIO().WantCaptureKeyboard || !input_queue_.player_key_waiting(GLFW_KEY_SPACE))
    return false;
  if (&viewer_->renderer() != held_.renderer || !(layout.view == held_.view)) return false;
  tspgl::RenderTarget& target = viewer_->renderer().compositor()->target();
  if (!target.restore_held()) return false;
  const WindowRect& v = layout.view;
  target.resolve(v.x, ctx->height() - v.y - v.h, v.w, v.h);
  trace("frame of step " + std::to_string(state_.step) +
        " dropped: Space went down while it was drawn; step " + std::to_string(held_.step) +
        " stays");
  state_.step = held_.step;
  last = held_.report;
  lod_loop_.drawn(held_.lod);
  within_ = held_.within;
  picture_fragments_ = held_.fragments;
  lod_loop_.take_back_step(held_.step);
  held_.step = -1;
  return true;
}

}  // namespace tspplayer
