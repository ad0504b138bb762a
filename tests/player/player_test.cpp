// tspplay play under the current display (xvfb-run in scripts/test.sh), driven by --screenshot and
// --script: the volume shows, scrubbing to step k shows step k (against `tspplay render` of the
// same view and size), a TF edit changes the picture; bad scripts and steps are clear errors.
#include <gtest/gtest.h>
#include <hdf5.h>
#include <sys/stat.h>

#include "jobs/playback_tuner.h"

#include <algorithm>
#include <cstdio>
#include <cstdlib>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>

#include "gl/context.h"
#include "support/paths.h"
#include "tsp/store/tsp_file.h"
#include "tsp/core/error.h"
#include "tsp/report/image.h"
#include "tsp/report/image_diff.h"
#include "tsp/source/open_source.h"

namespace {

namespace fs = std::filesystem;
using tsptest::run_tspplay;

constexpr const char* kSize = "128x96";
// Same view, TF and metric as `render`'s defaults, so frames should match up to blending noise.
constexpr double kSameFrameDeltaE = 0.5;
constexpr double kDifferentFrameDeltaE = 1.0;

std::string q(const fs::path& p) { return tsptest::quote(p); }

bool window_possible() {
  try {
    auto ctx = tspgl::create_window_context(16, 16, "probe", false);
    return true;
  } catch (const tsp::Error&) {
    return false;
  }
}

// Writes a bash script (the player in the background, xdotool driving it) and runs it; returns
// its exit status.
int run_bash(const fs::path& script, const std::string& text) {
  std::ofstream(script) << text;
  return std::system(("bash " + q(script)).c_str());
}

fs::path make_tsp() {
  fs::path dir = tsptest::temp_dir();
  auto g = run_tspplay("generate shock -o " + q(dir / "s.h5") + " --dims 30,28,26 --steps 4");
  EXPECT_EQ(g.exit_code, 0) << g.err;
  auto b =
      run_tspplay("build " + q(dir / "s.h5") + " --field shock --brick 16 -o " + q(dir / "s.tsp"));
  EXPECT_EQ(b.exit_code, 0) << b.err;
  return dir / "s.tsp";
}

fs::path write_script(const std::string& text) {
  fs::path p = tsptest::temp_dir() / "actions.txt";
  std::ofstream(p) << text;
  return p;
}

// Share of pixels that are not the black background.
double covered(const tsp::Image& im) {
  std::int64_t n = 0;
  for (int y = 0; y < im.height; ++y)
    for (int x = 0; x < im.width; ++x) {
      const std::uint8_t* p = im.at(x, y);
      if (p[0] + p[1] + p[2] > 6) ++n;
    }
  return double(n) / double(im.width * im.height);
}

tsp::Image render_step(const fs::path& tsp, int step, const std::string& tf = "preset:auto") {
  fs::path out = tsptest::temp_dir() / "frames";
  auto r = run_tspplay("render " + q(tsp) + " --tf " + tf + " --steps " + std::to_string(step) +
                       " --size " + kSize + " -o " + q(out));
  EXPECT_EQ(r.exit_code, 0) << r.err;
  char name[32];
  std::snprintf(name, sizeof name, "step_%04d.png", step);
  return tsp::read_png((out / name).string());
}

TEST(Player, ScreenshotShowsTheVolumeAtTheRequestedStep) {
  TSPTEST_REQUIRE(window_possible(), "no display (run under xvfb-run)");
  fs::path tsp = make_tsp(), shot = tsptest::temp_dir() / "shot.png";
  auto r = run_tspplay("play " + q(tsp) + " --step 2 --size " + kSize + " --screenshot " + q(shot));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const tsp::Image im = tsp::read_png(shot.string());
  ASSERT_EQ(im.width, 128);
  ASSERT_EQ(im.height, 96);
  EXPECT_GT(covered(im), 0.05);
  const tsp::DiffStats same = tsp::diff_images(im, render_step(tsp, 2));
  EXPECT_LT(same.mean, kSameFrameDeltaE);
}

TEST(Player, ScriptedScrubShowsEachStepAndATfEditChangesThePicture) {
  TSPTEST_REQUIRE(window_possible(), "no display (run under xvfb-run)");
  fs::path tsp = make_tsp(), dir = tsptest::temp_dir();
  fs::path s0 = dir / "s0.png", s3 = dir / "s3.png", s3f = dir / "s3f.png";
  fs::path script = write_script("# scrub, then edit the TF\nscreenshot " + s0.string() +
                                 "\nstep 3\nwait-frames 1\nscreenshot " + s3.string() +
                                 "\ntf preset:filled\nscreenshot " + s3f.string() + "\nquit\n");
  auto r = run_tspplay("play " + q(tsp) + " --size " + kSize + " --script " + q(script));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const tsp::Image a = tsp::read_png(s0.string()), b = tsp::read_png(s3.string()),
                   c = tsp::read_png(s3f.string());
  EXPECT_LT(tsp::diff_images(a, render_step(tsp, 0)).mean, kSameFrameDeltaE);
  EXPECT_LT(tsp::diff_images(b, render_step(tsp, 3)).mean, kSameFrameDeltaE);
  EXPECT_GT(tsp::diff_images(a, b).mean, kDifferentFrameDeltaE);  // step 3 is not step 0
  EXPECT_GT(tsp::diff_images(b, c).mean, kDifferentFrameDeltaE);  // the TF edit shows
  EXPECT_LT(tsp::diff_images(c, render_step(tsp, 3, "preset:filled")).mean, kSameFrameDeltaE);
}

// Real X key events (xdotool) at two frames a second: five quick taps of → move five steps and
// a tap of Space starts playback — none is lost between frames (the GLFW key queue).
TEST(Player, QuickKeyTapsAreNotLostWhenFramesAreSlow) {
  TSPTEST_REQUIRE(window_possible(), "no display (run under xvfb-run)");
  ASSERT_EQ(std::system("command -v xdotool > /dev/null"), 0)
      << "xdotool missing (scripts/install-deps.sh installs it)";
  fs::path dir = tsptest::temp_dir(), out = dir / "keys.out", tsp = dir / "k.tsp";
  ASSERT_EQ(run_tspplay("generate shock -o " + q(dir / "k.h5") + " --dims 24,20,16 --steps 8")
                .exit_code, 0);
  ASSERT_EQ(run_tspplay("build " + q(dir / "k.h5") + " --field shock -o " + q(tsp)).exit_code, 0);
  fs::path script = write_script("wait-seconds 6\nquit\n");
  const std::string cmd =
      "cd " + q(dir) + " && (" + q(tsptest::tspplay_bin()) + " play " + q(tsp) + " --size " + kSize +
      " --trace --frame-delay-ms 500 --script " + q(script) + " > " + q(out) + " 2>&1 &\n" +
      "w=$(xdotool search --sync --name " + q("tspplay - " + tsp.string()) + " | head -1)\n"
      "sleep 1\n"
      "xdotool key --window \"$w\" --delay 40 Right Right Right Right Right\n"
      "sleep 1.5\n"
      "xdotool key --window \"$w\" space\n"
      "sleep 1\n"
      "xdotool key --window \"$w\" r\n"
      "xdotool key --window \"$w\" s\n"
      "wait)\n";
  ASSERT_EQ(run_bash(dir / "keys.sh", cmd), 0);
  const std::string log = tsptest::read_file(out);
  EXPECT_NE(log.find("trace: step 5\n"), std::string::npos) << log;
  EXPECT_EQ(log.find("trace: playing"), log.rfind("trace: playing")) << log;  // once
  EXPECT_NE(log.find("trace: playing"), std::string::npos) << log;
  EXPECT_LT(log.find("trace: step 5\n"), log.find("trace: playing")) << log;
  EXPECT_NE(log.find("trace: camera reset"), std::string::npos) << log;  // R
  // S saves the view with the export's annotations, named by dataset, field and step, in the
  // working directory (issue 47 item 9).
  int saved = 0;
  for (const auto& e : fs::directory_iterator(dir)) {
    const std::string name = e.path().filename().string();
    if (name.rfind("k_shock_step_", 0) != 0 || e.path().extension() != ".png") continue;
    ++saved;
    const tsp::Image img = tsp::read_png(e.path().string());
    int outline = 0;  // pixels of the outline's colour (the volume is never this grey)
    for (int y = 0; y < img.height; ++y)
      for (int x = 0; x < img.width; ++x)
        outline += img.at(x, y)[0] == 200 && img.at(x, y)[1] == 200 && img.at(x, y)[2] == 200;
    EXPECT_GT(outline, 20) << name;
  }
  EXPECT_EQ(saved, 1) << log;
  EXPECT_NE(log.find("saved k_shock_step_"), std::string::npos) << log;
  // play --help lists the controls from the same table as the F1 overlay.
  const auto help = run_tspplay("play --help");
  for (const char* k : {"space", "reset the camera", "F1 or ?", "TF editor: drag a handle"})
    EXPECT_NE(help.out.find(k), std::string::npos) << k;
}

// Real X mouse events (xdotool) at two frames a second: press on the TF editor's last handle
// (top right of the canvas, opacity 1) and drag it at once down to mid-height and left (press
// and first moves fall into one frame), release: the point moves with the mouse. (800 tall: the
// canvas wholly inside the window below the Settings panel's rows.)
TEST(Player, DraggingATransferFunctionHandleMovesIt) {
  TSPTEST_REQUIRE(window_possible(), "no display (run under xvfb-run)");
  ASSERT_EQ(std::system("command -v xdotool > /dev/null"), 0)
      << "xdotool missing (scripts/install-deps.sh installs it)";
  fs::path tsp = make_tsp(), dir = tsptest::temp_dir();
  const tsp::ValueRange r = tsp::TspFile::open(tsp.string())->tree().value_range();
  const fs::path tf = dir / "ramp.json", out = dir / "drag.out", stats = dir / "drag.json";
  std::ofstream(tf) << "{\"range\": [" << r.lo << ", " << r.hi << "], \"points\": [[" << r.lo
                    << ", 0, 0, 1, 0], [" << r.hi << ", 1, 0, 0, 1]]}";
  fs::path script = write_script("wait-seconds 7\nstats " + stats.string() + "\nquit\n");
  const std::string cmd =
      "(" + q(tsptest::tspplay_bin()) + " play " + q(tsp) + " --size 800x800 --trace " +
      "--frame-delay-ms 500 --tf " + q(tf) + " --script " + q(script) + " > " + q(out) +
      " 2>&1 &\n" +
      "for i in $(seq 50); do grep -q 'tf canvas' " + q(out) + " && break; sleep 0.1; done\n"
      // (the canvas settles once the side panel's scroll bar appears: its last position)
      "sleep 1.5; read x y w h <<< $(grep 'tf canvas' " + q(out) + " | tail -1 | cut -d' ' -f4-7)\n"
      "win=$(xdotool search --sync --name " + q("tspplay - " + tsp.string()) + " | head -1)\n"
      "hx=$((x + w - 2)); hy=$((y + 1))\n"
      "xdotool mousemove --window \"$win\" $hx $hy; sleep 1.2\n"
      "xdotool mousedown 1\n"
      "for k in 1 2 3 4 5 6 7 8; do xdotool mousemove --window \"$win\" $((hx - 5 * k)) "
      "$((hy + h * k / 16)); sleep 0.02; done\n"
      "sleep 1.2; xdotool mouseup 1\n"
      "wait)\n";
  ASSERT_EQ(run_bash(dir / "drag.sh", cmd), 0);
  std::ifstream in(stats);
  const nlohmann::json j = nlohmann::json::parse(in);
  const auto& pts = j["tf_points"];
  ASSERT_EQ(pts.size(), 2u) << tsptest::read_file(out);
  // The last handle followed the mouse: about half opacity, and left of the domain's end.
  EXPECT_NEAR(pts[1][1].get<double>(), 0.5, 0.1) << tsptest::read_file(out);
  EXPECT_LT(pts[1][0].get<double>(), r.hi - 0.05 * (r.hi - r.lo));
  EXPECT_NE(tsptest::read_file(out).find("trace: transfer function edited"), std::string::npos);
}

// play on an HDF5 input: built into the cache folder first (saying so), reused the second time.
TEST(Player, PlaysARawInputThroughTheBuildCache) {
  TSPTEST_REQUIRE(window_possible(), "no display (run under xvfb-run)");
  const fs::path dir = tsptest::temp_dir(), h5 = dir / "raw.h5", cache = dir / "cache";
  ASSERT_EQ(run_tspplay("generate shock -o " + q(h5) + " --dims 20,18,16 --steps 3").exit_code, 0);
  const std::string args = "play " + q(h5) + " --field shock --cache-dir " + q(cache) +
                           " --size " + kSize + " --screenshot ";
  auto r = run_tspplay(args + q(dir / "a.png"));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("building it into"), std::string::npos) << r.out;
  EXPECT_TRUE(fs::exists(dir / "a.png"));
  int built = 0;
  for (const auto& e : fs::directory_iterator(cache / "builds")) built += e.path().extension() == ".tsp";
  EXPECT_EQ(built, 1);
  // The second time reuses the build; File > Open starts beside the input, not in the cache
  // (issue 47 item 6).
  r = run_tspplay("play " + q(h5) + " --field shock --cache-dir " + q(cache) + " --size " + kSize +
                  " --script " + q(write_script("stats " + (dir / "s.json").string() + "\nquit\n")));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("built from it earlier"), std::string::npos) << r.out;
  EXPECT_EQ(nlohmann::json::parse(tsptest::read_file(dir / "s.json"))["open_folder"], dir.string());
  r = run_tspplay(args + q(dir / "b.png"));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_LT(tsp::diff_images(tsp::read_png((dir / "a.png").string()),
                             tsp::read_png((dir / "b.png").string())).mean, kSameFrameDeltaE);
  // --field names a raw input's field, or one of a .tsp file's fields.
  r = run_tspplay("play " + q(make_tsp()) + " --field pressure --screenshot " + q(dir / "c.png"));
  EXPECT_EQ(r.exit_code, 2) << r.err;
  EXPECT_NE(r.err.find("holds the field(s) shock"), std::string::npos) << r.err;
}

