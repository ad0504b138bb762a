#include "player/layout.h"

#include <algorithm>
#include <cmath>

namespace tspplayer {

namespace {
// Share of the log opacity axis at its bottom that means "transparent".
constexpr double kLogZeroBand = 0.01;
}  // namespace

Layout compute_layout(int width, int height, bool panels, int menu_height) {
  Layout l;
  width = std::max(1, width);
  height = std::max(1, height);
  if (!panels || width < kDockMinWidth || height < kDockMinHeight) {
    l.view = {0, 0, width, height};
    return l;
  }
  l.docked = true;
  const int top = std::clamp(menu_height, 0, height / 4);
  const int left_w = width - kSidePanelWidth;
  l.side = {left_w, top, kSidePanelWidth, height - top};
  l.timeline = {0, height - kTimelineHeight, left_w, kTimelineHeight};
  l.view = {0, top, left_w, std::max(1, height - top - kTimelineHeight)};
  return l;
}

double opacity_to_axis(double a, bool log_scale) {
  a = std::clamp(a, 0.0, 1.0);
  if (!log_scale) return a;
  if (a < kLogOpacityFloor) return 0;
  const double span = -std::log10(kLogOpacityFloor);
  return kLogZeroBand + (1 - kLogZeroBand) * (std::log10(a) + span) / span;
}

double axis_to_opacity(double u, bool log_scale) {
  u = std::clamp(u, 0.0, 1.0);
  if (!log_scale) return u;
  if (u < kLogZeroBand) return 0;
  const double span = -std::log10(kLogOpacityFloor);
  return std::pow(10.0, (u - kLogZeroBand) / (1 - kLogZeroBand) * span - span);
}

}  // namespace tspplayer
