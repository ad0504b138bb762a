// tsp::open_source: picks the reader from the input's form.
#include "tsp/source/open_source.h"

#include <algorithm>
#include <cctype>
#include <filesystem>

#include "tsp/core/error.h"
#include "tsp/core/file_check.h"
#include "tsp/hdf5/hdf5_handle.h"
#include "tsp/source/hdf5_source.h"
#include "tsp/source/raw_source.h"
#include "tsp/source/series_list.h"
#include "tsp/source/volume_source.h"
#include "tsp/source/vti_source.h"

namespace tsp {
namespace {


bool has_hdf5_extension(const std::string& s) {
  for (const char* ext : {".h5", ".hdf5", ".nc", ".hdf", ".vtkhdf", ".he5", ".nc4"})
    if (io::has_suffix(s, ext)) return true;
  return false;
}

bool has_hdf5_signature(const std::string& path) {
  h5::silence_errors();
  return H5Fis_hdf5(path.c_str()) > 0;
}

}  // namespace

bool is_hdf5_input(const std::string& input) {
  std::error_code ec;
  if (input.empty() || input.find('\0') != std::string::npos ||
      !std::filesystem::is_regular_file(input, ec))
    return false;
  return has_hdf5_extension(input) || has_hdf5_signature(input);
}

std::unique_ptr<VolumeSource> open_source(const std::string& input, const SourceOptions& options) {
  if (input.empty()) throw UsageError("no input given");
  if (input.find('\0') != std::string::npos)
    throw UsageError("the input name holds a NUL byte, which no file name can hold");
  std::error_code ec;
  const bool exists = std::filesystem::exists(input, ec);
  // A pattern names many files; an existing file whose name merely contains '%' or '*' is
  // read as itself.
  if (!exists && io::is_file_pattern(input)) {
    if (io::has_suffix(input, ".vti")) return io::open_vti_pattern_source(input, options);
    if (has_hdf5_extension(input))
      throw UsageError(input +
                       ": a file pattern of HDF5 files is not supported; store the steps "
                       "in one file (a 4-D dataset or a group of 3-D datasets)");
    return io::open_raw_source(input, options);
  }
  if (io::has_suffix(input, ".pvd")) return io::open_pvd_source(input, options);
  if (io::has_suffix(input, ".vti.series")) return io::open_vti_series_source(input, options);
  if (io::has_suffix(input, ".vti")) return io::open_vti_source(input, options);
  if (!exists) throw IoError(input + ": input does not exist");
  if (std::filesystem::is_directory(input, ec))
    throw IoError(input + ": input is a directory, expected a file or a file pattern");
  // Before anything opens it: a FIFO would block the HDF5 signature check forever.
  require_regular_file(input, "input");
  if (has_hdf5_extension(input) || has_hdf5_signature(input))
    return io::open_hdf5_source(input, options);
  if (io::has_suffix(input, ".raw") || options.raw_dims) return io::open_raw_source(input, options);
  throw FormatError(input +
                    ": unrecognised input; expected HDF5/NetCDF-4/VTKHDF (.h5 .hdf5 .nc .hdf), "
                    "VTK image data (.vti .pvd .vti.series) or raw data (.raw, a %d pattern or a "
                    "glob, with --raw-dims)");
}

}  // namespace tsp
