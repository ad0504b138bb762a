#include "player/player.h"

// Our loader (gl/gl_api.h) declares the GL functions; GLFW must not pull in GL/gl.h.
#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>
#include <imgui.h>
#include <imgui_impl_glfw.h>
#include <imgui_impl_opengl3.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <thread>

#include "gl/gl_error.h"
#include "jobs/calibration.h"
#include "jobs/render_job.h"
#include "tsp/core/json_text.h"
#include "tsp/core/memory_use.h"
#include "tsp/core/temp_output.h"
#include "player/imgui_gl_load.h"
#include "player/player_app.h"
#include "tsp/core/error.h"
#include "tsp/core/stopwatch.h"
#include "tsp/metric/compute_errors.h"
#include "tsp/metric/tf_io.h"
#include "tsp/report/image.h"

namespace tspplayer {

namespace {

constexpr float kMinToleranceCeiling = 1e-3f;
constexpr float kKnotEpsilon = 1e-4f;  // slope change that marks a TF knot
constexpr int kMaxEditorPoints = 24;
constexpr double kMaxFrameDt = 0.25;  // a stalled frame does not skip many steps at once

// Largest finite error in e: the tolerance sliders' upper end (a tolerance above every error
// draws the root only).
float largest_error(const tsp::NodeErrors& e) {
  float m = 0;
  for (const auto* v : {&e.spatial, &e.temporal})
    for (float x : *v)
      if (std::isfinite(x)) m = std::max(m, x);
  return std::max(m, kMinToleranceCeiling);
}

// The TF's knots: the first and last entries and every entry where the table's slope changes, so
// that rebuilding from them reproduces a piecewise-linear TF (presets, our JSON). A TF with more
// knots than kMaxEditorPoints gets kEditorPoints evenly spaced samples instead.
std::vector<tsp::TfPoint> editor_points(const tsp::TransferFunction& tf) {
  const int n = tf.size();
  std::vector<tsp::TfPoint> pts;
  auto slope_changes = [&tf](int j) {
    const tsp::Rgba a = tf.entry(j - 1), b = tf.entry(j), c = tf.entry(j + 1);
    const float d[4] = {(c.r - b.r) - (b.r - a.r), (c.g - b.g) - (b.g - a.g),
                        (c.b - b.b) - (b.b - a.b), (c.a - b.a) - (b.a - a.a)};
    for (float v : d)
      if (std::fabs(v) > kKnotEpsilon) return true;
    return false;
  };
  // A knot between two entry centres bends the table at both: each run of bending entries is
  // one knot, placed mid-run (a 5-point file shows 5 handles, not 8).
  for (int j = 0; j < n; ++j) {
    if (j == 0 || j == n - 1) {
      pts.push_back({tf.entry_value(j), tf.entry(j)});
      continue;
    }
    if (!slope_changes(j)) continue;
    int last = j;
    while (last + 1 < n - 1 && slope_changes(last + 1)) ++last;
    const double x = 0.5 * (tf.entry_value(j) + tf.entry_value(last));
    pts.push_back({x, tf.lookup(x)});
    j = last;
  }
  if (int(pts.size()) <= kMaxEditorPoints) return pts;
  pts.clear();
  const tsp::ValueRange d = tf.domain();
  for (int i = 0; i < kEditorPoints; ++i) {
    const double x = d.lo + (d.hi - d.lo) * i / (kEditorPoints - 1);
    pts.push_back({x, tf.lookup(x)});
  }
  return pts;
}

}  // namespace

void run_player(const PlayerOptions& options) {
  PlayerApp app(options);
  app.run();
}

PlayerApp::PlayerApp(const PlayerOptions& options) : options_(options) {
  if (options.width < 1 || options.height < 1)
    throw tsp::UsageError("--size must be positive, found " + std::to_string(options.width) + "x" +
                          std::to_string(options.height));
  file = tsp::TspFile::open(options.tsp_path, options.field);
  const tsp::TspTree& tree = file->tree();
  if (options.step < 0 || options.step >= tree.time().steps())
    throw tsp::UsageError("--step " + std::to_string(options.step) + ": " + options.tsp_path +
                          " has steps 0.." + std::to_string(tree.time().steps() - 1));
  step = options.step;
  if (!(options.frame_delay_ms >= 0 && options.frame_delay_ms <= kMaxFrameDelayMs))
    throw tsp::UsageError("--frame-delay-ms " + std::to_string(options.frame_delay_ms) +
                          ": expected 0.." + std::to_string(int(kMaxFrameDelayMs)));
  frame_delay_ms_ = options.frame_delay_ms;
  if (!(options.upload_budget_mb >= 0) ||
      !(options.upload_budget_mb <= double(tspgl::kMaxBudgetBytes >> 20)))
    throw tsp::UsageError("--upload-budget " + std::to_string(options.upload_budget_mb) +
                          ": expected 0 (no limit) to " +
                          std::to_string(tspgl::kMaxBudgetBytes >> 20) + " MiB per frame");
  upload_budget_mb = options.upload_budget_mb;
  for (auto [value, name] : {std::pair{options.ram_budget_mb, "--ram-budget"},
                             std::pair{options.texture_budget_mb, "--texture-budget"}})
    if (!(value > 0) || !(value <= double(tspgl::kMaxBudgetBytes >> 20)))
      throw tsp::UsageError(std::string(name) + " " + std::to_string(value) +
                            ": expected a budget in (0, " +
                            std::to_string(tspgl::kMaxBudgetBytes >> 20) + "] MiB");
  texture_budget_mb = options.texture_budget_mb;
  if (!(options.target_fps >= 1 && options.target_fps <= kMaxTargetFps))
    throw tsp::UsageError("--target-fps " + std::to_string(options.target_fps) + ": expected 1 to " +
                          std::to_string(int(kMaxTargetFps)) + " frames per second");
  lod_on = options.lod;
  target_fps = float(options.target_fps);
  splat_fallback = options.splat_fallback;
  if (!options.script.empty()) script_ = load_script(options.script);
  if (!options.screenshot.empty()) {
    ScriptAction shot;
    shot.kind = ScriptAction::Kind::screenshot;
    shot.text = options.screenshot;
    script_.push_back(shot);
    script_.push_back(ScriptAction{});  // quit
  }
  tf = tsp::transfer_function_from_arg(options.tf, tree.value_range(), tsp::kDefaultTfEntries,
                                       tsp::parse_tf_range(options.tf_range));
  if (std::string w = tsp::tf_range_warning(tf, file->metadata().data_range); !w.empty()) {
    std::fprintf(stderr, "tspplay: warning: %s\n", w.c_str());
    status = w;
  }
  lazy_ = std::make_unique<tsp::LazyErrors>(tree, metric, tf);
  set_tf(tf, true);
  ready.assign(std::size_t(tree.time().steps()), -1.f);
  for (double k : options.scale)
    if (!(k > 0) || !(k <= tspgl::kMaxScale))
      throw tsp::UsageError("--scale: expected three factors in (0, " +
                            std::to_string(int(tspgl::kMaxScale)) + "], found " + std::to_string(k));
  camera.voxel_size = voxel_size();
  for (const std::string& text : options.probes) probes.push_back(tsp::parse_probe(text));
  probe_op = tsp::parse_probe_op(options.probe_op);
  probe_surface = options.probe_surface;
  (void)tsp::ClipRegion(probes, probe_op, file->metadata().origin, file->metadata().spacing);
  if (!probes.empty()) probe_selected = 0;

  ctx = tspgl::create_window_context(options.width, options.height, "tspplay - " + options.tsp_path,
                                     true);
  make_renderer();

  IMGUI_CHECKVERSION();
  ImGui::CreateContext();
  ImGui::GetIO().IniFilename = nullptr;  // no imgui.ini in the user's directory
  ImGui::StyleColorsDark();
  // Our key callback first: ImGui's back end keeps it and calls it before its own.
  GLFWwindow* window = static_cast<GLFWwindow*>(ctx->native_window());
  glfwSetWindowUserPointer(window, this);
  glfwSetKeyCallback(window, [](GLFWwindow* w, int key, int, int action, int) {
    if (action == GLFW_PRESS || action == GLFW_REPEAT)
      static_cast<PlayerApp*>(glfwGetWindowUserPointer(w))->key_queue_.push_back(key);
  });
  // The cursor as motion events report it, in order (glfwGetCursorPos asks X for the pointer
  // now, after every queued event): so a press knows where it happened.
  glfwSetCursorPosCallback(window, [](GLFWwindow* w, double x, double y) {
    static_cast<PlayerApp*>(glfwGetWindowUserPointer(w))->cursor_ = {float(x), float(y)};
  });
  glfwSetMouseButtonCallback(window, [](GLFWwindow* w, int button, int action, int) {
    if (button != GLFW_MOUSE_BUTTON_LEFT || action != GLFW_PRESS) return;
    auto* app = static_cast<PlayerApp*>(glfwGetWindowUserPointer(w));
    app->left_press_ = app->cursor_;
  });
  ImGui_ImplGlfw_InitForOpenGL(window, true);
  if (const char* missing = tsp_imgui_gl_load(ctx->proc_address_function()))
    throw tsp::GlError(std::string("the GL entry point ") + missing +
                       " needed by the UI is missing");
  ImGui_ImplOpenGL3_Init("#version 330 core");
  imgui_ = true;
  update_tol_max();
  start_s_ = last_frame_s_ = glfwGetTime();
  initial_camera = camera;
}

PlayerApp::~PlayerApp() {
  if (open_job_) {  // a File > Open build still running: stop it (it leaves no file)
    open_job_->cancel = true;
    open_job_->thread.join();
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
  prefetcher.reset();  // its thread reads into the renderer's brick cache
  renderer.reset();    // its GL objects go before the context
  parked_.clear();
  compositor_.reset();
}

void PlayerApp::make_renderer() {
  prefetcher.reset();
  // The programs are compiled once per window and shared by every renderer made after.
  if (renderer) compositor_ = renderer->compositor();
  renderer.reset();
  renderer = std::make_unique<tspgl::VolumeRenderer>(
      *ctx, *file, cache_on ? tsp::CachePolicy::on : tsp::CachePolicy::off,
      std::int64_t(texture_budget_mb * (1 << 20)), std::int64_t(options_.ram_budget_mb * (1 << 20)),
      compositor_);
  renderer->set_transfer_function(tf);
  prefetcher = std::make_unique<tsp::BrickPrefetcher>(renderer->brick_cache());
  prefetched_for_ = -1;
  prefetched_cut_ = -1;
  applied_probe_version_ = ~std::uint64_t(0);  // the new renderer gets the probes
}

std::array<double, 3> PlayerApp::voxel_size() const {
  return tspgl::shown_voxel_size(file->metadata().spacing, options_.scale,
                                 options_.physical_proportions);
}

void PlayerApp::set_scale(const std::array<double, 3>& scale) {
  options_.scale = scale;
  camera.voxel_size = initial_camera.voxel_size = voxel_size();
}

int PlayerApp::steps() const {
  return file->tree().time().steps();
}

void PlayerApp::go_to(int t) {
  playing = false;
  step = std::clamp(t, 0, steps() - 1);
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
      tf = next;
      lazy_->set_transfer_function(tf);
    }
  }
  if (resample_points) tf_points = editor_points(tf);
  if (renderer) renderer->set_transfer_function(tf);
}

