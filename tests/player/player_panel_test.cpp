// The side panel as a user meets it (issue 47 items 5 and 7), under the current display: at
// 1280×800 and 1920×1080 no label is wider than its item nor any item wider than its window
// (ImGui's item rectangles, written by `stats`), the transfer function comes first and the
// expert knobs are collapsed, a status message does not move the controls, the tolerance
// sliders say what they buy, the histogram of a skewed field has bars, and real X input
// (xdotool) in slow frames loses neither a drag's end nor a keystroke.
#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <string>

#include <nlohmann/json.hpp>

#include "support/paths.h"
#include "support/player_run.h"

namespace {

namespace fs = std::filesystem;
using namespace tsptest::player;
using tsptest::q;
using tsptest::run_tspplay;

fs::path script_in(const fs::path& dir, const std::string& name, const std::string& text) {
  std::ofstream(dir / name) << text;
  return dir / name;
}

std::map<std::string, nlohmann::json> items_by_label(const nlohmann::json& stats) {
  std::map<std::string, nlohmann::json> m;
  for (const auto& it : stats["ui_items"]) m.emplace(it["label"].get<std::string>(), it);
  return m;
}

// Every labelled item of a frame fits: its label within the item, the item within its window.
void expect_nothing_clipped(const nlohmann::json& stats, const std::string& where) {
  ASSERT_GT(stats["ui_items"].size(), 20u) << where;
  for (const auto& it : stats["ui_items"]) {
    const std::string label = it["label"];
    EXPECT_LE(it["text_w"].get<double>(), it["inner_w"].get<double>() + 0.5) << where << ": " << label;
    EXPECT_LE(it["x"].get<double>() + it["w"].get<double>(), it["clip_right"].get<double>() + 0.5)
        << where << ": " << label;
    // In a window that does not scroll (the status area), nothing runs past its bottom either.
    if (!it["scrolls"].get<bool>())
      EXPECT_LE(it["y"].get<double>() + it["h"].get<double>(), it["clip_bottom"].get<double>() + 0.5)
          << where << ": " << label;
  }
}

// Each File menu dialog, opened by the script's `dialog` (as its menu item opens it), at size:
// nothing in it (nor in the panels under it) is clipped, its fields and buttons lie within the
// window, and `dialog close` closes it (its items gone from the next stats).
void expect_dialogs_fit(const fs::path& tsp, const fs::path& dir, const std::string& size) {
  // Each dialog and a label only it has.
  const std::pair<const char*, const char*> dialogs[] = {
      {"open", "build options"},
      {"save-tf", "Our transfer-function JSON (docs/transfer-functions.md):"},
      {"record", "The volume as shown, with its annotations, in real time (.mp4 or .gif); "
                 "File > Stop recording writes it:"},
      {"save-session", "The transfer function, view, probes, surface, axis scale, speed and "
                       "panels, for tspplay play --session FILE:"}};
  std::string text = "wait-frames 2\n";
  for (const auto& [which, label] : dialogs)
    text += std::string("dialog ") + which + "\nwait-frames 3\nstats " +
            (dir / (size + "_dialog_" + which + ".json")).string() + "\ndialog close\nwait-frames 3\n";
  text += "stats " + (dir / (size + "_dialog_closed.json")).string() + "\nquit\n";
  const auto r = run_tspplay("play " + q(tsp) + " --size " + size + " --script " +
                             q(script_in(dir, size + "_dialogs.txt", text)));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const nlohmann::json closed = read_json(dir / (size + "_dialog_closed.json"));
  const auto after = items_by_label(closed);
  const double w = closed["window"][0].get<double>(), h = closed["window"][1].get<double>();
  for (const auto& [which, label] : dialogs) {
    const std::string where = size + " dialog " + which;
    const nlohmann::json j = read_json(dir / (size + "_dialog_" + which + ".json"));
    expect_nothing_clipped(j, where);
    const auto items = items_by_label(j);
    ASSERT_TRUE(items.count(label)) << where << ": " << j["ui_items"];
    EXPECT_FALSE(after.count(label)) << where << " stayed open after dialog close";
    const char* button = std::string(which) == "open" ? "Open" : "OK";
    for (const char* name : {label, button, "Cancel"}) {
      ASSERT_TRUE(items.count(name)) << where << ": " << name;
      const nlohmann::json& it = items.at(name);
      EXPECT_GE(it["x"].get<double>(), 0) << where << ": " << name;
      EXPECT_LE(it["x"].get<double>() + it["w"].get<double>(), w) << where << ": " << name;
      EXPECT_LE(it["y"].get<double>() + it["h"].get<double>(), h) << where << ": " << name;
    }
  }
  // Each dialog lies in the volume's view, clear of the side panel (File > Open's 560 px
  // overlapped the panel by 8 px at 1280x800).
  const std::pair<const char*, const char*> titles[] = {{"open", "Open"},
                                                         {"save-tf", "Save transfer function as"},
                                                         {"record", "Record movie"},
                                                         {"save-session", "Save session"}};
  for (const auto& [which, title] : titles) {
    const std::string where = size + " dialog " + which;
    const nlohmann::json j = read_json(dir / (size + "_dialog_" + which + ".json"));
    const auto items = items_by_label(j);
    ASSERT_TRUE(items.count(std::string("dialog: ") + title)) << where;
    const nlohmann::json& d = items.at(std::string("dialog: ") + title);
    const nlohmann::json& v = j["view"];
    EXPECT_GE(d["x"].get<double>(), v[0].get<double>()) << where;
    EXPECT_LE(d["x"].get<double>() + d["w"].get<double>(), v[0].get<double>() + v[2].get<double>())
        << where;
    EXPECT_GE(d["y"].get<double>(), v[1].get<double>()) << where;
    EXPECT_LE(d["y"].get<double>() + d["h"].get<double>(), v[1].get<double>() + v[3].get<double>())
        << where;
  }
  // The open dialog's kinds combo shows its choice whole (its extensions list ran off it).
  const auto open = items_by_label(read_json(dir / (size + "_dialog_open.json")));
  EXPECT_TRUE(open.count("Inputs play reads")) << size;
}

TEST(Player, PanelFitsAt1280x800And1920x1080WithTheTransferFunctionFirst) {
  TSPTEST_REQUIRE(window_possible(), "no display (run under xvfb-run)");
  const fs::path tsp = make_tsp(), dir = tsptest::temp_dir();
  for (const char* size : {"1280x800", "1920x1080"}) {
    const std::string s(size);
    const fs::path a = dir / (s + "_a.json"), b = dir / (s + "_b.json"), c = dir / (s + "_c.json");
    const fs::path d = dir / (s + "_d.json");
    // A message longer than the status area holds (an error naming a long path).
    const fs::path missing = dir / (std::string(120, 'm') + ".h5");
    // As it starts; after a message in the status area; every section open; playing (the rung
    // in the status area) with the long message under it.
    const fs::path script = script_in(
        dir, s + ".txt",
        "wait-frames 3\nstats " + a.string() + "\ntf-range 0.2:0.8\nwait-frames 3\nstats " +
            b.string() + "\nexpand on\nwait-frames 3\nstats " + c.string() +
            "\nplay\nwait-frames 1\nopen " + missing.string() + "\nwait-frames 3\nstats " +
            d.string() + "\nquit\n");
    const auto r = run_tspplay("play " + q(tsp) + " --size " + s + " --script " + q(script));
    ASSERT_EQ(r.exit_code, 0) << r.err;
    const nlohmann::json ja = read_json(a), jb = read_json(b), jc = read_json(c);
    expect_nothing_clipped(ja, s + " as it starts");
    expect_nothing_clipped(jc, s + " every section open");
    // Playing with a long message: the rung and the message share the status area, the
    // message cut short with "..." (in full in stats and the tooltip), nothing cut off.
    const nlohmann::json jd = read_json(d);
    expect_nothing_clipped(jd, s + " playing, a long message");
    const std::string full = jd["status"];
    ASSERT_NE(full.find(missing.string()), std::string::npos) << full;
    bool rung = false, cut_short = false;
    for (const auto& it : jd["ui_items"]) {
      if (it["scrolls"].get<bool>()) continue;
      const std::string label = it["label"];
      rung = rung || label.find("dE") != std::string::npos || label.find("tuning") != std::string::npos;
      if (label.size() > 3 && label.compare(label.size() - 3, 3, "...") == 0) {
        cut_short = true;
        EXPECT_EQ(full.rfind(label.substr(0, label.size() - 3), 0), 0u) << label;
      }
    }
    EXPECT_TRUE(rung) << jd["ui_items"];
    EXPECT_TRUE(cut_short) << jd["ui_items"];
    const auto start = items_by_label(ja), message = items_by_label(jb), open = items_by_label(jc);
    const int height = ja["window"][1].get<int>();
    // The transfer function's colour range is above the fold; the expert knobs are collapsed.
    ASSERT_TRUE(start.count("range LO:HI")) << s;
    EXPECT_LT(start.at("range LO:HI")["y"].get<double>() + 30, height) << s;
    EXPECT_TRUE(start.count("fit to bulk")) << s;
    EXPECT_FALSE(start.count("spatial tol")) << s;
    EXPECT_TRUE(open.count("spatial tol")) << s;
    EXPECT_TRUE(open.count("playing quality (mean dE)")) << s;
    // The message went to the status area: no control moved.
    EXPECT_NE(jb["status"].get<std::string>().find("stretched"), std::string::npos) << jb["status"];
    for (const auto& [label, it] : start) {
      ASSERT_TRUE(message.count(label)) << s << ": " << label;
      EXPECT_EQ(message.at(label)["y"], it["y"]) << s << ": " << label;
      EXPECT_EQ(message.at(label)["x"], it["x"]) << s << ": " << label;
    }
    // Play is as wide as Pause (the controls beside it do not move when it flips): room to
    // spare around its own label.
    EXPECT_GE(start.at("Play")["inner_w"].get<double>(), start.at("Play")["text_w"].get<double>() + 6);
    expect_dialogs_fit(tsp, dir, s);
  }
}

// The tolerance readout: at 0 the picture is the exact one (ΔE 0); at a large tolerance both
// frame times are measured and the picture differs.
TEST(Player, ToleranceSlidersShowWhatTheyBuy) {
  TSPTEST_REQUIRE(window_possible(), "no display (run under xvfb-run)");
  const fs::path tsp = make_tsp(), dir = tsptest::temp_dir();
  const fs::path z = dir / "zero.json", t = dir / "tol.json";
  const fs::path script = script_in(dir, "tol.txt",
                                    "tolerance 0 0\nwait-frames 2\nstats " + z.string() +
                                        "\ntolerance 0.5 0.5\nwait-frames 2\nstats " + t.string() +
                                        "\nquit\n");
  const auto r = run_tspplay("play " + q(tsp) + " --size 400x300 --script " + q(script));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const nlohmann::json rz = read_json(z)["tolerance_readout"], rt = read_json(t)["tolerance_readout"];
  EXPECT_EQ(rz["spatial"].get<double>(), 0);
  EXPECT_EQ(rz["mean_de"].get<double>(), 0);
  EXPECT_EQ(rt["spatial"].get<double>(), 0.5);
  EXPECT_EQ(rt["temporal"].get<double>(), 0.5);
  EXPECT_GT(rt["ms"].get<double>(), 0);
  EXPECT_GT(rt["exact_ms"].get<double>(), 0);
  EXPECT_GT(rt["mean_de"].get<double>(), 0);
}

}  // namespace

