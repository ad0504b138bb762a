#include "jobs/bench_job.h"

#include <algorithm>
#include <array>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <limits>
#include <map>
#include <memory>
#include <sstream>

#include "jobs/render_job.h"
#include "render/volume_renderer.h"
#include "tsp/core/error.h"
#include "tsp/core/temp_output.h"
#include "tsp/metric/compute_errors.h"
#include "tsp/metric/tf_io.h"
#include "tsp/report/image.h"
#include "tsp/report/image_diff.h"
#include "tsp/report/svg_plot.h"
#include "tsp/store/tsp_file.h"

namespace tspgl {

namespace {

namespace fs = std::filesystem;
using nlohmann::json;

// The search's low bracket is the smallest positive node error (below it every traversal is the
// zero-tolerance one), but at most this many decades below the largest, to bound the bisection.
constexpr double kMaxSearchDecades = 9;

// A timed run: run_render_job without files, summarised over its last pass.
struct Timing {
  double median_ms = 0, first_pass_median_ms = 0, metric_ms = 0;
  std::vector<int> steps;
  std::vector<double> step_ms;  // last pass, per step
  std::array<double, 4> classes{};
  double bytes_uploaded = 0;  // mean per frame, last pass
  std::string renderer;
};

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

json timing_json(const Timing& t) {
  return {{"median_ms", t.median_ms},    {"first_pass_median_ms", t.first_pass_median_ms},
          {"metric_ms", t.metric_ms},    {"steps", t.steps},
          {"step_ms", t.step_ms},        {"not_rendered", t.classes[0]},
          {"untextured", t.classes[1]},  {"reused_texture", t.classes[2]},
          {"new_texture", t.classes[3]}, {"bytes_uploaded_per_frame", t.bytes_uploaded}};
}

// Renders the search's sample steps into images on one offscreen context (cache off: the
// pictures do not depend on the cache, and nothing stale survives a tolerance change).
class ImageProbe {
 public:
  ImageProbe(const tsp::TspFile& file, const tsp::TransferFunction& tf,
             const tsp::CameraParams& params, std::vector<int> steps)
      : ctx_(create_offscreen_context(params.width, params.height)),
        renderer_(*ctx_, file, tsp::CachePolicy::off),
        camera_(file.tree().octree().dims(), params),
        steps_(std::move(steps)) {
    renderer_.set_transfer_function(tf);
  }
  // metric null: the non-TSP baseline.
  std::vector<tsp::Image> render(const tsp::MetricResult* metric, double tol) {
    RenderSettings s;
    s.tol = {tol, tol};
    std::vector<tsp::Image> out;
    for (int t : steps_) {
      if (metric)
        renderer_.render(t, camera_, s, *metric);
      else
        renderer_.render_baseline(t, camera_, s);
      out.push_back(ctx_->read_pixels());
    }
    return out;
  }