void PlayerApp::apply_tf_points() {
  std::vector<tsp::TfPoint> sorted = tf_points;
  std::stable_sort(sorted.begin(), sorted.end(),
                   [](const tsp::TfPoint& a, const tsp::TfPoint& b) { return a.x < b.x; });
  set_tf(tsp::TransferFunction::from_points(tf.domain(), sorted, tf.size()), false);
}

void PlayerApp::set_metric(tsp::Metric m) {
  if (m == metric) return;
  metric = m;
  if (m != tsp::Metric::reference)
    lazy_ = std::make_unique<tsp::LazyErrors>(file->tree(), m, tf);
  else
    reference_version_ = ~std::uint64_t(0);
  renderer->drop_unreachable(frame_metric(), tol, tspgl::RenderSettings{}.span_step, {},
                             skip_transparent);
  update_tol_max();
}

void PlayerApp::update_tol_max() {
  tol_max = largest_error(metric == tsp::Metric::reference ? reference_.errors
                                                           : lazy_->errors_for_step(step));
}

void PlayerApp::set_tolerances(tsp::Tolerances t) {
  tol = {std::max(0.0, t.spatial), std::max(0.0, t.temporal)};
  renderer->drop_unreachable(frame_metric(), tol, tspgl::RenderSettings{}.span_step, {},
                             skip_transparent);
}

