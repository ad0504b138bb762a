#include "jobs/bench_job.h"

#include <algorithm>
#include <cstdio>
#include <cctype>
#include <cmath>
#include <filesystem>
#include <optional>

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
  return timing_of(run_render_job(o), o.passes);
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
  if (o.head_to_head_rounds < 1 || o.head_to_head_rounds > kMaxRounds)
    throw tsp::UsageError("--rounds " + std::to_string(o.head_to_head_rounds) +
                          ": expected 1 to " + std::to_string(kMaxRounds) +
                          " head-to-head rounds");
  for (const KnobGrid* g : {&o.baseline_grid, &o.tsp_grid}) {
    if (g->compositings.empty() || g->spacings.empty())
      throw tsp::UsageError("bench: the knob search needs at least one compositing and spacing");
    for (double sp : g->spacings) {
      RenderSettings s;
      s.spacing = sp;
      validate(s);
    }
  }
  RenderSettings s;
  s.spacing = o.reference_spacing;
  validate(s);
  s.spacing = o.table3.spacing;
  validate(s);
}

// The timed run of knobs k (metric for the TSP renderer) under job's other options.
RenderJobOptions with_knobs(RenderJobOptions job, const Knobs& k, tsp::Metric metric) {
  job.baseline = k.baseline;
  apply(k, job.settings);
  job.lod = k.lod_level > 0 ? LodMode::fixed : LodMode::off;
  job.lod_level = k.lod_level;
  job.metric = metric;
  job.cache = tsp::CachePolicy::on;
  return job;
}

// One transfer function's share of the bench: reference pictures, Table 3, the knob searches
// and Table 4, then plots.
class TfBench {
 public:
  TfBench(GlContext& ctx, const BenchOptions& o, const tsp::TspFile& file,
          const tsp::TransferFunction& tf,
          const std::string& tf_arg, RenderJobOptions job, const std::vector<int>& sample,
          BenchReport& report, const std::function<void(const std::string&)>& tick)
      : o_(o), file_(file), tf_(tf), tf_arg_(tf_arg), tag_(tf_tag(tf_arg)), job_(std::move(job)),
        sample_(sample), report_(report), tick_(tick), probe_(ctx, file, tf, o.camera, sample) {
    job_.tf = tf_arg;
  }

