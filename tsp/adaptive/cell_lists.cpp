#include "tsp/adaptive/cell_lists.h"

#include <fcntl.h>
#include <unistd.h>

#include <cassert>
#include <cerrno>
#include <cstring>

#include "tsp/core/error.h"

namespace tsp {

template <class T>
DiskLists<T>::DiskLists(const std::string& dir, std::int64_t keys, const std::string& what)
    : dir_(dir.empty() ? "." : dir), what_(what), offset_(std::size_t(keys), 0),
      count_(std::size_t(keys), 0) {
  std::string tmpl = dir_ + "/.tspplay-cells-XXXXXX";
  fd_ = mkstemp(tmpl.data());
  if (fd_ < 0)
    throw IoError(dir_ + ": cannot create the scratch file of " + what_ + " (" +
                  std::string(std::strerror(errno)) + ")");
  unlink(tmpl.c_str());  // the descriptor keeps the data; a crash leaves nothing behind
}

template <class T>
DiskLists<T>::~DiskLists() {
  if (fd_ >= 0) close(fd_);
}

template <class T>
void DiskLists<T>::put(std::int64_t key, std::span<const T> cells) {
  offset_[std::size_t(key)] = end_;
  count_[std::size_t(key)] = std::int64_t(cells.size());
  const char* p = reinterpret_cast<const char*>(cells.data());
  std::size_t left = cells.size_bytes();
  off_t pos = off_t(end_);
  while (left > 0) {
    const ssize_t n = pwrite(fd_, p, left, pos);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0)
      throw IoError(dir_ + ": writing the scratch file of " + what_ + " failed (" +
                    std::string(n < 0 ? std::strerror(errno) : "nothing written") + ")");
    p += n;
    left -= std::size_t(n);
    pos += n;
  }
  end_ += std::int64_t(cells.size_bytes());
}

template <class T>
std::vector<T> DiskLists<T>::get(std::int64_t key) const {
  std::vector<T> out(static_cast<std::size_t>(count_[std::size_t(key)]));
  char* p = reinterpret_cast<char*>(out.data());
  std::size_t left = out.size() * sizeof(T);
  off_t pos = off_t(offset_[std::size_t(key)]);
  while (left > 0) {
    const ssize_t n = pread(fd_, p, left, pos);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0)
      throw IoError(dir_ + ": reading the scratch file of " + what_ + " failed (" +
                    std::string(n < 0 ? std::strerror(errno) : "short file") + ")");
    p += n;
    left -= std::size_t(n);
    pos += n;
  }
  return out;
}

template class DiskLists<std::int64_t>;
template class DiskLists<float>;

}  // namespace tsp