void PlayerApp::apply_quality(double de) {
  tspgl::CalibrationRequest r;
  r.tsp_path = options_.tsp_path;
  r.field = field();  // as render names it: one calibration serves both
  r.metric = metric;
  r.camera = camera;
  // The view's size as this frame lays it out (camera's is set when the volume is drawn: on the
  // first frame it is still the default).
  r.camera.width = std::max(1, layout.view.w);
  r.camera.height = std::max(1, layout.view.h);
  std::string cache;
  const tspgl::Calibration c = tspgl::calibrate(*ctx, r, *file, tf, &cache);
  const auto best = tspgl::pick_configuration(c, de);
  if (!best) {
    quality_note = "nothing calibrated stays within dE " + std::to_string(de);
    return;
  }
  compositing = best->knobs.compositing;
  spacing = best->knobs.spacing;
  preintegrated = best->knobs.preintegrated;
  sampling_tol = best->knobs.sampling_tol;
  tspgl::RenderSettings picked;
  tspgl::apply(best->knobs, picked);  // the tolerances its rule sets
  set_tolerances(picked.tol);
  quality_note = tspgl::render_options(best->knobs, metric) + (cache.empty() ? "" : " (" + cache + ")");
}

void PlayerApp::write_stats(const std::string& path) const {
  nlohmann::json j;
  std::vector<double> ms;
  for (const FrameSample& f : history) ms.push_back(f.ms);
  double sum = 0;
  for (double v : ms) sum += v;
  const double mean = ms.empty() ? 0 : sum / double(ms.size());
  j["window"] = {ctx->width(), ctx->height()};
  j["view"] = {layout.view.x, layout.view.y, layout.view.w, layout.view.h};
  j["docked"] = layout.docked;
  j["file"] = options_.tsp_path;
  j["field"] = file->fields()[std::size_t(file->field_index())];
  j["fields"] = file->fields();
  j["field_switch_ms"] = field_switch_ms;
  nlohmann::json jp = nlohmann::json::array();
  for (const tsp::Probe& p : probes) jp.push_back(tsp::to_string(p));
  j["probes"] = jp;
  j["probe_op"] = tsp::to_string(probe_op);
  j["ram_mib"] = double(renderer->brick_cache().stats().resident_bytes) / (1 << 20);
  j["rss_mib"] = double(tsp::resident_bytes()) / (1 << 20);
  j["peak_rss_mib"] = double(tsp::peak_resident_bytes()) / (1 << 20);
  j["step"] = step;
  j["steps_ready"] = ready;
  j["every_step"] = every_step;
  j["recording"] = recording();
  j["frames"] = ms.size();
  j["frame_ms"] = ms;
  j["mean_frame_ms"] = mean;
  j["fps"] = mean > 0 ? 1000.0 / mean : 0.0;
  j["render_ms"] = last.ms;
  j["fragments"] = last.fragments;
  j["compositing"] = tspgl::to_string(compositing);
  j["spacing"] = spacing;
  j["preintegrated"] = preintegrated;
  j["sampling_tol"] = sampling_tol;
  j["skip_transparent"] = skip_transparent;
  j["tolerance"] = {tol.spatial, tol.temporal};
  nlohmann::json points = nlohmann::json::array();  // the editor's handles: value, opacity
  for (const tsp::TfPoint& p : tf_points) points.push_back({p.x, p.c.a});
  j["tf_points"] = points;
  j["quality"] = quality_note;
  j["lod"] = {{"on", lod_on},
              {"target_fps", target_fps},
              {"refining", refining},
              {"cut_size", lod_stats.cut_size},
              {"nodes_per_level", lod_stats.nodes_per_level},
              {"render_scale", lod_stats.render_scale},
              {"splats", lod_stats.splats},
              {"splat_px", lod_stats.splat_px},
              {"splat_fallback", splat_fallback},
              {"max_error", lod_stats.max_error},
              {"full_quality_after_s", full_quality_after_s},
              // Full quality: no node left whose level differs from full resolution in the
              // picture (error 0: transparent, uniform or hidden), at full render size.
              {"full_quality", full_quality()}};
  j["classes"] = {{"not_rendered", last.class_percent[0]},
                  {"untextured", last.class_percent[1]},
                  {"reused_texture", last.class_percent[2]},
                  {"new_texture", last.class_percent[3]},
                  {"clipped", last.class_percent[4]}};
  tsp::write_file_atomically(path, tsp::json_text(j, 2) + "\n");
}