 private:
  std::unique_ptr<GlContext> ctx_;
  VolumeRenderer renderer_;
  tsp::Camera camera_;
  std::vector<int> steps_;
};

double mean_delta_e(const std::vector<tsp::Image>& a, const std::vector<tsp::Image>& b) {
  double sum = 0;
  for (std::size_t i = 0; i < a.size(); ++i) sum += tsp::diff_images(a[i], b[i]).mean;
  return a.empty() ? 0 : sum / double(a.size());
}

// Smallest positive and largest finite e_s or e_t of a non-transparent node: below the first
// every traversal is the zero-tolerance one; at or above the second it stops at the root.
struct ErrorSpan {
  double smallest_positive = 0, largest = 0;
};

ErrorSpan error_span(const tsp::MetricResult& m) {
  ErrorSpan s;
  s.smallest_positive = std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i < m.errors.spatial.size(); ++i) {
    if (m.transparent[i]) continue;
    for (float e : {m.errors.spatial[i], m.errors.temporal[i]}) {
      if (!std::isfinite(e)) continue;
      s.largest = std::max(s.largest, double(e));
      if (e > 0) s.smallest_positive = std::min(s.smallest_positive, double(e));
    }
  }
  if (!std::isfinite(s.smallest_positive)) s.smallest_positive = 0;
  return s;
}

// One search result.
struct Found {
  double target = 0, tol = 0, mean_de = 0;
  bool met = false;
};

// Tolerance search for one metric over all targets; evaluations are shared between targets.
std::vector<Found> search(ImageProbe& probe, const std::vector<tsp::Image>& baseline,
                          const tsp::MetricResult& metric, const std::vector<double>& targets,
                          int iterations, json& evaluations) {
  std::map<double, double> cache;
  auto eval = [&](double tol) {
    auto it = cache.find(tol);
    if (it != cache.end()) return it->second;
    const double de = mean_delta_e(probe.render(&metric, tol), baseline);
    cache[tol] = de;
    evaluations.push_back({{"tolerance", tol}, {"mean_delta_e", de}});
    return de;
  };
  const double zero_de = eval(0);
  const ErrorSpan span = error_span(metric);
  const double top = span.largest;
  std::vector<Found> out;
  for (double target : targets) {
    Found f;
    f.target = target;
    if (top <= 0) {
      f.tol = 0;
    } else if (eval(top) <= target) {
      f.tol = top;  // even the coarsest picture is within the target
    } else {
      double lo = std::max(span.smallest_positive, top * std::pow(10.0, -kMaxSearchDecades));
      double hi = top;
      if (eval(lo) > target) {
        f.tol = 0;
      } else {
        // Invariant: lo meets the target, hi does not.
        for (int i = 0; i < iterations; ++i) {
          const double mid = std::sqrt(lo * hi);
          (eval(mid) <= target ? lo : hi) = mid;
        }
        f.tol = lo;
      }
    }
    f.mean_de = f.tol == 0 ? zero_de : eval(f.tol);
    f.met = f.mean_de <= target;
    out.push_back(f);
  }
  return out;
}

// A CSV field: quoted when it holds a comma or a quote.
std::string csv(const std::string& s) {
  if (s.find_first_of(",\"\n") == std::string::npos) return s;
  std::string q = "\"";
  for (char c : s) q += c == '"' ? std::string("\"\"") : std::string(1, c);
  return q + "\"";
}

std::string fmt(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.6g", v);
  return buf;
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

}  // namespace

std::vector<int> search_step_sample(int first, int last, int count) {
  std::vector<int> out;
  const int n = last - first + 1;
  if (count <= 0 || n <= 0) return out;
  if (n <= count) {
    for (int t = first; t <= last; ++t) out.push_back(t);
  } else if (count == 1) {
    out.push_back(first);
  } else {
    for (int i = 0; i < count; ++i)
      out.push_back(first + int(std::lround(double(i) * (n - 1) / (count - 1))));
  }
  return out;
}

json run_bench(const BenchOptions& o, const BenchProgress& progress) {
  if (o.out_dir.empty()) throw tsp::UsageError("bench needs an output directory (-o)");
  if (o.tfs.empty()) throw tsp::UsageError("bench needs at least one transfer function");
  if (o.metrics.empty()) throw tsp::UsageError("--metrics: give at least one metric");
  for (double t : o.targets)
    if (!(t > 0) || !std::isfinite(t))
      throw tsp::UsageError("--targets: each target mean dE must be positive, got " + fmt(t));
  if (o.search_steps < 1) throw tsp::UsageError("--search-steps must be at least 1");
  if (o.search_iterations < 0) throw tsp::UsageError("--search-iterations must not be negative");
  if (o.passes < 1) throw tsp::UsageError("--passes must be at least 1");
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

  json report;
  report["file"] = o.tsp_path;
  report["dims"] = {tree.octree().dims().x, tree.octree().dims().y, tree.octree().dims().z};
  report["brick_size"] = tree.octree().brick_size();
  report["steps"] = {o.first_step, last};
  report["size"] = {o.camera.width, o.camera.height};
  report["view"] = {o.camera.azimuth_deg, o.camera.elevation_deg};
  report["passes"] = o.passes;
  report["targets"] = o.targets;
  report["search_steps"] = sample;
  report["search_iterations"] = o.search_iterations;
  report["tolerance_rule"] = "spatial = temporal = tolerance";
  report["table3"] = json::array();
  report["table4"] = json::array();
  report["table5"] = json::array();
  report["searches"] = json::array();
  report["plots"] = json::array();

  std::ostringstream t3, t4, t5;
  t3 << "tf,renderer,metric,cache,median_ms,first_pass_median_ms,speedup,metric_ms,mean_delta_e\n";
  t4 << "tf,metric,target_delta_e,tolerance,mean_delta_e,target_met,median_ms_cache_off,"
        "median_ms_cache_on,speedup_cache_off,speedup_cache_on\n";
  t5 << "tf,metric,cache,tolerance,target_delta_e,not_rendered,untextured,reused_texture,"
        "new_texture\n";
  auto add_t5 = [&](const std::string& tf, const std::string& metric, const char* cache, double tol,
                    double target, const Timing& t) {
    t5 << csv(tf) << ',' << metric << ',' << cache << ',' << fmt(tol) << ','
       << (target > 0 ? fmt(target) : "") << ',' << fmt(t.classes[0]) << ',' << fmt(t.classes[1])
       << ',' << fmt(t.classes[2]) << ',' << fmt(t.classes[3]) << '\n';
    report["table5"].push_back({{"tf", tf},
                                {"metric", metric},
                                {"cache", cache},
                                {"tolerance", tol},
                                {"target_delta_e", target > 0 ? json(target) : json()},
                                {"not_rendered", t.classes[0]},
                                {"untextured", t.classes[1]},
                                {"reused_texture", t.classes[2]},
                                {"new_texture", t.classes[3]}});
  };

  for (std::size_t k = 0; k < tfs.size(); ++k) {
    const std::string& tf_arg = o.tfs[k];
    const std::string tag = tf_tag(tf_arg);
    RenderJobOptions job = base;
    job.tf = tf_arg;

    // Searches first, on their own context (run_render_job makes its own current).
    std::vector<std::vector<Found>> found(o.metrics.size());
    std::vector<double> zero_de(o.metrics.size());
    std::vector<double> metric_ms(o.metrics.size());
    json searches = json::array();
    {
      ImageProbe probe(*file, tfs[k], o.camera, sample);
      const std::vector<tsp::Image> baseline = probe.render(nullptr, 0);
      for (std::size_t m = 0; m < o.metrics.size(); ++m) {
        const std::string name = tsp::to_string(o.metrics[m]);
        tick(tag + ": search " + name);
        tsp::MetricResult metric = tsp::compute_errors(o.metrics[m], tree, tfs[k], file.get(), 0);
        json evals = json::array();
        found[m] = search(probe, baseline, metric, o.targets, o.search_iterations, evals);
        zero_de[m] = evals[0]["mean_delta_e"];
        searches.push_back({{"tf", tf_arg},
                            {"metric", name},
                            {"largest_error", error_span(metric).largest},
                            {"smallest_positive_error", error_span(metric).smallest_positive},
                            {"evaluations", evals}});
        ++done;
      }
    }
    report["searches"].insert(report["searches"].end(), searches.begin(), searches.end());

    // Table 3: zero tolerance.
    tick(tag + ": baseline");
    job.baseline = true;
    const Timing b = time_run(job);
    report["renderer"] = b.renderer;
    ++done;
    t3 << csv(tf_arg) << ",baseline,,," << fmt(b.median_ms) << ',' << fmt(b.first_pass_median_ms)
       << ",1,,0\n";
    json rb = timing_json(b);
    rb["tf"] = tf_arg;
    rb["renderer"] = "baseline";
    report["table3"].push_back(rb);
    job.baseline = false;
    std::vector<tsp::PlotSeries> frame_series;
    frame_series.push_back({"baseline", {b.steps.begin(), b.steps.end()}, b.step_ms});
    for (std::size_t m = 0; m < o.metrics.size(); ++m) {
      const std::string name = tsp::to_string(o.metrics[m]);
      job.metric = o.metrics[m];
      for (tsp::CachePolicy c : {tsp::CachePolicy::off, tsp::CachePolicy::on}) {
        tick(tag + ": zero tolerance, " + name + ", cache " + cache_name(c));
        job.cache = c;
        job.tol = {0, 0};
        const Timing t = time_run(job);
        ++done;
        metric_ms[m] = t.metric_ms;
        t3 << csv(tf_arg) << ",tsp," << name << ',' << cache_name(c) << ',' << fmt(t.median_ms)
           << ',' << fmt(t.first_pass_median_ms) << ',' << fmt(b.median_ms / t.median_ms) << ','
           << fmt(t.metric_ms) << ',' << fmt(zero_de[m]) << '\n';
        json r = timing_json(t);
        r["tf"] = tf_arg;
        r["renderer"] = "tsp";
        r["metric"] = name;
        r["cache"] = cache_name(c);
        r["speedup"] = b.median_ms / t.median_ms;
        r["mean_delta_e"] = zero_de[m];
        report["table3"].push_back(r);
        add_t5(tf_arg, name, cache_name(c), 0, 0, t);
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
      tsp::PlotSeries pts{name + " (cache on)", {}, {}, true, true};
      for (const Found& f : found[m]) {
        job.tol = {f.tol, f.tol};
        std::array<Timing, 2> t;
        for (tsp::CachePolicy c : {tsp::CachePolicy::off, tsp::CachePolicy::on}) {
          tick(tag + ": target dE " + fmt(f.target) + ", " + name + ", cache " + cache_name(c));
          job.cache = c;
          t[c == tsp::CachePolicy::on] = time_run(job);
          ++done;
          add_t5(tf_arg, name, cache_name(c), f.tol, f.target, t[c == tsp::CachePolicy::on]);
        }
        t4 << csv(tf_arg) << ',' << name << ',' << fmt(f.target) << ',' << fmt(f.tol) << ','
           << fmt(f.mean_de) << ',' << (f.met ? 1 : 0) << ',' << fmt(t[0].median_ms) << ','
           << fmt(t[1].median_ms) << ',' << fmt(b.median_ms / t[0].median_ms) << ','
           << fmt(b.median_ms / t[1].median_ms) << '\n';
        report["table4"].push_back({{"tf", tf_arg},
                                    {"metric", name},
                                    {"target_delta_e", f.target},
                                    {"tolerance", f.tol},
                                    {"mean_delta_e", f.mean_de},
                                    {"target_met", f.met},
                                    {"cache_off", timing_json(t[0])},
                                    {"cache_on", timing_json(t[1])}});
        pts.x.push_back(f.mean_de);
        pts.y.push_back(t[1].median_ms);
      }
      // The zero-tolerance point starts each curve.
      for (const json& r : report["table3"])
        if (r["tf"] == tf_arg && r.value("metric", "") == name && r["cache"] == "on") {
          pts.x.insert(pts.x.begin(), zero_de[m]);
          pts.y.insert(pts.y.begin(), r["median_ms"].get<double>());
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
    report["plots"].push_back(frame_svg);
    report["plots"].push_back(error_svg);
  }
  tick("done");
  tsp::write_file_atomically((dir / "table3.csv").string(), t3.str());
  tsp::write_file_atomically((dir / "table4.csv").string(), t4.str());
  tsp::write_file_atomically((dir / "table5.csv").string(), t5.str());
  tsp::write_file_atomically((dir / "report.json").string(), report.dump(2) + "\n");
  return report;
}

}  // namespace tspgl