// The outline box is drawn over the volume by default (the UI screenshot holds it): a hint of
// where the data is even when the TF shows nothing.
TEST(Player, OutlineShowsInTheUiScreenshot) {
  TSPTEST_REQUIRE(window_possible(), "no display (run under xvfb-run)");
  fs::path tsp = make_tsp(), dir = tsptest::temp_dir(), shot = dir / "ui.png";
  fs::path script = write_script("wait-frames 2\nscreenshot-ui " + shot.string() + "\nquit\n");
  auto r = run_tspplay("play " + q(tsp) + " --size 900x600 --script " + q(script));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const tsp::Image img = tsp::read_png(shot.string());
  int outline = 0;
  for (int y = 0; y < img.height; ++y)
    for (int x = 0; x < img.width; ++x) {
      const std::uint8_t* p = img.at(x, y);
      outline += p[0] == 200 && p[1] == 200 && p[2] == 200;
    }
  EXPECT_GT(outline, 100);
}

// Issue 48: `wait-frames 0` is free. 100,000 such lines cost a frame each (minutes); now they
// run in the frame that reads them, and the stats written after them count almost no frames.
TEST(Player, WaitFramesZeroCostsNoFrame) {
  TSPTEST_REQUIRE(window_possible(), "no display (run under xvfb-run)");
  fs::path tsp = make_tsp(), dir = tsptest::temp_dir(), stats = dir / "s.json";
  std::string text;
  for (int i = 0; i < 100000; ++i) text += "wait-frames 0\n";
  text += "stats " + stats.string() + "\nquit\n";
  auto r = tsptest::run_command("timeout 120 " + q(tsptest::tspplay_bin()) + " play " + q(tsp) +
                                " --size 64x48 --script " + q(write_script(text)));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto j = nlohmann::json::parse(tsptest::read_file(stats));
  EXPECT_LT(j.at("frames").get<int>(), 10) << j.dump();
}

TEST(Player, TracePrintsEachAppliedChange) {
  TSPTEST_REQUIRE(window_possible(), "no display (run under xvfb-run)");
  fs::path tsp = make_tsp(), dir = tsptest::temp_dir(), shot = dir / "trace.png";
  fs::path script = write_script("step 1\nstep 3\ntolerance 0.2 0.1\ntf preset:filled\n"
                                 "metric scalar\nplay\nwait-frames 2\npause\nscreenshot " +
                                 shot.string() + "\nquit\n");
  auto r = run_tspplay("play " + q(tsp) + " --size " + kSize + " --trace --script " + q(script));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  for (const char* line : {"trace: step 1\n", "trace: step 3\n", "trace: tolerances spatial 0.2",
                           "trace: transfer function edited", "trace: metric scalar\n",
                           "trace: playing\n", "trace: paused\n", "saved "})
    EXPECT_NE(r.out.find(line), std::string::npos) << line << " in\n" << r.out;
  EXPECT_LT(r.out.find("trace: step 1\n"), r.out.find("trace: step 3\n"));  // in order
  // Without --trace nothing of it.
  r = run_tspplay("play " + q(tsp) + " --size " + kSize + " --script " + q(script));
  EXPECT_EQ(r.out.find("trace:"), std::string::npos) << r.out;
}

// The quality knobs from a script: the player's frame with compositing, spacing and
// pre-integration set matches `tspplay render` with the same options, and `stats` reports them
// with frame times and fragments.
TEST(Player, ScriptedKnobsMatchRenderAndStatsReportThem) {
  TSPTEST_REQUIRE(window_possible(), "no display (run under xvfb-run)");
  fs::path tsp = make_tsp(), dir = tsptest::temp_dir();
  fs::path shot = dir / "k.png", stats = dir / "stats.json";
  fs::path script = write_script("step 1\ncompositing slices\nspacing 2\npreintegrated on\n"
                                 "wait-frames 3\nscreenshot " + shot.string() + "\nstats " +
                                 stats.string() + "\nquit\n");
  auto r = run_tspplay("play " + q(tsp) + " --size " + kSize + " --script " + q(script));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  fs::path out = dir / "frames";
  auto rr = run_tspplay("render " + q(tsp) + " --steps 1 --size " + kSize +
                        " --compositing slices --spacing 2 --preintegrated on -o " + q(out));
  ASSERT_EQ(rr.exit_code, 0) << rr.err;
  EXPECT_LT(tsp::diff_images(tsp::read_png(shot.string()),
                             tsp::read_png((out / "step_0001.png").string()))
                .mean,
            kSameFrameDeltaE);
  std::ifstream in(stats);
  std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  for (const char* k : {"\"fps\"", "\"fragments\"", "\"compositing\": \"slices\"",
                        "\"spacing\": 2.0", "\"preintegrated\": true", "\"frame_ms\""})
    EXPECT_NE(text.find(k), std::string::npos) << k << " in " << text;
  // The picture on screen drew fragments, even when the last frame reused the whole image.
  EXPECT_GT(nlohmann::json::parse(text)["picture_fragments"].get<long long>(), 0) << text;
}