void PlayerApp::set_cache(bool on, double budget_mb) {
  cache_on = on;
  texture_budget_mb = std::max(1.0, budget_mb);
  make_renderer();
}

// During playback: the bricks the next kPrefetchSteps frames would upload, in playing order,
// go to the prefetch thread once per step change (the request replaces the previous one).
void PlayerApp::request_prefetch(const tsp::Camera& cam, const tspgl::RenderSettings& settings,
                                 tsp::LodStops stops) {
  if (!prefetch_on) return;
  // Holding still or turning: the bricks the cut's next splits will want, at this step, once per
  // cut change (the RAM cache then serves the split's uploads).
  if (!playing) {
    if (!lod_ || lod_stats.cut_size == prefetched_cut_) return;
    prefetched_cut_ = lod_stats.cut_size;
    std::vector<tsp::BrickKey> keys;
    for (int b : lod_->likely_split_bricks(kPrefetchSplits)) keys.push_back({b, step});
    prefetcher->request(std::move(keys));
    return;
  }
  if (prefetched_for_ == step) return;
  prefetched_for_ = step;
  std::vector<tsp::BrickKey> keys;
  for (int k = 1; k <= kPrefetchSteps; ++k) {
    int t = step + k;
    if (t >= steps()) {
      if (!loop) break;
      t %= steps();
    }
    std::vector<tsp::BrickKey> more =
        renderer->bricks_to_upload(t, cam, settings, frame_metric(), stops);
    keys.insert(keys.end(), more.begin(), more.end());
    if (lod_)  // and the cut's likely next splits at that step, after what it will draw
      for (int b : lod_->likely_split_bricks(kPrefetchSplits)) keys.push_back({b, t});
  }
  prefetcher->request(std::move(keys));
}

