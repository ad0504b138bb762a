// The player's files: File > Open (a .tsp file at once, any other input built into the cache
// folder on a thread with progress), recording the volume to a movie, saving the TF, the
// statistics `stats` writes.
// Our loader (gl/gl_api.h) declares the GL functions; GLFW must not pull in GL/gl.h.
#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <unistd.h>

#include "jobs/annotate.h"
#include "jobs/play_input.h"
#include "player/player_app.h"
#include "player/ui_items.h"
#include "player/player_ui.h"
#include "player/export_names.h"
#include "render/settings_table.h"
#include "tsp/core/json_text.h"
#include "tsp/core/memory_use.h"
#include "tsp/core/temp_output.h"
#include "tsp/core/error.h"
#include "tsp/frame/exaggeration.h"
#include "tsp/metric/tf_io.h"

namespace tspplayer {

namespace {

// Reports a failure in the UI and on stderr (a scripted run's log shows it too).
void report(PlayerApp& app, const std::string& what) { app.set_error(what); }

// A File > Open that failed: reported as above and, with --trace, as a trace line; the player
// keeps the file it plays.
void open_failed(PlayerApp& app, bool trace, const std::string& input, const std::string& why) {
  // (A reader's message names its file first already: the path once, so the reason shows.)
  const std::string what = why.rfind(input + ": ", 0) == 0 ? "open " + why : "open " + input + ": " + why;
  report(app, what);
  app.open_ended(what);
  if (trace) {
    std::printf("trace: open %s failed: %s\n", input.c_str(), why.c_str());
    std::fflush(stdout);
  }
}

}  // namespace

std::string PlayerApp::open_folder() const {
  const std::string& given = options_.input_path.empty() ? options_.tsp_path : options_.input_path;
  return std::filesystem::path(given).parent_path().string();
}

void PlayerApp::open_input(const std::string& input, const std::string& field,
                           const std::string& build_options) {
  options_.input_path = input;  // the next File > Open starts beside it
  if (open_job_) {
    open_failed(*this, options_.trace, input, "still opening " + open_job_->input());
    return;
  }
  if (tspgl::is_tsp_file(input)) {
    if (!build_options.empty()) {
      open_failed(*this, options_.trace, input,
                  "a .tsp file is built already: no build options (" + build_options + ")");
      return;
    }
    if (!field.empty()) {
      open_failed(*this, options_.trace, input, "a .tsp file has its field already (" + field + ")");
      return;
    }
    try {
      open_file(input);
    } catch (const tsp::Error& e) {
      open_failed(*this, options_.trace, input, e.what());
    }
    return;
  }
  // Anything else is built on a worker (the window keeps drawing the current file), then played;
  // whatever is wrong with it (missing, a device, bad contents) is the job's error, reported by
  // poll_open.
  try {
    tspgl::PlayInputOptions o = options_.input;
    if (!build_options.empty()) {
      if (!options_.parse_input_options)
        throw tsp::UsageError("build options are not taken here (" + build_options + ")");
      o = options_.parse_input_options(build_options);  // throws UsageError: nothing started
    }
    o.field = field;
    open_job_ = std::make_unique<OpenJob>(input, std::move(o), options_.cache_dir);
  } catch (const std::exception& e) {  // bad build options, or no thread could start
    open_failed(*this, options_.trace, input, e.what());
    return;
  }
  status = "opening " + input + " ...";
}

void PlayerApp::cancel_open() {
  if (open_job_) open_job_->cancel();
}

void PlayerApp::poll_open() {
  if (!open_job_ || !open_job_->done()) return;
  const std::unique_ptr<OpenJob> job = std::move(open_job_);
  std::string built;
  try {
    built = job->result();
  } catch (const std::exception& e) {
    open_failed(*this, options_.trace, job->input(), e.what());
    return;
  }
  try {
    open_file(built);
  } catch (const tsp::Error& e) {
    open_failed(*this, options_.trace, built, e.what());
  }
}

tsp::TransferFunction PlayerApp::start_tf(const tsp::TspFile& f) const {
  const tsp::TfRangeChoice range = tsp::parse_tf_range(options_.tf_range);
  const tsp::ValueHistogram histogram = tsp::histogram_of(f);
  return tsp::transfer_function_from_arg(
      options_.tf, tsp::tf_domain_of(range, f, 0),  // (a file opens at step 0)
      tsp::kDefaultTfEntries, range, &histogram);
}

void PlayerApp::open_file(const std::string& path) {
  std::unique_ptr<tsp::TspFile> next = tsp::TspFile::open(path);  // throws: nothing changed
  save_session_entry();  // the session of the input played so far
  if (recorder_) stop_recording();  // a movie has one size and one dataset
  // The programs outlive the session: every renderer of the window shares them.
  if (viewer_->has_renderer()) compositor_ = viewer_->renderer().compositor();
  viewer_.reset();  // the old file, metric, renderer, prefetcher and driver
  parked_.clear();
  options_.tsp_path = path;
  mesh_surface.reset();  // the surface belongs to the file opened first
  surface_mesh_.clear();
  // Nor does the compositor, which outlives the renderer, keep drawing it: the surface control
  // reads the opened input's own boundary below, or says why it cannot and goes off.
  if (compositor_) compositor_->set_surface({});
  const bool surface_asked = state_.settings.surface;
  state_.settings.surface = false;
  // The TF the player started with, fitted to the new data (a map edited for other data
  // rarely suits this one).
  tsp::TransferFunction fresh = start_tf(*next);
  tf.assign(fresh);  // (its version grows: what keys on it sees the change)
  viewer_ = std::make_unique<ViewerSession>(std::move(next), tf, state_.metric);
  const tsp::TspTree& tree = viewer_->file().tree();
  set_tf(tf, true);
  tf_label = tf_label_of(options_.tf);
  state_.step = 0;
  // A speed set in the window was this series' (the seventh walk: the plume's 6 steps/s went on
  // to a 2-step series and into its session); --speed is kept. The new input's session may set
  // one below.
  speed_chosen_ = options_.speed != 0;
  state_.speed = speed_chosen_ ? options_.speed : default_speed(tree.time().steps());
  state_.playing = false;
  lod_loop_.clear_focus();
  state_.settings.tol = {0, 0};
  state_.probes.clear();  // (in the old file's physical coordinates)
  probe_selected_ = -1;
  probes_changed();
  quality_note.clear();
  history.clear();
  ready.assign(std::size_t(tree.time().steps()), -1.f);
  ready_next_ = 0;
  state_.camera = tsp::CameraParams{};
  // The last file's exaggeration rarely suits this one: a flat one gets its own.
  options_.scale = options_.physical_proportions ? tsp::vertical_exaggeration(viewer_->file().frame())
                                                 : std::array<double, 3>{1, 1, 1};
  place_camera(state_.camera);
  initial_camera = state_.camera;
  make_renderer();
  update_tol_max();
  // The input as the user named it (an .h5 built into the cache), not the cache entry.
  const std::string shown = options_.input_path.empty() ? path : options_.input_path;
  glfwSetWindowTitle(static_cast<GLFWwindow*>(ctx->native_window()), ("tspplay - " + shown).c_str());
  // (An event, named as the user named the input: "playing PATH" stayed on while paused and
  // named the cache's build.)
  status = "opened " + shown + " (" + std::to_string(steps()) + (steps() == 1 ? " step)" : " steps)");
  std::printf("opened %s (%d steps)\n", path.c_str(), steps());
  std::fflush(stdout);
  if (surface_asked) set_setting("surface", "boundary");
  restore_session(false);  // this input's last session, if any
  open_ended("");
}

void PlayerApp::switch_field(const std::string& name) {
  if (name == field()) return;
  const std::vector<std::string>& names = viewer_->file().fields();
  if (std::find(names.begin(), names.end(), name) == names.end()) {
    std::string list;
    for (const std::string& n : names) list += (list.empty() ? "" : ", ") + n;
    throw tsp::UsageError("field '" + name + "': " + options_.tsp_path + " holds the field(s) " +
                          list);
  }
  FieldShelf::Field next;
  if (std::optional<FieldShelf::Field> parked = parked_.take(name)) {
    next = std::move(*parked);
  } else {
    next.file = tsp::TspFile::open(options_.tsp_path, name);  // throws: nothing changed
    // The TF the player was started with, fitted to this field's data.
    next.tf = start_tf(*next.file);
  }
  switch_started_s_ = clock_.seconds();
  const std::string current = field();
  FieldShelf::Field shown{nullptr, nullptr, tf};
  tf.assign(next.tf);  // (its version grows past both fields')
  std::tie(shown.file, shown.renderer) = viewer_->swap_field(std::move(next.file), compositor_);
  parked_.park(current, std::move(shown));
  tf_points_.clear();
  set_tf(tf, true);
  applied_probe_version_ = ~std::uint64_t(0);  // the probes go to this field's renderer too
  if (next.renderer) {
    viewer_->adopt_renderer(std::move(next.renderer));
    prefetched_for_ = prefetched_cut_ = -1;
  } else {
    make_renderer();
  }
  place_camera(state_.camera);  // (another grid: its own voxel size and place in the frame)
  place_camera(initial_camera);
  ready.assign(std::size_t(steps()), -1.f);
  ready_next_ = 0;
  update_tol_max();
  status = "field " + name;
  if (options_.trace) {
    std::printf("trace: field %s\n", name.c_str());
    std::fflush(stdout);
  }
}

void PlayerApp::start_recording(const std::string& path) {
  if (recorder_) stop_recording();
  try {
    recorder_ = std::make_unique<Recorder>(path, layout.view.w, layout.view.h, kRecordFps,
                                           clock_.seconds());
    status = "recording " + path;
    last_saved_folder_ = std::filesystem::absolute(path).parent_path().string();
  } catch (const tsp::Error& e) {
    report(*this, std::string("record: ") + e.what());
  }
}

double PlayerApp::recorded_seconds() const {
  return recorder_ ? recorder_->seconds() : 0.0;
}

void PlayerApp::stop_recording() {
  if (!recorder_) return;
  const std::unique_ptr<Recorder> r = std::move(recorder_);
  try {
    status = r->finish(clock_.seconds());
    std::printf("%s\n", status.c_str());
    std::fflush(stdout);
  } catch (const tsp::Error& e) {
    report(*this, std::string("record: ") + e.what());
  }
}

// The volume as shown, with the outline, axes, legend and step drawn in (as render --annotate):
// repeated or skipped so that the movie keeps the wall-clock time of what was played.
tsp::Image PlayerApp::export_view() {
  tsp::Image img = read_view();
  if (state_.annotations) {
    const auto& times = viewer_->file().metadata().times;
    tspgl::annotate_frame(img, tsp::Camera(viewer_->file().tree().octree().dims(), state_.camera),
                          viewer_->file().tree().octree().dims(), tf, state_.step,
                          times.empty() ? std::nullopt
                                        : std::optional<std::string>(tsp::format_time(
                                              times[std::size_t(state_.step)],
                                              viewer_->file().metadata().time_units)),
                          field(), tsp::exaggeration_text(options_.scale, true),
                          mesh_surface && state_.settings.surface
                              ? tspgl::SurfaceLegend{&mesh_surface->tf(), mesh_surface->field()}
                              : tspgl::SurfaceLegend{});
  }
  return img;
}

std::string PlayerApp::export_stem() const {
  // (The input's known extensions stripped: export_names.h.)
  const std::string given = options_.input_path.empty() ? options_.tsp_path : options_.input_path;
  return dataset_name(given) + "_" + field();
}

std::string PlayerApp::export_folder() const {
  // (S wrote into the working directory, wherever the data was.)
  namespace fs = std::filesystem;
  std::error_code ec;
  const fs::path cwd = fs::current_path(ec);
  fs::path folder = last_saved_folder_.empty() ? fs::path(open_folder()) : fs::path(last_saved_folder_);
  folder = folder.empty() ? cwd : fs::absolute(folder, ec);
  if (!fs::is_directory(folder, ec) || ::access(folder.c_str(), W_OK) != 0) folder = cwd;
  return folder.lexically_normal().string();
}

std::string PlayerApp::export_name() const {
  // NAME_FIELD_step_NNNN.png beside the data (or where a file was last saved), never over an
  // earlier one.
  char step[32];
  std::snprintf(step, sizeof step, "_step_%04d", state_.step);
  return tsp::unused_path((std::filesystem::path(export_folder()) / (export_stem() + step + ".png")).string());
}

void PlayerApp::record_frame(double now_s) {
  try {
    // Only pictures within the quality target go into the movie: while one is not (the LOD cut
    // during interaction), the last one that was is held.
    if (!within_) {
      recorder_->hold(now_s);
      return;
    }
    recorder_->frame(export_view(), now_s);
  } catch (const tsp::UsageError&) {  // the view changed size: keep the movie so far
    stop_recording();
    status += " (stopped: the view changed size)";
  } catch (const tsp::Error& e) {
    recorder_.reset();
    report(*this, std::string("record: ") + e.what());
  }
}

void PlayerApp::save_tf_as(const std::string& path) {
  try {
    tsp::save_transfer_function(tf, path);
    tf_file_path() = path;  // (the TF editor's file row and File > Save offer it next)
    status = "saved " + path;
    last_saved_folder_ = std::filesystem::absolute(path).parent_path().string();
  } catch (const tsp::Error& e) {
    report(*this, e.what());
  }
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
  j["open_folder"] = open_folder();  // where File > Open starts
  j["session"] = session_json();  // restored (from where), its cache entry, a file ignored
  j["camera"] = {{"azimuth_deg", state_.camera.azimuth_deg},
                 {"elevation_deg", state_.camera.elevation_deg},
                 {"zoom", state_.camera.zoom},
                 {"pan", state_.camera.pan},
                 {"perspective", state_.camera.projection == tsp::Projection::perspective}};
  j["scale"] = options_.scale;  // the axis stretch
  j["panels"] = state_.panels;
  j["surface_mesh"] = surface_mesh_;  // the mesh whose boundary is drawn ("": none)
  j["status"] = status;
  j["status_error"] = status_is_error();
  j["field"] = viewer_->file().fields()[std::size_t(viewer_->file().field_index())];
  j["fields"] = viewer_->file().fields();
  j["field_switch_ms"] = field_switch_ms;
  nlohmann::json jp = nlohmann::json::array();
  for (const tsp::Probe& p : state_.probes) jp.push_back(tsp::to_string(p));
  j["probes"] = jp;
  j["probe_op"] = tsp::to_string(state_.probe_op);
  j["axis_scale"] = options_.scale;  // the stretch per axis, automatic for a flat domain
  j["exaggeration"] = tsp::exaggeration_text(options_.scale);  // as the picture names it
  j["ram_mib"] = double(viewer_->renderer().brick_cache().stats().resident_bytes) / (1 << 20);
  j["rss_mib"] = double(tsp::resident_bytes()) / (1 << 20);
  j["peak_rss_mib"] = double(tsp::peak_resident_bytes()) / (1 << 20);
  j["step"] = state_.step;
  j["steps_ready"] = ready;
  j["every_step"] = state_.every_step;
  j["recording"] = recording();
  j["frames"] = ms.size();
  j["frame_ms"] = ms;
  j["mean_frame_ms"] = mean;
  j["fps"] = mean > 0 ? 1000.0 / mean : 0.0;
  // The last frame drawn, under frames.json's keys (to_json in render/frame_report.h): ms, caster
  // (who cast its rays; "backend" is the setting), fragments (0 when it reused the image), the
  // Table-5 classes, deferred_textures (left for later frames by the upload budget), …
  j["frame_report"] = last;
  j["picture_fragments"] = picture_fragments_;  // of the frame that drew the picture shown
  j.update(tspgl::settings_json(state_.settings));  // every knob of the settings table, as render's
  j["tolerance"] = {state_.settings.tol.spatial, state_.settings.tol.temporal};
  nlohmann::json points = nlohmann::json::array();  // the editor's handles: value, opacity
  for (const tsp::TfPoint& p : tf_points_) points.push_back({p.x, p.c.a});
  j["tf_points"] = points;
  j["tf_domain"] = {tf.domain().lo, tf.domain().hi};
  j["tf"] = tf_label;  // the map in use, as the preset combo names it
  // Issue 47 items 5 and 7: every entry's opacity (the editor warps the curve in place), the
  // panels' labelled items of the last frame (the clipped-label check), what the tolerances buy.
  nlohmann::json opacity = nlohmann::json::array();
  for (const tsp::Rgba& e : tf.entries()) opacity.push_back(e.a);
  j["tf_opacity"] = opacity;
  j["ui_items"] = ui_items_json();
  j["tf_histogram"] = {{"step", editor_histogram_.step}, {"nonempty_bins", editor_histogram_bins_}};
  j["tolerance_readout"] = {{"spatial", tol_readout.at.spatial},
                            {"temporal", tol_readout.at.temporal},
                            {"ms", tol_readout.ms},
                            {"exact_ms", tol_readout.exact_ms},
                            {"mean_de", tol_readout.mean_de}};
  j["quality"] = quality_note;
  j["frames_drawn"] = frames_drawn_;
  j["playback"] = playback_json();
  j["idle_waits"] = idle_waits_;
  j["cpu_seconds"] = tsp::cpu_seconds();
  j["tuning"] = tuning_.stats();  // (playback_tuning.h)
  j["lod"] = lod_loop_.stats();  // the last frame's cut, under frames.json's "lod" keys
  j["lod"].update({{"on", state_.lod_on},
                   {"target_fps", state_.target_fps},
                   {"refining", lod_loop_.refining()},
                   {"splat_fallback", state_.splat_fallback},
                   {"filter", tsp::to_string(state_.lod_filter.kind)},
                   {"filter_k", state_.lod_filter.scale},
                   {"full_quality_after_s", lod_loop_.full_quality_after_s()},
                   // Full quality: no node left whose level differs from full resolution in
                   // the picture (error 0: transparent, uniform or hidden), at full render size.
                   {"full_quality", full_quality()},
                   {"picture", refine_json()}});
  tsp::write_file_atomically(path, tsp::json_text(j, 2) + "\n");
}

}  // namespace tspplayer
