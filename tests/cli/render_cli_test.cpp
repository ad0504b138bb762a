// tspplay render / diff end to end: the files and frames.json keys the issue promises, TSP at zero
// tolerance against --baseline through `diff --json`, and bad input that writes nothing.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <vector>

#include "support/json_file.h"
#include "support/paths.h"
#include "tsp/metric/tf_io.h"
#include "tsp/report/image.h"
#include "tsp/report/image_diff.h"
#include "tsp/source/open_source.h"
#include "tsp/store/tsp_file.h"

namespace {

namespace fs = std::filesystem;
using nlohmann::json;
using namespace tsptest;  // run_tspplay, q, temp_dir and the JSON readers

fs::path make_tsp() {
  fs::path dir = tsptest::temp_dir();
  auto g = run_tspplay("generate shock -o " + q(dir / "s.h5") + " --dims 30,28,26 --steps 4");
  EXPECT_EQ(g.exit_code, 0) << g.err;
  auto b = run_tspplay("build " + q(dir / "s.h5") + " --field shock --brick 16 -o " + q(dir / "s.tsp"));
  EXPECT_EQ(b.exit_code, 0) << b.err;
  return dir / "s.tsp";
}

TEST(RenderCli, WritesFramesAndReportWithEveryKey) {
  fs::path tsp = make_tsp(), out = tsptest::temp_dir() / "frames";
  auto r = run_tspplay("render " + q(tsp) + " --tf preset:filled --steps 1:3 --size 96x64 --passes 2 -o " +
                       q(out));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  for (int t = 1; t <= 3; ++t) {
    char name[32];
    std::snprintf(name, sizeof name, "step_%04d.png", t);
    EXPECT_TRUE(fs::exists(out / name)) << name;
  }
  EXPECT_FALSE(fs::exists(out / "step_0000.png"));
  json j = frames_json(out);
  ASSERT_EQ(j["frames"].size(), 6u);  // 3 steps × 2 passes, in order
  int i = 0;
  for (const json& f : j["frames"]) {
    EXPECT_EQ(f["pass"], 1 + i / 3);
    EXPECT_EQ(f["step"], 1 + i % 3);
    ++i;
    for (const char* k : {"ms", "traversal_ms", "slicing_ms", "upload_ms", "draw_ms", "not_rendered",
                          "untextured", "reused_texture", "new_texture", "bytes_uploaded",
                          "textures_resident", "texture_bytes"})
      EXPECT_TRUE(f.contains(k)) << k;
    double sum = f["not_rendered"].get<double>() + f["untextured"].get<double>() +
                 f["reused_texture"].get<double>() + f["new_texture"].get<double>();
    EXPECT_NEAR(sum, 100.0, 1e-6);
    EXPECT_GE(f["ms"].get<double>(), f["draw_ms"].get<double>());
  }
  // The second pass finds every texture resident (cache on, budget ample): nothing new.
  for (int k = 3; k < 6; ++k) EXPECT_EQ(j["frames"][k]["new_texture"], 0.0) << k;
  EXPECT_EQ(j["skip_transparent"], true);  // our traversal rule by default
  auto paper = run_tspplay("render " + q(tsp) + " --tf preset:filled --steps 1 --size 96x64 "
                           "--skip-transparent off -o " + q(out.string() + "_paper"));
  ASSERT_EQ(paper.exit_code, 0) << paper.err;
  EXPECT_EQ(frames_json(fs::path(out.string() + "_paper"))["skip_transparent"], false);
}

TEST(RenderCli, ZeroToleranceMatchesBaselineThroughDiff) {
  fs::path tsp = make_tsp(), a = tsptest::temp_dir() / "tsp", b = tsptest::temp_dir() / "base";
  const std::string common = " --tf preset:sparse --steps 2 --size 120x90 --view 50,30 -o ";
  ASSERT_EQ(run_tspplay("render " + q(tsp) + common + q(a)).exit_code, 0);
  ASSERT_EQ(run_tspplay("render " + q(tsp) + " --baseline" + common + q(b)).exit_code, 0);
  auto d = run_tspplay("diff " + q(a / "step_0002.png") + " " + q(b / "step_0002.png") + " --json");
  ASSERT_EQ(d.exit_code, 0) << d.err;
  json j = json::parse(d.out);
  EXPECT_LT(j["mean"].get<double>(), 0.5);
  EXPECT_LT(j["p99"].get<double>(), 3.0);
  EXPECT_EQ(frames_json(b)["mode"], "baseline");
}

// LOD from the CLI: --lod K records its cut in every frame, --orbit turns the camera by DEG a
// frame, --target-ms (which implies --lod auto) records the target and the controller's cut.
TEST(RenderCli, LodOptionsRecordTheCutPerFrame) {
  fs::path tsp = make_tsp(), dir = tsptest::temp_dir();
  auto fixed = run_tspplay("render " + q(tsp) + " --tf preset:filled --steps 1:2 --size 96x64 "
                           "--lod 1 --orbit 10 -o " + q(dir / "fixed"));
  ASSERT_EQ(fixed.exit_code, 0) << fixed.err;
  json j = frames_json(dir / "fixed");
  EXPECT_EQ(j["lod"], 1);
  EXPECT_EQ(j["orbit_deg"], 10.0);
  ASSERT_EQ(j["frames"].size(), 2u);
  EXPECT_DOUBLE_EQ(j["frames"][1]["azimuth_deg"].get<double>() -
                       j["frames"][0]["azimuth_deg"].get<double>(), 10.0);
  for (const json& f : j["frames"]) {
    const json& l = f["lod"];
    ASSERT_TRUE(l.is_object());
    EXPECT_EQ(l["nodes_per_level"][0], 0);  // level 1 everywhere: no leaf in the cut
    EXPECT_GT(l["nodes_per_level"][1].get<int>(), 0);
    EXPECT_GT(l["texture_bytes"].get<std::int64_t>(), 0);
  }
  auto timed = run_tspplay("render " + q(tsp) + " --tf preset:filled --steps 0:3 --size 96x64 "
                           "--passes 3 --target-ms 30 -o " + q(dir / "timed"));
  ASSERT_EQ(timed.exit_code, 0) << timed.err;
  j = frames_json(dir / "timed");
  EXPECT_EQ(j["lod"], "auto");
  for (const char* k : {"target_ms", "cut_size", "nodes_per_level", "splits", "merges",
                        "texture_bytes", "predicted_ms", "render_scale"})
    EXPECT_TRUE(j["frames"][5]["lod"].contains(k)) << k;
  EXPECT_EQ(j["frames"][5]["lod"]["target_ms"], 30.0);
  EXPECT_EQ(j["frames"][0]["lod"]["cut_size"], 1);  // the first frame: the coarsest cut
  EXPECT_EQ(j["lod_fallback"], "scale");
  // --lod splat:PX: every frame the splat cut of that minimum size, no texture uploaded.
  for (const char* px : {"0", "100000"}) {
    const fs::path out = dir / (std::string("splat") + px);
    auto splat = run_tspplay("render " + q(tsp) + " --tf preset:filled --steps 0:1 --size 96x64 "
                             "--lod splat:" + px + " -o " + q(out));
    ASSERT_EQ(splat.exit_code, 0) << splat.err;
    j = frames_json(out);
    EXPECT_EQ(j["lod"], std::string("splat:") + px + ".0");
    for (const json& f : j["frames"]) {
      EXPECT_EQ(f["bytes_uploaded"], 0);
      EXPECT_EQ(f["lod"]["splat_px"], std::stod(px));
      EXPECT_EQ(f["lod"]["splats"], std::string(px) == "0" ? 8 : 1);  // every leaf, or the root
    }
  }
  auto fallback = run_tspplay("render " + q(tsp) + " --tf preset:filled --steps 0:1 --size 96x64 "
                              "--target-ms 30 --lod-fallback splats -o " + q(dir / "fallback"));
  ASSERT_EQ(fallback.exit_code, 0) << fallback.err;
  EXPECT_EQ(frames_json(dir / "fallback")["lod_fallback"], "splats");
}

TEST(RenderCli, BadInputIsAClearErrorAndWritesNothing) {
  fs::path tsp = make_tsp(), out = tsptest::temp_dir() / "none";
  struct Case {
    std::string args;
    int code;
    std::string message;
  };
  const Case cases[] = {
      {"render " + q(tsp) + " --steps 2:9 -o " + q(out), 2, "has steps 0..3"},
      {"render " + q(tsp) + " --size 0x10 -o " + q(out), 2, "--size"},
      {"render " + q(tsp) + " --view 10,95 -o " + q(out), 2, "elevation"},
      {"render " + q(tsp) + " --tf /nonexistent/tf.json -o " + q(out), 1, "/nonexistent/tf.json"},
      {"render " + q(tsptest::temp_dir() / "missing.tsp") + " -o " + q(out), 1, "missing.tsp"},
      {"render " + q(tsp) + " --metric nope -o " + q(out), 2, "metric"},
      {"render " + q(tsp) + " --lod 1 --target-ms 20 -o " + q(out), 2, "--target-ms needs --lod auto"},
      {"render " + q(tsp) + " --lod fine -o " + q(out), 2, "--lod"},
      {"render " + q(tsp) + " --target-ms -5 -o " + q(out), 2, "--target-ms"},
      {"render " + q(tsp) + " --lod 1 --baseline -o " + q(out), 2, "--lod is for the TSP renderer"},
      {"render " + q(tsp) + " --orbit 400 -o " + q(out), 2, "--orbit"},
      {"render " + q(tsp) + " --focus 1,2 --lod auto -o " + q(out), 2, "--focus"},
      {"render " + q(tsp) + " --lod splat:-1 -o " + q(out), 2, "--lod splat:-1"},
      {"render " + q(tsp) + " --skip-transparent maybe -o " + q(out), 2, "--skip-transparent"},
      {"render " + q(tsp) + " --lod splat:big -o " + q(out), 2, "--lod splat:PX"},
      {"render " + q(tsp) + " --target-ms 20 --lod-fallback smaller -o " + q(out), 2, "--lod-fallback smaller"},
  };
  for (const Case& c : cases) {
    auto r = run_tspplay(c.args);
    EXPECT_EQ(r.exit_code, c.code) << c.args << "\n" << r.err;
    EXPECT_NE(r.err.find(c.message), std::string::npos) << c.args << "\n" << r.err;
    EXPECT_FALSE(fs::exists(out)) << c.args;
  }
}

}  // namespace