std::string read_text(const fs::path& p) {
  std::ifstream in(p);
  return std::string((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
}

// A script that orbits at a target no software renderer reaches (stats in dir/moving.json), then
// stops and waits (dir/idle.json) and takes a screenshot, which waits for full quality.
std::string orbit_then_idle_script(const fs::path& dir, const fs::path& shot) {
  std::string text = "tf preset:filled\ntarget-fps 240\nview 30 20\nwait-frames 2\n";
  for (int k = 1; k <= 12; ++k) text += "view " + std::to_string(30 + 5 * k) + " 20\nwait-frames 1\n";
  return text + "stats " + (dir / "moving.json").string() + "\nview 30 20\nwait-seconds 1.5\nstats " +
         (dir / "idle.json").string() + "\nscreenshot " + shot.string() + "\nquit\n";
}

// The LOD cut: while the view keeps changing it holds the target (a coarse cut at a target no
// software renderer reaches), and once input stops it refines to full quality: the screenshot
// (which waits for that) matches the player with LOD off and `tspplay render`.
TEST(Player, LodHoldsTheTargetWhileOrbitingAndRefinesToFullQualityWhenIdle) {
  TSPTEST_REQUIRE(window_possible(), "no display (run under xvfb-run)");
  fs::path tsp = make_tsp(), dir = tsptest::temp_dir();
  const std::string text = orbit_then_idle_script(dir, dir / "lod.png");
  auto r = run_tspplay("play " + q(tsp) + " --size " + kSize + " --script " + q(write_script(text)));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const std::string moving = read_text(dir / "moving.json"), idle = read_text(dir / "idle.json");
  EXPECT_NE(moving.find("\"refining\": false"), std::string::npos) << moving;
  EXPECT_NE(moving.find("\"full_quality\": false"), std::string::npos) << moving;
  EXPECT_NE(idle.find("\"full_quality\": true"), std::string::npos) << idle;
  EXPECT_NE(idle.find("\"render_scale\": 1.0"), std::string::npos) << idle;

  auto off = run_tspplay("play " + q(tsp) + " --size " + kSize + " --script " +
                         q(write_script("tf preset:filled\nlod off\nview 30 20\nscreenshot " +
                                        (dir / "off.png").string() + "\nquit\n")));
  ASSERT_EQ(off.exit_code, 0) << off.err;
  const tsp::Image lod = tsp::read_png((dir / "lod.png").string());
  EXPECT_LT(tsp::diff_images(lod, tsp::read_png((dir / "off.png").string())).mean, kSameFrameDeltaE);
  EXPECT_LT(tsp::diff_images(lod, render_step(tsp, 0, "preset:filled")).mean, kSameFrameDeltaE);
}

// --lod-fallback splats: while orbiting at a target no software renderer reaches, the picture is
// never drawn at a smaller render target (splats instead, when even the root is too slow); idle,
// it refines to the same full-quality picture as with LOD off, with no splat left.
TEST(Player, SplatFallbackKeepsFullSizeAndRefinesToFullQuality) {
  TSPTEST_REQUIRE(window_possible(), "no display (run under xvfb-run)");
  fs::path tsp = make_tsp(), dir = tsptest::temp_dir();
  const std::string text = orbit_then_idle_script(dir, dir / "splat.png");
  auto r = run_tspplay("play " + q(tsp) + " --size " + kSize + " --lod-fallback splats --script " +
                       q(write_script(text)));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const std::string moving = read_text(dir / "moving.json"), idle = read_text(dir / "idle.json");
  EXPECT_NE(moving.find("\"splat_fallback\": true"), std::string::npos) << moving;
  EXPECT_NE(moving.find("\"render_scale\": 1.0"), std::string::npos) << moving;
  EXPECT_NE(idle.find("\"full_quality\": true"), std::string::npos) << idle;
  EXPECT_NE(idle.find("\"splats\": 0"), std::string::npos) << idle;
  EXPECT_LT(tsp::diff_images(tsp::read_png((dir / "splat.png").string()),
                             render_step(tsp, 0, "preset:filled"))
                .mean,
            kSameFrameDeltaE);
  auto bad = run_tspplay("play " + q(tsp) + " --lod-fallback smaller");
  EXPECT_NE(bad.exit_code, 0);
  EXPECT_NE(bad.err.find("--lod-fallback"), std::string::npos) << bad.err;
}

// Errors are found before any window opens, so these run without a display too.
TEST(Player, BadScriptLineIsAnErrorNamingFileAndLine) {
  fs::path tsp = make_tsp();
  fs::path script = write_script("step 1\nzoom fast\n");
  auto r = run_tspplay("play " + q(tsp) + " --script " + q(script));
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_NE(r.err.find("actions.txt:2"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("'fast' is not a number"), std::string::npos) << r.err;
  script = write_script("jump 3\n");
  r = run_tspplay("play " + q(tsp) + " --script " + q(script));
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_NE(r.err.find("unknown action 'jump'"), std::string::npos) << r.err;
}

TEST(Player, StepOutOfRangeAndMissingFilesAreErrors) {
  fs::path tsp = make_tsp();
  auto r = run_tspplay("play " + q(tsp) + " --step 4");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("has steps 0..3"), std::string::npos) << r.err;
  r = run_tspplay("play " + q(tsp) + " --script " + q(tsptest::temp_dir() / "none.txt"));
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_NE(r.err.find("none.txt"), std::string::npos) << r.err;
  r = run_tspplay("play " + q(tsp) + " --size 0x10");
  EXPECT_EQ(r.exit_code, 2);
}

// A tiny upload budget spreads the uploads over frames; the screenshot waits for the complete one.
TEST(Player, ScreenshotWaitsForTheCompleteFrameUnderAnUploadBudget) {
  TSPTEST_REQUIRE(window_possible(), "no display (run under xvfb-run)");
  fs::path tsp = make_tsp(), shot = tsptest::temp_dir() / "shot.png";
  auto r = run_tspplay("play " + q(tsp) + " --step 1 --upload-budget 0.000001 --size " + kSize +
                       " --screenshot " + q(shot));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_LT(tsp::diff_images(tsp::read_png(shot.string()), render_step(tsp, 1)).mean,
            kSameFrameDeltaE);
  EXPECT_EQ(run_tspplay("play " + q(tsp) + " --upload-budget -1").exit_code, 2);
}

// The UI panels are drawn beside the volume (ImGui's OpenGL3 back end works in the window), and
// the volume-only screenshot of the same frame has none of them.
TEST(Player, ScreenshotUiShowsThePanelsOverTheVolume) {
  TSPTEST_REQUIRE(window_possible(), "no display (run under xvfb-run)");
  fs::path tsp = make_tsp(), dir = tsptest::temp_dir();
  fs::path vol = dir / "vol.png", ui = dir / "ui.png";
  fs::path script = write_script("step 1\nscreenshot " + vol.string() + "\nscreenshot-ui " +
                                 ui.string() + "\nquit\n");
  auto r = run_tspplay("play " + q(tsp) + " --size 900x600 --script " + q(script));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const tsp::Image a = tsp::read_png(vol.string()), b = tsp::read_png(ui.string());
  ASSERT_EQ(b.width, 900);
  EXPECT_LT(a.width, b.width);  // the volume's own view, left of the side panel
  EXPECT_GT(covered(b), covered(a) + 0.1);  // the panels cover much of the black background
}


nlohmann::json read_json(const fs::path& p) {
  std::ifstream in(p);
  return nlohmann::json::parse(in);
}

// play takes build's input options (issue 30 item 1): a raw series with its grid size and type
// plays without a separate build, a different grid size is another cached build, and
// --field A,B builds both fields into one file (the first shown, the other in the field menu).
TEST(Player, PlaysARawSeriesAndSeveralFieldsDirectly) {
  TSPTEST_REQUIRE(window_possible(), "no display (run under xvfb-run)");
  const fs::path dir = tsptest::temp_dir(), cache = dir / "cache";
  for (int t = 0; t < 3; ++t) {
    std::vector<float> v(8 * 6 * 4);
    for (std::size_t i = 0; i < v.size(); ++i) v[i] = float((i + std::size_t(t) * 7) % 23) / 22.f;
    char name[32];
    std::snprintf(name, sizeof name, "u_%04d.raw", t);
    std::ofstream(dir / name, std::ios::binary)
        .write(reinterpret_cast<const char*>(v.data()), std::streamsize(v.size() * sizeof(float)));
  }
  const std::string raw = q((dir / "u_%04d.raw").string());
  auto r = run_tspplay("play " + raw + " --raw-dims 8,6,4 --raw-type f32 --cache-dir " + q(cache) +
                       " --size " + kSize + " --screenshot " + q(dir / "raw.png"));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("8x6x4 voxels, 3 steps"), std::string::npos) << r.out;
  EXPECT_TRUE(fs::exists(dir / "raw.png"));
  r = run_tspplay("play " + raw + " --raw-dims 4,6,8 --cache-dir " + q(cache) + " --size " + kSize +
                  " --screenshot " + q(dir / "raw2.png"));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("4x6x8 voxels, 3 steps"), std::string::npos) << r.out;
  int built = 0;
  for (const auto& e : fs::directory_iterator(cache / "builds")) built += e.path().extension() == ".tsp";
  EXPECT_EQ(built, 2) << "the grid size is part of the cached build's key";
  // Without the grid size: the reader's error, exit 1 or 2, nothing played.
  r = run_tspplay("play " + raw + " --cache-dir " + q(cache) + " --size " + kSize);
  EXPECT_NE(r.exit_code, 0);
  EXPECT_NE(r.err.find("raw"), std::string::npos) << r.err;

  const fs::path h5 = tsptest::test_data_dir() / "h5" / "int16.h5";
  // File > Open (script `open`) with build options as play takes them: the raw series' grid;
  // bad options are play's own error, and the file playing stays.
  const std::string raw_path = (dir / "u_%04d.raw").string();
  const fs::path script = write_script(
      "stats " + (dir / "f.json").string() + "\nfield u64\nstats " + (dir / "g.json").string() +
      "\nopen " + raw_path + " --raw-dims 8,6,4 --raw-type f32\nwait-frames 1\nstats " +
      (dir / "h.json").string() + "\nopen " + raw_path + " --raw-dims 8,6\nwait-frames 1\nstats " +
      (dir / "i.json").string() + "\nquit\n");
  r = run_tspplay("play " + q(h5) + " --field plain,u64 --cache-dir " + q(cache) + " --size " +
                  kSize + " --script " + q(script));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const nlohmann::json f = read_json(dir / "f.json"), g = read_json(dir / "g.json");
  EXPECT_EQ(f["fields"], nlohmann::json({"plain", "u64"}));
  EXPECT_EQ(f["field"], "plain");
  EXPECT_EQ(g["field"], "u64");
  const nlohmann::json h = read_json(dir / "h.json"), i = read_json(dir / "i.json");
  EXPECT_NE(h["file"].get<std::string>().find((cache / "builds").string()), std::string::npos) << h;
  EXPECT_EQ(h["steps_ready"].size(), 3u);  // the raw series' 3 steps
  EXPECT_NE(r.err.find("--raw-dims '8,6'"), std::string::npos) << r.err;
  EXPECT_EQ(i["file"], h["file"]);
}

