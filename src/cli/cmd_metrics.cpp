// tspplay metrics FILE.tsp --tf TF --metric M [--json] [--nodes]: recompute one
// error metric for a transfer function, time it, and summarise the errors over
// the TSP nodes.
#include <algorithm>
#include <cstdio>
#include <iostream>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "cli/commands.h"
#include "tsp/core/json_text.h"
#include "tsp/core/parallel_for.h"
#include "tsp/core/stopwatch.h"
#include "tsp/metric/compute_errors.h"
#include "tsp/metric/tf_io.h"
#include "tsp/store/tsp_file.h"

namespace tspcli {
namespace {

using nlohmann::json;

struct MetricsArgs {
  std::string file, field;
  std::string tf;
  std::string metric = "approximate";
  int entries = tsp::kDefaultTfEntries;
  int threads = 0;
  bool json = false;
  bool nodes = false;
};

// Summary of one error over the visible (non-transparent) nodes.
struct Distribution {
  std::size_t count = 0;
  double min = 0, mean = 0, p50 = 0, p90 = 0, p99 = 0, max = 0;
};

Distribution distribution(const std::vector<float> &values,
                          const std::vector<std::uint8_t> &clear) {
  std::vector<float> v;
  for (std::size_t i = 0; i < values.size(); ++i)
    if (!clear[i])
      v.push_back(values[i]);
  Distribution d;
  d.count = v.size();
  if (v.empty())
    return d;
  std::sort(v.begin(), v.end());
  auto pct = [&](double p) {
    return double(v[std::size_t(p * double(v.size() - 1) + 0.5)]);
  };
  double sum = 0;
  for (float x : v)
    sum += x;
  d.min = v.front();
  d.max = v.back();
  d.mean = sum / double(v.size());
  d.p50 = pct(0.50);
  d.p90 = pct(0.90);
  d.p99 = pct(0.99);
  return d;
}

json distribution_json(const Distribution &d) {
  return {{"nodes", d.count}, {"min", d.min}, {"mean", d.mean}, {"p50", d.p50},
          {"p90", d.p90},     {"p99", d.p99}, {"max", d.max}};
}

void run(const MetricsArgs &a) {
  const tsp::Metric metric = tsp::parse_metric(a.metric);
  auto file = tsp::TspFile::open(a.file, a.field);
  const tsp::TspTree &tree = file->tree();
  const tsp::ValueHistogram histogram = tsp::histogram_of(*file);
  const tsp::TransferFunction tf =
      tsp::transfer_function_from_arg(a.tf, tree.value_range(), a.entries, {}, &histogram);
  const int threads = tsp::resolve_threads(a.threads);
  const tsp::Stopwatch watch;
  const tsp::MetricResult r = tsp::compute_errors(metric, tree, tf, file.get(), threads);
  const double ms = watch.ms();
  const Distribution es = distribution(r.errors.spatial, r.transparent);
  const Distribution et = distribution(r.errors.temporal, r.transparent);

  if (a.json) {
    json j;
    j["file"] = a.file;
    j["metric"] = tsp::to_string(metric);
    j["recompute_ms"] = ms;
    j["threads"] = threads;
    j["tsp_nodes"] = tree.size();
    j["transparent_nodes"] = r.transparent_count();
    j["tf"] = {{"source", a.tf},
               {"range", {tf.domain().lo, tf.domain().hi}},
               {"entries", tf.size()}};
    j["spatial_error"] = distribution_json(es);
    j["temporal_error"] = distribution_json(et);
    if (a.nodes) {
      json nodes = json::array();
      for (int id = 0; id < tree.size(); ++id) {
        const tsp::Rgba &c = r.mean_colour[id];
        nodes.push_back({{"id", id},
                         {"spatial_error", r.errors.spatial[id]},
                         {"temporal_error", r.errors.temporal[id]},
                         {"transparent", bool(r.transparent[id])},
                         {"mean_colour", {c.r, c.g, c.b, c.a}}});
      }
      j["nodes"] = std::move(nodes);
    }
    std::cout << tsp::json_text(j, 1) << "\n";
    return;
  }
  const std::int64_t clear = r.transparent_count();
  std::printf("file          %s\n", a.file.c_str());
  std::printf("metric        %s\n", tsp::to_string(metric));
  std::printf("tf            %s (%d entries over [%g, %g])\n", a.tf.c_str(),
              tf.size(), tf.domain().lo, tf.domain().hi);
  std::printf("recompute     %.3f ms (%d threads)\n", ms, threads);
  std::printf("tsp nodes     %d, transparent %lld (%.1f%%)\n", tree.size(),
              (long long)clear,
              tree.size() ? 100.0 * double(clear) / tree.size() : 0.0);
  std::printf("errors over the %zu visible nodes:\n", es.count);
  std::printf("              %-10s %-10s %-10s %-10s %-10s %-10s\n", "min",
              "mean", "p50", "p90", "p99", "max");
  for (auto [name, d] : {std::pair{"spatial", es}, std::pair{"temporal", et}})
    std::printf("  %-11s %-10.4g %-10.4g %-10.4g %-10.4g %-10.4g %-10.4g\n",
                name, d.min, d.mean, d.p50, d.p90, d.p99, d.max);
  if (a.nodes) {
    std::printf("%-8s %-12s %-12s %-11s %s\n", "id", "e_s", "e_t",
                "transparent", "mean r g b a");
    for (int id = 0; id < tree.size(); ++id) {
      const tsp::Rgba &c = r.mean_colour[id];
      std::printf("%-8d %-12.6g %-12.6g %-11s %.4f %.4f %.4f %.4f\n", id,
                  r.errors.spatial[id], r.errors.temporal[id],
                  r.transparent[id] ? "yes" : "no", c.r, c.g, c.b, c.a);
    }
  }
}

const CommandRegistrar reg(40, [](CLI::App &app) {
  auto args = std::make_shared<MetricsArgs>();
  auto *c =
      app.add_subcommand("metrics", "Recompute an error metric for a transfer "
                                    "function and summarise the errors");
  c->add_option("file", args->file, "the .tsp file")->required();
  c->add_option("--field", args->field, "A file with several fields: this one (default: the first)");
  c->add_option("--tf", args->tf,
                "transfer function: a JSON file (ours or a ParaView preset) or "
                "preset:NAME "
                "(sparse, filled, grey) over the file's value range")
      ->required();
  c->add_option("--metric", args->metric,
                "scalar, reference, approximate or perceptual")
      ->capture_default_str();
  c->add_option("--entries", args->entries, "transfer-function entries K")
      ->capture_default_str()
      ->check(CLI::Range(2, 1 << 16));
  c->add_option("--threads", args->threads, "worker threads (0 = all cores)")
      ->capture_default_str()
      ->check(CLI::NonNegativeNumber);
  c->add_flag("--json", args->json, "print JSON");
  c->add_flag("--nodes", args->nodes,
              "list every TSP node (id as in `tspplay info --nodes`)");
  c->callback([args] { run(*args); });
});

} // namespace
} // namespace tspcli