namespace {

TEST(RenderCli, StepStrideAndOutputFolderRules) {
  const fs::path tsp = make_tsp();
  const fs::path dir = tsptest::temp_dir();
  // A:B:S renders every S-th step.
  const fs::path out = dir / "strided";
  fs::remove_all(out);
  auto r = run_tspplay("render " + q(tsp) + " --steps 0:3:2 --size 48x32 -o " + q(out));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_TRUE(fs::exists(out / "step_0000.png"));
  EXPECT_FALSE(fs::exists(out / "step_0001.png"));
  EXPECT_TRUE(fs::exists(out / "step_0002.png"));
  EXPECT_EQ(frames_json(out)["frames"].size(), 2u);
  // A bad range is quoted whole.
  r = run_tspplay("render " + q(tsp) + " --steps 0:40:x -o " + q(out));
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("'0:40:x'"), std::string::npos) << r.err;
  // The output folder is made, a missing parent is an error (as build's -o), nothing is made.
  const fs::path deep = dir / "no_such_parent" / "frames";
  fs::remove_all(dir / "no_such_parent");
  r = run_tspplay("render " + q(tsp) + " --steps 0 -o " + q(deep));
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_NE(r.err.find("no_such_parent"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(dir / "no_such_parent"));
  // bench takes no stride.
  r = run_tspplay("bench " + q(tsp) + " --steps 0:3:2 -o " + q(dir / "b"));
  EXPECT_EQ(r.exit_code, 2);
}

TEST(Cli, UnknownSubcommandNamesTheKnownOnes) {
  auto r = run_tspplay("frobnicate x");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("unknown subcommand 'frobnicate'"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("build"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("render"), std::string::npos) << r.err;
  // The raw reader's hint names the option the CLI has.
  const fs::path raw = tsptest::temp_dir() / "hint.raw";
  { std::ofstream(raw) << std::string(64, '\0'); }
  r = run_tspplay("build " + q(raw) + " -o " + q(tsptest::temp_dir() / "hint.tsp"));
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("--raw-dims"), std::string::npos) << r.err;
}

}  // namespace

