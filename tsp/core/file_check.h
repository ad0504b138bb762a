// Checks on paths before anything opens them: an input must be a regular file (opening a FIFO
// would block forever, a directory gives a misleading error). Outputs are checked by TempOutput
// (temp_output.h).
#pragma once
#include <string>

namespace tsp {

/// Throws IoError naming path and `what` ("input", "step file", …) unless path names an existing
/// regular file (symbolic links followed): "does not exist", "is a directory" or "is not a
/// regular file (a FIFO, socket or device)". Opens nothing, so it never blocks. Thread-safe.
void require_regular_file(const std::string& path, const std::string& what = "input");

}  // namespace tsp
