// Hostile outputs end to end (issue 28 items 1-5): an existing device node or FIFO at the output
// path is refused and kept; an output that is an input is refused and the input kept; a failed
// ffmpeg keeps the old movie; a failed or interrupted re-render keeps the old folder of frames;
// a failed build keeps the old .tsp and names the input; a full disk names the folder asked for.
#include <fcntl.h>
#include <gtest/gtest.h>
#include <hdf5.h>
#include <signal.h>
#include <sys/stat.h>
#include <sys/sysmacros.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <limits>
#include <map>
#include <nlohmann/json.hpp>
#include <vector>

#include "support/json_file.h"
#include "support/paths.h"

namespace {

namespace fs = std::filesystem;
using tsptest::quote;
using tsptest::run_tspplay;

// A small .tsp (4 steps) under dir, built once per test.
fs::path small_tsp(const fs::path& dir) {
  const fs::path h5 = dir / "s.h5", tsp = dir / "s.tsp";
  EXPECT_EQ(run_tspplay("generate shock -o " + quote(h5) + " --dims 12 --steps 4").exit_code, 0);
  EXPECT_EQ(run_tspplay("build " + quote(h5) + " -o " + quote(tsp)).exit_code, 0);
  return tsp;
}

// Writes an executable `ffmpeg` shell script with body into dir/bin and returns the command
// prefix that puts it first on PATH. The script's last argument is the output file.
std::string fake_ffmpeg(const fs::path& dir, const std::string& body) {
  fs::create_directories(dir / "bin");
  const fs::path script = dir / "bin" / "ffmpeg";
  std::ofstream(script) << "#!/bin/sh\nfor last; do :; done\n" << body << "\n";
  fs::permissions(script, fs::perms::owner_all);
  return "PATH=" + quote(dir / "bin") + ":\"$PATH\" ";
}

// Runs tspplay ARGS with the fake ffmpeg of fake_ffmpeg first on PATH.
tsptest::RunResult run_with(const std::string& path_prefix, const std::string& args) {
  return tsptest::run_command(path_prefix + quote(tsptest::tspplay_bin()) + " " + args);
}

// The hidden temporaries (files or folders starting with '.') left in dir.
std::vector<std::string> temporaries(const fs::path& dir) {
  std::vector<std::string> found;
  for (const auto& e : fs::directory_iterator(dir))
    if (e.path().filename().string()[0] == '.') found.push_back(e.path().filename().string());
  return found;
}

// Every file of a folder with its bytes.
std::map<std::string, std::string> folder_contents(const fs::path& dir) {
  std::map<std::string, std::string> files;
  for (const auto& e : fs::directory_iterator(dir))
    files[e.path().filename().string()] = tsptest::read_file(e.path());
  return files;
}

bool is_fifo_node(const fs::path& p) {
  struct stat st {};
  return ::lstat(p.c_str(), &st) == 0 && S_ISFIFO(st.st_mode);
}

bool is_char_device(const fs::path& p) {
  struct stat st {};
  return ::lstat(p.c_str(), &st) == 0 && S_ISCHR(st.st_mode);
}

// Issue 28 item 1: build, generate, diff, render --save-tf and --movie replaced an existing
// device node or FIFO at the output path with a regular file and exited 0.
TEST(HostileOutput, DeviceNodesAndFifosAtTheOutputAreRefusedAndKept) {
  const fs::path dir = tsptest::temp_dir();
  const fs::path tsp = small_tsp(dir);
  const fs::path h5 = dir / "s.h5";
  ASSERT_EQ(run_tspplay("render " + quote(tsp) + " --steps 0 --size 16x12 -o " +
                        quote(dir / "png")).exit_code, 0);
  const fs::path png = dir / "png" / "step_0000.png";
  const std::string ffmpeg = fake_ffmpeg(dir, "printf GIF89a > \"$last\"");
  // The same node (a null device made here, never the machine's /dev/null) or FIFO for each kind.
  const fs::path nodes = dir / "nodes";
  fs::create_directory(nodes);
  const bool have_device = ::mknod((nodes / "dev.gif").c_str(), S_IFCHR | 0666, makedev(1, 3)) == 0;
  if (!have_device) std::printf("(no mknod here: FIFOs only)\n");
  ASSERT_EQ(::mkfifo((nodes / "fifo.gif").c_str(), 0600), 0);
  std::vector<std::pair<fs::path, std::string>> targets = {{nodes / "fifo.gif", "is a FIFO"}};
  if (have_device) targets.push_back({nodes / "dev.gif", "is a character device"});
  for (const auto& [node, kind] : targets) {
    const std::vector<std::string> commands = {
        "build " + quote(h5) + " -o " + quote(node),
        "generate shock --dims 8 --steps 2 -o " + quote(node),
        "diff " + quote(png) + " " + quote(png) + " -o " + quote(node),
        "render " + quote(tsp) + " --steps 0 --size 16x12 -o " + quote(dir / "r") +
            " --save-tf " + quote(node),
        "render " + quote(tsp) + " --steps 0 --size 16x12 -o " + quote(dir / "r") + " --movie " +
            quote(node)};
    for (const std::string& c : commands) {
      auto r = run_with(ffmpeg, c);
      EXPECT_EQ(r.exit_code, 1) << c << "\n" << r.err;
      EXPECT_NE(r.err.find(node.string() + ": " + kind), std::string::npos) << c << "\n" << r.err;
      EXPECT_TRUE(node.filename() == "fifo.gif" ? is_fifo_node(node) : is_char_device(node)) << c;
      EXPECT_TRUE(temporaries(nodes).empty()) << c;
    }
  }
  EXPECT_FALSE(fs::exists(dir / "r"));  // a refused render wrote no frames either
}

// Issue 28 item 2: inputs overwritten with exit 0 by diff -o, play --screenshot, the player
// script's screenshot and stats, and render -o into a folder holding its input as a frame name.
TEST(HostileOutput, OutputsThatAreInputsAreRefusedAndTheInputsKept) {
  const fs::path dir = tsptest::temp_dir();
  const fs::path tsp = small_tsp(dir);
  const std::string tsp_bytes = tsptest::read_file(tsp);
  ASSERT_EQ(run_tspplay("render " + quote(tsp) + " --steps 0:1 --size 16x12 -o " +
                        quote(dir / "png")).exit_code, 0);
  const fs::path a = dir / "png" / "step_0000.png", b = dir / "png" / "step_0001.png";
  const std::string a_bytes = tsptest::read_file(a);
  fs::create_hard_link(a, dir / "alias.png");
  for (const fs::path& out : {a, dir / "alias.png"}) {
    auto r = run_tspplay("diff " + quote(a) + " " + quote(b) + " -o " + quote(out));
    EXPECT_EQ(r.exit_code, 2) << r.err;
    EXPECT_NE(r.err.find("the output is the input file"), std::string::npos) << r.err;
    EXPECT_TRUE(tsptest::read_file(a) == a_bytes) << "a.png changed";
  }
  // render's input named like a frame of the folder it would replace, and its TF as frames.json.
  const fs::path frames = dir / "frames";
  fs::create_directory(frames);
  fs::copy_file(tsp, frames / "step_0000.png");
  auto r = run_tspplay("render " + quote(frames / "step_0000.png") + " --steps 0 --size 16x12 -o " +
                       quote(frames));
  EXPECT_EQ(r.exit_code, 2) << r.err;
  EXPECT_NE(r.err.find("step_0000.png is the input file"), std::string::npos) << r.err;
  EXPECT_TRUE(tsptest::read_file(frames / "step_0000.png") == tsp_bytes) << "the input changed";
  ASSERT_EQ(run_tspplay("render " + quote(tsp) + " --steps 0 --size 16x12 -o " + quote(dir / "t") +
                        " --save-tf " + quote(frames / "frames.json")).exit_code, 0);
  const std::string tf_bytes = tsptest::read_file(frames / "frames.json");
  r = run_tspplay("render " + quote(tsp) + " --tf " + quote(frames / "frames.json") +
                  " --steps 0 --size 16x12 -o " + quote(frames));
  EXPECT_EQ(r.exit_code, 2) << r.err;
  EXPECT_NE(r.err.find("frames.json is the input file"), std::string::npos) << r.err;
  EXPECT_EQ(tsptest::read_file(frames / "frames.json"), tf_bytes);
  EXPECT_TRUE(temporaries(dir).empty());
}

// The player: --screenshot, and a script's screenshot and stats, aimed at the played file. (A
// test of its own: it opens a window, so the sanitizer suite runs it with the window tests.)
TEST(HostileOutputWindow, ScreenshotsAndStatsAimedAtThePlayedFileAreRefused) {
  const fs::path dir = tsptest::temp_dir();
  const fs::path tsp = small_tsp(dir);
  const std::string tsp_bytes = tsptest::read_file(tsp);
  auto p = run_tspplay("play " + quote(tsp) + " --size 32x24 --screenshot " + quote(tsp));
  EXPECT_EQ(p.exit_code, 2) << p.err;
  EXPECT_NE(p.err.find("the output is the input file"), std::string::npos) << p.err;
  for (const char* action : {"screenshot", "stats"}) {
    const fs::path script = dir / (std::string(action) + ".txt");
    std::ofstream(script) << action << " " << tsp.string() << "\nquit\n";
    p = run_tspplay("play " + quote(tsp) + " --size 32x24 --script " + quote(script));
    TSPTEST_REQUIRE(p.err.find("no display") == std::string::npos &&
                        p.err.find("GLFW") == std::string::npos,
                    "no display (run under xvfb-run): " << p.err);
    EXPECT_EQ(p.exit_code, 2) << action << "\n" << p.err;
    EXPECT_NE(p.err.find("the output is the input file"), std::string::npos) << p.err;
    EXPECT_TRUE(tsptest::read_file(tsp) == tsp_bytes) << action << " changed the played file";
  }
}

// Issue 28 items 4 and 5: ffmpeg reported "No space left on device" yet exited 0, and the old
// movie was replaced by a broken one; a re-render replaced frames one by one, so a failed run left
// new frames beside old ones. The folder is now replaced as a whole, the movie only when ffmpeg
// succeeded, and a user's other files in the folder are kept.
TEST(HostileOutput, AFailedMovieOrRenderKeepsTheOldMovieAndFrames) {
  const fs::path dir = tsptest::temp_dir();
  const fs::path tsp = small_tsp(dir);
  const fs::path out = dir / "out", movie = dir / "m.gif";
  const std::string good = fake_ffmpeg(dir / "good", "printf GIF89a-new > \"$last\"");
  ASSERT_EQ(run_with(good, "render " + quote(tsp) + " --size 16x12 -o " + quote(out) +
                               " --movie " + quote(movie)).exit_code, 0);
  std::ofstream(out / "notes.txt") << "mine";
  std::ofstream(movie) << "GIF89a-old";
  const auto old_frames = folder_contents(out);
  ASSERT_EQ(old_frames.size(), 6u);  // 4 steps, frames.json, notes.txt

  const std::string full = fake_ffmpeg(
      dir / "full", "printf GIF8 > \"$last\"\n"
                    "echo '[out#0/gif] Error writing trailer: No space left on device' >&2");
  const std::string failing = fake_ffmpeg(dir / "failing", "printf GIF8 > \"$last\"\nexit 1");
  for (const std::string& ffmpeg : {full, failing}) {
    auto r = run_with(ffmpeg, "render " + quote(tsp) + " --view 60,10 --size 16x12 -o " +
                                  quote(out) + " --movie " + quote(movie));
    EXPECT_EQ(r.exit_code, 1) << r.err;
    EXPECT_NE(r.err.find("m.gif: ffmpeg failed"), std::string::npos) << r.err;
    EXPECT_EQ(ffmpeg == full, r.err.find("No space left on device") != std::string::npos) << r.err;
    EXPECT_EQ(tsptest::read_file(movie), "GIF89a-old");
    EXPECT_TRUE(folder_contents(out) == old_frames) << "the old frames changed";
    EXPECT_TRUE(temporaries(dir).empty()) << temporaries(dir).front();
    EXPECT_TRUE(temporaries(out).empty());
  }
  // A successful re-render of fewer steps: the old set goes as a whole, notes.txt stays.
  auto r = run_tspplay("render " + quote(tsp) + " --steps 0:1 --size 16x12 -o " + quote(out));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  std::vector<std::string> names;
  for (const auto& [name, bytes] : folder_contents(out)) names.push_back(name);
  EXPECT_EQ(names, (std::vector<std::string>{"frames.json", "notes.txt", "step_0000.png",
                                             "step_0001.png"}));
  EXPECT_EQ(tsptest::read_file(out / "notes.txt"), "mine");
  const auto j = tsptest::frames_json(out);
  EXPECT_EQ(j["frames"].size(), 2u);
  EXPECT_TRUE(temporaries(dir).empty());
  // A movie inside a new output folder lands there beside the frames.
  r = run_with(good, "render " + quote(tsp) + " --steps 0 --size 16x12 -o " + quote(dir / "in") +
                         " --movie " + quote(dir / "in" / "m.gif"));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(tsptest::read_file(dir / "in" / "m.gif"), "GIF89a-new");
  EXPECT_TRUE(fs::exists(dir / "in" / "step_0000.png"));
  EXPECT_TRUE(temporaries(dir / "in").empty());
}

TEST(HostileOutput, AFullDiskNamesTheFolderAskedForNotItsTemporary) {
  // A 4 KiB file size limit (SIGXFSZ ignored) fails the PNG writes as a full disk would
  // (EFBIG); stderr, a few lines, stays under it.
  const fs::path dir = tsptest::temp_dir();
  const fs::path tsp = small_tsp(dir);
  const fs::path out = dir / "frames";
  const auto r = tsptest::run_command("trap '' XFSZ; ulimit -f 8; " +
                                      quote(tsptest::tspplay_bin()) + " render " + quote(tsp) +
                                      " --size 640x480 -o " + quote(out));
  EXPECT_EQ(r.exit_code, 1) << r.err;
  EXPECT_NE(r.err.find(out.string() + "/"), std::string::npos) << r.err;
  EXPECT_EQ(r.err.find(".tmp-"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(out));
  EXPECT_TRUE(temporaries(dir).empty());
}

// Issue 28 item 5: SIGINT (or SIGTERM) killed render by the signal, leaving partial frames and
// a temporary movie. The signal is sent while the (fake) encoder runs: every new frame is
// written then, nothing is committed yet. The fake encoder says it started on a pipe the test
// reads, so no sleep or timing decides when the signal comes.
TEST(HostileOutput, AnInterruptedRenderKeepsTheOldSetAndLeavesNoTemporaries) {
  const fs::path dir = tsptest::temp_dir();
  const fs::path tsp = small_tsp(dir);
  const fs::path out = dir / "out", movie = dir / "m.gif";
  ASSERT_EQ(run_tspplay("render " + quote(tsp) + " --size 16x12 -o " + quote(out)).exit_code, 0);
  std::ofstream(movie) << "GIF89a-old";
  const auto old_frames = folder_contents(out);
  // Fake ffmpeg: writes its process id on descriptor 9, then waits to be stopped (its output
  // away from the test's, so that nothing waits for it if it outlived a failing run).
  fake_ffmpeg(dir, "echo $$ >&9\nexec sleep 600 >/dev/null 2>&1 9>&-");
  const std::string path = (dir / "bin").string() + ":" + std::getenv("PATH");
  for (const int sig : {SIGINT, SIGTERM}) {
    int ready[2];
    ASSERT_EQ(::pipe(ready), 0);
    const fs::path err = dir / "stderr.txt";
    const pid_t pid = ::fork();
    ASSERT_GE(pid, 0);
    if (pid == 0) {
      ::dup2(ready[1], 9);
      ::close(ready[0]);
      ::setenv("PATH", path.c_str(), 1);
      const int e = ::open(err.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0600);
      ::dup2(e, 2);
      const std::string bin = tsptest::tspplay_bin().string();
      ::execl(bin.c_str(), bin.c_str(), "render", tsp.c_str(), "--view", "60,10", "--size",
              "16x12", "-o", out.c_str(), "--movie", movie.c_str(), static_cast<char*>(nullptr));
      ::_exit(127);
    }
    ::close(ready[1]);
    char line[16] = {};
    const ssize_t n = ::read(ready[0], line, sizeof line - 1);  // EOF if render ended first
    ::close(ready[0]);
    ASSERT_GT(n, 0) << "render ended before the encoder started";
    const pid_t encoder = pid_t(std::atol(line));
    ::kill(pid, sig);
    int status = 0;
    ::waitpid(pid, &status, 0);
    if (::kill(encoder, 0) == 0) {  // render did not stop it (the test fails below)
      ADD_FAILURE() << "the encoder outlived render";
      ::kill(encoder, SIGKILL);
    }
    ASSERT_TRUE(WIFEXITED(status)) << "ended by signal " << WTERMSIG(status);
    EXPECT_EQ(WEXITSTATUS(status), 1);
    const std::string message = tsptest::read_file(err);
    EXPECT_NE(message.find(sig == SIGINT ? "interrupted by SIGINT" : "interrupted by SIGTERM"),
              std::string::npos) << message;
    EXPECT_TRUE(folder_contents(out) == old_frames) << "the old frames changed";
    EXPECT_EQ(tsptest::read_file(movie), "GIF89a-old");
    const auto left = temporaries(dir);
    EXPECT_TRUE(left.empty()) << left.front();
    EXPECT_TRUE(temporaries(out).empty());
  }
}

// Issue 28 item 3: a VTKHDF mesh with NaN in Steps/Values built, replaced keep.tsp with a file
// the reader refuses and reported the error under keep.tsp's name.
TEST(HostileOutput, AFailedBuildKeepsTheOldTspAndNamesTheInput) {
  const fs::path dir = tsptest::temp_dir();
  const fs::path good = tsptest::test_data_dir() / "vtu" / "transient.hdf";
  const fs::path bad = dir / "nan_times.hdf", keep = dir / "keep.tsp";
  fs::copy_file(good, bad);
  {
    const hid_t f = H5Fopen(bad.c_str(), H5F_ACC_RDWR, H5P_DEFAULT);
    ASSERT_GE(f, 0);
    const hid_t d = H5Dopen2(f, "/VTKHDF/Steps/Values", H5P_DEFAULT);
    ASSERT_GE(d, 0);
    const hid_t space = H5Dget_space(d);
    const hssize_t n = H5Sget_simple_extent_npoints(space);
    std::vector<double> v(std::size_t(n), std::numeric_limits<double>::quiet_NaN());
    EXPECT_GE(H5Dwrite(d, H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, v.data()), 0);
    H5Sclose(space);
    H5Dclose(d);
    H5Fclose(f);
  }
  auto r = run_tspplay("build " + quote(good) + " --field f --resolution 16 -o " + quote(keep));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const std::string before = tsptest::read_file(keep);
  r = run_tspplay("build " + quote(bad) + " --field f --resolution 16 -o " + quote(keep));
  EXPECT_EQ(r.exit_code, 1) << r.err;
  EXPECT_NE(r.err.find("nan_times.hdf"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("time of step 0 is not a finite number"), std::string::npos) << r.err;
  EXPECT_EQ(r.err.find("keep.tsp"), std::string::npos) << r.err;
  EXPECT_TRUE(tsptest::read_file(keep) == before) << "keep.tsp changed";
  EXPECT_TRUE(temporaries(dir).empty());
  EXPECT_EQ(run_tspplay("info " + quote(keep)).exit_code, 0);
}

}  // namespace
