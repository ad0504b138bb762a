#include "tsp/core/parallel_for.h"

#include <algorithm>
#include <atomic>
#include <cassert>
#include <cstdlib>
#include <exception>
#include <mutex>
#include <thread>
#include <vector>

#include "tsp/core/interrupt.h"

namespace tsp {

int resolve_threads(int threads) {
  if (threads > 0) return threads;
  // TSPPLAY_THREADS (a positive count) caps "all": tspplay-mpi render gives each rank's render
  // its share of the node's cores.
  static const int from_env = [] {
    const char* v = std::getenv("TSPPLAY_THREADS");
    char* end = nullptr;
    const long n = v ? std::strtol(v, &end, 10) : 0;
    return v && end != v && *end == 0 && n > 0 && n <= 4096 ? int(n) : 0;
  }();
  if (from_env > 0) return from_env;
  return std::max(1, int(std::thread::hardware_concurrency()));
}

int parallel_workers(std::int64_t n, std::int64_t grain, int threads) {
  assert(grain >= 1);
  const std::int64_t chunks = n > 0 ? (n + grain - 1) / grain : 0;
  return int(std::max<std::int64_t>(1, std::min<std::int64_t>(resolve_threads(threads), chunks)));
}

void parallel_for(std::int64_t n, std::int64_t grain, int threads, const ChunkFn& body) {
  assert(grain >= 1);
  if (n <= 0) return;
  const int workers = parallel_workers(n, grain, threads);
  std::atomic<std::int64_t> next{0};
  std::atomic<bool> failed{false};
  std::exception_ptr error;
  std::mutex error_mutex;
  auto run = [&](int worker) {
    try {
      for (std::int64_t first; !failed && (first = next.fetch_add(grain)) < n;) {
        throw_if_interrupted();  // every long loop of the library stops within one chunk
        body(worker, first, std::min(n, first + grain));
      }
    } catch (...) {
      std::lock_guard lock(error_mutex);
      if (!error) error = std::current_exception();
      failed = true;
    }
  };
  if (workers == 1) {
    run(0);
  } else {
    std::vector<std::jthread> pool;
    pool.reserve(std::size_t(workers - 1));
    for (int w = 1; w < workers; ++w) pool.emplace_back(run, w);
    run(0);
  }  // the jthreads join here
  if (error) std::rethrow_exception(error);
}

}  // namespace tsp
