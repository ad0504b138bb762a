#include "tsp/core/temp_output.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>

#include "tsp/core/error.h"

namespace tsp {

namespace fs = std::filesystem;

namespace {

// Takes an exclusive open-file-description lock on fd without waiting; true when taken.
bool try_lock(int fd) {
  struct flock fl {};
  fl.l_type = F_WRLCK;
  fl.l_whence = SEEK_SET;
  return ::fcntl(fd, F_OFD_SETLK, &fl) == 0;
}

std::string temp_prefix(const fs::path& out) { return "." + out.filename().string() + ".tmp-"; }

}  // namespace

std::string output_directory(const std::string& out_path) {
  const fs::path dir = fs::path(out_path).parent_path();
  return dir.empty() ? "." : dir.string();
}

int remove_stale_temporaries(const std::string& out_path) {
  const fs::path p(out_path);
  const fs::path dir = output_directory(out_path);
  const std::string prefix = temp_prefix(p);
  int removed = 0;
  std::error_code ec;
  for (fs::directory_iterator it(dir, ec), end; !ec && it != end; it.increment(ec)) {
    const std::string name = it->path().filename().string();
    if (name.size() != prefix.size() + 6 || name.compare(0, prefix.size(), prefix) != 0) continue;
    if (!it->is_regular_file(ec)) continue;
    const int fd = ::open(it->path().c_str(), O_RDWR | O_CLOEXEC | O_NOFOLLOW);
    if (fd < 0) continue;
    // Locked: its writer is alive. Unlocked: the writer is gone (the kernel released its lock).
    if (try_lock(fd) && ::unlink(it->path().c_str()) == 0) ++removed;
    ::close(fd);
  }
  return removed;
}

TempOutput::TempOutput(const std::string& out_path) : final_(out_path) {
  fs::path p(out_path);
  fs::path dir = output_directory(out_path);
  std::error_code ec;
  if (fs::is_directory(p, ec)) throw IoError(out_path + ": is a directory, expected a file name");
  if (!fs::is_directory(dir, ec))
    throw IoError(out_path + ": directory " + dir.string() + " does not exist");
  dir_ = dir.string();
  remove_stale_temporaries(out_path);
  // The file is created under a name no sweeper looks at, locked, and only then linked under
  // its `.tmp-` name, so no other build ever sees it unlocked.
  for (int attempt = 0; tmp_.empty(); ++attempt) {
    std::string fresh = (dir / ("." + p.filename().string() + ".new-XXXXXX")).string();
    int fd = mkstemp(fresh.data());
    if (fd < 0)
      throw IoError(out_path + ": cannot create a file in " + dir_ + " (" +
                    std::strerror(errno) + ")");
    // Where locks are unsupported (some network file systems) no sweeper can lock it either,
    // so it is never taken for stale.
    try_lock(fd);
    const std::string tmp = (dir / temp_prefix(p)).string() + fresh.substr(fresh.size() - 6);
    const bool linked = ::link(fresh.c_str(), tmp.c_str()) == 0;
    const int err = errno;
    ::unlink(fresh.c_str());
    if (!linked) {
      ::close(fd);
      if (err == EEXIST && attempt < 100) continue;
      throw IoError(out_path + ": cannot create a file in " + dir_ + " (" + std::strerror(err) +
                    ")");
    }
    // mkstemp creates 0600; the finished file gets the permissions a plain create would give.
    const mode_t mask = umask(0);
    umask(mask);
    fchmod(fd, 0666 & ~mask);
    lock_fd_ = fd;
    tmp_ = tmp;
  }
}

TempOutput::~TempOutput() {
  if (!committed_) std::remove(tmp_.c_str());
  if (lock_fd_ >= 0) ::close(lock_fd_);
}

void TempOutput::commit() {
  if (std::rename(tmp_.c_str(), final_.c_str()) != 0)
    throw IoError(final_ + ": cannot rename the finished file into place (" + std::strerror(errno) +
                  ")");
  committed_ = true;
}

void write_file_atomically(const std::string& path, const std::string& text) {
  TempOutput out(path);
  std::ofstream f(out.tmp(), std::ios::binary | std::ios::trunc);
  f << text;
  f.close();
  if (!f) throw IoError(path + ": cannot write (disk full?)");
  out.commit();
}

}  // namespace tsp
