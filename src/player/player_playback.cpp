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
}  // namespace

double default_speed(int steps) {
  return std::clamp(double(steps) / kDefaultLoopSeconds, kMinSpeed, kDefaultMaxSpeed);
}

void PlayerApp::advance_playback(double dt) {
  if (!state_.playing) {
    playback_clock_.reset();
    return;
  }
  for (int advance = playback_clock_.advance(dt, state_.speed, state_.every_step); advance > 0;
       --advance) {
    if (state_.step + 1 < steps()) {
      ++state_.step;
    } else if (state_.loop) {
      state_.step = 0;
    } else {
      state_.playing = false;
      playback_clock_.reset();
      break;
    }
  }
}

double PlayerApp::until_next_step() const {
  if (!state_.playing) return kIdleWaitSeconds;
  return playback_clock_.until_next(clock_.seconds() - last_frame_s_, state_.speed);
}

double PlayerApp::steps_shown_per_s() const {
  // Steps after the first over the time since it was shown (0 before a second step was: it
  // once read "playing at 0.0 steps/s" as playback started).
  if (!rate_measured()) return 0.0;
  return rate_readout_.rate();  // (over step periods, at the last frame: rate_readout.h)
}

bool PlayerApp::rate_measured() const {
  return state_.playing && rate_readout_.measured();
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
          {"metric", tsp::to_string(state_.metric)},
          {"settings", tspgl::settings_json(state_.settings)},
          {"size", {view.width, view.height}},
          {"view", {view.azimuth_deg, view.elevation_deg, view.zoom, view.pan[0], view.pan[1]}},
          {"perspective", view.projection == tsp::Projection::perspective}};
}

TuneKey PlayerApp::tune_key() const {
  TuneKey k;
  k.file = &viewer_->file();
  k.field = field();
  k.tf_version = tf.version();
  k.metric = state_.metric;
  k.settings = state_.settings;
  k.width = std::max(1, layout.view.w);
  k.height = std::max(1, layout.view.h);
  return k;
}

const tspgl::Rung* PlayerApp::rung_drawn() const {
  if (!state_.playing || state_.quality <= 0) return nullptr;
  if (rungs_.ladder().empty()) return &tspgl::playback_rungs()[tspgl::kProvisionalRung];
  return &rungs_.ladder()[std::size_t(rungs_.choice().index)].rung;
}

void PlayerApp::apply_quality(double de) {
  state_.quality = float(de);
  if (de > 0 && !tuning_.tuner() && !(tuning_.tuned_for() == tune_key() && !rungs_.ladder().empty()))
    start_tuning();
  advance_tuning();  // (a slice now: a script's next action waits for the rest)
}

void PlayerApp::start_tuning() {
  const TuneKey key = tune_key();
  // The view's aspect at no more than kMaxTunePixels.
  const double shrink =
      std::min(1.0, std::sqrt(double(tspgl::kMaxTunePixels) / (double(key.width) * key.height)));
  tsp::CameraParams view = state_.camera;
  view.width = std::max(1, int(std::lround(key.width * shrink)));
  view.height = std::max(1, int(std::lround(key.height * shrink)));
  nlohmann::json disk_key = tuning_disk_key(view);  // (the view's, whatever pixels it probes)
  std::string file = tspgl::tuning_cache_path(disk_key, options_.cache_dir);
  try {
    auto cached = tuning_.start(
        key, std::move(disk_key), std::move(file),
        [this, view](double pixel_share) {  // (fewer pixels when playing needs: playback_tuning.h)
          tsp::CameraParams v = view;
          v.width = std::max(1, int(std::lround(view.width * std::sqrt(pixel_share))));
          v.height = std::max(1, int(std::lround(view.height * std::sqrt(pixel_share))));
          return std::make_unique<tspgl::PlaybackTuner>(*ctx, viewer_->file(), tf, frame_metric(),
                                                        v, state_.settings);
        },
        clock_.seconds(), frames_drawn_);
    if (cached) rungs_.set_ladder(std::move(*cached));  // kept on disk: played at once
  } catch (const tsp::Error& e) {
    status = std::string("playback tuning: ") + e.what();
  }
}

void PlayerApp::begin_tuning() {
  if (state_.quality <= 0) {
    tuning_.stop();
    return;
  }
  const TuneKey key = tune_key();
  // Out of date: again, for what is shown.
  if (tuning_.tuner() && !(tuning_.running_for() == key)) start_tuning();
  // Tuned when playing (a still window never pays for it) or when the target is set.
  if (!tuning_.tuner() && state_.playing &&
      (rungs_.ladder().empty() || !(tuning_.tuned_for() == key)))
    start_tuning();
}

void PlayerApp::advance_tuning() {
  begin_tuning();
  if (!tuning_.tuner()) return;
  // Playing, the pictures that end before the next step is due (playback_tuning.h).
  const bool step_frame = state_.step != drawn_tuning_step_;
  drawn_tuning_step_ = state_.step;
  std::string note;
  try {
    auto ladder = tuning_.advance(state_.playing, 1000 * until_next_step(), step_frame,
                                  1000 / std::max(state_.speed, 1e-3), clock_.seconds(),
                                  frames_drawn_, note);
    if (ladder) rungs_.set_ladder(std::move(*ladder));
  } catch (const tsp::Error& e) {
    status = std::string("playback tuning: ") + e.what();
  }
  if (!note.empty()) status = note;
}

void PlayerApp::choose_rung(double now_s) {
  if (!playing_rung()) return;
  rungs_.choose(state_.quality, state_.speed, state_.keep_quality, lod_loop_.overhead_ms(), now_s);
}

void PlayerApp::measured_rung(double render_ms) {
  if (playing_rung()) rungs_.measured(render_ms);
}

nlohmann::json PlayerApp::playback_json() const {
  nlohmann::json j = {{"speed", state_.speed},
                      {"quality", state_.quality},
                      {"keep", state_.keep_quality ? "quality" : "rate"},
                      {"playing", state_.playing},
                      {"steps_shown_per_s", steps_shown_per_s()},
                      {"tuned", !rungs_.ladder().empty()},
                      {"time_ratio", rungs_.time_ratio()}};
  if (playing_rung()) {
    const tspgl::RungChoice& rung = rungs_.choice();
    const tspgl::TunedRung& t = rungs_.ladder()[std::size_t(rung.index)];
    const tspgl::RenderSettings s = tspgl::rung_settings(state_.settings, t.rung);
    j["rung"] = {{"name", t.rung.name},
                 {"spacing", s.spacing},
                 {"render_scale", s.render_scale},
                 {"lod_level", t.rung.lod_level},
                 {"predicted_de", t.mean_de},
                 {"predicted_max_step_de", t.max_step_de},
                 {"predicted_ms", rung.predicted_ms},
                 {"period_ms", 1000.0 / std::max(state_.speed, 1e-3)},
                 {"fits_rate", rung.fits_rate},
                 {"within_quality", rung.within_quality}};
  }
  nlohmann::json ladder = nlohmann::json::array();
  const std::vector<tspgl::TunedRung>& tuned = rungs_.ladder();
  for (std::size_t i = 0; i < tuned.size(); ++i)
    ladder.push_back({{"name", tuned[i].rung.name},
                      {"mean_de", tuned[i].mean_de},
                      {"max_step_de", tuned[i].max_step_de},
                      {"probe_ms", tuned[i].ms},
                      {"frames", rungs_.frames(i)}});
  j["ladder"] = ladder;
  return j;
}

}  // namespace tspplayer
