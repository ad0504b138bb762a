// src/jobs: headless CLI jobs (render, bench) as library calls; may include tsp/, gl/, render/.
// `tspplay render` as a library call: render a range of steps of a .tsp file headless, write
// step_NNNN.png and frames.json, and return the per-frame reports.
#pragma once
#include <filesystem>
#include <functional>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "gl/headless.h"
#include "jobs/frame_set.h"
#include "render/frame_driver.h"
#include "render/frame_report.h"
#include "tsp/metric/tf_io.h"
#include "tsp/clip/probe.h"
#include "tsp/frame/camera.h"
#include "tsp/frame/texture_cache.h"
#include "tsp/lod/lod_controller.h"
#include "tsp/metric/metric.h"
#include "tsp/report/image.h"
#include "tsp/store/tsp_file.h"
#include "tsp/tree/tsp_tree.h"

namespace tspgl {

struct FrameRecord;
/// Called after every frame with its record and pixels (benchmarks comparing pictures).
using FrameSink = std::function<void(const FrameRecord&, const tsp::Image&)>;


/// Everything `tspplay render` takes.
struct RenderJobOptions {
  std::string tsp_path;                       ///< the .tsp file
  HeadlessGl gl = HeadlessGl::automatic;      ///< --gl: EGL or OSMesa (gl/headless.h)
  int gpu = -1;                               ///< --gpu: EGL device index (−1: by --gl's rule)
  std::string field;                          ///< --field: one of its fields ("": the first)
  std::string tf = "preset:auto";             ///< --tf: a file or preset:NAME
  tsp::TfRangeChoice tf_range;                ///< --tf-range: where the TF sits over the data
  bool annotate = false;                      ///< --annotate: outline, axes, legend, step/time
  std::string out_dir;                        ///< frames/: replaced as a whole when the job
                                              ///< succeeded (tsp::OutputFolder); empty: none
  std::string movie;                          ///< --movie out.mp4|out.gif from out_dir's frames
                                              ///< ("": none); needs ffmpeg on PATH
  int fps = 8;                                ///< --fps of the movie
  int first_step = 0, last_step = -1;         ///< inclusive; −1: the last step
  int step_stride = 1;                        ///< every step_stride-th step from first_step
  tsp::Metric metric = tsp::Metric::approximate;
  tsp::CachePolicy cache = tsp::CachePolicy::on;
  bool baseline = false;                      ///< render without the TSP tree
  tsp::CameraParams camera;                   ///< size, view, projection (voxel_size is set
                                              ///< from the file, physical_proportions and scale)
  bool physical_proportions = true;           ///< --proportions physical|samples
  std::vector<tsp::Probe> probes;             ///< --probe: the clip solid's probes
  tsp::ProbeOp probe_op = tsp::ProbeOp::intersect;  ///< --probe-op
  bool probe_surface = false;                 ///< --probe-surface on: draw the clip surface
  std::string probe_tf;                       ///< --probe-tf: its colours ("": the volume's TF)
  std::array<double, 3> probe_motion{0, 0, 0};  ///< --probe-motion: every probe moves this far
                                                ///< each frame (physical units)
  /// With settings.surface (--surface boundary): the mesh series whose boundary is drawn opaque
  /// under the volume as TetSplat's splats (render/mesh_surface.h), the one the file was built
  /// from; its minimum splat size is settings.surface_px.
  std::string surface_mesh;                   ///< --surface-mesh: that mesh series
  std::string surface_field;                  ///< --surface-field ("": the file's field)
  std::string surface_tf;                     ///< --surface-tf ("": cool-to-warm over the
                                              ///< surface's values at the first step)
  /// --surface-target-ms (> 0): the minimum splat size adapts frame by frame so the surface
  /// pass takes this long (TetSplat's frame-rate knob); surface_px is where it starts.
  double surface_target_ms = 0;
  std::array<double, 3> scale{1, 1, 1};       ///< --scale SX,SY,SZ: exaggeration per axis
  int passes = 1;                             ///< times the step range is played
  /// The frame knobs: --spatial-tol/--temporal-tol, --spacing, --compositing, --flat,
  /// --span-step, --preintegrated, --reuse (upload_budget: unused, a job uploads every frame).
  RenderSettings settings;
  std::int64_t texture_budget = kDefaultTextureBudget;
  std::int64_t ram_budget = kDefaultBrickBudget;  ///< --ram-budget: bricks held in RAM (bytes)
  bool write_images = true;                   ///< PNGs (frames.json is written when out_dir is set)
  /// --quality DE (> 0): compositing, spacing, tolerances and pre-integration are picked from the
  /// calibration (calibration.h) instead of those in settings; 0: off.
  double quality = 0;
  std::string calibration_dir;                ///< --calibration-dir ("": the default; "-": none)
  std::string save_tf;                        ///< --save-tf: write the TF used here (JSON),
                                              ///< replaced only when the whole job succeeded
  LodMode lod = LodMode::off;                 ///< --lod off|K|auto
  int lod_level = 0;                          ///< --lod K
  double splat_px = 0;                        ///< --lod splat:PX, the minimum splat size
  tsp::SelectionFilter lod_filter;            ///< --lod-filter distance|fov (LodMode::filter)
  /// --target-ms (> 0, with --lod auto): the controller holds this frame time; 0 with --lod auto:
  /// every frame refined until no node's error is above lod_options.min_error.
  double target_ms = 0;
  tsp::LodOptions lod_options;                ///< split/merge limits, min error, focus
  double orbit_deg = 0;                       ///< --orbit: azimuth advance per frame
  FrameSink on_frame;                         ///< called after every frame; may be empty
  /// Stop once every option, input and output is checked (nothing written, no GL context; with
  /// --quality the calibration is made, and cached, first): tspplay-mpi render's first step.
  bool check_only = false;
  /// A render split over `parts` processes (tspplay-mpi render; 0: not split): this one draws
  /// only the frames part_frames gives part `part` in every pass, each frame's record saying
  /// "rank": part. Every other frame is skipped but still counted, so the TF, the orbit, the
  /// probes' motion and the steps are those of the whole render.
  int part = 0, parts = 0;
};

/// What the LOD cut did in one frame (frames.json's "lod").
struct LodRecord {
  double target_ms = 0;
  tsp::LodFrameStats stats;
};

/// Largest --target-ms.
inline constexpr double kMaxTargetMs = 60000;
/// Largest --scale factor.
inline constexpr double kMaxScale = 1000;
/// Smallest minimum splat size --surface-target-ms goes down to (half a pixel: every leaf).
inline constexpr double kMinSurfacePx = 0.5;
/// Largest factor --surface-target-ms changes the minimum splat size by from one frame to the
/// next.
inline constexpr double kSurfacePxStep = 2;

/// The voxel size a view shows: the file's spacing (or cubes, without physical proportions)
/// times scale per axis. Spacing that is not positive and finite counts as 1. Never throws.
std::array<double, 3> shown_voxel_size(const std::array<double, 3>& spacing,
                                       const std::array<double, 3>& scale, bool physical);
/// Places field `file` in the view c: its shown voxel size (shown_voxel_size); with physical
/// proportions and several fields in the file, also its origin and the file's frame (every
/// field's box, TspFile::frame) times scale, so that fields on different grids (WRF's staggered
/// W beside T) overlay and switching fields keeps the view. Never throws.
void place_field(tsp::CameraParams& c, const tsp::TspFile& file, const std::array<double, 3>& scale,
                 bool physical);
/// Most passes a job plays.
inline constexpr int kMaxPasses = 1000;

/// One frame of a job.
struct FrameRecord {
  int pass = 1;
  FrameReport report;
  double azimuth_deg = 0;          ///< the camera's azimuth (it moves with --orbit)
  std::optional<LodRecord> lod;    ///< with --lod
  std::optional<double> time;      ///< the step's physical time, when the file has times
  std::string time_text;           ///< time as tsp::format_time writes it (a date with CF units)
  std::int64_t ram_bytes = 0;      ///< bricks in RAM after the frame (the brick cache)
  std::int64_t rss_bytes = 0;      ///< the process's resident memory after the frame
  int surface_splats = -1;         ///< --surface: splats drawn (−1: no surface)
  double surface_cut_ms = 0;       ///< --surface: choosing the cut and filling its buffer
  double surface_ms = 0;           ///< --surface: the whole surface pass
  double surface_px = 0;           ///< --surface: the minimum splat size it was cut at
  int rank = -1;                   ///< the part that drew it in a split render (−1: not split)
};

/// What a job did.
struct RenderJobResult {
  std::vector<FrameRecord> frames;
  double metric_ms = 0;   ///< whole-tree metric computation before the first frame
  std::string renderer;   ///< the GL renderer string
  std::string gl_vendor;  ///< the GL vendor string
  std::string context;    ///< what drew: "OSMesa" or "EGL device N (name)" (GlContext::kind)
  std::string quality_options;   ///< with --quality: the render options it picked
  double quality_calibrated_de = 0;  ///< their largest per-step mean ΔE on the calibration steps
  std::string calibration_file;  ///< the cache file read or written ("" without a cache)
  std::vector<std::string> warnings;  ///< for the user (a TF that misses the data, …)
};

/// Progress callback: frames done, frames total.
using RenderProgress = std::function<void(int done, int total)>;

/// Runs the job on an offscreen OSMesa context (calibrating first for --quality, reporting to
/// calibration_progress). Throws tsp::UsageError (bad steps, sizes, a quality nothing reaches),
/// tsp::IoError / tsp::FormatError (files), tsp::GlError.
RenderJobResult run_render_job(
    const RenderJobOptions& options, const RenderProgress& progress = {},
    const std::function<void(const std::string&, int, int)>& calibration_progress = {});

/// The inclusive step range [first, last] of path's tree (last −1: the final step), validated;
/// returns last. Throws tsp::UsageError naming the file and its steps.
int checked_last_step(const tsp::TspTree& tree, int first, int last, const std::string& path);

/// One frame's entry of frames.json: its FrameReport's keys (to_json in frame_report.h) and
/// the record's own (pass, azimuth, time, memory, LOD, rank, surface). Never throws but bad_alloc.
void to_json(nlohmann::json& j, const FrameRecord& f);

/// Makes the output folder out (bench -o) if it is not there; its parent must exist.
/// Throws tsp::IoError naming the missing parent or the folder that cannot be made.
std::filesystem::path make_output_dir(const std::string& out);

/// Median of the frames' `ms` in pass `pass` (0: all passes).
double median_frame_ms(const RenderJobResult& result, int pass = 0);

}  // namespace tspgl
