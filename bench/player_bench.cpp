// The player's two latency numbers, headless (OSMesa), on any .tsp file:
//
//   player_bench FILE.tsp [--tf preset:sparse] [--size 320x240] [--texture-budget MIB]
//                         [--brick-budget MIB] [--scrubs N] [--seed S]
//
// Playback: two full passes over every step, with and without background brick prefetch
// (tsp::BrickPrefetcher fed with VolumeRenderer::bricks_to_upload of the next 2 steps, as the
// player does), reporting steps per second per pass. By default the texture and brick budgets
// are half of what all steps' bricks need, so the second pass cannot be served from the caches
// alone: the dataset is larger than the texture budget.
//
// Scrub latency: jumps to N random steps (seeded), timing the frame from the jump to the
// complete picture; cold = a fresh renderer (empty texture and brick caches) for every jump,
// warm = one renderer after a full pass.
//
// Approximate metric through LazyErrors, tolerances 0, view 30°/20°, orthographic. Timings are
// wall clock; llvmpipe timings say little about a GPU. The file's bricks come from the page cache
// after the first pass (the file is read once up front).
#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <memory>
#include <random>
#include <string>
#include <vector>

#include "bench/support/bench_util.h"
#include "gl/context.h"
#include "render/volume_renderer.h"
#include "tsp/core/error.h"
#include "tsp/core/stopwatch.h"
#include "tsp/frame/camera.h"
#include "tsp/frame/frame_plan.h"
#include "tsp/metric/lazy_errors.h"
#include "tsp/metric/tf_io.h"
#include "tsp/store/brick_prefetcher.h"
#include "tsp/store/tsp_file.h"

namespace {

constexpr int kPrefetchSteps = 2;
constexpr double kMiB = 1 << 20;

struct Args {
  std::string file, tf = "preset:sparse";
  int width = 320, height = 240, scrubs = 10;
  unsigned seed = 1;
  double texture_budget_mib = 0, brick_budget_mib = 0;  // 0: half of all steps' bricks
};

[[noreturn]] void usage(const std::string& what) {
  std::fprintf(stderr,
               "player_bench: %s\nusage: player_bench FILE.tsp [--tf T] [--size WxH] "
               "[--texture-budget MIB] [--brick-budget MIB] [--scrubs N] [--seed S]\n",
               what.c_str());
  std::exit(2);
}

Args parse(int argc, char** argv) {
  Args a;
  for (int i = 1; i < argc; ++i) {
    std::string s = argv[i];
    auto next = [&]() -> std::string {
      if (i + 1 >= argc) usage(s + " needs a value");
      return argv[++i];
    };
    if (s == "--tf")
      a.tf = next();
    else if (s == "--size") {
      std::string v = next();
      if (std::sscanf(v.c_str(), "%dx%d", &a.width, &a.height) != 2 || a.width < 1 || a.height < 1)
        usage("--size expects WxH");
    } else if (s == "--texture-budget")
      a.texture_budget_mib = std::atof(next().c_str());
    else if (s == "--brick-budget")
      a.brick_budget_mib = std::atof(next().c_str());
    else if (s == "--scrubs")
      a.scrubs = std::atoi(next().c_str());
    else if (s == "--seed")
      a.seed = unsigned(std::atoi(next().c_str()));
    else if (!s.empty() && s[0] != '-' && a.file.empty())
      a.file = s;
    else
      usage("unknown argument " + s);
  }
  if (a.file.empty()) usage("no .tsp file given");
  return a;
}

// Everything one measurement needs; a fresh one has empty caches.
struct Player {
  std::unique_ptr<tspgl::VolumeRenderer> renderer;
  std::unique_ptr<tsp::BrickPrefetcher> prefetcher;
  Player(tspgl::GlContext& ctx, const tsp::TspFile& file, const tsp::TransferFunction& tf,
         std::int64_t texture_budget, std::int64_t brick_budget, bool prefetch) {
    renderer = std::make_unique<tspgl::VolumeRenderer>(ctx, file, tsp::CachePolicy::on,
                                                       texture_budget, brick_budget);
    renderer->set_transfer_function(tf);
    if (prefetch) prefetcher = std::make_unique<tsp::BrickPrefetcher>(renderer->brick_cache());
  }
  ~Player() { prefetcher.reset(); }
};

}  // namespace

