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
#include <mutex>

#include "tsp/core/error.h"
#include "tsp/core/interrupt.h"

namespace tsp {

namespace fs = std::filesystem;

namespace detail {
bool try_lock(int fd) {
  struct flock fl {};
  fl.l_type = F_WRLCK;
  fl.l_whence = SEEK_SET;
  return ::fcntl(fd, F_OFD_SETLK, &fl) == 0;
}
}  // namespace detail

namespace {

using detail::try_lock;

std::string temp_prefix(const fs::path& out) { return "." + out.filename().string() + ".tmp-"; }

// The guarded inputs of every live InputGuard (one entry per guard and path).
struct GuardedInput {
  dev_t dev;
  ino_t ino;
  std::string path;
};
std::mutex g_inputs_mutex;
std::vector<GuardedInput>& guarded_inputs() {
  static std::vector<GuardedInput> inputs;
  return inputs;
}

// What a non-regular file is, for messages.
const char* file_kind(mode_t mode) {
  if (S_ISDIR(mode)) return "a directory";
  if (S_ISFIFO(mode)) return "a FIFO";
  if (S_ISSOCK(mode)) return "a socket";
  if (S_ISCHR(mode)) return "a character device";
  if (S_ISBLK(mode)) return "a block device";
  return "not a regular file";
}

}  // namespace

InputGuard::InputGuard(const std::vector<std::string>& paths) {
  for (const std::string& p : paths) add(p);
}

InputGuard::~InputGuard() {
  std::lock_guard<std::mutex> lock(g_inputs_mutex);
  auto& inputs = guarded_inputs();
  for (const auto& [dev, ino] : ids_)
    for (auto it = inputs.begin(); it != inputs.end(); ++it)
      if (it->dev == dev && it->ino == ino) {
        inputs.erase(it);
        break;
      }
}

void InputGuard::add(const std::string& path) {
  struct stat st {};
  if (path.empty() || ::stat(path.c_str(), &st) != 0) return;  // not there: nothing to protect
  std::lock_guard<std::mutex> lock(g_inputs_mutex);
  guarded_inputs().push_back({st.st_dev, st.st_ino, path});
  ids_.emplace_back(st.st_dev, st.st_ino);
}

std::string guarded_input_at(const std::string& path) {
  struct stat st {};
  if (::stat(path.c_str(), &st) != 0) return "";
  std::lock_guard<std::mutex> lock(g_inputs_mutex);
  for (const GuardedInput& in : guarded_inputs())
    if (in.dev == st.st_dev && in.ino == st.st_ino) return in.path;
  return "";
}

void check_output_path(const std::string& path) {
  if (const std::string in = guarded_input_at(path); !in.empty())
    throw UsageError(path + ": the output is the input file " + in +
                     "; writing it would destroy the input (choose another output name)");
  struct stat st {};
  if (::stat(path.c_str(), &st) != 0) return;  // a new file (or a dangling link: replaced)
  if (S_ISDIR(st.st_mode)) throw IoError(path + ": is a directory, expected a file name");
  if (!S_ISREG(st.st_mode))
    throw IoError(path + ": is " + file_kind(st.st_mode) +
                  ", not a regular file; tspplay writes outputs only as regular files (it would "
                  "replace it): write to a file name instead");
}

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

namespace {
// Under OutputLinks::replace, whatever non-folder entry is at path (a link, a FIFO, a device) is
// replaced by rename() itself, never opened or followed: it needs no check.
bool replaced_as_is(const std::string& path, OutputLinks links) {
  std::error_code ec;
  const fs::file_status st = fs::symlink_status(path, ec);
  return links == OutputLinks::replace && fs::exists(st) && !fs::is_directory(st);
}
}  // namespace

TempOutput::TempOutput(const std::string& out_path, OutputLinks links)
    : shown_(out_path), final_(out_path), links_(links) {
  std::error_code ec;
  if (!replaced_as_is(out_path, links)) check_output_path(out_path);
  // A link to an existing file: the file is replaced and the link kept.
  if (links == OutputLinks::follow && fs::is_symlink(out_path, ec) && fs::exists(out_path, ec)) {
    const fs::path target = fs::canonical(out_path, ec);
    if (!ec) final_ = target.string();
  }
  fs::path p(final_);
  fs::path dir = output_directory(final_);
  if (!fs::is_directory(dir, ec))
    throw IoError(out_path + ": directory " + dir.string() + " does not exist");
  dir_ = dir.string();
  remove_stale_temporaries(final_);
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
  throw_if_interrupted();
  // Nothing put a device or FIFO there meanwhile (under replace: whatever is there goes).
  if (!replaced_as_is(final_, links_)) check_output_path(final_);
  if (std::rename(tmp_.c_str(), final_.c_str()) != 0)
    throw IoError(shown_ + ": cannot rename the finished file into place (" +
                  std::strerror(errno) + ")");
  committed_ = true;
}

void write_file_atomically(const std::string& path, const std::string& text, OutputLinks links) {
  TempOutput out(path, links);
  std::ofstream f(out.tmp(), std::ios::binary | std::ios::trunc);
  f << text;
  f.close();
  if (!f) throw IoError(path + ": cannot write (disk full?)");
  out.commit();
}

std::string unused_path(const std::string& path) {
  const fs::path p(path);
  std::error_code ec;
  std::string name = path;
  for (int k = 2; fs::exists(fs::symlink_status(name, ec)); ++k)  // (a dangling link exists too)
    name = (p.parent_path() / (p.stem().string() + "-" + std::to_string(k) + p.extension().string()))
               .string();
  return name;
}

}  // namespace tsp
