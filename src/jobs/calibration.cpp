#include "jobs/calibration.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <limits>
#include <sstream>

#include "jobs/cache_key.h"
#include "jobs/image_probe.h"
#include "jobs/render_job.h"
#include "tsp/core/error.h"
#include "tsp/core/input_file.h"
#include "tsp/core/json_read.h"
#include "tsp/core/json_text.h"
#include "tsp/core/stopwatch.h"
#include "tsp/core/temp_output.h"
#include "tsp/metric/compute_errors.h"
#include "tsp/report/image_diff.h"

namespace tspgl {

namespace {

namespace fs = std::filesystem;
using nlohmann::json;

// Largest calibration cache read (a real one is a few kilobytes: one point per grid cell).
constexpr std::int64_t kMaxCalibrationBytes = std::int64_t(16) << 20;
// Bumped whenever what a calibration measures changes, so old cache files are recomputed.
constexpr int kCalibrationVersion = 5;  // 2: the key holds the voxel size; 3: frames skip
                                         // transparent children (--skip-transparent on); 4: rays
                                         // sample exact segments, spans textured by their mean;
                                         // 5: lit by default, levels drawn with their TF rows


json knobs_json(const Knobs& k) {
  return {{"compositing", to_string(k.compositing)},
          {"spacing", k.spacing},
          {"tolerance", k.tol},
          {"tolerance_rule", to_string(k.rule)},
          {"preintegrated", k.preintegrated},
          {"sampling_tol", k.sampling_tol}};
}

json key_of(const CalibrationRequest& r, const tsp::TransferFunction& tf,
            const std::vector<int>& steps) {
  std::error_code ec;
  const fs::path canon = fs::weakly_canonical(r.tsp_path, ec);
  const auto bytes = fs::file_size(r.tsp_path, ec);
  const auto mtime = fs::last_write_time(r.tsp_path, ec).time_since_epoch().count();
  std::ostringstream tf_text;
  tf_text.precision(9);
  tf_text << tf.domain().lo << ' ' << tf.domain().hi;
  for (const tsp::Rgba& e : tf.entries()) tf_text << ' ' << e.r << ' ' << e.g << ' ' << e.b << ' ' << e.a;
  json comps = json::array();
  for (Compositing c : r.grid.compositings) comps.push_back(to_string(c));
  json pre = json::array();
  for (bool p : r.grid.preintegration) pre.push_back(p);
  json rules = json::array();
  for (ToleranceRule t : r.grid.tolerance_rules) rules.push_back(to_string(t));
  const tsp::CameraParams& c = r.camera;
  return {{"version", kCalibrationVersion},
          {"file", canon.string()},
          {"file_bytes", std::int64_t(bytes)},
          {"file_mtime", std::int64_t(mtime)},
          {"field", r.field},
          {"tf", key_hash(tf_text.str())},
          {"metric", tsp::to_string(r.metric)},
          {"size", {c.width, c.height}},
          {"view", {c.azimuth_deg, c.elevation_deg}},
          {"zoom", c.zoom},
          {"pan", {c.pan[0], c.pan[1]}},
          {"projection", c.projection == tsp::Projection::perspective ? "perspective" : "orthographic"},
          {"fov", c.fov_deg},
          {"voxel_size", {c.voxel_size[0], c.voxel_size[1], c.voxel_size[2]}},
          {"steps", steps},
          {"sweep", r.sweep},
          {"sweep_decades", kSweepDecades},
          {"compositings", comps},
          {"spacings", r.grid.spacings},
          {"preintegration", pre},
          {"sampling_tols", r.grid.sampling_tols},
          {"tolerance_rules", rules},
          {"reference_spacing", r.reference_spacing}};
}

std::optional<Calibration> read_cache(const fs::path& file, const json& key) {
  std::error_code ec;
  if (!fs::exists(fs::symlink_status(file, ec))) return std::nullopt;
  try {
    // Through the input gate: a FIFO, a device or a file larger than any calibration is refused
    // before a byte is read, and recomputed.
    const std::string text =
        tsp::read_input_file(file.string(), "calibration cache", kMaxCalibrationBytes);
    Calibration c = calibration_from_json(tsp::parse_json(text, file.string()), file.string());
    if (c.key != key) return std::nullopt;
    return c;
  } catch (const std::exception&) {
    return std::nullopt;  // corrupt or foreign: recompute
  }
}

}  // namespace

std::string default_calibration_dir() {
  if (const char* d = std::getenv("TSPPLAY_CACHE_DIR"); d && *d) return d;
  if (const char* x = std::getenv("XDG_CACHE_HOME"); x && *x) return (fs::path(x) / "tspplay").string();
  if (const char* h = std::getenv("HOME"); h && *h)
    return (fs::path(h) / ".cache" / "tspplay").string();
  return "";
}

json to_json(const Calibration& c) {
  json pts = json::array();
  for (const CalibrationPoint& p : c.points) {
    json j = knobs_json(p.knobs);
    j["mean_delta_e"] = p.mean_de;
    j["max_step_delta_e"] = p.max_step_de;
    j["probe_ms"] = p.ms;
    pts.push_back(j);
  }
  return {{"key", c.key}, {"points", pts}};
}

Calibration calibration_from_json(const json& j, const std::string& what) {
  try {
    Calibration c;
    c.key = j.at("key");
    for (const json& p : j.at("points")) {
      CalibrationPoint pt;
      pt.knobs.compositing = parse_compositing(p.at("compositing").get<std::string>(), what);
      pt.knobs.spacing = p.at("spacing").get<double>();
      pt.knobs.tol = p.at("tolerance").get<double>();
      pt.knobs.rule = parse_tolerance_rule(p.value("tolerance_rule", std::string("equal")), what);
      pt.knobs.preintegrated = p.at("preintegrated").get<bool>();
      pt.knobs.sampling_tol = p.value("sampling_tol", 0.0);
      pt.mean_de = p.at("mean_delta_e").get<double>();
      pt.max_step_de = p.at("max_step_delta_e").get<double>();
      pt.ms = p.at("probe_ms").get<double>();
      RenderSettings check;
      apply(pt.knobs, check);
      validate(check);  // a bad spacing or tolerance: UsageError, reported as FormatError below
      for (double v : {pt.mean_de, pt.max_step_de, pt.ms})
        if (!(v >= 0) || !std::isfinite(v))
          throw tsp::FormatError(what + ": not a tspplay calibration: a point's dE or time is " +
                                 std::to_string(v));
      c.points.push_back(pt);
    }
    return c;
  } catch (const json::exception& e) {
    throw tsp::FormatError(what + ": not a tspplay calibration: " + e.what());
  } catch (const tsp::UsageError& e) {
    throw tsp::FormatError(what + ": not a tspplay calibration: " + e.what());
  }
}

std::optional<CalibrationPoint> pick_configuration(const Calibration& c, double de) {
  std::optional<CalibrationPoint> best;
  for (const CalibrationPoint& p : c.points)
    if (p.max_step_de <= kQualityMargin * de && (!best || p.ms < best->ms)) best = p;
  return best;
}

Calibrator::Calibrator(GlContext& ctx, const CalibrationRequest& r,
                       const tsp::BrickStore& bricks, const tsp::TransferFunction& tf)
    : ctx_(ctx), request_(r), bricks_(bricks), tf_(tf) {
  steps_ = search_step_sample(0, bricks.tree().time().steps() - 1, std::max(1, r.steps));
  calibration_.key = key_of(r, tf, steps_);
  const std::string dir = r.cache_dir.empty() ? default_calibration_dir() : r.cache_dir;
  if (dir != "-" && !dir.empty())
    cache_file_ = (fs::path(dir) / ("calibration-" + key_hash(tsp::json_text(calibration_.key)) +
                                    ".json")).string();
  if (!cache_file_.empty())
    if (auto cached = read_cache(cache_file_, calibration_.key)) {
      calibration_ = std::move(*cached);
      done_ = true;
      return;
    }
  probe_ = std::make_unique<ImageProbe>(ctx_, bricks_, tf_, r.camera, steps_);
}

Calibrator::~Calibrator() = default;

int Calibrator::probes_total() const {
  if (metric_) return int(queue_.size());
  const std::size_t cells = grid_cells(request_.grid, false).size();
  return int(cells * std::size_t(request_.sweep + 1));
}

void Calibrator::plan() {
  metric_ = std::make_unique<tsp::MetricResult>(
      tsp::compute_errors(request_.metric, bricks_.tree(), tf_, &bricks_, 0));
  // Tolerances: 0 and `sweep` log-spaced values up to the largest node error.
  const ErrorSpan span = error_span(*metric_);
  std::vector<double> tols{0};
  const int sweep = request_.sweep;
  if (span.largest > 0 && sweep > 0) {
    const double lo =
        std::max(span.smallest_positive, span.largest * std::pow(10.0, -kSweepDecades));
    for (int i = 0; i < sweep; ++i)
      tols.push_back(sweep == 1 ? span.largest
                                : lo * std::pow(span.largest / lo, double(i) / (sweep - 1)));
  }
  for (const Knobs& cell : grid_cells(request_.grid, false))
    for (double tol : tols) {
      // Zero tolerance is the same picture under every rule: calibrated under the first only.
      if (tol == 0 && cell.rule != request_.grid.tolerance_rules.front()) continue;
      Knobs k = cell;
      k.tol = tol;
      queue_.push_back(k);
    }
}

void Calibrator::finish() {
  done_ = true;
  probe_.reset();
  if (cache_file_.empty()) return;
  const fs::path path(cache_file_);
  std::error_code ec;
  fs::create_directories(path.parent_path(), ec);
  if (ec)
    throw tsp::IoError(path.parent_path().string() +
                       ": cannot create the calibration cache directory: " + ec.message());
  // A link, FIFO or device planted at the entry's name is replaced, never written through.
  tsp::write_file_atomically(path.string(), tsp::json_text(to_json(calibration_), 1) + "\n",
                             tsp::OutputLinks::replace);
}

bool Calibrator::advance(double budget_ms, const CalibrationProgress& progress) {
  const tsp::Stopwatch watch;
  while (!done_) {
    if (reference_.size() < steps_.size()) {  // the full-quality pictures first
      Knobs ref;
      ref.baseline = true;
      ref.compositing = Compositing::slices;
      ref.spacing = request_.reference_spacing;
      reference_.push_back(probe_->render_step(ref, nullptr, reference_.size()).first);
    } else if (!metric_) {
      plan();
    } else if (next_ < queue_.size()) {
      const Knobs& k = queue_[next_];
      auto [image, ms] = probe_->render_step(k, metric_.get(), step_);
      const double de = tsp::diff_images(image, reference_[step_]).mean;
      current_.mean_de += de / double(steps_.size());
      current_.max_step_de = std::max(current_.max_step_de, de);
      current_ms_.push_back(ms);
      if (++step_ == steps_.size()) {
        current_.knobs = k;
        current_.ms = median(std::move(current_ms_));
        calibration_.points.push_back(current_);
        current_ = {};
        current_ms_.clear();
        step_ = 0;
        ++next_;
        if (progress)
          progress("calibrating " + render_options(k, request_.metric), probes_done(),
                   probes_total());
      }
    } else {
      finish();
    }
    if (watch.ms() >= budget_ms) break;
  }
  return done_;
}

Calibration calibrate(GlContext& ctx, const CalibrationRequest& r, const tsp::BrickStore& bricks,
                      const tsp::TransferFunction& tf, std::string* cache_file,
                      const CalibrationProgress& progress) {
  Calibrator c(ctx, r, bricks, tf);
  if (cache_file) *cache_file = c.cache_file();
  while (!c.advance(std::numeric_limits<double>::infinity(), progress)) {
  }
  return c.calibration();
}

}  // namespace tspgl