// play MESH --octree-error E builds Leven's adaptive octree into the cache (a version-3 file,
// the same picture as the file `build --octree-error` writes), apart from the uniform build of
// the same mesh; File > Open takes the option too.
TEST(Player, PlaysAMeshThroughAnAdaptiveOctree) {
  TSPTEST_REQUIRE(window_possible(), "no display (run under xvfb-run)");
  const fs::path dir = tsptest::temp_dir(), cache = dir / "cache", built = dir / "built.tsp";
  const std::string mesh =
      q(tsptest::datasets_dir() / "samples/damBreakWithObstacle/damBreakWithObstacle.vtu.series");
  const std::string opts = " --field alpha.water --resolution 32 --octree-error 5%";
  auto r = run_tspplay("play " + mesh + opts + " --cache-dir " + q(cache) + " --size " + kSize +
                       " --screenshot " + q(dir / "a.png"));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("building its adaptive octree into"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("adaptive octree (E = 0.05)"), std::string::npos) << r.out;
  std::vector<fs::path> builds;
  for (const auto& e : fs::directory_iterator(cache / "builds"))
    if (e.path().extension() == ".tsp") builds.push_back(e.path());
  ASSERT_EQ(builds.size(), 1u);
  EXPECT_TRUE(tsp::TspFile::open(builds[0].string())->tree().octree().has_stops());
  ASSERT_EQ(run_tspplay("build " + mesh + opts + " -o " + q(built)).exit_code, 0);
  ASSERT_EQ(run_tspplay("play " + q(built) + " --size " + kSize + " --screenshot " + q(dir / "b.png"))
                .exit_code,
            0);
  EXPECT_LT(tsp::diff_images(tsp::read_png((dir / "a.png").string()),
                             tsp::read_png((dir / "b.png").string())).mean, kSameFrameDeltaE);
  // File > Open: without the option the uniform grid (a build of its own), with it the octree
  // built above, reused.
  const fs::path script = write_script(
      "open " + mesh.substr(1, mesh.size() - 2) + " alpha.water --resolution 32\nwait-frames 1\nstats " +
      (dir / "u.json").string() + "\nopen " + mesh.substr(1, mesh.size() - 2) +
      " alpha.water --resolution 32 --octree-error 5%\nwait-frames 1\nstats " +
      (dir / "o.json").string() + "\nquit\n");
  r = run_tspplay("play " + q(built) + " --cache-dir " + q(cache) + " --size " + kSize +
                  " --script " + q(script));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const std::string u = read_json(dir / "u.json")["file"], o = read_json(dir / "o.json")["file"];
  EXPECT_FALSE(tsp::TspFile::open(u)->tree().octree().has_stops()) << u;
  EXPECT_EQ(o, builds[0].string());
}

// WRF's T, W (15 staggered levels) and QVAPOR played straight from the NetCDF file: built into
// one file, each on its own grid, switching keeps the view (issue 30).
TEST(Player, PlaysSeveralWrfFieldsOnTheirOwnGrids) {
  TSPTEST_REQUIRE(window_possible(), "no display (run under xvfb-run)");
  const fs::path wrf = tsptest::shared_data_dir() / "wrf-katrina" / "ci_test_file.nc";
  if (!fs::exists(wrf)) GTEST_SKIP() << "shared data absent: " << wrf;
  const fs::path dir = tsptest::temp_dir();
  const fs::path script = write_script(
      "stats " + (dir / "t.json").string() + "\nfield W\nstats " + (dir / "w.json").string() +
      "\ntf-range histogram\nstats " + (dir / "h.json").string() + "\ntf-range -1:2\nstats " +
      (dir / "e.json").string() + "\nstep 3\ntf-range step\nstats " + (dir / "s.json").string() +
      "\ntf-range visible\nstats " + (dir / "v.json").string() + "\nquit\n");
  auto r = run_tspplay("play " + q(wrf) + " --field T,W,QVAPOR --cache-dir " + q(dir / "cache") +
                       " --size " + kSize + " --script " + q(script));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const nlohmann::json t = read_json(dir / "t.json"), w = read_json(dir / "w.json");
  EXPECT_EQ(t["fields"], nlohmann::json({"T", "W", "QVAPOR"}));
  // tf-range (the panel's "fit to bulk"): W's map moves inside its data range (W is near 0 but
  // for a few updrafts: the 1st to 99th percentile is far narrower), then to an explicit one.
  const nlohmann::json h = read_json(dir / "h.json"), e = read_json(dir / "e.json");
  const double lo = h["tf_domain"][0], hi = h["tf_domain"][1];
  EXPECT_GT(lo, double(w["tf_domain"][0]));
  EXPECT_LT(hi, double(w["tf_domain"][1]));
  EXPECT_LT(hi - lo, 0.8 * (double(w["tf_domain"][1]) - double(w["tf_domain"][0])));
  EXPECT_EQ(e["tf_domain"], nlohmann::json({-1.0, 2.0}));
  // tf-range step (the panel's "fit to step"): W's values at step 3, read from the NetCDF file.
  tsp::SourceOptions so;
  so.field = "W";
  auto src = tsp::open_source(wrf.string(), so);
  std::vector<float> v(std::size_t(src->dims().count()));
  src->read_step(3, v);
  const auto [vlo, vhi] = std::minmax_element(v.begin(), v.end());
  const nlohmann::json st = read_json(dir / "s.json");
  const double tol = 1e-5 * (*vhi - *vlo);
  EXPECT_NEAR(double(st["tf_domain"][0]), *vlo, tol);
  EXPECT_NEAR(double(st["tf_domain"][1]), *vhi, tol);
  // tf-range visible ("fit to view"): the whole volume is in view, so the step's range again.
  const nlohmann::json vis = read_json(dir / "v.json");
  EXPECT_NEAR(double(vis["tf_domain"][0]), *vlo, tol);
  EXPECT_NEAR(double(vis["tf_domain"][1]), *vhi, tol);
  EXPECT_EQ(t["field"], "T");
  EXPECT_EQ(w["field"], "W");
  EXPECT_EQ(t["steps_ready"].size(), 4u);
  EXPECT_EQ(t["file"], w["file"]);
}


// A window large enough docks the panels beside the volume: the volume-only screenshot is the
// view's size (stats say where it is) and matches `tspplay render` at that size; hidden panels
// (Tab, or `panels off`) give the volume the whole window.
TEST(Player, DockedPanelsLeaveTheVolumeItsOwnViewAndTabHidesThem) {
  TSPTEST_REQUIRE(window_possible(), "no display (run under xvfb-run)");
  fs::path tsp = make_tsp(), dir = tsptest::temp_dir();
  fs::path script = write_script("step 1\nwait-frames 2\nstats " + (dir / "d.json").string() +
                                 "\nscreenshot " + (dir / "d.png").string() + "\nscreenshot-ui " +
                                 (dir / "ui.png").string() + "\npanels off\nwait-frames 2\nstats " +
                                 (dir / "f.json").string() + "\nscreenshot " +
                                 (dir / "f.png").string() + "\nquit\n");
  auto r = run_tspplay("play " + q(tsp) + " --size 900x600 --trace --script " + q(script));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("trace: panels off"), std::string::npos) << r.out;
  const nlohmann::json d = read_json(dir / "d.json"), f = read_json(dir / "f.json");
  ASSERT_TRUE(d["docked"].get<bool>());
  const int vw = d["view"][2], vh = d["view"][3];
  EXPECT_EQ(vw, 900 - 370);  // the side panel's width
  EXPECT_LT(vh, 600);
  const tsp::Image docked = tsp::read_png((dir / "d.png").string());
  ASSERT_EQ(docked.width, vw);
  ASSERT_EQ(docked.height, vh);
  EXPECT_GT(covered(docked), 0.02);
  fs::path out = dir / "frames";
  const std::string size = std::to_string(vw) + "x" + std::to_string(vh);
  auto rr = run_tspplay("render " + q(tsp) + " --steps 1 --size " + size + " -o " + q(out));
  ASSERT_EQ(rr.exit_code, 0) << rr.err;
  EXPECT_LT(tsp::diff_images(docked, tsp::read_png((out / "step_0001.png").string())).mean,
            kSameFrameDeltaE);
  // The UI screenshot is the whole window; left of the side panel it is the volume.
  const tsp::Image ui = tsp::read_png((dir / "ui.png").string());
  EXPECT_EQ(ui.width, 900);
  EXPECT_FALSE(f["docked"].get<bool>());
  EXPECT_EQ(f["view"][2].get<int>(), 900);
  EXPECT_EQ(tsp::read_png((dir / "f.png").string()).height, 600);
}

