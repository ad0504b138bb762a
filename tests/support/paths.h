// Paths the tests need, fixed at configure time.
#pragma once
#include <filesystem>
#include <string>

namespace tsptest {
/// Directory of small committed test inputs (tests/data).
std::filesystem::path test_data_dir();
/// The shared real data sets (../shared/data beside the checkout).
std::filesystem::path shared_data_dir();
/// The shared WRF test file (Hurricane Katrina): wrf-katrina/ci_test_file.nc in shared_data_dir().
std::filesystem::path katrina_file();
/// The repository's datasets/ folder.
std::filesystem::path datasets_dir();
/// The built tspplay executable, for CLI tests.
std::filesystem::path tspplay_bin();
/// A fresh, empty temporary directory unique to the calling test; removed at process exit.
std::filesystem::path temp_dir();

/// The bytes of file p (empty when it cannot be read).
std::string read_file(const std::filesystem::path& p);

/// p in single quotes, for the shell command lines run_tspplay takes.
inline std::string quote(const std::filesystem::path& p) { return "'" + p.string() + "'"; }
/// quote(p), short for the many command lines tests write.
inline std::string q(const std::filesystem::path& p) { return quote(p); }

/// Result of running a command line: exit code and captured stdout/stderr.
struct RunResult {
  int exit_code = -1;
  std::string out;
  std::string err;
};
/// The built tspplay-mpi executable and the MPI launcher; empty when MPI was not found.
std::filesystem::path tspplay_mpi_bin();
/// The MPI launcher (mpirun) found with MPI; empty when MPI was not found.
std::filesystem::path mpiexec_bin();
/// Runs a shell command line through /bin/sh (stdin from /dev/null) and captures its output.
RunResult run_command(const std::string& command);
/// Runs `tspplay ARGS` through /bin/sh (args are passed as-is: quote them) and captures its output.
/// `play` runs get an empty cache folder of their own (TSPPLAY_CACHE_DIR; --cache-dir wins).
RunResult run_tspplay(const std::string& args);
/// True under CI (the environment's CI is "true" or "1"): there a missing display, MPI or tool a
/// test needs fails the test instead of skipping it (TSPTEST_REQUIRE).
bool under_ci();
}  // namespace tsptest

/// Goes on when cond holds; otherwise skips the test with `why` — or, under CI (under_ci()),
/// fails it: the suite there has every display, MPI and tool scripts/test.sh installs.
#define TSPTEST_REQUIRE(cond, why)                                        \
  do {                                                                    \
    if (!(cond)) {                                                        \
      if (tsptest::under_ci()) FAIL() << "CI needs this test to run: " << why; \
      GTEST_SKIP() << why;                                                \
    }                                                                     \
  } while (0)
