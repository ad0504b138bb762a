#include "tsp/core/file_check.h"

#include <sys/stat.h>

#include <cerrno>
#include <cstring>

#include "tsp/core/error.h"

namespace tsp {

void require_regular_file(const std::string& path, const std::string& what) {
  if (path.find('\0') != std::string::npos)
    throw IoError("a " + what + " name holds a NUL byte, which no file name can hold");
  struct stat st {};
  if (::stat(path.c_str(), &st) != 0) {
    if (errno == ENOENT || errno == ENOTDIR)
      throw IoError(path + ": " + what + " does not exist");
    throw IoError(path + ": " + what + " cannot be examined (" + std::strerror(errno) + ")");
  }
  if (S_ISDIR(st.st_mode)) throw IoError(path + ": " + what + " is a directory, expected a file");
  if (!S_ISREG(st.st_mode))
    throw IoError(path + ": " + what + " is not a regular file (a FIFO, socket or device)");
}

}  // namespace tsp
