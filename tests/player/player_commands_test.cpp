// The panels send the script's commands (player/command.h): the TF editor's "fit to data"
// button, clicked with real X input (xdotool), stretches the map over the data's range as the
// script's `tf-range data` does (it used to stretch the map over its own domain: nothing moved);
// the editor's point edits are the script's tf-point lines, which change the map exactly as the
// handles' functions (player/tf_handles.h) say and the picture as `render` draws that map.
#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "player/tf_handles.h"
#include "support/paths.h"
#include "support/player_run.h"
#include "tsp/core/number_text.h"
#include "tsp/metric/tf_io.h"
#include "tsp/report/image_diff.h"
#include "tsp/store/tsp_file.h"

namespace {

namespace fs = std::filesystem;
using namespace tsptest::player;
using tsptest::q;

// The stats of a window before and after a real click on one of its items, and after script
// lines that should do what the click did.
struct Clicked {
  nlohmann::json before, after, reference;
};

// Plays tsp at 1280x800 with `options`, in dir as its working folder, under a script that writes
// stats, waits while xdotool clicks the item labelled `label` (where those stats put it: the
// `click` handshake), writes stats again, then runs `reference` (script lines) and writes stats
// a third time.
Clicked click_then_script(const fs::path& tsp, const fs::path& dir, const std::string& options,
                          const std::string& label, const std::string& reference) {
  const fs::path rects = dir / "rects.json", clicked = dir / "clicked.json",
                 scripted = dir / "scripted.json", out = dir / "click.out";
  std::ofstream(dir / "click.txt") << "wait-frames 3\nstats " << rects.string() << "\n"
                                   << taken(dir, "click") << "stats " << clicked.string() << "\n"
                                   << reference << "wait-frames 1\nstats " << scripted.string()
                                   << "\nquit\n";
  const std::string rect =
      "$(python3 -c 'import json,sys; i=[i for i in json.load(open(sys.argv[1]))[\"ui_items\"] "
      "if i[\"label\"]==sys.argv[2]][0]; print(int(i[\"x\"]),int(i[\"y\"]),int(i[\"w\"]),"
      "int(i[\"h\"]))' " + q(rects) + " " + q(label) + ")";
  const std::string cmd =
      log_waits(out) + handshakes(dir) + "cd " + q(dir) + " && (" + q(tsptest::tspplay_bin()) +
      " play " + q(tsp) +
      " --size 1280x800 " + options + " --script " + q(dir / "click.txt") + " > " + q(out) +
      " 2>&1 &\n" +
      "p=$!\n"
      "until_file " + q(rects) + "\n"
      "win=$(xdotool search --sync --name " + q("tspplay - " + tsp.string()) + " | head -1)\n"
      "read fx fy fw fh <<< " + rect + "\n"
      "xdotool mousemove --window \"$win\" $((fx + fw / 2)) $((fy + fh / 2)) click 1\n"
      "handshake click\n"
      "wait $p)\n";
  EXPECT_EQ(run_bash(dir / "click.sh", cmd), 0) << tsptest::read_file(out);
  return {read_json(rects), read_json(clicked), read_json(scripted)};
}

TEST(Player, FitToDataButtonSendsTheScriptsTfRangeData) {
  TSPTEST_REQUIRE_X_EVENTS();
  const fs::path tsp = make_tsp(), dir = tsptest::temp_dir();
  // The click comes while the script waits; then the script's own tf-range data, for reference.
  const Clicked c = click_then_script(tsp, dir, "--tf-range=0.2:0.8", "fit to data",
                                      "tf-range 0.2:0.8\ntf-range data\n");
  EXPECT_NEAR(c.before["tf_domain"][0].get<double>(), 0.2, 1e-9);
  EXPECT_NEAR(c.before["tf_domain"][1].get<double>(), 0.8, 1e-9);
  EXPECT_NE(c.reference["tf_domain"], c.before["tf_domain"]);
  EXPECT_EQ(c.after["tf_domain"], c.reference["tf_domain"]) << c.after["status"];
  EXPECT_EQ(c.after["status"], c.reference["status"]);
}

// The editor's handles and every entry's opacity in a stats file equal points and tf's.
void expect_map(const nlohmann::json& stats, const std::vector<tsp::TfPoint>& points,
                const tsp::TransferFunction& tf, const char* after) {
  ASSERT_EQ(stats["tf_points"].size(), points.size()) << after;
  for (std::size_t i = 0; i < points.size(); ++i) {
    EXPECT_EQ(stats["tf_points"][i][0].get<double>(), points[i].x) << after << ", point " << i;
    EXPECT_EQ(stats["tf_points"][i][1].get<double>(), double(points[i].c.a)) << after;
  }
  ASSERT_EQ(stats["tf_opacity"].size(), std::size_t(tf.size())) << after;
  for (int j = 0; j < tf.size(); ++j)
    ASSERT_EQ(stats["tf_opacity"][std::size_t(j)].get<double>(), double(tf.entry(j).a))
        << after << ", entry " << j;
  EXPECT_EQ(stats["tf"], "edited") << after;
}

// tf.json in dir: a three-point map over tsp's value range (returned).
tsp::ValueRange write_three_point_tf(const fs::path& tsp, const fs::path& dir) {
  const tsp::ValueRange r = tsp::TspFile::open(tsp.string())->tree().value_range();
  std::ofstream(dir / "tf.json") << nlohmann::json{
      {"range", {r.lo, r.hi}},
      {"points", {{r.lo, 0.2, 0.4, 1, 0}, {r.lo + 0.5 * (r.hi - r.lo), 1, 0.6, 0.1, 0.05},
                  {r.hi, 1, 1, 1, 0.3}}}};
  return r;
}

// A value of r at share t written with every digit (a script's value is this double exactly).
std::string value_text(const tsp::ValueRange& r, double t) {
  return tsp::number_text(r.lo + t * (r.hi - r.lo), "%.17g");
}

// The handles the player places over tf.json in dir and their map.
tspplayer::TfHandles start_handles(const fs::path& dir, const tsp::ValueRange& r) {
  return tspplayer::place_handles(tsp::transfer_function_from_arg(
      (dir / "tf.json").string(), r, tsp::kDefaultTfEntries, {tsp::TfRangeChoice::Mode::file, {}}));
}

// A script moves, adds and removes the TF editor's points (tf-point, what the handles' drag,
// double-click and right-click send): after each line the handles and the map are what
// clamp_handle_x, warp_handles, add_handle and remove_handle make of the map before, and the
// picture is `render`'s with the edited map.
TEST(Player, ScriptedTfPointEditsChangeTheMapAndThePictureExactly) {
  TSPTEST_REQUIRE(window_possible(), "no display (run under xvfb-run)");
  const fs::path tsp = make_tsp(), dir = tsptest::temp_dir();
  const tsp::ValueRange r = write_three_point_tf(tsp, dir);
  const std::string move_text = value_text(r, 0.6), add_text = value_text(r, 0.8);
  const double moved_to = std::stod(move_text), added_at = std::stod(add_text);
  std::ofstream(dir / "edit.txt")
      << "stats " << (dir / "s0.json").string() << "\ntf-point move 2 " << move_text
      << " 0.8\nstats " << (dir / "s1.json").string() << "\ntf-point add " << add_text
      << " 0.1\nstats " << (dir / "s2.json").string() << "\ntf-point remove 1\nscreenshot "
      << (dir / "shot.png").string() << "\nstats " << (dir / "s3.json").string() << "\nquit\n";
  auto run = tsptest::run_tspplay("play " + q(tsp) + " --size " + kSize + " --tf " +
                                  q(dir / "tf.json") + " --tf-range file --script " +
                                  q(dir / "edit.txt"));
  ASSERT_EQ(run.exit_code, 0) << run.err;

  // The same edits through the handles' functions.
  tspplayer::TfHandles h = start_handles(dir, r);
  std::vector<tsp::TfPoint> points = h.placed;
  ASSERT_EQ(points.size(), 3u);
  const nlohmann::json s0 = read_json(dir / "s0.json");
  for (std::size_t i = 0; i < 3; ++i)
    EXPECT_EQ(s0["tf_points"][i][0].get<double>(), points[i].x);
  points[1].x = tspplayer::clamp_handle_x(points, 1, moved_to);
  points[1].c.a = 0.8f;
  const tsp::TransferFunction moved = tspplayer::warp_handles(h, points);
  expect_map(read_json(dir / "s1.json"), points, moved, "move");
  tsp::Rgba c = tspplayer::sample_tf(moved, added_at);
  c.a = 0.1f;
  EXPECT_EQ(tspplayer::add_handle(h, points, moved, added_at, c), 2);
  const tsp::TransferFunction added = tspplayer::warp_handles(h, points);
  expect_map(read_json(dir / "s2.json"), points, added, "add");
  const tsp::TransferFunction removed = tspplayer::remove_handle(h, points, added, 0);
  expect_map(read_json(dir / "s3.json"), points, removed, "remove");

  // The picture: render's with the edited map, not with the map it started from.
  tsp::save_transfer_function(removed, (dir / "edited.json").string());
  const tsp::Image shot = tsp::read_png((dir / "shot.png").string());
  EXPECT_LT(tsp::diff_images(shot, render_step(tsp, 0, (dir / "edited.json").string())).mean,
            kSameFrameDeltaE);
  EXPECT_GT(tsp::diff_images(shot, render_step(tsp, 0, (dir / "tf.json").string())).mean,
            kDifferentFrameDeltaE);
}

// The handles a session restores move the map it restores: the next window's tf-point edit warps
// the edited map of the last (the handles were left placed over the map the window started
// with: the edit failed, 3 handles for 9, or warped that map).
TEST(Player, TfPointsRestoredFromASessionMoveTheRestoredMap) {
  TSPTEST_REQUIRE(window_possible(), "no display (run under xvfb-run)");
  const fs::path tsp = make_tsp(), dir = tsptest::temp_dir();
  const tsp::ValueRange r = write_three_point_tf(tsp, dir);
  const std::string cache = " --cache-dir " + q(dir / "cache"), first = value_text(r, 0.6),
                    second = value_text(r, 0.9);
  std::ofstream(dir / "a.txt") << "tf-point move 2 " << first << " 0.8\nquit\n";
  auto a = tsptest::run_tspplay("play " + q(tsp) + " --size " + kSize + cache + " --tf " +
                                q(dir / "tf.json") + " --tf-range file --script " +
                                q(dir / "a.txt"));
  ASSERT_EQ(a.exit_code, 0) << a.err;
  std::ofstream(dir / "b.txt") << "stats " << (dir / "s0.json").string() << "\ntf-point move 3 "
                               << second << " 0.5\nstats " << (dir / "s1.json").string()
                               << "\nquit\n";
  auto b = tsptest::run_tspplay("play " + q(tsp) + " --size " + kSize + cache + " --script " +
                                q(dir / "b.txt"));
  ASSERT_EQ(b.exit_code, 0) << b.err;

  tspplayer::TfHandles h = start_handles(dir, r);
  std::vector<tsp::TfPoint> points = h.placed;
  points[1].x = tspplayer::clamp_handle_x(points, 1, std::stod(first));
  points[1].c.a = 0.8f;
  const tsp::TransferFunction restored = tspplayer::warp_handles(h, points);
  expect_map(read_json(dir / "s0.json"), points, restored, "restore");
  const tspplayer::TfHandles placed{restored, points};
  points[2].x = tspplayer::clamp_handle_x(points, 2, std::stod(second));
  points[2].c.a = 0.5f;
  const nlohmann::json s1 = read_json(dir / "s1.json");
  expect_map(s1, points, tspplayer::warp_handles(placed, points), "move after restore");
  EXPECT_EQ(s1["status"].get<std::string>().find("handles"), std::string::npos) << s1["status"];
}

// The TF editor's load button sends the script's tf line (cmd::LoadTf): clicked with the path
// field's tf.json, the map, its handles, its name and the status are what `tf tf.json` makes.
TEST(Player, LoadButtonSendsTheScriptsTf) {
  TSPTEST_REQUIRE_X_EVENTS();
  const fs::path tsp = make_tsp(), dir = tsptest::temp_dir();
  write_three_point_tf(tsp, dir);
  const Clicked c = click_then_script(tsp, dir, "", "load", "tf preset:filled\ntf tf.json\n");
  EXPECT_EQ(c.before["tf"], "auto");
  EXPECT_EQ(c.after["tf"], "tf.json");
  EXPECT_EQ(c.after["status"], "loaded tf.json");
  for (const char* key : {"tf", "tf_domain", "tf_points", "tf_opacity", "status"})
    EXPECT_EQ(c.after[key], c.reference[key]) << key;
  EXPECT_EQ(c.after["tf_points"].size(), 3u);
}

}  // namespace
