// File > Open's filter (the names of the kinds of file play reads, against a hand-made list) and
// play's build cache: keyed by every file the source reads, entries of the wrong kind replaced,
// never written through.
#include "jobs/play_input.h"

#include <gtest/gtest.h>
#include <sys/stat.h>

#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <vector>

#include "support/paths.h"
#include "support/reader_formula.h"
#include "tsp/build/build.h"
#include "tsp/core/error.h"
#include "tsp/store/tsp_file.h"
#include "tsp/voxelize/open_input.h"

namespace tspgl {
namespace {

namespace fs = std::filesystem;

TEST(PlayInput, KnownInputNamesAreTheKindsPlayReads) {
  for (const char* name : {"run.tsp", "a/b/T.h5", "x.hdf5", "can_0.hdf", "s.he5", "wrf.nc", "w.nc4",
                           "m.vtkhdf", "step.vti", "mesh.vtu", "case.vtm", "case.pvd",
                           "img.vti.series", "mesh.vtu.series", "case.vtm.series", "u_0001.raw",
                           "grid.vts", "grid.vts.series", "flow_0001.q",
                           "UPPER.H5", "Mixed.Vtu"})
    EXPECT_TRUE(has_input_extension(name)) << name;
  for (const char* name : {"", "notes.txt", "frame.png", "log", "run.tsp.log", "h5", ".h5",
                           "movie.mp4", "tf.json", "archive.tar.gz", "x.series", "data.vt"})
    EXPECT_FALSE(has_input_extension(name)) << name;
}

// A small raw series (three steps of 8³ floats) in dir, its pattern returned.
std::string raw_series(const fs::path& dir) {
  for (int t = 0; t < 3; ++t) {
    std::vector<float> v(8 * 8 * 8);
    for (std::size_t i = 0; i < v.size(); ++i) v[i] = float((i * 7 + std::size_t(t) * 13) % 31);
    char name[32];
    std::snprintf(name, sizeof name, "u_%04d.raw", t);
    std::ofstream(dir / name, std::ios::binary)
        .write(reinterpret_cast<const char*>(v.data()), std::streamsize(v.size() * sizeof(float)));
  }
  return (dir / "u_%04d.raw").string();
}

PlayInputOptions raw_options() {
  PlayInputOptions o;
  o.source.raw_dims = tsp::Dims{8, 8, 8};
  return o;
}

// Hooks that build for real and count the builds.
PlayBuildHooks counting_hooks(int& builds, std::vector<std::string>& said) {
  PlayBuildHooks h;
  h.say = [&said](const std::string& line) { said.push_back(line); };
  h.build = [&builds](tsp::VolumeSource& src, const std::string& out, tsp::BuildOptions bo) {
    ++builds;
    return tsp::build_tsp_file(src, out, bo);
  };
  return h;
}

TEST(PlayInput, AChangedSeriesMemberIsRebuilt) {
  // The cache key holds every file the source reads, not only the pattern's text.
  const fs::path dir = tsptest::temp_dir();
  const std::string input = raw_series(dir);
  int builds = 0;
  std::vector<std::string> said;
  const auto hooks = counting_hooks(builds, said);
  const std::string a = prepare_play_input(input, raw_options(), (dir / "cache").string(), hooks);
  EXPECT_EQ(prepare_play_input(input, raw_options(), (dir / "cache").string(), hooks), a);
  EXPECT_EQ(builds, 1) << "unchanged: reused";
  {  // the middle member rewritten, same size, a later time
    std::fstream io(dir / "u_0001.raw", std::ios::in | std::ios::out | std::ios::binary);
    const float big = 1000.f;
    io.seekp(100 * sizeof(float));
    io.write(reinterpret_cast<const char*>(&big), sizeof big);
  }
  fs::last_write_time(dir / "u_0001.raw",
                      fs::last_write_time(dir / "u_0001.raw") + std::chrono::seconds(5));
  const std::string b = prepare_play_input(input, raw_options(), (dir / "cache").string(), hooks);
  EXPECT_NE(b, a);
  EXPECT_EQ(builds, 2) << "a member changed: rebuilt";
  EXPECT_GE(tsp::TspFile::open(b)->metadata().data_range.hi, 1000.0);
}

TEST(PlayInput, AnEntryThatIsNotThisUsersTspIsReplacedNeverWrittenThrough) {
  const fs::path dir = tsptest::temp_dir();
  const std::string input = raw_series(dir);
  const std::string cache = (dir / "cache").string();
  auto source = tsp::open_input(input, raw_options().source, {});
  const std::string entry = play_cache_path(input, raw_options(), cache, source->files());
  fs::create_directories(fs::path(entry).parent_path());
  { std::ofstream(dir / "victim.txt") << "precious"; }
  int builds = 0;
  std::vector<std::string> said;
  const auto hooks = counting_hooks(builds, said);
  // A link planted at the entry's name (another user of a shared cache folder), then a FIFO.
  fs::create_symlink(dir / "victim.txt", entry);
  EXPECT_EQ(prepare_play_input(input, raw_options(), cache, hooks), entry);
  EXPECT_EQ(tsptest::read_file(dir / "victim.txt"), "precious");
  EXPECT_FALSE(fs::is_symlink(entry));
  EXPECT_TRUE(is_tsp_file(entry));
  ASSERT_FALSE(said.empty());
  EXPECT_NE(said[0].find("was a symbolic link"), std::string::npos) << said[0];
  fs::remove(entry);
  ASSERT_EQ(::mkfifo(entry.c_str(), 0600), 0);
  EXPECT_EQ(prepare_play_input(input, raw_options(), cache, hooks), entry);  // never hangs
  EXPECT_TRUE(is_tsp_file(entry));
  EXPECT_EQ(builds, 2);
  // A folder with files in it cannot be replaced: refused, naming it.
  fs::remove(entry);
  fs::create_directories(fs::path(entry) / "sub");
  const std::string m = tsptest::error_of<tsp::IoError>(
      [&] { prepare_play_input(input, raw_options(), cache, hooks); });
  EXPECT_NE(m.find(entry), std::string::npos) << m;
  EXPECT_NE(m.find("a folder"), std::string::npos) << m;
}

}  // namespace
}  // namespace tspgl
