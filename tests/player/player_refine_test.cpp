// No popping (issue 47 item 2): every frame the window shows after a pause, and while it refines
// after a change, is within the quality target of `tspplay render` at full quality, and full
// quality comes back within a bounded number of frames; the recorder writes only such frames.
// Frames are captured as drawn with the script's `capture` (frames.jsonl says what each drew);
// counted in frames, never timed. (Helpers: support/player_run.h.)
#include <gtest/gtest.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <string>
#include <tuple>
#include <vector>

#include <nlohmann/json.hpp>

#include "support/paths.h"
#include "support/player_run.h"
#include "tsp/report/image.h"
#include "tsp/report/image_diff.h"

namespace {

namespace fs = std::filesystem;
using tsptest::q;
using tsptest::run_tspplay;
using namespace tsptest::player;

// The player's quality target in these tests (mean ΔE), and the most frames a refinement of
// the 128×96 view may take (4 bands of 32 rows, one frame at least each, and slack).
constexpr double kTarget = 1.0;
constexpr int kMaxRefineFrames = 12;

// The frames a `capture` folder holds, in order.
std::vector<nlohmann::json> captured(const fs::path& dir) {
  std::vector<nlohmann::json> frames;
  std::ifstream in(dir / "frames.jsonl");
  for (std::string line; std::getline(in, line);) frames.push_back(nlohmann::json::parse(line));
  return frames;
}

// `tspplay render` at full quality of (step, azimuth, elevation), once each.
class References {
 public:
  explicit References(fs::path tsp) : tsp_(std::move(tsp)) {}
  const tsp::Image& at(int step, double az, double el) {
    const auto key = std::make_tuple(step, az, el);
    auto it = images_.find(key);
    if (it != images_.end()) return it->second;
    const fs::path out = tsptest::temp_dir() / "ref";
    char view[64];
    std::snprintf(view, sizeof view, "%g,%g", az, el);
    auto r = run_tspplay("render " + q(tsp_) + " --steps " + std::to_string(step) + " --size " +
                         kSize + " --view " + view + " -o " + q(out));
    EXPECT_EQ(r.exit_code, 0) << r.err;
    char name[32];
    std::snprintf(name, sizeof name, "step_%04d.png", step);
    return images_.emplace(key, tsp::read_png((out / name).string())).first->second;
  }

