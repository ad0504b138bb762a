#include "jobs/bench_report.h"

#include <cstdio>
#include <filesystem>

#include "render/frame_report.h"
#include "tsp/core/json_text.h"
#include "tsp/core/temp_output.h"

namespace tspgl {

namespace {

using nlohmann::json;

// A CSV field: quoted when it holds a comma, a quote or a newline.
std::string csv(const std::string& s) {
  if (s.find_first_of(",\"\n") == std::string::npos) return s;
  std::string q = "\"";
  for (char c : s) q += c == '"' ? std::string("\"\"") : std::string(1, c);
  return q + "\"";
}

}  // namespace

std::string fmt(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.6g", v);
  return buf;
}

BenchReport::BenchReport(json header) : report_(std::move(header)) {
  for (const char* k : {"table3", "table4", "table5", "searches", "plots"})
    report_[k] = json::array();
  t3_ << "tf,renderer,metric,cache,median_ms,first_pass_median_ms,speedup,metric_ms,"
         "mean_delta_e\n";
  t4_ << "tf,renderer,metric,target_delta_e,render_options,compositing,spacing,tolerance,"
         "mean_delta_e,target_met,median_ms,speedup_vs_best_baseline,speedup_vs_reference\n";
  t5_ << "tf,metric,cache,tolerance,target_delta_e,not_rendered,untextured,reused_texture,"
         "new_texture\n";
}

void BenchReport::add_search(const std::string& tf, const std::string& metric,
                             const ErrorSpan& span, const json& evaluations) {
  report_["searches"].push_back({{"tf", tf},
                                 {"metric", metric},
                                 {"largest_error", span.largest},
                                 {"smallest_positive_error", span.smallest_positive},
                                 {"evaluations", evaluations}});
}

void BenchReport::add_baseline(const std::string& tf, const Timing& b) {
  report_["renderer"] = b.renderer;
  t3_ << csv(tf) << ",baseline,,," << fmt(b.median_ms) << ',' << fmt(b.first_pass_median_ms)
      << ",1,,0\n";
  json rb = b;
  rb["tf"] = tf;
  rb["renderer"] = "baseline";
  report_["table3"].push_back(rb);
}

void BenchReport::add_zero_tolerance(const std::string& tf, const std::string& metric,
                                     const char* cache, const Timing& t, double baseline_ms,
                                     double mean_de) {
  t3_ << csv(tf) << ",tsp," << metric << ',' << cache << ',' << fmt(t.median_ms) << ','
      << fmt(t.first_pass_median_ms) << ',' << fmt(baseline_ms / t.median_ms) << ','
      << fmt(t.metric_ms) << ',' << fmt(mean_de) << '\n';
  json r = t;
  r["tf"] = tf;
  r["renderer"] = "tsp";
  r["metric"] = metric;
  r["cache"] = cache;
  r["speedup"] = baseline_ms / t.median_ms;
  r["mean_delta_e"] = mean_de;
  report_["table3"].push_back(r);
  add_classes(tf, metric, cache, 0, 0, t);
}

void BenchReport::add_best(const std::string& tf, const std::string& renderer,
                           const std::string& metric, double target, const KnobCandidate* best,
                           const Timing* t, tsp::Metric options_metric, double best_baseline_ms,
                           double reference_ms) {
  json r{{"tf", tf}, {"renderer", renderer}, {"metric", metric}, {"target_delta_e", target},
         // Its ΔE is the fresh render's (bench_job.cpp), which may land a hair above the probe's.
         {"target_met", best != nullptr && best->probe.mean_de <= target}};
  t4_ << csv(tf) << ',' << renderer << ',' << metric << ',' << fmt(target) << ',';
  if (!best || !t) {
    t4_ << ",,,,,0,,,\n";
    report_["table4"].push_back(r);
    return;
  }
  const Knobs& k = best->knobs;
  const std::string options = render_options(k, options_metric);
  t4_ << csv(options) << ',' << to_string(k.compositing) << ',' << fmt(k.spacing) << ','
      << fmt(k.tol) << ',' << fmt(best->probe.mean_de) << ',' << (r["target_met"].get<bool>() ? 1 : 0) << ',' << fmt(t->median_ms) << ','
      << fmt(best_baseline_ms / t->median_ms) << ',' << fmt(reference_ms / t->median_ms) << '\n';
  r["render_options"] = options;
  r["compositing"] = to_string(k.compositing);
  r["spacing"] = k.spacing;
  r["tolerance"] = k.tol;
  r["tolerance_rule"] = to_string(k.rule);
  r["mean_delta_e"] = best->probe.mean_de;
  r["probe_ms"] = best->probe.ms;
  r["timing"] = *t;
  r["median_ms"] = t->median_ms;
  r["speedup_vs_best_baseline"] = best_baseline_ms / t->median_ms;
  r["speedup_vs_reference"] = reference_ms / t->median_ms;
  report_["table4"].push_back(r);
  if (renderer == "tsp") add_classes(tf, metric, "on", k.tol, target, *t);
}

void BenchReport::add_classes(const std::string& tf, const std::string& metric, const char* cache,
                              double tol, double target, const Timing& t) {
  t5_ << csv(tf) << ',' << metric << ',' << cache << ',' << fmt(tol) << ','
      << (target > 0 ? fmt(target) : "") << ',' << fmt(t.classes[0]) << ',' << fmt(t.classes[1])
      << ',' << fmt(t.classes[2]) << ',' << fmt(t.classes[3]) << '\n';
  json row = {{"tf", tf},
              {"metric", metric},
              {"cache", cache},
              {"tolerance", tol},
              {"target_delta_e", target > 0 ? json(target) : json()}};
  tspgl::add_class_shares(row, t.classes);
  report_["table5"].push_back(row);
}

void BenchReport::add_plot(const std::string& file) { report_["plots"].push_back(file); }

json BenchReport::write(const std::string& dir) {
  const std::filesystem::path d = dir;
  tsp::write_file_atomically((d / "table3.csv").string(), t3_.str());
  tsp::write_file_atomically((d / "table4.csv").string(), t4_.str());
  tsp::write_file_atomically((d / "table5.csv").string(), t5_.str());
  tsp::write_file_atomically((d / "report.json").string(), tsp::json_text(report_, 2) + "\n");
  return report_;
}

}  // namespace tspgl
