#include "player/playback_tuning.h"

#include <algorithm>

#include "jobs/tuning_cache.h"
#include "tsp/core/error.h"

namespace tspplayer {

double TuningPace::budget(bool playing, double until_next_ms, bool step_frame, double next_ms) {
  waiting_ = false;
  if (!playing) {  // still: a slice, at least one picture
    waits_ = 0;
    return kCalibrationSliceMs;
  }
  // Playing: the pictures that end before the next step is due.
  if (next_ms < 0 || next_ms <= until_next_ms) {
    waits_ = 0;
    return std::max(until_next_ms, 0.0);
  }
  // None fits: wait for the next step, and after a few step frames draw one anyway.
  if (step_frame && ++waits_ > kMaxTuningWaits) {
    waits_ = 0;
    return std::max(until_next_ms, 0.0);  // (one picture: advance draws at least one)
  }
  waiting_ = true;
  return 0;
}

std::optional<std::vector<tspgl::TunedRung>> PlaybackTuning::start(
    const TuneKey& key, nlohmann::json disk_key, std::string cache_file, MakeTuner make,
    double now_s, std::int64_t frame) {
  tuner_.reset();
  disk_key_ = std::move(disk_key);
  cache_file_ = std::move(cache_file);
  // A tuning of the same data, map and view kept on disk from an earlier run: played at once.
  if (auto cached = tspgl::read_tuning(cache_file_, disk_key_)) {
    tuned_for_ = key;
    seconds_ = 0;
    from_cache_ = true;
    return cached;
  }
  pixel_share_ = 1;
  restarts_ = 0;
  tuner_ = make(pixel_share_);
  make_ = std::move(make);
  running_for_ = key;
  pace_.restart();
  started_s_ = now_s;
  started_frame_ = frame;
  frames_before_first_picture_ = -1;
  frames_while_tuning_ = 0;
  longest_frame_ms_ = 0;
  late_frames_ = 0;
  return std::nullopt;
}

std::optional<std::vector<tspgl::TunedRung>> PlaybackTuning::advance(
    bool playing, double until_next_ms, bool step_frame, double period_ms, double now_s,
    std::int64_t frame, std::string& note) {
  if (!tuner_) return std::nullopt;
  const double budget = pace_.budget(playing, until_next_ms, step_frame, tuner_->next_picture_ms());
  if (budget <= 0) {
    ++frames_while_tuning_;
    return std::nullopt;
  }
  if (frames_before_first_picture_ < 0) frames_before_first_picture_ = frame - started_frame_;
  try {
    const bool done = tuner_->advance(budget);
    // The first picture (full quality, the costliest) too long for a playing frame: again with
    // fewer pixels, so that each picture fits beside the frame's own drawing (cost ∝ pixels).
    const double first_ms = tuner_->next_picture_ms();
    if (!done && playing && tuner_->pictures_done() == 1 && pixel_share_ > kMinProbePixelShare &&
        first_ms > kTuningPictureShare * period_ms) {
      pixel_share_ = std::max(kMinProbePixelShare,
                              pixel_share_ * 0.9 * kTuningPictureShare * period_ms / first_ms);
      ++restarts_;
      tuner_ = make_(pixel_share_);
    }
    if (!done) {
      ++frames_while_tuning_;
      return std::nullopt;
    }
  } catch (const tsp::Error&) {
    tuner_.reset();
    throw;
  }
  std::vector<tspgl::TunedRung> ladder = tuner_->tuned();
  tuned_for_ = running_for_;
  tuner_.reset();
  seconds_ = now_s - started_s_;
  from_cache_ = false;
  if (!cache_file_.empty()) {
    try {
      tspgl::write_tuning(cache_file_, disk_key_, ladder);
    } catch (const tsp::Error& e) {  // playing goes on; the next run tunes again
      note = std::string("playback tuning not kept: ") + e.what();
    }
  }
  return ladder;
}

void PlaybackTuning::frame_drawn(double frame_ms, double period_ms) {
  if (!tuner_) return;
  longest_frame_ms_ = std::max(longest_frame_ms_, frame_ms);
  late_frames_ += period_ms > 0 && frame_ms > 1.5 * period_ms;
}

nlohmann::json PlaybackTuning::stats() const {
  return {{"running", tuner_ != nullptr},
          {"pictures_done", tuner_ ? tuner_->pictures_done() : 0},
          {"pictures_total", tuner_ ? tuner_->pictures_total() : 0},
          {"seconds", seconds_},
          {"frames_while_tuning", frames_while_tuning_},
          {"longest_frame_ms", longest_frame_ms_},
          {"late_frames", late_frames_},
          {"frames_before_first_picture", frames_before_first_picture_},
          {"from_cache", from_cache_},  // read from disk: no probing this run
          {"cache_file", cache_file_},
          {"waiting", waiting()},
          {"probe_pixel_share", pixel_share_},  // of 640x400 at most (kMaxTunePixels)
          {"restarts", restarts_}};
}

}  // namespace tspplayer
