// tspplay bench run.tsp [--tf ...] -o report/: the paper's Tables 3, 4 and 5 with plots.
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <memory>
#include <optional>
#include <string>
#include <tuple>
#include <vector>

#include "cli/args.h"
#include "cli/commands.h"
#include "cli/session_options.h"
#include "cli/progress_bar.h"
#include "jobs/bench_job.h"
#include "tsp/core/error.h"
#include "tsp/core/stopwatch.h"
#include "tsp/core/temp_output.h"

namespace tspcli {
namespace {

struct BenchArgs : SessionArgs {  // the shared options' fields (session_options.h) and bench's
  BenchArgs() : SessionArgs(session_defaults(SessionCommand::bench)), tfs{tf} {}
  std::string file, out, steps;
  std::vector<std::string> tfs;  // --tf, several (one search each); the table's default first
  std::string targets = "1,3";
  int passes = 2, timed_candidates = 3, rounds = 3;
  // Unless given, from the sweep (kQuickSweep or kFullSweep).
  std::string sweep = "quick", metrics, compositings, spacings, baseline_spacings, render_scales;
  std::optional<int> search_steps, search_iterations;
  std::string compositing = "rays", preintegration = "off", lod_levels = "0", sampling_tols = "0",
              tolerance_rules = "equal,temporal";
  double spacing = tspgl::kDefaultSliceSpacing, reference_spacing = 0.25;
};

// The searches' defaults: `--sweep quick` (the default) finishes in minutes on a 64³ series on
// two cores, `--sweep full` is the paper's grid (over 20 minutes there). Options given win.
struct Sweep {
  const char *metrics, *compositings, *spacings, *baseline_spacings, *render_scales;
  int search_steps, search_iterations;
};
// Render scales as VTK's image sample distances 1, 2 and 3.3 (the quick sweep) or 1 to 4 (full):
// at equal error the best configurations of both renderers cast fewer rays than pixels.
constexpr Sweep kQuickSweep{"approximate", "rays", "1,2,4", "0.5,1,2,4", "1,0.5,0.3", 4, 8};
constexpr Sweep kFullSweep{"scalar,approximate,perceptual,reference", "slices,boxes,rays",
                           "0.5,1,1.5,2,3,4,6,8", "0.25,0.5,0.75,1,1.5,2,3,4,6,8",
                           "1,0.75,0.5,0.35,0.3,0.25", 8, 10};

// a's sweep-dependent options, filled from its sweep where not given. Throws UsageError.
BenchArgs with_sweep(BenchArgs a) {
  if (a.sweep != "quick" && a.sweep != "full")
    throw tsp::UsageError("--sweep " + a.sweep + ": expected quick or full");
  const Sweep& s = a.sweep == "full" ? kFullSweep : kQuickSweep;
  if (a.metrics.empty()) a.metrics = s.metrics;
  if (a.compositings.empty()) a.compositings = s.compositings;
  if (a.spacings.empty()) a.spacings = s.spacings;
  if (a.baseline_spacings.empty()) a.baseline_spacings = s.baseline_spacings;
  if (a.render_scales.empty()) a.render_scales = s.render_scales;
  if (!a.search_steps) a.search_steps = s.search_steps;
  if (!a.search_iterations) a.search_iterations = s.search_iterations;
  return a;
}

std::vector<std::string> split(const std::string& text) {
  std::vector<std::string> out;
  std::size_t p = 0;
  while (p <= text.size()) {
    std::size_t c = text.find(',', p);
    if (c == std::string::npos) c = text.size();
    out.push_back(text.substr(p, c - p));
    p = c + 1;
  }
  return out;
}

std::vector<double> parse_spacings(const std::string& text, const std::string& option) {
  std::vector<double> out;
  for (const std::string& t : split(text)) out.push_back(parse_number(t, option));
  return out;
}

double parse_target(const std::string& text) {
  const double v = parse_number(text, "--targets");
  if (!(v > 0) || !std::isfinite(v))
    throw tsp::UsageError("--targets '" + text + "': expected a positive mean dE (e.g. 1,3)");
  return v;
}

void run(const BenchArgs& given) {
  const BenchArgs a = with_sweep(given);
  std::vector<std::string> inputs = a.tfs;  // the report never replaces the file or a TF
  inputs.push_back(a.file);
  const tsp::InputGuard guard(inputs);
  tspgl::BenchOptions o;
  o.tsp_path = a.file;
  o.field = a.field;
  o.out_dir = a.out;
  if (!a.tfs.empty()) o.tfs = a.tfs;
  if (!a.steps.empty()) {
    const StepRange steps = parse_steps(a.steps);
    if (steps.stride != 1)
      throw tsp::UsageError("--steps '" + a.steps +
                            "': bench measures every step of a range; a stride is for render");
    o.first_step = steps.first;
    o.last_step = steps.last;
  }

  std::tie(o.camera.width, o.camera.height) = parse_size(a.size);
  auto view = tsp::parse_view_angles(a.view);
  o.camera.azimuth_deg = view[0];
  o.camera.elevation_deg = view[1];
  o.metrics.clear();
  for (const std::string& m : split(a.metrics)) o.metrics.push_back(tsp::parse_metric(m));
  o.targets.clear();
  for (const std::string& t : split(a.targets)) o.targets.push_back(parse_target(t));
  o.search_steps = *a.search_steps;
  o.search_iterations = *a.search_iterations;
  o.passes = a.passes;
  o.sweep = a.sweep;
  o.gl = tspgl::parse_headless_gl(a.gl, "--gl");
  o.gpu = a.gpu;
  o.timed_candidates = a.timed_candidates;
  o.head_to_head_rounds = a.rounds;
  if (o.timed_candidates < 1)
    throw tsp::UsageError("--timed-candidates " + std::to_string(a.timed_candidates) +
                          ": expected at least 1");
  o.table3.compositing = tspgl::parse_compositing(a.compositing, "--compositing");
  o.table3.spacing = a.spacing;
  o.reference_spacing = a.reference_spacing;
  std::vector<tspgl::Compositing> comps;
  for (const std::string& c : split(a.compositings))
    comps.push_back(tspgl::parse_compositing(c, "--compositings"));
  o.tsp_grid.compositings = o.baseline_grid.compositings = comps;
  o.tsp_grid.spacings = parse_spacings(a.spacings, "--spacings");
  o.tsp_grid.lod_levels.clear();
  for (const std::string& l : split(a.lod_levels))
    o.tsp_grid.lod_levels.push_back(int(parse_integer(l, "--lod-levels", 0, 16, "levels 0..16")));
  o.baseline_grid.spacings = parse_spacings(a.baseline_spacings, "--baseline-spacings");
  o.tsp_grid.render_scales = o.baseline_grid.render_scales =
      parse_spacings(a.render_scales, "--render-scales");
  for (double v : o.tsp_grid.render_scales)
    if (!(v >= tspgl::kMinRenderScale && v <= 1))
      throw tsp::UsageError("--render-scales " + a.render_scales + ": expected scales in [" +
                            std::to_string(tspgl::kMinRenderScale).substr(0, 4) + ", 1], e.g. 1,0.5");
  o.tsp_grid.sampling_tols.clear();
  for (const std::string& t : split(a.sampling_tols)) {
    char* end = nullptr;
    const double v = std::strtod(t.c_str(), &end);
    if (t.empty() || *end != '\0' || !(v >= 0) || !std::isfinite(v))
      throw tsp::UsageError("--sampling-tols " + t + ": expected finite tolerances >= 0, e.g. 0,0.05");
    o.tsp_grid.sampling_tols.push_back(v);
  }
  o.tsp_grid.tolerance_rules.clear();
  for (const std::string& r : split(a.tolerance_rules)) {
    const tspgl::ToleranceRule rule = tspgl::parse_tolerance_rule(r, "--tolerance-rules");
    if (std::find(o.tsp_grid.tolerance_rules.begin(), o.tsp_grid.tolerance_rules.end(), rule) ==
        o.tsp_grid.tolerance_rules.end())
      o.tsp_grid.tolerance_rules.push_back(rule);
  }
  std::vector<bool> pre;
  for (const std::string& p : split(a.preintegration)) {
    if (p != "on" && p != "off")
      throw tsp::UsageError("--preintegration " + p + ": expected off, on or off,on");
    pre.push_back(p == "on");
  }
  o.tsp_grid.preintegration = o.baseline_grid.preintegration = pre;

  // One line per run on stdout (a log that survives redirection), a counter on a terminal.
  const bool tty = isatty(STDERR_FILENO) == 1;
  // The time left is estimated from the runs done so far (runs differ in cost: a rough guide).
  const tsp::Stopwatch watch;
  auto report = tspgl::run_bench(o, [tty, &watch](const std::string& phase, int done, int total) {
    if (tty) std::fprintf(stderr, "\r\x1b[K");
    const double s = watch.seconds();
    const std::string left =
        done > 0 ? ", about " + clock_text(s / done * (total - done)) + " left" : "";
    std::printf("[%3d/%d] %s  (%s elapsed%s)\n", done, total, phase.c_str(),
                clock_text(s).c_str(), left.c_str());
    std::fflush(stdout);
  });
  std::printf("\nTable 3 (zero tolerance, median ms of pass %d):\n", o.passes);
  for (const auto& r : report["table3"]) {
    std::string label = r["renderer"].get<std::string>();
    if (label == "tsp")
      label += " " + r["metric"].get<std::string>() + ", cache " + r["cache"].get<std::string>();
    std::printf("  %-16s %-34s %9.2f ms  NR %5.1f%% UP %5.1f%% RT %5.1f%% NT %5.1f%%\n",
                r["tf"].get<std::string>().c_str(), label.c_str(), r["median_ms"].get<double>(),
                r["not_rendered"].get<double>(), r["untextured"].get<double>(),
                r["reused_texture"].get<double>(), r["new_texture"].get<double>());
  }
  std::printf("Table 4 (fastest configuration within each target mean dE against the reference):\n");
  for (const auto& r : report["table4"]) {
    std::string label = r["renderer"].get<std::string>();
    if (label == "tsp") label += " " + r["metric"].get<std::string>();
    if (!r["target_met"].get<bool>()) {
      std::printf("  %-16s %-16s target %4.2f: nothing met it\n", r["tf"].get<std::string>().c_str(),
                  label.c_str(), r["target_delta_e"].get<double>());
      continue;
    }
    std::printf("  %-16s %-16s target %4.2f: dE %6.3f %9.2f ms  x%.2f vs best non-TSP  [%s]\n",
                r["tf"].get<std::string>().c_str(), label.c_str(),
                r["target_delta_e"].get<double>(), r["mean_delta_e"].get<double>(),
                r["median_ms"].get<double>(), r["speedup_vs_best_baseline"].get<double>(),
                r["render_options"].get<std::string>().c_str());
  }
  std::printf("wrote %s/{table3.csv,table4.csv,table5.csv,report.json} and %zu plots\n",
              o.out_dir.c_str(), report["plots"].size());
}

const CommandRegistrar reg(45, [](CLI::App& app) {
  auto* c = app.add_subcommand("bench", "Reproduce the paper's Tables 3, 4 and 5 with plots");
  auto a = std::make_shared<BenchArgs>();
  c->add_option("file", a->file, "The .tsp file")->required();
  // The session options, with bench's defaults: one table (session_options.h); --tf takes
  // several here, one search each.
  add_session_options(c, SessionCommand::bench, *a, {"--tf"});
  add_session_option(c, SessionCommand::bench, "--tf", a->tfs);
  c->add_option("-o,--output", a->out, "Report directory (CSV, JSON, SVG)")->required();
  c->add_option("--steps", a->steps, "Steps A:B (inclusive), A: or A (default: all)");
  c->add_option("--sweep", a->sweep,
                "How much the searches try unless their options are given: quick (default: "
                "--metrics approximate --compositings rays --spacings 1,2,4 --baseline-spacings "
                "0.5,1,2,4 --search-steps 4 --search-iterations 8; minutes) or full (all four "
                "metrics, three compositings, eight and ten spacings, 8 steps, 10 iterations)");
  c->add_option("--metrics", a->metrics, "Comma-separated metrics (default: the sweep's)");
  c->add_option("--targets", a->targets, "Target mean dE values for Table 4 (default 1,3)");
  c->add_option("--search-steps", a->search_steps,
                "Steps rendered per search probe (default: the sweep's, 4 or 8)");
  c->add_option("--search-iterations", a->search_iterations,
                "Bisection steps (default: the sweep's, 8 or 10)");
  c->add_option("--passes", a->passes, "Timed passes over the steps; the last counts (default 2)");
  c->add_option("--compositing", a->compositing, "Table 3's compositing: slices|boxes|rays (default rays)");
  c->add_option("--spacing", a->spacing, "Table 3's slice spacing in voxels (default 0.5)");
  c->add_option("--reference-spacing", a->reference_spacing,
                "Spacing of the full-quality reference picture (baseline, slices; default 0.25)");
  c->add_option("--compositings", a->compositings,
                "Compositings the Table-4 search tries (default: the sweep's)");
  c->add_option("--spacings", a->spacings, "TSP spacings the Table-4 search tries (default: the sweep's)");
  c->add_option("--lod-levels", a->lod_levels,
                "LOD levels the TSP search draws everywhere, e.g. 0,1,2 (default 0: full "
                "resolution; each adds a search of every compositing and spacing)");
  c->add_option("--sampling-tols", a->sampling_tols,
                "Adaptive sampling tolerances the TSP search tries with rays (render "
                "--sampling-tol), e.g. 0,0.05,0.1 (default 0: off)");
  c->add_option("--tolerance-rules", a->tolerance_rules,
                "Which tolerances the TSP search's tolerance sets: equal (spatial = temporal), "
                "temporal (spatial 0), spatial (temporal 0); e.g. equal,temporal,spatial "
                "(default equal,temporal)");
  c->add_option("--preintegration", a->preintegration,
                "TF lookups the Table-4 search tries, for both renderers: off, on or off,on "
                "(default off)");
  c->add_option("--rounds", a->rounds,
                "Head-to-head rounds timing the reference and each winner in turn (default 3)");
  c->add_option("--render-scales", a->render_scales,
                 "Render scales both Table-4 searches try with every spacing, e.g. 1,0.5 (rays every "
                 "1/S pixels, VTK's image sample distance; default: the sweep's, 1,0.5,0.3 or "
                 "1,0.75,0.5,0.35,0.3,0.25)");
  c->add_option("--baseline-spacings", a->baseline_spacings,
                "Baseline spacings the Table-4 search tries (default: the sweep's)");
  c->add_option("--timed-candidates", a->timed_candidates,
                "Fastest probed configurations timed per target and renderer (default 3)");
  c->callback([a] { run(*a); });
});

}  // namespace
}  // namespace tspcli
