// Helpers shared by the benchmarks: run a measurement in a child process (so each variant's peak
// resident set size is its own), warm the page cache, format numbers.
#pragma once
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <functional>
#include <string>
#include <vector>

#include "tsp/core/stopwatch.h"

namespace tspbench {

/// Result of one child-process measurement.
struct ChildRun {
  bool ok = false;
  double seconds = 0;        ///< wall time measured inside the child around fn
  double peak_rss_mib = 0;   ///< the child's peak resident set size
};

/// Runs fn in a forked child (after sync()) and returns its wall time and peak RSS; fn returns
/// false on failure.
inline ChildRun run_in_child(const std::function<bool()>& fn) {
  // Flush earlier runs' dirty pages first: their writeback would otherwise be charged to this run.
  sync();
  int fds[2];
  if (pipe(fds) != 0) return {};
  pid_t pid = fork();
  if (pid == 0) {
    close(fds[0]);
    const tsp::Stopwatch watch;
    bool ok = fn();
    double s = watch.seconds();
    if (write(fds[1], &s, sizeof s) != sizeof s) _exit(3);
    _exit(ok ? 0 : 1);
  }
  close(fds[1]);
  ChildRun r;
  double s = 0;
  bool got = read(fds[0], &s, sizeof s) == sizeof s;
  close(fds[0]);
  int status = 0;
  struct rusage ru {};
  wait4(pid, &status, 0, &ru);
  r.ok = got && WIFEXITED(status) && WEXITSTATUS(status) == 0;
  r.seconds = s;
  r.peak_rss_mib = double(ru.ru_maxrss) / 1024.0;  // Linux reports KiB
  return r;
}

/// Reads a file once so later reads come from the page cache.
inline void warm_page_cache(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::vector<char> buf(1 << 22);
  while (in.read(buf.data(), std::streamsize(buf.size())) || in.gcount() > 0) {
  }
}

/// Value of environment variable name as an int, or fallback.
inline int env_int(const char* name, int fallback) {
  const char* v = std::getenv(name);
  return v ? std::atoi(v) : fallback;
}

}  // namespace tspbench