namespace {

// ffprobe's "width,height,frames" of a movie's first video stream.
std::string probe(const fs::path& movie) {
  const std::string cmd = "ffprobe -v error -count_frames -select_streams v:0 -show_entries "
                          "stream=width,height,nb_read_frames -of csv=p=0 " + q(movie);
  std::string out;
  if (FILE* p = popen(cmd.c_str(), "r")) {
    char buf[256];
    while (fgets(buf, sizeof buf, p)) out += buf;
    pclose(p);
  }
  while (!out.empty() && (out.back() == '\n' || out.back() == '\r')) out.pop_back();
  return out;
}

TEST(RenderCli, MovieOfTheRenderedStepsDecodes) {
  // Needs ffmpeg and ffprobe (scripts/install-deps.sh installs them).
  const fs::path tsp = make_tsp();
  const fs::path dir = tsptest::temp_dir();
  auto r = run_tspplay("render " + q(tsp) + " --steps 0:3:2 --size 64x48 --movie " +
                       q(dir / "m.mp4") + " -o " + q(dir / "mf"));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(probe(dir / "m.mp4"), "64,48,2");
  r = run_tspplay("render " + q(tsp) + " --steps 1:3 --size 65x47 --movie " + q(dir / "m.gif") +
                  " -o " + q(dir / "mg"));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(probe(dir / "m.gif"), "65,47,3");
  // A name that is no movie is refused before anything is rendered.
  r = run_tspplay("render " + q(tsp) + " --movie " + q(dir / "m.avi") + " -o " + q(dir / "mx"));
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_FALSE(fs::exists(dir / "mx"));
}

}  // namespace

