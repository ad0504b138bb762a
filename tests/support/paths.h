// Paths the tests need, fixed at configure time.
#pragma once
#include <filesystem>
#include <string>

namespace tsptest {
/// Directory of small committed test inputs (tests/data).
std::filesystem::path test_data_dir();
/// The shared real data sets (../shared/data beside the checkout).
std::filesystem::path shared_data_dir();
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
RunResult run_tspplay(const std::string& args);
}  // namespace tsptest
