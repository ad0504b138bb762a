#include "tsp/core/input_file.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstring>

#include "tsp/core/error.h"

namespace tsp {

InputFile::InputFile(const std::string& path, const std::string& what) : path_(path) {
  if (path.find('\0') != std::string::npos)
    throw IoError("a " + what + " name holds a NUL byte, which no file name can hold");
  fd_ = ::open(path.c_str(), O_RDONLY | O_NONBLOCK | O_CLOEXEC);
  if (fd_ < 0) {
    if (errno == ENOENT || errno == ENOTDIR) throw IoError(path + ": " + what + " does not exist");
    throw IoError(path + ": " + what + " cannot be opened (" + std::strerror(errno) + ")");
  }
  struct stat st {};
  if (::fstat(fd_, &st) != 0) {
    const int err = errno;
    ::close(fd_);
    throw IoError(path + ": " + what + " cannot be examined (" + std::strerror(err) + ")");
  }
  if (!S_ISREG(st.st_mode)) {
    ::close(fd_);
    if (S_ISDIR(st.st_mode)) throw IoError(path + ": " + what + " is a directory, expected a file");
    throw IoError(path + ": " + what + " is not a regular file (a FIFO, socket or device)");
  }
  size_ = std::int64_t(st.st_size);
  // Reads block as usual from here on (a regular file never waits anyway).
  const int flags = ::fcntl(fd_, F_GETFL);
  if (flags >= 0) ::fcntl(fd_, F_SETFL, flags & ~O_NONBLOCK);
}

InputFile::~InputFile() {
  if (fd_ >= 0) ::close(fd_);
}

std::size_t InputFile::read(char* buf, std::size_t n) {
  n = std::size_t(std::min<std::int64_t>(std::int64_t(n), size_ - offset_));
  std::size_t got = 0;
  while (got < n) {
    const ssize_t r = ::read(fd_, buf + got, n - got);
    if (r < 0 && errno == EINTR) continue;
    if (r < 0) throw IoError(path_ + ": read error (" + std::strerror(errno) + ")");
    if (r == 0) break;  // the file shrank since it was opened
    got += std::size_t(r);
  }
  offset_ += std::int64_t(got);
  return got;
}

std::string read_input_file(const std::string& path, const std::string& what,
                            std::int64_t max_bytes) {
  InputFile in(path, what);
  if (in.size() > max_bytes)
    throw IoError(path + ": " + what + " holds " + std::to_string(in.size()) +
                  " bytes, more than the " + std::to_string(max_bytes) + " bytes accepted");
  std::string text(std::size_t(in.size()), '\0');
  text.resize(in.read(text.data(), text.size()));
  return text;
}

}  // namespace tsp