// File > Open from a script: another .tsp plays at once; a raw input is built into the cache
// folder first (on a thread; the script waits), then plays; the picture is the new file's.
TEST(Player, OpenSwitchesToAnotherFileAndBuildsARawInputFirst) {
  TSPTEST_REQUIRE(window_possible(), "no display (run under xvfb-run)");
  const fs::path dir = tsptest::temp_dir(), other = dir / "v.tsp", h5 = dir / "raw.h5";
  ASSERT_EQ(run_tspplay("generate vortex -o " + q(dir / "v.h5") + " --dims 24,22,20 --steps 3")
                .exit_code, 0);
  ASSERT_EQ(run_tspplay("build " + q(dir / "v.h5") + " -o " + q(other)).exit_code, 0);
  ASSERT_EQ(run_tspplay("generate shock -o " + q(h5) + " --dims 20,18,16 --steps 5").exit_code, 0);
  fs::path tsp = make_tsp();
  fs::path script = write_script(
      "open " + other.string() + "\nwait-frames 2\nstats " + (dir / "a.json").string() +
      "\nscreenshot " + (dir / "a.png").string() + "\nopen " + h5.string() +
      " shock\nwait-frames 2\nstats " + (dir / "b.json").string() + "\nopen " +
      (dir / "missing.h5").string() + "\nwait-frames 1\nstats " + (dir / "c.json").string() +
      "\nquit\n");
  auto r = run_tspplay("play " + q(tsp) + " --size " + kSize + " --cache-dir " +
                       q(dir / "cache") + " --script " + q(script));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(read_json(dir / "a.json")["file"], other.string());
  EXPECT_LT(tsp::diff_images(tsp::read_png((dir / "a.png").string()), render_step(other, 0)).mean,
            kSameFrameDeltaE);
  const std::string built = read_json(dir / "b.json")["file"];
  EXPECT_NE(built.find((dir / "cache" / "builds").string()), std::string::npos) << built;
  EXPECT_EQ(read_json(dir / "b.json")["steps_ready"].size(), 5u);  // the raw input's 5 steps
  EXPECT_NE(r.out.find("building it into"), std::string::npos) << r.out;
  // A missing input is reported (stderr and the status line) and the player keeps playing.
  EXPECT_NE(r.err.find("missing.h5"), std::string::npos) << r.err;
  EXPECT_EQ(read_json(dir / "c.json")["file"], built);
}

// File > Open (script `open`) never aborts (issue 28 item 7): a missing path, a device, a FIFO,
// a bad .vtu and an HDF5 file refused for its external storage are each reported on stderr (and
// in the trace) while the old file keeps playing; a valid input that needs building is built
// and played; `open X` right before `quit` still reports X's failure.
TEST(Player, OpenNeverAbortsAndReportsEveryFailure) {
  TSPTEST_REQUIRE(window_possible(), "no display (run under xvfb-run)");
  const fs::path dir = tsptest::temp_dir(), tsp = make_tsp(), h5 = dir / "raw.h5";
  ASSERT_EQ(run_tspplay("generate vortex -o " + q(h5) + " --dims 20,18,16 --steps 3").exit_code, 0);
  std::ofstream(dir / "bad.vtu") << "<VTKFile type=\"UnstructuredGrid\"><Unstructured";
  ASSERT_EQ(mkfifo((dir / "pipe.h5").c_str(), 0600), 0);
  // HDF5 files whose only dataset is stored in another file (/etc/passwd; 64 floats of ours):
  // refused without --allow-external.
  auto write_external = [](const fs::path& path, const std::string& external) {
    const hsize_t dims[3] = {4, 4, 4};
    hid_t f = H5Fcreate(path.c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, H5P_DEFAULT);
    hid_t space = H5Screate_simple(3, dims, nullptr);
    hid_t dcpl = H5Pcreate(H5P_DATASET_CREATE);
    H5Pset_external(dcpl, external.c_str(), 0, 256);
    H5Dclose(H5Dcreate2(f, "d", H5T_IEEE_F32LE, space, H5P_DEFAULT, dcpl, H5P_DEFAULT));
    H5Pclose(dcpl);
    H5Sclose(space);
    H5Fclose(f);
  };
  write_external(dir / "ext.h5", "/etc/passwd");
  {
    std::vector<float> v(64);
    for (int i = 0; i < 64; ++i) v[std::size_t(i)] = float(i);
    std::ofstream(dir / "raw.bin", std::ios::binary)
        .write(reinterpret_cast<const char*>(v.data()), 256);
  }
  write_external(dir / "ext_ok.h5", (dir / "raw.bin").string());
  const std::vector<std::string> bad = {(dir / "missing.h5").string(), "/dev/zero",
                                        (dir / "pipe.h5").string(), (dir / "bad.vtu").string(),
                                        (dir / "ext.h5").string()};
  std::string text;
  for (std::size_t i = 0; i < bad.size(); ++i)
    text += "open " + bad[i] + "\nwait-frames 1\nstats " + (dir / ("bad" + std::to_string(i) + ".json")).string() + "\n";
  text += "open " + h5.string() + "\nwait-frames 1\nstats " + (dir / "built.json").string() +
          "\nopen " + (dir / "last.h5").string() + "\nquit\n";
  auto r = run_tspplay("play " + q(tsp) + " --size " + kSize + " --trace --cache-dir " +
                       q(dir / "cache") + " --script " + q(write_script(text)));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  for (std::size_t i = 0; i < bad.size(); ++i) {
    EXPECT_NE(r.err.find("open " + bad[i] + ": "), std::string::npos) << bad[i] << "\n" << r.err;
    EXPECT_NE(r.out.find("trace: open " + bad[i] + " failed: "), std::string::npos) << r.out;
    EXPECT_EQ(read_json(dir / ("bad" + std::to_string(i) + ".json"))["file"], tsp.string());
  }
  EXPECT_NE(r.err.find("--allow-external"), std::string::npos) << r.err;
  const std::string built = read_json(dir / "built.json")["file"];
  EXPECT_NE(built.find((dir / "cache" / "builds").string()), std::string::npos) << built;
  EXPECT_EQ(read_json(dir / "built.json")["steps_ready"].size(), 3u);  // the input's 3 steps
  EXPECT_NE(r.err.find("open " + (dir / "last.h5").string() + ": "), std::string::npos) << r.err;
  // With --allow-external, File > Open builds such a file.
  r = run_tspplay("play " + q(tsp) + " --size " + kSize + " --allow-external --cache-dir " +
                  q(dir / "cache") + " --script " +
                  q(write_script("open " + (dir / "ext_ok.h5").string() + "\nwait-frames 1\nstats " +
                                 (dir / "ext.json").string() + "\nquit\n")));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const std::string ext_built = read_json(dir / "ext.json")["file"];
  EXPECT_NE(ext_built.find("ext_ok.h5-"), std::string::npos) << ext_built << r.err;
}

// The record button's script action: the volume as played, with its annotations, in real time
// (25 frames a second of wall time), decoded by ffprobe; an unknown extension is refused.
TEST(Player, RecordWritesAMovieOfWhatIsPlayed) {
  TSPTEST_REQUIRE(window_possible(), "no display (run under xvfb-run)");
  ASSERT_EQ(std::system("command -v ffprobe > /dev/null"), 0)
      << "ffmpeg missing (scripts/install-deps.sh installs it)";
  fs::path tsp = make_tsp(), dir = tsptest::temp_dir(), movie = dir / "rec.mp4";
  // (The first 'play' tunes playback and the script waits for it: tuned before recording.)
  fs::path script = write_script("wait-frames 2\nplay\npause\nrecord " + movie.string() +
                                 "\nplay\nwait-seconds 1.2\nrecord stop\nstats " +
                                 (dir / "s.json").string() + "\nquit\n");
  auto r = run_tspplay("play " + q(tsp) + " --size " + kSize + " --script " + q(script));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("recorded " + movie.string()), std::string::npos) << r.out << r.err;
  const std::string cmd = "ffprobe -v error -count_frames -select_streams v:0 -show_entries "
                          "stream=width,height,nb_read_frames -of csv=p=0 " + q(movie);
  std::string probe;
  if (FILE* p = popen(cmd.c_str(), "r")) {
    char buf[256];
    while (fgets(buf, sizeof buf, p)) probe += buf;
    pclose(p);
  }
  int w = 0, h = 0, frames = 0;
  ASSERT_EQ(std::sscanf(probe.c_str(), "%d,%d,%d", &w, &h, &frames), 3) << probe;
  EXPECT_EQ(w, 128);
  EXPECT_EQ(h, 96);
  EXPECT_GE(frames, 25);  // 1.2 s of wall time at 25 frames a second, give or take a frame
  EXPECT_LE(frames, 45);
  EXPECT_FALSE(read_json(dir / "s.json")["recording"].get<bool>());
  EXPECT_EQ(run_tspplay("play " + q(tsp) + " --script " +
                        q(write_script("record " + (dir / "m.avi").string() + "\n")))
                .exit_code,
            1);
}

