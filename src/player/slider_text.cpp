#include "player/slider_text.h"

#include <algorithm>

namespace tspplayer {

namespace {
constexpr float kGrabPadding = 2;  // ImGui 1.86's grab_padding in SliderBehaviorT
constexpr float kTextGap = 4;      // between the text and the grab or the frame's edge
}  // namespace

GrabSpan slider_grab(float x0, float x1, double t, float grab) {
  const float usable = std::max(0.f, x1 - x0 - 2 * kGrabPadding);
  grab = std::min(grab, usable);
  const float centre = x0 + kGrabPadding + grab * 0.5f +
                       float(std::clamp(t, 0.0, 1.0)) * (usable - grab);
  return {centre - grab * 0.5f, centre + grab * 0.5f};
}

float int_slider_grab_width(float x0, float x1, int lo, int hi, float grab_min) {
  const float usable = std::max(0.f, x1 - x0 - 2 * kGrabPadding);
  return std::max(usable / float(std::max(1, hi - lo + 1)), grab_min);
}

float text_beside_grab(float x0, float x1, GrabSpan grab, float text_w) {
  const float left = grab.lo - x0, right = x1 - grab.hi;
  if (left >= right) {  // left of the grab
    const float room = left - 2 * kTextGap;
    return room >= text_w ? x0 + kTextGap + (room - text_w) * 0.5f : x0 + kTextGap;
  }
  const float room = right - 2 * kTextGap;
  return room >= text_w ? grab.hi + kTextGap + (room - text_w) * 0.5f : grab.hi + kTextGap;
}

bool room_beside_grab(float x0, float x1, GrabSpan grab, float text_w) {
  return std::max(grab.lo - x0, x1 - grab.hi) - 2 * kTextGap >= text_w / 3;
}

}  // namespace tspplayer
