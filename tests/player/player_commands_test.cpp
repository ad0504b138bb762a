// The panels send the script's commands (player/command.h): the TF editor's "fit to data"
// button, clicked with real X input (xdotool), stretches the map over the data's range as the
// script's `tf-range data` does (it used to stretch the map over its own domain: nothing moved).
#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>

#include <nlohmann/json.hpp>

#include "support/paths.h"
#include "support/player_run.h"

namespace {

namespace fs = std::filesystem;
using namespace tsptest::player;
using tsptest::q;

TEST(Player, FitToDataButtonSendsTheScriptsTfRangeData) {
  TSPTEST_REQUIRE(window_possible(), "no display (run under xvfb-run)");
  ASSERT_EQ(std::system("command -v xdotool > /dev/null"), 0)
      << "xdotool missing (scripts/install-deps.sh installs it)";
  const fs::path tsp = make_tsp(), dir = tsptest::temp_dir();
  const fs::path rects = dir / "rects.json", clicked = dir / "clicked.json",
                 scripted = dir / "scripted.json", out = dir / "fit.out";
  // The click comes while the script waits; then the script's own tf-range data, for reference.
  std::ofstream(dir / "fit.txt") << "wait-frames 3\nstats " << rects.string()
                                 << "\nwait-seconds 15\nstats " << clicked.string()
                                 << "\ntf-range 0.2:0.8\ntf-range data\nwait-frames 1\nstats "
                                 << scripted.string() << "\nquit\n";
  const std::string rect =
      "$(python3 -c 'import json,sys; i=[i for i in json.load(open(sys.argv[1]))[\"ui_items\"] "
      "if i[\"label\"]==sys.argv[2]][0]; print(int(i[\"x\"]),int(i[\"y\"]),int(i[\"w\"]),"
      "int(i[\"h\"]))' " + q(rects) + " " + q("fit to data") + ")";
  const std::string cmd =
      "(" + q(tsptest::tspplay_bin()) + " play " + q(tsp) + " --size 1280x800 " +
      "--tf-range=0.2:0.8 --script " + q(dir / "fit.txt") + " > " + q(out) + " 2>&1 &\n" +
      "p=$!\n"
      "for i in $(seq 300); do [ -s " + q(rects) + " ] && break; sleep 0.1; done\n"
      "win=$(xdotool search --sync --name " + q("tspplay - " + tsp.string()) + " | head -1)\n"
      "read fx fy fw fh <<< " + rect + "\n"
      "xdotool mousemove --window \"$win\" $((fx + fw / 2)) $((fy + fh / 2)) click 1\n"
      "wait $p)\n";
  ASSERT_EQ(run_bash(dir / "fit.sh", cmd), 0) << tsptest::read_file(out);
  const nlohmann::json before = read_json(rects), after = read_json(clicked),
                       reference = read_json(scripted);
  EXPECT_NEAR(before["tf_domain"][0].get<double>(), 0.2, 1e-9);
  EXPECT_NEAR(before["tf_domain"][1].get<double>(), 0.8, 1e-9);
  EXPECT_NE(reference["tf_domain"], before["tf_domain"]);
  EXPECT_EQ(after["tf_domain"], reference["tf_domain"]) << after["status"];
  EXPECT_EQ(after["status"], reference["status"]);
}

}  // namespace
