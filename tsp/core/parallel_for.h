// The one parallel-for of the library: indices [0, n) handed out in chunks to a few threads
// (the caller's thread is one of them), with per-worker state and the first error rethrown.
#pragma once
#include <cstdint>
#include <functional>

namespace tsp {

/// Worker threads for a request of `threads` (0 or less: all hardware threads, or the
/// environment's TSPPLAY_THREADS when it is a positive count), at least 1. Never throws;
/// thread-safe.
int resolve_threads(int threads);

/// Workers parallel_for(n, grain, threads, …) runs: resolve_threads(threads), at most one per
/// chunk of grain (≥ 1) indices, at least 1. Never throws; thread-safe.
int parallel_workers(std::int64_t n, std::int64_t grain, int threads);

/// The work of one chunk: indices [begin, end), run by worker `worker`
/// (0 ≤ worker < parallel_workers(n, grain, threads); worker 0 is the calling thread).
using ChunkFn = std::function<void(int worker, std::int64_t begin, std::int64_t end)>;

/// Calls body on consecutive chunks of grain (≥ 1, asserted) indices covering [0, n), each
/// chunk exactly once, the chunks handed out in increasing order to whichever worker is free;
/// returns when all are done. One worker never runs two chunks at once, so state indexed by
/// worker needs no lock. If a body throws, no new chunk starts, and the first exception is
/// rethrown once every worker has stopped. Once SIGINT/SIGTERM arrived under an InterruptScope
/// (tsp/core/interrupt.h) no new chunk starts and Interrupted is thrown, so every loop built on
/// it stops within one chunk. Thread-safe to call from several threads; body
/// must be safe to run concurrently on disjoint chunks.
void parallel_for(std::int64_t n, std::int64_t grain, int threads, const ChunkFn& body);

}  // namespace tsp
