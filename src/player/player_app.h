// The player's state and frame loop, shared by player.cpp (loop, input, script) and
// player_ui.cpp (the Dear ImGui panels). Internal to src/player.
#pragma once
#include <array>
#include <atomic>
#include <cstdint>
#include <deque>
#include <map>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <thread>
#include <vector>

#include "gl/context.h"
#include "jobs/calibration.h"
#include "jobs/playback_tuner.h"
#include <nlohmann/json.hpp>
#include "jobs/movie.h"
#include "player/field_shelf.h"
#include "player/input_queue.h"
#include "player/layout.h"
#include "player/lod_loop.h"
#include "player/playback_clock.h"
#include "player/playback_tuning.h"
#include "player/rate_readout.h"
#include "player/rung_picker.h"
#include "player/open_job.h"
#include "player/recorder.h"
#include "player/player.h"
#include "player/player_state.h"
#include "player/command.h"
#include "player/script.h"
#include "player/session.h"
#include "player/tf_handles.h"
#include "player/tf_histogram.h"
#include "player/viewer_session.h"
#include "render/frame_driver.h"
#include "render/mesh_surface.h"
#include "render/tile_refinement.h"
#include "render/volume_renderer.h"
#include "tsp/clip/probe.h"
#include "tsp/core/stopwatch.h"
#include "tsp/frame/camera.h"
#include "tsp/lod/lod_controller.h"
#include "tsp/metric/frame_metric.h"
#include "tsp/metric/lazy_errors.h"
#include "tsp/metric/metric.h"
#include "tsp/metric/transfer_function.h"
#include "tsp/store/brick_prefetcher.h"
#include "tsp/store/tsp_file.h"

namespace tspplayer {

/// Seconds of frame times kept for the HUD plot.
inline constexpr double kFrameHistorySeconds = 5.0;
/// Playback prefetches the bricks of the steps it will show in the next kPrefetchSeconds (at
/// least kMinPrefetchSteps, at most kMaxPrefetchSteps): more steps ahead at a higher speed.
inline constexpr double kPrefetchSeconds = 0.25;
/// See kPrefetchSeconds.
inline constexpr int kMinPrefetchSteps = 2, kMaxPrefetchSteps = 16;
/// Split candidates of the LOD cut whose children's bricks are prefetched.
inline constexpr int kPrefetchSplits = 4;

/// Largest --frame-delay-ms (a test's slow machine).
inline constexpr double kMaxFrameDelayMs = 2000;

/// Steps whose readiness (bricks in RAM or textures) is re-checked per frame, for the timeline.
inline constexpr int kReadyStepsPerFrame = 4;
/// Frames drawn after the last input event (Dear ImGui's hover and popups settle).
inline constexpr int kSettleFrames = 3;
/// Longest sleep of an idle window before it looks at its state again.
inline constexpr double kIdleWaitSeconds = 0.5;
/// How often a window whose script waits for a file (wait-file) looks for it, seconds.
inline constexpr double kFilePollSeconds = 0.02;
/// Frames per second of a recorded movie (frames repeat or drop to keep the wall-clock time).
inline constexpr int kRecordFps = 25;

/// One frame time sample for the HUD.
struct FrameSample {
  double at_s = 0;  ///< seconds since the player started
  double ms = 0;    ///< whole frame (render + UI + swap)
};

/// How the preset combo names the map a --tf / `tf` argument gives: "auto" for none, NAME for
/// preset:NAME, else the file's name. Never throws but bad_alloc.
std::string tf_label_of(const std::string& tf_arg);

/// True when TSPPLAY_REFINE_BY_CUT is set: the LOD cut refines as before issue 47 (a pause
/// is a change; coarse cuts while refining), for measuring against (docs/results.md).
bool refine_by_cut();

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

  /// What is shown and how (read-only: changed by commands, apply, command, the set_* below).
  const PlayerState& state() const { return state_; }

  // ---- what the frames use (player_ui.cpp reads it) ----
  std::unique_ptr<tspgl::GlContext> ctx;
  /// The open file, its metric, renderer, prefetcher and frame driver (viewer_session.h).
  const ViewerSession& viewer() const { return *viewer_; }

