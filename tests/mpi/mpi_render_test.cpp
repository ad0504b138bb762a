// tspplay-mpi render (src/mpi/render_driver.*, docs/mpi.md): N ranks write the serial render's
// step PNGs byte for byte and its frames.json (each frame with its rank), rank 0 encodes the
// movie; a failing rank is named and the output folder is left as it was. Runs when MPI was
// found at configure time (scripts/install-deps.sh --mpi).
#include <gtest/gtest.h>
#include <hdf5.h>

#include <filesystem>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "support/mpi_run.h"
#include "support/paths.h"

namespace {

namespace fs = std::filesystem;
using nlohmann::json;
using tsptest::quote;

using tsptest::have_mpi;
using tsptest::run_mpi;

// Every file of dir by name, with its bytes.
std::map<std::string, std::string> files_of(const fs::path& dir) {
  std::map<std::string, std::string> out;
  for (const auto& e : fs::directory_iterator(dir)) out[e.path().filename().string()] = tsptest::read_file(e.path());
  return out;
}

json frames_json(const fs::path& dir) {
  std::ifstream in(dir / "frames.json");
  return json::parse(in);
}

// Entries beside out that a run left behind (hidden temporaries of out or of a movie).
std::vector<std::string> leftovers(const fs::path& parent) {
  std::vector<std::string> out;
  for (const auto& e : fs::directory_iterator(parent))
    if (e.path().filename().string().find(".tmp-") != std::string::npos)
      out.push_back(e.path().filename().string());
  return out;
}

class MpiRender : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    dir_ = new fs::path(tsptest::temp_dir());
    // 7 steps: blocks of 7/2 and 7/3 frames are uneven.
    ASSERT_EQ(tsptest::run_tspplay("generate shock -o " + quote(*dir_ / "s.h5") +
                                   " --dims 32 --steps 7").exit_code, 0);
    const auto b = tsptest::run_tspplay("build " + quote(*dir_ / "s.h5") +
                                        " --field shock --brick 8 -o " + quote(*dir_ / "s.tsp"));
    ASSERT_EQ(b.exit_code, 0) << b.err;
  }
  static void TearDownTestSuite() { delete dir_; }
  static inline fs::path* dir_ = nullptr;
};

// A temporal tolerance (spans of steps share one texture) and an orbit (the camera moves with
// the frame's index): a rank's block must be drawn as in the whole run.
const std::string kOptions = " --size 96x72 --tf preset:filled --temporal-tol 10 --orbit 7 --annotate on";

TEST_F(MpiRender, RanksWriteTheSerialFrames) {
  TSPTEST_REQUIRE(have_mpi(), "MPI not found at configure time (install-deps.sh --mpi)");
  const fs::path tsp = *dir_ / "s.tsp", serial = *dir_ / "serial";
  // All steps; a stride over two passes; the adaptive LOD cut, which carries over from frame to
  // frame (a rank replays the cuts of the frames before its own).
  for (const std::string& extra : {std::string(" --steps 0:6"), std::string(" --steps 1:6:2 --passes 2"),
                                   std::string(" --steps 0:6 --lod auto --split-limit 2")}) {
    fs::remove_all(serial);
    const auto s = tsptest::run_tspplay("render " + quote(tsp) + kOptions + extra + " -o " + quote(serial));
    ASSERT_EQ(s.exit_code, 0) << s.err;
    const auto want = files_of(serial);
    const json want_json = frames_json(serial);
    for (int ranks : {1, 2, 3}) {
      const fs::path out = *dir_ / ("mpi" + std::to_string(ranks));
      const auto r = run_mpi(ranks, "render " + quote(tsp) + kOptions + extra + " -o " + quote(out));
      ASSERT_EQ(r.exit_code, 0) << r.err;
      EXPECT_NE(r.out.find("on " + std::to_string(ranks) + " ranks"), std::string::npos) << r.out;
      const auto got = files_of(out);
      ASSERT_EQ(got.size(), want.size()) << ranks << " ranks" << extra;
      for (const auto& [name, bytes] : want) {
        if (name == "frames.json") continue;
        ASSERT_TRUE(got.count(name)) << name;
        EXPECT_TRUE(got.at(name) == bytes) << name << ", " << ranks << " ranks" << extra;
      }
      const json j = frames_json(out);
      EXPECT_EQ(j["ranks"], ranks);
      ASSERT_EQ(j["frames"].size(), want_json["frames"].size());
      const int per_pass =
          int(j["frames"].size()) / (extra.find("--passes 2") != std::string::npos ? 2 : 1);
      for (std::size_t i = 0; i < j["frames"].size(); ++i) {
        const json& f = j["frames"][i];
        const json& w = want_json["frames"][i];
        EXPECT_EQ(f["step"], w["step"]);
        EXPECT_EQ(f["pass"], w["pass"]);
        EXPECT_EQ(f["azimuth_deg"], w["azimuth_deg"]);
        EXPECT_EQ(f["steps_merged"], w["steps_merged"]) << "frame " << i;
        if (w["lod"].is_object()) {  // the same cut (predicted_ms follows measured times)
          for (const char* key : {"cut_size", "splits", "merges", "nodes_per_level"})
            EXPECT_EQ(f["lod"][key], w["lod"][key]) << key << ", frame " << i;
        }
        // Consecutive blocks: frame k of a pass of n frames is drawn by rank floor(k * N / n)
        // rounded to the block boundaries n * r / N.
        const int k = int(i) % per_pass;
        int rank = 0;
        while (rank + 1 < ranks && k >= per_pass * (rank + 1) / ranks) ++rank;
        EXPECT_EQ(f["rank"], rank) << "frame " << i << ", " << ranks << " ranks";
      }
      for (const char* key : {"file", "mode", "size", "view", "spatial_tol", "temporal_tol"})
        if (want_json.contains(key)) {
          EXPECT_EQ(j[key], want_json[key]) << key;
        }
      EXPECT_EQ(j["rank_contexts"].size(), std::size_t(ranks));
      EXPECT_TRUE(leftovers(*dir_).empty()) << leftovers(*dir_)[0];
    }
  }
}

