#include "player/recorder.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace tspplayer {

std::int64_t frames_due(double start_s, double now_s, int fps) {
  const double elapsed = std::max(0.0, now_s - start_s);
  return std::int64_t(std::floor(elapsed * fps)) + 1;
}

Recorder::Recorder(const std::filesystem::path& path, int width, int height, int fps,
                   double start_s)
    : movie_(path, width, height, fps), fps_(fps), start_s_(start_s) {}

void Recorder::pad_to(const tsp::Image& image, std::int64_t total) {
  const std::int64_t cap = std::int64_t(kMaxRepeatSeconds * fps_);
  const int repeat = int(std::clamp<std::int64_t>(total - movie_.frames(), 0, cap));
  if (repeat > 0) movie_.write(image, repeat);
}

void Recorder::frame(const tsp::Image& image, double now_s) {
  const std::int64_t before = movie_.frames();
  pad_to(image, frames_due(start_s_, now_s, fps_));
  shown_ += movie_.frames() - before;
  last_ = image;
}

void Recorder::hold(double now_s) {
  if (!last_) return;
  const std::int64_t before = movie_.frames();
  pad_to(*last_, frames_due(start_s_, now_s, fps_));
  held_ += movie_.frames() - before;
}

std::string Recorder::finish(double now_s) {
  // The last frame stays on screen until the stop, so it lasts until then in the movie too: the
  // movie holds round(elapsed × fps) frames, as long as the recording.
  if (last_)
    pad_to(*last_, std::max<std::int64_t>(1, std::llround(std::max(0.0, now_s - start_s_) * fps_)));
  movie_.finish();
  char line[512];
  std::snprintf(line, sizeof line, "recorded %s (%lld frames, %.1f s)", path().c_str(),
                static_cast<long long>(movie_.frames()), seconds());
  return line;
}

}  // namespace tspplayer
