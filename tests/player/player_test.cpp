// tspplay play under the current display (xvfb-run in scripts/test.sh), driven by --screenshot and
// --script: the volume shows, scrubbing to step k shows step k (against `tspplay render` of the
// same view and size), a TF edit changes the picture, keys and drags, the LOD cut while orbiting;
// bad scripts and steps are clear errors. (Inputs: player_inputs_test.cpp; playback and what it
// draws against render: player_playback_test.cpp; shared helpers: support/player_run.h.)
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

#include "support/player_run.h"

namespace {

namespace fs = std::filesystem;
using tsptest::run_tspplay;
using namespace tsptest::player;

using tsptest::q;

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
  TSPTEST_REQUIRE_X_EVENTS();
  fs::path dir = tsptest::temp_dir(), out = dir / "keys.out", tsp = dir / "k.tsp";
  ASSERT_EQ(run_tspplay("generate shock -o " + q(dir / "k.h5") + " --dims 24,20,16 --steps 8")
                .exit_code, 0);
  ASSERT_EQ(run_tspplay("build " + q(dir / "k.h5") + " --field shock -o " + q(tsp)).exit_code, 0);
  // (Each step waits on the player's --trace lines; the script quits once the last keys are
  // taken: the `keys` handshake.)
  fs::path script = write_script(taken(dir, "keys") + "quit\n");
  const std::string cmd =
      log_waits(out) + handshakes(dir) + "cd " + q(dir) + " && (" + q(tsptest::tspplay_bin()) +
      " play " + q(tsp) + " --size " + kSize + " --trace --frame-delay-ms 500 --script " +
      q(script) + " > " + q(out) + " 2>&1 &\n" +
      "w=$(xdotool search --sync --name " + q("tspplay - " + tsp.string()) + " | head -1)\n"
      "until_log 'trace: step 0'\n"
      "xdotool key --window \"$w\" --delay 40 Right Right Right Right Right\n"
      "until_log 'trace: step 5'\n"
      "xdotool key --window \"$w\" space\n"
      "until_log 'trace: playing'\n"
      "xdotool key --window \"$w\" r\n"
      "xdotool key --window \"$w\" s\n"
      "handshake keys\n"
      "wait)\n";
  ASSERT_EQ(run_bash(dir / "keys.sh", cmd), 0);
  const std::string log = tsptest::read_file(out);
  EXPECT_NE(log.find("trace: step 5\n"), std::string::npos) << log;
  EXPECT_EQ(log.find("trace: playing"), log.rfind("trace: playing")) << log;  // once
  EXPECT_NE(log.find("trace: playing"), std::string::npos) << log;
  EXPECT_LT(log.find("trace: step 5\n"), log.find("trace: playing")) << log;
  EXPECT_NE(log.find("trace: camera reset"), std::string::npos) << log;  // R
  // S saves the view with the export's annotations, named by dataset, field and step, beside
  // the data (here the working directory too; issue 47 item 9), the status naming the full path.
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
  EXPECT_NE(log.find("saved " + (dir / "k_shock_step_").string()), std::string::npos) << log;
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
  TSPTEST_REQUIRE_X_EVENTS();
  fs::path tsp = make_tsp(), dir = tsptest::temp_dir();
  const tsp::ValueRange r = tsp::TspFile::open(tsp.string())->tree().value_range();
  const fs::path tf = dir / "ramp.json", out = dir / "drag.out", stats = dir / "drag.json";
  std::ofstream(tf) << "{\"range\": [" << r.lo << ", " << r.hi << "], \"points\": [[" << r.lo
                    << ", 0, 0, 1, 0], [" << r.hi << ", 1, 0, 0, 1]]}";
  // Each stage of the drag is a handshake: the script goes on once the window has taken every
  // event sent before it (the stats come after the release, however slow the frames).
  // (The canvas settles once the side panel's scroll bar appears, in the first frames: its last
  // traced place once the script signals `ready`.)
  fs::path script = write_script("wait-frames 4\nsignal " + (dir / "ready").string() + "\n" +
                                 taken(dir, "hover") + taken(dir, "drag") + taken(dir, "release") +
                                 "stats " + stats.string() + "\nquit\n");
  const std::string cmd =
      log_waits(out) + handshakes(dir) + "(" + q(tsptest::tspplay_bin()) + " play " + q(tsp) +
      " --size 800x800 --trace " + "--frame-delay-ms 500 --tf " + q(tf) + " --script " +
      q(script) + " > " + q(out) + " 2>&1 &\n" +
      "until_file " + q(dir / "ready") + "\n"
      "read x y w h <<< $(grep 'tf canvas' " + q(out) + " | tail -1 | cut -d' ' -f4-7)\n"
      "win=$(xdotool search --sync --name " + q("tspplay - " + tsp.string()) + " | head -1)\n"
      "hx=$((x + w - 2)); hy=$((y + 1))\n"
      "xdotool mousemove --window \"$win\" $hx $hy; handshake hover\n"
      "xdotool mousedown 1\n"
      "for k in 1 2 3 4 5 6 7 8; do xdotool mousemove --window \"$win\" $((hx - 5 * k)) "
      "$((hy + h * k / 16)); sleep 0.02; done\n"
      "handshake drag; xdotool mouseup 1; handshake release\n"
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

// The script's handshakes: `signal` writes its file when the script gets there (after the
// stats before it), a `wait-file` whose file is there goes on, and one whose file never comes
// fails the run after its timeout, naming the line — the script does not go on to quit.
TEST(Player, WaitFileFailsNamingTheLineWhenTheFileNeverComes) {
  TSPTEST_REQUIRE(window_possible(), "no display (run under xvfb-run)");
  const fs::path tsp = make_tsp(), dir = tsptest::temp_dir();
  const fs::path script = write_script("stats " + (dir / "s.json").string() + "\nsignal " +
                                       (dir / "ready").string() + "\nwait-file " +
                                       (dir / "ready").string() + "\nwait-file " +
                                       (dir / "never").string() + " 0.5\nquit\n");
  auto r = run_tspplay("play " + q(tsp) + " --size " + kSize + " --script " + q(script));
  EXPECT_EQ(r.exit_code, 1) << r.out;
  EXPECT_NE(r.err.find(script.string() + ":4: wait-file " + (dir / "never").string() +
                       ": not there after 0.5 s"),
            std::string::npos)
      << r.err;
  EXPECT_EQ(read_text(dir / "ready").rfind("frame ", 0), 0u);
  EXPECT_TRUE(fs::exists(dir / "s.json"));
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

}  // namespace
