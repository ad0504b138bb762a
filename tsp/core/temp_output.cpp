#include "tsp/core/temp_output.h"

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

TempOutput::TempOutput(const std::string& out_path) : final_(out_path) {
  fs::path p(out_path);
  fs::path dir = p.parent_path().empty() ? fs::path(".") : p.parent_path();
  std::error_code ec;
  if (fs::is_directory(p, ec)) throw IoError(out_path + ": is a directory, expected a file name");
  if (!fs::is_directory(dir, ec))
    throw IoError(out_path + ": directory " + dir.string() + " does not exist");
  dir_ = dir.string();
  std::string tmpl = (dir / ("." + p.filename().string() + ".tmp-XXXXXX")).string();
  int fd = mkstemp(tmpl.data());
  if (fd < 0)
    throw IoError(out_path + ": cannot create a file in " + dir_ + " (" + std::strerror(errno) +
                  ")");
  // mkstemp creates 0600; the finished file gets the permissions a plain create would give.
  const mode_t mask = umask(0);
  umask(mask);
  fchmod(fd, 0666 & ~mask);
  close(fd);
  tmp_ = tmpl;
}

TempOutput::~TempOutput() {
  if (!committed_) std::remove(tmp_.c_str());
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
