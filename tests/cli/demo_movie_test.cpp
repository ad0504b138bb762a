// tspplay demo's movie: encoded through ffmpeg when it is on PATH (a stand-in script here, as the
// test machine need not have ffmpeg), skipped with a message when it is not or when it fails,
// and never left half-written.
#include <gtest/gtest.h>
#include <stdlib.h>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>

#include "support/paths.h"

namespace {

namespace fs = std::filesystem;
using tsptest::run_tspplay;

// A stand-in ffmpeg: records its arguments, then writes "movie" to its last argument (or fails).
fs::path fake_ffmpeg(bool fail) {
  const fs::path bin = tsptest::temp_dir();
  const fs::path script = bin / "ffmpeg";
  std::ofstream f(script);
  f << "#!/bin/sh\necho \"$@\" > '" << (bin / "args.txt").string() << "'\n";
  if (fail)
    f << "exit 3\n";
  else
    f << "for a; do last=$a; done\necho movie > \"$last\"\n";
  f.close();
  fs::permissions(script, fs::perms::owner_all);
  return bin;
}

// Runs the demo with PATH set to path_dir only (the binary and /bin/sh are absolute).
tsptest::RunResult demo_with_path(const fs::path& dir, const fs::path& path_dir) {
  const std::string saved = getenv("PATH") ? getenv("PATH") : "";
  setenv("PATH", path_dir.c_str(), 1);
  auto r = run_tspplay("demo -o '" + dir.string() + "' --dims 12,10,8 --steps 3");
  setenv("PATH", saved.c_str(), 1);
  return r;
}

bool has_temp_files(const fs::path& dir) {
  for (const auto& e : fs::directory_iterator(dir))
    if (e.path().filename().string().rfind(".demo.mp4", 0) == 0) return true;
  return false;
}

TEST(DemoMovie, EncodesFramesWhenFfmpegIsOnPath) {
  const fs::path dir = tsptest::temp_dir() / "demo", bin = fake_ffmpeg(false);
  auto r = demo_with_path(dir, bin);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  ASSERT_TRUE(fs::exists(dir / "demo.mp4")) << r.out;
  std::ifstream m(dir / "demo.mp4");
  std::string content;
  m >> content;
  EXPECT_EQ(content, "movie");
  std::ifstream a(bin / "args.txt");
  std::string args((std::istreambuf_iterator<char>(a)), std::istreambuf_iterator<char>());
  EXPECT_NE(args.find("frame_%05d.png"), std::string::npos) << args;  // the linked frames
  EXPECT_NE(args.find("-f mp4"), std::string::npos) << args;
  EXPECT_FALSE(has_temp_files(dir));
  std::ifstream rep(dir / "report.json");
  EXPECT_EQ(nlohmann::json::parse(rep)["movie"], (dir / "demo.mp4").string());
}

TEST(DemoMovie, SkipsWithAMessageWithoutFfmpeg) {
  const fs::path dir = tsptest::temp_dir() / "demo", empty = tsptest::temp_dir();
  auto r = demo_with_path(dir, empty);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("movie: skipped (no ffmpeg"), std::string::npos) << r.out;
  EXPECT_FALSE(fs::exists(dir / "demo.mp4"));
}

TEST(DemoMovie, AFailingEncoderLeavesNoFile) {
  const fs::path dir = tsptest::temp_dir() / "demo", bin = fake_ffmpeg(true);
  auto r = demo_with_path(dir, bin);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("ffmpeg failed"), std::string::npos) << r.out;
  EXPECT_FALSE(fs::exists(dir / "demo.mp4"));
  EXPECT_FALSE(has_temp_files(dir));
}

}  // namespace
