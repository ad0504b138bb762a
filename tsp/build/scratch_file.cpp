#include "tsp/build/scratch_file.h"

#include <fcntl.h>
#include <unistd.h>

#include <cassert>
#include <cerrno>
#include <cstring>

#include "tsp/core/error.h"

namespace tsp {

namespace {
std::string errno_text() {
  return std::strerror(errno);
}
}  // namespace

ScratchFile::ScratchFile(const std::string& dir, const std::vector<std::int64_t>& brick_samples,
                         int steps)
    : steps_(steps), dir_(dir.empty() ? "." : dir), samples_(brick_samples) {
  offsets_.resize(samples_.size() + 1, 0);
  for (std::size_t b = 0; b < samples_.size(); ++b)
    offsets_[b + 1] = offsets_[b] + samples_[b] * steps_;
  std::string tmpl = dir_ + "/.tspplay-scratch-XXXXXX";
  fd_ = mkstemp(tmpl.data());
  if (fd_ < 0)
    throw IoError(dir_ + ": cannot create the build's scratch file (" + errno_text() + ")");
  // Unlinked right away: the open descriptor keeps the data; a crash leaves nothing behind.
  unlink(tmpl.c_str());
}

ScratchFile::~ScratchFile() {
  if (fd_ >= 0) close(fd_);
}

void ScratchFile::write(int brick, int step, std::span<const float> samples) {
  assert(std::int64_t(samples.size()) == samples_[brick]);
  const char* p = reinterpret_cast<const char*>(samples.data());
  std::size_t left = samples.size_bytes();
  off_t pos = off_t((offsets_[brick] + samples_[brick] * step) * std::int64_t(sizeof(float)));
  while (left > 0) {
    ssize_t n = pwrite(fd_, p, left, pos);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0)
      throw IoError(dir_ + ": writing the build's scratch file failed (" +
                    (n < 0 ? errno_text() : std::string("no progress")) + "; " +
                    std::to_string(size_bytes() >> 20) + " MiB needed)");
    p += n;
    left -= std::size_t(n);
    pos += n;
  }
}

void ScratchFile::read_series(int brick, std::span<float> out) const {
  assert(std::int64_t(out.size()) == samples_[brick] * steps_);
  read_floats(out, offsets_[brick]);
}

void ScratchFile::read(int brick, int step, std::span<float> out) const {
  assert(std::int64_t(out.size()) == samples_[brick] && step >= 0 && step < steps_);
  read_floats(out, offsets_[brick] + samples_[brick] * step);
}

void ScratchFile::read_floats(std::span<float> out, std::int64_t at) const {
  char* p = reinterpret_cast<char*>(out.data());
  std::size_t left = out.size_bytes();
  off_t pos = off_t(at * std::int64_t(sizeof(float)));
  while (left > 0) {
    ssize_t n = pread(fd_, p, left, pos);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0)
      throw IoError(dir_ + ": reading the build's scratch file failed (" +
                    (n < 0 ? errno_text() : std::string("short file")) + ")");
    p += n;
    left -= std::size_t(n);
    pos += n;
  }
}

void ScratchFile::discard(int brick) {
  const off_t pos = off_t(offsets_[brick] * std::int64_t(sizeof(float)));
  const off_t len = off_t(samples_[brick] * steps_ * std::int64_t(sizeof(float)));
  // Best effort: file systems without hole punching keep the data until the file is closed.
  (void)fallocate(fd_, FALLOC_FL_PUNCH_HOLE | FALLOC_FL_KEEP_SIZE, pos, len);
}

}  // namespace tsp
