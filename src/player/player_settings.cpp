// The player's render settings and the commands that change them: tolerances, metric, any row
// of the settings table, the quality target's calibrated knobs, the texture cache.
#include <algorithm>
#include <cmath>
#include <cstdio>

#include "jobs/calibration.h"
#include "player/player_app.h"
#include "render/settings_table.h"
#include "tsp/core/error.h"

namespace tspplayer {

namespace {

constexpr float kMinToleranceCeiling = 1e-3f;

// Largest finite error in e: the tolerance sliders' upper end (a tolerance above every error
// draws the root only).
float largest_error(const tsp::NodeErrors& e) {
  float m = 0;
  for (const auto* v : {&e.spatial, &e.temporal})
    for (float x : *v)
      if (std::isfinite(x)) m = std::max(m, x);
  return std::max(m, kMinToleranceCeiling);
}

}  // namespace

void PlayerApp::set_metric(tsp::Metric m) {
  if (m == state.metric) return;
  state.metric = m;
  if (m != tsp::Metric::reference)
    lazy_ = std::make_unique<tsp::LazyErrors>(file->tree(), m, tf);
  else
    reference_version_ = ~std::uint64_t(0);
  renderer->drop_unreachable(frame_metric(), state.settings.tol, state.settings.skip_transparent,
                             state.settings.span_step);
  update_tol_max();
}

void PlayerApp::update_tol_max() {
  tol_max = largest_error(state.metric == tsp::Metric::reference ? reference_.errors
                                                           : lazy_->errors_for_step(state.step));
}

void PlayerApp::set_tolerances(tsp::Tolerances t) {
  state.settings.tol = {std::max(0.0, t.spatial), std::max(0.0, t.temporal)};
  renderer->drop_unreachable(frame_metric(), state.settings.tol, state.settings.skip_transparent,
                             state.settings.span_step);
}

void PlayerApp::set_setting(const std::string& name, const std::string& text) {
  const tspgl::SettingSpec* spec = tspgl::find_setting(name);
  if (!spec) throw tsp::UsageError("no render setting '" + name + "'");
  tspgl::RenderSettings next = state.settings;
  tspgl::set_setting(next, *spec, text, name);
  if (next.tol != state.settings.tol || next.span_step != state.settings.span_step ||
      next.skip_transparent != state.settings.skip_transparent) {
    state.settings = next;
    set_tolerances(next.tol);  // what the traversal reaches changed: drop the rest
  } else {
    state.settings = next;
  }
}

void PlayerApp::apply_quality(double de) {
  tspgl::CalibrationRequest r;
  r.tsp_path = options_.tsp_path;
  r.field = field();  // as render names it: one calibration serves both
  r.metric = state.metric;
  r.camera = state.camera;
  // The view's size as this frame lays it out (camera's is set when the volume is drawn: on the
  // first frame it is still the default).
  r.camera.width = std::max(1, layout.view.w);
  r.camera.height = std::max(1, layout.view.h);
  calibrator_.reset();
  try {
    calibrator_ = std::make_unique<tspgl::Calibrator>(*ctx, r, *file, tf);
  } catch (const tsp::Error& e) {
    status = std::string("quality: ") + e.what();
    return;
  }
  calibrating_de_ = de;
  calibrating_tf_ = tf.version();
  calibration_started_s_ = clock_.seconds();
  frames_while_calibrating_ = 0;
  quality_note = "calibrating (once per tree, TF, metric and view; the window keeps playing)";
  advance_calibration();  // a cached calibration applies at once
}

void PlayerApp::advance_calibration() {
  if (!calibrator_) return;
  if (calibrating_tf_ != tf.version()) {  // the TF changed: calibrate for the new one
    apply_quality(calibrating_de_);
    return;
  }
  try {
    if (!calibrator_->advance(kCalibrationSliceMs)) {
      ++frames_while_calibrating_;
      return;
    }
  } catch (const tsp::Error& e) {
    calibrator_.reset();
    status = std::string("quality: ") + e.what();
    quality_note.clear();
    return;
  }
  const std::unique_ptr<tspgl::Calibrator> c = std::move(calibrator_);
  calibration_s_ = clock_.seconds() - calibration_started_s_;
  const auto best = tspgl::pick_configuration(c->calibration(), calibrating_de_);
  if (!best) {  // say what would work, as render --quality does
    double lowest = 1e300;
    for (const tspgl::CalibrationPoint& p : c->calibration().points)
      lowest = std::min(lowest, p.max_step_de);
    char note[256];
    std::snprintf(note, sizeof note,
                  "nothing calibrated stays within dE %g (with a %g margin) on every calibration "
                  "step; the closest reaches %.3g, so %.3g is the least target that works",
                  calibrating_de_, tspgl::kQualityMargin, lowest,
                  lowest / tspgl::kQualityMargin);
    quality_note = note;
    return;
  }
  tspgl::apply(best->knobs, state.settings);  // compositing, spacing, tolerances (by its rule), ...
  quality_applied_ = true;
  set_tolerances(state.settings.tol);
  const std::string& cache = c->cache_file();
  quality_note = tspgl::render_options(best->knobs, state.metric) + (cache.empty() ? "" : " (" + cache + ")");
}

void PlayerApp::set_cache(bool on, double budget_mb) {
  state.cache_on = on;
  state.texture_budget_mb = std::max(1.0, budget_mb);
  make_renderer();
}

}  // namespace tspplayer
