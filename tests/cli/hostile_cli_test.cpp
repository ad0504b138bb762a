// Hostile inputs and options end to end: exit codes, messages naming the file and the limit,
// inputs never overwritten, reports never lost to a non-UTF-8 name, constant fields rendered,
// and nothing left behind by a killed build.
#include <gtest/gtest.h>
#include <signal.h>
#include <poll.h>
#include <sys/inotify.h>
#include <sys/wait.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>

#include "support/paths.h"

namespace {

namespace fs = std::filesystem;
using nlohmann::json;
using tsptest::quote;
using tsptest::run_tspplay;

// Writes steps raw float32 files name_000T.raw of 4³ samples, value(t, i).
template <class F>
void write_raw_series(const fs::path& dir, const std::string& name, int steps, F value) {
  for (int t = 0; t < steps; ++t) {
    char file[64];
    std::snprintf(file, sizeof file, "%s_%04d.raw", name.c_str(), t);
    std::ofstream out(dir / file, std::ios::binary);
    for (int i = 0; i < 64; ++i) {
      const float v = value(t, i);
      out.write(reinterpret_cast<const char*>(&v), sizeof v);
    }
  }
}

TEST(HostileCli, OutputNamedLikeAnInputIsRefusedAndTheInputKept) {
  const auto dir = tsptest::temp_dir();
  write_raw_series(dir, "u", 3, [](int t, int i) { return float(t * 100 + i); });
  const std::string before = tsptest::read_file(dir / "u_0001.raw");
  auto r = run_tspplay("build " + quote(dir / "u_%04d.raw") + " --raw-dims 4,4,4 -o " +
                       quote(dir / "u_0001.raw"));
  EXPECT_EQ(r.exit_code, 2) << r.err;
  EXPECT_NE(r.err.find("the output is the input file"), std::string::npos) << r.err;
  EXPECT_EQ(tsptest::read_file(dir / "u_0001.raw"), before);
}

TEST(HostileCli, FifoInputFailsAtOnce) {
  const auto dir = tsptest::temp_dir();
  ASSERT_EQ(mkfifo((dir / "p.raw").c_str(), 0600), 0);
  // (A hang would end only at ctest's timeout, as a failure.)
  auto r = run_tspplay("build " + quote(dir / "p.raw") + " --raw-dims 4,4,4 -o " +
                       quote(dir / "o.tsp"));
  EXPECT_EQ(r.exit_code, 1) << r.err;
  EXPECT_NE(r.err.find("is not a regular file"), std::string::npos) << r.err;
}

TEST(HostileCli, NonUtf8NamesDoNotLoseTheReport) {
  const auto dir = tsptest::temp_dir();
  write_raw_series(dir, "s\xe9rie", 2, [](int t, int i) { return float(t + i % 7); });
  const fs::path tsp_path = dir / "caf\xe9.tsp";
  auto b = run_tspplay("build " + quote(dir / "s\xe9rie_%04d.raw") + " --raw-dims 4,4,4 -o " +
                       quote(tsp_path));
  ASSERT_EQ(b.exit_code, 0) << b.err;
  auto info = run_tspplay("info " + quote(tsp_path) + " --json");
  ASSERT_EQ(info.exit_code, 0) << info.err;
  const json j = json::parse(info.out);  // valid UTF-8 JSON
  EXPECT_NE(j["file"].get<std::string>().find("caf"), std::string::npos);
  auto m = run_tspplay("metrics " + quote(tsp_path) + " --tf preset:filled --json");
  ASSERT_EQ(m.exit_code, 0) << m.err;
  EXPECT_NO_THROW(json::parse(m.out));
  auto r = run_tspplay("render " + quote(tsp_path) + " --size 32x24 -o " + quote(dir / "fr\xe9"));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_TRUE(fs::exists(dir / "fr\xe9" / "frames.json"));
}

TEST(HostileCli, ConstantFieldBuildsRendersAndMeasures) {
  const auto dir = tsptest::temp_dir();
  write_raw_series(dir, "c", 3, [](int, int) { return 4.25f; });
  const auto tsp_path = dir / "c.tsp";
  ASSERT_EQ(run_tspplay("build " + quote(dir / "c_%04d.raw") + " --raw-dims 4,4,4 -o " +
                        quote(tsp_path)).exit_code, 0);
  auto r = run_tspplay("render " + quote(tsp_path) + " --tf preset:filled --size 40x30 -o " +
                       quote(dir / "frames"));
  EXPECT_EQ(r.exit_code, 0) << r.err;
  EXPECT_TRUE(fs::exists(dir / "frames" / "step_0002.png"));
  auto m = run_tspplay("metrics " + quote(tsp_path) + " --tf preset:filled --metric perceptual");
  EXPECT_EQ(m.exit_code, 0) << m.err;
}

TEST(HostileCli, NumericOptionsOutsideTheirRangeNameTheLimit) {
  const auto dir = tsptest::temp_dir();
  write_raw_series(dir, "v", 2, [](int t, int i) { return float(t * i); });
  const auto tsp_path = dir / "v.tsp";
  ASSERT_EQ(run_tspplay("build " + quote(dir / "v_%04d.raw") + " --raw-dims 4,4,4 -o " +
                        quote(tsp_path)).exit_code, 0);
  struct Case {
    std::string args, needle;
  };
  for (const Case& c : {Case{"--spacing 1e-5", "[0.015625, 64] (voxels)"},
                        Case{"--spacing 1e-300", "[0.015625, 64] (voxels)"},
                        Case{"--spacing nan", "--spacing"},
                        Case{"--texture-budget 1e30", "--texture-budget"},
                        Case{"--spatial-tol inf", "expected a finite number >= 0"},
                        Case{"--passes 0", "--passes 0"},
                        Case{"--lod auto --focus nan,1,1", "three finite numbers"},
                        Case{"--scale 1,inf,1", "three finite numbers"}}) {
    auto r = run_tspplay("render " + quote(tsp_path) + " " + c.args + " -o " + quote(dir / "f"));
    EXPECT_EQ(r.exit_code, 2) << c.args << ": " << r.err;
    EXPECT_NE(r.err.find(c.needle), std::string::npos) << c.args << ": " << r.err;
  }
  EXPECT_FALSE(fs::exists(dir / "f" / "step_0000.png"));
  auto e = run_tspplay("build " + quote(dir / "v_%04d.raw") + " --raw-dims 4,4,4 -o ''");
  EXPECT_EQ(e.exit_code, 2) << e.err;
  auto g = run_tspplay("build " + quote(dir / "v_%04d.raw") +
                       " --raw-dims 4,4,4 --range=-1e308:1e308 -o " + quote(dir / "w.tsp"));
  EXPECT_EQ(g.exit_code, 2) << g.err;
  EXPECT_NE(g.err.find("width"), std::string::npos) << g.err;
}

// A build killed with SIGKILL leaves its temporary behind; the next build of the same output
// removes it (its writer's lock is gone) and leaves exactly the finished file.
// bench --rounds has an upper bound (a huge count ran for ever), and a player script's field that
// the file does not have is an error naming the fields it has (it exited 0).
TEST(HostileCli, BenchRoundsAndScriptFieldsAreChecked) {
  const auto dir = tsptest::temp_dir();
  write_raw_series(dir, "v", 2, [](int t, int i) { return float(t * i); });
  const auto tsp_path = dir / "v.tsp";
  ASSERT_EQ(run_tspplay("build " + quote(dir / "v_%04d.raw") + " --raw-dims 4,4,4 -o " +
                        quote(tsp_path)).exit_code, 0);
  auto b = run_tspplay("bench " + quote(tsp_path) + " --rounds 1000000000 -o " + quote(dir / "b"));
  EXPECT_EQ(b.exit_code, 2) << b.err;
  EXPECT_NE(b.err.find("--rounds 1000000000: expected 1 to 100"), std::string::npos) << b.err;
  EXPECT_FALSE(fs::exists(dir / "b" / "report.json"));
  const auto script = dir / "field.txt";
  std::ofstream(script) << "field nosuchfield\nquit\n";
  auto p = run_tspplay("play " + quote(tsp_path) + " --size 32x24 --script " + quote(script));
  TSPTEST_REQUIRE(p.err.find("no display") == std::string::npos &&
                     p.err.find("GLFW") == std::string::npos,
                 "no display (run under xvfb-run): " << p.err);
  EXPECT_EQ(p.exit_code, 2) << p.err;
  EXPECT_NE(p.err.find("field.txt:1: field 'nosuchfield'"), std::string::npos) << p.err;
}

TEST(HostileCli, KilledBuildLeavesNothingAfterTheNextBuild) {
  const auto dir = tsptest::temp_dir();
  const auto h5 = dir / "big.h5";
  ASSERT_EQ(run_tspplay("generate shock -o " + quote(h5) + " --dims 96 --steps 24").exit_code, 0);
  const auto out = dir / "run.tsp";
  // Told by the kernel when the build creates its temporary (inotify), not by polling.
  const int watch = inotify_init1(IN_CLOEXEC);
  ASSERT_GE(watch, 0);
  ASSERT_GE(inotify_add_watch(watch, dir.c_str(), IN_CREATE), 0);
  const pid_t pid = fork();
  ASSERT_GE(pid, 0);
  if (pid == 0) {
    const std::string bin = tsptest::tspplay_bin().string();
    execl(bin.c_str(), bin.c_str(), "build", h5.c_str(), "--field", "shock", "--brick", "8", "-o",
          out.c_str(), static_cast<char*>(nullptr));
    _exit(127);
  }
  auto temporaries = [&] {
    int n = 0;
    for (const auto& e : fs::directory_iterator(dir))
      n += e.path().filename().string().rfind(".run.tsp.tmp-", 0) == 0;
    return n;
  };
  constexpr int kGuardMs = 120000;  // a guard against a hang, not a timing: never reached
  // Kill it as soon as its temporary exists (pass 2 writes the output; a 96³ × 24 build takes
  // far longer than a kill).
  alignas(inotify_event) char events[4096];
  for (bool created = false; !created;) {
    pollfd ready{watch, POLLIN, 0};
    ASSERT_EQ(poll(&ready, 1, kGuardMs), 1) << "no temporary within the guard: the build failed?";
    const ssize_t n = read(watch, events, sizeof events);
    ASSERT_GT(n, 0);
    for (ssize_t at = 0; at < n;) {
      const auto* e = reinterpret_cast<const inotify_event*>(events + at);
      created |= e->len > 0 && std::string(e->name).rfind(".run.tsp.tmp-", 0) == 0;
      at += ssize_t(sizeof(inotify_event) + e->len);
    }
  }
  close(watch);
  kill(pid, SIGKILL);
  int status = 0;
  waitpid(pid, &status, 0);
  ASSERT_TRUE(WIFSIGNALED(status)) << "the build finished before it could be killed";
  EXPECT_EQ(temporaries(), 1);
  EXPECT_FALSE(fs::exists(out));
  auto r = run_tspplay("build " + quote(h5) + " --field shock --brick 16 -o " + quote(out));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(temporaries(), 0);
  EXPECT_TRUE(fs::exists(out));
}

}  // namespace
