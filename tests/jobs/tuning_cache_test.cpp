// The playback tunings kept on disk: a round trip per key, and every entry that is not this
// key's tuning (another key or version, a rung the ladder lacks, a FIFO, a planted link) is
// ignored or replaced, never followed.
#include "jobs/tuning_cache.h"

#include <gtest/gtest.h>
#include <sys/stat.h>

#include <filesystem>
#include <fstream>

#include "support/paths.h"

namespace tspgl {
namespace {

namespace fs = std::filesystem;

std::vector<TunedRung> ladder() {
  std::vector<TunedRung> rungs;
  double ms = 100;
  for (const Rung& r : playback_rungs()) {
    TunedRung t;
    t.rung = r;
    t.mean_de = 0.1 * double(rungs.size());
    t.max_step_de = 2 * t.mean_de;
    t.ms = ms;
    ms *= 0.7;
    rungs.push_back(t);
  }
  return rungs;
}

TEST(TuningCache, RoundTripsPerKeyAndIgnoresOtherKeys) {
  const fs::path dir = tsptest::temp_dir();
  const nlohmann::json key = {{"file", "/data/a.tsp"}, {"size", {320, 240}}};
  const std::string path = tuning_cache_path(key, dir.string());
  ASSERT_FALSE(path.empty());
  EXPECT_EQ(fs::path(path).parent_path(), dir / "tuning");
  EXPECT_FALSE(read_tuning(path, key));  // nothing yet
  write_tuning(path, key, ladder());
  const auto back = read_tuning(path, key);
  ASSERT_TRUE(back);
  ASSERT_EQ(back->size(), playback_rungs().size());
  for (std::size_t i = 0; i < back->size(); ++i) {
    EXPECT_STREQ((*back)[i].rung.name, playback_rungs()[i].name);
    EXPECT_DOUBLE_EQ((*back)[i].mean_de, ladder()[i].mean_de);
    EXPECT_DOUBLE_EQ((*back)[i].ms, ladder()[i].ms);
  }
  nlohmann::json other = key;
  other["size"] = {640, 480};
  EXPECT_NE(tuning_cache_path(other, dir.string()), path);
  EXPECT_FALSE(read_tuning(path, other));  // (a hash collision would still be refused)
  EXPECT_EQ(tuning_cache_path(key, "-"), "");
}

TEST(TuningCache, ForeignOrHostileEntriesAreIgnoredOrReplaced) {
  const fs::path dir = tsptest::temp_dir();
  const nlohmann::json key = {{"file", "/data/b.tsp"}};
  const std::string path = tuning_cache_path(key, dir.string());
  fs::create_directories(fs::path(path).parent_path());
  // Another version, an unknown rung, garbage: tuned again.
  std::ofstream(path) << R"({"version": 99, "key": {"file": "/data/b.tsp"}, "rungs": []})";
  EXPECT_FALSE(read_tuning(path, key));
  std::ofstream(path) << R"({"version": 1, "key": {"file": "/data/b.tsp"},
                             "rungs": [{"name": "warp", "mean_de": 0, "max_step_de": 0, "ms": 1}]})";
  EXPECT_FALSE(read_tuning(path, key));
  std::ofstream(path) << "{ not json";
  EXPECT_FALSE(read_tuning(path, key));
  // A FIFO at the name: never blocks the reader; replaced by the writer.
  fs::remove(path);
  ASSERT_EQ(::mkfifo(path.c_str(), 0600), 0);
  EXPECT_FALSE(read_tuning(path, key));
  write_tuning(path, key, ladder());
  EXPECT_TRUE(fs::is_regular_file(path));
  // A link planted at the name: replaced, its target untouched.
  { std::ofstream(dir / "victim.txt") << "precious"; }
  fs::remove(path);
  fs::create_symlink(dir / "victim.txt", path);
  write_tuning(path, key, ladder());
  EXPECT_EQ(tsptest::read_file(dir / "victim.txt"), "precious");
  EXPECT_FALSE(fs::is_symlink(path));
  EXPECT_TRUE(read_tuning(path, key));
}

}  // namespace
}  // namespace tspgl
