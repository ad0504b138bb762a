// The LOD cut's targets (issue "LOD cut", docs/results.md): an orbiting camera over a series at
// 640×480, the adaptive cut at each frame-time target against the full-resolution renderer and
// every fixed level, all in one run, in --rounds rounds (each configuration once per round). Per run: median frame time (after the first `--warmup`
// frames), the share of frames under 1.5× the target, and the mean ΔE (CIE L*u*v*) of each frame
// against the full-resolution frame of the same view and step. For each target the best fixed
// level of the same speed (median within 10 % of the adaptive run's, or faster) is named with its
// ΔE. Writes a plot of ΔE against the target.
//
//   lod_bench FILE.tsp [--tf preset:filled] [--targets 20,40,80] [--orbit 3] [--passes 10]
//             [--texture-budget MiB] [--size WxH] [--warmup 10] [--rounds 2] [--plot lod.svg]
#include <algorithm>
#include <cstdio>
#include <iterator>
#include <string>
#include <vector>

#include "jobs/render_job.h"
#include "tsp/report/image_diff.h"
#include "tsp/report/svg_plot.h"
#include "tsp/store/tsp_file.h"

namespace {

struct Run {
  std::string label;
  double target = 0;
  std::vector<double> ms;
  std::vector<tsp::Image> images;
  std::vector<double> de;  // per frame against the reference
  double median() const { return tspgl::median(ms); }
  double p90() const {
    std::vector<double> v = ms;
    std::sort(v.begin(), v.end());
    return v.empty() ? 0 : v[v.size() * 9 / 10];
  }
  double mean_de() const {
    double s = 0;
    for (double d : de) s += d;
    return de.empty() ? 0 : s / double(de.size());
  }
};

Run play(const std::string& label, tspgl::RenderJobOptions o, int warmup) {
  Run r;
  r.label = label;
  r.target = o.target_ms;
  int frame = 0;
  o.on_frame = [&](const tspgl::FrameRecord& f, const tsp::Image& img) {
    if (frame++ < warmup) return;
    r.ms.push_back(f.report.ms);
    r.images.push_back(img);
  };
  tspgl::run_render_job(o);
  return r;
}

std::vector<double> parse_list(const std::string& v) {
  std::vector<double> out;
  for (std::size_t p = 0; p <= v.size();) {
    const std::size_t c = v.find(',', p);
    out.push_back(std::stod(v.substr(p, c == std::string::npos ? std::string::npos : c - p)));
    p = c == std::string::npos ? v.size() + 1 : c + 1;
  }
  return out;
}

}  // namespace