 private:
  /// See viewer(); File > Open replaces it (declared after ctx: it goes first).
  std::unique_ptr<ViewerSession> viewer_;

 public:
  /// The boundary of options' surface mesh and its colours (the first file only; File > Open
  /// of another file drops it), drawn when state.settings.surface is on.
  std::optional<tspgl::MeshSurface> mesh_surface;
  std::string surface_mesh_;  ///< the mesh mesh_surface was read from ("": none)
  /// Turning the surface on without one: reads the played input's boundary when it is a mesh,
  /// else says what is needed and turns it off again.
  void offer_surface();
  tsp::TransferFunction tf;
  /// The TF editor's control points, by increasing value (changed by the tf-point commands).
  const std::vector<tsp::TfPoint>& tf_points() const { return tf_points_; }
  /// The map in use as the preset combo names it: a preset's name, a TF file's name, or
  /// "edited" once its points were edited.
  std::string tf_label = "auto";
  std::string quality_note;   ///< what the last quality pick chose
  float tol_max = 1;  ///< upper end of the tolerance sliders (largest error of a step)
  Layout layout;            ///< this frame's layout (the volume's rectangle, docked panels)
  /// Per step: the share of the bricks its frame would read that are in RAM or textures
  /// (−1: not checked yet), for the timeline's marks.
  std::vector<float> ready;
  /// The last message shown in the UI (saved files, errors); set by the player's members and
  /// commands, never by a panel.
  const std::string& status_line() const { return status; }
  /// Shows an error in the status area (and on stderr): it stays until a message replaces it or
  /// the next action succeeds (cleared_by_action). Never throws but bad_alloc.
  void set_error(const std::string& what);
  /// True while the status area shows the last error set_error showed (drawn in red).
  bool status_is_error() const { return !error_status_.empty() && status == error_status_; }
  /// The controls overlay (F1 or ?) is shown.
  bool help_shown() const { return show_help_; }
  /// 1: open every section of the panels at the next frame; -1: back to how they start; 0: as
  /// the user left them (script `expand on|off`).
  int expand_sections = 0;
  /// What the tolerances buy, measured when they change: the shown step and view drawn
  /// off-screen at them and at 0 (at most 320 × 200).
  struct ToleranceReadout {
    tsp::Tolerances at{-1, -1};  ///< the tolerances measured (spatial −1: none yet)
    double ms = 0, exact_ms = 0;  ///< a frame at them, and at 0
    double mean_de = 0;           ///< mean ΔE of the picture at them against the one at 0
  } tol_readout;
  bool tol_readout_due = false;  ///< set_tolerances asks for a new readout
  /// The TF editor's histogram over d in `bins` bars (≥ 1) at the step shown, counted again only
  /// when the domain, the file or the bars change (a step's count reads bricks; the step it
  /// counted stays until then); an error empties the bars and goes to status. `stats`
  /// (tf_histogram) reports the last one. Never throws but bad_alloc.
  const EditorHistogram& editor_histogram(const tsp::ValueRange& d, int bins);
  /// Measures tol_readout (frame(), after the volume); errors go to status.
  void measure_tolerance();
  tsp::CameraParams initial_camera;     ///< what R resets the camera to

  // ---- statistics for the HUD ----
  tspgl::FrameReport last;
  std::deque<FrameSample> history;

