// The default transfer function (preset:auto, built from the file's histogram, issue 29 item 4)
// shows a picture on every committed sample and on the demo's dataset: every step that holds
// more than one value, drawn with no --tf, differs visibly from the same frame drawn fully
// transparent (some pixel by ΔE > 10), and each sample's last step shows a picture (more than
// 1 % of its pixels by ΔE > 5). A step of one value (the plume's first: still air at 300 K) is
// all background and clear. For comparison the test prints how many frames show less than 1 %
// of their pixels with the default map and with the sparse preset, the old default.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "support/paths.h"
#include "tsp/report/image.h"
#include "tsp/report/image_diff.h"
#include "tsp/store/tsp_file.h"
#include "tsp/tree/tsp_tree.h"

namespace fs = std::filesystem;
using tsptest::run_tspplay;

namespace {

using tsptest::q;

// ΔE above which a pixel shows something; the last step's 99th percentile must pass
// kPictureDeltaE (more than 1 % of the pixels show something).
constexpr double kShownDeltaE = 10.0, kPictureDeltaE = 5.0;

struct Sample {
  std::string name, input, build_args;
};

// Renders every step of tsp with tf_args into dir/name; returns the frames' paths.
std::vector<fs::path> render_all(const fs::path& tsp, const fs::path& dir, const std::string& name,
                                 const std::string& tf_args, int steps) {
  const auto r = run_tspplay("render " + q(tsp) + " --size 96x72 " + tf_args + " -o " +
                             q(dir / name));
  EXPECT_EQ(r.exit_code, 0) << r.err;
  std::vector<fs::path> frames;
  for (int t = 0; t < steps; ++t) {
    char f[32];
    std::snprintf(f, sizeof f, "step_%04d.png", t);
    frames.push_back(dir / name / f);
  }
  return frames;
}

TEST(DefaultTfCli, TheHistogramMapShowsEveryStepOfEveryCommittedSample) {
  const fs::path dir = tsptest::temp_dir();
  ASSERT_EQ(run_tspplay("generate shock -o " + q(dir / "shock.h5") + " --dims 32 --steps 6").exit_code,
            0);
  // A map with no opacity anywhere: the empty picture each frame is compared with.
  std::ofstream(dir / "clear.json") << R"({"range":[0,1],"points":[[0,0,0,0,0],[1,0,0,0,0]]})";
  const fs::path samples = tsptest::datasets_dir() / "samples";
  const std::vector<Sample> all = {
      {"shock", (dir / "shock.h5").string(), "--field shock --brick 16"},
      {"plume", (samples / "hotPlume_32.h5").string(), "--field T --brick 16"},
      {"dambreak", (samples / "damBreakWithObstacle" / "damBreakWithObstacle.vtu.series").string(),
       "--field alpha.water --resolution 32 --brick 16"},
  };
  int sparse_empty = 0, auto_empty = 0, frames = 0;
  for (const Sample& s : all) {
    SCOPED_TRACE(s.name);
    const fs::path tsp = dir / (s.name + ".tsp");
    const auto b = run_tspplay("build " + q(s.input) + " " + s.build_args + " -o " + q(tsp));
    ASSERT_EQ(b.exit_code, 0) << b.err;
    const auto file = tsp::TspFile::open(tsp.string());
    const int steps = file->tree().time().steps();
    const auto shown = render_all(tsp, dir, s.name + "_auto", "", steps);
    const auto clear =
        render_all(tsp, dir, s.name + "_clear", "--tf " + q(dir / "clear.json") + " --tf-range data", steps);
    const auto sparse = render_all(tsp, dir, s.name + "_sparse", "--tf preset:sparse", steps);
    for (int t = 0; t < steps; ++t) {
      const tsp::TspTree& tree = file->tree();
      const tsp::NodeStats& st = tree.stats(tree.id(0, tree.time().leaf_of(t)));
      if (!(st.min < st.max)) continue;  // one value: the background, clear
      const tsp::Image empty = tsp::read_png(clear[std::size_t(t)].string());
      const tsp::DiffStats d = tsp::diff_images(tsp::read_png(shown[std::size_t(t)].string()), empty);
      EXPECT_GT(d.max, kShownDeltaE) << "step " << t << ": the default map shows nothing";
      if (t == steps - 1) {
        EXPECT_GT(d.p99, kPictureDeltaE) << "step " << t << ": the default map shows too little";
      }
      const tsp::DiffStats old = tsp::diff_images(tsp::read_png(sparse[std::size_t(t)].string()), empty);
      sparse_empty += old.p99 <= kPictureDeltaE;
      auto_empty += d.p99 <= kPictureDeltaE;
      ++frames;
    }
  }
  std::printf("frames showing less than 1 %% of their pixels: default map %d, sparse preset %d, "
              "of %d\n", auto_empty, sparse_empty, frames);
}

}  // namespace
