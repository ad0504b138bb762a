#include "jobs/bench_job.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <filesystem>

#include "jobs/bench_report.h"
#include "jobs/image_probe.h"
#include "jobs/render_job.h"
#include "jobs/tolerance_search.h"
#include "tsp/core/error.h"
#include "tsp/metric/compute_errors.h"
#include "tsp/metric/tf_io.h"
#include "tsp/report/svg_plot.h"
#include "tsp/store/tsp_file.h"

namespace tspgl {

namespace {

namespace fs = std::filesystem;
using nlohmann::json;

// A timed run: run_render_job without files, summarised over its last pass.
Timing time_run(RenderJobOptions o) {
  o.out_dir.clear();
  RenderJobResult r = run_render_job(o);
  Timing t;
  t.median_ms = median_frame_ms(r, o.passes);
  t.first_pass_median_ms = median_frame_ms(r, 1);
  t.metric_ms = r.metric_ms;
  t.renderer = r.renderer;
  for (const FrameRecord& f : r.frames) {
    if (f.pass != o.passes) continue;
    t.steps.push_back(f.report.step);
    t.step_ms.push_back(f.report.ms);
    for (std::size_t c = 0; c < 4; ++c) t.classes[c] += f.report.class_percent[c];
    t.bytes_uploaded += double(f.report.bytes_uploaded);
  }
  const double n = double(std::max<std::size_t>(1, t.steps.size()));
  for (double& c : t.classes) c /= n;
  t.bytes_uploaded /= n;
  return t;
}

// File-name-safe form of a TF argument ("preset:sparse" → "sparse", "a/b.json" → "b").
std::string tf_tag(const std::string& tf) {
  std::string s = tf.rfind("preset:", 0) == 0 ? tf.substr(7) : fs::path(tf).stem().string();
  for (char& c : s)
    if (!std::isalnum(static_cast<unsigned char>(c)) && c != '-' && c != '_') c = '_';
  return s.empty() ? "tf" : s;
}

const char* cache_name(tsp::CachePolicy c) {
  return c == tsp::CachePolicy::on ? "on" : "off";
}

void check_options(const BenchOptions& o) {
  if (o.out_dir.empty()) throw tsp::UsageError("bench needs an output directory (-o)");
  if (o.tfs.empty()) throw tsp::UsageError("bench needs at least one transfer function");
  if (o.metrics.empty()) throw tsp::UsageError("--metrics: give at least one metric");
  for (double t : o.targets)
    if (!(t > 0) || !std::isfinite(t))
      throw tsp::UsageError("--targets: each target mean dE must be positive, got " + fmt(t));
  if (o.search_steps < 1) throw tsp::UsageError("--search-steps must be at least 1");
  if (o.search_iterations < 0) throw tsp::UsageError("--search-iterations must not be negative");
  if (o.passes < 1) throw tsp::UsageError("--passes must be at least 1");
}

// One transfer function's share of the bench: searches, then Table 3, then Table 4, then plots.
class TfBench {
 public:
  TfBench(const BenchOptions& o, const tsp::TspFile& file, const tsp::TransferFunction& tf,
          const std::string& tf_arg, RenderJobOptions job, const std::vector<int>& sample,
          BenchReport& report, const std::function<void(const std::string&)>& tick)
      : o_(o), file_(file), tf_(tf), tf_arg_(tf_arg), tag_(tf_tag(tf_arg)), job_(std::move(job)),
        sample_(sample), report_(report), tick_(tick) {
    job_.tf = tf_arg;
  }

  void run(const fs::path& dir) {
    search();
    zero_tolerance();
    targets();
    plots(dir);
  }

 private:
  const BenchOptions& o_;
  const tsp::TspFile& file_;
  const tsp::TransferFunction& tf_;
  const std::string& tf_arg_;
  const std::string tag_;
  RenderJobOptions job_;
  const std::vector<int>& sample_;
  BenchReport& report_;
  const std::function<void(const std::string&)>& tick_;
  // Per metric: the tolerances found, the zero-tolerance picture's ΔE, its cache-on frame time.
  std::vector<std::vector<FoundTolerance>> found_;
  std::vector<double> zero_de_, zero_ms_cache_on_;
  Timing baseline_;
  std::vector<tsp::PlotSeries> frame_series_, error_series_;

  // The tolerance searches, on their own context (run_render_job makes its own current).
  void search() {
    const std::size_t n = o_.metrics.size();
    found_.assign(n, {});
    zero_de_.assign(n, 0);
    ImageProbe probe(file_, tf_, o_.camera, sample_);
    const std::vector<tsp::Image> baseline = probe.render_baseline();
    for (std::size_t m = 0; m < n; ++m) {
      const std::string name = tsp::to_string(o_.metrics[m]);
      tick_(tag_ + ": search " + name);
      const tsp::MetricResult metric =
          tsp::compute_errors(o_.metrics[m], file_.tree(), tf_, &file_, 0);
      json evals = json::array();
      auto error_at = [&](double tol) {
        const double de = mean_delta_e(probe.render(metric, tol), baseline);
        evals.push_back({{"tolerance", tol}, {"mean_delta_e", de}});
        if (tol == 0) zero_de_[m] = de;
        return de;
      };
      const ErrorSpan span = error_span(metric);
      found_[m] = search_tolerances(error_at, span, o_.targets, o_.search_iterations);
      report_.add_search(tf_arg_, name, span, evals);
    }
  }