// Playback shows each step in turn by default even when frames are slower than the speed asks
// (here 100 ms a frame at 60 steps a second); with "skip steps" (every-step off) steps are
// dropped to keep time. Unless chosen, the speed suits the series: 12 steps in about 4 s.
TEST(Player, PlaybackShowsEveryStepInOrderUnlessAskedToSkip) {
  TSPTEST_REQUIRE(window_possible(), "no display (run under xvfb-run)");
  const fs::path dir = tsptest::temp_dir(), tsp = dir / "e.tsp";
  ASSERT_EQ(run_tspplay("generate shock -o " + q(dir / "e.h5") + " --dims 16,14,12 --steps 12")
                .exit_code, 0);
  ASSERT_EQ(run_tspplay("build " + q(dir / "e.h5") + " -o " + q(tsp)).exit_code, 0);
  auto steps_seen = [&](const std::string& every) {
    auto r = run_tspplay("play " + q(tsp) + " --size " + kSize +
                         " --trace --frame-delay-ms 100 --script " +
                         q(write_script((every.empty() ? "" : "every-step " + every + "\n") +
                                        "loop off\nspeed 60\nplay\nwait-seconds 2\nquit\n")));
    EXPECT_EQ(r.exit_code, 0) << r.err;
    std::vector<int> seen;
    for (std::size_t p = r.out.find("trace: step "); p != std::string::npos;
         p = r.out.find("trace: step ", p + 1))
      seen.push_back(std::stoi(r.out.substr(p + 12)));
    return seen;
  };
  const std::vector<int> every = steps_seen("");  // the default
  ASSERT_GE(every.size(), 6u);
  for (std::size_t i = 1; i < every.size(); ++i) EXPECT_EQ(every[i], every[i - 1] + 1) << i;
  auto r = run_tspplay("play " + q(tsp) + " --size " + kSize + " --script " +
                       q(write_script("stats " + (dir / "s.json").string() +
                                      "\ntf preset:filled\nstats " + (dir / "t.json").string() +
                                      "\nquit\n")));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_DOUBLE_EQ(read_json(dir / "s.json")["playback"]["speed"].get<double>(), 3.0);
  // The preset combo names the map in use (issue 47 item 3): the default, then the one chosen.
  EXPECT_EQ(read_json(dir / "s.json")["tf"], "auto");
  EXPECT_EQ(read_json(dir / "t.json")["tf"], "filled");
  const std::vector<int> real_time = steps_seen("off");
  bool skipped = false;
  for (std::size_t i = 1; i < real_time.size(); ++i) skipped |= real_time[i] > real_time[i - 1] + 1;
  EXPECT_TRUE(skipped);
}

// A playback tuning is kept on disk per file, map, settings and view: the second window on the
// same data plays at its tuned rung at once, probing nothing (issue 47 item 1).
TEST(Player, ATuningIsKeptOnDiskAndReusedByTheNextWindow) {
  TSPTEST_REQUIRE(window_possible(), "no display (run under xvfb-run)");
  const fs::path tsp = make_tsp(), dir = tsptest::temp_dir(), cache = dir / "cache";
  auto run = [&](const std::string& stats) {
    return run_tspplay("play " + q(tsp) + " --size " + kSize + " --cache-dir " + q(cache) +
                       " --script " +
                       q(write_script("quality 1\nstats " + (dir / stats).string() + "\nquit\n")));
  };
  auto a = run("a.json");
  ASSERT_EQ(a.exit_code, 0) << a.err;
  const nlohmann::json ta = read_json(dir / "a.json")["tuning"];
  EXPECT_FALSE(ta["from_cache"].get<bool>()) << ta;
  EXPECT_GT(ta["seconds"].get<double>(), 0) << ta;
  ASSERT_TRUE(fs::is_regular_file(ta["cache_file"].get<std::string>())) << ta;
  EXPECT_EQ(fs::path(ta["cache_file"].get<std::string>()).parent_path(), cache / "tuning");
  auto b = run("b.json");
  ASSERT_EQ(b.exit_code, 0) << b.err;
  const nlohmann::json jb = read_json(dir / "b.json");
  EXPECT_TRUE(jb["tuning"]["from_cache"].get<bool>()) << jb["tuning"];
  EXPECT_EQ(jb["tuning"]["frames_while_tuning"].get<int>(), 0);
  EXPECT_EQ(jb["playback"]["ladder"], read_json(dir / "a.json")["playback"]["ladder"]);
}

// The timeline's marks: after one pass over every step with prefetch, each step's bricks are in
// memory (ready 1); a fresh player has only the shown step ready.
TEST(Player, TimelineMarksTheStepsWhoseBricksAreInMemory) {
  TSPTEST_REQUIRE(window_possible(), "no display (run under xvfb-run)");
  fs::path tsp = make_tsp(), dir = tsptest::temp_dir();
  std::string text = "lod off\ntf preset:filled\nwait-frames 3\nstats " + (dir / "a.json").string() + "\n";
  for (int k = 0; k < 4; ++k) text += "step " + std::to_string(k) + "\nwait-frames 1\n";
  text += "step 0\nwait-frames 3\nstats " + (dir / "b.json").string() + "\nquit\n";
  auto r = run_tspplay("play " + q(tsp) + " --size " + kSize + " --script " + q(write_script(text)));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const nlohmann::json a = read_json(dir / "a.json")["steps_ready"];
  const nlohmann::json b = read_json(dir / "b.json")["steps_ready"];
  ASSERT_EQ(a.size(), 4u);
  EXPECT_EQ(a[0].get<double>(), 1.0);
  EXPECT_LT(a[3].get<double>(), 1.0);
  for (int k = 0; k < 4; ++k) EXPECT_EQ(b[std::size_t(k)].get<double>(), 1.0) << k;
}

// Physical proportions in the player: a file with tall voxels (and --scale) shows as render
// shows it.
TEST(Player, ShowsThePhysicalProportionsAsRenderDoes) {
  TSPTEST_REQUIRE(window_possible(), "no display (run under xvfb-run)");
  const fs::path dir = tsptest::temp_dir(), tall = dir / "tall.tsp";
  ASSERT_EQ(run_tspplay("generate shock -o " + q(dir / "t.h5") + " --dims 30,28,26 --steps 2")
                .exit_code, 0);
  ASSERT_EQ(run_tspplay("build " + q(dir / "t.h5") + " --spacing 1,1,2 -o " + q(tall)).exit_code,
            0);
  for (const std::string scale : {"1,1,1", "2,1,1"}) {
    const fs::path shot = dir / ("p" + scale + ".png"), out = dir / ("r" + scale);
    auto p = run_tspplay("play " + q(tall) + " --step 1 --scale " + scale + " --size " + kSize +
                         " --screenshot " + q(shot));
    ASSERT_EQ(p.exit_code, 0) << p.err;
    auto r = run_tspplay("render " + q(tall) + " --steps 1 --scale " + scale + " --size " + kSize +
                         " -o " + q(out));
    ASSERT_EQ(r.exit_code, 0) << r.err;
    EXPECT_LT(tsp::diff_images(tsp::read_png(shot.string()),
                               tsp::read_png((out / "step_0001.png").string())).mean,
              kSameFrameDeltaE)
        << scale;
  }
}

// Several fields: `field NAME` shows the other field (as `render --field` does), each with its
// own TF; switching back finds the first field's textures still resident; stats say which field
// and how long the switch took to its first complete frame.
TEST(Player, SwitchesFieldsLiveEachWithItsOwnTransferFunction) {
  TSPTEST_REQUIRE(window_possible(), "no display (run under xvfb-run)");
  const fs::path dir = tsptest::temp_dir(), h5 = dir / "two.h5", tsp = dir / "two.tsp";
  ASSERT_EQ(run_tspplay("generate shock -o " + q(dir / "a.h5") + " --dims 24,20,18 --steps 3")
                .exit_code, 0);
  // Two fields in one HDF5 file: the shock and the vortex datasets copied side by side.
  ASSERT_EQ(run_tspplay("generate vortex -o " + q(dir / "b.h5") + " --dims 24,20,18 --steps 3")
                .exit_code, 0);
  ASSERT_EQ(std::system(("h5copy -i " + q(dir / "a.h5") + " -o " + q(h5) + " -s shock -d shock && " +
                         "h5copy -i " + q(dir / "b.h5") + " -o " + q(h5) + " -s vortex -d vortex")
                            .c_str()),
            0);
  auto b = run_tspplay("build " + q(h5) + " --field shock,vortex -o " + q(tsp));
  ASSERT_EQ(b.exit_code, 0) << b.err;
  const std::string script =
      "step 1\ntf preset:filled\nwait-frames 2\nscreenshot " + (dir / "s.png").string() +
      "\nfield vortex\nscreenshot " + (dir / "v.png").string() + "\nstats " +
      (dir / "v.json").string() + "\nfield shock\nscreenshot " + (dir / "s2.png").string() +
      "\nstats " + (dir / "s.json").string() + "\nquit\n";
  auto r = run_tspplay("play " + q(tsp) + " --size " + kSize + " --trace --script " +
                       q(write_script(script)));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("trace: field vortex"), std::string::npos) << r.out;
  auto render = [&](const std::string& field, const std::string& tf) {
    const fs::path out = dir / ("r" + field);
    auto rr = run_tspplay("render " + q(tsp) + " --field " + field + " --tf " + tf +
                          " --steps 1 --size " + kSize + " -o " + q(out));
    EXPECT_EQ(rr.exit_code, 0) << rr.err;
    return tsp::read_png((out / "step_0001.png").string());
  };
  // The shock with the filled TF set before the switch; the vortex with the start TF (the
  // default map, from the vortex's own histogram).
  EXPECT_LT(tsp::diff_images(tsp::read_png((dir / "s.png").string()), render("shock", "preset:filled")).mean,
            kSameFrameDeltaE);
  EXPECT_LT(tsp::diff_images(tsp::read_png((dir / "v.png").string()), render("vortex", "preset:auto")).mean,
            kSameFrameDeltaE);
  EXPECT_LT(tsp::diff_images(tsp::read_png((dir / "s2.png").string()),
                             tsp::read_png((dir / "s.png").string())).mean,
            kSameFrameDeltaE);  // back: its TF kept
  const nlohmann::json v = read_json(dir / "v.json"), s = read_json(dir / "s.json");
  EXPECT_EQ(v["field"], "vortex");
  EXPECT_EQ(s["field"], "shock");
  EXPECT_EQ(v["fields"].size(), 2u);
  EXPECT_GE(v["field_switch_ms"].get<double>(), 0.0);
  // No such field: a script error naming the line and the fields the file holds (issue 28: it
  // used to be reported in the window and the script went on, exit 0).
  auto bad = run_tspplay("play " + q(tsp) + " --size " + kSize + " --script " +
                         q(write_script("field density\nquit\n")));
  EXPECT_EQ(bad.exit_code, 2) << bad.err;
  EXPECT_NE(bad.err.find("actions.txt:1: field 'density'"), std::string::npos) << bad.err;
  EXPECT_NE(bad.err.find("holds the field(s) shock, vortex"), std::string::npos) << bad.err;
}

