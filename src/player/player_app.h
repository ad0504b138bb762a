// The player's state and frame loop, shared by player.cpp (loop, input, script) and
// player_ui.cpp (the Dear ImGui panels). Internal to src/player.
#pragma once
#include <cstdint>
#include <deque>
#include <memory>
#include <string>
#include <vector>

#include "gl/context.h"
#include "player/player.h"
#include "player/script.h"
#include "render/volume_renderer.h"
#include "tsp/frame/camera.h"
#include "tsp/metric/frame_metric.h"
#include "tsp/metric/lazy_errors.h"
#include "tsp/metric/metric.h"
#include "tsp/metric/transfer_function.h"
#include "tsp/store/brick_prefetcher.h"
#include "tsp/store/tsp_file.h"

namespace tspplayer {

/// Seconds of frame times kept for the HUD plot.
inline constexpr double kFrameHistorySeconds = 5.0;
/// Control points the TF editor samples from a TF without few clear knots.
inline constexpr int kEditorPoints = 9;
/// Steps ahead whose bricks are read in the background during playback.
inline constexpr int kPrefetchSteps = 2;

/// One frame time sample for the HUD.
struct FrameSample {
  double at_s = 0;  ///< seconds since the player started
  double ms = 0;    ///< whole frame (render + UI + swap)
};

/// The window player.
class PlayerApp {
 public:
  /// Opens the file and the window. Throws like run_player.
  explicit PlayerApp(const PlayerOptions& options);
  ~PlayerApp();
  PlayerApp(const PlayerApp&) = delete;
  PlayerApp& operator=(const PlayerApp&) = delete;
  /// Runs frames until the window closes or the script/screenshot ends it.
  void run();

  // ---- state the UI reads and edits (player_ui.cpp) ----
  std::unique_ptr<tsp::TspFile> file;
  std::unique_ptr<tspgl::GlContext> ctx;
  std::unique_ptr<tspgl::VolumeRenderer> renderer;
  std::unique_ptr<tsp::BrickPrefetcher>
      prefetcher;  ///< reads into renderer's brick cache; made after it
  tsp::TransferFunction tf;
  std::vector<tsp::TfPoint> tf_points;  ///< the editor's control points
  std::string tf_path = "tf.json";      ///< load/save path in the editor
  tsp::Metric metric = tsp::Metric::approximate;
  tsp::CameraParams camera;
  tsp::Tolerances tol;
  tspgl::Compositing compositing = tspgl::Compositing::rays;
  double spacing = tspgl::kDefaultSliceSpacing;
  bool preintegrated = false;
  float quality = 0;          ///< the quality slider (mean ΔE; 0: the raw knobs)
  std::string quality_note;   ///< what the last quality pick chose
  float tol_max = 1;  ///< upper end of the tolerance sliders (largest error of a step)
  bool cache_on = true;
  double upload_budget_mb = 16;  ///< texture MiB one frame may upload (0: no limit)
  bool prefetch_on = true;       ///< read the next steps' bricks in the background while playing
  double texture_budget_mb = double(tspgl::kDefaultTextureBudget) / (1 << 20);
  int step = 0;
  bool playing = false, loop = true;
  double speed = 5;    ///< steps per second
  std::string status;  ///< last message shown in the UI (saved files, errors)

  // ---- statistics for the HUD ----
  tspgl::FrameReport last;
  std::deque<FrameSample> history;
  double metric_ms = 0;                 ///< last metric (re)compute
  std::int64_t metric_evaluations = 0;  ///< node evaluations of the last recompute

  /// Applies a transfer function (from a file, preset or the editor) from the next frame on.
  void set_tf(const tsp::TransferFunction& next, bool resample_points);
  /// Rebuilds the TF from tf_points (an editor change).
  void apply_tf_points();
  /// Switches the metric (the reference metric is computed in full, blocking).
  void set_metric(tsp::Metric m);
  /// Changes tolerances and drops textures no frame can use any more.
  void set_tolerances(tsp::Tolerances t);
  /// Picks the fastest calibrated knobs within mean ΔE de for the current TF, metric and view
  /// (calibrating first, blocking, when the cache has none) and applies them; reports in
  /// quality_note. Errors go to status.
  void apply_quality(double de);
  /// Writes the HUD's statistics as JSON to path (atomically). Throws tsp::IoError.
  void write_stats(const std::string& path) const;
  /// Recreates the renderer for a cache policy or budget change.
  void set_cache(bool on, double budget_mb);
  /// Goes to step t (clamped), pausing playback.
  void go_to(int t);
  /// Number of steps of the file.
  int steps() const;
  /// Saves the current volume frame as PNG (path chosen from the step) and reports it in status.
  void request_save();

 private:
  void frame();
  void advance_playback(double dt);
  void handle_input();
  void run_script();
  void apply(const ScriptAction& a);
  void draw_ui();  // player_ui.cpp
  void render_volume();
  void save_pending_shot();
  void refresh_reference();
  /// The current metric as frames read it (the reference metric brought up to date first).
  tsp::FrameMetric& frame_metric();
  void request_prefetch(const tsp::Camera& cam, const tspgl::RenderSettings& settings);
  void make_renderer();
  void update_tol_max();

  PlayerOptions options_;
  std::unique_ptr<tsp::LazyErrors> lazy_;
  tsp::MetricResult reference_;
  tsp::WholeTreeMetric reference_nodes_{reference_};  ///< reference_ as a FrameMetric
  std::uint64_t reference_version_ = ~std::uint64_t(0);
  std::vector<ScriptAction> script_;
  std::size_t script_pos_ = 0;
  int wait_frames_ = 0;
  std::string pending_shot_;      ///< screenshot to save after the next complete frame
  bool pending_with_ui_ = false;  ///< pending_shot_ includes the UI panels
  bool save_requested_ = false;
  bool quit_ = false;
  bool imgui_ = false;
  double play_accum_ = 0;
  int prefetched_for_ = -1;  ///< step whose successors were last requested
  double start_s_ = 0, last_frame_s_ = 0;
};

}  // namespace tspplayer