  /// Applies a transfer function (from a file, preset or the editor) from the next frame on.
  void set_tf(const tsp::TransferFunction& next, bool resample_points);
  /// Switches the metric (the reference metric is computed in full, blocking).
  void set_metric(tsp::Metric m);
  /// Changes tolerances and drops textures no frame can use any more.
  void set_tolerances(tsp::Tolerances t);
  /// Sets the render setting `name` (a row of render/settings_table.h) from text — the one path
  /// for script lines and panel widgets; tolerances go through set_tolerances. Throws
  /// tsp::UsageError naming the setting and what it accepts.
  void set_setting(const std::string& name, const std::string& text);
  /// Sets the quality target while playing (mean ΔE against full quality; 0: none, the LOD cut
  /// holds the frame rate as when interacting) and tunes playback for it if not tuned yet for
  /// this file, field, TF, metric, settings and view size (tuning() meanwhile). Errors go to
  /// status.
  void apply_quality(double de);
  /// Fragments of the picture on screen: the last frame that drew any (a frame that reused the
  /// whole image draws none).
  std::int64_t picture_fragments() const { return picture_fragments_; }
  /// Distinct steps drawn per second over the last 2 s (playback's real rate; 0 until
  /// rate_measured()).
  double steps_shown_per_s() const;
  /// True once playback showed a second step since it started: a rate was measured.
  bool rate_measured() const;
  /// True while the rate readout says playback is slower than the speed (rate_readout.h: one
  /// steady answer, with hysteresis).
  bool rate_slow() const { return rate_readout_.slow(); }
  bool rate_playing_ = false;  ///< playing at the last frame (the rate restarts with playback)
  /// Seconds until playback's next step is due (0: due now); kIdleWaitSeconds when paused.
  double until_next_step() const;
  /// The playback tuning in progress, if any (for its progress bar).
  const tspgl::PlaybackTuner* tuning() const { return tuning_.tuner(); }
  /// The rung playing draws (meaningful while playing_rung()).
  const tspgl::RungChoice& rung_choice() const { return rungs_.choice(); }
  /// The tuned ladder (empty before the first tuning ends).
  const std::vector<tspgl::TunedRung>& tuned_rungs() const { return rungs_.ladder(); }
  /// True when frames are drawn with a tuned rung: playing with a quality target, tuned.
  bool playing_rung() const {
    return state_.playing && state_.quality > 0 && !rungs_.ladder().empty();
  }
  /// The rung a playing frame draws with a quality target: the chosen one, or before the first
  /// tuning ends tspgl::kProvisionalRung; null when not playing or without a target.
  const tspgl::Rung* rung_drawn() const;
  /// What playback does, as JSON: speed, target, the rung played and why, the tuned ladder.
  nlohmann::json playback_json() const;
  /// Writes the HUD's statistics as JSON to path (atomically). Throws tsp::IoError.
  void write_stats(const std::string& path) const;
  /// Recreates the renderer for a cache policy or budget change.
  void set_cache(bool on, double budget_mb);
  /// --trace: reports where the TF editor's canvas is on screen when it moves (for tests that
  /// drag its handles with real mouse events). Never throws.
  void trace_tf_canvas(float x, float y, float w, float h);
  /// Where the left button last went down, in window coordinates, as GLFW reported it (the
  /// cursor at the press, not at the frame: on a slow frame the mouse has moved on since).
  std::array<float, 2> left_press() const { return left_press_; }
  /// Goes to step t (clamped), pausing playback.
  void go_to(int t);
  /// Validates and carries out one command now (as script lines, keys and panels make them);
  /// errors go to status and stderr.
  void command(const Command& c);
  /// Queues a command for the frame loop to carry out after the panels are drawn (what panel
  /// widgets send: they read the state and never write it). Never throws but bad_alloc.
  void push(Command c) { pending_commands_.push_back(std::move(c)); }
  /// Number of steps of the file.
  int steps() const;
  /// The TF the player starts a file or field with: --tf placed as --tf-range says over f's data.
  /// Throws like tsp::transfer_function_from_arg.
  tsp::TransferFunction start_tf(const tsp::TspFile& f) const;
  /// Sets c's voxel size, origin and frame for the current field (tspgl::place_field).
  void place_camera(tsp::CameraParams& c) const;
  /// Stretches the axes by scale (exaggeration) from the next frame on.
  void set_scale(const std::array<double, 3>& scale);
  /// The axis stretch (--scale).
  const std::array<double, 3>& scale() const { return options_.scale; }
  /// True with --trace (stdout lines that tests read).
  bool tracing() const { return options_.trace; }
  /// Where S's pictures go and the Record dialog offers its movie: the folder a file was last
  /// saved to from a dialog (session, TF, movie), else beside the data (open_folder()); the
  /// working directory when that folder cannot be written. Absolute. Never throws but bad_alloc.
  std::string export_folder() const;
  /// The dataset and field part of saved files' names (S's pictures, movies): NAME_FIELD, NAME
  /// the input as the user named it without its known extensions (export_names.h).
  std::string export_stem() const;
  /// Saves the current volume frame as PNG (path chosen from the step) and reports it in status.
  void request_save();
  /// True when the last frame is at full quality: LOD off, or the idle refinement left no node
  /// with any error and the render target at full size.
  bool full_quality() const;
  /// Turns the LOD cut on or off (off: every frame at full resolution).
  void set_lod(bool on);
  /// Sets the LOD focus from a window pixel: the point of the view ray there at the depth of the
  /// volume's centre.
  void set_focus_at(double x, double y);

