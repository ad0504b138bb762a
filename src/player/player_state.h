// What the player shows and how: the state player commands change (script lines, keys and panel
// widgets all make Commands, command.h, checked by validate() and carried out by apply()).
// A value type: no GL, no files.
#pragma once
#include <vector>

#include "player/player.h"
#include "render/render_settings.h"
#include "tsp/clip/probe.h"
#include "tsp/frame/camera.h"
#include "tsp/lod/selection_filter.h"
#include "tsp/metric/metric.h"

namespace tspplayer {

/// Target frames per second while interacting (the LOD cut holds it).
inline constexpr double kDefaultTargetFps = 30;

/// The player's state. Changed through PlayerApp's commands; the panels read it.
struct PlayerState {
  int step = 0;             ///< the step shown
  bool playing = false;     ///< playback running
  bool loop = true;         ///< playback wraps at the end
  bool every_step = true;   ///< playback shows every step in order (slower than the speed if
                            ///< frames are slow); false: real time, skipping steps
  double speed = 5;         ///< playback, steps per second
  tsp::CameraParams camera;                       ///< the view
  tspgl::RenderSettings settings;                 ///< the settings table's knobs
  tsp::Metric metric = tsp::Metric::approximate;  ///< the error metric frames read
  /// While playing: the mean ΔE target against full quality the tuned rung keeps (0: none, the
  /// LOD cut holds the frame rate).
  float quality = float(kDefaultPlayingQuality);
  /// While playing with a quality target, when no rung both fits the step period and keeps the
  /// target: true keeps the target (steps show later), false the rate (a coarser rung).
  bool keep_quality = true;
  bool lod_on = true;       ///< the adaptive LOD cut (off: full resolution always)
  float target_fps = float(kDefaultTargetFps);  ///< held while interacting
  bool show_cut = false;       ///< outline the cut's nodes, coloured by level (key L)
  bool splat_fallback = false; ///< splats (not a smaller target) below the coarsest cut
  tsp::SelectionFilter lod_filter;  ///< error: the adaptive cut; distance|fov: LaMar's filters
  bool panels = true;       ///< the UI panels (Tab); hidden: the volume fills the window
  bool annotations = true;  ///< outline box, axes triad, step/time over the volume
  bool log_opacity = false; ///< the TF editor's opacity axis on a log scale
  bool cache_on = true;     ///< the texture cache
  bool prefetch_on = true;  ///< read the next steps' bricks in the background while playing
  double texture_budget_mb = double(tspgl::kDefaultTextureBudget) / (1 << 20);
  std::vector<tsp::Probe> probes;                 ///< clip probes, in physical coordinates
  tsp::ProbeOp probe_op = tsp::ProbeOp::intersect;
  bool probe_surface = true;  ///< draw the clip surface (the data on the probe)
};

}  // namespace tspplayer
