// Shared by the fuzz targets: the input bytes as a file with a given name (the readers take
// paths), and the rule every target follows — a tsp::Error is the expected answer to bad input;
// anything else (another exception, a crash, a sanitizer report) is a bug.
#pragma once
#include <unistd.h>

#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>

#include "tsp/core/error.h"

namespace tspfuzz {

/// A per-process scratch directory for the current input's files, removed at exit.
inline const std::filesystem::path& scratch_dir() {
  struct Dir {
    std::filesystem::path path =
        std::filesystem::temp_directory_path() / ("tspfuzz-" + std::to_string(getpid()));
    Dir() { std::filesystem::create_directories(path); }
    ~Dir() {
      std::error_code ec;
      std::filesystem::remove_all(path, ec);
    }
  };
  static const Dir dir;
  return dir.path;
}

/// Writes bytes to scratch_dir()/name and returns its path.
inline std::string write_input(const std::string& name, const std::uint8_t* data,
                               std::size_t size) {
  const auto path = scratch_dir() / name;
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  out.write(reinterpret_cast<const char*>(data), std::streamsize(size));
  return path.string();
}

/// Runs f; a tsp::Error (IoError, FormatError, UsageError, …) is a correct refusal.
template <class F>
void expect_clean(F&& f) {
  try {
    f();
  } catch (const tsp::Error&) {
  }
}

}  // namespace tspfuzz