TEST_F(MpiRender, Rank0EncodesTheMovie) {
  TSPTEST_REQUIRE(have_mpi(), "MPI not found at configure time (install-deps.sh --mpi)");
  TSPTEST_REQUIRE(tsptest::run_command("command -v ffmpeg").exit_code == 0, "ffmpeg not installed");
  const fs::path out = *dir_ / "movie_frames", movie = *dir_ / "m.mp4";
  const auto r = run_mpi(2, "render " + quote(*dir_ / "s.tsp") + kOptions + " --steps 0:6 -o " + quote(out) +
                                " --movie " + quote(movie) + " --save-tf " + quote(*dir_ / "tf.json"));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("(7 frames, 8 a second)"), std::string::npos) << r.out;
  ASSERT_TRUE(fs::exists(movie));
  EXPECT_GT(fs::file_size(movie), 0u);
  const auto probe = tsptest::run_command(
      "ffprobe -v error -count_frames -select_streams v:0 -show_entries stream=nb_read_frames "
      "-of csv=p=0 " + quote(movie));
  if (probe.exit_code == 0) {
    EXPECT_EQ(probe.out, "7\n");
  }
  // --save-tf: the serial command's file.
  const fs::path serial_tf = *dir_ / "serial_tf.json";
  ASSERT_EQ(tsptest::run_tspplay("render " + quote(*dir_ / "s.tsp") + kOptions + " --steps 0 -o " +
                                 quote(*dir_ / "one") + " --save-tf " + quote(serial_tf)).exit_code, 0);
  EXPECT_EQ(tsptest::read_file(*dir_ / "tf.json"), tsptest::read_file(serial_tf));
  EXPECT_FALSE(fs::exists(out / ".rank-0.tf.json"));
  EXPECT_TRUE(leftovers(*dir_).empty()) << leftovers(*dir_)[0];
}

