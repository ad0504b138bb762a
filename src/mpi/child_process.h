// tspplay-mpi render's processes: each rank runs the serial `tspplay render` (which links the
// renderer and serial HDF5, neither of which can live in this MPI + parallel HDF5 binary).
#pragma once
#include <filesystem>
#include <string>
#include <utility>
#include <vector>

namespace tspmpi {

/// How a child process ended.
struct ChildResult {
  int exit_code = 0;   ///< its exit status, or 128 + the signal that ended it
  std::string err;     ///< everything it wrote to standard error
  std::string out;     ///< its standard output, when asked for (else discarded)
};

/// The serial tspplay: `tspplay` beside this executable (/proc/self/exe), else the first on PATH.
/// Throws tsp::IoError naming both places when there is none.
std::filesystem::path serial_tspplay();

/// Runs program with args (argv[1..]) and the environment plus `env` (NAME=VALUE each, replacing
/// a variable of the same name), standard input from /dev/null, standard error captured and
/// standard output captured when keep_out (else /dev/null); waits for it. The child gets SIGTERM
/// should this process die first (PR_SET_PDEATHSIG), so no render outlives its rank. Throws
/// tsp::IoError when the process cannot be started.
ChildResult run_child(const std::filesystem::path& program, const std::vector<std::string>& args,
                      const std::vector<std::string>& env, bool keep_out = false);

/// The lines of a child tspplay's standard error, its `tspplay: ` prefixes removed ("error: …",
/// "usage error: …", "warning: …"), without the blank ones. Never throws but bad_alloc.
std::vector<std::string> child_lines(const std::string& err);

}  // namespace tspmpi