void PlayerApp::request_save() {
  save_requested_ = true;
}

tsp::FrameMetric& PlayerApp::frame_metric() {
  if (metric != tsp::Metric::reference) return *lazy_;
  refresh_reference();
  return reference_nodes_;
}

void PlayerApp::refresh_reference() {
  if (reference_version_ == tf.version()) return;
  // The reference metric reads every voxel: computed in full, blocking (the UI says so).
  const tsp::Stopwatch t0;
  reference_ = tsp::compute_errors(tsp::Metric::reference, file->tree(), tf, file.get(), 0);
  metric_ms = t0.ms();
  metric_evaluations = std::int64_t(reference_.transparent.size());
  reference_version_ = tf.version();
}

void PlayerApp::render_volume() {
  camera.width = layout.view.w;
  camera.height = layout.view.h;
  if (camera.width < 1 || camera.height < 1 || ctx->width() < 1 || ctx->height() < 1)
    return;  // minimised
  const tsp::Camera cam(file->tree().octree().dims(), camera);
  tspgl::RenderSettings settings;
  settings.tol = tol;
  settings.upload_budget = std::int64_t(std::max(0.0, upload_budget_mb) * (1 << 20));
  settings.compositing = compositing;
  settings.spacing = spacing;
  settings.preintegrated = preintegrated;
  settings.sampling_tol = preintegrated ? 0 : sampling_tol;  // the two exclude each other
  settings.skip_transparent = skip_transparent;
  // GL's window coordinates start at the bottom: the view's lower-left corner.
  settings.viewport_origin = {layout.view.x, ctx->height() - layout.view.y - layout.view.h};
  if (metric != tsp::Metric::reference) {
    // Evaluate this step's nodes here so the HUD can show the recompute cost; render() then
    // only reads memoised results.
    const std::int64_t before = lazy_->evaluations();
    const tsp::Stopwatch t0;
    lazy_->errors_for_step(step);
    const double ms = t0.ms();
    if (lazy_->evaluations() > before) {
      metric_ms = ms;
      metric_evaluations = lazy_->evaluations() - before;
    }
  }
  const tsp::LodStops stops = update_lod(cam, settings, glfwGetTime());
  last = renderer->render(step, cam, settings, frame_metric(), stops);
  request_prefetch(cam, settings, stops);
  update_ready(cam, settings, stops);
}

