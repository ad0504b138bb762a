#include "support/player_run.h"

#include <gtest/gtest.h>

#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <iterator>

#include "gl/context.h"
#include "support/paths.h"
#include "tsp/core/error.h"

namespace tsptest::player {

namespace fs = std::filesystem;

namespace {

// Each test's players get a cache folder of their own (TSPPLAY_CACHE_DIR, inherited by every
// tspplay the test starts): a session, tuning or calibration one test leaves is never restored by
// another test on the same small .tsp (tests that name --cache-dir use theirs).
class FreshCacheFolder : public ::testing::EmptyTestEventListener {
  void OnTestStart(const ::testing::TestInfo&) override {
    const fs::path cache = tsptest::temp_dir() / "tspplay-cache";
    ::setenv("TSPPLAY_CACHE_DIR", cache.c_str(), 1);
  }
};

[[maybe_unused]] const bool kFreshCacheFolders = [] {
  ::testing::UnitTest::GetInstance()->listeners().Append(new FreshCacheFolder);
  return true;
}();

}  // namespace

bool window_possible() {
  try {
    auto ctx = tspgl::create_window_context(16, 16, "probe", false);
    return true;
  } catch (const tsp::Error&) {
    return false;
  }
}

int run_bash(const fs::path& script, const std::string& text) {
  std::ofstream(script) << text;
  // A display of its own: no window of a test running beside it takes the focus (keys sent to
  // a window without it arrive as synthetic events, which GLFW drops after a real press of the
  // same key) or covers this window where the mouse goes.
  fs::path own = script;
  own += ".display.sh";
  std::ofstream(own)
      << "d=$(mktemp)\n"
         "Xvfb -displayfd 3 -screen 0 1280x1024x24 -nolisten tcp 3> \"$d\" 2> /dev/null &\n"
         "xvfb=$!\n"
         "for i in $(seq 600); do [ -s \"$d\" ] && break; sleep 0.05; done\n"
         "[ -s \"$d\" ] || { echo 'no X server of its own (Xvfb)'; kill $xvfb; exit 1; }\n"
         "DISPLAY=:$(head -1 \"$d\") bash " + q(script) + "\nrc=$?\n"
         "rm -f \"$d\"; kill $xvfb; wait $xvfb 2> /dev/null; exit $rc\n";
  return std::system(("bash " + q(own)).c_str());
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

double covered(const tsp::Image& im) {
  std::int64_t n = 0;
  for (int y = 0; y < im.height; ++y)
    for (int x = 0; x < im.width; ++x) {
      const std::uint8_t* p = im.at(x, y);
      if (p[0] + p[1] + p[2] > 6) ++n;
    }
  return double(n) / double(im.width * im.height);
}

tsp::Image render_step(const fs::path& tsp, int step, const std::string& tf) {
  fs::path out = tsptest::temp_dir() / "frames";
  auto r = run_tspplay("render " + q(tsp) + " --tf " + tf + " --steps " + std::to_string(step) +
                       " --size " + kSize + " -o " + q(out));
  EXPECT_EQ(r.exit_code, 0) << r.err;
  char name[32];
  std::snprintf(name, sizeof name, "step_%04d.png", step);
  return tsp::read_png((out / name).string());
}

std::string read_text(const fs::path& p) {
  std::ifstream in(p);
  return std::string((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
}

std::string log_waits(const fs::path& log) {
  const std::string file = quote(log);
  return "give_up() { echo \"$1\"; kill $! 2> /dev/null; exit 1; }\n"
         "until_log() { for i in $(seq 600); do grep -q -- \"$1\" " + file +
         " && return 0; sleep 0.1; done; give_up \"never saw $1\"; }\n"
         "until_n() { for i in $(seq 600); do [ \"$(grep -c -- \"$1\" " + file +
         ")\" -ge \"$2\" ] && return 0; sleep 0.1; done; give_up \"never saw $1 $2 times\"; }\n"
         "until_file() { for i in $(seq 600); do [ -e \"$1\" ] && return 0; sleep 0.1; done; "
         "give_up \"never saw the file $1\"; }\n"
         // Ctrl+Q to window $w, then the player's exit status. xdotool sends through XTEST to
         // the focused window; once Ctrl+Q has closed it, Q's release fails and Q would stay
         // down on the display, repeating into the next test's window: released here.
         "quit_player() { xdotool key --window \"$w\" ctrl+q; wait; local rc=$?; "
         "xdotool keyup ctrl q; return $rc; }\n";
}

std::string select_all_in_open_dialog() {
  return "xdotool key --window \"$w\" ctrl+o\n"
         "until_log 'trace: open path field active'\n"
         "xdotool type --window \"$w\" abc\n"
         "until_log 'abc$'\n"
         "xdotool key --delay 40 --window \"$w\" ctrl+a\n"
         "until_log 'trace: select all'\n"
         "xdotool type --window \"$w\" x\n"
         "until_log 'trace: open path x$'\n";
}

void expect_select_all_replaced(const std::string& log) {
  const std::size_t typed = log.find("abc\n");
  ASSERT_NE(typed, std::string::npos) << log;
  EXPECT_NE(log.find("trace: open path x\n", typed), std::string::npos) << log;
  EXPECT_EQ(log.find("abcx"), std::string::npos) << log;
}

nlohmann::json read_json(const fs::path& p) {
  std::ifstream in(p);
  return nlohmann::json::parse(in);
}

std::vector<std::string> labels_with(const nlohmann::json& stats, const std::string& text) {
  std::vector<std::string> found;
  for (const nlohmann::json& it : stats["ui_items"])
    if (it["label"].get<std::string>().find(text) != std::string::npos)
      found.push_back(it["label"]);
  return found;
}

std::string orbit_then_idle_script(const fs::path& dir, const fs::path& shot) {
  std::string text = "tf preset:filled\ntarget-fps 240\nview 30 20\nwait-frames 2\n";
  for (int k = 1; k <= 12; ++k) text += "view " + std::to_string(30 + 5 * k) + " 20\nwait-frames 1\n";
  return text + "stats " + (dir / "moving.json").string() + "\nview 30 20\nscreenshot " +
         shot.string() + "\nstats " + (dir / "idle.json").string() + "\nquit\n";
}

std::string handshakes(const fs::path& dir) {
  return "handshake() { touch " + quote(dir) + "/\"$1\".sent; until_file " + quote(dir) +
         "/\"$1\".taken; }\n";
}

std::string until_ctrl_q(const fs::path& dir) {
  return "wait-file " + (dir / "ctrl-q-never-came").string() + " 300\n";
}

std::string taken(const fs::path& dir, const std::string& name) {
  return "wait-file " + (dir / (name + ".sent")).string() + "\nsignal " +
         (dir / (name + ".taken")).string() + "\n";
}

}  // namespace tsptest::player
