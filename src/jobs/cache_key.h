// The one hash the caches name their entries by (play's builds, calibrations, playback tunings):
// FNV-1a of the key's text.
#pragma once
#include <cstdint>
#include <cstdio>
#include <string>
#include <string_view>

namespace tspgl {

/// 64-bit FNV-1a of text. Never throws; thread-safe.
inline std::uint64_t fnv1a(std::string_view text) {
  std::uint64_t h = 1469598103934665603ull;
  for (unsigned char c : text) h = (h ^ c) * 1099511628211ull;
  return h;
}

/// fnv1a(text) as 16 lower-case hex digits, for cache file names. Never throws but bad_alloc.
inline std::string key_hash(std::string_view text) {
  char buf[17];
  std::snprintf(buf, sizeof buf, "%016llx", static_cast<unsigned long long>(fnv1a(text)));
  return buf;
}

}  // namespace tspgl
