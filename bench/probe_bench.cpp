// Clip probes and fields (issue 14, docs/results.md), headless at 640×480, in one run:
//  1. a plane probe sweeping through the data with the LOD cut holding a frame-time target:
//     median and p90 frame time against the target;
//  2. half the volume clipped away (a plane through the centre, six orientations) against the
//     unclipped frame timed right before it, TSP renderer at zero tolerance: the frame-time ratio
//     per orientation, and the share of the unclipped frame's fragments each half keeps;
//  3. switching field (a file with two fields): time from the switch to the other field's first
//     complete frame — cold (its bricks read from the file) and back again (its renderer kept,
//     as the player keeps it).
//
//   probe_bench FILE.tsp [--tf preset:filled] [--steps A:B] [--target-ms 40] [--passes 3]
//               [--size WxH] [--part all|sweep|half|switch]
#include <algorithm>
#include <cstdio>
#include <string>
#include <vector>

#include "gl/context.h"
#include "jobs/render_job.h"
#include "render/volume_renderer.h"
#include "tsp/core/error.h"
#include "tsp/core/stopwatch.h"
#include "tsp/lod/lod_cut.h"
#include "tsp/metric/lazy_errors.h"
#include "tsp/metric/tf_io.h"
#include "tsp/store/tsp_file.h"

namespace {

double median_of(std::vector<double> v) { return tspgl::median(std::move(v)); }

double percentile(std::vector<double> v, double q) {
  std::sort(v.begin(), v.end());
  return v.empty() ? 0 : v[std::min(v.size() - 1, std::size_t(q * double(v.size())))];
}

std::vector<double> frame_ms(const tspgl::RenderJobResult& r, int from_pass) {
  std::vector<double> ms;
  for (const auto& f : r.frames)
    if (f.pass >= from_pass) ms.push_back(f.report.ms);
  return ms;
}


}  // namespace

