// tspplay-mpi render: a movie's frames split over MPI ranks (docs/mpi.md). Every rank runs the
// serial `tspplay render` on its block of frames into a folder inside rank 0's temporary output
// folder; rank 0 joins them into the serial render's frame set, frames.json and movie.
#pragma once
#include <mpi.h>

#include <string>
#include <vector>

namespace tspmpi {

/// Runs `tspplay-mpi render ARGS` on every rank of comm (collective: every rank calls it with
/// the same args): checks the arguments and outputs once (rank 0, through `tspplay render
/// --mpi-check`), renders each rank's frames with `threads` worker threads in its own process,
/// and on rank 0 joins and commits the outputs, or reports every rank that failed. Returns the
/// exit status every rank ends with: 0, 1 (a rank or the join failed; nothing written), 2 (a
/// usage error, said once) or the serial command's status for a bad argument. Never throws but
/// bad_alloc; MPI errors abort the job.
int run_render(MPI_Comm comm, int threads, const std::vector<std::string>& args);

}  // namespace tspmpi