namespace {

TEST(RenderCli, ATransferFunctionThatMissesTheDataIsWarnedAbout) {
  const fs::path tsp = make_tsp(), dir = tsptest::temp_dir(), tf = dir / "miss.json";
  std::ofstream(tf) << R"({"range": [5, 6], "points": [[5, 1, 0, 0, 1], [6, 1, 0, 0, 1]]})";
  auto r = run_tspplay("render " + q(tsp) + " --tf " + q(tf) + " --steps 0 --size 32x24 -o " +
                       q(dir / "a"));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.err.find("warning: the transfer function covers"), std::string::npos) << r.err;
  r = run_tspplay("render " + q(tsp) + " --tf " + q(tf) + " --tf-range data --steps 0 " +
                  "--size 32x24 -o " + q(dir / "b"));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(r.err.find("warning"), std::string::npos) << r.err;
  r = run_tspplay("render " + q(tsp) + " --tf preset:viridis --tf-range 1:0 -o " + q(dir / "c"));
  EXPECT_EQ(r.exit_code, 2);
}

// --tf-range step: the map is stretched over the first drawn step's own range — the extreme
// values of that step read back from the source (brute force) — not the series'; the colours
// change accordingly and match an explicit LO:HI of those values.
TEST(RenderCli, TfRangeStepStretchesTheMapOverTheStepsRange) {
  const fs::path dir = tsptest::temp_dir();
  // The vortex's early steps span less than the series' range.
  auto g = run_tspplay("generate vortex -o " + q(dir / "v.h5") + " --dims 24,24,24 --steps 6");
  ASSERT_EQ(g.exit_code, 0) << g.err;
  ASSERT_EQ(run_tspplay("build " + q(dir / "v.h5") + " --field vortex --brick 8 -o " +
                        q(dir / "v.tsp")).exit_code, 0);
  tsp::SourceOptions so;
  so.field = "vortex";
  auto src = tsp::open_source((dir / "v.h5").string(), so);
  std::vector<float> v(std::size_t(src->dims().count()));
  src->read_step(0, v);
  const auto [lo, hi] = std::minmax_element(v.begin(), v.end());
  float series_lo = *lo, series_hi = *hi;
  for (int t = 1; t < src->steps(); ++t) {
    src->read_step(t, v);
    series_lo = std::min(series_lo, *std::min_element(v.begin(), v.end()));
    series_hi = std::max(series_hi, *std::max_element(v.begin(), v.end()));
  }
  src->read_step(0, v);
  const float step_lo = *std::min_element(v.begin(), v.end());
  const float step_hi = *std::max_element(v.begin(), v.end());
  ASSERT_GT(series_hi - series_lo, 1.05 * (step_hi - step_lo)) << "the fixture's step 0 must span less";

  const std::string common = " --tf preset:filled --steps 0 --size 96x72 ";
  auto r = run_tspplay("render " + q(dir / "v.tsp") + common + "--tf-range step --save-tf " +
                       q(dir / "step.json") + " -o " + q(dir / "step"));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const tsp::ValueRange d = tsp::load_transfer_function((dir / "step.json").string()).domain();
  const double tol = 1e-5 * (series_hi - series_lo);
  EXPECT_NEAR(d.lo, step_lo, tol);
  EXPECT_NEAR(d.hi, step_hi, tol);
  ASSERT_EQ(run_tspplay("render " + q(dir / "v.tsp") + common + "-o " + q(dir / "auto")).exit_code, 0);
  char range[96];
  std::snprintf(range, sizeof range, "%.9g:%.9g", double(step_lo), double(step_hi));
  ASSERT_EQ(run_tspplay("render " + q(dir / "v.tsp") + common + "--tf-range " + range + " -o " +
                        q(dir / "explicit")).exit_code, 0);
  const tsp::Image step = tsp::read_png((dir / "step" / "step_0000.png").string());
  const tsp::DiffStats vs_auto =
      tsp::diff_images(step, tsp::read_png((dir / "auto" / "step_0000.png").string()));
  const tsp::DiffStats vs_explicit =
      tsp::diff_images(step, tsp::read_png((dir / "explicit" / "step_0000.png").string()));
  EXPECT_GT(vs_auto.mean, 1.0);       // other colours than the series' map
  EXPECT_LT(vs_explicit.mean, 0.05);  // the step's own range, as written out
  // Bad choices are usage errors.
  r = run_tspplay("render " + q(dir / "v.tsp") + " --tf-range steps -o " + q(dir / "bad"));
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("step"), std::string::npos) << r.err;
}

