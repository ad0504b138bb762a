#include "jobs/playback_tuner.h"

#include <algorithm>
#include <cassert>

#include "jobs/image_probe.h"
#include "jobs/render_job.h"
#include "tsp/core/stopwatch.h"
#include "tsp/report/image_diff.h"

namespace tspgl {

namespace {

// Probe steps spread evenly over n steps: the middle of each of `count` equal parts.
std::vector<int> spread_steps(int n, int count) {
  std::vector<int> out;
  for (int k = 0; k < count; ++k) {
    const int t = std::clamp(int((k + 0.5) * n / count), 0, n - 1);
    if (out.empty() || out.back() != t) out.push_back(t);
  }
  return out;
}

}  // namespace

const std::vector<Rung>& playback_rungs() {
  // Cost falls with pixels (render scale squared), samples (spacing) and texels (level); the
  // order matters only for probing (full quality first: the others are compared with it).
  // At 1280×800 on llvmpipe a 64³ frame at full quality costs about a second: the ladder
  // reaches down to a sixteenth of the pixels and an eighth of the samples; LOD levels, which
  // save uploads rather than samples, come last (large series).
  static const std::vector<Rung> rungs = {
      {"full", 1, 1, 0},
      {"scale 0.85", 1, 0.85, 0},
      {"scale 0.7", 1, 0.7, 0},
      {"spacing x2", 2, 1, 0},
      {"spacing x2, scale 0.7", 2, 0.7, 0},
      {"spacing x2, scale 0.5", 2, 0.5, 0},
      {"spacing x4, scale 0.5", 4, 0.5, 0},
      {"spacing x2, scale 0.35", 2, 0.35, 0},
      {"spacing x4, scale 0.35", 4, 0.35, 0},
      {"spacing x4, scale 0.25", 4, 0.25, 0},
      {"spacing x8, scale 0.25", 8, 0.25, 0},
      {"level 1, spacing x2, scale 0.5", 2, 0.5, 1},
      {"level 1, spacing x4, scale 0.35", 4, 0.35, 1},
      {"level 2, spacing x4, scale 0.25", 4, 0.25, 2},
  };

  return rungs;
}

RenderSettings rung_settings(const RenderSettings& s, const Rung& r) {
  RenderSettings out = s;
  out.spacing = std::min(kMaxSliceSpacing, s.spacing * r.spacing_factor);
  out.render_scale = std::max(kMinRenderScale, s.render_scale * r.render_scale);
  return out;
}

RungChoice choose_rung(const std::vector<TunedRung>& tuned, double period_ms, double time_ratio,
                       double overhead_ms, double target_de, bool keep_quality) {
  assert(!tuned.empty());
  const auto predicted = [&](const TunedRung& t) { return t.ms * time_ratio + overhead_ms; };
  const auto fits = [&](const TunedRung& t) { return predicted(t) <= period_ms; };
  const auto within = [&](const TunedRung& t) {
    return t.mean_de <= kPlaybackQualityMargin * target_de;
  };
  // Best of those passing `keep`: least ΔE (then fastest), or fastest.
  const auto best = [&](auto keep, bool by_quality) {
    int pick = -1;
    for (int i = 0; i < int(tuned.size()); ++i) {
      const TunedRung& t = tuned[std::size_t(i)];
      if (!keep(t)) continue;
      if (pick < 0) {
        pick = i;
        continue;
      }
      const TunedRung& p = tuned[std::size_t(pick)];
      const bool better = by_quality ? (t.mean_de < p.mean_de ||
                                        (t.mean_de == p.mean_de && t.ms < p.ms))
                                     : t.ms < p.ms;
      if (better) pick = i;
    }
    return pick;
  };
  int pick = best([&](const TunedRung& t) { return fits(t) && within(t); }, true);
  if (pick < 0 && keep_quality) pick = best(within, false);
  if (pick < 0) pick = best(fits, true);
  if (pick < 0) pick = best([](const TunedRung&) { return true; }, false);
  if (pick < 0) pick = 0;  // (tuned[0] is full quality: always within)
  const TunedRung& t = tuned[std::size_t(pick)];
  return {pick, fits(t), within(t), predicted(t)};
}

PlaybackTuner::PlaybackTuner(GlContext& ctx, const tsp::BrickStore& bricks,
                             const tsp::TransferFunction& tf, tsp::FrameMetric& nodes,
                             const tsp::CameraParams& camera, const RenderSettings& settings,
                             int steps)
    : probe_(std::make_unique<ImageProbe>(ctx, bricks, tf, camera,
                                          spread_steps(bricks.tree().time().steps(), steps))),
      nodes_(nodes),
      settings_(settings) {
  // Playing uploads every texture a step needs (shown late, never with bricks left flat for
  // later frames): so does each probe picture.
  settings_.upload_budget = 0;
}

PlaybackTuner::~PlaybackTuner() = default;

int PlaybackTuner::pictures_total() const {
  return int(playback_rungs().size() * probe_->steps());
}

double PlaybackTuner::next_picture_ms() const {
  if (done()) return 0;
  if (!current_ms_.empty()) return current_ms_.back();  // this rung's last picture
  if (!tuned_.empty()) return tuned_.back().ms;          // the last rung's (rungs get cheaper)
  return last_ms_;
}

bool PlaybackTuner::advance(double budget_ms) {
  const tsp::Stopwatch clock;
  const std::vector<Rung>& rungs = playback_rungs();
  while (!done()) {
    const Rung& r = rungs[rungs_done_];
    if (step_ == 0) current_ = {r, 0, 0, 0};
    auto [image, ms] = probe_->render_step(rung_settings(settings_, r), r.lod_level, nodes_, step_);
    ++pictures_done_;
    current_ms_.push_back(ms);
    last_ms_ = ms;
    if (rungs_done_ == 0) {
      reference_.push_back(std::move(image));  // full quality: the pictures the rest are held to
    } else {
      const double de = tsp::diff_images(image, reference_[step_]).mean;
      current_.mean_de += de / double(probe_->steps());
      current_.max_step_de = std::max(current_.max_step_de, de);
    }
    if (++step_ == probe_->steps()) {
      current_.ms = median(std::move(current_ms_));
      current_ms_.clear();
      tuned_.push_back(current_);
      step_ = 0;
      ++rungs_done_;
    }
    // (Another only when it is predicted to end within the budget: it ran past it by a picture.)
    if (clock.ms() + next_picture_ms() > budget_ms) break;
  }
  return done();
}

}  // namespace tspgl