  // ---- clip probes (player_probes.cpp) ----
  /// The probe the gizmo moves (−1: none); the probes panel selects with cmd::SelectProbe.
  int selected_probe() const { return probe_selected_; }
  std::uint64_t probe_version = 0; ///< bumped on every probe change (interaction for the LOD)
  /// Adds a probe (selected); errors (more than ClipRegion::kMaxProbes) go to status.
  void add_probe(const tsp::Probe& p);
  /// A new probe of `kind` through the volume's centre, sized to it.
  tsp::Probe default_probe(tsp::Probe::Kind kind) const;
  /// Marks the probes changed (after editing them in place).
  void probes_changed() { ++probe_version; }

  // ---- files (player_files.cpp) ----
  /// File > Open: plays input (a .tsp file at once; any other input is built into the cache
  /// folder on a thread, with progress, then played) with build_options as play's command line
  /// takes them (PlayerOptions::parse_input_options; empty: play's own). Errors go to status.
  void open_input(const std::string& input, const std::string& field,
                  const std::string& build_options = "");
  /// The running File > Open build, if any (for its progress dialog).
  OpenJob* open_job() { return open_job_.get(); }
  /// Asks the running File > Open build to stop (no file is left).
  void cancel_open();
  /// File > Open's outcomes (its dialog stays open on a failure, the error shown in it).
  struct OpenOutcome {
    std::uint64_t ended = 0;  ///< opens that succeeded or failed so far
    std::string error;        ///< the last one's error ("": it opened)
  };
  const OpenOutcome& open_outcome() const { return open_outcome_; }  ///< see OpenOutcome
  /// Records that an open ended (error "": it opened); the window draws a few frames more, so
  /// the dialog it reopens settles (its path field takes the keys). Never throws but bad_alloc.
  void open_ended(const std::string& error) {
    ++open_outcome_.ended;
    open_outcome_.error = error;
    settle_frames_ = kSettleFrames;
  }
  /// Starts recording the volume (with its annotations) to a movie at path. Errors go to status.
  void start_recording(const std::string& path);
  /// Stops recording and writes the movie (waits for ffmpeg). Errors go to status.
  void stop_recording();
  /// True while recording; seconds recorded so far.
  bool recording() const { return recorder_ != nullptr; }
  double recorded_seconds() const;
  /// Saves the TF to path (our JSON). Errors go to status.
  void save_tf_as(const std::string& path);
  /// The file being played.
  const std::string& tsp_path() const { return options_.tsp_path; }
  /// Where File > Open starts: the folder of the input last opened, as the user named it (not
  /// the cache folder it was built into).
  std::string open_folder() const;
  /// Shows another field of the file (its own TF, kept per field; its bricks stream in through
  /// its own caches, kept while another field is shown). Throws tsp::UsageError for a field
  /// the file does not have, tsp::Error when it cannot be opened; nothing changes then.
  void switch_field(const std::string& name);
  /// The shown field's name.
  const std::string& field() const {
    return viewer_->file().fields()[std::size_t(viewer_->file().field_index())];
  }
  /// Milliseconds from the last field switch to its first complete frame (−1: none yet).
  double field_switch_ms = -1;