int main(int argc, char** argv) {
  tspgl::RenderJobOptions base;
  base.tf = "preset:filled";
  base.orbit_deg = 3;
  base.passes = 10;
  base.texture_budget = std::int64_t(24) << 20;
  std::vector<double> targets = {20, 40, 80};
  int warmup = 10;
  int rounds = 2;
  std::string plot = "lod.svg";
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    auto next = [&]() -> std::string { return i + 1 < argc ? argv[++i] : ""; };
    if (a == "--tf") base.tf = next();
    else if (a == "--targets") targets = parse_list(next());
    else if (a == "--orbit") base.orbit_deg = std::stod(next());
    else if (a == "--passes") base.passes = std::stoi(next());
    else if (a == "--texture-budget") base.texture_budget = std::int64_t(std::stod(next()) * (1 << 20));
    else if (a == "--size") std::sscanf(next().c_str(), "%dx%d", &base.camera.width, &base.camera.height);
    else if (a == "--warmup") warmup = std::stoi(next());
    else if (a == "--plot") plot = next();
    else if (a == "--rounds") rounds = std::max(1, std::stoi(next()));
    else base.tsp_path = a;
  }
  if (base.tsp_path.empty()) {
    std::fprintf(stderr, "usage: lod_bench FILE.tsp [--tf ...] [--targets 20,40,80] ...\n");
    return 2;
  }
  auto file = tsp::TspFile::open(base.tsp_path);
  const tsp::Octree& o = file->tree().octree();
  std::printf("%s: %s x %d steps, bricks of %d (%d levels); %dx%d, %s, orbit %g deg/frame, %d "
              "passes, texture budget %.0f MiB (one full step: %.0f MiB)\n",
              base.tsp_path.c_str(), tsp::to_string(o.dims()).c_str(), file->tree().time().steps(),
              o.brick_size(), o.max_lod_level() + 1, base.camera.width, base.camera.height,
              base.tf.c_str(), base.orbit_deg, base.passes, double(base.texture_budget) / (1 << 20),
              double(o.dims().count()) * 2 / (1 << 20));
  // Every configuration once per round, the rounds one after the other, so that a machine whose
  // speed drifts (this one does, by up to 2×) moves them alike; frame times and ΔE pool over
  // the rounds. The reference's pictures are the first round's (it is deterministic).
  std::vector<tspgl::RenderJobOptions> configs;
  std::vector<std::string> labels;
  tspgl::RenderJobOptions full = base;
  full.lod = tspgl::LodMode::off;
  configs.push_back(full);
  labels.push_back("full resolution");
  for (int k = 1; k <= o.max_lod_level(); ++k) {
    tspgl::RenderJobOptions f = base;
    f.lod = tspgl::LodMode::fixed;
    f.lod_level = k;
    configs.push_back(f);
    labels.push_back("level " + std::to_string(k));
  }
  for (double t : targets) {
    tspgl::RenderJobOptions a = base;
    a.lod = tspgl::LodMode::adaptive;
    a.target_ms = t;
    char label[64];
    std::snprintf(label, sizeof label, "auto, target %g ms", t);
    configs.push_back(a);
    labels.push_back(label);
  }
  std::vector<Run> all(configs.size());
  for (int round = 0; round < rounds; ++round)
    for (std::size_t c = 0; c < configs.size(); ++c) {
      Run r = play(labels[c], configs[c], warmup);
      all[c].label = r.label;
      all[c].target = r.target;
      all[c].ms.insert(all[c].ms.end(), r.ms.begin(), r.ms.end());
      if (c == 0 && round > 0) continue;  // the reference's pictures: the first round's
      for (tsp::Image& img : r.images) all[c].images.push_back(std::move(img));
    }
  const Run reference = std::move(all[0]);
  std::vector<Run> runs(std::make_move_iterator(all.begin() + 1), std::make_move_iterator(all.end()));
  const std::size_t fixed_count = std::size_t(o.max_lod_level());
  const std::size_t per_round = reference.images.size();
  for (Run& r : runs) {
    for (std::size_t i = 0; i < r.images.size(); ++i)
      r.de.push_back(tsp::diff_images(r.images[i], reference.images[i % per_round]).mean);
    r.images.clear();
  }

  std::printf("\n%-22s %10s %8s %8s %12s %9s\n", "run", "median ms", "p90 ms", "speed-up",
              "< 1.5 target", "mean dE");
  std::printf("%-22s %10.1f %8.1f %7.2fx %12s %9.3f\n", reference.label.c_str(), reference.median(),
              reference.p90(), 1.0, "", 0.0);
  for (const Run& r : runs) {
    char within[32] = "";
    if (r.target > 0) {
      int n = 0;
      for (double m : r.ms) n += m < 1.5 * r.target;
      std::snprintf(within, sizeof within, "%.0f%%", 100.0 * n / double(std::max<std::size_t>(1, r.ms.size())));
    }
    std::printf("%-22s %10.1f %8.1f %7.2fx %12s %9.3f\n", r.label.c_str(), r.median(), r.p90(),
                reference.median() / r.median(), within, r.mean_de());
  }
  std::printf("\n%-22s %14s %12s %-10s %12s %9s\n", "target", "median/target", "dE (auto)",
              "fixed", "median ms", "dE");
  tsp::PlotSeries auto_series{"adaptive cut", {}, {}, true, true};
  for (std::size_t i = fixed_count; i < runs.size(); ++i) {
    const Run& r = runs[i];
    const Run* best = nullptr;
    for (std::size_t k = 0; k < fixed_count; ++k)
      if (runs[k].median() <= 1.1 * r.median() && (!best || runs[k].mean_de() < best->mean_de()))
        best = &runs[k];
    std::printf("%-22g %13.0f%% %12.3f %-10s %12.1f %9.3f\n", r.target, 100 * r.median() / r.target,
                r.mean_de(), best ? best->label.c_str() : "none", best ? best->median() : 0.0,
                best ? best->mean_de() : 0.0);
    auto_series.x.push_back(r.target);
    auto_series.y.push_back(r.mean_de());
  }
  tsp::PlotSeries fixed_series{"fixed levels (at their median ms)", {}, {}, false, true};
  for (std::size_t k = 0; k < fixed_count; ++k) {
    fixed_series.x.push_back(runs[k].median());
    fixed_series.y.push_back(runs[k].mean_de());
  }
  tsp::PlotSpec spec;
  spec.title = "LOD: mean dE against full resolution";
  spec.x_label = "frame time target (ms)";
  spec.y_label = "mean dE";
  spec.series = {auto_series, fixed_series};
  tsp::write_svg_plot(spec, plot);
  std::printf("\nwrote %s\n", plot.c_str());
  return 0;
}
