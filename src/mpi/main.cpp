// tspplay-mpi: `build` and `render` split over MPI ranks (docs/mpi.md). main only sets up MPI,
// parses and dispatches; the build is tspplay's own (src/cli/cmd_build.cpp) with a
// tsp::BuildPartition, render runs the serial tspplay on every rank (src/mpi/render_driver.h).
#include <mpi.h>
#include <sched.h>

#include <algorithm>
#include <cstdio>
#include <exception>
#include <string>
#include <thread>
#include <vector>

#include "cli/build_runner.h"
#include "cli/commands.h"
#include "mpi/mpi_partition.h"
#include "mpi/render_driver.h"
#include "tsp/core/error.h"

namespace {

// Ends the whole job: a rank that failed cannot send the bricks rank 0 waits for.
[[noreturn]] void abort_job(int rank, int ranks, const char* kind, const char* what, int code) {
  std::fprintf(stderr, "tspplay-mpi: rank %d of %d: %s: %s\n", rank, ranks, kind, what);
  std::fflush(stderr);
  MPI_Abort(MPI_COMM_WORLD, code);
  std::_Exit(code);
}

// Worker threads per rank: the cores this rank may run on (mpirun binds each rank to one core
// when it starts one or two), and no more than its share of the node's cores.
int default_threads(int ranks_on_node) {
  const int cores = int(std::max(1u, std::thread::hardware_concurrency()));
  cpu_set_t set;
  CPU_ZERO(&set);
  const int allowed = sched_getaffinity(0, sizeof(set), &set) == 0 ? CPU_COUNT(&set) : cores;
  return std::max(1, std::min(allowed, cores / std::max(1, ranks_on_node)));
}

}  // namespace

int main(int argc, char** argv) {
  int provided = 0;
  if (MPI_Init_thread(&argc, &argv, MPI_THREAD_MULTIPLE, &provided) != MPI_SUCCESS) {
    std::fprintf(stderr, "tspplay-mpi: error: MPI_Init_thread failed\n");
    return 1;
  }
  tspmpi::MpiPartition partition(MPI_COMM_WORLD);
  const int rank = partition.rank(), ranks = partition.ranks();
  if (provided < MPI_THREAD_MULTIPLE)
    abort_job(rank, ranks, "error", "the MPI library does not provide MPI_THREAD_MULTIPLE", 1);
  const int threads = default_threads(partition.ranks_on_node());
  // render runs the serial tspplay on every rank (the renderer cannot link parallel HDF5): its
  // arguments go through untouched, to be checked by that command.
  if (argc > 1 && std::string(argv[1]) == "render") {
    const int code = tspmpi::run_render(MPI_COMM_WORLD, threads,
                                        std::vector<std::string>(argv + 2, argv + argc));
    MPI_Finalize();
    return code;
  }
  tspcli::set_build_partition(&partition, threads);

  CLI::App app{"tspplay-mpi " TSPPLAY_VERSION
               " - build .tsp files and render movies with MPI: mpirun -np N tspplay-mpi build "
               "INPUT -o OUT.tsp, mpirun -np N tspplay-mpi render FILE -o frames/ [--movie M]"};
  app.require_subcommand(1);
  app.set_version_flag("--version", "tspplay-mpi " TSPPLAY_VERSION);
  tspcli::add_all_commands(app);
  app.add_subcommand("render", "Render steps split over the ranks (tspplay render's options; "
                               "render --help)");  // listed only: handled above
  int code = 0;
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    // Every rank parses the same arguments: rank 0 speaks for all; --help and --version exit 0.
    if (rank == 0) code = app.exit(e);
    else code = e.get_exit_code();
    code = code == 0 ? 0 : 2;
  } catch (const tsp::UsageError& e) {
    if (rank == 0) std::fprintf(stderr, "tspplay-mpi: usage error: %s\n", e.what());
    code = 2;
  } catch (const tsp::Error& e) {
    abort_job(rank, ranks, "error", e.what(), 1);
  } catch (const std::exception& e) {
    abort_job(rank, ranks, "internal error", e.what(), 3);
  }
  MPI_Finalize();
  return code;
}