int main(int argc, char** argv) try {
  const Args a = parse(argc, argv);
  tspbench::warm_page_cache(a.file);
  auto file = tsp::TspFile::open(a.file);
  const tsp::TspTree& tree = file->tree();
  const int steps = tree.time().steps();
  const tsp::TransferFunction tf = tsp::transfer_function_from_arg(a.tf, tree.value_range());
  tsp::LazyErrors lazy(tree, tsp::Metric::approximate, tf);
  auto ctx = tspgl::create_offscreen_context(a.width, a.height);
  tsp::CameraParams cp;
  cp.width = a.width;
  cp.height = a.height;
  const tsp::Camera cam(tree.octree().dims(), cp);
  const tspgl::RenderSettings settings;

  std::int64_t all_bytes = 0;
  for (int b = 0; b < tree.octree().brick_count(); ++b)
    all_bytes += tsp::texture_bytes(tree.octree(), tsp::TextureKey{b, 0, 0});
  all_bytes *= steps;
  auto budget = [&](double mib) {
    return mib > 0 ? std::int64_t(mib * kMiB) : std::max<std::int64_t>(1, all_bytes / 2);
  };
  const std::int64_t tex_budget = budget(a.texture_budget_mib);
  const std::int64_t brick_budget = budget(a.brick_budget_mib);
  std::printf(
      "%s: %d steps, all bricks %.1f MiB; texture budget %.1f MiB, brick budget %.1f MiB; "
      "%dx%d, %s\n",
      a.file.c_str(), steps, double(all_bytes) / kMiB, double(tex_budget) / kMiB,
      double(brick_budget) / kMiB, a.width, a.height, ctx->describe().c_str());
  lazy.all();  // the metric is not what is measured here

  std::printf("\nplayback (2 passes, steps per second)\n%-12s %10s %10s %12s %12s\n", "prefetch",
              "pass 1", "pass 2", "misses", "prefetched");
  for (bool prefetch : {false, true}) {
    Player p(*ctx, *file, tf, tex_budget, brick_budget, prefetch);
    double rate[2] = {0, 0};
    for (int pass = 0; pass < 2; ++pass) {
      const tsp::Stopwatch t0;
      for (int t = 0; t < steps; ++t) {
        p.renderer->render(t, cam, settings, lazy);
        if (p.prefetcher) {
          std::vector<tsp::BrickKey> keys;
          for (int k = 1; k <= kPrefetchSteps; ++k) {
            auto more = p.renderer->bricks_to_upload((t + k) % steps, cam, settings, lazy);
            keys.insert(keys.end(), more.begin(), more.end());
          }
          p.prefetcher->request(std::move(keys));
        }
      }
      rate[pass] = steps / t0.seconds();
    }
    const tsp::BrickCacheStats s = p.renderer->brick_cache().stats();
    std::printf("%-12s %10.2f %10.2f %12lld %12lld\n", prefetch ? "on" : "off", rate[0], rate[1],
                static_cast<long long>(s.misses), static_cast<long long>(s.prefetched));
  }

  std::mt19937 rng(a.seed);
  std::uniform_int_distribution<int> pick(0, steps - 1);
  std::vector<int> jumps;
  for (int i = 0; i < a.scrubs; ++i) jumps.push_back(pick(rng));
  std::vector<double> cold, warm;
  for (int t : jumps) {
    Player p(*ctx, *file, tf, tex_budget, brick_budget, false);
    const tsp::Stopwatch t0;
    p.renderer->render(t, cam, settings, lazy);
    cold.push_back(t0.seconds() * 1000);
  }
  {
    Player p(*ctx, *file, tf, tex_budget, brick_budget, false);
    for (int t = 0; t < steps; ++t) p.renderer->render(t, cam, settings, lazy);
    for (int t : jumps) {
      const tsp::Stopwatch t0;
      p.renderer->render(t, cam, settings, lazy);
      warm.push_back(t0.seconds() * 1000);
    }
  }
  auto median = [](std::vector<double> v) {
    std::sort(v.begin(), v.end());
    return v.empty() ? 0.0 : v[v.size() / 2];
  };
  std::printf("\nscrub latency, jump -> complete frame (%d random steps, seed %u)\n", a.scrubs,
              a.seed);
  std::printf("cold  median %8.2f ms  max %8.2f ms\n", median(cold),
              cold.empty() ? 0.0 : *std::max_element(cold.begin(), cold.end()));
  std::printf("warm  median %8.2f ms  max %8.2f ms\n", median(warm),
              warm.empty() ? 0.0 : *std::max_element(warm.begin(), warm.end()));
  return 0;
} catch (const tsp::Error& e) {
  std::fprintf(stderr, "player_bench: %s\n", e.what());
  return 1;
}