int main(int argc, char** argv) {
  if (argc < 2) {
    std::fprintf(stderr, "usage: probe_bench FILE.tsp [--tf T] [--steps A:B] [--target-ms MS] "
                         "[--passes N] [--size WxH] [--part all|sweep|half|switch]\n");
    return 2;
  }
  try {
    tspgl::RenderJobOptions base;
    base.tsp_path = argv[1];
    base.tf = "preset:filled";
    base.passes = 3;
    double target = 40;
    std::string part = "all";  // --part sweep|half|switch: one part alone
    for (int i = 2; i + 1 < argc; i += 2) {
      const std::string a = argv[i], v = argv[i + 1];
      if (a == "--tf") base.tf = v;
      else if (a == "--target-ms") target = std::stod(v);
      else if (a == "--passes") base.passes = std::stoi(v);
      else if (a == "--part") part = v;
      else if (a == "--steps") {
        const auto c = v.find(':');
        base.first_step = std::stoi(v.substr(0, c));
        base.last_step = c == std::string::npos ? base.first_step : std::stoi(v.substr(c + 1));
      } else if (a == "--size") {
        const auto x = v.find('x');
        base.camera.width = std::stoi(v.substr(0, x));
        base.camera.height = std::stoi(v.substr(x + 1));
      } else {
        throw tsp::UsageError("unknown option " + a);
      }
    }
    auto file = tsp::TspFile::open(base.tsp_path);
    const tsp::Dims d = file->tree().octree().dims();
    const auto& org = file->metadata().origin;
    const auto& sp = file->metadata().spacing;
    double centre[3], extent[3];
    for (int a = 0; a < 3; ++a) {
      centre[a] = org[std::size_t(a)] + sp[std::size_t(a)] * 0.5 * (d[a] - 1);
      extent[a] = sp[std::size_t(a)] * (d[a] - 1);
    }
    std::printf("file %s, %s voxels, TF %s, %dx%d\n", base.tsp_path.c_str(),
                tsp::to_string(d).c_str(), base.tf.c_str(), base.camera.width, base.camera.height);

    if (part != "all" && part != "sweep" && part != "half" && part != "switch")
      throw tsp::UsageError("--part " + part + ": expected all, sweep, half or switch");
    // 1. A plane sweeping along z from the bottom to the top, the cut holding the target.
    if (part == "all" || part == "sweep") {
      tspgl::RenderJobOptions o = base;
      o.lod = tspgl::LodMode::adaptive;
      o.target_ms = target;
      o.probe_surface = true;
      char text[128];
      std::snprintf(text, sizeof text, "plane:0,0,1,%g", org[2]);
      o.probes = {tsp::parse_probe(text)};
      const int steps = (o.last_step < 0 ? file->tree().time().steps() - 1 : o.last_step) -
                        o.first_step + 1;
      const int frames = steps * o.passes;
      o.probe_motion = {0, 0, extent[2] / std::max(1, frames - 1)};
      const tspgl::RenderJobResult r = tspgl::run_render_job(o);
      std::vector<double> ms = frame_ms(r, 1);
      ms.erase(ms.begin(), ms.begin() + std::min<std::ptrdiff_t>(3, std::ptrdiff_t(ms.size())));
      int under = 0;
      for (double m : ms) under += m < 1.5 * target;
      std::printf("sweep: plane through z, surface on, LOD target %.0f ms: median %.1f ms (%.0f %%), "
                  "p90 %.1f ms, %.0f %% of %zu frames under 1.5x the target\n",
                  target, median_of(ms), 100 * median_of(ms) / target, percentile(ms, 0.9),
                  100.0 * under / std::max<std::size_t>(1, ms.size()), ms.size());
    }

    // 2. Half the volume clipped away, six ways, against the unclipped frame.
    if (part == "all" || part == "half") {
      // Fragments (pixels the rays start from) of one frame: the share of the image the half
      // still covers bounds what it can save once rays stop early in opaque matter.
      const auto fragments = [](const tspgl::RenderJobResult& r) {
        return r.frames.empty() ? 0.0 : double(r.frames.back().report.fragments);
      };
      const tspgl::RenderJobResult unclipped = tspgl::run_render_job(base);
      const double whole_fragments = fragments(unclipped);
      std::printf("unclipped: median %.1f ms\n", median_of(frame_ms(unclipped, 2)));
      double sum = 0, sum_fragments = 0;
      const char* names[6] = {"x <= c", "x >= c", "y <= c", "y >= c", "z <= c", "z >= c"};
      for (int k = 0; k < 6; ++k) {
        const int a = k / 2;
        const double sign = k % 2 == 0 ? 1 : -1;
        double n[3] = {0, 0, 0};
        n[a] = sign;
        char text[128];
        std::snprintf(text, sizeof text, "plane:%g,%g,%g,%g", n[0], n[1], n[2], sign * centre[a]);
        tspgl::RenderJobOptions o = base;
        o.probes = {tsp::parse_probe(text)};
        // Head to head: the unclipped frame timed again right before each half, so that a host
        // whose speed drifts moves both alike.
        const double whole = median_of(frame_ms(tspgl::run_render_job(base), 2));
        const tspgl::RenderJobResult r = tspgl::run_render_job(o);
        const double half = median_of(frame_ms(r, 2));
        const double share = fragments(r) / std::max(1.0, whole_fragments);
        sum += half / whole;
        sum_fragments += share;
        std::printf("half clipped (%s): median %.1f ms against %.1f unclipped, %.2fx; fragments "
                    "%.2fx\n", names[k], half, whole, half / whole, share);
      }
      std::printf("half clipped, mean of six: %.2fx the unclipped frame; fragments %.2fx\n",
                  sum / 6, sum_fragments / 6);
    }

    // 3. Field switch.
    if (part != "all" && part != "switch") {
    } else if (file->fields().size() > 1) {
      const std::string fa = file->fields()[0], fb = file->fields()[1];
      auto ctx = tspgl::create_offscreen_context(base.camera.width, base.camera.height);
      tsp::CameraParams cp = base.camera;
      cp.voxel_size = tspgl::shown_voxel_size(sp, {1, 1, 1}, true);
      const tsp::Camera cam(d, cp);
      struct Shown {
        std::unique_ptr<tsp::TspFile> file;
        tsp::TransferFunction tf;  // (the metric keeps a reference)
        std::unique_ptr<tsp::LazyErrors> metric;
        std::unique_ptr<tspgl::VolumeRenderer> renderer;
      };
      std::shared_ptr<tspgl::SliceCompositor> shared;
      const int step = std::max(0, base.first_step);
      // Opens field f (its renderer sharing the compositor) and draws its first complete frame.
      auto show = [&](Shown& s, const std::string& f, tsp::LodStops stops = {}) {
        const tsp::Stopwatch w;
        if (!s.renderer) {
          s.file = tsp::TspFile::open(base.tsp_path, f);
          s.tf = tsp::transfer_function_from_arg(base.tf, s.file->tree().value_range());
          s.metric = std::make_unique<tsp::LazyErrors>(s.file->tree(), tsp::Metric::approximate, s.tf);
          s.renderer = std::make_unique<tspgl::VolumeRenderer>(
              *ctx, *s.file, tsp::CachePolicy::on, tspgl::kDefaultTextureBudget,
              tspgl::kDefaultBrickBudget, shared);
          s.renderer->set_transfer_function(s.tf);
          if (!shared) shared = s.renderer->compositor();
        }
        tspgl::RenderSettings rs;
        rs.reuse_image = false;
        s.renderer->render(step, cam, rs, *s.metric, stops);
        return w.ms();
      };
      Shown a, b;
      show(a, fa);  // warm: the programs compiled, field a's bricks resident
      const double steady_a = show(a, fa);
      const double cold = show(b, fb);
      const double steady_b = show(b, fb);
      const double back = show(a, fa);
      const double again = show(b, fb);
      std::printf("field switch %s -> %s: first complete frame %.1f ms after the switch (cold: "
                  "its bricks read from the file), a steady frame of it %.1f ms: %.1f ms for the "
                  "switch itself\n",
                  fa.c_str(), fb.c_str(), cold, steady_b, cold - steady_b);
      std::printf("switch back to %s: %.1f ms (steady %.1f), to %s again: %.1f ms (renderers "
                  "kept: their textures resident)\n",
                  fa.c_str(), back, steady_a, fb.c_str(), again);
      // The player with its LOD cut on starts the other field from the coarsest cut (its
      // controller is reset on a switch) and refines from there: that first frame, cold.
      Shown c;
      const tsp::LodCut root(a.file->tree().octree());
      const double cold_lod = show(c, fb, root.stops());
      std::printf("field switch %s -> %s with the LOD cut (the player): first complete frame "
                  "%.1f ms after the switch (the coarsest cut, cold)\n",
                  fa.c_str(), fb.c_str(), cold_lod);
    } else {
      std::printf("field switch: the file has one field (build --field A,B for this part)\n");
    }
  } catch (const std::exception& e) {
    std::fprintf(stderr, "probe_bench: %s\n", e.what());
    return 1;
  }
  return 0;
}
