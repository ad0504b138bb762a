// Writing a file atomically: under a hidden temporary name in the same directory, renamed over
// the final name only when complete.
#pragma once
#include <string>

namespace tsp {

/// A reserved temporary file beside out_path; removed on destruction unless commit() ran.
/// While it exists its writer holds a lock on it (an open-file-description lock, fcntl
/// F_OFD_SETLK), which the kernel drops when the writer dies however it dies: a temporary of
/// the same output name that can be locked is stale and is removed by the next TempOutput.
class TempOutput {
 public:
  /// Checks that out_path's directory exists and out_path is not a directory, removes stale
  /// `.NAME.tmp-*` files of the same name (see above), and creates a locked, empty
  /// `.NAME.tmp-XXXXXX` there. Throws IoError.
  explicit TempOutput(const std::string& out_path);
  /// Removes the temporary file unless committed.
  ~TempOutput();
  TempOutput(const TempOutput&) = delete;
  TempOutput& operator=(const TempOutput&) = delete;
  /// Path of the temporary file to write.
  const std::string& tmp() const { return tmp_; }
  /// Directory of the output ("." for a bare file name).
  const std::string& dir() const { return dir_; }
  /// Renames the temporary file to out_path (replacing it). Throws IoError.
  void commit();

 private:
  std::string final_, tmp_, dir_;
  int lock_fd_ = -1;  ///< holds the lock that marks the temporary as in use
  bool committed_ = false;
};

/// The directory out_path goes to ("." for a bare file name), where TempOutput puts its
/// temporary. Never throws.
std::string output_directory(const std::string& out_path);

/// Removes the stale temporaries of out_path (`.NAME.tmp-*` beside it whose writer is gone) and
/// returns how many. Never throws.
int remove_stale_temporaries(const std::string& out_path);

/// Writes text to path atomically (temporary name, renamed when complete). Throws IoError.
void write_file_atomically(const std::string& path, const std::string& text);

}  // namespace tsp
