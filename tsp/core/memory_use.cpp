#include "tsp/core/memory_use.h"

#include <sys/resource.h>

#include <cstdio>
#include <cstring>

namespace tsp {

namespace {

// The "NAME:  N kB" line of /proc/self/status, in bytes.
std::int64_t status_kib(const char* name) {
  std::FILE* f = std::fopen("/proc/self/status", "r");
  if (!f) return 0;
  char line[256];
  std::int64_t kib = 0;
  const std::size_t n = std::strlen(name);
  while (std::fgets(line, sizeof line, f))
    if (std::strncmp(line, name, n) == 0 && line[n] == ':') {
      long long v = 0;
      if (std::sscanf(line + n + 1, "%lld", &v) == 1) kib = v;
      break;
    }
  std::fclose(f);
  return kib * 1024;
}

}  // namespace

std::int64_t resident_bytes() { return status_kib("VmRSS"); }
std::int64_t peak_resident_bytes() { return status_kib("VmHWM"); }

double cpu_seconds() {
  rusage u{};
  if (getrusage(RUSAGE_SELF, &u) != 0) return 0;
  auto s = [](const timeval& t) { return double(t.tv_sec) + double(t.tv_usec) * 1e-6; };
  return s(u.ru_utime) + s(u.ru_stime);
}

}  // namespace tsp