  void run(const fs::path& dir) {
    tick_(tag_ + ": reference pictures and metrics");
    Knobs ref;
    ref.baseline = true;
    ref.compositing = Compositing::slices;
    ref.spacing = o_.reference_spacing;
    reference_ = probe_.render(ref, nullptr).images;
    for (tsp::Metric m : o_.metrics)
      metrics_.push_back(tsp::compute_errors(m, file_.tree(), tf_, &file_, 0));
    zero_tolerance();
    targets(ref);
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
  ImageProbe probe_;
  std::vector<tsp::Image> reference_;
  std::vector<tsp::MetricResult> metrics_;
  std::vector<double> zero_de_, zero_ms_cache_on_;
  std::vector<tsp::PlotSeries> frame_series_, error_series_;

  // Probes k (under metric m, its result `metric`; null for the baseline) and logs it.
  ProbeResult probe(const Knobs& k, const tsp::MetricResult* metric, tsp::Metric m, json& log) {
    const ProbeFrames f = probe_.render(k, metric);
    const ProbeResult r{mean_delta_e(f.images, reference_), f.median_ms};
    log.push_back({{"render_options", render_options(k, m)},
                   {"compositing", to_string(k.compositing)},
                   {"spacing", k.spacing},
                   {"tolerance", k.tol},
                   {"tolerance_rule", to_string(k.rule)},
                   {"preintegrated", k.preintegrated},
                   {"sampling_tol", k.sampling_tol},
                   {"mean_delta_e", r.mean_de},
                   {"probe_ms", r.ms}});
    return r;
  }

  // Table 3: the baseline and every metric at zero tolerance, cache off and on, at the table3
  // knobs; ΔE of the zero-tolerance pictures against the baseline's at the same knobs.
  void zero_tolerance() {
    tick_(tag_ + ": baseline");
    Knobs k = o_.table3;
    k.baseline = true;
    k.tol = 0;
    const std::vector<tsp::Image> base = probe_.render(k, nullptr).images;
    const Timing baseline = time_run(with_knobs(job_, k, tsp::Metric::approximate));
    report_.add_baseline(tf_arg_, baseline);
    frame_series_.push_back(
        {"baseline", {baseline.steps.begin(), baseline.steps.end()}, baseline.step_ms});
    k.baseline = false;
    zero_ms_cache_on_.assign(o_.metrics.size(), 0);
    zero_de_.assign(o_.metrics.size(), 0);
    for (std::size_t m = 0; m < o_.metrics.size(); ++m) {
      const std::string name = tsp::to_string(o_.metrics[m]);
      const std::vector<tsp::Image> zero = probe_.render(k, &metrics_[m]).images;
      const double de = mean_delta_e(zero, base);
      zero_de_[m] = mean_delta_e(zero, reference_);
      for (tsp::CachePolicy c : {tsp::CachePolicy::off, tsp::CachePolicy::on}) {
        tick_(tag_ + ": zero tolerance, " + name + ", cache " + cache_name(c));
        RenderJobOptions job = with_knobs(job_, k, o_.metrics[m]);
        job.cache = c;
        const Timing t = time_run(job);
        if (c == tsp::CachePolicy::on) zero_ms_cache_on_[m] = t.median_ms;
        report_.add_zero_tolerance(tf_arg_, name, cache_name(c), t, baseline.median_ms, de);
        frame_series_.push_back({"tsp " + name + ", cache " + cache_name(c),
                                 {t.steps.begin(), t.steps.end()},
                                 t.step_ms});
      }
    }
  }

  // The fastest of the first timed_candidates candidates, timed for real (cache on).
  std::optional<std::pair<KnobCandidate, Timing>> fastest(const std::vector<KnobCandidate>& c,
                                                          tsp::Metric metric,
                                                          const std::string& label) {
    std::optional<std::pair<KnobCandidate, Timing>> best;
    const std::size_t n = std::min(c.size(), std::size_t(std::max(1, o_.timed_candidates)));
    for (std::size_t i = 0; i < n; ++i) {
      tick_(tag_ + ": " + label + " candidate " + std::to_string(i + 1) + ": " +
            render_options(c[i].knobs, metric));
      const Timing t = time_run(with_knobs(job_, c[i].knobs, metric));
      if (!best || t.median_ms < best->second.median_ms) best = {{c[i], t}};
    }
    return best;
  }

  // A row's mean ΔE as `render FILE <its render_options> --steps <bench's steps>` draws the
  // search steps: a fresh renderer (one pass, cache on, steps in order), not the probe's. The
  // probe's renderer has drawn every configuration before, and the GL caster's texel weights
  // round with where a brick sits in the atlas, which that history sets: a row drawn by GL
  // re-rendered by `render` differed from the probe by up to 1e-4 ΔE (issue 44).
  double rendered_mean_delta_e(const Knobs& k, tsp::Metric metric) {
    RenderJobOptions job = with_knobs(job_, k, metric);
    job.out_dir.clear();
    job.passes = 1;
    std::vector<tsp::Image> images(sample_.size());
    job.on_frame = [&](const FrameRecord& f, const tsp::Image& pixels) {
      const auto it = std::find(sample_.begin(), sample_.end(), f.report.step);
      if (it != sample_.end()) images[std::size_t(it - sample_.begin())] = pixels;
    };
    run_render_job(job);
    return mean_delta_e(images, reference_);
  }

  // Table 4: per target, the fastest non-TSP configuration and per metric the fastest TSP one
  // within the target against the full-quality pictures.
  void targets(const Knobs& ref) {
    const std::size_t nt = o_.targets.size(), nm = o_.metrics.size();
    tick_(tag_ + ": baseline knob search");
    json log = json::array();
    const auto base = search_baseline_knobs(
        [&](const Knobs& k) { return probe(k, nullptr, tsp::Metric::approximate, log); }, o_.baseline_grid, o_.targets);
    report_.add_search(tf_arg_, "baseline", ErrorSpan{}, log);
    // Winners: [target][0] the baseline, [target][1 + m] metric m.
    using Winner = std::optional<std::pair<KnobCandidate, Timing>>;
    std::vector<std::vector<Winner>> win(nt, std::vector<Winner>(1 + nm));
    for (std::size_t i = 0; i < nt; ++i)
      win[i][0] = fastest(base[i], tsp::Metric::approximate,
                          "baseline, target dE " + fmt(o_.targets[i]));
    for (std::size_t m = 0; m < nm; ++m) {
      const std::string name = tsp::to_string(o_.metrics[m]);
      tick_(tag_ + ": knob search " + name);
      json evals = json::array();
      const ErrorSpan span = error_span(metrics_[m]);
      const auto found = search_tsp_knobs(
          [&](const Knobs& k) { return probe(k, &metrics_[m], o_.metrics[m], evals); }, o_.tsp_grid, span,
          o_.targets, o_.search_iterations);
      report_.add_search(tf_arg_, name, span, evals);
      for (std::size_t i = 0; i < nt; ++i)
        win[i][1 + m] = fastest(found[i], o_.metrics[m], name + ", target dE " + fmt(o_.targets[i]));
    }
    // Head to head: the reference and every winner timed again in turn, round after round, so
    // that a machine slowing down or speeding up during the bench moves all of them alike; the
    // reported times are the median over rounds of each run's median.
    std::vector<std::vector<std::vector<double>>> rounds(nt, std::vector<std::vector<double>>(1 + nm));
    std::vector<double> ref_rounds;
    auto metric_of = [&](std::size_t w) { return w == 0 ? tsp::Metric::approximate : o_.metrics[w - 1]; };
    for (int r = 0; r < o_.head_to_head_rounds; ++r) {
      tick_(tag_ + ": head to head, round " + std::to_string(r + 1));
      ref_rounds.push_back(time_run(with_knobs(job_, ref, tsp::Metric::approximate)).median_ms);
      for (std::size_t i = 0; i < nt; ++i)
        for (std::size_t w = 0; w < 1 + nm; ++w)
          if (win[i][w]) {
            const Timing t = time_run(with_knobs(job_, win[i][w]->first.knobs, metric_of(w)));
            rounds[i][w].push_back(t.median_ms);
            if (r == 0) win[i][w]->second = t;  // per-step times and class shares of one round
          }
    }
    const double ref_ms = median(ref_rounds);
    for (std::size_t i = 0; i < nt; ++i)
      for (std::size_t w = 0; w < 1 + nm; ++w)
        if (win[i][w]) {
          tick_(tag_ + ": mean dE of the winner as render draws it, target dE " + fmt(o_.targets[i]));
          win[i][w]->first.probe.mean_de = rendered_mean_delta_e(win[i][w]->first.knobs, metric_of(w));
        }
    tsp::PlotSeries base_pts{"best non-TSP", {}, {}, true, true};
    std::vector<tsp::PlotSeries> pts;
    for (std::size_t m = 0; m < nm; ++m)
      pts.push_back({std::string(tsp::to_string(o_.metrics[m])) + " (cache on)", {zero_de_[m]},
                     {zero_ms_cache_on_[m]}, true, true});
    for (std::size_t i = 0; i < nt; ++i) {
      for (std::size_t w = 0; w < 1 + nm; ++w)
        if (win[i][w] && !rounds[i][w].empty()) win[i][w]->second.median_ms = median(rounds[i][w]);
      const double base_ms = win[i][0] ? win[i][0]->second.median_ms : ref_ms;
      for (std::size_t w = 0; w < 1 + nm; ++w) {
        const Winner& b = win[i][w];
        report_.add_best(tf_arg_, w == 0 ? "baseline" : "tsp",
                         w == 0 ? "" : tsp::to_string(o_.metrics[w - 1]), o_.targets[i],
                         b ? &b->first : nullptr, b ? &b->second : nullptr, metric_of(w), base_ms,
                         ref_ms);
        if (!b) continue;
        tsp::PlotSeries& p = w == 0 ? base_pts : pts[w - 1];
        p.x.push_back(b->first.probe.mean_de);
        p.y.push_back(b->second.median_ms);
      }
    }
    error_series_.push_back(base_pts);
    for (auto& p : pts) error_series_.push_back(p);
  }

  void plots(const fs::path& dir) {
    const std::string size =
        std::to_string(o_.camera.width) + "x" + std::to_string(o_.camera.height);
    // The TF's file name, not its whole path (a preset stays preset:NAME).
    const std::string tf_name = fs::path(tf_arg_).filename().string();
    const std::string frame_svg = "frame_time_" + tag_ + ".svg",
                      error_svg = "time_vs_error_" + tag_ + ".svg";
    tsp::write_svg_plot({"Frame time per step, zero tolerance (" + tf_name + ", " + size + ")",
                         "time step", "frame time (ms)", frame_series_},
                        (dir / frame_svg).string());
    tsp::write_svg_plot({"Fastest frame within a mean dE (" + tf_name + ", " + size + ")",
                         "mean dE against the full-quality picture",
                         "median frame time (ms), cache on", error_series_},
                        (dir / error_svg).string());
    report_.add_plot(frame_svg);
    report_.add_plot(error_svg);
  }
};

}  // namespace

