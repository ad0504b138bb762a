// How much memory this process holds, for the out-of-core measurements (docs/results.md): the
// resident set now and its peak, from /proc/self/status (Linux); and the CPU time it used (the
// idle player's share of a core).
#pragma once
#include <cstdint>

namespace tsp {

/// Resident set size in bytes now (VmRSS); 0 where /proc is not available. Never throws.
std::int64_t resident_bytes();
/// Peak resident set size in bytes (VmHWM); 0 where /proc is not available. Never throws.
std::int64_t peak_resident_bytes();
/// CPU seconds this process used so far, user and system, all threads (getrusage). Never throws.
double cpu_seconds();

}  // namespace tsp
