#include "jobs/knob_search.h"

#include <algorithm>
#include <cstdio>
#include <map>

namespace tspgl {

namespace {

std::string exact(double v) {
  char buf[40];
  std::snprintf(buf, sizeof buf, "%.17g", v);
  return buf;
}

void sort_fastest_first(std::vector<KnobCandidate>& v) {
  std::stable_sort(v.begin(), v.end(), [](const KnobCandidate& a, const KnobCandidate& b) {
    return a.probe.ms < b.probe.ms;
  });
}

}  // namespace

void apply(const Knobs& k, RenderSettings& settings) {
  settings.compositing = k.compositing;
  settings.spacing = k.spacing;
  settings.tol = {k.tol, k.tol};
  settings.preintegrated = k.preintegrated;
  settings.sampling_tol = k.baseline ? 0 : k.sampling_tol;
}

std::vector<Knobs> grid_cells(const KnobGrid& grid, bool baseline) {
  std::vector<Knobs> out;
  const std::vector<int> levels = baseline ? std::vector<int>{0} : grid.lod_levels;
  const std::vector<double> sampling = baseline ? std::vector<double>{0} : grid.sampling_tols;
  for (int level : levels)
    for (double st : sampling)
      for (bool pre : grid.preintegration)
        for (Compositing c : grid.compositings) {
          if (st > 0 && (pre || c != Compositing::rays)) continue;  // adaptive: rays, point lookup
          for (double s : grid.spacings) {
            Knobs& k = out.emplace_back();
            k.baseline = baseline;
            k.compositing = c;
            k.spacing = s;
            k.preintegrated = pre;
            k.lod_level = level;
            k.sampling_tol = st;
          }
        }
  return out;
}

std::string render_options(const Knobs& k, tsp::Metric metric) {
  std::string s = k.baseline ? "--baseline " : "";
  s += "--compositing " + std::string(to_string(k.compositing)) + " --spacing " + exact(k.spacing);
  if (k.preintegrated) s += " --preintegrated on";
  if (!k.baseline && k.sampling_tol > 0) s += " --sampling-tol " + exact(k.sampling_tol);
  if (!k.baseline && k.lod_level > 0) s += " --lod " + std::to_string(k.lod_level);
  if (!k.baseline)
    s += std::string(" --metric ") + tsp::to_string(metric) + " --spatial-tol " + exact(k.tol) +
         " --temporal-tol " + exact(k.tol);
  return s;
}

std::vector<std::vector<KnobCandidate>> search_baseline_knobs(const ProbeKnobs& probe,
                                                              const KnobGrid& grid,
                                                              const std::vector<double>& targets) {
  std::vector<KnobCandidate> all;
  for (const Knobs& k : grid_cells(grid, true)) all.push_back({k, probe(k)});
  std::vector<std::vector<KnobCandidate>> out;
  for (double target : targets) {
    std::vector<KnobCandidate>& v = out.emplace_back();
    for (const KnobCandidate& c : all)
      if (c.probe.mean_de <= target) v.push_back(c);
    sort_fastest_first(v);
  }
  return out;
}

std::vector<std::vector<KnobCandidate>> search_tsp_knobs(const ProbeKnobs& probe,
                                                         const KnobGrid& grid,
                                                         const ErrorSpan& span,
                                                         const std::vector<double>& targets,
                                                         int iterations) {
  std::vector<std::vector<KnobCandidate>> out(targets.size());
  for (Knobs k : grid_cells(grid, false)) {
    std::map<double, ProbeResult> seen;  // tolerance → probe, for the found tolerances' times
    auto error_at = [&](double tol) {
      k.tol = tol;
      const ProbeResult r = probe(k);
      seen[tol] = r;
      return r.mean_de;
    };
    error_at(0);  // zero tolerance too: on some data it is the fastest picture (no flat nodes)
    const std::vector<FoundTolerance> found = search_tolerances(error_at, span, targets, iterations);
    for (std::size_t i = 0; i < found.size(); ++i) {
      // The fastest tolerance probed that met the target: the largest one found, unless a
      // smaller one drew faster (a tolerance can cost time: flat nodes break a whole-volume
      // frame into the brick grid).
      const ProbeResult* best = nullptr;
      double best_tol = 0;
      for (const auto& [tol, r] : seen)
        if (r.mean_de <= targets[i] && (!best || r.ms < best->ms)) {
          best = &r;
          best_tol = tol;
        }
      if (!best) continue;
      k.tol = best_tol;
      out[i].push_back({k, *best});
    }
  }
  for (auto& v : out) sort_fastest_first(v);
  return out;
}

}  // namespace tspgl
