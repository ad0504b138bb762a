#include "jobs/knob_search.h"

#include <algorithm>
#include <cstdio>
#include <map>

#include "render/settings_table.h"
#include "tsp/core/error.h"

namespace tspgl {

namespace {

void sort_fastest_first(std::vector<KnobCandidate>& v) {
  std::stable_sort(v.begin(), v.end(), [](const KnobCandidate& a, const KnobCandidate& b) {
    return a.probe.ms < b.probe.ms;
  });
}

}  // namespace

const char* to_string(ToleranceRule r) {
  switch (r) {
    case ToleranceRule::temporal: return "temporal";
    case ToleranceRule::spatial: return "spatial";
    case ToleranceRule::equal: break;
  }
  return "equal";
}

ToleranceRule parse_tolerance_rule(const std::string& text, const std::string& option) {
  for (ToleranceRule r : {ToleranceRule::equal, ToleranceRule::temporal, ToleranceRule::spatial})
    if (text == to_string(r)) return r;
  throw tsp::UsageError(option + " " + text + ": expected equal, temporal or spatial");
}

namespace {
tsp::Tolerances tolerances(const Knobs& k) {
  return {k.rule == ToleranceRule::temporal ? 0 : k.tol,
          k.rule == ToleranceRule::spatial ? 0 : k.tol};
}
}  // namespace

void apply(const Knobs& k, RenderSettings& settings) {
  settings.compositing = k.compositing;
  settings.spacing = k.spacing;
  settings.tol = tolerances(k);
  settings.preintegrated = k.preintegrated;
  settings.sampling_tol = k.baseline ? 0 : k.sampling_tol;
  settings.render_scale = k.render_scale;
}

std::vector<Knobs> grid_cells(const KnobGrid& grid, bool baseline) {
  std::vector<Knobs> out;
  const std::vector<int> levels = baseline ? std::vector<int>{0} : grid.lod_levels;
  const std::vector<double> sampling = baseline ? std::vector<double>{0} : grid.sampling_tols;
  const std::vector<ToleranceRule> rules =
      baseline ? std::vector<ToleranceRule>{ToleranceRule::equal} : grid.tolerance_rules;
  for (ToleranceRule rule : rules)
    for (int level : levels)
      for (double st : sampling)
        for (bool pre : grid.preintegration)
          for (Compositing c : grid.compositings) {
            RenderSettings asked;
            asked.sampling_tol = st;
            asked.preintegrated = pre;
            // Adaptive sampling is a mode of the rays, and excludes pre-integration.
            if (!sampling_conflict(asked).empty() || (st > 0 && c != Compositing::rays)) continue;
            for (double s : grid.spacings)
              for (double scale : grid.render_scales) {
                Knobs& k = out.emplace_back();
                k.baseline = baseline;
                k.compositing = c;
                k.spacing = s;
                k.preintegrated = pre;
                k.lod_level = level;
                k.sampling_tol = st;
                k.rule = rule;
                k.render_scale = scale;
              }
          }
  return out;
}

std::string render_options(const Knobs& k, tsp::Metric metric) {
  RenderSettings s;
  apply(k, s);
  // "--NAME VALUE" as the settings table writes it (numbers with 17 digits: they parse back).
  auto opt = [&s](std::string_view name) {
    return "--" + std::string(name) + " " + get_setting(s, *find_setting(name));
  };
  std::string out = k.baseline ? "--baseline " : "";
  out += opt("compositing") + " " + opt("spacing");
  if (k.preintegrated) out += " " + opt("preintegrated");
  if (!k.baseline && k.sampling_tol > 0) out += " " + opt("sampling-tol");
  if (!k.baseline && k.lod_level > 0) out += " --lod " + std::to_string(k.lod_level);
  if (k.render_scale != 1) out += " " + opt("render-scale");
  if (!k.baseline)
    out += std::string(" --metric ") + tsp::to_string(metric) + " " + opt("spatial-tol") + " " +
           opt("temporal-tol");
  return out;
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
  // Zero tolerance draws the same picture under every rule: probed once per cell (its knobs
  // with the equal rule), shared.
  std::vector<KnobCandidate> zeros;
  for (Knobs k : grid_cells(grid, false)) {
    std::map<double, ProbeResult> seen;  // tolerance → probe, for the found tolerances' times
    auto error_at = [&](double tol) {
      if (auto it = seen.find(tol); it != seen.end()) return it->second.mean_de;
      k.tol = tol;
      ProbeResult r;
      if (tol == 0) {
        Knobs z = k;
        z.rule = ToleranceRule::equal;
        auto it = std::find_if(zeros.begin(), zeros.end(),
                               [&](const KnobCandidate& c) { return c.knobs == z; });
        r = it != zeros.end() ? it->probe : zeros.emplace_back(KnobCandidate{z, probe(k)}).probe;
      } else {
        r = probe(k);
      }
      seen[tol] = r;
      return r.mean_de;
    };
    // Zero tolerance too (search_tolerances starts there): on some data it is the fastest
    // picture (no flat nodes). Only the first rule's cells offer it as a candidate.
    const bool offers_zero = k.rule == grid.tolerance_rules.front();
    const std::vector<FoundTolerance> found = search_tolerances(error_at, span, targets, iterations);
    for (std::size_t i = 0; i < found.size(); ++i) {
      // The fastest tolerance probed that met the target: the largest one found, unless a
      // smaller one drew faster (a tolerance can cost time: flat nodes break a whole-volume
      // frame into the brick grid).
      const ProbeResult* best = nullptr;
      double best_tol = 0;
      for (const auto& [tol, r] : seen)
        if ((tol > 0 || offers_zero) && r.mean_de <= targets[i] && (!best || r.ms < best->ms)) {
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