  /// A key press with modifiers from GLFW's callback: true when it is a shortcut it took —
  /// Ctrl+A (the text field with the focus selects all its text), Ctrl+O (File > Open) or
  /// Ctrl+Q (quit).
  /// Never throws.
  bool shortcut(int key, int mods);
  /// --trace: prints "trace: WHAT" (dialogs report what their fields hold). Never throws.
  void trace(const std::string& what) const;

  // ---- sessions (player_session.cpp; issue 47 item 4) ----
  /// What the window shows as a session (TF, camera, step, speed, probes, surface, scale, panels).
  Session capture_session() const;
  /// Saves the session to path (File > Save session..., save-session). Errors go to status.
  void save_session_as(const std::string& path);
  /// The file File > Save session offers: DATASET.session.json (export_names.h) in the folder a
  /// session was last saved to, or else in the data's folder (open_folder()).
  std::string session_offer() const;
  /// Where the session was restored from, its cache entry, any file ignored and the panels'
  /// open sections as the windows hold them, for stats.
  nlohmann::json session_json() const;

 private:
  void frame();
  /// True while something is to be drawn that is not on screen yet (playing, a script, the LOD
  /// refinement, uploads, calibration, an open, a recording, input settling).
  bool busy() const;
  void start_tuning();    // a new tuning for what is shown (errors to status)
  void advance_tuning();  // one slice of the playback tuning; (re)starts it when out of date
  void begin_tuning();    // (re)starts the tuning when out of date, no picture yet
  void choose_rung(double now_s);  // the rung the next playing frame draws
  void measured_rung(double render_ms);  // the window's time for the rung it drew
  void advance_playback(double dt);
  void handle_input();
  void run_script();
  void draw_ui();  // player_ui.cpp
  void render_volume();
  void save_pending_shot();
  /// The volume's pixels as shown (the layout's view rectangle), top row first.
  tsp::Image read_view();
  /// The one export look of S and the recorder: read_view() with the annotations (outline,
  /// axes, legend titled with the field, step and time) unless they are turned off.
  tsp::Image export_view();
  /// S's file name: NAME_FIELD_step_NNNN.png in export_folder() (NAME: the input as the user
  /// named it), made absolute, with -2, -3, … rather than over an existing file.
  std::string export_name() const;
  /// Swaps in the .tsp file at path (File > Open): new tree, renderer, metric, TF and camera.
  void open_file(const std::string& path);
  void poll_open();                  // a finished File > Open build: play it or report
  void record_frame(double now_s);   // appends this frame to the movie while recording
  void update_ready(const tsp::Camera& cam, const tspgl::RenderSettings& frame_settings,
                    tsp::LodStops stops);
  // Probes (player_probes.cpp): hands them to the renderer when they changed; moves the
  // selected one with the mouse (ctrl: drag moves, wheel resizes; alt: drag turns) and returns
  // true when it took the mouse; outlines it over the volume.
  void apply_probes();
  bool probe_gizmo(const tsp::Camera& cam);
  void draw_probe_overlay(const tsp::Camera& cam);
  std::uint64_t applied_probe_version_ = ~std::uint64_t(0);
  std::uint64_t applied_probe_tf_ = ~std::uint64_t(0);
  void trace_changes();  // --trace: prints what changed since the last frame
  void apply_key(int key);  // one key press (or repeat) from the queue

  /// The current metric as frames read it (the reference metric brought up to date first).
  tsp::FrameMetric& frame_metric();
  void request_prefetch(const tsp::Camera& cam, const tspgl::RenderSettings& frame_settings,
                        tsp::LodStops stops);
  void make_renderer();
  void update_tol_max();
  // LOD (player_lod.cpp): the cut this frame asks for (interaction holds the target frame
  // rate, idle refines to full quality), what the drawn cut did, the frame's time outside
  // rendering.
  tspgl::LodSpec lod_spec(double now_s);
  void lod_drawn(const std::optional<tsp::LodFrameStats>& stats, double now_s);
  void measured_lod(double render_ms, double frame_ms);
  /// The frame driver of the current renderer (made on first use after a renderer change).
  tspgl::FrameDriver& driver();
  void draw_cut_overlay(const tsp::Camera& cam);
  /// With the cut shown (L): keeps the cut the frame drew (empty stops: every leaf).
  void keep_drawn_cut(tsp::LodStops stops);
  std::string traced_cut_;                  ///< the cut caption last traced
  void draw_annotations(const tsp::Camera& cam);

