#include "player/player.h"

// Our loader (gl/gl_api.h) declares the GL functions; GLFW must not pull in GL/gl.h.
#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>
#include <imgui.h>
#include <imgui_impl_glfw.h>
#include <imgui_impl_opengl3.h>

#include <algorithm>
#include <chrono>
#include <cfloat>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <thread>

#include "gl/gl_error.h"
#include "jobs/render_job.h"
#include "tsp/core/temp_output.h"
#include "player/imgui_gl_load.h"
#include "player/player_app.h"
#include "player/player_style.h"
#include "tsp/core/error.h"
#include "tsp/core/interrupt.h"
#include "tsp/core/stopwatch.h"
#include "tsp/frame/exaggeration.h"
#include "tsp/metric/compute_errors.h"
#include "tsp/metric/tf_io.h"
#include "tsp/report/image.h"

namespace tspplayer {

tspgl::RenderSettings default_player_settings() {
  tspgl::RenderSettings s;
  s.upload_budget = std::int64_t(kDefaultPlayerUploadMib * (1 << 20));
  return s;
}

void run_player(const PlayerOptions& options) {
  PlayerApp app(options);
  app.run();
}

PlayerApp::PlayerApp(const PlayerOptions& options) : options_(options) {
  if (options.width < 1 || options.height < 1)
    throw tsp::UsageError("--size must be positive, found " + std::to_string(options.width) + "x" +
                          std::to_string(options.height));
  viewer_ = std::make_unique<ViewerSession>(tsp::TspFile::open(options.tsp_path, options.field),
                                            tf, state_.metric);
  const tsp::TspTree& tree = viewer_->file().tree();
  if (options.step < 0 || options.step >= tree.time().steps())
    throw tsp::UsageError("--step " + std::to_string(options.step) + ": " + options.tsp_path +
                          " has steps 0.." + std::to_string(tree.time().steps() - 1));
  state_.step = options.step;
  if (!(options.frame_delay_ms >= 0 && options.frame_delay_ms <= kMaxFrameDelayMs))
    throw tsp::UsageError("--frame-delay-ms " + std::to_string(options.frame_delay_ms) +
                          ": expected 0.." + std::to_string(int(kMaxFrameDelayMs)));
  frame_delay_ms_ = options.frame_delay_ms;
  tspgl::validate(options.settings);
  if (!options.surface_mesh.empty())
    mesh_surface.emplace(options.surface_mesh, options.surface_field, viewer_->file(), options.surface_tf, options.step);
  surface_mesh_ = options.surface_mesh;
  state_.settings = options.settings;
  for (auto [value, name] : {std::pair{options.ram_budget_mb, "--ram-budget"},
                             std::pair{options.texture_budget_mb, "--texture-budget"}})
    if (!(value > 0) || !(value <= double(tspgl::kMaxBudgetBytes >> 20)))
      throw tsp::UsageError(std::string(name) + " " + std::to_string(value) +
                            ": expected a budget in (0, " +
                            std::to_string(tspgl::kMaxBudgetBytes >> 20) + "] MiB");
  state_.texture_budget_mb = options.texture_budget_mb;
  if (!(options.target_fps >= 1 && options.target_fps <= kMaxTargetFps))
    throw tsp::UsageError("--target-fps " + std::to_string(options.target_fps) + ": expected 1 to " +
                          std::to_string(int(kMaxTargetFps)) + " frames per second");
  state_.lod_on = options.lod;
  state_.target_fps = float(options.target_fps);
  if (options.speed != 0 && !(options.speed >= kMinSpeed && options.speed <= kMaxSpeed))
    throw tsp::UsageError("--speed " + std::to_string(options.speed) + ": expected " +
                          std::to_string(kMinSpeed).substr(0, 4) + " to " +
                          std::to_string(int(kMaxSpeed)) + " steps per second");
  speed_chosen_ = options.speed != 0;
  state_.speed = speed_chosen_ ? options.speed : default_speed(steps());
  if (!(options.quality >= 0 && options.quality <= tspgl::kMaxQualityDe))
    throw tsp::UsageError("--quality " + std::to_string(options.quality) +
                          ": expected a mean dE in [0, " +
                          std::to_string(int(tspgl::kMaxQualityDe)) + "] (0: off)");
  state_.quality = float(options.quality);  // tuned when playing starts
  state_.keep_quality = options.keep_quality;
  state_.splat_fallback = options.splat_fallback;
  state_.lod_filter = tsp::parse_lod_filter(options.lod_filter, "--lod-filter");
  if (!options.script.empty()) script_ = load_script(options.script);
  if (!options.screenshot.empty()) {
    script_.push_back({cmd::Screenshot{options.screenshot, false}, 0});
    script_.push_back({cmd::Quit{}, 0});
  }
  const tsp::TfRangeChoice range = tsp::parse_tf_range(options.tf_range);
  const tsp::ValueHistogram histogram = tsp::histogram_of(viewer_->file());
  tf = tsp::transfer_function_from_arg(
      options.tf, tsp::tf_domain_of(range, viewer_->file(), state_.step),
      tsp::kDefaultTfEntries, range, &histogram);
  if (std::string w = tsp::tf_range_warning(tf, viewer_->file().metadata().data_range); !w.empty()) {
    std::fprintf(stderr, "tspplay: warning: %s\n", w.c_str());
    status = tsp::tf_range_warning(tf, viewer_->file().metadata().data_range, "fit to data");  // (window)
  }
  viewer_->set_metric(state_.metric);  // (over the TF just made)
  set_tf(tf, true);
  tf_label = tf_label_of(options.tf);
  ready.assign(std::size_t(tree.time().steps()), -1.f);
  for (double k : options.scale)
    if (!(k > 0) || !(k <= tspgl::kMaxScale))
      throw tsp::UsageError("--scale: expected three factors in (0, " +
                            std::to_string(int(tspgl::kMaxScale)) + "], found " + std::to_string(k));
  // A flat domain (WRF's 480 km × 6 km) opens stretched in height, named on screen ("z × 30").
  // (--scale given: in options.given, which a restored session does not override either.)
  const bool scale_given =
      std::find(options.given.begin(), options.given.end(), "--scale") != options.given.end();
  if (!scale_given && options.physical_proportions)
    options_.scale = tsp::vertical_exaggeration(viewer_->file().frame());
  place_camera(state_.camera);
  for (const std::string& text : options.probes) state_.probes.push_back(tsp::parse_probe(text));
  state_.probe_op = tsp::parse_probe_op(options.probe_op);
  state_.probe_surface = options.probe_surface;
  (void)tsp::ClipRegion(state_.probes, state_.probe_op, viewer_->file().metadata().origin, viewer_->file().metadata().spacing);
  if (!state_.probes.empty()) probe_selected_ = 0;
  if (range.mode == tsp::TfRangeChoice::Mode::visible) {  // now that view and probes are known
    apply(*this, cmd::StretchTf{"visible"});
  }

  ctx = tspgl::create_window_context(options.width, options.height, "tspplay - " + (options.input_path.empty() ? options.tsp_path : options.input_path),
                                     true);
  make_renderer();

  IMGUI_CHECKVERSION();
  ImGui::CreateContext();
  ImGui::GetIO().IniFilename = nullptr;  // no imgui.ini in the user's directory
  apply_player_style(ImGui::GetStyle());  // (opaque popups)
  install_callbacks();
  glfwSwapInterval(1);  // vsync where the display has it (a virtual one has none)
  // Dear ImGui's back end installs no callbacks: ours queue every event (input_queue_), and
  // each frame hands ImGui what it can tell apart (frame()), so nothing is lost in a slow frame.
  ImGui_ImplGlfw_InitForOpenGL(static_cast<GLFWwindow*>(ctx->native_window()), false);
  if (const char* missing = tsp_imgui_gl_load(ctx->proc_address_function()))
    throw tsp::GlError(std::string("the GL entry point ") + missing +
                       " needed by the UI is missing");
  ImGui_ImplOpenGL3_Init("#version 330 core");
  imgui_ = true;
  update_tol_max();
  tol_readout_due = state_.settings.tol.spatial > 0 || state_.settings.tol.temporal > 0;
  start_s_ = last_frame_s_ = clock_.seconds();
  initial_camera = state_.camera;
  restore_session(true);  // the input's last session, or --session FILE (throws)
}

PlayerApp::~PlayerApp() {
  if (open_job_) {  // a File > Open build still running: stop it (it leaves no file)
    open_job_.reset();
  }
  if (recorder_) {  // the window closed while recording: keep what was recorded
    try {
      stop_recording();
      std::printf("%s\n", status.c_str());
    } catch (...) {
    }
  }
  if (imgui_) {
    ctx->make_current();
    ImGui_ImplOpenGL3_Shutdown();
    ImGui_ImplGlfw_Shutdown();
    ImGui::DestroyContext();
  }
  viewer_.reset();  // the renderer's GL objects go before the context
  parked_.clear();
  compositor_.reset();
}

void PlayerApp::make_renderer() {
  viewer_->make_renderer(
      *ctx, state_.cache_on ? tsp::CachePolicy::on : tsp::CachePolicy::off,
      std::int64_t(state_.texture_budget_mb * (1 << 20)), std::int64_t(options_.ram_budget_mb * (1 << 20)),
      compositor_);
  prefetched_for_ = -1;
  prefetched_cut_ = -1;
  applied_probe_version_ = ~std::uint64_t(0);  // the new renderer gets the probes
}

void PlayerApp::place_camera(tsp::CameraParams& c) const {
  tspgl::place_field(c, viewer_->file(), options_.scale, options_.physical_proportions);
}

void PlayerApp::set_scale(const std::array<double, 3>& scale) {
  const bool changed = scale != options_.scale;  // (one change, one trace line)
  options_.scale = scale;
  if (options_.trace && changed) {
    std::printf("trace: axis scale %g,%g,%g\n", scale[0], scale[1], scale[2]);
    std::fflush(stdout);
  }
  place_camera(state_.camera);
  place_camera(initial_camera);
}

int PlayerApp::steps() const {
  return viewer_->steps();
}

void PlayerApp::go_to(int t) {
  state_.playing = false;
  state_.step = std::clamp(t, 0, steps() - 1);
}

void PlayerApp::set_tf(const tsp::TransferFunction& next, bool resample_points) {
  if (&next != &tf) {
    if (next.size() == tf.size() && next.domain().lo == tf.domain().lo &&
        next.domain().hi == tf.domain().hi) {
      // Only the entries that differ are marked changed, so the lazy metric re-evaluates only
      // the nodes whose [j_min, j_max] they touch.
      int lo = -1, hi = -1;
      for (int j = 0; j < tf.size(); ++j)
        if (!(next.entry(j) == tf.entry(j))) {
          if (lo < 0) lo = j;
          hi = j;
        }
      if (lo >= 0)
        tf.set_entries(lo, next.entries().subspan(std::size_t(lo), std::size_t(hi - lo + 1)));
    } else {
      tf.assign(next);  // (its version grows: a copy took next's, and fits after the first
                        // went unseen by the LOD loop, the tuning, the metric and --trace)
      viewer_->tf_replaced();
    }
  }
  if (resample_points) {  // the editor's handles over the TF as it now is
    tf_handles_ = place_handles(tf);
    tf_points_ = tf_handles_.placed;
  }
  if (viewer_->has_renderer()) viewer_->renderer().set_transfer_function(tf);
}

std::string tf_label_of(const std::string& tf_arg) {
  if (tf_arg.empty()) return "auto";
  if (tf_arg.rfind("preset:", 0) == 0) return tf_arg.substr(7);
  return std::filesystem::path(tf_arg).filename().string();
}

void PlayerApp::apply_tf_points() {
  tf_label = "edited";
  // The TF warped in place by the handles' moves (the detailed curve keeps its shape).
  set_tf(warp_handles(tf_handles_, tf_points_), false);
}

// During playback: the bricks the frames of the next kPrefetchSeconds would upload, in playing
// order, go to the prefetch thread once per step change (the request replaces the previous one).
void PlayerApp::request_prefetch(const tsp::Camera& cam, const tspgl::RenderSettings& frame_settings,
                                 tsp::LodStops stops) {
  if (!state_.prefetch_on) return;
  // Holding still or turning: the bricks the cut's next splits will want, at this step, once per
  // cut change (the RAM cache then serves the split's uploads).
  if (!state_.playing) {
    const tsp::LodController* lod = driver().controller();
    if (!lod || lod_loop_.stats().cut_size == prefetched_cut_) return;
    prefetched_cut_ = lod_loop_.stats().cut_size;
    std::vector<tsp::BrickKey> keys;
    for (int b : lod->likely_split_bricks(kPrefetchSplits)) keys.push_back({b, state_.step});
    viewer_->prefetcher().request(std::move(keys));
    return;
  }
  if (prefetched_for_ == state_.step) return;
  prefetched_for_ = state_.step;
  std::vector<tsp::BrickKey> keys;
  const int ahead = std::clamp(int(std::ceil(state_.speed * kPrefetchSeconds)), kMinPrefetchSteps,
                              kMaxPrefetchSteps);
  for (int k = 1; k <= ahead; ++k) {
    int t = state_.step + k;
    if (t >= steps()) {
      if (!state_.loop) break;
      t %= steps();
    }
    std::vector<tsp::BrickKey> more =
        viewer_->renderer().bricks_to_upload(t, cam, frame_settings, frame_metric(), stops);
    keys.insert(keys.end(), more.begin(), more.end());
    if (const tsp::LodController* lod = driver().controller())  // and its likely next splits
      for (int b : lod->likely_split_bricks(kPrefetchSplits)) keys.push_back({b, t});
  }
  viewer_->prefetcher().request(std::move(keys));
}

void PlayerApp::request_save() {
  save_requested_ = true;
}

tsp::FrameMetric& PlayerApp::frame_metric() {
  return viewer_->frame_metric();
}

void PlayerApp::render_volume() {
  state_.camera.width = layout.view.w;
  state_.camera.height = layout.view.h;
  if (state_.camera.width < 1 || state_.camera.height < 1 || ctx->width() < 1 || ctx->height() < 1)
    return;  // minimised
  const tsp::Camera cam(viewer_->file().tree().octree().dims(), state_.camera);
  tspgl::RenderSettings fs = state_.settings;
  // Playing, a step's frame uploads all it needs: shown late when its bricks are late, never
  // with holes of bricks left for later frames (the upload budget keeps interaction smooth).
  if (state_.playing) fs.upload_budget = 0;
  // GL's window coordinates start at the bottom: the view's lower-left corner.
  fs.viewport_origin = {layout.view.x, ctx->height() - layout.view.y - layout.view.h};
  viewer_->evaluate_step(state_.step);  // (the HUD shows what it cost)
  const double now = clock_.seconds();
  choose_rung(now);
  const bool rung = playing_rung();  // playing at a quality target: the tuned rung's frame
  if (const tspgl::Rung* r = rung_drawn()) fs = tspgl::rung_settings(fs, *r);
  tspgl::FrameDriver& d = driver();
  const tspgl::LodSpec spec = lod_spec(now);
  tspgl::FrameRequest request;
  request.step = state_.step;
  request.camera = &cam;
  request.settings = fs;
  request.metric = &frame_metric();
  request.tf = &tf;
  if (mesh_surface && fs.surface)  // (a step's mesh is read only while it is shown)
    viewer_->renderer().compositor()->set_surface(mesh_surface->frame(state_.step, fs.surface_px));
  was_within_ = within_;
  tspgl::DrawnFrame drawn;
  // Paused after playing, or settled after a change: full-resolution bands over a picture
  // within the target (player_refine.cpp); otherwise the cut the LOD spec asks for.
  const bool refined = refine_draw(now, request, drawn);
  if (!refined) {
    d.set_lod(spec);
    drawn = d.draw(request);
    cut_drawn(rung);
  }
  last = drawn.report;
  if (rung) measured_rung(last.ms);
  if (last.redrawn_percent > 0) picture_fragments_ = last.fragments;
  lod_drawn(drawn.lod, now);
  if (!refined && stage_ == "interacting" && full_quality()) within_ = true;  // (the cut refined)
  const tsp::LodStops stops = refined ? tsp::LodStops{} : d.current_stops();
  keep_drawn_cut(stops);
  request_prefetch(cam, drawn.settings, stops);
  update_ready(cam, drawn.settings, stops);
}

tspgl::FrameDriver& PlayerApp::driver() {
  return viewer_->driver();
}

// A few steps a frame, round robin: how much of what each step's frame would upload is in RAM
// already (1 when its textures are all resident).
void PlayerApp::update_ready(const tsp::Camera& cam, const tspgl::RenderSettings& frame_settings,
                             tsp::LodStops stops) {
  const int n = steps();
  for (int k = 0; k < std::min(n, kReadyStepsPerFrame); ++k) {
    const int t = ready_next_;
    ready_next_ = (ready_next_ + 1) % n;
    const std::vector<tsp::BrickKey> keys =
        viewer_->renderer().bricks_to_upload(t, cam, frame_settings, frame_metric(), stops);
    int in_ram = 0;
    for (const tsp::BrickKey& key : keys) in_ram += viewer_->renderer().brick_cache().contains(key.brick, key.step);
    ready[std::size_t(t)] = keys.empty() ? 1.f : float(in_ram) / float(keys.size());
  }
}

tsp::Image PlayerApp::read_view() {
  const WindowRect& v = layout.view;
  return ctx->read_pixels(v.x, ctx->height() - v.y - v.h, v.w, v.h);
}

void PlayerApp::save_pending_shot() {
  tsp::write_png(pending_shot_, pending_with_ui_ ? ctx->read_pixels() : read_view());
  std::printf("saved %s (step %d)\n", pending_shot_.c_str(), state_.step);
  std::fflush(stdout);
  pending_shot_.clear();
}

void PlayerApp::frame() {
  ctx->poll_events();
  // An input event: Dear ImGui needs a few frames to settle (hover, popups, animations).
  if (events_ != events_seen_) {
    events_seen_ = events_;
    settle_frames_ = kSettleFrames;
  } else if (settle_frames_ > 0) {
    --settle_frames_;
  }
  ++frames_drawn_;
  const double now = clock_.seconds();
  const double dt = now - last_frame_s_;
  last_frame_s_ = now;
  const tsp::Stopwatch t_frame;

  ImGui_ImplOpenGL3_NewFrame();
  ImGui_ImplGlfw_NewFrame();
  feed_imgui(input_queue_.take());
  ImGui::NewFrame();
  // The volume's rectangle: beside the docked panels, or the whole window (again below, after
  // keys and script actions that may show or hide the panels).
  layout = compute_layout(ctx->width(), ctx->height(), state_.panels, int(ImGui::GetFrameHeight()));
  poll_open();
  run_script();
  if (quit_) {
    ImGui::EndFrame();
    return;
  }
  handle_input();
  advance_playback(dt);
  if (options_.trace) trace_changes();
  layout = compute_layout(ctx->width(), ctx->height(), state_.panels, int(ImGui::GetFrameHeight()));
  if (layout.docked) {  // what the volume does not cover is the panels' background
    const tspgl::GlApi& gl = ctx->gl();
    gl.BindFramebuffer(GL_FRAMEBUFFER, 0);
    gl.Viewport(0, 0, ctx->width(), ctx->height());
    gl.ClearColor(0, 0, 0, 1);
    gl.Clear(GL_COLOR_BUFFER_BIT);
  }
  apply_probes();
  hold_shown();  // (playing: the picture on screen, for a Space press while this frame draws)
  render_volume();
  if (!(state_.playing && !rate_playing_)) advance_tuning();  // (not in playback's first frame)
  if (tol_readout_due && imgui_) measure_tolerance();
  if (frame_delay_ms_ > 0)
    std::this_thread::sleep_for(std::chrono::duration<double, std::milli>(frame_delay_ms_));
  drop_for_space();  // Space went down while this frame drew: the step on screen stays
  drawn_step_ = state_.step;
  capture_frame();
  if (state_.playing != rate_playing_) {  // playback's rate is measured from its start on
    rate_playing_ = state_.playing;
    rate_readout_.restart();
    last_shown_step_ = -1;
  }
  const bool shown = state_.step != last_shown_step_;  // playback's real rate: distinct steps
  last_shown_step_ = state_.step;
  rate_readout_.frame(now, shown, state_.speed);

  // Screenshots hold the volume only (read before the UI is drawn).
  // A screenshot waits for the first complete frame (no texture left for later frames).
  // With the LOD cut it also waits for full quality (the idle refinement), unless playing.
  const bool full = state_.playing || full_quality();
  const bool shot_now = !pending_shot_.empty() && last.complete() && full;
  if (shot_now && !pending_with_ui_) save_pending_shot();
  if (save_requested_) {
    save_requested_ = false;
    const std::string name = export_name();
    try {
      tsp::write_png(name, export_view());
      status = "saved " + name;
    } catch (const tsp::Error& e) {
      status = e.what();
    }
    std::printf("%s\n", status.c_str());
    std::fflush(stdout);  // (a log read while the window runs sees it)
  }

  if (recorder_) record_frame(now);
  if (switch_started_s_ >= 0 && last.complete() && (state_.playing || full_quality())) {
    field_switch_ms = (clock_.seconds() - switch_started_s_) * 1000;  // the new field's first frame
    switch_started_s_ = -1;
  }
  if (state_.camera.width > 0 && state_.camera.height > 0) {
    const tsp::Camera cam(viewer_->file().tree().octree().dims(), state_.camera);
    draw_cut_overlay(cam);
    draw_annotations(cam);
    if (state_.panels) draw_probe_overlay(cam);
  }
  apply_pending_ui();  // a restored session's open sections
  draw_ui();
  apply_commands();  // what the panels sent
  ImGui::Render();
  ctx->gl().BindFramebuffer(GL_FRAMEBUFFER, 0);
  ctx->gl().Viewport(0, 0, ctx->width(), ctx->height());
  ImGui_ImplOpenGL3_RenderDrawData(ImGui::GetDrawData());
  if (shot_now && !pending_shot_.empty()) save_pending_shot();
  ctx->swap_buffers();

  measured_lod(last.ms - last.upload_ms, t_frame.ms());
  history.push_back({now - start_s_, t_frame.ms()});
  tuning_.frame_drawn(t_frame.ms(), state_.playing ? 1000 / std::max(state_.speed, 1e-3) : 0);
  while (!history.empty() && history.front().at_s < now - start_s_ - kFrameHistorySeconds)
    history.pop_front();
}

bool PlayerApp::busy() const {
  // A script waiting out wait-seconds is not busy: the window sleeps as when idle, waking for
  // the script's clock (run() waits at most until wait_until_s_).
  const bool script_running =
      (script_pos_ < script_.size() && clock_.seconds() >= wait_until_s_ && !file_not_there_yet()) ||
      wait_frames_ > 0;
  // Playing draws a frame when a step is due, not in between: a frame faster than the step
  // period would draw the same step again, and a coarse playing rung is not refined meanwhile.
  const bool step_due = state_.playing && until_next_step() <= 0;
  return quit_ || step_due || settle_frames_ > 0 || input_queue_.pending() || script_running || !pending_shot_.empty() ||
         save_requested_ || (tuning_.tuner() && !tuning_.waiting()) || open_job_ || recorder_ || !last.complete() ||
         (!state_.playing && state_.lod_on && !full_quality()) || switch_started_s_ >= 0;
}

void PlayerApp::run() {
  int frames = 0;
  while (!quit_ && !ctx->should_close()) {
    tsp::throw_if_interrupted();  // SIGINT/SIGTERM: unwind; a recording in progress is dropped
    // Nothing to show that is not shown already: sleep until an event (or a timeout, for the
    // window's own timers), and draw only when something came.
    if (!busy()) {
      const std::uint64_t before = events_;
      const double to_script = wait_until_s_ - clock_.seconds();
      ctx->wait_events(std::min({to_script > 0 ? to_script : kIdleWaitSeconds, kIdleWaitSeconds,
                                  until_next_step(),
                                  file_not_there_yet() ? kFilePollSeconds : kIdleWaitSeconds}));
      if (events_ == before && !busy()) {
        ++idle_waits_;
        continue;
      }
    }
    frame();
    ++frames;
  }
  save_session_entry();  // quit or closed: the next window on this input starts here
  const tsp::BrickCacheStats b = viewer_->renderer().brick_cache().stats();
  std::printf("played %d frames; bricks: %lld hits, %lld misses, %lld prefetched\n", frames,
              static_cast<long long>(b.hits), static_cast<long long>(b.misses),
              static_cast<long long>(b.prefetched));
}

}  // namespace tspplayer
