#include "render/tile_refinement.h"

#include <algorithm>
#include <cmath>

namespace tspgl {

namespace {
// The time per pixel follows the frames with this weight for the newest.
constexpr double kRateSmoothing = 0.5;
}  // namespace

void TileRefinement::start(int width, int height) {
  width_ = std::max(1, width);
  height_ = std::max(1, height);
  const int n = (height_ + kRefineBand - 1) / kRefineBand;
  order_.clear();
  // The middle band, then alternately the one above and the one below.
  const int mid = n / 2;
  order_.push_back(mid);
  for (int d = 1; int(order_.size()) < n; ++d) {
    if (mid + d < n) order_.push_back(mid + d);
    if (mid - d >= 0) order_.push_back(mid - d);
  }
  next_ = 0;
  handed_ = 0;
}

void TileRefinement::stop() {
  order_.clear();
  next_ = 0;
  handed_ = 0;
}

std::vector<PixelRect> TileRefinement::next(double target_ms) {
  handed_ = 0;
  if (!active()) return {};
  const std::int64_t total = std::int64_t(width_) * height_;
  const double budget = ms_per_pixel_ > 0 ? std::max(0.0, target_ms) / ms_per_pixel_
                                          : kRefineFirstShare * double(total);
  std::vector<int> bands;
  do {
    const int b = order_[std::size_t(next_++)];
    bands.push_back(b);
    const int rows = std::min(kRefineBand, height_ - b * kRefineBand);
    handed_ += std::int64_t(rows) * width_;
  } while (active() && double(handed_) < budget);
  // Adjacent bands as one rectangle each run.
  std::sort(bands.begin(), bands.end());
  std::vector<PixelRect> rects;
  for (int b : bands) {
    const int y0 = b * kRefineBand, y1 = std::min(height_, y0 + kRefineBand);
    if (!rects.empty() && rects.back().y1 == y0)
      rects.back().y1 = y1;
    else
      rects.push_back({0, y0, width_, y1});
  }
  return rects;
}

void TileRefinement::drawn(double ms) {
  if (handed_ <= 0 || !(ms > 0)) return;
  const double rate = ms / double(handed_);
  ms_per_pixel_ = ms_per_pixel_ > 0 ? ms_per_pixel_ + kRateSmoothing * (rate - ms_per_pixel_) : rate;
}

}  // namespace tspgl