  PlayerState state_;  ///< see state(); written by the members and CommandApplier only
  std::vector<tsp::TfPoint> tf_points_;  ///< see tf_points()
  TfHandles tf_handles_;  ///< where tf_points_ were placed and the TF then (edits warp it)
  /// Rebuilds the TF from tf_points_ (a tf-point command).
  void apply_tf_points();
  PlayerOptions options_;
  /// The player's one clock (seconds since it started): frame times, playback, waits, the
  /// LOD's idle delay, recordings.
  tsp::Stopwatch clock_;
  /// Key presses and repeats GLFW reported since the last frame, in order (filled by the key
  /// callback during glfwPollEvents on this thread): every tap counts however slow a frame is,
  /// which Dear ImGui 1.86's per-frame key state cannot promise.
  /// Every input event for Dear ImGui, handed to it a frame's worth at a time (input_queue.h).
  InputQueue input_queue_;
  void install_callbacks();  // the window's GLFW callbacks, queueing every event
  void feed_imgui(const InputFrame& in);  // this frame's share of the queue, into ImGuiIO
  std::uint64_t events_ = 0;       ///< window events so far (every GLFW callback counts one)
  std::uint64_t events_seen_ = 0;  ///< events_ at the last frame
  int settle_frames_ = 0;          ///< frames still drawn after the last event
  std::int64_t frames_drawn_ = 0;  ///< frames drawn since the start
  std::int64_t idle_waits_ = 0;    ///< waits that ended with nothing to draw
  std::array<float, 2> left_press_{-1, -1};
  std::array<float, 2> cursor_{-1, -1};  ///< the last motion event's position
  std::array<float, 4> traced_canvas_{-1, -1, -1, -1};  ///< the last traced TF canvas rect
  /// Frame delay for tests (--frame-delay-ms): sleeps this long every frame.
  double frame_delay_ms_ = 0;
  /// What --trace compares from frame to frame.
  struct Traced {
    int step = -1;
    std::uint64_t tf_version = 0;
    tsp::Tolerances tol{-1, -1};
    tsp::Metric metric = tsp::Metric::approximate;
    bool playing = false, lod_on = true, panels = true;
    bool first = true;
  } traced_;
  std::vector<ScriptLine> script_;
  std::size_t script_pos_ = 0;
  int wait_frames_ = 0;
  double wait_until_s_ = 0;  ///< wait-seconds: the script resumes at this clock_ reading
  std::string pending_shot_;      ///< screenshot to save after the next complete frame
  bool pending_with_ui_ = false;  ///< pending_shot_ includes the UI panels
  bool save_requested_ = false;
  bool quit_ = false;
  bool imgui_ = false;
  PlaybackClock playback_clock_;  ///< playback's fraction of a step (playback_clock.h)
  bool speed_chosen_ = false;  ///< --speed or a speed command: kept; else default_speed per file
  int prefetched_for_ = -1;  ///< step whose successors were last requested
  int prefetched_cut_ = -1;  ///< cut size whose likely splits were last requested
  double start_s_ = 0, last_frame_s_ = 0;
  std::unique_ptr<OpenJob> open_job_;
  OpenOutcome open_outcome_;  ///< see open_outcome()
  /// What a tuning is for now (playback_tuning.h).
  TuneKey tune_key() const;
  /// What a tuning at view depends on, for the tuning cache on disk (jobs/tuning_cache.h).
  nlohmann::json tuning_disk_key(const tsp::CameraParams& view) const;
  PlaybackTuning tuning_;  ///< the tuning in progress and its stats (playback_tuning.h)
  int drawn_tuning_step_ = -1;  ///< the step shown at the last tuning frame
  RungPicker rungs_;  ///< the last complete tuning's ladder and the rung playing draws
  RateReadout rate_readout_;            ///< steps shown per second while playing, slow or not
  int last_shown_step_ = -1;
  std::int64_t picture_fragments_ = 0;  ///< see picture_fragments()
  std::unique_ptr<Recorder> recorder_;
  FieldShelf parked_;  ///< fields switched away from, kept with their renderers
  /// The programs every renderer of this window shares.
  std::shared_ptr<tspgl::SliceCompositor> compositor_;
  double switch_started_s_ = -1;  ///< when the last switch began (−1: reported)
  int ready_next_ = 0;  ///< the next step update_ready checks
  /// What changed last (interaction), the frame's time outside rendering, the focus, the drawn
  /// cut and its stats, for the LOD target (lod_loop.h).
  LodLoop lod_loop_;
  // Sessions (player_session.cpp): the input's entry in the cache folder ("": none, or
  // --no-session), where the shown session came from ("": defaults), why an entry was ignored,
  // and the sections to open once their windows exist.
  std::string session_file_, session_from_, session_note_;
  std::string session_input_;  ///< the input the entry is for, as named (absolute)
  nlohmann::json pending_ui_open_ = nlohmann::json::object();
  /// Restores the input's session (at the start: --session FILE, which throws, else the cache
  /// entry; a bad entry is reported and ignored) and says so in status.
  void restore_session(bool at_start);
  /// Throws tsp::FormatError naming origin when s cannot apply to this file (a field it lacks,
  /// a bad probe or TF).
  void check_session(const Session& s, const std::string& origin) const;
  /// Applies a checked session; with command_line, what play's command line named wins.
  void apply_session(const Session& s, bool command_line);
  /// Writes the session to the input's cache entry (quit, File > Open). Errors to status.
  void save_session_entry();
  /// Opens the sections a restored session had open, in the windows that exist now; with
  /// --trace, says when the sections open change ("trace: open sections {...}").
  void apply_pending_ui();
  std::string traced_sections_ = "{}";

