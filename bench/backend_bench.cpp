// The CPU ray caster against the GL one (issue 43): for each renderer (the TSP tree at zero
// tolerance, the non-TSP baseline) lit and unlit at the default settings, the median frame time
// of each back end (second pass, partial-image reuse off so every frame is drawn whole) and
// their ratio, measured in the same round — rounds alternate the back ends so a loaded
// machine's drift falls on both alike — with the pictures' difference between the back ends
// (worst step's mean and 99th-percentile ΔE) and the samples each frame reads, as samples per
// second per core for each back end (llvmpipe and the CPU caster both use every core).
//
//   backend_bench [FILE.tsp] [--tf TF] [--size WxH] [--steps A:B] [--rounds N] [--spacing D]
//                 [--refine-tol T]
//
// With no file it builds the built-in shock dataset (64³ × 32 steps, bricks of 16) in $TMPDIR.
#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <map>
#include <string>
#include <thread>
#include <vector>

#include "jobs/render_job.h"
#include "tsp/build/build.h"
#include "tsp/report/image_diff.h"
#include "tsp/source/procedural/generate.h"

namespace {

namespace fs = std::filesystem;
using tspgl::Backend;

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  return v.empty() ? 0 : v[v.size() / 2];
}

struct Run {
  double ms = 0;                        // median second-pass frame
  double samples = 0;                   // median samples a frame (CPU frames)
  std::map<int, tsp::Image> pictures;   // second pass, by step
  std::string backend;
};

Run run(tspgl::RenderJobOptions o, Backend b) {
  o.out_dir.clear();
  o.passes = 2;
  o.settings.backend = b;
  o.settings.reuse_image = false;
  Run r;
  std::vector<double> samples;
  o.on_frame = [&](const tspgl::FrameRecord& f, const tsp::Image& img) {
    if (f.pass != 2) return;
    r.pictures[f.report.step] = img;
    samples.push_back(double(f.report.samples));
    r.backend = f.report.backend;
  };
  r.ms = tspgl::median_frame_ms(tspgl::run_render_job(o), 2);
  r.samples = median(samples);
  return r;
}

}  // namespace

int main(int argc, char** argv) {
  std::string file;
  tspgl::RenderJobOptions base;
  base.tf = "preset:auto";
  int rounds = 3;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    auto next = [&]() -> std::string { return i + 1 < argc ? argv[++i] : ""; };
    if (a == "--size")
      std::sscanf(next().c_str(), "%dx%d", &base.camera.width, &base.camera.height);
    else if (a == "--steps")
      std::sscanf(next().c_str(), "%d:%d", &base.first_step, &base.last_step);
    else if (a == "--rounds")
      rounds = std::max(1, std::atoi(next().c_str()));
    else if (a == "--spacing")
      base.settings.spacing = std::atof(next().c_str());
    else if (a == "--refine-tol")
      base.settings.refine_tol = std::atof(next().c_str());
    else if (a == "--tf")
      base.tf = next();
    else
      file = a;
  }
  if (file.empty()) {
    file = (fs::temp_directory_path() / "backend_bench_shock.tsp").string();
    if (!fs::exists(file)) {
      auto src = tsp::make_generated_source("shock");
      tsp::BuildOptions bo;
      bo.brick_size = 16;
      tsp::build_tsp_file(*src, file, bo);
    }
  }
  base.tsp_path = file;
  const unsigned cores = std::max(1u, std::thread::hardware_concurrency());
  std::printf("%s: %dx%d, tf %s, spacing %g, refine-tol %g, %d rounds, %u cores\n", file.c_str(),
              base.camera.width, base.camera.height, base.tf.c_str(), base.settings.spacing,
              base.settings.refine_tol, rounds, cores);
  std::printf("%-9s %-6s %10s %10s %9s %13s %13s %9s %9s\n", "renderer", "light", "gl ms",
              "cpu ms", "speedup", "gl Ms/s/core", "cpu Ms/s/core", "mean dE", "p99 dE");
  for (bool baseline : {false, true})
    for (bool shade : {false, true}) {
      tspgl::RenderJobOptions o = base;
      o.baseline = baseline;
      o.settings.shade = shade;
      std::vector<double> gl_ms, cpu_ms, speedup;
      Run gl, cpu;
      for (int r = 0; r < rounds; ++r) {
        gl = run(o, Backend::gl);
        cpu = run(o, Backend::cpu);
        gl_ms.push_back(gl.ms);
        cpu_ms.push_back(cpu.ms);
        speedup.push_back(gl.ms / cpu.ms);
      }
      double worst_mean = 0, worst_p99 = 0;
      for (const auto& [step, img] : cpu.pictures) {
        const tsp::DiffStats d = tsp::diff_images(img, gl.pictures.at(step));
        worst_mean = std::max(worst_mean, d.mean);
        worst_p99 = std::max(worst_p99, d.p99);
      }
      // The same samples on both (the GL caster takes the ones the CPU caster counts).
      const double per_core = cpu.samples / cores / 1e3;  // samples / ms / core → M/s
      std::printf("%-9s %-6s %10.1f %10.1f %8.2fx %13.1f %13.1f %9.3f %9.3f%s\n",
                  baseline ? "baseline" : "tsp", shade ? "lit" : "unlit", median(gl_ms),
                  median(cpu_ms), median(speedup), per_core / median(gl_ms),
                  per_core / median(cpu_ms), worst_mean, worst_p99,
                  cpu.backend == "cpu" ? "" : "  (cpu run drawn by gl!)");
      std::fflush(stdout);
    }
  return 0;
}
