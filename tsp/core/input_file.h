// The one gate every input file we read ourselves goes through (XML and JSON lists, VTK files,
// player scripts, transfer functions, PNG images): opened without blocking, regular files only,
// its size known and checked before a byte is read, never read past that size. A file a library
// opens by name (HDF5) is checked by require_regular_file (file_check.h) first.
#pragma once
#include <cstddef>
#include <cstdint>
#include <string>

namespace tsp {

/// Largest text input read whole: `.pvd`, `.series` and `.vtm` lists, player scripts, transfer
/// functions (64 MiB; the largest real one is a few kilobytes).
inline constexpr std::int64_t kMaxTextInputBytes = std::int64_t(64) << 20;

/// A regular file open for reading. Not thread-safe (one reader at a time).
class InputFile {
 public:
  /// Opens path for reading with O_NONBLOCK (opening a FIFO never waits for a writer), then
  /// refuses anything but a regular file. `what` names the file in errors ("input", "step
  /// file", "player script", …). Throws IoError: "does not exist", "is a directory", "is not a
  /// regular file (a FIFO, socket or device)", or the system's reason.
  InputFile(const std::string& path, const std::string& what);
  /// Closes the file. Never throws.
  ~InputFile();
  InputFile(const InputFile&) = delete;
  InputFile& operator=(const InputFile&) = delete;

  /// The file's size when it was opened, in bytes.
  std::int64_t size() const { return size_; }
  /// The path it was opened by.
  const std::string& path() const { return path_; }
  /// Reads up to n bytes into buf, never past size(); returns how many (0 at the end). Throws
  /// IoError on a read error.
  std::size_t read(char* buf, std::size_t n);

 private:
  std::string path_;
  int fd_ = -1;
  std::int64_t size_ = 0, offset_ = 0;
};

/// The whole of the regular file path (through InputFile), refused with an IoError naming its
/// size and the limit before anything is read when it is larger than max_bytes. Throws IoError.
std::string read_input_file(const std::string& path, const std::string& what,
                            std::int64_t max_bytes = kMaxTextInputBytes);

}  // namespace tsp