  // ---- no popping (player_refine.cpp; docs/player.md "Level of detail") ----
 public:
  /// What the last frame drew, for the LOD status line, `stats` and `capture`: "playing",
  /// "interacting" (the LOD cut), "refining" (full-quality bands over a picture within the
  /// target), "full" or "off" (LOD off: full resolution every frame).
  const std::string& picture_stage() const { return stage_; }
  /// True when the picture on screen is within the quality target of the full-quality picture
  /// (what the recorder writes; a frame that is not repeats the last one that was).
  bool picture_within_target() const { return within_; }
  /// The LOD status line: what the last frame drew and its time.
  std::string lod_line() const;
  /// What the refinement did, as JSON (for stats and capture).
  nlohmann::json refine_json() const;

 private:
  // Draws this frame by the progressive refinement when it applies (paused after playing, or
  // settled after a change): true when it drew (drawn filled).
  bool refine_draw(double now_s, tspgl::FrameRequest& request, tspgl::DrawnFrame& drawn);
  // A frame drawn by the cut (or at full resolution with LOD off): its stage and whether it is
  // within the target (rung: drawn with the playing rung).
  void cut_drawn(bool rung);
  // The fastest tuned rung within the quality target for this view size (null: none cheaper
  // than full quality, or not tuned).
  const tspgl::TunedRung* base_rung() const;
  // Writes this frame to the capture folder (script `capture`).
  void capture_frame();
  tspgl::TileRefinement bands_;        ///< the bands left of the full-quality picture
  tspgl::PartialFrame part_;           ///< this frame's bands
  std::unique_ptr<tspgl::FrameDriver> full_driver_;  ///< full-resolution frames (no cut)
  const void* refine_renderer_ = nullptr;  ///< the renderer full_driver_ draws
  bool refine_on_ = false;     ///< a refinement is under way or done since the last change
  bool base_pending_ = false;  ///< the next refining frame draws base_rung() whole first
  bool whole_ = false;         ///< no picture within the target to draw bands over: all at once
  bool uploading_ = false;     ///< frames upload the full picture's textures before the bands
  std::string base_;           ///< what the bands are drawn over
  int refine_frames_ = 0;      ///< frames since the refinement started
  std::string stage_ = "interacting";
  bool within_ = false, was_within_ = false;  ///< this frame's and the last frame's picture
  std::string capture_dir_;    ///< script capture: the folder ("": off)
  int capture_count_ = 0;

