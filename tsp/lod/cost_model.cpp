#include "tsp/lod/cost_model.h"

#include <algorithm>
#include <cmath>

namespace tsp {

namespace {
// The slope is identified once the costs seen spread by this share of their mean (std/mean).
constexpr double kMinRelativeSpread = 0.1;
// Before that: this share of the first frame is taken as fixed cost.
constexpr double kPriorFixedShare = 0.5;
}  // namespace

void CostModel::Sums::add(double lambda, double cx, double cy) {
  w = w * lambda + 1;
  x = x * lambda + cx;
  y = y * lambda + cy;
  xx = xx * lambda + cx * cx;
  xy = xy * lambda + cx * cy;
}

CostModel::CostModel(double slope_forgetting, double intercept_forgetting)
    : slope_lambda_(std::clamp(slope_forgetting, 1e-3, 1.0)),
      intercept_lambda_(std::clamp(intercept_forgetting, 1e-3, 1.0)) {}

void CostModel::add(double cost, double ms) {
  if (!(cost >= 0) || !(ms > 0) || !std::isfinite(cost) || !std::isfinite(ms)) return;
  long_.add(slope_lambda_, cost, ms);
  short_.add(intercept_lambda_, cost, ms);
  const double mx = long_.x / long_.w, my = long_.y / long_.w;
  const double var = long_.xx / long_.w - mx * mx;
  if (mx > 0 && var > (kMinRelativeSpread * mx) * (kMinRelativeSpread * mx)) {
    const double b = (long_.xy / long_.w - mx * my) / var;
    if (b > 0) {
      slope_ = b;
      identified_ = true;
    }
  }
  // Not identified (yet): a share of the recent frames' time is taken as proportional to cost.
  if (!identified_ && short_.x > 0) slope_ = (1 - kPriorFixedShare) * short_.y / short_.x;
  // Given the slope, the intercept that fits the recent frames best (never negative).
  intercept_ = std::max(0.0, (short_.y - slope_ * short_.x) / short_.w);
}

}  // namespace tsp
