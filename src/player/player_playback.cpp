// Playback (docs/player.md, "Playing at a quality target"): steps advance at the speed; with a
// quality target each playing frame draws the rung of the tuned ladder (jobs/playback_tuner.h)
// that fits the step period within the target — the ladder probed a slice of each frame against
// the full-quality picture at this view's size, re-tuned when the file, field, TF, metric,
// settings or view size change; the window's measured time per rung corrects the probe's.
#include <algorithm>
#include <cmath>
#include <cstdio>

#include <sys/stat.h>

#include <filesystem>

#include "jobs/tuning_cache.h"
#include "player/player_app.h"
#include "render/settings_table.h"
#include "tsp/core/error.h"

namespace tspplayer {

namespace {
// The ratio of window to probe time is kept within these bounds (one odd frame cannot swing it).
constexpr double kMinTimeRatio = 0.25, kMaxTimeRatio = 8;
}  // namespace

double default_speed(int steps) {
  return std::clamp(double(steps) / kDefaultLoopSeconds, kMinSpeed, kDefaultMaxSpeed);
}

void PlayerApp::advance_playback(double dt) {
  if (!state.playing) {
    playback_clock_.reset();
    return;
  }
  for (int advance = playback_clock_.advance(dt, state.speed, state.every_step); advance > 0;
       --advance) {
    if (state.step + 1 < steps()) {
      ++state.step;
    } else if (state.loop) {
      state.step = 0;
    } else {
      state.playing = false;
      playback_clock_.reset();
      break;
    }
  }
}

double PlayerApp::until_next_step() const {
  if (!state.playing) return kIdleWaitSeconds;
  return playback_clock_.until_next(clock_.seconds() - last_frame_s_, state.speed);
}

double PlayerApp::steps_shown_per_s() const {
  const double span = std::min(kShownWindowSeconds, clock_.seconds() - start_s_);
  return span > 0 ? double(shown_at_s_.size()) / span : 0.0;
}

nlohmann::json PlayerApp::tuning_disk_key(const tsp::CameraParams& view) const {
  namespace fs = std::filesystem;
  std::error_code ec;
  const fs::path canon = fs::weakly_canonical(options_.tsp_path, ec);
  struct stat st {};
  ::stat(options_.tsp_path.c_str(), &st);
  std::string tf_text = std::to_string(tf.domain().lo) + " " + std::to_string(tf.domain().hi);
  char buf[64];
  for (const tsp::Rgba& e : tf.entries()) {
    std::snprintf(buf, sizeof buf, " %.6g %.6g %.6g %.6g", e.r, e.g, e.b, e.a);
    tf_text += buf;
  }
  return {{"file", canon.string()},
          {"bytes", std::int64_t(st.st_size)},
          {"mtime", std::to_string(st.st_mtim.tv_sec) + "." + std::to_string(st.st_mtim.tv_nsec)},
          {"field", field()},
          {"tf", tf_text},
          {"metric", tsp::to_string(state.metric)},
          {"settings", tspgl::settings_json(state.settings)},
          {"size", {view.width, view.height}},
          {"view", {view.azimuth_deg, view.elevation_deg, view.zoom, view.pan[0], view.pan[1]}},
          {"perspective", view.projection == tsp::Projection::perspective}};
}

PlayerApp::TuneKey PlayerApp::tune_key() const {
  TuneKey k;
  k.file = file.get();
  k.field = field();
  k.tf_version = tf.version();
  k.metric = state.metric;
  k.settings = state.settings;
  k.width = std::max(1, layout.view.w);
  k.height = std::max(1, layout.view.h);
  return k;
}

const tspgl::Rung* PlayerApp::rung_drawn() const {
  if (!state.playing || state.quality <= 0) return nullptr;
  if (tuned_.empty()) return &tspgl::playback_rungs()[tspgl::kProvisionalRung];
  return &tuned_[std::size_t(rung_.index)].rung;
}

void PlayerApp::apply_quality(double de) {
  state.quality = float(de);
  if (de > 0 && !tuner_ && !(tuned_for_ == tune_key() && !tuned_.empty())) start_tuning();
  advance_tuning();  // (a slice now: a script's next action waits for the rest)
}

void PlayerApp::start_tuning() {
  const TuneKey key = tune_key();
  // The view's aspect at no more than kMaxTunePixels.
  const double shrink =
      std::min(1.0, std::sqrt(double(tspgl::kMaxTunePixels) / (double(key.width) * key.height)));
  tsp::CameraParams view = state.camera;
  view.width = std::max(1, int(std::lround(key.width * shrink)));
  view.height = std::max(1, int(std::lround(key.height * shrink)));
  tuner_.reset();
  // A tuning of the same data, map and view kept on disk from an earlier run: played at once.
  tuning_cache_key_ = tuning_disk_key(view);
  tuning_cache_file_ = tspgl::tuning_cache_path(tuning_cache_key_, options_.cache_dir);
  if (auto cached = tspgl::read_tuning(tuning_cache_file_, tuning_cache_key_)) {
    tuned_ = std::move(*cached);
    tuned_for_ = key;
    tuning_s_ = 0;
    tuning_from_cache_ = true;
    rung_frames_.assign(tuned_.size(), 0);
    rung_ = {};
    rung_for_ = {};
    return;
  }
  try {
    tuner_ = std::make_unique<tspgl::PlaybackTuner>(*ctx, *file, tf, frame_metric(), view,
                                                    state.settings);
  } catch (const tsp::Error& e) {
    status = std::string("playback tuning: ") + e.what();
    return;
  }
  tuning_for_ = key;
  tuning_started_s_ = clock_.seconds();
  frames_while_tuning_ = 0;
}

void PlayerApp::advance_tuning() {
  if (state.quality <= 0) {
    tuner_.reset();
    return;
  }
  const TuneKey key = tune_key();
  if (tuner_ && !(tuning_for_ == key)) start_tuning();  // out of date: again, for what is shown
  // Tuned when playing (a still window never pays for it) or when the target is set.
  if (!tuner_ && state.playing && (tuned_.empty() || !(tuned_for_ == key))) start_tuning();
  if (!tuner_) return;
  try {
    if (!tuner_->advance(kCalibrationSliceMs)) {
      ++frames_while_tuning_;
      return;
    }
  } catch (const tsp::Error& e) {
    tuner_.reset();
    status = std::string("playback tuning: ") + e.what();
    return;
  }
  tuned_ = tuner_->tuned();
  tuned_for_ = tuning_for_;
  tuner_.reset();
  tuning_s_ = clock_.seconds() - tuning_started_s_;
  tuning_from_cache_ = false;
  if (!tuning_cache_file_.empty()) {
    try {
      tspgl::write_tuning(tuning_cache_file_, tuning_cache_key_, tuned_);
    } catch (const tsp::Error& e) {  // playing goes on; the next run tunes again
      status = std::string("playback tuning not kept: ") + e.what();
    }
  }
  rung_frames_.assign(tuned_.size(), 0);
  rung_ = {};
  rung_for_ = {};
}

void PlayerApp::choose_rung(double now_s) {
  if (!playing_rung()) return;
  const double period_ms = 1000.0 / std::max(state.speed, 1e-3);
  const tspgl::RungChoice next =
      tspgl::choose_rung(tuned_, period_ms, time_ratio_, lod_loop_.overhead_ms(),
                         state.quality, state.keep_quality);
  // A new target, speed or rule applies at once; otherwise a cheaper rung at once (the rate or
  // the quality is being missed) and a costlier one with headroom, not straight after a change.
  const RungFor asked{state.quality, state.speed, state.keep_quality};
  const bool costlier = tuned_[std::size_t(next.index)].ms > tuned_[std::size_t(rung_.index)].ms;
  if (!(asked == rung_for_) || !costlier ||
      (next.predicted_ms <= kRungHeadroom * period_ms && now_s - rung_changed_s_ >= kRungHoldSeconds)) {
    if (next.index != rung_.index) rung_changed_s_ = now_s;
    rung_ = next;
    rung_for_ = asked;
    return;
  }
  // The same rung: its prediction with the current ratio.
  const tspgl::TunedRung& t = tuned_[std::size_t(rung_.index)];
  rung_.predicted_ms = t.ms * time_ratio_ + lod_loop_.overhead_ms();
  rung_.fits_rate = rung_.predicted_ms <= period_ms;
  rung_.within_quality = t.mean_de <= tspgl::kPlaybackQualityMargin * state.quality;
}

void PlayerApp::measured_rung(double render_ms) {
  if (!playing_rung() || rung_.index >= int(tuned_.size())) return;
  ++rung_frames_[std::size_t(rung_.index)];
  const double probe_ms = tuned_[std::size_t(rung_.index)].ms;
  if (probe_ms <= 0 || render_ms <= 0) return;
  const double ratio = std::clamp(render_ms / probe_ms, kMinTimeRatio, kMaxTimeRatio);
  time_ratio_ += kTimeRatioSmoothing * (ratio - time_ratio_);
}

nlohmann::json PlayerApp::playback_json() const {
  nlohmann::json j = {{"speed", state.speed},
                      {"quality", state.quality},
                      {"keep", state.keep_quality ? "quality" : "rate"},
                      {"playing", state.playing},
                      {"steps_shown_per_s", steps_shown_per_s()},
                      {"tuned", !tuned_.empty()},
                      {"time_ratio", time_ratio_}};
  if (playing_rung()) {
    const tspgl::TunedRung& t = tuned_[std::size_t(rung_.index)];
    const tspgl::RenderSettings s = tspgl::rung_settings(state.settings, t.rung);
    j["rung"] = {{"name", t.rung.name},
                 {"spacing", s.spacing},
                 {"render_scale", s.render_scale},
                 {"lod_level", t.rung.lod_level},
                 {"predicted_de", t.mean_de},
                 {"predicted_max_step_de", t.max_step_de},
                 {"predicted_ms", rung_.predicted_ms},
                 {"period_ms", 1000.0 / std::max(state.speed, 1e-3)},
                 {"fits_rate", rung_.fits_rate},
                 {"within_quality", rung_.within_quality}};
  }
  nlohmann::json ladder = nlohmann::json::array();
  for (std::size_t i = 0; i < tuned_.size(); ++i)
    ladder.push_back({{"name", tuned_[i].rung.name},
                      {"mean_de", tuned_[i].mean_de},
                      {"max_step_de", tuned_[i].max_step_de},
                      {"probe_ms", tuned_[i].ms},
                      {"frames", i < rung_frames_.size() ? rung_frames_[i] : 0}});
  j["ladder"] = ladder;
  return j;
}

}  // namespace tspplayer