// --tf-range visible: the map over the values of the leaf bricks the view shows — with a plane
// probe keeping x <= 4, the column of bricks at x = 0 alone — checked against the source's own
// samples inside those bricks' boxes; with the whole volume in view and no probe, the step's
// range.
TEST(RenderCli, TfRangeVisibleTakesTheBricksInViewAndInsideTheProbes) {
  const fs::path dir = tsptest::temp_dir();
  ASSERT_EQ(run_tspplay("generate vortex -o " + q(dir / "v.h5") + " --dims 24,24,24 --steps 6")
                .exit_code, 0);
  ASSERT_EQ(run_tspplay("build " + q(dir / "v.h5") + " --field vortex --brick 8 -o " +
                        q(dir / "v.tsp")).exit_code, 0);
  // The bricks' own boxes at x = 0 reach up to x_hi (the plane at 4 removes the next column).
  auto file = tsp::TspFile::open((dir / "v.tsp").string());
  const tsp::Octree& octree = file->tree().octree();
  int x_hi = 0;
  for (int o = 0; o < octree.size(); ++o)
    if (octree.node(o).is_leaf() && octree.node(o).box.lo[0] == 0)
      x_hi = std::max(x_hi, octree.node(o).box.hi[0]);
  ASSERT_GT(x_hi, 4);
  ASSERT_LT(x_hi, 12);
  tsp::SourceOptions so;
  so.field = "vortex";
  auto src = tsp::open_source((dir / "v.h5").string(), so);
  const tsp::Dims d = src->dims();
  std::vector<float> v(std::size_t(d.count()));
  src->read_step(2, v);
  float lo = 1e30f, hi = -1e30f;
  for (int z = 0; z < d.z; ++z)
    for (int y = 0; y < d.y; ++y)
      for (int x = 0; x < x_hi; ++x) {
        const float s = v[std::size_t(x + d.x * (y + std::int64_t(d.y) * z))];
        lo = std::min(lo, s);
        hi = std::max(hi, s);
      }
  const float step_lo = *std::min_element(v.begin(), v.end());
  const float step_hi = *std::max_element(v.begin(), v.end());
  ASSERT_TRUE(lo > step_lo || hi < step_hi) << "the column must span less than the step";
  const std::string common = " --steps 2 --size 96x72 --tf-range visible --save-tf ";
  auto r = run_tspplay("render " + q(dir / "v.tsp") + common + q(dir / "probe.json") +
                       " --probe plane:1,0,0,4 -o " + q(dir / "probe"));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const tsp::ValueRange p = tsp::load_transfer_function((dir / "probe.json").string()).domain();
  const double tol = 1e-5 * (step_hi - step_lo);
  EXPECT_NEAR(p.lo, lo, tol);
  EXPECT_NEAR(p.hi, hi, tol);
  r = run_tspplay("render " + q(dir / "v.tsp") + common + q(dir / "all.json") + " -o " +
                  q(dir / "all"));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const tsp::ValueRange a = tsp::load_transfer_function((dir / "all.json").string()).domain();
  EXPECT_NEAR(a.lo, step_lo, tol);
  EXPECT_NEAR(a.hi, step_hi, tol);
}

}  // namespace

