// The one output mechanism: every file tspplay writes goes through TempOutput (a hidden temporary
// in the same directory, renamed over the final name only when complete), which first refuses an
// output that is one of the command's inputs (InputGuard) or an existing non-regular file (a
// device, FIFO, socket or folder), and refuses to commit once SIGINT/SIGTERM arrived.
#pragma once
#include <sys/types.h>

#include <string>
#include <vector>

namespace tsp {

/// What an output at a symbolic link replaces.
enum class OutputLinks {
  follow,   ///< the link's target (the link kept): a user's `-o link.png` writes where it points
  replace,  ///< the link itself, its target untouched, and likewise a FIFO or device there:
            ///< cache entries, where another user may have planted them
};

/// The files the running command reads, for the guard's lifetime: no TempOutput or OutputFolder
/// may replace any of them (compared by device and inode, links followed). Paths that do not
/// exist are skipped (a file that does not exist cannot be read). Thread-safe.
class InputGuard {
 public:
  /// Guards paths (may be empty). Never throws.
  explicit InputGuard(const std::vector<std::string>& paths = {});
  /// Stops guarding this guard's paths. Never throws.
  ~InputGuard();
  InputGuard(const InputGuard&) = delete;
  InputGuard& operator=(const InputGuard&) = delete;
  /// Guards one more path. Never throws.
  void add(const std::string& path);

 private:
  std::vector<std::pair<dev_t, ino_t>> ids_;
};

/// The guarded input that path names (same device and inode, links followed), or "" when none.
/// Never throws; thread-safe.
std::string guarded_input_at(const std::string& path);

/// Checks that path may be written as an output file: throws UsageError when it is a guarded
/// input, IoError when it exists and is not a regular file (links followed: "is a directory", "is
/// a FIFO", "is a character device", ...). A path that does not exist passes. Thread-safe.
void check_output_path(const std::string& path);

/// A reserved temporary file beside out_path; removed on destruction unless commit() ran.
/// While it exists its writer holds a lock on it (an open-file-description lock, fcntl
/// F_OFD_SETLK), which the kernel drops when the writer dies however it dies: a temporary of
/// the same output name that can be locked is stale and is removed by the next TempOutput.
class TempOutput {
 public:
  /// Checks out_path (check_output_path) and that its directory exists, removes stale
  /// `.NAME.tmp-*` files of the same name (see above), and creates a locked, empty
  /// `.NAME.tmp-XXXXXX` there. A symbolic link to a regular file is written through (its target
  /// replaced, the link kept) under OutputLinks::follow; under OutputLinks::replace the entry
  /// itself (a link whatever it points at, a FIFO, a device; not a folder) is replaced. Throws UsageError (an input) or IoError.
  explicit TempOutput(const std::string& out_path, OutputLinks links = OutputLinks::follow);
  /// Removes the temporary file unless committed.
  ~TempOutput();
  TempOutput(const TempOutput&) = delete;
  TempOutput& operator=(const TempOutput&) = delete;
  /// Path of the temporary file to write.
  const std::string& tmp() const { return tmp_; }
  /// Directory of the output ("." for a bare file name).
  const std::string& dir() const { return dir_; }
  /// Renames the temporary file to out_path (replacing it). Throws Interrupted (nothing replaced)
  /// once SIGINT/SIGTERM arrived, IoError when the rename fails or out_path became a non-regular
  /// file meanwhile.
  void commit();

 private:
  std::string shown_;  ///< out_path as given, for messages
  std::string final_, tmp_, dir_;
  OutputLinks links_;
  int lock_fd_ = -1;  ///< holds the lock that marks the temporary as in use
  bool committed_ = false;
};

/// The directory out_path goes to ("." for a bare file name), where TempOutput puts its
/// temporary. Never throws.
std::string output_directory(const std::string& out_path);

/// path when nothing is there (not even a dangling link), else the first of STEM-2.EXT,
/// STEM-3.EXT, … beside it that is free: a name a new output can take without replacing an
/// earlier one. Never throws.
std::string unused_path(const std::string& path);

/// Removes the stale temporaries of out_path (`.NAME.tmp-*` beside it whose writer is gone) and
/// returns how many. Never throws.
int remove_stale_temporaries(const std::string& out_path);

namespace detail {
/// Takes an exclusive open-file-description lock on fd without waiting; true when taken.
bool try_lock(int fd);
}  // namespace detail

/// Writes text to path atomically (temporary name, renamed when complete). Throws what TempOutput
/// throws, IoError when the write fails.
void write_file_atomically(const std::string& path, const std::string& text,
                           OutputLinks links = OutputLinks::follow);

}  // namespace tsp