  // Table 3: the baseline and every metric at zero tolerance, cache off and on.
  void zero_tolerance() {
    tick_(tag_ + ": baseline");
    job_.baseline = true;
    baseline_ = time_run(job_);
    report_.add_baseline(tf_arg_, baseline_);
    job_.baseline = false;
    frame_series_.push_back(
        {"baseline", {baseline_.steps.begin(), baseline_.steps.end()}, baseline_.step_ms});
    zero_ms_cache_on_.assign(o_.metrics.size(), 0);
    for (std::size_t m = 0; m < o_.metrics.size(); ++m) {
      const std::string name = tsp::to_string(o_.metrics[m]);
      job_.metric = o_.metrics[m];
      for (tsp::CachePolicy c : {tsp::CachePolicy::off, tsp::CachePolicy::on}) {
        tick_(tag_ + ": zero tolerance, " + name + ", cache " + cache_name(c));
        job_.cache = c;
        job_.tol = {0, 0};
        const Timing t = time_run(job_);
        if (c == tsp::CachePolicy::on) zero_ms_cache_on_[m] = t.median_ms;
        report_.add_zero_tolerance(tf_arg_, name, cache_name(c), t, baseline_.median_ms,
                                   zero_de_[m]);
        frame_series_.push_back({"tsp " + name + ", cache " + cache_name(c),
                                 {t.steps.begin(), t.steps.end()},
                                 t.step_ms});
      }
    }
  }

  // Table 4: the found tolerances, timed cache off and on.
  void targets() {
    error_series_.push_back({"baseline", {0.0}, {baseline_.median_ms}, false, true});
    for (std::size_t m = 0; m < o_.metrics.size(); ++m) {
      const std::string name = tsp::to_string(o_.metrics[m]);
      job_.metric = o_.metrics[m];
      // The zero-tolerance point starts each curve.
      tsp::PlotSeries pts{name + " (cache on)", {zero_de_[m]}, {zero_ms_cache_on_[m]}, true, true};
      for (const FoundTolerance& f : found_[m]) {
        job_.tol = {f.tol, f.tol};
        std::array<Timing, 2> t;
        for (tsp::CachePolicy c : {tsp::CachePolicy::off, tsp::CachePolicy::on}) {
          tick_(tag_ + ": target dE " + fmt(f.target) + ", " + name + ", cache " + cache_name(c));
          job_.cache = c;
          t[c == tsp::CachePolicy::on] = time_run(job_);
        }
        report_.add_target(tf_arg_, name, f, t[0], t[1], baseline_.median_ms);
        pts.x.push_back(f.mean_de);
        pts.y.push_back(t[1].median_ms);
      }
      error_series_.push_back(pts);
    }
  }

  void plots(const fs::path& dir) {
    const std::string size =
        std::to_string(o_.camera.width) + "x" + std::to_string(o_.camera.height);
    const std::string frame_svg = "frame_time_" + tag_ + ".svg",
                      error_svg = "time_vs_error_" + tag_ + ".svg";
    tsp::write_svg_plot({"Frame time per step, zero tolerance (" + tf_arg_ + ", " + size + ")",
                         "time step", "frame time (ms)", frame_series_},
                        (dir / frame_svg).string());
    tsp::write_svg_plot({"Frame time vs image error (" + tf_arg_ + ", " + size + ")",
                         "mean dE against the baseline", "median frame time (ms), cache on",
                         error_series_},
                        (dir / error_svg).string());
    report_.add_plot(frame_svg);
    report_.add_plot(error_svg);
  }
};

}  // namespace

json run_bench(const BenchOptions& o, const BenchProgress& progress) {
  check_options(o);
  auto file = tsp::TspFile::open(o.tsp_path);
  const tsp::TspTree& tree = file->tree();
  const int last = checked_last_step(tree, o.first_step, o.last_step, o.tsp_path);
  std::vector<tsp::TransferFunction> tfs;
  for (const std::string& arg : o.tfs)
    tfs.push_back(tsp::transfer_function_from_arg(arg, tree.value_range()));

  const fs::path dir = o.out_dir;
  std::error_code ec;
  fs::create_directories(dir, ec);
  if (ec) throw tsp::IoError(o.out_dir + ": cannot create the report directory: " + ec.message());

  const std::vector<int> sample = search_step_sample(o.first_step, last, o.search_steps);
  // Runs per TF: one search per metric, the baseline, 2 zero-tolerance runs and 2 per target
  // per metric.
  const int m_count = int(o.metrics.size()), t_count = int(o.targets.size());
  const int total = int(tfs.size()) * (1 + 2 * m_count + m_count + 2 * m_count * t_count);
  int done = -1;
  const std::function<void(const std::string&)> tick = [&](const std::string& phase) {
    ++done;
    if (progress) progress(phase, done, total);
  };

  RenderJobOptions base;
  base.tsp_path = o.tsp_path;
  base.first_step = o.first_step;
  base.last_step = last;
  base.camera = o.camera;
  base.passes = o.passes;

  json header;
  header["file"] = o.tsp_path;
  header["dims"] = {tree.octree().dims().x, tree.octree().dims().y, tree.octree().dims().z};
  header["brick_size"] = tree.octree().brick_size();
  header["steps"] = {o.first_step, last};
  header["size"] = {o.camera.width, o.camera.height};
  header["view"] = {o.camera.azimuth_deg, o.camera.elevation_deg};
  header["passes"] = o.passes;
  header["targets"] = o.targets;
  header["search_steps"] = sample;
  header["search_iterations"] = o.search_iterations;
  header["tolerance_rule"] = "spatial = temporal = tolerance";
  BenchReport report(std::move(header));

  for (std::size_t k = 0; k < tfs.size(); ++k)
    TfBench(o, *file, tfs[k], o.tfs[k], base, sample, report, tick).run(dir);
  tick("done");
  return report.write(dir.string());
}

}  // namespace tspgl