namespace {

// Pixels of img within [x0, x1) × [y0, y1) equal to rgb.
int count_colour(const tsp::Image& img, int x0, int y0, int x1, int y1, const unsigned char rgb[3]) {
  int n = 0;
  for (int y = y0; y < y1; ++y)
    for (int x = x0; x < x1; ++x) {
      const std::uint8_t* p = img.at(x, y);
      n += p[0] == rgb[0] && p[1] == rgb[1] && p[2] == rgb[2];
    }
  return n;
}

TEST(RenderCli, AnnotateDrawsOutlineLegendAndStep) {
  const fs::path tsp = make_tsp(), dir = tsptest::temp_dir();
  const std::string common = " --tf preset:cool-to-warm --steps 1 --size 320x240 -o ";
  ASSERT_EQ(run_tspplay("render " + q(tsp) + " --annotate" + common + q(dir / "a")).exit_code, 0);
  ASSERT_EQ(run_tspplay("render " + q(tsp) + common + q(dir / "b")).exit_code, 0);
  const tsp::Image a = tsp::read_png((dir / "a" / "step_0001.png").string());
  const tsp::Image b = tsp::read_png((dir / "b" / "step_0001.png").string());
  const unsigned char outline[3] = {200, 200, 200}, text[3] = {235, 235, 235};
  // The outline box: many pixels of its colour, none without --annotate.
  EXPECT_GT(count_colour(a, 0, 0, 320, 240, outline), 300);
  EXPECT_EQ(count_colour(b, 0, 0, 320, 240, outline), 0);
  // The legend: its top row the map's high end, its bottom row the low end (cool-to-warm).
  const int lx = 320 - 10 - 16 - 48 + 8, top = (240 - 120) / 2, bottom = top + 119;
  const std::uint8_t* hi = a.at(lx, top);
  const std::uint8_t* lo = a.at(lx, bottom);
  EXPECT_NEAR(hi[0], 180, 2);
  EXPECT_NEAR(hi[2], 38, 2);
  EXPECT_NEAR(lo[0], 59, 2);
  EXPECT_NEAR(lo[2], 192, 2);
  // "step 1" top left, in the text colour.
  EXPECT_GT(count_colour(a, 0, 0, 120, 30, text), 40);
  EXPECT_EQ(count_colour(b, 0, 0, 120, 30, text), 0);
}

}  // namespace

