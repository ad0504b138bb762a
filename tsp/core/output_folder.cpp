#include "tsp/core/output_folder.h"

#include <fcntl.h>
#include <stdio.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <filesystem>

#include "tsp/core/error.h"
#include "tsp/core/interrupt.h"
#include "tsp/core/temp_output.h"

namespace tsp {

namespace fs = std::filesystem;

namespace {

/// The marker file a live writer holds locked inside its temporary folder.
constexpr const char* kMarker = ".tspplay-writing";
/// Length of the random suffix mkdtemp fills in.
constexpr std::size_t kSuffix = 6;

std::string temp_prefix(const fs::path& dir) { return "." + dir.filename().string() + ".tmp-"; }

// dir without a trailing slash, so that filename() and parent_path() name the folder itself.
fs::path normalized(const std::string& dir) {
  fs::path p = fs::path(dir).lexically_normal();
  if (p.filename().empty() && p.has_parent_path()) p = p.parent_path();
  return p;
}

fs::path parent_of(const fs::path& p) {
  const fs::path parent = p.parent_path();
  return parent.empty() ? fs::path(".") : parent;
}

void remove_tree(const fs::path& p) {
  std::error_code ec;
  fs::remove_all(p, ec);
}

// Whether the entry may be carried into the new folder by a hard link.
bool carriable(const struct stat& st) { return S_ISREG(st.st_mode) || S_ISLNK(st.st_mode); }

const char* kind(const struct stat& st) {
  if (S_ISDIR(st.st_mode)) return "a folder";
  if (S_ISFIFO(st.st_mode)) return "a FIFO";
  if (S_ISSOCK(st.st_mode)) return "a socket";
  return "a device";
}

}  // namespace

int remove_stale_temporary_folders(const std::string& dir) {
  const fs::path p = normalized(dir);
  const std::string prefix = temp_prefix(p);
  int removed = 0;
  std::error_code ec;
  for (fs::directory_iterator it(parent_of(p), ec), end; !ec && it != end; it.increment(ec)) {
    const std::string name = it->path().filename().string();
    if (name.size() != prefix.size() + kSuffix || name.compare(0, prefix.size(), prefix) != 0)
      continue;
    std::error_code e2;
    if (!it->is_directory(e2) || it->is_symlink(e2)) continue;
    // A live writer holds its marker locked; no marker: an old set left by an interrupted swap.
    const int fd = ::open((it->path() / kMarker).c_str(), O_RDWR | O_CLOEXEC | O_NOFOLLOW);
    const bool stale = fd < 0 ? errno == ENOENT : detail::try_lock(fd);
    if (fd >= 0) ::close(fd);
    if (stale) {
      remove_tree(it->path());
      ++removed;
    }
  }
  return removed;
}

std::string OutputFolder::as_shown(std::string text) const {
  for (std::size_t at = 0; !tmp_.empty() && (at = text.find(tmp_, at)) != std::string::npos;
       at += shown_.size())
    text.replace(at, tmp_.size(), shown_);
  return text;
}

OutputFolder::OutputFolder(const std::string& dir, BelongsToSet belongs)
    : shown_(dir), belongs_(std::move(belongs)) {
  fs::path p = normalized(dir);
  std::error_code ec;
  if (fs::is_symlink(p, ec) && fs::is_directory(p, ec)) p = fs::canonical(p, ec);
  if (!fs::is_directory(parent_of(p), ec))
    throw IoError(dir + ": directory " + parent_of(p).string() + " does not exist");
  struct stat st {};
  const bool exists = ::stat(p.c_str(), &st) == 0;
  if (exists && !S_ISDIR(st.st_mode))
    throw IoError(dir + ": exists and is not a folder; the output folder of frames must be a "
                        "folder or a new name");
  if (exists) {
    const fs::path here = fs::current_path(ec);
    const fs::path whole = fs::canonical(p, ec);
    if (!ec && !here.empty()) {
      const auto rel = here.lexically_relative(whole);
      if (!rel.empty() && *rel.begin() != "..")
        throw UsageError(dir + ": the current folder is inside it, and the output folder is "
                               "replaced as a whole: name a subfolder");
    }
    for (fs::directory_iterator it(p, ec), end; !ec && it != end; it.increment(ec)) {
      const std::string name = it->path().filename().string();
      struct stat e {};
      if (::lstat(it->path().c_str(), &e) != 0) continue;
      if (belongs_(name)) {
        if (const std::string in = guarded_input_at(it->path().string()); !in.empty())
          throw UsageError(it->path().string() + " is the input file " + in +
                           ", and writing " + dir + " replaces it (choose another output folder)");
      } else if (!carriable(e)) {
        throw IoError(dir + ": holds " + name + " (" + kind(e) + "); the folder's frames are "
                      "replaced as a whole, which keeps other files but not folders, FIFOs or "
                      "devices: move it or choose another output folder");
      }
    }
    if (ec) throw IoError(dir + ": cannot list the folder (" + ec.message() + ")");
  }
  final_ = p.string();
  remove_stale_temporary_folders(final_);
  // Made under a name no sweeper looks at, its marker locked, only then given its `.tmp-` name.
  const fs::path parent = parent_of(p);
  for (int attempt = 0; tmp_.empty(); ++attempt) {
    std::string fresh = (parent / ("." + p.filename().string() + ".new-XXXXXX")).string();
    if (!::mkdtemp(fresh.data()))
      throw IoError(dir + ": cannot create a folder in " + parent.string() + " (" +
                    std::strerror(errno) + ")");
    const int fd = ::open((fs::path(fresh) / kMarker).c_str(),
                          O_RDWR | O_CREAT | O_EXCL | O_CLOEXEC, 0600);
    if (fd < 0) {
      const int err = errno;
      remove_tree(fresh);
      throw IoError(dir + ": cannot create a file in " + fresh + " (" + std::strerror(err) + ")");
    }
    detail::try_lock(fd);
    const mode_t mask = ::umask(0);
    ::umask(mask);
    ::chmod(fresh.c_str(), exists ? (st.st_mode & 07777) : (0777 & ~mask));
    const std::string tmp = (parent / temp_prefix(p)).string() + fresh.substr(fresh.size() - kSuffix);
    if (::renameat2(AT_FDCWD, fresh.c_str(), AT_FDCWD, tmp.c_str(), RENAME_NOREPLACE) != 0) {
      const int err = errno;
      ::close(fd);
      remove_tree(fresh);
      if (err == EEXIST && attempt < 100) continue;
      throw IoError(dir + ": cannot create a folder in " + parent.string() + " (" +
                    std::strerror(err) + ")");
    }
    lock_fd_ = fd;
    tmp_ = tmp;
  }
  if (!exists) {  // made empty now, so that outputs inside it (a movie) have their folder
    if (::mkdir(p.c_str(), 0777) != 0 && errno != EEXIST) {
      const int err = errno;
      remove_tree(tmp_);
      ::close(lock_fd_);
      throw IoError(dir + ": cannot create the output folder (" + std::strerror(err) + ")");
    }
    created_ = true;
  }
}

OutputFolder::~OutputFolder() {
  if (!committed_ && !tmp_.empty()) remove_tree(tmp_);
  if (!committed_ && created_) ::rmdir(final_.c_str());  // only if still empty
  if (lock_fd_ >= 0) ::close(lock_fd_);
}

void OutputFolder::commit() {
  throw_if_interrupted();
  const fs::path final_path = final_, tmp_path = tmp_;
  struct stat st {};
  if (::stat(final_.c_str(), &st) != 0) {  // no old folder: the new one takes the name
    if (::renameat2(AT_FDCWD, tmp_.c_str(), AT_FDCWD, final_.c_str(), RENAME_NOREPLACE) != 0)
      throw IoError(shown_ + ": cannot rename the finished folder into place (" +
                    std::strerror(errno) + ")");
    committed_ = true;
    ::unlink((final_path / kMarker).c_str());
    return;
  }
  if (!S_ISDIR(st.st_mode)) throw IoError(shown_ + ": is no longer a folder; nothing replaced");
  // The entries outside the set come along as hard links: until the swap they are in both.
  std::error_code ec;
  for (fs::directory_iterator it(final_path, ec), end; !ec && it != end; it.increment(ec)) {
    const std::string name = it->path().filename().string();
    if (belongs_(name)) continue;
    struct stat e {};
    if (::lstat(it->path().c_str(), &e) != 0) continue;
    if (!carriable(e))
      throw IoError(shown_ + ": " + name + " (" + kind(e) + ") appeared in the folder while "
                    "writing; nothing replaced");
    if (::linkat(AT_FDCWD, it->path().c_str(), AT_FDCWD, (tmp_path / name).c_str(), 0) != 0 &&
        errno != EEXIST)
      throw IoError(shown_ + ": cannot keep " + name + " in the new folder (" +
                    std::strerror(errno) + "); nothing replaced");
  }
  if (ec) throw IoError(shown_ + ": cannot list the folder (" + ec.message() + ")");
  throw_if_interrupted();
  if (::renameat2(AT_FDCWD, tmp_.c_str(), AT_FDCWD, final_.c_str(), RENAME_EXCHANGE) != 0) {
    if (errno != EINVAL && errno != ENOSYS)
      throw IoError(shown_ + ": cannot swap the new folder in (" + std::strerror(errno) +
                    "); nothing replaced");
    // No atomic exchange on this file system: move the old set aside, then the new one in.
    const std::string aside = tmp_ + ".old";
    if (::rename(final_.c_str(), aside.c_str()) != 0)
      throw IoError(shown_ + ": cannot move the old folder aside (" + std::strerror(errno) +
                    "); nothing replaced");
    if (::rename(tmp_.c_str(), final_.c_str()) != 0) {
      const int err = errno;
      ::rename(aside.c_str(), final_.c_str());
      throw IoError(shown_ + ": cannot rename the finished folder into place (" +
                    std::strerror(err) + "); the old folder is back");
    }
    committed_ = true;
    ::unlink((final_path / kMarker).c_str());
    remove_tree(aside);
    return;
  }
  committed_ = true;
  ::unlink((final_path / kMarker).c_str());
  remove_tree(tmp_path);  // now the old set
}

}  // namespace tsp