// Every brick of the last step is corrupt: the last rank's frames hit it. The job names that
// rank, exits non-zero and leaves the output folder (and the movie) exactly as they were.
TEST_F(MpiRender, FailingRankIsNamedAndNothingIsWritten) {
  TSPTEST_REQUIRE(have_mpi(), "MPI not found at configure time (install-deps.sh --mpi)");
  const fs::path tsp = *dir_ / "bad.tsp";
  fs::copy_file(*dir_ / "s.tsp", tsp, fs::copy_options::overwrite_existing);
  std::vector<std::pair<haddr_t, hsize_t>> chunks;
  {
    hid_t f = H5Fopen(tsp.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
    ASSERT_GE(f, 0);
    hid_t ds = H5Dopen2(f, "/bricks/data", H5P_DEFAULT);
    ASSERT_GE(ds, 0);
    hsize_t dims[5] = {};
    hid_t space = H5Dget_space(ds);
    ASSERT_EQ(H5Sget_simple_extent_ndims(space), 5);
    H5Sget_simple_extent_dims(space, dims, nullptr);
    H5Sclose(space);
    ASSERT_EQ(dims[1], 7u);  // bricks × steps × samples
    H5Eset_auto2(H5E_DEFAULT, nullptr, nullptr);  // bricks with no chunk are skipped quietly
    for (hsize_t b = 0; b < dims[0]; ++b) {
      hsize_t offset[5] = {b, 6, 0, 0, 0};
      unsigned mask = 0;
      haddr_t addr = 0;
      hsize_t size = 0;
      if (H5Dget_chunk_info_by_coord(ds, offset, &mask, &addr, &size) >= 0 && size > 8)
        chunks.emplace_back(addr, size);
    }
    H5Dclose(ds);
    H5Fclose(f);
  }
  ASSERT_FALSE(chunks.empty());
  {
    std::fstream io(tsp, std::ios::in | std::ios::out | std::ios::binary);
    for (const auto& [addr, size] : chunks) {
      for (hsize_t at : {size / 3, size / 2}) {
        io.seekg(std::streamoff(addr + at));
        char c = 0;
        io.read(&c, 1);
        c = char(c ^ 0x5a);
        io.seekp(std::streamoff(addr + at));
        io.write(&c, 1);
      }
    }
  }
  const fs::path out = *dir_ / "kept", movie = *dir_ / "kept.mp4";
  fs::create_directory(out);
  std::ofstream(out / "step_0000.png") << "an old frame";
  std::ofstream(out / "notes.txt") << "mine";
  std::ofstream(movie) << "an old movie";
  const auto before = files_of(out);
  // No temporal tolerance here: every step's own bricks are read.
  const auto r = run_mpi(3, "render " + quote(tsp) + " --size 96x72 --steps 0:6 -o " + quote(out) +
                                (tsptest::run_command("command -v ffmpeg").exit_code == 0
                                     ? " --movie " + quote(movie) : std::string()));
  EXPECT_NE(r.exit_code, 0);
  EXPECT_NE(r.err.find("tspplay-mpi: rank 2 of 3: error: "), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("step 6"), std::string::npos) << r.err;
  EXPECT_EQ(r.err.find("rank 0 of 3: error"), std::string::npos) << r.err;
  EXPECT_EQ(r.err.find("rank 1 of 3: error"), std::string::npos) << r.err;
  EXPECT_EQ(files_of(out), before);
  EXPECT_EQ(tsptest::read_file(movie), "an old movie");
  EXPECT_TRUE(leftovers(*dir_).empty()) << leftovers(*dir_)[0];
}

// Bad arguments are the serial command's errors, said once, before any rank renders.
TEST_F(MpiRender, BadArgumentsAreTheSerialErrors) {
  TSPTEST_REQUIRE(have_mpi(), "MPI not found at configure time (install-deps.sh --mpi)");
  const fs::path out = *dir_ / "never";
  for (const std::string& args :
       {"render " + quote(*dir_ / "missing.tsp") + " -o " + quote(out),
        "render " + quote(*dir_ / "s.tsp") + " --size 0x0 -o " + quote(out),
        "render " + quote(*dir_ / "s.tsp") + " --steps 3:99 -o " + quote(out),
        "render " + quote(*dir_ / "s.tsp") + " --movie " + quote(*dir_ / "m.avi") + " -o " + quote(out)}) {
    const auto s = tsptest::run_tspplay(args);
    const auto r = run_mpi(2, args);
    ASSERT_NE(s.exit_code, 0) << args;
    EXPECT_EQ(r.exit_code, s.exit_code) << args << "\n" << r.err;
    const std::string said = s.err.substr(s.err.find(": ") + 2);
    EXPECT_NE(r.err.find("tspplay-mpi: " + said), std::string::npos) << r.err << "\nserial: " << s.err;
    EXPECT_EQ(r.err.find(said), r.err.rfind(said)) << "said once: " << r.err;
    EXPECT_FALSE(fs::exists(out));
  }
  const auto h = run_mpi(2, "render --help");
  EXPECT_EQ(h.exit_code, 0) << h.err;
  EXPECT_NE(h.out.find("mpirun -np N tspplay-mpi render"), std::string::npos) << h.out;
  EXPECT_NE(h.out.find("--movie"), std::string::npos) << h.out;
  EXPECT_EQ(h.out.find("--mpi-part"), std::string::npos) << h.out;  // the protocol is hidden
}

}  // namespace
