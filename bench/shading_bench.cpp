// The cost of lighting, pre-integration and refinement (issue 29): each configuration's median
// frame time over the steps (second pass, partial-image reuse off so every frame is drawn whole)
// as a ratio against shading, pre-integration and refinement off, measured in the same round;
// rounds alternate the configurations so a loaded machine's drift falls on all of them alike.
// TFs: the sparse and filled presets, or those --tfs names (presets or files).
//
//   shading_bench FILE.tsp [--size WxH] [--steps A:B] [--rounds N] [--spacing D]
//       [--compositing slices|boxes|rays] [--tfs TF,TF...] [--refine-tol T] [--configs I,J...]
//
// --configs: the configurations to time besides plain, by their index in kConfigs (default all).
//
// With no file it builds the built-in shock dataset (64³ × 32 steps, bricks of 16) in $TMPDIR.
#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <sstream>
#include <string>
#include <vector>

#include "jobs/render_job.h"
#include "tsp/build/build.h"
#include "tsp/frame/refine.h"
#include "tsp/source/procedural/generate.h"

namespace {

namespace fs = std::filesystem;

struct Config {
  const char* label;
  bool shade, preintegrated, refine;
};
constexpr Config kConfigs[] = {{"plain", false, false, false},
                               {"shade on", true, false, false},
                               {"preintegrated", false, true, false},
                               {"shade + preintegrated", true, true, false},
                               {"refine", false, false, true},
                               {"shade + refine", true, false, true}};
constexpr int kConfigCount = int(std::size(kConfigs));

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  return v.empty() ? 0 : v[v.size() / 2];
}

double frame_ms(tspgl::RenderJobOptions o, const Config& c, double refine_tol) {
  o.out_dir.clear();  // time only
  o.passes = 2;
  o.settings.shade = c.shade;
  o.settings.preintegrated = c.preintegrated;
  o.settings.refine_tol = c.refine ? refine_tol : 0;
  o.settings.reuse_image = false;
  return tspgl::median_frame_ms(tspgl::run_render_job(o), 2);
}

}  // namespace

int main(int argc, char** argv) {
  std::string file;
  tspgl::RenderJobOptions base;
  int rounds = 3;
  double refine_tol = tsp::kDefaultRefineTol;
  std::vector<std::string> tfs{"preset:sparse", "preset:filled"};
  std::vector<bool> timed(kConfigCount, true);
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    auto next = [&]() -> std::string { return i + 1 < argc ? argv[++i] : ""; };
    if (a == "--size") {
      std::sscanf(next().c_str(), "%dx%d", &base.camera.width, &base.camera.height);
    } else if (a == "--steps") {
      std::sscanf(next().c_str(), "%d:%d", &base.first_step, &base.last_step);
    } else if (a == "--rounds") {
      rounds = std::max(1, std::atoi(next().c_str()));
    } else if (a == "--spacing") {
      base.settings.spacing = std::atof(next().c_str());
    } else if (a == "--refine-tol") {
      refine_tol = std::atof(next().c_str());
    } else if (a == "--tfs") {
      tfs.clear();
      std::stringstream list(next());
      for (std::string t; std::getline(list, t, ',');) tfs.push_back(t);
    } else if (a == "--configs") {
      timed.assign(kConfigCount, false);
      std::stringstream list(next());
      for (std::string t; std::getline(list, t, ',');)
        if (const int c = std::atoi(t.c_str()); c >= 0 && c < kConfigCount) timed[std::size_t(c)] = true;
      timed[0] = true;  // the ratios' base
    } else if (a == "--compositing") {
      base.settings.compositing = tspgl::parse_compositing(next(), "--compositing");
    } else {
      file = a;
    }
  }
  if (file.empty()) {
    file = (fs::temp_directory_path() / "shading_bench_shock.tsp").string();
    auto src = tsp::make_generated_source("shock");
    tsp::BuildOptions bo;
    bo.brick_size = 16;
    tsp::build_tsp_file(*src, file, bo);
  }
  base.tsp_path = file;
  std::printf("%s: %dx%d, view 30,20, spacing %g, %s, refine-tol %g, %d rounds\n", file.c_str(),
              base.camera.width, base.camera.height, base.settings.spacing,
              tspgl::to_string(base.settings.compositing), refine_tol, rounds);
  std::printf("%-14s %-22s %14s %14s\n", "tf", "configuration", "median ms", "ratio to plain");
  for (const std::string& tf : tfs) {
    tspgl::RenderJobOptions o = base;
    o.tf = tf;
    const std::string tf_name = fs::path(tf).filename().string();
    std::vector<double> ms[kConfigCount], ratio[kConfigCount];
    for (int r = 0; r < rounds; ++r) {
      double t[kConfigCount];
      for (int c = 0; c < kConfigCount; ++c)
        if (timed[std::size_t(c)]) t[c] = frame_ms(o, kConfigs[c], refine_tol);
      for (int c = 0; c < kConfigCount; ++c) {
        if (!timed[std::size_t(c)]) continue;
        ms[c].push_back(t[c]);
        ratio[c].push_back(t[c] / t[0]);
      }
    }
    for (int c = 0; c < kConfigCount; ++c)
      if (timed[std::size_t(c)])
        std::printf("%-14s %-22s %14.2f %13.3fx\n", tf_name.c_str(), kConfigs[c].label,
                    median(ms[c]), median(ratio[c]));
    std::fflush(stdout);
  }
  return 0;
}
