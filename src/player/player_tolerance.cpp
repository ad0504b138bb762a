// What the tolerances buy (docs/player.md "Settings"): when they change, the shown step and view
// are drawn off-screen at them and at 0, and the panel shows both frame times and the mean ΔE
// between the two pictures beside the tolerance sliders.
#include <algorithm>
#include <cmath>

#include "jobs/image_probe.h"
#include "player/player_app.h"
#include "tsp/core/error.h"
#include "tsp/report/image_diff.h"

namespace tspplayer {

namespace {
// The readout's pictures are at most this size (the view's aspect).
constexpr int kReadoutWidth = 320, kReadoutHeight = 200;
}  // namespace

void PlayerApp::measure_tolerance() {
  tol_readout_due = false;
  if (state_.camera.width < 1 || state_.camera.height < 1) return;
  tsp::CameraParams view = state_.camera;
  const double shrink = std::min({1.0, double(kReadoutWidth) / view.width,
                                  double(kReadoutHeight) / view.height});
  view.width = std::max(1, int(std::lround(view.width * shrink)));
  view.height = std::max(1, int(std::lround(view.height * shrink)));
  try {
    tspgl::ImageProbe probe(*ctx, viewer_->file(), tf, view, {state_.step});
    tspgl::RenderSettings s = state_.settings;
    s.upload_budget = 0;  // whole pictures
    tspgl::RenderSettings exact = s;
    exact.tol = {0, 0};
    const auto [at, ms] = probe.render_step(s, 0, frame_metric(), 0);
    const auto [zero, exact_ms] = probe.render_step(exact, 0, frame_metric(), 0);
    tol_readout = {state_.settings.tol, ms, exact_ms, tsp::diff_images(at, zero).mean};
  } catch (const tsp::Error& e) {
    status = std::string("tolerance readout: ") + e.what();
  }
  ctx->make_current();
}

}  // namespace tspplayer