json run_bench(const BenchOptions& options, const BenchProgress& progress) {
  check_options(options);
  BenchOptions o = options;
  auto file = tsp::TspFile::open(o.tsp_path, o.field);
  // Physical proportions, as render shows the file by default.
  o.camera.voxel_size = shown_voxel_size(file->metadata().spacing, {1, 1, 1}, true);
  const tsp::TspTree& tree = file->tree();
  const int last = checked_last_step(tree, o.first_step, o.last_step, o.tsp_path);
  std::vector<tsp::TransferFunction> tfs;
  const tsp::ValueHistogram histogram = tsp::histogram_of(*file);
  for (const std::string& arg : o.tfs)
    tfs.push_back(tsp::transfer_function_from_arg(arg, tree.value_range(), tsp::kDefaultTfEntries,
                                                  {}, &histogram));

  const fs::path dir = make_output_dir(o.out_dir);

  const std::vector<int> sample = search_step_sample(o.first_step, last, o.search_steps);
  // Phases per TF: reference, Table 3 (baseline, 2 per metric), reference timing, baseline
  // search, one search per metric, and up to timed_candidates timed runs per target for the
  // baseline and each metric (fewer when fewer candidates meet a target), then each winner's
  // mean ΔE rendered afresh.
  const int m_count = int(o.metrics.size()), t_count = int(o.targets.size());
  const int total = int(tfs.size()) * (3 + 3 * m_count + o.head_to_head_rounds +
                                       t_count * (1 + m_count) * (std::max(1, o.timed_candidates) + 1));
  int done = -1;
  const std::function<void(const std::string&)> tick = [&](const std::string& phase) {
    ++done;
    if (progress) progress(phase, done, total);
  };

  RenderJobOptions base;
  base.tsp_path = o.tsp_path;
  base.field = o.field;
  base.first_step = o.first_step;
  base.last_step = last;
  base.camera = o.camera;
  base.passes = o.passes;
  base.gl = o.gl;
  base.gpu = o.gpu;

  json header;
  header["file"] = o.tsp_path;
  header["dims"] = {tree.octree().dims().x, tree.octree().dims().y, tree.octree().dims().z};
  header["brick_size"] = tree.octree().brick_size();
  header["steps"] = {o.first_step, last};
  header["size"] = {o.camera.width, o.camera.height};
  header["view"] = {o.camera.azimuth_deg, o.camera.elevation_deg};
  header["passes"] = o.passes;
  header["sweep"] = o.sweep;
  header["targets"] = o.targets;
  header["search_steps"] = sample;
  header["search_iterations"] = o.search_iterations;
  header["tolerance_rule"] =
      "per tsp_grid.tolerance_rules: equal (spatial = temporal = tolerance), temporal (spatial 0), "
      "spatial (temporal 0)";
  header["table3_knobs"] = {{"compositing", to_string(o.table3.compositing)},
                            {"spacing", o.table3.spacing}};
  header["reference"] = {{"renderer", "baseline"},
                         {"compositing", "slices"},
                         {"spacing", o.reference_spacing}};
  auto grid_json = [](const KnobGrid& g) {
    json c = json::array();
    for (Compositing m : g.compositings) c.push_back(to_string(m));
    json pre = json::array();
    for (bool p : g.preintegration) pre.push_back(p);
    json rules = json::array();
    for (ToleranceRule r : g.tolerance_rules) rules.push_back(to_string(r));
    return json{{"compositings", c},
                {"spacings", g.spacings},
                {"preintegration", pre},
                {"sampling_tols", g.sampling_tols},
                {"render_scales", g.render_scales},
                {"tolerance_rules", rules}};
  };
  header["baseline_grid"] = grid_json(o.baseline_grid);
  header["tsp_grid"] = grid_json(o.tsp_grid);
  header["timed_candidates"] = o.timed_candidates;
  header["head_to_head_rounds"] = o.head_to_head_rounds;
  BenchReport report(std::move(header));

  // The probes' pictures: on a canvas of one offscreen context (the head-to-head timings run
  // render jobs, each on a context of its own).
  std::string gl_note;
  auto ctx = create_headless_context(o.camera.width, o.camera.height, o.gl, o.gpu, &gl_note);
  if (!gl_note.empty()) std::fprintf(stderr, "tspplay: warning: %s\n", gl_note.c_str());
  for (std::size_t k = 0; k < tfs.size(); ++k)
    TfBench(*ctx, o, *file, tfs[k], o.tfs[k], base, sample, report, tick).run(dir);
  if (progress) progress("done", total, total);
  return report.write(dir.string());
}

}  // namespace tspgl