namespace {

TEST(RenderCli, FramesSayWhichStepsATemporalToleranceMerged) {
  const fs::path tsp = make_tsp(), dir = tsptest::temp_dir();
  ASSERT_EQ(run_tspplay("render " + q(tsp) + " --tf preset:filled --size 48x32 -o " +
                        q(dir / "exact")).exit_code, 0);
  ASSERT_EQ(run_tspplay("render " + q(tsp) + " --tf preset:filled --temporal-tol 10 --size 48x32 "
                        "-o " + q(dir / "merged")).exit_code, 0);
  const json exact = frames_json(dir / "exact"),
             merged = frames_json(dir / "merged");  // named: they outlive the loops
  // Zero tolerance merges only where the data do not change in time; a large one merges more.
  int exact_width = 0, merged_width = 0;
  for (const auto& f : exact["frames"])
    exact_width += f["steps_merged"][1].get<int>() - f["steps_merged"][0].get<int>();
  for (const auto& f : merged["frames"])
    merged_width += f["steps_merged"][1].get<int>() - f["steps_merged"][0].get<int>();
  EXPECT_GE(merged_width, exact_width);
  bool wider = false;
  for (const auto& f : merged["frames"]) {
    wider |= f["steps_merged"][1].get<int>() > f["steps_merged"][0].get<int>();
    EXPECT_LE(f["steps_merged"][0].get<int>(), f["step"].get<int>());
    EXPECT_GE(f["steps_merged"][1].get<int>(), f["step"].get<int>());
  }
  EXPECT_TRUE(wider) << merged["frames"].dump();
}

// --span-step: what textures a merged span. Its mean shows every step of the span; its first or
// middle (the default) step one step each; frames.json records the rule; other words are refused.
TEST(RenderCli, SpanStepChoosesWhatTexturesAMergedSpan) {
  const fs::path tsp = make_tsp(), dir = tsptest::temp_dir();
  for (const char* rule : {"", "first", "middle", "mean"}) {
    const std::string name = *rule ? rule : "default";
    ASSERT_EQ(run_tspplay("render " + q(tsp) + " --tf preset:filled --temporal-tol 10 --size 48x32 " +
                          (*rule ? std::string("--span-step ") + rule + " " : "") + "-o " +
                          q(dir / name)).exit_code, 0) << name;
    const json j = frames_json(dir / name);
    EXPECT_EQ(j["span_step"], *rule ? rule : "middle");
    bool shows_a_span = false;
    for (const auto& f : j["frames"]) {
      const int lo = f["steps_shown"][0].get<int>(), hi = f["steps_shown"][1].get<int>();
      EXPECT_GE(lo, f["steps_merged"][0].get<int>());
      EXPECT_LE(hi, f["steps_merged"][1].get<int>());
      shows_a_span |= hi > lo;
    }
    // One step per texture under first and middle: a frame shows several steps only when its
    // textures come from different spans; under the mean every merged span shows all its steps.
    if (name == "mean") {
      EXPECT_TRUE(shows_a_span) << j["frames"].dump();
    }
  }
  EXPECT_NE(tsptest::read_file(dir / "first" / "step_0001.png"),
            tsptest::read_file(dir / "mean" / "step_0001.png"));
  const auto bad = run_tspplay("render " + q(tsp) + " --tf preset:filled --span-step last -o " +
                               q(dir / "bad"));
  EXPECT_NE(bad.exit_code, 0);
  EXPECT_NE(bad.err.find("--span-step"), std::string::npos) << bad.err;
  EXPECT_FALSE(fs::exists(dir / "bad"));
}


// Physical proportions: `build --spacing` records the voxel size (info shows it); render shows the
// volume in those proportions by default — a different picture from `--proportions samples`,
// which matches a file of unit spacing — and `--scale` stretches an axis further.
TEST(RenderCli, SpacingShapesTheViewUnlessSamplesAreAskedFor) {
  const fs::path dir = tsptest::temp_dir(), h5 = dir / "s.h5";
  ASSERT_EQ(run_tspplay("generate shock -o " + q(h5) + " --dims 30,28,26 --steps 2").exit_code, 0);
  ASSERT_EQ(run_tspplay("build " + q(h5) + " -o " + q(dir / "unit.tsp")).exit_code, 0);
  auto b = run_tspplay("build " + q(h5) + " --spacing 1,1,3 --origin 0,0,-5 -o " +
                       q(dir / "tall.tsp"));
  ASSERT_EQ(b.exit_code, 0) << b.err;
  const auto info = run_tspplay("info " + q(dir / "tall.tsp"));
  EXPECT_NE(info.out.find("at (0, 0, -5) + (i,j,k)*(1, 1, 3)"), std::string::npos) << info.out;
  auto frame = [&](const std::string& file, const std::string& extra, const std::string& name) {
    auto r = run_tspplay("render " + q(dir / file) + " --tf preset:filled --steps 1 --size 80x60 " +
                         extra + " -o " + q(dir / name));
    EXPECT_EQ(r.exit_code, 0) << r.err;
    return tsp::read_png((dir / name / "step_0001.png").string());
  };
  const tsp::Image unit = frame("unit.tsp", "", "u"), tall = frame("tall.tsp", "", "t"),
                   samples = frame("tall.tsp", "--proportions samples", "s"),
                   scaled = frame("unit.tsp", "--scale 1,1,3", "x");
  EXPECT_GT(tsp::diff_images(tall, unit).mean, 1.0);      // three times as tall
  EXPECT_LT(tsp::diff_images(samples, unit).mean, 0.05);  // cubes: the unit file's picture
  EXPECT_LT(tsp::diff_images(scaled, tall).mean, 0.05);   // --scale does what spacing does
  for (const char* bad : {"--scale 1,0,1", "--scale 1,2", "--proportions real"})
    EXPECT_EQ(run_tspplay("render " + q(dir / "unit.tsp") + " " + bad + " -o " + q(dir / "bad"))
                  .exit_code,
              2)
        << bad;
  EXPECT_EQ(run_tspplay("build " + q(h5) + " --spacing 1,-1,1 -o " + q(dir / "bad.tsp")).exit_code,
            2);
  EXPECT_FALSE(fs::exists(dir / "bad.tsp"));
}

// Out of core: with --ram-budget far below the file's bricks, every frame keeps the bricks in
// RAM within the budget (frames.json ram_mib), and the pictures are those of an unbounded run.
TEST(RenderCli, RamBudgetBoundsTheBricksHeldWhateverTheFileSize) {
  const fs::path dir = tsptest::temp_dir(), h5 = dir / "s.h5", tsp = dir / "s.tsp";
  ASSERT_EQ(run_tspplay("generate shock -o " + q(h5) + " --dims 48,40,36 --steps 8").exit_code, 0);
  ASSERT_EQ(run_tspplay("build " + q(h5) + " --brick 16 -o " + q(tsp)).exit_code, 0);
  // The bricks: 8 steps of 48·40·36 samples (and their levels) at 2 bytes — about 1 MiB; the
  // budget a tenth of that.
  const double budget_mib = 0.1;
  auto r = run_tspplay("render " + q(tsp) + " --tf preset:filled --size 64x48 --passes 2 "
                       "--ram-budget 0.1 --texture-budget 0.1 -o " + q(dir / "small"));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  auto big = run_tspplay("render " + q(tsp) + " --tf preset:filled --size 64x48 -o " + q(dir / "big"));
  ASSERT_EQ(big.exit_code, 0) << big.err;
  const json frames = frames_json(dir / "small")["frames"];
  ASSERT_EQ(frames.size(), 16u);
  for (const auto& f : frames) {
    EXPECT_LE(f["ram_mib"].get<double>(), budget_mib + 1e-9) << f.dump();
    EXPECT_GT(f["rss_mib"].get<double>(), 0.0);
  }
  for (int t = 0; t < 8; ++t) {
    char name[32];
    std::snprintf(name, sizeof name, "step_%04d.png", t);
    EXPECT_LT(tsp::diff_images(tsp::read_png((dir / "small" / name).string()),
                               tsp::read_png((dir / "big" / name).string()))
                  .mean,
              0.01)
        << t;
  }
  EXPECT_EQ(run_tspplay("render " + q(tsp) + " --ram-budget 0 -o " + q(dir / "x")).exit_code, 2);
}

}  // namespace
