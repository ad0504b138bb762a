// Checks on paths before anything opens them: an input must be a regular file (opening a FIFO
// would block forever, a directory gives a misleading error), and an output must never be one
// of the inputs.
#pragma once
#include <string>
#include <vector>

namespace tsp {

/// Throws IoError naming path and `what` ("input", "step file", …) unless path names an existing
/// regular file (symbolic links followed): "does not exist", "is a directory" or "is not a
/// regular file (a FIFO, socket or device)". Opens nothing, so it never blocks. Thread-safe.
void require_regular_file(const std::string& path, const std::string& what = "input");

/// True when a and b name the same existing file (same device and inode, so hard and symbolic
/// links count); false when either does not exist. Never throws; thread-safe.
bool same_file(const std::string& a, const std::string& b);

/// Throws UsageError when output names the same file as any of inputs (it would be replaced
/// by the output). Thread-safe.
void require_not_an_input(const std::string& output, const std::vector<std::string>& inputs);

}  // namespace tsp
