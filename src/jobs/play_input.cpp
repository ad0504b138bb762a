#include "jobs/play_input.h"

#include <cctype>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <mutex>

#include <sys/stat.h>
#include <unistd.h>

#include "jobs/cache_key.h"
#include "jobs/calibration.h"
#include "tsp/core/error.h"
#include "tsp/hdf5/hdf5_handle.h"
#include "tsp/hdf5/hdf5_lock.h"
#include "tsp/source/open_mesh_source.h"
#include "tsp/voxelize/open_fields.h"
#include "tsp/voxelize/open_input.h"

namespace tspgl {

namespace fs = std::filesystem;

namespace {

// Creates the folder the cache entry out goes in. Throws tsp::IoError.
void make_builds_folder(const std::string& out) {
  std::error_code ec;
  const fs::path builds = fs::path(out).parent_path();
  fs::create_directories(builds, ec);
  if (ec) throw tsp::IoError(builds.string() + ": cannot create the build cache: " + ec.message());
}

}  // namespace

bool is_tsp_file(const std::string& path) {
  std::error_code ec;
  if (!fs::is_regular_file(path, ec)) return false;
  std::lock_guard lock(tsp::hdf5_mutex());
  tsp::h5::silence_errors();
  if (H5Fis_hdf5(path.c_str()) <= 0) return false;
  tsp::h5::Handle f(H5Fopen(path.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT));
  return f && H5Aexists(f.get(), "format") > 0;
}

bool has_input_extension(const std::string& name) {
  std::string lower = name;
  for (char& c : lower) c = char(std::tolower(static_cast<unsigned char>(c)));
  static constexpr const char* kSuffixes[] = {
      ".tsp", ".h5",  ".hdf5", ".hdf", ".he5",        ".nc",         ".nc4",        ".vtkhdf",
      ".vti", ".vtu", ".vts",  ".vtm", ".pvd", ".vti.series", ".vtu.series", ".vts.series",
      ".vtm.series", ".q", ".raw"};
  for (const char* s : kSuffixes) {
    const std::size_t n = std::char_traits<char>::length(s);
    if (lower.size() > n && lower.compare(lower.size() - n, n, s) == 0) return true;
  }
  return false;
}

std::string play_cache_path(const std::string& input, const PlayInputOptions& o,
                            const std::string& cache_dir, const std::vector<std::string>& files) {
  std::error_code ec;
  const fs::path abs = fs::absolute(input, ec);
  std::string key = abs.string() + "|" + o.field + o.key;
  // Without --field, builds record the field the reader picked since issue 47's walk (those
  // made before recorded none: an untitled legend): a key of their own, so they are built again.
  if (o.field.empty()) key += "|picked field named";
  std::vector<std::string> read = files;
  read.push_back(input);  // (a pattern names no one file: then its path alone)
  for (const std::string& f : read) {
    struct stat st;
    if (::stat(f.c_str(), &st) != 0 || !S_ISREG(st.st_mode)) continue;
    key += "|" + fs::absolute(f, ec).string() + "|" + std::to_string(st.st_size) + "|" +
           std::to_string(st.st_mtim.tv_sec) + "." + std::to_string(st.st_mtim.tv_nsec);
  }
  const std::string dir = cache_dir.empty() ? default_calibration_dir() : cache_dir;
  if (dir.empty())
    throw tsp::UsageError(input + " is not a .tsp file and there is no cache folder to build it "
                          "into (set HOME, XDG_CACHE_HOME or --cache-dir)");
  return (fs::path(dir) / "builds" / (abs.filename().string() + "-" + key_hash(key) + ".tsp"))
      .string();
}

namespace {

// True when the cache entry out is one to play: a regular file (not a link) of this user holding
// a .tsp. Anything else found there (a link, another user's file, a FIFO, an empty folder, a
// file that is not a .tsp) is removed, never followed, so the build puts its own file in its
// place; what cannot be removed is refused. Throws tsp::IoError.
bool reuse_cache_entry(const std::string& out, const PlayBuildHooks& hooks) {
  struct stat st;
  if (::lstat(out.c_str(), &st) != 0) return false;  // nothing there yet
  if (S_ISREG(st.st_mode) && st.st_uid == ::geteuid() && is_tsp_file(out)) return true;
  const char* what = S_ISLNK(st.st_mode)   ? "a symbolic link"
                     : S_ISDIR(st.st_mode) ? "a folder"
                     : !S_ISREG(st.st_mode) ? "not a regular file (a FIFO, socket or device)"
                     : st.st_uid != ::geteuid() ? "a file of another user"
                                                : "not a .tsp file";
  std::error_code ec;
  fs::remove(out, ec);  // a link itself, never its target; a folder only when empty
  if (ec)
    throw tsp::IoError(out + ": the build cache entry is " + what + " and cannot be removed (" +
                       ec.message() + "); remove it, or play with --cache-dir DIR");
  hooks.say("play: the build cache entry " + out + " was " + std::string(what) +
            "; building the input anew in its place");
  return false;
}

std::string prepare_adaptive(const std::string& input, const PlayInputOptions& o,
                             const std::string& cache_dir, const PlayBuildHooks& hooks) {
  if (o.field.find(',') != std::string::npos)
    throw tsp::UsageError("--octree-error builds one field; --field " + o.field +
                          " names several");
  if (!tsp::is_mesh_input(input, o.source.allow_external))
    throw tsp::UsageError("--octree-error: " + input +
                          " is not an unstructured mesh; regular grids are built without it");
  auto mesh = tsp::open_mesh_source(input, o.field, o.source.allow_external, o.source.plot3d_grid);
  const std::string out = play_cache_path(input, o, cache_dir, mesh->files());
  if (reuse_cache_entry(out, hooks)) {
    hooks.say("play: " + input + " is not a .tsp file; playing " + out + ", built from it earlier");
    return out;
  }
  make_builds_folder(out);
  hooks.say("play: " + input + " is not a .tsp file; building its adaptive octree into " + out +
            " (reused next time)");
  tsp::AdaptiveOptions ao = o.octree;
  ao.voxelize = o.voxelize;
  ao.build.field_name = o.field;
  ao.build.brick_size = 0;  // the default for the finest grid, as build picks it
  ao.build.threads = o.voxelize.sample.threads;
  ao.build.output_links = tsp::OutputLinks::replace;
  hooks.build_adaptive(*mesh, out, ao);
  return out;
}

}  // namespace

std::string prepare_play_input(const std::string& input, const PlayInputOptions& o,
                               const std::string& cache_dir, const PlayBuildHooks& hooks) {
  if (is_tsp_file(input)) return input;  // (a field then picks one of its fields)
  if (o.adaptive) return prepare_adaptive(input, o, cache_dir, hooks);
  // --field A,B,C: several fields, one tree each (the first shown), as `build` does (an HDF5
  // file opened once for all of them).
  const std::vector<std::string> fields = tsp::field_names(o.field);
  const tsp::FieldOpener open_field = tsp::open_input_fields(input, o.source, o.voxelize, fields);
  const std::string first_field = fields.empty() ? o.field : fields[0];
  // Keyed by every file the source reads (series members, blocks, grid and solutions). A mesh
  // series is listed through its mesh source, without reading or voxelizing a step, so that a
  // cached build plays at once; a grid's source is opened once and kept for the build.
  std::unique_ptr<tsp::VolumeSource> first;
  std::vector<std::string> files;
  if (tsp::is_mesh_input(input, o.source.allow_external)) {
    files = tsp::open_mesh_source(input, first_field, o.source.allow_external,
                                  o.source.plot3d_grid)->files();
  } else {
    first = open_field(first_field);
    files = first->files();
  }
  const std::string out = play_cache_path(input, o, cache_dir, files);
  if (reuse_cache_entry(out, hooks)) {
    hooks.say("play: " + input + " is not a .tsp file; playing " + out + ", built from it earlier");
    return out;
  }
  if (!first) first = open_field(first_field);
  make_builds_folder(out);
  hooks.say("play: " + input + " is not a .tsp file; building it into " + out +
            " (reused next time)");
  tsp::BuildOptions bo;
  bo.field_name = o.field;
  bo.brick_size = tsp::default_brick_size(first->dims());
  bo.threads = o.voxelize.sample.threads;
  bo.output_links = tsp::OutputLinks::replace;
  if (fields.empty()) {
    hooks.build(*first, out, bo);
    return out;
  }
  auto open_with_first = [&](const std::string& field) {
    return first ? std::move(first) : open_field(field);
  };
  hooks.build_fields(open_with_first, fields, out, bo);
  return out;
}

}  // namespace tspgl