  // ---- commands (player_commands.cpp) ----
  friend struct CommandApplier;  ///< carries out each command (apply())
  std::vector<Command> pending_commands_;  ///< pushed by the panels this frame
  /// Carries out the pushed commands in order (errors to status). Never throws but bad_alloc.
  void apply_commands();

  // ---- Space pauses on the step on screen (player_pause.cpp) ----
  /// Before a playing frame draws a new step: holds the picture on screen (the target's copy)
  /// and what the last frame reported with it.
  void hold_shown();
  /// After the frame is drawn, before it is shown: when a Space press for the player came
  /// meanwhile, the held picture and step are put back (the frame is dropped), so the pause
  /// the press makes stops on the step that was on screen, with its picture. True when it did.
  bool drop_for_space();
  struct Held {
    int step = -1;  ///< the held picture's step (−1: none)
    const void* renderer = nullptr;
    WindowRect view;
    tspgl::FrameReport report;
    tsp::LodFrameStats lod;
    bool within = false;
    std::int64_t fragments = 0;
  } held_;
  int drawn_step_ = -1;  ///< the step the last frame drew (−1: none)

  std::string last_session_folder_;  ///< where save_session_as last wrote ("": nowhere yet)
  std::string last_saved_folder_;    ///< where a dialog last saved a file ("": nowhere yet)

  // ---- stale errors (player_commands.cpp) ----
  std::string error_status_;     ///< the last error set_error showed
  std::uint64_t errors_ = 0;     ///< set_error calls so far
  /// After command c succeeded (errors_before: errors_ as it began): an error shown before it,
  /// still in the status area, is cleared when c is an action (not a wait, stats, screenshot,
  /// capture or quit) that showed no message of its own.
  void cleared_by_action(const Command& c, std::uint64_t errors_before);

  // ---- handshakes with a test driving the window (player_handshake.cpp) ----
  cmd::WaitFile wait_file_;       ///< wait-file: what the script waits for (path "": none)
  double wait_file_until_s_ = 0;  ///< ... and when it gives up (clock_)
  int wait_file_line_ = 0;        ///< ... and its script line
  bool wait_file_seen_ = false;   ///< it came: the events sent before it are being taken
  /// wait-file and signal as a script line makes them.
  void start_wait_file(const cmd::WaitFile& c, int line);
  void write_signal(const cmd::Signal& c, int line);
  /// True while a wait-file holds the script. Once the file exists: one round trip to the
  /// window system takes every event sent before it, then frames run until the input queue is
  /// empty and Dear ImGui has settled. Throws tsp::IoError (naming the line) past the timeout.
  bool waiting_for_file();
  /// True while a wait-file waits for a file that is not there yet (the window may sleep).
  bool file_not_there_yet() const;

  // ---- what the panels show but never write (panels send commands) ----
  std::string status;        ///< see status_line() (the members that set it keep its name)
  int probe_selected_ = -1;  ///< see selected_probe()
  bool show_help_ = false;   ///< see help_shown()
  EditorHistogram editor_histogram_;               ///< see editor_histogram()
  const void* editor_histogram_file_ = nullptr;    ///< the file it counted
  int editor_histogram_bins_ = 0;                  ///< its non-empty bars (stats)
};

/// Carries out one command on app (line: its script line for messages, 0: a key or a panel).
/// Throws tsp::Error (a tsp::UsageError naming the script line) when it cannot.
void apply(PlayerApp& app, const Command& c, int line = 0);

}  // namespace tspplayer