// A few steps a frame, round robin: how much of what each step's frame would upload is in RAM
// already (1 when its textures are all resident).
void PlayerApp::update_ready(const tsp::Camera& cam, const tspgl::RenderSettings& settings,
                             tsp::LodStops stops) {
  const int n = steps();
  for (int k = 0; k < std::min(n, kReadyStepsPerFrame); ++k) {
    const int t = ready_next_;
    ready_next_ = (ready_next_ + 1) % n;
    const std::vector<tsp::BrickKey> keys =
        renderer->bricks_to_upload(t, cam, settings, frame_metric(), stops);
    int in_ram = 0;
    for (const tsp::BrickKey& key : keys) in_ram += renderer->brick_cache().contains(key.brick, key.step);
    ready[std::size_t(t)] = keys.empty() ? 1.f : float(in_ram) / float(keys.size());
  }
}

tsp::Image PlayerApp::read_view() {
  const WindowRect& v = layout.view;
  return ctx->read_pixels(v.x, ctx->height() - v.y - v.h, v.w, v.h);
}

void PlayerApp::advance_playback(double dt) {
  if (!playing) {
    play_accum_ = 0;
    return;
  }
  play_accum_ += std::min(dt, kMaxFrameDt) * speed;
  // Every step: at most one step a frame, however slow the frames (no step is skipped).
  if (every_step) play_accum_ = std::min(play_accum_, 1.0);
  while (play_accum_ >= 1) {
    play_accum_ -= 1;
    if (step + 1 < steps()) {
      ++step;
    } else if (loop) {
      step = 0;
    } else {
      playing = false;
      play_accum_ = 0;
      break;
    }
  }
}

void PlayerApp::save_pending_shot() {
  tsp::write_png(pending_shot_, pending_with_ui_ ? ctx->read_pixels() : read_view());
  std::printf("saved %s (step %d)\n", pending_shot_.c_str(), step);
  std::fflush(stdout);
  pending_shot_.clear();
}

