#include <cstdlib>
#include "support/paths.h"

#include <gtest/gtest.h>
#include <sys/wait.h>

#include <atomic>
#include <cstdio>
#include <fstream>
#include <sstream>
#include <unistd.h>

namespace fs = std::filesystem;

namespace tsptest {
fs::path test_data_dir() { return TSP_TEST_DATA_DIR; }
bool under_ci() {
  const char* ci = std::getenv("CI");
  return ci && (std::string(ci) == "true" || std::string(ci) == "1");
}
fs::path shared_data_dir() { return TSP_SHARED_DATA_DIR; }
fs::path katrina_file() {
  return shared_data_dir() / "wrf-katrina" / "ci_test_file.nc";
}
fs::path datasets_dir() { return TSP_DATASETS_DIR; }
fs::path tspplay_bin() { return TSPPLAY_BIN; }
fs::path tspplay_mpi_bin() { return TSPPLAY_MPI_BIN; }
fs::path mpiexec_bin() { return TSPPLAY_MPIEXEC; }

namespace {
struct TempRoot {
  fs::path root;
  TempRoot() {
    std::string tmpl = (fs::temp_directory_path() / "tsptest-XXXXXX").string();
    root = mkdtemp(tmpl.data());
  }
  ~TempRoot() {
    std::error_code ec;
    if (!getenv("TSPTEST_KEEP")) fs::remove_all(root, ec);
  }
};
TempRoot& temp_root() {
  static TempRoot r;
  return r;
}
std::string slurp(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}
}  // namespace

std::string read_file(const fs::path& p) { return slurp(p); }

fs::path temp_dir() {
  static std::atomic<int> counter{0};
  const auto* info = testing::UnitTest::GetInstance()->current_test_info();
  std::string name = info ? std::string(info->test_suite_name()) + "." + info->name() : "global";
  for (char& c : name)
    if (c == '/') c = '_';
  fs::path dir = temp_root().root / (name + "-" + std::to_string(counter++));
  fs::create_directories(dir);
  return dir;
}

RunResult run_tspplay(const std::string& args) {
  // Each window a test opens starts from an empty cache folder of its own: no session (nor
  // tuning) one `play` keeps is restored by the next, within a test or across tests. A test
  // that means two windows to share one names --cache-dir, which wins.
  std::string env;
  if (args.rfind("play ", 0) == 0)
    env = "TSPPLAY_CACHE_DIR='" + (temp_dir() / "play-cache").string() + "' ";
  return run_command(env + "'" + tspplay_bin().string() + "' " + args);
}

RunResult run_command(const std::string& command) {
  fs::path dir = temp_dir();
  fs::path out = dir / "stdout.txt", err = dir / "stderr.txt";
  std::string cmd =
      command + " </dev/null >'" + out.string() + "' 2>'" + err.string() + "'";
  int status = std::system(cmd.c_str());
  RunResult r;
  r.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  r.out = slurp(out);
  r.err = slurp(err);
  return r;
}
}  // namespace tsptest
