// The annotations over the volume after issue 47's fresh-eye walk: the mesh surface's colours
// get their own legend bar ("surface: FIELD") in the window, in S's PNGs, movies and render
// --annotate; the caption sits on an opaque box that a stretched outline never crosses.
// (Helpers: support/player_run.h.)
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cstdlib>
#include <filesystem>
#include <string>

#include "support/paths.h"
#include "support/player_run.h"
#include "tsp/metric/tf_io.h"
#include "tsp/report/image.h"

namespace {

namespace fs = std::filesystem;
using tsptest::q;
using tsptest::run_tspplay;
using namespace tsptest::player;

// An end of a preset's map as the legends write it (8 bits, rounded).
std::array<int, 3> map_end(const std::string& preset, bool high) {
  const tsp::TransferFunction tf =
      tsp::transfer_function_from_arg(preset, {0, 1}, tsp::kDefaultTfEntries);
  const tsp::Rgba c = tf.lookup(high ? 1.0 : 0.0);
  const auto u8 = [](float x) { return int(std::clamp(x, 0.f, 1.f) * 255 + 0.5f); };
  return {u8(c.r), u8(c.g), u8(c.b)};
}

// Pixels of img in columns [x0, x1) within 1 of rgb on every channel.
int count_near(const tsp::Image& img, int x0, int x1, const std::array<int, 3>& rgb) {
  int n = 0;
  for (int y = 0; y < img.height; ++y)
    for (int x = std::max(0, x0); x < std::min(img.width, x1); ++x) {
      const std::uint8_t* p = img.at(x, y);
      n += std::abs(p[0] - rgb[0]) <= 1 && std::abs(p[1] - rgb[1]) <= 1 &&
           std::abs(p[2] - rgb[2]) <= 1;
    }
  return n;
}

// With --surface boundary the legend shows the surface's map too (cool-to-warm by default: a
// row of its high end and one of its low end in the legend's column), in render --annotate's
// frames and in the window (panels off: the view fills it); without the surface, neither.
TEST(Player, TheSurfaceHasItsOwnLegendBarInTheWindowAndInExports) {
  TSPTEST_REQUIRE(window_possible(), "no display (run under xvfb-run)");
  const fs::path dir = tsptest::temp_dir();
  const std::string mesh = (tsptest::test_data_dir() / "vtu" / "binary_%d.vtu").string();
  ASSERT_EQ(run_tspplay("build " + q(mesh) + " --field f --resolution 32 -o " + q(dir / "m.tsp"))
                .exit_code,
            0);
  const std::string surface = " --surface boundary --surface-mesh " + q(mesh) + " --surface-field c";
  const std::string common = " --tf preset:grayscale --size " + std::string(kSize);
  const std::array<int, 3> hi = map_end("preset:cool-to-warm", true),
                           lo = map_end("preset:cool-to-warm", false);
  // render --annotate (the same drawing as S and movies): the legend's column is x 54..70.
  for (const bool with : {true, false}) {
    const fs::path out = dir / (with ? "rs" : "rn");
    auto r = run_tspplay("render " + q(dir / "m.tsp") + " --steps 0 --annotate" + common +
                         (with ? surface : "") + " -o " + q(out));
    ASSERT_EQ(r.exit_code, 0) << r.err;
    const tsp::Image img = tsp::read_png((out / "step_0000.png").string());
    if (with) {
      EXPECT_GE(count_near(img, 54, 70, hi), 16);
      EXPECT_GE(count_near(img, 54, 70, lo), 16);
    } else {
      EXPECT_LT(count_near(img, 54, 70, hi), 4);
      EXPECT_LT(count_near(img, 54, 70, lo), 4);
    }
  }
  // The window's overlay: the legend's column is x 48..62.
  for (const bool with : {true, false}) {
    const fs::path shot = dir / (with ? "ws.png" : "wn.png");
    auto p = run_tspplay("play " + q(dir / "m.tsp") + common + (with ? surface : "") +
                         " --script " +
                         q(write_script("panels off\nwait-frames 2\nscreenshot-ui " + shot.string() +
                                        "\nquit\n")));
    ASSERT_EQ(p.exit_code, 0) << p.err;
    const tsp::Image img = tsp::read_png(shot.string());
    if (with) {
      EXPECT_GE(count_near(img, 48, 62, hi), 14);
      EXPECT_GE(count_near(img, 48, 62, lo), 14);
    } else {
      EXPECT_LT(count_near(img, 48, 62, hi), 4);
      EXPECT_LT(count_near(img, 48, 62, lo), 4);
    }
  }
}

// Pixels of img within [x0, x1) × [y0, y1) exactly rgb.
int count_exact(const tsp::Image& img, int x0, int y0, int x1, int y1,
                const unsigned char rgb[3]) {
  int n = 0;
  for (int y = std::max(0, y0); y < std::min(img.height, y1); ++y)
    for (int x = std::max(0, x0); x < std::min(img.width, x1); ++x) {
      const std::uint8_t* p = img.at(x, y);
      n += p[0] == rgb[0] && p[1] == rgb[1] && p[2] == rgb[2];
    }
  return n;
}

// After a z stretch (×30: the tall outline reaches the top of the frame) the
// caption ("step 0", "z x 30") sits on its opaque box: no outline pixel in its rectangle, in
// render --annotate's frame (top left, scale-2 font) and in the window (top left too).
TEST(Player, TheCaptionSitsOnAnOpaqueBoxTheStretchedOutlineNeverCrosses) {
  TSPTEST_REQUIRE(window_possible(), "no display (run under xvfb-run)");
  const fs::path tsp = make_tsp(), dir = tsptest::temp_dir();
  const unsigned char outline[3] = {200, 200, 200}, box[3] = {24, 24, 40};
  auto r = run_tspplay("render " + q(tsp) + " --steps 0 --annotate --scale 1,1,30 --size " +
                       kSize + " -o " + q(dir / "r"));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const tsp::Image img = tsp::read_png((dir / "r" / "step_0000.png").string());
  // The caption's box: 4 pixels around "step 0" (6 glyphs × 12) and "z x 30" under it.
  EXPECT_EQ(count_exact(img, 4, 4, 84, 44, outline), 0);
  EXPECT_GT(count_exact(img, 4, 4, 84, 44, box), 1000);
  const fs::path shot = dir / "w.png";
  auto p = run_tspplay("play " + q(tsp) + " --size " + kSize + " --scale 1,1,30 --script " +
                       q(write_script("panels off\nzoom 1.5\nwait-frames 2\nscreenshot-ui " +
                                      shot.string() + "\nquit\n")));
  ASSERT_EQ(p.exit_code, 0) << p.err;
  const tsp::Image win = tsp::read_png(shot.string());
  // The window's caption starts 8 pixels in from the view's top-left corner, as the export's.
  EXPECT_EQ(count_exact(win, 6, 6, 44, 30, outline), 0);
  EXPECT_GT(count_exact(win, 6, 6, 44, 30, box), 200);
  // One place (issue 47 walk 6: the window's sat top centre, from x 21): the boxes' left
  // edges before the text, 8 pixels in, in both.
  EXPECT_EQ(count_exact(img, 4, 4, 8, 20, box), 4 * 16);
  EXPECT_EQ(count_exact(win, 5, 5, 8, 20, box), 3 * 15);
}

}  // namespace