void PlayerApp::frame() {
  ctx->poll_events();
  const double now = glfwGetTime();
  const double dt = now - last_frame_s_;
  last_frame_s_ = now;
  const tsp::Stopwatch t_frame;

  ImGui_ImplOpenGL3_NewFrame();
  ImGui_ImplGlfw_NewFrame();
  ImGui::NewFrame();
  // The volume's rectangle: beside the docked panels, or the whole window (again below, after
  // keys and script actions that may show or hide the panels).
  layout = compute_layout(ctx->width(), ctx->height(), panels, int(ImGui::GetFrameHeight()));
  poll_open();
  run_script();
  if (quit_) {
    ImGui::EndFrame();
    return;
  }
  handle_input();
  advance_playback(dt);
  if (options_.trace) trace_changes();
  layout = compute_layout(ctx->width(), ctx->height(), panels, int(ImGui::GetFrameHeight()));
  if (layout.docked) {  // what the volume does not cover is the panels' background
    const tspgl::GlApi& gl = ctx->gl();
    gl.BindFramebuffer(GL_FRAMEBUFFER, 0);
    gl.Viewport(0, 0, ctx->width(), ctx->height());
    gl.ClearColor(0, 0, 0, 1);
    gl.Clear(GL_COLOR_BUFFER_BIT);
  }
  apply_probes();
  render_volume();
  if (frame_delay_ms_ > 0)
    std::this_thread::sleep_for(std::chrono::duration<double, std::milli>(frame_delay_ms_));

  // Screenshots hold the volume only (read before the UI is drawn).
  // A screenshot waits for the first complete frame (no texture left for later frames).
  // With the LOD cut it also waits for full quality (the idle refinement), unless playing.
  const bool full = playing || full_quality();
  const bool shot_now = !pending_shot_.empty() && last.complete() && full;
  if (shot_now && !pending_with_ui_) save_pending_shot();
  if (save_requested_) {
    save_requested_ = false;
    char name[64];
    std::snprintf(name, sizeof name, "tspplay_step_%04d.png", step);
    try {
      tsp::write_png(name, read_view());
      status = std::string("saved ") + name;
    } catch (const tsp::Error& e) {
      status = e.what();
    }
    std::printf("%s\n", status.c_str());
  }

  if (recorder_) record_frame(now);
  if (switch_started_s_ >= 0 && last.complete() && (playing || full_quality())) {
    field_switch_ms = (glfwGetTime() - switch_started_s_) * 1000;  // the new field's first frame
    switch_started_s_ = -1;
  }
  if (camera.width > 0 && camera.height > 0) {
    const tsp::Camera cam(file->tree().octree().dims(), camera);
    draw_cut_overlay(cam);
    draw_annotations(cam);
    if (panels) draw_probe_overlay(cam);
  }
  draw_ui();
  ImGui::Render();
  ctx->gl().BindFramebuffer(GL_FRAMEBUFFER, 0);
  ctx->gl().Viewport(0, 0, ctx->width(), ctx->height());
  ImGui_ImplOpenGL3_RenderDrawData(ImGui::GetDrawData());
  if (shot_now && !pending_shot_.empty()) save_pending_shot();
  ctx->swap_buffers();

  measured_lod(last.ms - last.upload_ms, t_frame.ms());
  history.push_back({now - start_s_, t_frame.ms()});
  while (!history.empty() && history.front().at_s < now - start_s_ - kFrameHistorySeconds)
    history.pop_front();
}

void PlayerApp::run() {
  int frames = 0;
  for (; !quit_ && !ctx->should_close(); ++frames) frame();
  const tsp::BrickCacheStats b = renderer->brick_cache().stats();
  std::printf("played %d frames; bricks: %lld hits, %lld misses, %lld prefetched\n", frames,
              static_cast<long long>(b.hits), static_cast<long long>(b.misses),
              static_cast<long long>(b.prefetched));
}

}  // namespace tspplayer
