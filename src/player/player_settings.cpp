// The player's render settings and the commands that change them: tolerances, metric, any row
// of the settings table, the texture cache.
#include <algorithm>
#include <cmath>
#include <cstdio>

#include "player/player_app.h"
#include "tsp/source/open_mesh_source.h"
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
  if (m == state_.metric) return;
  state_.metric = m;
  viewer_->set_metric(m);
  viewer_->renderer().drop_unreachable(frame_metric(), state_.settings.tol, state_.settings.skip_transparent,
                             state_.settings.span_step);
  update_tol_max();
}

void PlayerApp::update_tol_max() {
  tol_max = largest_error(viewer_->errors_for_step(state_.step));
}

void PlayerApp::set_tolerances(tsp::Tolerances t) {
  state_.settings.tol = {std::max(0.0, t.spatial), std::max(0.0, t.temporal)};
  viewer_->renderer().drop_unreachable(frame_metric(), state_.settings.tol, state_.settings.skip_transparent,
                             state_.settings.span_step);
  tol_readout_due = true;  // what they buy, measured after the next frame's volume
}

void PlayerApp::set_setting(const std::string& name, const std::string& text) {
  const tspgl::SettingSpec* spec = tspgl::find_setting(name);
  if (!spec) throw tsp::UsageError("no render setting '" + name + "'");
  tspgl::RenderSettings next = state_.settings;
  tspgl::set_setting(next, *spec, text, name);
  // The knob just changed wins over one it excludes, and the status line says so.
  if (std::string off = tspgl::settle_sampling(next, name); !off.empty()) status = off;
  // (The line that said what the boundary drew stayed after it was turned off: the eighth walk.)
  if (state_.settings.surface && !next.surface) status = "surface off";
  if (next.tol != state_.settings.tol || next.span_step != state_.settings.span_step ||
      next.skip_transparent != state_.settings.skip_transparent) {
    state_.settings = next;
    set_tolerances(next.tol);  // what the traversal reaches changed: drop the rest
  } else {
    state_.settings = next;
  }
  if (state_.settings.surface && !mesh_surface) offer_surface();
}

void PlayerApp::offer_surface() {
  // The boundary of the mesh this file was built from, when the input played is that mesh;
  // otherwise the control says what it needs and goes back off (it never silently does nothing).
  const std::string& input = options_.input_path;
  std::string why;
  if (!input.empty() && tsp::is_mesh_input(input, options_.input.source.allow_external)) {
    try {
      mesh_surface.emplace(input, options_.surface_field, viewer_->file(), options_.surface_tf, state_.step);
      surface_mesh_ = input;
      status = "surface: the boundary of " + input + ", the mesh this file was built from";
      return;
    } catch (const tsp::Error& e) {
      why = e.what();
    }
  } else if (viewer_->file().metadata().source.find(", voxelized to ") != std::string::npos) {
    why = "surface boundary needs the mesh the file was built from: play the mesh itself "
          "(tspplay play MESH), or start with --surface-mesh MESH";
  } else {  // (it spoke of "the mesh the file was built from" for a grid's file too)
    why = "surface boundary draws a mesh's outer surface, and this input is a grid (" +
          viewer_->file().metadata().source +
          "): play a mesh input (tspplay play MESH), or start with --surface-mesh MESH";
  }
  state_.settings.surface = false;
  status = why;
  if (options_.trace) std::printf("trace: surface refused: %s\n", why.c_str());
}

void PlayerApp::set_cache(bool on, double budget_mb) {
  state_.cache_on = on;
  state_.texture_budget_mb = std::max(1.0, budget_mb);
  make_renderer();
}

}  // namespace tspplayer