namespace {

// Real X input (xdotool) in frames of at least 150 ms: a drag of the speed slider from its right
// end past its left, pressed, moved and released within one frame, ends at the slider's minimum
// (it used to be lost: "dragged to 0, got 0.1019"); in the colour range field, ten backspaces
// typed within a frame or two each delete a character (Dear ImGui used to see one a frame: "18
// of 70 applied"), so the typed range replaces the old one exactly. The old range starts with
// '-': any character left over changes the result. (Each stage is a handshake: the script goes
// on once the window has taken the input sent before it.)
TEST(Player, SlowFramesLoseNeitherADragsEndNorAKeystroke) {
  TSPTEST_REQUIRE_X_EVENTS();
  const fs::path tsp = make_tsp(), dir = tsptest::temp_dir();
  const fs::path rects = dir / "rects.json", done = dir / "done.json", out = dir / "input.out";
  const fs::path script = script_in(dir, "input.txt",
                                    "wait-frames 3\nstats " + rects.string() + "\n" +
                                        taken(dir, "drag") + taken(dir, "click") +
                                        taken(dir, "typed") + "stats " + done.string() +
                                        "\nquit\n");
  // (Python reads an item's rectangle from the stats: x y w h.)
  auto rect = [&](const std::string& label) {
    return "$(python3 -c 'import json,sys; i=[i for i in json.load(open(sys.argv[1]))[\"ui_items\"] "
           "if i[\"label\"]==sys.argv[2]][0]; print(int(i[\"x\"]),int(i[\"y\"]),int(i[\"w\"]),"
           "int(i[\"h\"]))' " + q(rects) + " " + q(label) + ")";
  };
  std::string keys;
  for (int i = 0; i < 10; ++i) keys += " BackSpace";  // "-0.25:0.75"
  const std::string cmd =
      log_waits(out) + handshakes(dir) + "(" + q(tsptest::tspplay_bin()) + " play " + q(tsp) +
      " --size 1280x800 " + "--frame-delay-ms 150 --tf-range=-0.25:0.75 --script " + q(script) +
      " > " + q(out) + " 2>&1 &\n" + "p=$!\n"
      "until_file " + q(rects) + "\n"
      "win=$(xdotool search --sync --name " + q("tspplay - " + tsp.string()) + " | head -1)\n"
      "read sx sy sw sh <<< " + rect("steps/s") + "\n"
      "read rx ry rw rh <<< " + rect("range LO:HI") + "\n"
      "y=$((sy + sh / 2)); x=$((sx + 130))\n"
      "xdotool mousemove --window \"$win\" $x $y mousedown 1 mousemove --window \"$win\" "
      "$((x - 50)) $y mousemove --window \"$win\" $((x - 110)) $y mousemove --window \"$win\" "
      "$((sx - 40)) $y mouseup 1\n"
      "handshake drag\n"
      "xdotool mousemove --window \"$win\" $((rx + 40)) $((ry + rh / 2)) click 1\n"
      "handshake click\n"
      "xdotool key --window \"$win\" --delay 15 End" + keys + "\n"
      "xdotool type --window \"$win\" --delay 15 0.3:0.7\n"
      "xdotool key --window \"$win\" Return\n"
      "handshake typed\n"
      "wait $p)\n";
  ASSERT_EQ(run_bash(dir / "input.sh", cmd), 0) << tsptest::read_file(out);
  const nlohmann::json j = read_json(done);
  EXPECT_EQ(j["playback"]["speed"].get<double>(), 0.25) << tsptest::read_file(out);
  EXPECT_NEAR(j["tf_domain"][0].get<double>(), 0.3, 1e-9) << j["status"];
  EXPECT_NEAR(j["tf_domain"][1].get<double>(), 0.7, 1e-9) << j["status"];
}

}  // namespace
