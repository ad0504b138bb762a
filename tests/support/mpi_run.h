// Running tspplay-mpi from the MPI tests (tests/mpi): whether MPI was found at configure time,
// and `mpirun -np N tspplay-mpi ARGS`.
#pragma once
#include <string>

#include "support/paths.h"

namespace tsptest {

/// True when tspplay-mpi and mpiexec were found at configure time.
inline bool have_mpi() { return !tspplay_mpi_bin().empty() && !mpiexec_bin().empty(); }

/// `mpirun -np N tspplay-mpi ARGS`, as root and with more ranks than cores where needed.
inline RunResult run_mpi(int ranks, const std::string& args) {
  return run_command(quote(mpiexec_bin()) + " --oversubscribe --allow-run-as-root -np " +
                     std::to_string(ranks) + " " + quote(tspplay_mpi_bin()) + " " + args);
}

}  // namespace tsptest