// Clip probes from a script: the picture is render's with the same --probe options, the removed
// voxels are counted as clipped, and moving a probe changes the picture (and counts as input).
TEST(Player, ProbesClipAsRenderDoesAndMoveFromTheScript) {
  TSPTEST_REQUIRE(window_possible(), "no display (run under xvfb-run)");
  fs::path tsp = make_tsp(), dir = tsptest::temp_dir();
  const std::string probe = "sphere:8,8,7,7", plane = "plane:0,0,1,9";  // in the first brick
  // (LOD off: with the cut, a uniform node across the surface stays whole and is clipped per
  // sample — the same picture, but no voxel counted as clipped.)
  fs::path script = write_script("lod off\ntf preset:filled\nprobe " + probe + "\nprobe " + plane +
                                 "\nscreenshot " + (dir / "a.png").string() + "\nstats " +
                                 (dir / "a.json").string() + "\nprobe-move 2 0 0 -4\nscreenshot " +
                                 (dir / "b.png").string() + "\nprobe-clear\nscreenshot " +
                                 (dir / "c.png").string() + "\nquit\n");
  auto r = run_tspplay("play " + q(tsp) + " --size " + kSize + " --script " + q(script));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  auto rr = run_tspplay("render " + q(tsp) + " --tf preset:filled --steps 0 --size " + kSize +
                        " --probe " + probe + " --probe " + plane + " --probe-surface on -o " +
                        q(dir / "r"));
  ASSERT_EQ(rr.exit_code, 0) << rr.err;
  const tsp::Image a = tsp::read_png((dir / "a.png").string());
  EXPECT_LT(tsp::diff_images(a, tsp::read_png((dir / "r" / "step_0000.png").string())).mean,
            kSameFrameDeltaE);
  const nlohmann::json j = read_json(dir / "a.json");
  EXPECT_EQ(j["probes"].size(), 2u);
  EXPECT_GT(j["classes"]["clipped"].get<double>(), 10.0);
  EXPECT_GT(tsp::diff_images(a, tsp::read_png((dir / "b.png").string())).mean,
            kDifferentFrameDeltaE);  // the plane moved down
  EXPECT_LT(tsp::diff_images(tsp::read_png((dir / "c.png").string()), render_step(tsp, 0, "preset:filled")).mean,
            kSameFrameDeltaE);  // no probe left
  // A bad probe is a script error naming the line.
  auto bad = run_tspplay("play " + q(tsp) + " --script " + q(write_script("probe sphere:1,2\n")));
  EXPECT_EQ(bad.exit_code, 1);
  EXPECT_NE(bad.err.find("actions.txt:1"), std::string::npos) << bad.err;
}

// One settings table for both commands: the same options on `play` (paused, full quality) and
// `render` give the same picture — the defaults (lit), slices at spacing 2 with a temporal
// tolerance (unlit), a sphere probe with its surface, rays with pre-integration (unlit).
TEST(Player, PausedPlayerDrawsWhatRenderDrawsForTheSameSettings) {
  TSPTEST_REQUIRE(window_possible(), "no display (run under xvfb-run)");
  const fs::path tsp = make_tsp(), dir = tsptest::temp_dir();
  const std::vector<std::string> configurations = {
      "", "--shade off --compositing slices --spacing 2 --temporal-tol 0.02",
      "--probe sphere:15,14,13,9 --probe-surface on",
      "--compositing rays --preintegrated on --shade off",
      "--lod-filter fov:2"};  // LaMar's filter: the same cut in the window as in render
  for (std::size_t k = 0; k < configurations.size(); ++k) {
    const std::string& o = configurations[k];
    const fs::path shot = dir / ("p" + std::to_string(k) + ".png"), out = dir / ("r" + std::to_string(k));
    auto p = run_tspplay("play " + q(tsp) + " --step 2 --size " + kSize + " " + o +
                         " --screenshot " + q(shot));
    ASSERT_EQ(p.exit_code, 0) << o << ": " << p.err;
    auto r = run_tspplay("render " + q(tsp) + " --steps 2 --size " + kSize + " " + o + " -o " +
                         q(out));
    ASSERT_EQ(r.exit_code, 0) << o << ": " << r.err;
    const tsp::Image played = tsp::read_png(shot.string());
    EXPECT_GT(covered(played), 0.02) << o;
    EXPECT_LT(tsp::diff_images(played, tsp::read_png((out / "step_0002.png").string())).mean,
              kSameFrameDeltaE)
        << o;
  }
}

// The mesh's boundary (--surface boundary, issue 31 item 2) in the window is render's picture
// of it, and the script's `surface off` (the settings table's action) takes it away.
TEST(Player, TheMeshBoundaryDrawsAsRenderDrawsItAndTheScriptTurnsItOff) {
  TSPTEST_REQUIRE(window_possible(), "no display (run under xvfb-run)");
  const fs::path dir = tsptest::temp_dir();
  const std::string mesh = (tsptest::test_data_dir() / "vtu" / "binary_%d.vtu").string();
  ASSERT_EQ(run_tspplay("build " + q(mesh) + " --field f --resolution 64 -o " + q(dir / "m.tsp")).exit_code, 0);
  const std::string surface = " --surface boundary --surface-mesh " + q(mesh) + " --surface-field c";
  const fs::path on = dir / "on.png", off = dir / "off.png";
  auto p = run_tspplay("play " + q(dir / "m.tsp") + " --size " + kSize + surface + " --script " +
                       q(write_script("screenshot " + on.string() + "\nsurface off\nscreenshot " +
                                      off.string() + "\nquit\n")));
  ASSERT_EQ(p.exit_code, 0) << p.err;
  auto r = run_tspplay("render " + q(dir / "m.tsp") + " --steps 0 --size " + kSize + surface + " -o " +
                       q(dir / "r"));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const tsp::Image played = tsp::read_png(on.string());
  EXPECT_GT(covered(played), 0.005);
  EXPECT_LT(tsp::diff_images(played, tsp::read_png((dir / "r" / "step_0000.png").string())).mean,
            kSameFrameDeltaE);
  EXPECT_GT(tsp::diff_images(played, tsp::read_png(off.string())).mean, kDifferentFrameDeltaE);
  // Turned on in a window started without --surface (issue 47 item 3): on a .tsp the control
  // says what it needs and goes back off; on the mesh played itself it reads that mesh.
  const auto stats_after = [&](const std::string& input, const std::string& extra,
                               const std::string& name) {
    auto s = run_tspplay("play " + q(input) + extra + " --size " + kSize + " --cache-dir " +
                         q(dir / "cache") + " --script " +
                         q(write_script("surface boundary\nstats " + (dir / name).string() +
                                        "\nquit\n")));
    EXPECT_EQ(s.exit_code, 0) << s.err;
    return read_json(dir / name);
  };
  const nlohmann::json t = stats_after((dir / "m.tsp").string(), "", "t.json");
  EXPECT_EQ(t["surface"], "off");
  EXPECT_EQ(t["surface_mesh"], "");
  EXPECT_NE(t["status"].get<std::string>().find("needs the mesh the file was built from"),
            std::string::npos) << t["status"];
  const nlohmann::json m = stats_after(mesh, " --field f", "m.json");
  EXPECT_EQ(m["surface"], "boundary");
  EXPECT_EQ(m["surface_mesh"], mesh);
}

// Renders on demand: a window with nothing to change sleeps in its event wait (a generous bound
// on its CPU share while idle, measured from /proc, not timed), and a key wakes it at once.
TEST(Player, IdleWindowSleepsAndAKeyWakesIt) {
  TSPTEST_REQUIRE(window_possible(), "no display (run under xvfb-run)");
  ASSERT_EQ(std::system("command -v xdotool > /dev/null"), 0)
      << "xdotool missing (scripts/install-deps.sh installs it)";
  const fs::path tsp = make_tsp(), dir = tsptest::temp_dir(), out = dir / "idle.out";
  // The script ends without quit: the window stays open, idle.
  const fs::path script = write_script("step 1\nwait-frames 3\nstats " + (dir / "ready.json").string() + "\n");
  const std::string cmd =
      q(tsptest::tspplay_bin()) + " play " + q(tsp) + " --size 320x240 --trace --script " +
      q(script) + " > " + q(out) + " 2>&1 &\n" +
      "p=$!\n"
      "w=$(xdotool search --sync --name " + q("tspplay - " + tsp.string()) + " | head -1)\n"
      "for i in $(seq 300); do [ -e " + q(dir / "ready.json") + " ] && break; sleep 0.1; done\n"
      "sleep 1\n"  // the LOD refinement and the last UI frames settle
      "a=$(awk '{print $14+$15}' /proc/$p/stat)\n"
      "sleep 3\n"
      "b=$(awk '{print $14+$15}' /proc/$p/stat)\n"
      "echo \"idle_ticks $((b - a)) $(getconf CLK_TCK)\" > " + q(dir / "cpu.txt") + "\n"
      "xdotool key --window \"$w\" Right\n"
      "for i in $(seq 100); do grep -q 'trace: step 2' " + q(out) + " && break; sleep 0.1; done\n"
      "kill $p; wait $p; true\n";
  ASSERT_EQ(run_bash(dir / "idle.sh", cmd), 0);
  std::ifstream cpu(dir / "cpu.txt");
  std::string word;
  long ticks = -1, per_second = 0;
  cpu >> word >> ticks >> per_second;
  ASSERT_EQ(word, "idle_ticks");
  ASSERT_GT(per_second, 0);
  // The target is under 5 % of a core; the bound leaves room for a loaded test machine. A window
  // that drew continuously used 90-140 %.
  EXPECT_LT(double(ticks) / double(per_second) / 3.0, 0.25) << ticks << " ticks in 3 s";
  EXPECT_NE(tsptest::read_file(out).find("trace: step 2"), std::string::npos)
      << tsptest::read_file(out);
}

