// The builder's brick-major scratch file: each brick's whole time series lies contiguous,
// [T][brick samples] float32, so pass 2 reads one brick's series with one read.
#pragma once
#include <cstdint>
#include <span>
#include <string>
#include <vector>

namespace tsp {

/// An anonymous temporary file in a given directory: created and unlinked at once (only the
/// descriptor keeps it), so nothing is left behind when the process dies.
class ScratchFile {
 public:
  /// Creates the file in dir for bricks of the given sample counts over `steps` steps;
  /// throws IoError when dir is not writable.
  ScratchFile(const std::string& dir, const std::vector<std::int64_t>& brick_samples, int steps);
  ~ScratchFile();
  ScratchFile(const ScratchFile&) = delete;
  ScratchFile& operator=(const ScratchFile&) = delete;
  /// Stores brick b's samples at step t (brick_samples[b] floats); thread-safe for distinct
  /// (b, t). Throws IoError (e.g. disk full).
  void write(int brick, int step, std::span<const float> samples);
  /// Reads brick b's whole series, steps × brick_samples[b] floats; thread-safe. Throws IoError.
  void read_series(int brick, std::span<float> out) const;
  /// Reads brick b's samples at step t (brick_samples[b] floats); thread-safe. Throws IoError.
  void read(int brick, int step, std::span<float> out) const;
  /// Drops brick b's series (after its last read): frees its page cache and cancels its pending
  /// write-back, so the scratch data never reaches the disk when memory allows. Never throws.
  void discard(int brick);
  /// Total size in bytes.
  std::int64_t size_bytes() const { return offsets_.back() * std::int64_t(sizeof(float)); }

 private:
  void read_floats(std::span<float> out, std::int64_t at) const;  // at: in floats
  int fd_ = -1;
  int steps_;
  std::string dir_;
  std::vector<std::int64_t> samples_;
  std::vector<std::int64_t> offsets_;  // in floats, per brick, plus the total at the end
};

}  // namespace tsp
