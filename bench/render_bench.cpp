// The paper's Table 3 and Table 5 on our data: at zero tolerance, the non-TSP baseline against
// the TSP renderer with each metric, texture cache off and on, sparse and filled transfer
// functions; median frame time over all steps at 640×480 (second pass: the cache is warm when
// on), the class shares, and the share of a cached frame spent outside drawing.
//
//   render_bench FILE.tsp [FILE.tsp ...] [--size WxH] [--steps A:B] [--metrics a,b] [--tol S,T]
//
// With no file it builds the built-in shock dataset (64³ × 32 steps, bricks of 16) in $TMPDIR.
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <string>
#include <vector>

#include "jobs/render_job.h"
#include "tsp/build/build.h"
#include "tsp/source/procedural/generate.h"
#include "tsp/store/tsp_file.h"

namespace {

namespace fs = std::filesystem;

struct Row {
  std::string label;
  double median_ms = 0;
  double classes[4] = {0, 0, 0, 0};
  double outside_draw = 0;  // (traversal + slicing + upload) / ms, cached pass
};

Row measure(const std::string& label, tspgl::RenderJobOptions o) {
  o.out_dir.clear();  // time only
  o.passes = 2;
  tspgl::RenderJobResult r = tspgl::run_render_job(o);
  Row row;
  row.label = label;
  row.median_ms = tspgl::median_frame_ms(r, 2);
  int n = 0;
  for (const auto& f : r.frames) {
    if (f.pass != 2) continue;
    for (int c = 0; c < 4; ++c) row.classes[c] += f.report.class_percent[std::size_t(c)];
    const auto& p = f.report;
    row.outside_draw += (p.traversal_ms + p.slicing_ms + p.upload_ms) / p.ms;
    ++n;
  }
  for (double& c : row.classes) c /= n;
  row.outside_draw /= n;
  return row;
}

}  // namespace

int main(int argc, char** argv) {
  std::vector<std::string> files;
  tspgl::RenderJobOptions base;
  std::vector<tsp::Metric> metrics = {tsp::Metric::scalar, tsp::Metric::approximate,
                                      tsp::Metric::perceptual, tsp::Metric::reference};
  for (int i = 1; i < argc; ++i) {
    std::string a = argv[i];
    auto next = [&]() -> std::string { return i + 1 < argc ? argv[++i] : ""; };
    if (a == "--size") {
      std::string v = next();
      std::sscanf(v.c_str(), "%dx%d", &base.camera.width, &base.camera.height);
    } else if (a == "--steps") {
      std::string v = next();
      std::sscanf(v.c_str(), "%d:%d", &base.first_step, &base.last_step);
    } else if (a == "--tol") {
      std::string v = next();
      std::sscanf(v.c_str(), "%lf,%lf", &base.settings.tol.spatial, &base.settings.tol.temporal);
    } else if (a == "--metrics") {
      metrics.clear();
      std::string v = next();
      for (std::size_t p = 0; p <= v.size();) {
        std::size_t c = v.find(',', p);
        metrics.push_back(tsp::parse_metric(v.substr(p, c == std::string::npos ? c : c - p)));
        p = c == std::string::npos ? v.size() + 1 : c + 1;
      }
    } else {
      files.push_back(a);
    }
  }
  if (files.empty()) {
    const std::string path = (fs::temp_directory_path() / "render_bench_shock.tsp").string();
    auto src = tsp::make_generated_source("shock");
    tsp::BuildOptions bo;
    bo.brick_size = 16;
    tsp::build_tsp_file(*src, path, bo);
    files.push_back(path);
  }
  for (const std::string& file : files) {
    auto f = tsp::TspFile::open(file);
    const auto& tree = f->tree();
    std::printf("\n%s: %s x %d steps, brick %d; %dx%d, view 30,20, spacing 0.5, tol %g/%g\n",
                file.c_str(), tsp::to_string(tree.octree().dims()).c_str(), tree.time().steps(),
                tree.octree().brick_size(), base.camera.width, base.camera.height, base.settings.tol.spatial,
                base.settings.tol.temporal);
    std::printf("%-8s %-26s %10s %8s %7s %7s %7s %7s %9s\n", "tf", "renderer", "median ms", "speedup",
                "NR %", "UP %", "RT %", "NT %", "non-draw");
    for (const char* tf : {"sparse", "filled"}) {
      tspgl::RenderJobOptions o = base;
      o.tsp_path = file;
      o.tf = std::string("preset:") + tf;
      o.baseline = true;
      Row b = measure("baseline (non-TSP)", o);
      std::vector<Row> rows = {b};
      o.baseline = false;
      for (tsp::Metric m : metrics)
        for (tsp::CachePolicy c : {tsp::CachePolicy::off, tsp::CachePolicy::on}) {
          o.metric = m;
          o.cache = c;
          rows.push_back(measure(std::string("tsp ") + tsp::to_string(m) +
                                     (c == tsp::CachePolicy::on ? ", cache on" : ", cache off"),
                                 o));
        }
      for (const Row& r : rows)
        std::printf("%-8s %-26s %10.2f %7.2fx %7.1f %7.1f %7.1f %7.1f %8.1f%%\n", tf, r.label.c_str(),
                    r.median_ms, b.median_ms / r.median_ms, r.classes[0], r.classes[1],
                    r.classes[2], r.classes[3], 100 * r.outside_draw);
      std::fflush(stdout);
    }
  }
  return 0;
}