// Playing at a quality target draws the tuned rung that fits the step period within the target
// — never the time-only LOD cut, which a 240 fps target makes coarse: a frame shown while
// playing is within the target of `render`'s full-quality picture of its step. When no rung
// fits the period (each frame held 100 ms, at 24 steps/s), "keep quality" plays the fastest rung
// within the target and "keep rate" the fastest rung of all; quality 0 brings the LOD cut back.
TEST(Player, PlayingAtAQualityTargetDrawsTheTunedRungWithinTheTarget) {
  TSPTEST_REQUIRE(window_possible(), "no display (run under xvfb-run)");
  const fs::path tsp = make_tsp(), dir = tsptest::temp_dir();
  auto run = [&](const std::string& head, const std::string& tag, const std::string& extra) {
    const fs::path script = write_script(
        "target-fps 240\n" + head + "\nplay\nwait-seconds 1\nscreenshot " +
        (dir / (tag + ".png")).string() + "\nstats " + (dir / (tag + ".json")).string() +
        "\nquit\n");
    auto r = run_tspplay("play " + q(tsp) + " --size " + kSize + " --speed 24 " + extra +
                         " --script " + q(script));
    EXPECT_EQ(r.exit_code, 0) << r.err;
    return r.out;
  };
  const std::string out = run("quality 2\nplayback quality", "q", "");
  const nlohmann::json j = read_json(dir / "q.json");
  const nlohmann::json& p = j["playback"];
  EXPECT_EQ(p["keep"], "quality");
  ASSERT_TRUE(p["tuned"].get<bool>()) << p;
  ASSERT_TRUE(p.contains("rung")) << p;
  EXPECT_TRUE(p["rung"]["within_quality"].get<bool>()) << p;
  EXPECT_LE(p["rung"]["predicted_de"].get<double>(), tspgl::kPlaybackQualityMargin * 2) << p;
  EXPECT_EQ(p["ladder"].size(), tspgl::playback_rungs().size());
  EXPECT_EQ(p["ladder"][0]["mean_de"].get<double>(), 0) << "full quality against itself";
  EXPECT_GT(p["steps_shown_per_s"].get<double>(), 0);
  // The step the screenshot shows, from "saved PATH (step N)".
  const std::size_t at = out.find("q.png (step ");
  ASSERT_NE(at, std::string::npos) << out;
  const int shown = std::stoi(out.substr(at + std::string("q.png (step ").size()));
  EXPECT_LT(tsp::diff_images(tsp::read_png((dir / "q.png").string()), render_step(tsp, shown)).mean,
            2.0);

  // Nothing fits 41.7 ms when every frame takes 100 ms more.
  run("quality 2\nplayback quality", "slow_q", "--frame-delay-ms 100");
  const nlohmann::json sq = read_json(dir / "slow_q.json")["playback"];
  ASSERT_TRUE(sq.contains("rung")) << sq;
  EXPECT_FALSE(sq["rung"]["fits_rate"].get<bool>()) << sq;
  EXPECT_TRUE(sq["rung"]["within_quality"].get<bool>()) << sq;
  run("quality 0.01\nplayback rate", "slow_r", "--frame-delay-ms 100");
  const nlohmann::json sr = read_json(dir / "slow_r.json")["playback"];
  ASSERT_TRUE(sr.contains("rung")) << sr;
  EXPECT_FALSE(sr["rung"]["fits_rate"].get<bool>()) << sr;
  double fastest = 1e300;
  std::string fastest_name;
  for (const auto& r : sr["ladder"])
    if (r["probe_ms"].get<double>() < fastest) {
      fastest = r["probe_ms"].get<double>();
      fastest_name = r["name"];
    }
  EXPECT_EQ(sr["rung"]["name"], fastest_name) << "keeping the rate: the fastest rung" << sr;

  run("quality 0", "off", "");
  const nlohmann::json off = read_json(dir / "off.json");
  EXPECT_FALSE(off["playback"].contains("rung"));
  EXPECT_GT(off["lod"]["cut_size"].get<int>(), 0) << "no target: the LOD cut holds the rate";
}

// A step shown while playing is complete, however small the upload budget (which spreads uploads
// over frames while interacting): late rather than with holes of bricks left for later frames.
TEST(Player, StepsShownWhilePlayingHaveNoHolesUnderAnUploadBudget) {
  TSPTEST_REQUIRE(window_possible(), "no display (run under xvfb-run)");
  const fs::path tsp = make_tsp(), dir = tsptest::temp_dir();
  // (No quality target: every frame at full quality, the picture `render` draws.)
  const fs::path script = write_script("lod off\nquality 0\ncache off\nplay\nwait-seconds 0.5\nstats " +
                                       (dir / "p.json").string() + "\nscreenshot " +
                                       (dir / "p.png").string() + "\nquit\n");
  auto r = run_tspplay("play " + q(tsp) + " --size " + kSize +
                       " --upload-budget 0.001 --speed 24 --script " + q(script));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const std::size_t at = r.out.find("p.png (step ");
  ASSERT_NE(at, std::string::npos) << r.out;
  const int shown = std::stoi(r.out.substr(at + std::string("p.png (step ").size()));
  EXPECT_LT(tsp::diff_images(tsp::read_png((dir / "p.png").string()), render_step(tsp, shown)).mean,
            kSameFrameDeltaE);
  // The frame drawn just before (playing, every texture uploaded anew): nothing left for later.
  EXPECT_EQ(read_json(dir / "p.json")["deferred_textures"].get<long long>(), 0);
}

}  // namespace

// The quality slider (script `quality`) tunes playback on an offscreen canvas of the window's own
// context, a slice of each frame: the window draws while it tunes, afterwards it keeps drawing, a
// real Tab hides the panels (it used to exit with "the 16-bit render target ... is not
// supported" when a calibration left another context current) and the paused picture is
// `render`'s full-quality one.
TEST(Player, QualitySliderKeepsTheWindowDrawingAndTabWorking) {
  TSPTEST_REQUIRE(window_possible(), "no display (run under xvfb-run)");
  ASSERT_EQ(std::system("command -v xdotool > /dev/null"), 0)
      << "xdotool missing (scripts/install-deps.sh installs it)";
  const fs::path tsp = make_tsp(), dir = tsptest::temp_dir(), out = dir / "q.out";
  const fs::path script = write_script(
      "step 1\nquality 2\nstats " + (dir / "q0.json").string() + "\nwait-frames 2\nstats " +
      (dir / "q.json").string() + "\nscreenshot " +
      (dir / "q.png").string() + "\nwait-seconds 3\nstats " + (dir / "f.json").string() +
      "\nscreenshot " + (dir / "f.png").string() + "\nquit\n");
  // Tab goes in once the first screenshot is written (the tuning is over by then).
  const std::string cmd =
      q(tsptest::tspplay_bin()) + " play " +
      q(tsp) + " --size " + kSize + " --trace --script " + q(script) + " > " + q(out) + " 2>&1 &\n" +
      "p=$!\n"
      "w=$(xdotool search --sync --name " + q("tspplay - " + tsp.string()) + " | head -1)\n"
      "for i in $(seq 1500); do [ -e " + q(dir / "q.png") + " ] && break; sleep 0.2; done\n"
      "xdotool key --window \"$w\" Tab\n"
      "wait $p\n";
  ASSERT_EQ(run_bash(dir / "quality.sh", cmd), 0) << tsptest::read_file(out);
  const std::string log = tsptest::read_file(out);
  EXPECT_NE(log.find("trace: panels off"), std::string::npos) << log;
  const nlohmann::json q0 = read_json(dir / "q0.json"), qj = read_json(dir / "q.json"),
                       fj = read_json(dir / "f.json");
  // The action after `quality` waited for the tuning to end, which ran a slice of each frame:
  // the window kept drawing meanwhile.
  EXPECT_FALSE(q0["tuning"]["running"].get<bool>());
  EXPECT_TRUE(q0["playback"]["tuned"].get<bool>());
  EXPECT_GE(q0["tuning"]["frames_while_tuning"].get<int>(), 1) << q0["tuning"];
  EXPECT_EQ(q0["playback"]["quality"].get<double>(), 2);
  EXPECT_GT(fj["frames_drawn"].get<int>(), qj["frames_drawn"].get<int>());
  EXPECT_FALSE(fj["docked"].get<bool>());
  // After Tab the volume fills the window and shows the data as `render` draws it.
  const tsp::Image full = tsp::read_png((dir / "f.png").string());
  ASSERT_EQ(full.width, 128);
  ASSERT_EQ(full.height, 96);
  EXPECT_GT(covered(full), 0.02);
  EXPECT_LT(tsp::diff_images(full, render_step(tsp, 1)).mean, kSameFrameDeltaE);
}
