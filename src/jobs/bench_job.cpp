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
  const int m_count = int(o.metrics.size()), t_count = int(o.targets.size());
  const int total = int(tfs.size()) * (1 + 2 * m_count + m_count + 2 * m_count * t_count);
  int done = 0;
  auto tick = [&](const std::string& phase) {
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

  for (std::size_t k = 0; k < tfs.size(); ++k) {
    const std::string& tf_arg = o.tfs[k];
    const std::string tag = tf_tag(tf_arg);
    RenderJobOptions job = base;
    job.tf = tf_arg;

    // Searches first, on their own context (run_render_job makes its own current).
    std::vector<std::vector<FoundTolerance>> found(o.metrics.size());
    std::vector<double> zero_de(o.metrics.size());
    {
      ImageProbe probe(*file, tfs[k], o.camera, sample);
      const std::vector<tsp::Image> baseline = probe.render_baseline();
      for (std::size_t m = 0; m < o.metrics.size(); ++m) {
        const std::string name = tsp::to_string(o.metrics[m]);
        tick(tag + ": search " + name);
        const tsp::MetricResult metric =
            tsp::compute_errors(o.metrics[m], tree, tfs[k], file.get(), 0);
        json evals = json::array();
        auto error_at = [&](double tol) {
          const double de = mean_delta_e(probe.render(metric, tol), baseline);
          evals.push_back({{"tolerance", tol}, {"mean_delta_e", de}});
          if (tol == 0) zero_de[m] = de;
          return de;
        };
        const ErrorSpan span = error_span(metric);
        found[m] = search_tolerances(error_at, span, o.targets, o.search_iterations);
        report.add_search(tf_arg, name, span, evals);
        ++done;
      }
    }

    // Table 3: zero tolerance.
    tick(tag + ": baseline");
    job.baseline = true;
    const Timing b = time_run(job);
    ++done;
    report.add_baseline(tf_arg, b);
    job.baseline = false;
    std::vector<tsp::PlotSeries> frame_series;
    frame_series.push_back({"baseline", {b.steps.begin(), b.steps.end()}, b.step_ms});
    std::vector<double> zero_ms_cache_on(o.metrics.size());
    for (std::size_t m = 0; m < o.metrics.size(); ++m) {
      const std::string name = tsp::to_string(o.metrics[m]);
      job.metric = o.metrics[m];
      for (tsp::CachePolicy c : {tsp::CachePolicy::off, tsp::CachePolicy::on}) {
        tick(tag + ": zero tolerance, " + name + ", cache " + cache_name(c));
        job.cache = c;
        job.tol = {0, 0};
        const Timing t = time_run(job);
        ++done;
        if (c == tsp::CachePolicy::on) zero_ms_cache_on[m] = t.median_ms;
        report.add_zero_tolerance(tf_arg, name, cache_name(c), t, b.median_ms, zero_de[m]);
        frame_series.push_back({"tsp " + name + ", cache " + cache_name(c),
                                {t.steps.begin(), t.steps.end()},
                                t.step_ms});
      }
    }

    // Table 4: the found tolerances, timed.
    std::vector<tsp::PlotSeries> error_series;
    error_series.push_back({"baseline", {0.0}, {b.median_ms}, false, true});
    for (std::size_t m = 0; m < o.metrics.size(); ++m) {
      const std::string name = tsp::to_string(o.metrics[m]);
      job.metric = o.metrics[m];
      // The zero-tolerance point starts each curve.
      tsp::PlotSeries pts{name + " (cache on)", {zero_de[m]}, {zero_ms_cache_on[m]}, true, true};
      for (const FoundTolerance& f : found[m]) {
        job.tol = {f.tol, f.tol};
        std::array<Timing, 2> t;
        for (tsp::CachePolicy c : {tsp::CachePolicy::off, tsp::CachePolicy::on}) {
          tick(tag + ": target dE " + fmt(f.target) + ", " + name + ", cache " + cache_name(c));
          job.cache = c;
          t[c == tsp::CachePolicy::on] = time_run(job);
          ++done;
        }
        report.add_target(tf_arg, name, f, t[0], t[1], b.median_ms);
        pts.x.push_back(f.mean_de);
        pts.y.push_back(t[1].median_ms);
      }
      error_series.push_back(pts);
    }

    const std::string size = std::to_string(o.camera.width) + "x" + std::to_string(o.camera.height);
    const std::string frame_svg = "frame_time_" + tag + ".svg",
                      error_svg = "time_vs_error_" + tag + ".svg";
    tsp::write_svg_plot({"Frame time per step, zero tolerance (" + tf_arg + ", " + size + ")",
                         "time step", "frame time (ms)", frame_series},
                        (dir / frame_svg).string());
    tsp::write_svg_plot(
        {"Frame time vs image error (" + tf_arg + ", " + size + ")", "mean dE against the baseline",
         "median frame time (ms), cache on", error_series},
        (dir / error_svg).string());
    report.add_plot(frame_svg);
    report.add_plot(error_svg);
  }
  tick("done");
  return report.write(dir.string());
}

}  // namespace tspgl