 private:
  fs::path tsp_;
  std::map<std::tuple<int, double, double>, tsp::Image> images_;
};

// Mean ΔE of a captured frame against render at full quality of its step and view.
double frame_de(References& refs, const fs::path& dir, const nlohmann::json& f) {
  const tsp::Image& ref = refs.at(f["step"].get<int>(), f["view"][0].get<double>(),
                                  f["view"][1].get<double>());
  return tsp::diff_images(tsp::read_png((dir / f["file"].get<std::string>()).string()), ref).mean;
}

// Played, then paused: the frames that follow are bands at full resolution over the last
// playing frame (the tuned rung, within the target) — never a coarser LOD cut — so each is
// within the target of the full-quality picture, and the last is that picture. After a change
// of view the frames drawn once it settles (0.25 s without a change; the script's screenshot
// waits for full quality) are within the target too.
TEST(Player, FramesAfterAPauseAndWhileRefiningStayWithinTheQualityTarget) {
  TSPTEST_REQUIRE(window_possible(), "no display (run under xvfb-run)");
  const fs::path tsp = make_tsp(), dir = tsptest::temp_dir();
  const fs::path paused = dir / "paused", moved = dir / "moved";
  const std::string script = "quality " + std::to_string(kTarget) + "\nplay\nwait-frames 3\n" +
                             "pause\ncapture " + paused.string() + "\nwait-frames " +
                             std::to_string(kMaxRefineFrames + 4) + "\ncapture " +
                             moved.string() + "\nview 55 25\nscreenshot " +
                             (dir / "settled.png").string() + "\ncapture off\nstats " +
                             (dir / "s.json").string() + "\nquit\n";
  auto r = run_tspplay("play " + q(tsp) + " --size " + kSize + " --cache-dir " + q(dir / "cache") +
                       " --script " + q(write_script(script)));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  References refs(tsp);

  const std::vector<nlohmann::json> after_pause = captured(paused);
  ASSERT_GE(after_pause.size(), std::size_t(kMaxRefineFrames)) << r.out;
  int to_full = -1;
  for (std::size_t k = 0; k < after_pause.size(); ++k) {
    const nlohmann::json& f = after_pause[k];
    EXPECT_NE(f["stage"], "interacting") << "a coarse cut after a pause: " << f;
    EXPECT_TRUE(f["within_target"].get<bool>()) << f;
    EXPECT_LE(frame_de(refs, paused, f), kTarget) << "frame " << k << " after the pause: " << f;
    if (to_full < 0 && f["stage"] == "full") to_full = int(k);
  }
  ASSERT_GE(to_full, 0) << "never full quality";
  EXPECT_LE(to_full, kMaxRefineFrames);
  EXPECT_LT(frame_de(refs, paused, after_pause.back()), kSameFrameDeltaE);
  EXPECT_EQ(after_pause.front()["base"], "the last playing frame") << after_pause.front();

  const std::vector<nlohmann::json> after_move = captured(moved);
  int refining = 0;
  for (const nlohmann::json& f : after_move) {
    if (f["stage"] == "interacting") {
      EXPECT_EQ(refining, 0) << "a coarse cut after the refinement began: " << f;
      continue;
    }
    ++refining;
    EXPECT_LE(frame_de(refs, moved, f), kTarget) << f;
  }
  EXPECT_GT(refining, 0) << "the view never settled";
  EXPECT_EQ(after_move.back()["stage"], "full") << after_move.back();
  EXPECT_LT(frame_de(refs, moved, after_move.back()), kSameFrameDeltaE);
  // The status line says what the last frame drew.
  const nlohmann::json stats = read_json(dir / "s.json");
  EXPECT_EQ(stats["lod"]["picture"]["line"].get<std::string>().rfind("full quality (last frame", 0),
            0u)
      << stats["lod"];
}

// Recording across play, pause and a change of view: a frame goes into the movie only when it
// is within the target (the LOD cut's frames while the view changes are not: the last good
// frame is held instead), and each that does is within the target of `render`.
TEST(Player, TheRecorderWritesOnlyFramesWithinTheQualityTarget) {
  TSPTEST_REQUIRE(window_possible(), "no display (run under xvfb-run)");
  TSPTEST_REQUIRE(std::system("command -v ffmpeg > /dev/null") == 0, "no ffmpeg");
  const fs::path tsp = make_tsp(), dir = tsptest::temp_dir(), frames = dir / "frames";
  std::string script = "quality " + std::to_string(kTarget) + "\nplay\npause\nwait-frames " +
                       std::to_string(kMaxRefineFrames) + "\nrecord " + (dir / "m.mp4").string() +
                       "\ncapture " + frames.string() + "\nplay\nwait-frames 4\npause\n" +
                       "wait-frames " + std::to_string(kMaxRefineFrames) + "\n";
  for (int k = 1; k <= 4; ++k) script += "view " + std::to_string(30 + 6 * k) + " 20\nwait-frames 1\n";
  // (The screenshot waits for the view to settle and refine to full quality.)
  script += "screenshot " + (dir / "settled.png").string() + "\nrecord stop\ncapture off\nquit\n";
  auto r = run_tspplay("play " + q(tsp) + " --size " + kSize + " --cache-dir " + q(dir / "cache") +
                       " --script " + q(write_script(script)));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("recorded " + (dir / "m.mp4").string()), std::string::npos) << r.out;
  References refs(tsp);
  int recorded = 0, held = 0;
  for (const nlohmann::json& f : captured(frames)) {
    if (f["stage"] == "interacting") {
      EXPECT_FALSE(f["recorded"].get<bool>()) << "a coarse cut in the movie: " << f;
      ++held;
      continue;
    }
    if (!f["recorded"].get<bool>()) continue;
    ++recorded;
    EXPECT_LE(frame_de(refs, frames, f), kTarget) << f;
  }
  EXPECT_GT(recorded, 0);
  EXPECT_GT(held, 0) << "the view change drew no LOD cut: nothing was held";
}

}  // namespace
